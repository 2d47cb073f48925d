//! Helpers shared by the integration tests (each test file includes this with `mod common;`
//! and uses what it needs).
#![allow(dead_code)]
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

/// The cheap tail of a test's `sequence` command line: one sample per pixel, a small eye
/// budget, no report, no progress bar.
pub const QUICK: &[&str] = &[
    "--spp",
    "1",
    "--eye-samples",
    "64",
    "--no-report",
    "--no-progress-bar",
];

/// `eyeadapt render builtin:cornell-box` at 8 × 8 and 1 spp into `out`: the cheapest render
/// command, for tests of what happens around rendering.
pub fn tiny_render(out: &Path) -> std::process::Command {
    let mut c = std::process::Command::new(env!("CARGO_BIN_EXE_eyeadapt"));
    c.args([
        "render",
        "builtin:cornell-box",
        "--width",
        "8",
        "--height",
        "8",
    ])
    .args(["--spp", "1", "--out"])
    .arg(out);
    c
}

/// Every file under `dir`, as (path relative to `dir`, full path); empty when `dir` does not
/// exist.
pub fn walk(dir: &Path) -> Vec<(String, PathBuf)> {
    let mut out = Vec::new();
    if !dir.exists() {
        return out;
    }
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        for e in std::fs::read_dir(&d).unwrap() {
            let p = e.unwrap().path();
            if p.is_dir() {
                stack.push(p);
            } else {
                out.push((
                    p.strip_prefix(dir).unwrap().to_string_lossy().into_owned(),
                    p,
                ));
            }
        }
    }
    out
}

/// Every file of a sequence output except the lock, by relative path, asserting that no
/// temporary file is left; EXRs as their size plus the bits of every decoded channel (so
/// equal snapshots mean equal pixels and AOVs, whatever the compressor wrote).
pub fn snapshot(dir: &Path) -> BTreeMap<String, Vec<u8>> {
    let mut out = BTreeMap::new();
    for (rel, p) in walk(dir) {
        if rel == ".eyeadapt.lock" {
            continue;
        }
        assert!(!rel.contains(".tmp-"), "temporary file left behind: {rel}");
        let bytes = if rel.ends_with(".exr") {
            let f = eyeadapt_sequencer::output::read_exr(&p).unwrap();
            let mut b = format!("{}x{}", f.width, f.height).into_bytes();
            for v3 in [&f.rgb, &f.albedo, &f.achromatic, &f.irradiance, &f.normal] {
                b.extend(v3.iter().flatten().flat_map(|v| v.to_bits().to_le_bytes()));
            }
            for v in [&f.depth, &f.emitter, &f.hit] {
                b.extend(v.iter().flat_map(|v| v.to_bits().to_le_bytes()));
            }
            b
        } else {
            std::fs::read(&p).unwrap()
        };
        out.insert(rel, bytes);
    }
    out
}

/// What a SIGKILLed `sequence` run may leave in `dir/adaptation.csv`: the header, the rows of
/// every committed frame whole, then at most a prefix of the row file of the frame in flight.
/// The frame's rows go to the CSV in one `write`, but Linux ends a write to a regular file
/// short when a fatal signal arrives between two of its pages, so a kill can cut that frame's
/// rows anywhere; the next run rebuilds the CSV from the committed row files. Frames are
/// committed in order, so the frame in flight, if any, has the last row file. Returns true
/// when the CSV ends inside the frame in flight.
pub fn assert_killed_csv_intact(dir: &Path, committed: usize) -> bool {
    let Ok(csv) = std::fs::read_to_string(dir.join("adaptation.csv")) else {
        return false;
    };
    let Some((header, _)) = csv.split_once('\n') else {
        assert!(csv.is_empty(), "the CSV's header is torn: {csv:?}");
        return false;
    };
    // The committed and in-flight row files, not a killed write's temporary file
    // (`.frame_NNNNNN.csv.tmp-PID`, which the next run removes): sorted with them, it came
    // first and shifted every frame (a failure seen under load, when kills land in writes).
    let mut rows: Vec<_> = walk(&dir.join("rows"))
        .into_iter()
        .filter(|(name, _)| !name.starts_with('.'))
        .collect();
    rows.sort();
    let files: Vec<String> = rows
        .iter()
        .map(|(_, p)| std::fs::read_to_string(p).unwrap())
        .collect();
    assert!(
        files.len() <= committed + 1,
        "{} row files for {committed} committed frames",
        files.len()
    );
    let committed_text = format!("{header}\n{}", files[..committed.min(files.len())].concat());
    let everything = format!("{header}\n{}", files.concat());
    assert!(
        csv.starts_with(&committed_text),
        "a committed frame's rows are missing or torn in the CSV:\n{csv}"
    );
    assert!(
        everything.starts_with(&csv),
        "the CSV holds more than the row files:\n{csv}"
    );
    !csv.ends_with('\n')
}
