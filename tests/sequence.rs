//! `eyeadapt sequence` end to end: determinism across chunking and threads, resume after
//! SIGKILL at random moments, refusal to mix jobs.
mod common;

use common::snapshot;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::Duration;

fn eyeadapt() -> Command {
    Command::new(env!("CARGO_BIN_EXE_eyeadapt"))
}

/// A small job: 8 frames of the demo walkthrough at 32x18, 2 spp, 512 eye samples.
const ARGS: &[&str] = &[
    "--frames",
    "0-7",
    "--width",
    "32",
    "--height",
    "18",
    "--spp",
    "2",
    "--eye-samples",
    "512",
    "--no-report",
];

fn sequence(out: &Path, extra: &[&str]) -> std::process::Output {
    let o = eyeadapt()
        .arg("sequence")
        .args(ARGS)
        .args(["--out", out.to_str().unwrap()])
        .args(extra)
        .output()
        .unwrap();
    assert!(
        o.status.success(),
        "sequence {extra:?} failed: {}",
        String::from_utf8_lossy(&o.stderr)
    );
    o
}

fn assert_same(a: &BTreeMap<String, Vec<u8>>, b: &BTreeMap<String, Vec<u8>>, what: &str) {
    let ka: Vec<_> = a.keys().collect();
    let kb: Vec<_> = b.keys().collect();
    assert_eq!(ka, kb, "{what}: different file sets");
    for (k, v) in a {
        assert!(v == &b[k], "{what}: {k} differs");
    }
}

#[test]
fn whole_run_equals_four_merged_chunks_and_any_thread_count() {
    let t = tempfile::tempdir().unwrap();
    let whole = t.path().join("whole");
    sequence(&whole, &[]);
    let base = snapshot(&whole);
    assert!(base.contains_key("adaptation.csv") && base.len() > 8 * 10);
    let csv = String::from_utf8(base["adaptation.csv"].clone()).unwrap();
    assert_eq!(
        csv.lines().count(),
        1 + 8 * 8,
        "header + 8 frames x 8 estimators"
    );

    let mut chunks: Vec<PathBuf> = Vec::new();
    for i in 0..4 {
        let c = t.path().join(format!("chunk{i}"));
        sequence(&c, &["--chunk-size", "2", "--chunk-index", &i.to_string()]);
        chunks.push(c);
    }
    let merged = t.path().join("merged");
    let mut cmd = eyeadapt();
    cmd.arg("merge")
        .args(&chunks)
        .args(["--out", merged.to_str().unwrap(), "--frames", "0-7"]);
    assert!(cmd.status().unwrap().success());
    // Everything, the manifest included, is identical.
    assert_same(&base, &snapshot(&merged), "4 merged chunks vs whole run");

    for threads in ["1", "2"] {
        let d = t.path().join(format!("t{threads}"));
        sequence(&d, &["--threads", threads]);
        assert_same(&base, &snapshot(&d), &format!("--threads {threads}"));
    }
}

#[test]
fn killed_runs_resume_to_identical_outputs() {
    let t = tempfile::tempdir().unwrap();
    let reference = t.path().join("ref");
    sequence(&reference, &[]);
    let want = snapshot(&reference);
    let out = t.path().join("killed");
    // Deterministic "random" kill moments (xorshift), 5 kills then a final resume.
    let mut x: u64 = 0x9e37_79b9_7f4a_7c15;
    for _ in 0..5 {
        x ^= x << 13;
        x ^= x >> 7;
        x ^= x << 17;
        let delay = Duration::from_millis(20 + x % 400);
        let mut child = eyeadapt()
            .arg("sequence")
            .args(ARGS)
            .args(["--out", out.to_str().unwrap()])
            .stdout(Stdio::null())
            .stderr(Stdio::null())
            .spawn()
            .unwrap();
        std::thread::sleep(delay);
        let _ = child.kill(); // SIGKILL
        let _ = child.wait();
        // The committed frames' rows are whole; only the frame in flight may be cut short.
        let manifest = std::fs::read_to_string(out.join("manifest.json")).unwrap_or_default();
        common::assert_killed_csv_intact(&out, manifest.matches("\"time_s\"").count());
    }
    let o = sequence(&out, &[]);
    let _ = String::from_utf8_lossy(&o.stdout);
    assert_same(
        &want,
        &snapshot(&out),
        "resumed after 5 kills vs uninterrupted",
    );
}

#[test]
fn changed_job_is_refused_and_force_restarts() {
    let t = tempfile::tempdir().unwrap();
    let out = t.path().join("o");
    sequence(&out, &[]);
    let o = eyeadapt()
        .arg("sequence")
        .args(ARGS)
        .args(["--out", out.to_str().unwrap(), "--seed", "9"])
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("refusing to mix"));
    let before = snapshot(&out);
    assert_eq!(before, snapshot(&out), "refusal changed nothing");
    sequence(&out, &["--seed", "9", "--force"]);
    assert_ne!(before["adaptation.csv"], snapshot(&out)["adaptation.csv"]);
}

#[test]
fn farm_log_lines_and_resume_skip() {
    let t = tempfile::tempdir().unwrap();
    let out = t.path().join("o");
    let o = sequence(&out, &["--log-format", "openjd"]);
    let s = String::from_utf8_lossy(&o.stdout);
    assert!(s.contains("openjd_progress: 100"), "{s}");
    assert!(s.contains("Saved: '"), "{s}");
    let o = sequence(&out, &[]);
    let s = String::from_utf8_lossy(&o.stdout);
    assert!(s.contains("0 frame(s) rendered, 8 already done"), "{s}");
    // Deleting a committed frame's file makes the next run redo exactly that frame.
    std::fs::remove_file(out.join("frames/eye/frame_000003.png")).unwrap();
    let o = sequence(&out, &[]);
    assert!(String::from_utf8_lossy(&o.stdout).contains("1 frame(s) rendered, 7 already done"));
}
