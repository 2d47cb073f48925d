//! The malformed-input corpus (`tests/corpus/`, format in its README): every case must exit
//! with code 2, print its expected location and message parts, and leave an output directory
//! that already held good results byte-for-byte unchanged.
//!
//! | directory | case | command |
//! |---|---|---|
//! | `scene/` | `NAME.toml` | `eyeadapt render CASE` into a directory holding a good render |
//! | `obj/` | `NAME.obj` (+ `NAME.mtl`) | `render` of a scene whose only shape is the OBJ |
//! | `job/` | `NAME.toml` | `eyeadapt sequence CASE` into a directory holding a good sequence |
//! | `frames/` | `NAME.spec` | `eyeadapt sequence --frames SPEC` into the same directory |
//! | `merge/` | `NAME/` (a chunk output) | `eyeadapt merge GOOD_CHUNK CASE` into a good merge |
//! | `xml/` | `NAME.xml` | `eyeadapt render CASE` (Mitsuba 3 XML) into the good render |
//! | `fuzz-regressions/` | inputs the fuzzers once crashed on | see `fuzz_regressions` below |
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::Command;

fn corpus() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/corpus")
}

fn eyeadapt() -> Command {
    Command::new(env!("CARGO_BIN_EXE_eyeadapt"))
}

/// Small sequences: the built-in demo job at 8×6, 1 spp.
const SEQ: &[&str] = &[
    "--width",
    "8",
    "--height",
    "6",
    "--spp",
    "1",
    "--eye-samples",
    "32",
    "--no-report",
    "--no-progress-bar",
];

/// Scenes render at their own size (8×6 or 16×12), so that a scene's size is what is checked.
const RENDER: &[&str] = &["--spp", "1"];

/// Job files bring their own settings.
const JOB: &[&str] = &["--no-report", "--no-progress-bar"];

fn run(cmd: &mut Command) -> (i32, String) {
    let o = cmd.output().unwrap();
    (
        o.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&o.stderr).into_owned(),
    )
}

fn must(cmd: &mut Command) {
    let (code, err) = run(cmd);
    assert_eq!(code, 0, "setup command failed: {cmd:?}\n{err}");
}

/// Every file of a directory with its bytes and modification time.
fn snapshot(dir: &Path) -> BTreeMap<String, (Vec<u8>, std::time::SystemTime)> {
    let mut out = BTreeMap::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        for e in std::fs::read_dir(&d).unwrap() {
            let p = e.unwrap().path();
            if p.is_dir() {
                stack.push(p);
                continue;
            }
            let rel = p.strip_prefix(dir).unwrap().to_string_lossy().into_owned();
            let meta = std::fs::metadata(&p).unwrap();
            out.insert(rel, (std::fs::read(&p).unwrap(), meta.modified().unwrap()));
        }
    }
    out
}

/// A case's `.expected` file: `at: FILE:LINE` (or `FILE`, or `none` where the input is not a
/// file, e.g. a frame spec given on the command line), any number of `message: TEXT`, optional
/// `inputs: …` (merge). Lines starting with `#` are comments.
#[derive(Debug, Default)]
struct Expected {
    at: Option<String>,
    messages: Vec<String>,
    inputs: Option<String>,
}

fn expected(path: &Path) -> Expected {
    let text = std::fs::read_to_string(path)
        .unwrap_or_else(|e| panic!("{}: {e} (every case needs one)", path.display()));
    let mut x = Expected::default();
    for l in text.lines() {
        if l.trim().is_empty() || l.starts_with('#') {
            continue;
        }
        let (k, v) = l
            .split_once(": ")
            .or_else(|| l.split_once(':'))
            .unwrap_or_else(|| panic!("{}: bad line {l:?}", path.display()));
        match k {
            "at" => x.at = (v != "none").then(|| v.to_string()),
            "message" => x.messages.push(v.to_string()),
            "inputs" => x.inputs = Some(v.to_string()),
            _ => panic!("{}: unknown key {k:?}", path.display()),
        }
    }
    assert!(
        text.lines().any(|l| l.starts_with("at:")),
        "{}: needs an `at:` line",
        path.display()
    );
    x
}

/// `FILE:LINE` appears as `FILE:LINE:` (our diagnostics) or as `FILE` … `line LINE column`
/// (serde_json's); a bare `FILE` just appears.
fn located(stderr: &str, at: &str) -> bool {
    match at.rsplit_once(':') {
        Some((file, line)) if line.chars().all(|c| c.is_ascii_digit()) => {
            stderr.contains(&format!("{at}:"))
                || (stderr.contains(file) && stderr.contains(&format!("line {line} column")))
        }
        _ => stderr.contains(at),
    }
}

struct Outcome {
    case: String,
    problems: Vec<String>,
}

fn check(case: &str, code: i32, stderr: &str, x: &Expected) -> Outcome {
    let mut problems = Vec::new();
    if code != 2 {
        problems.push(format!("exit code {code}, want 2"));
    }
    if let Some(at) = &x.at
        && !located(stderr, at)
    {
        problems.push(format!("location {at} not in the message"));
    }
    for m in &x.messages {
        if !stderr.contains(m.as_str()) {
            problems.push(format!("{m:?} not in the message"));
        }
    }
    if stderr.contains("panicked") || stderr.contains("RUST_BACKTRACE") {
        problems.push("panicked".into());
    }
    if !problems.is_empty() {
        problems.push(format!("stderr was:\n{stderr}"));
    }
    Outcome {
        case: case.to_string(),
        problems,
    }
}

/// Cases of one directory: files with extension `ext` (or subdirectories when `ext` is empty).
fn cases(dir: &str, ext: &str) -> Vec<(String, PathBuf, Expected)> {
    let d = corpus().join(dir);
    let Ok(entries) = std::fs::read_dir(&d) else {
        return Vec::new();
    };
    let mut out: Vec<_> = entries
        .map(|e| e.unwrap().path())
        .filter(|p| {
            if ext.is_empty() {
                p.is_dir()
            } else {
                p.extension().is_some_and(|e| e == ext)
            }
        })
        .map(|p| {
            let stem = p.file_stem().unwrap().to_string_lossy().into_owned();
            let x = expected(&d.join(format!("{stem}.expected")));
            (format!("{dir}/{stem}"), p, x)
        })
        .collect();
    out.sort_by(|a, b| a.0.cmp(&b.0));
    out
}

/// Replaces `@NAME@` placeholders in every file of a copied merge case.
fn instantiate(src: &Path, dst: &Path, vars: &[(&str, String)]) {
    std::fs::create_dir_all(dst).unwrap();
    for e in std::fs::read_dir(src).unwrap() {
        let p = e.unwrap().path();
        let to = dst.join(p.file_name().unwrap());
        if p.is_dir() {
            instantiate(&p, &to, vars);
        } else {
            let mut bytes = std::fs::read(&p).unwrap();
            if let Ok(mut text) = String::from_utf8(bytes.clone()) {
                for (k, v) in vars {
                    text = text.replace(&format!("@{k}@"), v);
                }
                bytes = text.into_bytes();
            }
            std::fs::write(to, bytes).unwrap();
        }
    }
}

#[test]
fn every_malformed_input_exits_2_with_its_location_and_leaves_outputs_alone() {
    let t = tempfile::tempdir().unwrap();
    let root = t.path();
    // Good outputs first.
    let render_out = root.join("render-out");
    let good_scene = corpus().join("good/scene.toml");
    must(
        eyeadapt()
            .arg("render")
            .arg(&good_scene)
            .args(RENDER)
            .arg("--out")
            .arg(&render_out),
    );
    let seq_out = root.join("seq-out");
    must(
        eyeadapt()
            .args(["sequence", "--frames", "0-3"])
            .args(SEQ)
            .arg("--out")
            .arg(&seq_out),
    );
    let chunk = |i: usize| {
        let d = root.join(format!("chunk{i}"));
        must(
            eyeadapt()
                .args(["sequence", "--frames", "0-3", "--chunk-size", "2"])
                .args(["--chunk-index", &i.to_string()])
                .args(SEQ)
                .arg("--out")
                .arg(&d),
        );
        d
    };
    let (chunk0, chunk1) = (chunk(0), chunk(1));
    let merge_out = root.join("merge-out");
    must(
        eyeadapt()
            .arg("merge")
            .args([&chunk0, &chunk1])
            .arg("--out")
            .arg(&merge_out),
    );
    let chunk1_manifest = std::fs::read_to_string(chunk1.join("manifest.json")).unwrap();
    let m = eyeadapt_sequencer::manifest::Manifest::load(&chunk1)
        .unwrap()
        .unwrap();
    let vars = [
        ("JOB_HASH", m.job_hash.clone()),
        ("JOB_FRAMES", m.job_frames.clone()),
        ("SETTINGS", serde_settings(&chunk1_manifest)),
    ];

    let before = [&render_out, &seq_out, &merge_out, &chunk0].map(|d| snapshot(d));
    let mut outcomes = Vec::new();

    for (case, path, x) in cases("scene", "toml")
        .into_iter()
        .chain(cases("xml", "xml"))
    {
        let (code, err) = run(eyeadapt()
            .arg("render")
            .arg(&path)
            .args(RENDER)
            .arg("--out")
            .arg(&render_out));
        outcomes.push(check(&case, code, &err, &x));
    }
    for (case, path, x) in cases("obj", "obj") {
        // A scene in a scratch directory whose only shape is the corpus OBJ (absolute path, so
        // its MTL resolves next to it).
        let d = root.join("obj-scenes").join(path.file_stem().unwrap());
        std::fs::create_dir_all(&d).unwrap();
        let scene = d.join("scene.toml");
        std::fs::write(
            &scene,
            format!(
                "[camera]\nposition = [0.3, 0.3, 3.0]\nlook_at = [0.3, 0.3, 0.0]\nfov_deg = 45.0\n\
                 width = 8\nheight = 6\n\n[[shapes]]\ntype = \"obj\"\nfile = {:?}\n\n\
                 [environment]\nradiance = [1.0, 1.0, 1.0]\n",
                path.to_str().unwrap()
            ),
        )
        .unwrap();
        let (code, err) = run(eyeadapt()
            .arg("render")
            .arg(&scene)
            .args(RENDER)
            .arg("--out")
            .arg(&render_out));
        let mut o = check(&case, code, &err, &x);
        if !err.contains("scene.toml:10:") {
            o.problems.push(format!(
                "the scene's `file` line (scene.toml:10) not named:\n{err}"
            ));
        }
        outcomes.push(o);
    }
    for (case, path, x) in cases("job", "toml") {
        let (code, err) = run(eyeadapt()
            .arg("sequence")
            .arg(&path)
            .args(JOB)
            .arg("--out")
            .arg(&seq_out));
        outcomes.push(check(&case, code, &err, &x));
    }
    for (case, path, x) in cases("frames", "spec") {
        let spec = std::fs::read_to_string(&path).unwrap();
        let spec = spec.strip_suffix('\n').unwrap_or(&spec);
        let (code, err) = run(eyeadapt()
            .arg("sequence")
            .arg(format!("--frames={spec}"))
            .args(SEQ)
            .arg("--out")
            .arg(&seq_out));
        outcomes.push(check(&case, code, &err, &x));
    }
    for (case, path, x) in cases("merge", "") {
        let dir = root.join("merge-cases").join(path.file_name().unwrap());
        instantiate(&path, &dir, &vars);
        let mut cmd = eyeadapt();
        cmd.arg("merge");
        match x.inputs.as_deref() {
            Some("case") => cmd.arg(&dir),
            None | Some("chunk0 case") => cmd.arg(&chunk0).arg(&dir),
            Some(other) => panic!("{case}: unknown inputs {other:?}"),
        };
        let (code, err) = run(cmd.arg("--out").arg(&merge_out));
        outcomes.push(check(&case, code, &err, &x));
    }

    let after = [&render_out, &seq_out, &merge_out, &chunk0].map(|d| snapshot(d));
    for (b, a) in before.iter().zip(&after) {
        let changed: Vec<&String> = b
            .keys()
            .chain(a.keys())
            .filter(|k| b.get(*k) != a.get(*k) && !k.ends_with(".eyeadapt.lock"))
            .collect();
        assert!(
            changed.is_empty(),
            "bad inputs changed outputs: {changed:?}"
        );
    }
    let failed: Vec<&Outcome> = outcomes.iter().filter(|o| !o.problems.is_empty()).collect();
    for o in &failed {
        eprintln!("--- {}: {}", o.case, o.problems.join("\n    "));
    }
    let mut per_dir: BTreeMap<&str, usize> = BTreeMap::new();
    for o in &outcomes {
        *per_dir
            .entry(o.case.split('/').next().unwrap())
            .or_default() += 1;
    }
    println!(
        "corpus: {} cases {per_dir:?}, {} as expected, {} not",
        outcomes.len(),
        outcomes.len() - failed.len(),
        failed.len()
    );
    assert!(failed.is_empty(), "{} corpus case(s) failed", failed.len());
    assert!(
        outcomes.len() >= 40,
        "the corpus shrank to {}",
        outcomes.len()
    );
}

/// The `settings` object of a manifest, as JSON text on one line (so that the line numbers of
/// a case's manifest do not move), for merge cases that need a valid one.
fn serde_settings(manifest: &str) -> String {
    let start = manifest.find("\"settings\": {").unwrap() + "\"settings\": ".len();
    let end = start + manifest[start..].find('}').unwrap() + 1;
    manifest[start..end]
        .lines()
        .map(str::trim)
        .collect::<Vec<_>>()
        .join(" ")
}
