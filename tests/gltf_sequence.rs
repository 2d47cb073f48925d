//! A job whose scene is a glTF file (`tests/corpus/good/walk.gltf`: an animated camera, a
//! floor and a lamp, no `[camera_path]` in the job) through everything a farm does with it:
//! chunks merged equal one whole run bit for bit, any thread count gives the same bits, a
//! rerun resumes without rendering, and the report reads it.
mod common;

use common::snapshot;
use std::path::Path;
use std::process::Command;

fn eyeadapt() -> Command {
    Command::new(env!("CARGO_BIN_EXE_eyeadapt"))
}

fn run(args: &[&str], dir: &Path) -> String {
    let o = eyeadapt().args(args).current_dir(dir).output().unwrap();
    assert!(
        o.status.success(),
        "eyeadapt {args:?} failed: {}",
        String::from_utf8_lossy(&o.stderr)
    );
    String::from_utf8_lossy(&o.stdout).into_owned() + &String::from_utf8_lossy(&o.stderr)
}

fn sequence(dir: &Path, out: &str, extra: &[&str]) -> String {
    let mut args = vec![
        "sequence",
        "job.toml",
        "--eye-samples",
        "64",
        "--no-report",
        "--log-format",
        "plain",
        "--out",
        out,
    ];
    args.extend_from_slice(extra);
    run(&args, dir)
}

#[test]
fn a_gltf_job_chunks_merges_resumes_and_reports_like_any_other() {
    let t = tempfile::tempdir().unwrap();
    let dir = t.path();
    let repo = Path::new(env!("CARGO_MANIFEST_DIR"));
    std::fs::copy(
        repo.join("tests/corpus/good/walk.gltf"),
        dir.join("walk.gltf"),
    )
    .unwrap();
    std::fs::write(
        dir.join("job.toml"),
        "scene = \"walk.gltf\"\n[render]\nwidth = 16\nheight = 9\nspp = 1\n",
    )
    .unwrap();

    sequence(dir, "whole", &[]);
    let whole = snapshot(&dir.join("whole"));
    let csv = String::from_utf8(whole["adaptation.csv"].clone()).unwrap();
    let frames: std::collections::BTreeSet<&str> = csv
        .lines()
        .skip(1)
        .map(|l| l.split(',').next().unwrap())
        .collect();
    assert_eq!(frames.len(), 25, "the file's 1 s animation at 24 fps");

    for i in 0..3 {
        let idx = i.to_string();
        sequence(
            dir,
            &format!("chunk{i}"),
            &["--chunk-size", "10", "--chunk-index", &idx],
        );
    }
    run(
        &["merge", "chunk0", "chunk1", "chunk2", "--out", "merged"],
        dir,
    );
    let mut merged = snapshot(&dir.join("merged"));
    let mut want = whole.clone();
    merged.remove("manifest.json");
    want.remove("manifest.json");
    assert_eq!(
        want.keys().collect::<Vec<_>>(),
        merged.keys().collect::<Vec<_>>()
    );
    for (k, v) in &want {
        assert!(
            v == &merged[k],
            "merged chunks: {k} differs from the whole run"
        );
    }

    sequence(dir, "one-thread", &["--threads", "1"]);
    assert!(
        snapshot(&dir.join("one-thread")) == whole,
        "--threads 1 gives other bits"
    );

    let again = sequence(dir, "whole", &[]);
    assert!(again.contains("0 frame(s) rendered"), "{again}");
    assert!(
        snapshot(&dir.join("whole")) == whole,
        "a rerun changed the outputs"
    );

    run(&["report", "whole"], dir);
    assert!(dir.join("whole/report.html").is_file());
}
