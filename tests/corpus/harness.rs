//! The corpus harness: where the cases are, how `eyeadapt` runs on them, what a case's
//! `.expected` file says and how an outcome is checked against it, the good outputs a bad
//! input must leave alone, and the tally each kind's test ends with.
use super::common;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::Command;

pub fn corpus() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/corpus")
}

pub fn eyeadapt() -> Command {
    Command::new(env!("CARGO_BIN_EXE_eyeadapt"))
}

/// Small sequences: the built-in demo job at 8×6, 1 spp.
pub const SEQ: &[&str] = &[
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
pub const RENDER: &[&str] = &["--spp", "1"];

/// Job files bring their own settings.
pub const JOB: &[&str] = &["--no-report", "--no-progress-bar"];

pub fn run(cmd: &mut Command) -> (i32, String) {
    let o = cmd.output().unwrap();
    (
        o.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&o.stderr).into_owned(),
    )
}

pub fn must(cmd: &mut Command) {
    let (code, err) = run(cmd);
    assert_eq!(code, 0, "setup command failed: {cmd:?}\n{err}");
}

/// Renders chunk `i` of two (frames 0-3, two per chunk) of the corpus job into `root/NAMEi`.
pub fn render_chunk(root: &Path, name: &str, i: usize) -> PathBuf {
    let d = root.join(format!("{name}{i}"));
    must(
        eyeadapt()
            .args(["sequence", "--frames", "0-3", "--chunk-size", "2"])
            .args(["--chunk-index", &i.to_string()])
            .args(SEQ)
            .arg("--out")
            .arg(&d),
    );
    d
}

/// Every file of a directory with its bytes and modification time.
pub fn snapshot(dir: &Path) -> BTreeMap<String, (Vec<u8>, std::time::SystemTime)> {
    common::walk(dir)
        .into_iter()
        .map(|(rel, p)| {
            let modified = std::fs::metadata(&p).unwrap().modified().unwrap();
            (rel, (std::fs::read(&p).unwrap(), modified))
        })
        .collect()
}

/// A case's `.expected` file: `at: FILE:LINE` (or `FILE`, or `none` where the input is not a
/// file, e.g. a frame spec given on the command line), any number of `message: TEXT`, optional
/// `inputs: …` (merge). Lines starting with `#` are comments.
#[derive(Debug, Default)]
pub struct Expected {
    pub at: Option<String>,
    pub messages: Vec<String>,
    pub inputs: Option<String>,
}

pub fn expected(path: &Path) -> Expected {
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
pub fn located(stderr: &str, at: &str) -> bool {
    match at.rsplit_once(':') {
        Some((file, line)) if line.chars().all(|c| c.is_ascii_digit()) => {
            stderr.contains(&format!("{at}:"))
                || (stderr.contains(file) && stderr.contains(&format!("line {line} column")))
        }
        _ => stderr.contains(at),
    }
}

pub struct Outcome {
    pub case: String,
    pub problems: Vec<String>,
}

pub fn check(case: &str, code: i32, stderr: &str, x: &Expected) -> Outcome {
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
pub fn cases(dir: &str, ext: &str) -> Vec<(String, PathBuf, Expected)> {
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

pub fn copy_dir(from: &Path, to: &Path) {
    std::fs::create_dir_all(to).unwrap();
    for e in std::fs::read_dir(from).unwrap() {
        let p = e.unwrap().path();
        let dst = to.join(p.file_name().unwrap());
        if p.is_dir() {
            copy_dir(&p, &dst);
        } else {
            std::fs::copy(&p, &dst).unwrap();
        }
    }
}

/// Replaces `@NAME@` placeholders in every file of a copied merge case.
pub fn instantiate(src: &Path, dst: &Path, vars: &[(&str, String)]) {
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

/// The `settings` object of a manifest, as JSON text on one line (so that the line numbers of
/// a case's manifest do not move), for merge cases that need a valid one.
pub fn serde_settings(manifest: &str) -> String {
    let start = manifest.find("\"settings\": {").unwrap() + "\"settings\": ".len();
    let end = start + manifest[start..].find('}').unwrap() + 1;
    manifest[start..end]
        .lines()
        .map(str::trim)
        .collect::<Vec<_>>()
        .join(" ")
}

/// The files of `dirs` as [`snapshot`] sees them, for [`assert_unchanged`].
pub type Snapshots = Vec<BTreeMap<String, (Vec<u8>, std::time::SystemTime)>>;

pub fn snapshots(dirs: &[&Path]) -> Snapshots {
    dirs.iter().map(|d| snapshot(d)).collect()
}

/// The good outputs `dirs` are byte-for-byte as in `before` (lock files aside).
pub fn assert_unchanged(dirs: &[&Path], before: &Snapshots) {
    for (b, a) in before.iter().zip(snapshots(dirs)) {
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
}

/// Prints the failed outcomes and the tally per corpus directory, and fails unless every case
/// behaved as expected and each directory still has at least its `minimum` cases (so that no
/// case is lost silently).
pub fn finish(outcomes: &[Outcome], minimum: &[(&str, usize)]) {
    let failed: Vec<&Outcome> = outcomes.iter().filter(|o| !o.problems.is_empty()).collect();
    for o in &failed {
        eprintln!("--- {}: {}", o.case, o.problems.join("\n    "));
    }
    let mut per_dir: BTreeMap<&str, usize> = BTreeMap::new();
    for o in outcomes {
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
    for (dir, n) in minimum {
        let have = per_dir.get(dir).copied().unwrap_or(0);
        assert!(
            have >= *n,
            "the corpus's {dir}/ shrank to {have} cases (from {n})"
        );
    }
}

/// A good still render of `good/scene.toml` in `root/render-out`.
pub fn good_render(root: &Path) -> PathBuf {
    let out = root.join("render-out");
    must(
        eyeadapt()
            .arg("render")
            .arg(corpus().join("good/scene.toml"))
            .args(RENDER)
            .arg("--out")
            .arg(&out),
    );
    out
}

/// A good four-frame sequence of the demo job in `root/NAME`.
pub fn good_sequence(root: &Path, name: &str) -> PathBuf {
    let out = root.join(name);
    must(
        eyeadapt()
            .args(["sequence", "--frames", "0-3"])
            .args(SEQ)
            .arg("--out")
            .arg(&out),
    );
    out
}
