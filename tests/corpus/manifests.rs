//! Output directories are input too: manifests that claim too little or too much are
//! refused with exit 2, never a panic or a write outside `--out`.
use super::harness::*;

/// Output directories are input too: a manifest whose job hash is short (or not ASCII) must be
/// refused with exit 2, not panic on slicing it (`sequence` printed its first 12 bytes).
#[test]
fn a_foreign_manifest_with_a_short_hash_is_refused_not_a_panic() {
    let t = tempfile::tempdir().unwrap();
    let out = t.path().join("out");
    must(
        eyeadapt()
            .args(["sequence", "--frames", "0-1"])
            .args(SEQ)
            .arg("--out")
            .arg(&out),
    );
    let m = std::fs::read_to_string(out.join("manifest.json")).unwrap();
    let start = m.find("\"job_hash\": \"").unwrap() + "\"job_hash\": \"".len();
    let end = start + m[start..].find('"').unwrap();
    // Byte 12 of the second one falls inside a character.
    for hash in ["abc", "aéééééééé"] {
        std::fs::write(
            out.join("manifest.json"),
            format!("{}{hash}{}", &m[..start], &m[end..]),
        )
        .unwrap();
        let before = snapshot(&out);
        let (code, err) = run(eyeadapt()
            .args(["sequence", "--frames", "0-1"])
            .args(SEQ)
            .arg("--out")
            .arg(&out));
        assert_eq!(code, 2, "{hash}: {err}");
        assert!(
            err.contains("refusing to mix") && err.contains(&hash[..3]),
            "{err}"
        );
        assert_eq!(before, snapshot(&out), "{hash}: the refusal changed files");
    }
}

/// Hostile chunk manifests (these were bugs, found by this corpus): a chunk manifest whose `job_hash` is
/// shorter than 12 bytes panics (exit 101) when the hashes differ, and a file `path` with `..`
/// makes merge read a file outside the chunk and write it outside `--out`.
#[test]
fn merge_refuses_hostile_chunk_manifests() {
    let t = tempfile::tempdir().unwrap();
    let root = t.path();
    let chunk = |i: usize| render_chunk(root, "c", i);
    let (c0, c1) = (chunk(0), chunk(1));
    let manifest = std::fs::read_to_string(c1.join("manifest.json")).unwrap();
    // 1. A short hash that differs from the other chunk's.
    let short = root.join("short");
    copy_dir(&c1, &short);
    let start = manifest.find("\"job_hash\": \"").unwrap() + "\"job_hash\": \"".len();
    let end = start + manifest[start..].find('"').unwrap();
    std::fs::write(
        short.join("manifest.json"),
        format!("{}abc{}", &manifest[..start], &manifest[end..]),
    )
    .unwrap();
    let (code, err) = run(eyeadapt()
        .arg("merge")
        .args([&c0, &short])
        .arg("--out")
        .arg(root.join("m1")));
    assert_eq!(code, 2, "short hash: {err}");
    // 2. A file path that climbs out of the chunk (and so out of --out).
    let climb = root.join("climb");
    copy_dir(&c1, &climb);
    std::fs::write(root.join("outside.txt"), "outside").unwrap();
    // (The checksum does not matter: merge copies before anything compares it.)
    let entry = "\"files\": [\n        {\n          \"path\": \"../outside.txt\",\n          \"bytes\": 7,\n          \"sha256_128\": \"00000000000000000000000000000000\"\n        },";
    std::fs::write(
        climb.join("manifest.json"),
        manifest.replacen("\"files\": [", entry, 1),
    )
    .unwrap();
    let out = root.join("deep").join("m2");
    let (code, err) = run(eyeadapt()
        .arg("merge")
        .args([&c0, &climb])
        .arg("--out")
        .arg(&out));
    assert_eq!(code, 2, "`..` path: {err}");
    assert!(
        !root.join("deep").join("outside.txt").exists(),
        "merge wrote outside --out"
    );
}
