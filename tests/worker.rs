//! The worker talks and stops cleanly (issue #17): the start-up line, progress inside a
//! frame, the report phase, a rerun of a finished directory that leaves its report alone, and
//! SIGINT/SIGTERM that stop after the frame in flight (or at once) with every committed frame
//! kept, so that rerunning the same command finishes the job with the same bits.
mod common;

use common::snapshot;
use std::io::{BufRead, BufReader};
use std::path::Path;
use std::process::{Command, Stdio};

fn eyeadapt() -> Command {
    Command::new(env!("CARGO_BIN_EXE_eyeadapt"))
}

const TINY: &[&str] = &[
    "--width",
    "12",
    "--height",
    "8",
    "--spp",
    "1",
    "--eye-samples",
    "64",
    "--no-progress-bar",
];

fn sequence(out: &Path, extra: &[&str]) -> (String, String) {
    let o = eyeadapt()
        .arg("sequence")
        .args(TINY)
        .arg("--out")
        .arg(out)
        .args(extra)
        .output()
        .unwrap();
    let (stdout, stderr) = (
        String::from_utf8_lossy(&o.stdout).into_owned(),
        String::from_utf8_lossy(&o.stderr).into_owned(),
    );
    assert!(o.status.success(), "{extra:?}: {stderr}");
    (stdout, stderr)
}

fn mtime(p: &Path) -> std::time::SystemTime {
    std::fs::metadata(p).unwrap().modified().unwrap()
}

#[test]
fn start_up_line_in_frame_progress_report_phase_and_a_quiet_rerun() {
    let t = tempfile::tempdir().unwrap();
    let out = t.path().join("o");
    let (log, _) = sequence(&out, &["--frames", "0-1"]);
    let first = log.lines().next().unwrap();
    assert!(
        first.starts_with("eyeadapt sequence: job \"demo\" (builtin:demo), scene builtin:three-rooms, frames 0-1: 2 to do, 0 already done, output ")
            && first.contains(" thread"),
        "{first}"
    );
    // Inside frame 0 (8 rows): a line at each quarter (rows finish in parallel, so which
    // row count each line names may vary), with the share of the whole run.
    let inside: Vec<&str> = log
        .lines()
        .filter(|l| l.starts_with("Fra:0 | rows ") && l.contains("/8 | Remaining:"))
        .collect();
    assert_eq!(inside.len(), 3, "{log}");
    assert!(inside[2].ends_with("| Progress: 37%"), "{log}");
    assert!(log.contains("| 1/2 frames | Remaining:"), "{log}");
    for step in [
        "report: writing the coherence report of",
        "report: image metrics (raw EXRs) 4/4",
    ] {
        assert!(log.contains(step), "{step}: {log}");
    }

    // Nothing changed: no report, same files.
    let files = [
        "report.html",
        "coherence.csv",
        "adaptation.csv",
        "report.stamp",
    ];
    let before: Vec<_> = files.iter().map(|f| mtime(&out.join(f))).collect();
    let (log, _) = sequence(&out, &["--frames", "0-1"]);
    assert!(
        log.contains("0 to do, 2 already done") && log.contains("is up to date"),
        "{log}"
    );
    let after: Vec<_> = files.iter().map(|f| mtime(&out.join(f))).collect();
    assert_eq!(
        before, after,
        "a rerun that renders nothing rewrote the report"
    );
    // A frame redone is a change: the report is written again.
    std::fs::remove_file(out.join("frames/raw/frame_000001.exr")).unwrap();
    let (log, _) = sequence(&out, &["--frames", "0-1"]);
    assert!(
        log.contains("1 frame(s) rendered") && log.contains("report: writing"),
        "{log}"
    );

    // OpenJD: every line is a directive or a plain log line of a known form.
    let (log, _) = sequence(
        &t.path().join("j"),
        &["--frames", "0-1", "--log-format", "openjd"],
    );
    let progress = log
        .lines()
        .filter(|l| l.starts_with("openjd_progress: "))
        .count();
    assert_eq!(
        progress,
        2 * (3 + 1),
        "in-frame and per-frame progress: {log}"
    );
    for l in log.lines() {
        let known = [
            "openjd_status: ",
            "openjd_progress: ",
            "Fra:",
            "Saved: '",
            "report: ",
            "demo: ",
        ];
        assert!(
            known.iter().any(|k| l.starts_with(k)),
            "unparsable line {l:?}"
        );
    }
}

/// Starts a long tiny sequence, sends `signals` (via `kill`) once frame 0 is committed, and
/// returns the exit code and stderr.
fn interrupted(out: &Path, signals: &[&str]) -> (Option<i32>, String) {
    let mut child = eyeadapt()
        .arg("sequence")
        .args(TINY)
        .args(["--frames", "0-29", "--no-report", "--out"])
        .arg(out)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let stdout = BufReader::new(child.stdout.take().unwrap());
    let mut lines = stdout.lines();
    for l in lines.by_ref() {
        if l.unwrap().starts_with("Fra:0 done") {
            break;
        }
    }
    for s in signals {
        let pid = child.id().to_string();
        assert!(
            Command::new("kill")
                .args([*s, pid.as_str()])
                .status()
                .unwrap()
                .success()
        );
    }
    lines.for_each(drop);
    let o = child.wait_with_output().unwrap();
    (
        o.status.code(),
        String::from_utf8_lossy(&o.stderr).into_owned(),
    )
}

#[test]
fn sigint_and_sigterm_stop_cleanly_and_the_rerun_resumes() {
    let t = tempfile::tempdir().unwrap();
    let whole = t.path().join("whole");
    sequence(&whole, &["--frames", "0-29", "--no-report"]);
    let want = snapshot(&whole);
    for (name, signals, code) in [
        ("int", &["-INT"][..], 130),
        ("term-twice", &["-TERM", "-TERM"][..], 143),
    ] {
        let out = t.path().join(name);
        let (got, err) = interrupted(&out, signals);
        assert_eq!(got, Some(code), "{name}: {err}");
        assert!(
            err.contains("of 30 frames committed; rerun the same command to resume"),
            "{name}: {err}"
        );
        let m = eyeadapt_sequencer::manifest::Manifest::load(&out)
            .unwrap()
            .unwrap();
        assert!(
            (1..30).contains(&m.frames.len()),
            "{name}: {} frames",
            m.frames.len()
        );
        let (log, _) = sequence(&out, &["--frames", "0-29", "--no-report"]);
        assert!(
            log.contains(&format!("{} already done", m.frames.len())),
            "{log}"
        );
        assert_eq!(want, snapshot(&out), "{name}: resumed run differs");
    }
}
