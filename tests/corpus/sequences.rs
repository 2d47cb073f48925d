//! `job/` (job files), `frames/` (`--frames` specs) and `merge/` (broken chunk outputs):
//! every case exits 2 with its location and message, and the good sequence, chunk and merge
//! the commands would write into stay byte-for-byte unchanged.
use super::harness::*;

#[test]
fn bad_jobs_and_frame_specs_exit_2_and_leave_a_sequence_alone() {
    let t = tempfile::tempdir().unwrap();
    let seq_out = good_sequence(t.path(), "seq-out");
    let before = snapshots(&[&seq_out]);
    let mut outcomes = Vec::new();
    for (case, path, x) in cases("job", "toml") {
        let (code, err) = run(eyeadapt()
            .arg("sequence")
            .arg(&path)
            .args(JOB)
            .arg("--out")
            .arg(&seq_out));
        outcomes.push(check(&case, code, &err, &x));
    }
    for (case, path, x) in cases("frames", "spec") {
        let spec = std::fs::read_to_string(&path).unwrap();
        let spec = spec.strip_suffix('\n').unwrap_or(&spec);
        let (code, err) = run(eyeadapt()
            .arg("sequence")
            .arg(format!("--frames={spec}"))
            .args(SEQ)
            .arg("--out")
            .arg(&seq_out));
        outcomes.push(check(&case, code, &err, &x));
    }
    assert_unchanged(&[&seq_out], &before);
    finish(&outcomes, &[("job", 34), ("frames", 16)]);
}

#[test]
fn bad_chunk_outputs_exit_2_and_leave_a_merge_alone() {
    let t = tempfile::tempdir().unwrap();
    let root = t.path();
    let chunk = |i: usize| render_chunk(root, "chunk", i);
    let (chunk0, chunk1) = (chunk(0), chunk(1));
    let merge_out = root.join("merge-out");
    must(
        eyeadapt()
            .arg("merge")
            .args([&chunk0, &chunk1])
            .args(["--frames", "0-3", "--out"])
            .arg(&merge_out),
    );
    let chunk1_manifest = std::fs::read_to_string(chunk1.join("manifest.json")).unwrap();
    let m = eyeadapt_sequencer::manifest::Manifest::load(&chunk1)
        .unwrap()
        .unwrap();
    let vars = [
        ("JOB_HASH", m.job_hash.clone()),
        ("JOB_FRAMES", m.job_frames.clone()),
        ("SETTINGS", serde_settings(&chunk1_manifest)),
    ];
    let before = snapshots(&[&merge_out, &chunk0]);
    let mut outcomes = Vec::new();
    for (case, path, x) in cases("merge", "") {
        let dir = root.join("merge-cases").join(path.file_name().unwrap());
        instantiate(&path, &dir, &vars);
        let mut cmd = eyeadapt();
        cmd.arg("merge");
        match x.inputs.as_deref() {
            Some("case") => cmd.arg(&dir),
            None | Some("chunk0 case") => cmd.arg(&chunk0).arg(&dir),
            Some(other) => panic!("{case}: unknown inputs {other:?}"),
        };
        let (code, err) = run(cmd.args(["--frames", "0-3", "--out"]).arg(&merge_out));
        outcomes.push(check(&case, code, &err, &x));
    }
    assert_unchanged(&[&merge_out, &chunk0], &before);
    finish(&outcomes, &[("merge", 15)]);
}
