//! Crash torture: 20 trials, each SIGKILLs `eyeadapt sequence` at a seeded pseudo-random moment
//! (some trials kill the resumed run a second time), resumes to the end, and requires the
//! outputs to equal an uninterrupted run's: decoded EXR pixels of every channel, PNG bytes,
//! row files, `adaptation.csv` bytes and `manifest.json` bytes.
//!
//! Frames are tiny (8×6, 1 spp, 64 eye samples), so most of a run is file writes, fsyncs,
//! renames and the CSV append. Half of the kills come at a seeded time between process start
//! and the end of a run; the other half a seeded 0–4 ms after the run reports its k-th saved
//! file (k seeded too, and for half of them the last file of a frame), which lands them in the
//! writes of later files, the row file, the CSV append and the manifest commit.
//! What each kill interrupted is read from the directory it left (a temporary file: during an
//! atomic write; CSV rows beyond the manifest: between the append and the manifest commit) and
//! printed, with the tally, by `cargo test --release --test torture -- --nocapture`.
//!
//! Each trial's directory also holds a user's files named like temporaries, which must
//! survive every kill and resume (the stale-temporary cleanup deletes only its own).
//!
//! Reproduce one trial: `EYEADAPT_TORTURE_SEED=<seed> EYEADAPT_TORTURE_TRIALS=1`.
mod common;

use common::snapshot;
use std::collections::BTreeMap;
use std::io::{BufRead, BufReader};
use std::path::Path;
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

const ARGS: &[&str] = &["--frames", "0-11", "--width", "8", "--height", "6"];

/// Files a run saves: 12 frames × (raw EXR, raw PNG, 8 adapted PNGs).
const SAVED_LINES: u64 = 12 * 10;

/// Files a user keeps in the output directory under names like the run's temporaries.
const USER_FILES: [(&str, &str); 2] = [
    (".notes.tmp-1", "user notes"),
    ("mine/.frame_000001.png.tmp-2", "user image"),
];

fn sequence_cmd(out: &Path) -> Command {
    let mut c = Command::new(env!("CARGO_BIN_EXE_eyeadapt"));
    c.arg("sequence")
        .args(ARGS)
        .args(common::QUICK)
        .args(["--out", out.to_str().unwrap()]);
    c
}

fn run_to_end(out: &Path) -> Duration {
    let t = Instant::now();
    let o = sequence_cmd(out).output().unwrap();
    assert!(
        o.status.success(),
        "sequence into {} failed: {}",
        out.display(),
        String::from_utf8_lossy(&o.stderr)
    );
    t.elapsed()
}

/// xorshift64*: the kill schedule depends on the seed alone.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_f491_4f6c_dd1d)
    }

    /// Uniform in [0, 1) with 2^-24 resolution.
    fn unit(&mut self) -> f64 {
        (self.next() >> 40) as f64 / (1u64 << 24) as f64
    }
}

/// What the killed run was doing, judged from what it left behind.
fn interrupted_in(dir: &Path) -> String {
    if !dir.join("manifest.json").exists() {
        return "startup".into();
    }
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        for e in std::fs::read_dir(&d).unwrap().flatten() {
            let p = e.path();
            if p.is_dir() {
                stack.push(p);
            } else if USER_FILES.iter().any(|(rel, _)| p.ends_with(rel)) {
                continue;
            } else if let Some((name, _)) = e.file_name().to_string_lossy().split_once(".tmp-") {
                // .frame_000003.png.tmp-PID -> "writing a png"; .manifest.json.tmp-PID
                let kind = match name.rsplit_once('.') {
                    Some((_, ext)) if name.contains("frame_") && ext == "csv" => "row file",
                    Some((_, ext)) if name.contains("frame_") => ext,
                    _ => name.trim_start_matches('.'),
                };
                return format!("writing {kind}");
            }
        }
    }
    let manifest = std::fs::read_to_string(dir.join("manifest.json")).unwrap_or_default();
    let committed = manifest.matches("\"time_s\"").count();
    if common::assert_killed_csv_intact(dir, committed) {
        return "appending to the CSV".into();
    }
    let csv = std::fs::read_to_string(dir.join("adaptation.csv")).unwrap_or_default();
    let csv_frames: std::collections::BTreeSet<&str> = csv
        .lines()
        .skip(1)
        .filter_map(|l| l.split(',').next())
        .collect();
    let rows = std::fs::read_dir(dir.join("rows")).map_or(0, |r| r.count());
    if csv_frames.len() > committed {
        "CSV appended, manifest not yet".into()
    } else if rows > committed {
        "row file written, CSV not yet".into()
    } else {
        "between commits (rendering)".into()
    }
}

#[test]
fn twenty_kills_at_random_moments_resume_to_identical_outputs() {
    let started = Instant::now();
    let t = tempfile::tempdir().unwrap();
    let reference = t.path().join("ref");
    let first = run_to_end(&reference);
    let want = snapshot(&reference);
    // The clock-based kills spread over the duration of an uninterrupted run (the shorter of
    // two: the first one pays for cold caches).
    let full = first.min(run_to_end(&t.path().join("warm")));
    assert!(want.contains_key("manifest.json") && want.contains_key("adaptation.csv"));
    let trials: usize = std::env::var("EYEADAPT_TORTURE_TRIALS")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(20);
    let seed: u64 = std::env::var("EYEADAPT_TORTURE_SEED")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(0x5eed_0009);
    println!(
        "torture: uninterrupted run {:.0} ms; seed {seed}",
        full.as_secs_f64() * 1e3
    );
    let mut tally: BTreeMap<String, usize> = BTreeMap::new();
    let mut passed = 0;
    for trial in 0..trials {
        let trial_seed = seed.wrapping_add(trial as u64);
        let mut rng = Rng(trial_seed.wrapping_mul(0x9e37_79b9_7f4a_7c15) | 1);
        let out = t.path().join(format!("trial{trial:02}"));
        // A user's files that merely look like temporaries must outlive every kill and resume.
        for (rel, text) in USER_FILES {
            std::fs::create_dir_all(out.join(rel).parent().unwrap()).unwrap();
            std::fs::write(out.join(rel), text).unwrap();
        }
        // One kill, or two for about a third of the seeds (the second kills the resumed run).
        let kills = if trial_seed % 3 == 2 { 2 } else { 1 };
        let mut what = Vec::new();
        for _ in 0..kills {
            let mut child = sequence_cmd(&out)
                .stdout(Stdio::piped())
                .stderr(Stdio::null())
                .spawn()
                .unwrap();
            let when = if rng.next().is_multiple_of(2) {
                // By the clock: anywhere from process start to the end of a run.
                let delay = full.mul_f64(0.02 + 0.93 * rng.unit());
                std::thread::sleep(delay);
                format!("{:.1} ms", delay.as_secs_f64() * 1e3)
            } else {
                // By progress: 0-4 ms after the k-th "Saved:" line, which the run prints
                // right after renaming a file into place. The last file of a frame is
                // followed by its row file, the CSV append and the manifest commit.
                // Half of these aim at the last file of a frame (its 10th), right before
                // the row file, the CSV append and the manifest commit.
                let k = if rng.next().is_multiple_of(2) {
                    rng.next() % SAVED_LINES
                } else {
                    10 * (rng.next() % (SAVED_LINES / 10)) + 9
                };
                let extra = Duration::from_micros(rng.next() % 4000);
                let stdout = child.stdout.take().unwrap();
                let mut seen = 0;
                for line in BufReader::new(stdout).lines() {
                    if line.unwrap().starts_with("Saved:") {
                        seen += 1;
                        if seen > k {
                            break;
                        }
                    }
                }
                std::thread::sleep(extra);
                format!(
                    "{:.2} ms after file {} of {SAVED_LINES}",
                    extra.as_secs_f64() * 1e3,
                    k + 1
                )
            };
            let finished = child.try_wait().unwrap().is_some();
            child.kill().unwrap_or(()); // SIGKILL
            let status = child.wait().unwrap();
            let at = if finished || status.success() {
                "after the end (nothing killed)".to_string()
            } else {
                interrupted_in(&out)
            };
            *tally.entry(at.clone()).or_default() += 1;
            what.push(format!("{when}: {at}"));
        }
        run_to_end(&out);
        for (rel, text) in USER_FILES {
            let kept = std::fs::read_to_string(out.join(rel)).ok();
            assert_eq!(
                kept.as_deref(),
                Some(text),
                "trial {trial}: {rel} was deleted"
            );
            std::fs::remove_file(out.join(rel)).unwrap();
        }
        std::fs::remove_dir(out.join("mine")).unwrap();
        let got = snapshot(&out);
        let same_files = got.keys().eq(want.keys());
        let differing: Vec<&String> = want
            .iter()
            .filter(|(k, v)| got.get(*k) != Some(v))
            .map(|(k, _)| k)
            .collect();
        let ok = same_files && differing.is_empty();
        println!(
            "trial {trial:2} (seed {trial_seed}): killed at {} -> {}",
            what.join(", then "),
            if ok { "identical" } else { "DIFFERENT" }
        );
        assert!(
            ok,
            "trial {trial} (EYEADAPT_TORTURE_SEED={trial_seed} EYEADAPT_TORTURE_TRIALS=1): \
             files {:?} vs {:?}; differing {differing:?}",
            got.keys().collect::<Vec<_>>(),
            want.keys().collect::<Vec<_>>()
        );
        passed += 1;
    }
    println!("torture: kills landed in {tally:?}");
    println!(
        "torture: {passed}/{trials} trials identical to the uninterrupted run in {:.1} s",
        started.elapsed().as_secs_f64()
    );
}
