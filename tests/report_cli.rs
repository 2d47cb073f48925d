//! `eyeadapt report --video` where the movies cannot be made (no ffmpeg on PATH): the rest of
//! the report is written, and the command fails (exit 1) so a scripted job notices.
mod common;
use std::process::Command;

#[test]
fn report_video_without_ffmpeg_writes_the_report_and_fails() {
    let t = tempfile::tempdir().unwrap();
    let out = t.path().join("seq");
    let bin = env!("CARGO_BIN_EXE_eyeadapt");
    let o = Command::new(bin)
        .args([
            "sequence", "--frames", "0-1", "--width", "16", "--height", "9",
        ])
        .args([
            "--spp",
            "1",
            "--eye-samples",
            "64",
            "--no-report",
            "--no-progress-bar",
        ])
        .arg("--out")
        .arg(&out)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let empty = t.path().join("no-programs");
    std::fs::create_dir(&empty).unwrap();
    let o = Command::new(bin)
        .arg("report")
        .arg(&out)
        .arg("--video")
        .env("PATH", &empty)
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(1), "{err}");
    assert!(err.contains("report --video"), "{err}");
    assert!(out.join("report.html").exists());
    assert!(out.join("coherence.csv").exists());
}
