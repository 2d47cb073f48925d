//! Storage failures under `eyeadapt sequence`: a full disk, a read-only file system and an
//! output path that is a file. Each must end with a clear message and the documented exit
//! code, leave every frame committed before the failure byte-for-byte intact (and the CSV
//! without a torn row), and a resume once the storage is fixed must produce exactly what an
//! uninterrupted run produces.
//!
//! Exit codes: disk full is 75 (freeing space and retrying succeeds). A read-only file system
//! is also 75: the directory was writable when the job was planned, and read-only storage is
//! an administrative state (a remount after errors, maintenance, a snapshot), not a property
//! of the job, so a retry after the storage is back resumes where the job stopped; farm
//! submitters cap exit-75 retries. An output path that is a file is bad usage: 2.
//!
//! The full-disk and read-only cases mount small tmpfs file systems and need root (root also
//! ignores `chmod`, which is why read-only is a mount here); without root they print why they
//! are skipped and pass.
mod common;

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::Command;

const ARGS: &[&str] = &["--width", "32", "--height", "18"];

struct Run {
    code: i32,
    stderr: String,
}

fn sequence(out: &Path, extra: &[&str]) -> Run {
    let frames: &[&str] = if extra.contains(&"--frames") {
        &[]
    } else {
        &["--frames", "0-11"]
    };
    let o = Command::new(env!("CARGO_BIN_EXE_eyeadapt"))
        .arg("sequence")
        .args(ARGS)
        .args(common::QUICK)
        .args(frames)
        .args(extra)
        .args(["--out", out.to_str().unwrap()])
        .output()
        .unwrap();
    Run {
        code: o.status.code().unwrap_or(-1),
        stderr: String::from_utf8_lossy(&o.stderr).into_owned(),
    }
}

fn ok(out: &Path, extra: &[&str]) {
    let r = sequence(out, extra);
    assert_eq!(r.code, 0, "sequence failed: {}", r.stderr);
}

/// Every file except the lock, by relative path (raw bytes).
fn snapshot(dir: &Path) -> BTreeMap<String, Vec<u8>> {
    common::walk(dir)
        .into_iter()
        .filter(|(rel, _)| rel != ".eyeadapt.lock")
        .map(|(rel, p)| (rel, std::fs::read(&p).unwrap()))
        .collect()
}

/// Frames committed in `dir`'s manifest, with their files.
fn committed(dir: &Path) -> BTreeMap<u32, Vec<String>> {
    let Some(m) = eyeadapt_sequencer::manifest::Manifest::load(dir).unwrap() else {
        return BTreeMap::new();
    };
    m.frames
        .iter()
        .map(|(f, e)| (*f, e.files.iter().map(|x| x.path.clone()).collect()))
        .collect()
}

/// The damage check: every file of every committed frame equals the reference's, no
/// temporary file is left, and `adaptation.csv` is exactly the header plus the committed
/// frames' rows of the reference (so no torn or uncommitted row either).
fn assert_committed_intact(dir: &Path, reference: &BTreeMap<String, Vec<u8>>, what: &str) {
    let have = snapshot(dir);
    for rel in have.keys() {
        assert!(!rel.contains(".tmp-"), "{what}: temporary file left: {rel}");
    }
    let frames = committed(dir);
    for (f, files) in &frames {
        for rel in files {
            assert!(
                have.get(rel) == reference.get(rel),
                "{what}: file {rel} of committed frame {f} differs from the reference"
            );
        }
    }
    if let Some(csv) = have.get("adaptation.csv") {
        let want: String = String::from_utf8_lossy(&reference["adaptation.csv"])
            .lines()
            .enumerate()
            .filter(|(i, l)| {
                *i == 0
                    || l.split(',')
                        .next()
                        .and_then(|f| f.parse().ok())
                        .is_some_and(|f: u32| frames.contains_key(&f))
            })
            .map(|(_, l)| format!("{l}\n"))
            .collect();
        let have = String::from_utf8_lossy(csv);
        let extra: Vec<&str> = have.lines().filter(|l| !want.contains(l)).collect();
        assert!(
            have == want,
            "{what}: adaptation.csv is not exactly the committed frames' rows ({} lines, want \
             {}; committed frames {:?}; lines not in the reference's committed rows: {extra:?})",
            have.lines().count(),
            want.lines().count(),
            frames.keys().collect::<Vec<_>>()
        );
    }
}

fn is_root() -> bool {
    Command::new("id")
        .arg("-u")
        .output()
        .is_ok_and(|o| String::from_utf8_lossy(&o.stdout).trim() == "0")
}

/// A tmpfs mounted for the life of the value.
struct Tmpfs {
    dir: PathBuf,
}

impl Tmpfs {
    /// `None` (with the reason printed) when mounting is impossible here.
    fn mount(dir: &Path, options: &str) -> Option<Tmpfs> {
        if !is_root() {
            println!("skipped: mounting a tmpfs needs root");
            return None;
        }
        std::fs::create_dir_all(dir).unwrap();
        let o = Command::new("mount")
            .args(["-t", "tmpfs", "-o", options, "eyeadapt-test"])
            .arg(dir)
            .output();
        match o {
            Ok(o) if o.status.success() => Some(Tmpfs {
                dir: dir.to_path_buf(),
            }),
            Ok(o) => {
                println!(
                    "skipped: cannot mount a tmpfs here: {}",
                    String::from_utf8_lossy(&o.stderr).trim()
                );
                None
            }
            Err(e) => {
                println!("skipped: no mount command: {e}");
                None
            }
        }
    }

    fn remount(&self, options: &str) {
        let o = Command::new("mount")
            .args(["-o", &format!("remount,{options}")])
            .arg(&self.dir)
            .output()
            .unwrap();
        assert!(
            o.status.success(),
            "remount {options}: {}",
            String::from_utf8_lossy(&o.stderr)
        );
    }
}

impl Drop for Tmpfs {
    fn drop(&mut self) {
        let _ = Command::new("umount").arg("-l").arg(&self.dir).status();
    }
}

fn reference(root: &Path) -> BTreeMap<String, Vec<u8>> {
    let r = root.join("reference");
    ok(&r, &[]);
    snapshot(&r)
}

#[test]
fn disk_full_at_many_points_exits_75_keeps_committed_frames_and_resumes() {
    let t = tempfile::tempdir().unwrap();
    let want = reference(t.path());
    let total: usize = want.values().map(Vec::len).sum();
    // Sizes from about a fifth to nine tenths of the finished output, in steps that are not
    // multiples of the 4 KiB page, so the disk fills up in different files: EXRs, PNGs, row
    // files, the CSV append and the manifest.
    let steps = 14;
    let mut failed_in: BTreeMap<String, usize> = BTreeMap::new();
    for k in 0..steps {
        let size_k = (total / 5 + k * (total * 7 / 10) / steps) / 1024 + 4;
        let Some(fs) = Tmpfs::mount(
            &t.path().join(format!("m{k}")),
            &format!("size={size_k}k,mode=0755"),
        ) else {
            return;
        };
        let out = fs.dir.join("out");
        let r = sequence(&out, &[]);
        let what = format!("tmpfs size={size_k}k");
        if r.code == 0 {
            // Everything fitted (page rounding): nothing to check beyond equality.
            assert_eq!(snapshot(&out), want, "{what}");
            continue;
        }
        assert_eq!(r.code, 75, "{what}: exit code; stderr:\n{}", r.stderr);
        assert!(
            r.stderr.contains("No space left on device") && r.stderr.contains("retrying"),
            "{what}: unclear message:\n{}",
            r.stderr
        );
        let file = r
            .stderr
            .split_whitespace()
            .find(|w| w.contains("/out/"))
            .map_or("?".to_string(), |w| {
                let name = w.rsplit('/').next().unwrap().trim_end_matches(':');
                // .frame_000003.png.tmp-123 -> png; manifest.json -> manifest.json
                let name = name.split(".tmp-").next().unwrap();
                match name.rsplit_once('.') {
                    Some((stem, ext)) if stem.contains("frame_") => ext.to_string(),
                    _ => name.trim_start_matches('.').to_string(),
                }
            });
        *failed_in.entry(file).or_default() += 1;
        assert_committed_intact(&out, &want, &what);
        let before = committed(&out).len();
        // A second attempt on the still-full disk fails the same way and damages nothing.
        let again = sequence(&out, &[]);
        assert_eq!(again.code, 75, "{what}, second attempt:\n{}", again.stderr);
        assert_committed_intact(&out, &want, &format!("{what}, second attempt"));
        assert!(committed(&out).len() >= before);
        // Free space and resume.
        fs.remount("size=64m");
        ok(&out, &[]);
        assert_eq!(snapshot(&out), want, "{what}: resumed output differs");
    }
    println!("disk full: the failing write was in {failed_in:?}");
    assert!(
        failed_in.values().sum::<usize>() >= steps / 2,
        "most sizes must run out of space"
    );
}

#[test]
fn read_only_file_system_exits_75_untouched_and_resumes_after_remount() {
    let t = tempfile::tempdir().unwrap();
    let want = reference(t.path());
    let Some(fs) = Tmpfs::mount(&t.path().join("m"), "size=64m,mode=0755") else {
        return;
    };
    let out = fs.dir.join("out");
    ok(&out, &["--frames", "0-4"]);
    let before = snapshot(&out);
    fs.remount("ro");
    let r = sequence(&out, &[]);
    assert_eq!(r.code, 75, "read-only: exit code; stderr:\n{}", r.stderr);
    assert!(
        r.stderr.contains("Read-only file system") && r.stderr.contains(out.to_str().unwrap()),
        "read-only: the message must say so and name the directory:\n{}",
        r.stderr
    );
    assert_eq!(snapshot(&out), before, "read-only run changed files");
    assert_committed_intact(&out, &want, "read-only");
    assert_eq!(committed(&out).len(), 5);
    fs.remount("rw");
    ok(&out, &[]);
    assert_eq!(snapshot(&out), want, "resumed after remount rw");
}

#[test]
fn output_path_that_is_a_file_exits_2_and_leaves_it_alone() {
    let t = tempfile::tempdir().unwrap();
    let file = t.path().join("not-a-dir");
    std::fs::write(&file, b"precious").unwrap();
    for out in [file.clone(), file.join("sub")] {
        let r = sequence(&out, &[]);
        assert_eq!(r.code, 2, "--out {}: stderr:\n{}", out.display(), r.stderr);
        assert!(
            r.stderr.contains(file.to_str().unwrap()) && r.stderr.contains("not a directory"),
            "--out {}: the message must name the file:\n{}",
            out.display(),
            r.stderr
        );
        let o = common::tiny_render(&out).output().unwrap();
        assert_eq!(o.status.code(), Some(2), "render --out {}", out.display());
    }
    assert_eq!(std::fs::read(&file).unwrap(), b"precious");
}
