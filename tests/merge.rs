//! `eyeadapt merge` end to end: chunks chosen in any way join into the whole run, and a
//! damaged chunk (truncated file, wrong checksum, missing file) is refused before anything is
//! written (issue #17, #18 class 1).
mod common;

use common::{QUICK, snapshot};
use std::path::{Path, PathBuf};
use std::process::Command;

fn eyeadapt() -> Command {
    Command::new(env!("CARGO_BIN_EXE_eyeadapt"))
}

/// A job whose own frames are 0-5, tiny and fast.
fn job(dir: &Path) -> PathBuf {
    let p = dir.join("six.toml");
    std::fs::write(
        &p,
        "name = \"six\"\nscene = \"builtin:three-rooms\"\nframes = \"0-5\"\n\
         [render]\nwidth = 12\nheight = 8\n[estimators]\nlist = [\"eye\", \"wcam\"]\n",
    )
    .unwrap();
    p
}

fn sequence(job: &Path, out: &Path, select: &[&str]) {
    let o = eyeadapt()
        .arg("sequence")
        .arg(job)
        .args(select)
        .args(QUICK)
        .arg("--out")
        .arg(out)
        .output()
        .unwrap();
    assert!(
        o.status.success(),
        "sequence {select:?}: {}",
        String::from_utf8_lossy(&o.stderr)
    );
}

fn merge(dirs: &[&Path], out: &Path, extra: &[&str]) -> (i32, String) {
    let o = eyeadapt()
        .arg("merge")
        .args(dirs)
        .arg("--out")
        .arg(out)
        .args(extra)
        .output()
        .unwrap();
    (
        o.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&o.stderr).into_owned(),
    )
}

#[test]
fn chunks_chosen_in_every_way_merge_into_the_whole_run() {
    let t = tempfile::tempdir().unwrap();
    let job = job(t.path());
    let whole = t.path().join("whole");
    sequence(&job, &whole, &[]);
    // Frames 0-1 by chunk index, 2-3 by start/end, 4 by a frame spec, 5 in Blender's form.
    let parts: [(&str, &[&str]); 4] = [
        ("a", &["--chunk-size", "2", "--chunk-index", "0"]),
        ("b", &["--start", "2", "--end", "3"]),
        ("c", &["--frames", "4"]),
        ("d", &["--frames", "5..5"]),
    ];
    let dirs: Vec<PathBuf> = parts
        .iter()
        .map(|(name, sel)| {
            let d = t.path().join(name);
            sequence(&job, &d, sel);
            d
        })
        .collect();
    let refs: Vec<&Path> = dirs.iter().map(|d| d.as_path()).collect();
    let merged = t.path().join("merged");
    let (code, err) = merge(&refs, &merged, &[]);
    assert_eq!(code, 0, "{err}");
    assert_eq!(snapshot(&whole), snapshot(&merged), "merge vs whole run");

    // Without chunk d the job's frame 5 is a gap; naming the part wanted merges it.
    let part = t.path().join("part");
    let (code, err) = merge(&refs[..3], &part, &[]);
    assert_eq!(code, 2);
    assert!(
        err.contains("gap: 1 frame(s) of the job's selection are in no input: 5"),
        "{err}"
    );
    assert!(!part.exists(), "a refused merge created its --out");
    let (code, err) = merge(&refs[..3], &part, &["--frames", "1-4"]);
    assert_eq!(code, 0, "{err}");
    let m = eyeadapt_sequencer::manifest::Manifest::load(&part)
        .unwrap()
        .unwrap();
    assert_eq!(m.frames.keys().copied().collect::<Vec<_>>(), [1, 2, 3, 4]);
    assert_eq!((m.planned.as_str(), m.job_frames.as_str()), ("1-4", "0-5"));
    let (code, err) = merge(&refs[..3], &part, &["--frames", "4-9"]);
    assert_eq!(code, 2);
    assert!(
        err.contains("outside the job's frames 0-5 (first: 6)"),
        "{err}"
    );
}

/// Damages a chunk directory in place.
type Damage<'a> = &'a dyn Fn(&Path);

/// Damages a copy of a good chunk in one way; the merge must exit 2 naming the chunk, the
/// frame and the file, and leave `--out` as it was (a good earlier merge, or nothing).
#[test]
fn damaged_chunks_are_refused_before_anything_is_written() {
    let t = tempfile::tempdir().unwrap();
    let job = job(t.path());
    let a = t.path().join("a");
    let b = t.path().join("b");
    sequence(&job, &a, &["--frames", "0-2"]);
    sequence(&job, &b, &["--frames", "3-5"]);
    let good = t.path().join("good");
    assert_eq!(merge(&[&a, &b], &good, &[]).0, 0);
    let before = snapshot(&good);

    let exr = "frames/raw/frame_000004.exr";
    let damages: [(&str, Damage, &str); 3] = [
        (
            "truncated",
            &|d| {
                let bytes = std::fs::read(d.join(exr)).unwrap();
                std::fs::write(d.join(exr), &bytes[..100]).unwrap();
            },
            "has 100 bytes, the manifest says",
        ),
        (
            "checksum",
            &|d| {
                let p = d.join("manifest.json");
                let text = std::fs::read_to_string(&p).unwrap();
                let m = eyeadapt_sequencer::manifest::Manifest::load(d)
                    .unwrap()
                    .unwrap();
                let sum = &m.frames[&4].files[0].sha256_128;
                std::fs::write(&p, text.replace(sum.as_str(), &"f".repeat(32))).unwrap();
            },
            "the manifest says ffffffffffffffffffffffffffffffff",
        ),
        (
            "missing",
            &|d| std::fs::remove_file(d.join(exr)).unwrap(),
            "is missing",
        ),
    ];
    for (name, damage, says) in damages {
        let bad = t.path().join(format!("bad-{name}"));
        copy_dir(&b, &bad);
        damage(&bad);
        for out in [good.clone(), t.path().join(format!("fresh-{name}"))] {
            let existed = out.exists();
            let (code, err) = merge(&[&a, &bad], &out, &[]);
            assert_eq!(code, 2, "{name}: {err}");
            let chunk = format!("damaged chunk {}: frame 4: {exr} ", bad.display());
            assert!(err.contains(&chunk) && err.contains(says), "{name}: {err}");
            if existed {
                assert_eq!(before, snapshot(&out), "{name}: --out changed");
            } else {
                assert!(!out.exists(), "{name}: a refused merge created --out");
            }
        }
    }
}

fn copy_dir(from: &Path, to: &Path) {
    for (rel, p) in common::walk(from) {
        let dst = to.join(rel);
        std::fs::create_dir_all(dst.parent().unwrap()).unwrap();
        std::fs::copy(p, dst).unwrap();
    }
}
