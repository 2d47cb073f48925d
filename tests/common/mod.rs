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
