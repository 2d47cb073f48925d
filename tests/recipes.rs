//! The farm recipes of `scripts/slurm/README.md`, run as written: each test takes its
//! manager's command lines out of the README text, substitutes the manager's tokens for the
//! tasks of a tiny job (frames 0-5 instead of 0-239, small chunks), runs the tasks, the merge
//! and the report, and compares the result bit for bit with one whole run (issue #17). So the
//! documentation and the tests cannot drift apart.
//!
//! Paths in the README are replaced: `/opt/eyeadapt/eyeadapt` and a bare `eyeadapt` by the
//! binary under test (on `PATH`), `/shared/jobs/walk.toml` by the tiny job,
//! `/shared/renders/walk` by a scratch directory. The Flamenco recipe is JavaScript and runs
//! in `node` with stand-ins for Flamenco's `author`, `frameChunker` and `path`; without node
//! it is skipped with a note unless `EYEADAPT_REQUIRE_NODE=1`.
mod common;

use common::snapshot;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::Command;

const README: &str = include_str!("../scripts/slurm/README.md");

/// The frames every recipe renders here, in place of the README's `0-239`.
const FRAMES: &str = "0-5";

fn bin() -> PathBuf {
    PathBuf::from(env!("CARGO_BIN_EXE_eyeadapt"))
}

/// The text of the README section `### TITLE`, up to the next heading.
fn section(title: &str) -> &'static str {
    let start = README
        .find(&format!("\n### {title}"))
        .unwrap_or_else(|| panic!("README has no section {title:?}"));
    let rest = &README[start + 1..];
    let end = rest[4..].find("\n##").map_or(rest.len(), |i| i + 4);
    &rest[..end]
}

/// The fenced code blocks of `lang` in `text`, in order.
fn blocks(text: &str, lang: &str) -> Vec<String> {
    let fence = format!("```{lang}\n");
    text.split(&fence)
        .skip(1)
        .map(|b| b.split("\n```").next().unwrap().to_string())
        .collect()
}

/// A scratch farm: the tiny job, the shared output directory, and the whole run to compare.
struct Farm {
    _tmp: tempfile::TempDir,
    job: PathBuf,
    out: PathBuf,
    whole: BTreeMap<String, Vec<u8>>,
}

impl Farm {
    fn new() -> Farm {
        let tmp = tempfile::tempdir().unwrap();
        let job = tmp.path().join("walk.toml");
        std::fs::write(
            &job,
            "name = \"walk\"\nscene = \"builtin:three-rooms\"\n\
             [render]\nwidth = 12\nheight = 8\nspp = 1\n\
             [estimators]\nlist = [\"eye\", \"wcam\"]\n\
             [estimators.eye]\nsamples = 64\ntarget_std_err_uv = 0\n",
        )
        .unwrap();
        let whole_dir = tmp.path().join("whole");
        let o = Command::new(bin())
            .args(["sequence", "--frames", FRAMES])
            .arg(&job)
            .arg("--out")
            .arg(&whole_dir)
            .output()
            .unwrap();
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        assert!(
            whole_dir.join("report.html").exists(),
            "the whole run reports"
        );
        let out = tmp.path().join("renders/walk");
        Farm {
            whole: snapshot(&whole_dir),
            job,
            out,
            _tmp: tmp,
        }
    }

    /// A README command line with the README's paths replaced by this farm's.
    fn local(&self, cmd: &str) -> String {
        cmd.replace("/opt/eyeadapt/eyeadapt", bin().to_str().unwrap())
            .replace("/shared/jobs/walk.toml", self.job.to_str().unwrap())
            .replace("/shared/renders/walk", self.out.to_str().unwrap())
            .replace("0-239", FRAMES)
    }

    /// Runs a shell command line (with the binary on PATH as `eyeadapt`); returns stdout.
    fn sh(&self, cmd: &str) -> String {
        self.run(Command::new("sh").args(["-c", cmd]))
    }

    fn run(&self, cmd: &mut Command) -> String {
        let path = format!(
            "{}:{}",
            bin().parent().unwrap().display(),
            std::env::var("PATH").unwrap_or_default()
        );
        let o = cmd.env("PATH", path).output().unwrap();
        assert!(
            o.status.success(),
            "{cmd:?} failed ({}):\n{}",
            o.status,
            String::from_utf8_lossy(&o.stderr)
        );
        String::from_utf8_lossy(&o.stdout).into_owned()
    }

    /// The merged directory equals the whole run, file for file and bit for bit.
    fn assert_merged_equals_whole(&self, recipe: &str) {
        let merged = snapshot(&self.out.join("merged"));
        let names = |m: &BTreeMap<String, Vec<u8>>| m.keys().cloned().collect::<Vec<_>>();
        assert_eq!(names(&self.whole), names(&merged), "{recipe}: file sets");
        for (k, v) in &self.whole {
            assert!(*v == merged[k], "{recipe}: {k} differs from the whole run");
        }
    }
}

/// `(start, end)` of each task when a manager splits `first..=last` into chunks of `size`
/// and, like OpenCue, does not clamp the last chunk's end.
fn chunks(first: u32, last: u32, size: u32, clamp: bool) -> Vec<(u32, u32)> {
    (first..=last)
        .step_by(size as usize)
        .map(|s| {
            (
                s,
                if clamp {
                    (s + size - 1).min(last)
                } else {
                    s + size - 1
                },
            )
        })
        .collect()
}

/// A shell block with its line continuations joined.
fn one_line(block: &str) -> String {
    block.replace("\\\n", " ")
}

/// The value of `-arguments "…"` (or `-executable X`) in a `deadlinecommand` line.
fn deadline_option(line: &str, name: &str) -> String {
    let at = line
        .find(&format!("-{name} "))
        .unwrap_or_else(|| panic!("no -{name} in {line}"))
        + name.len()
        + 2;
    let rest = line[at..].trim_start();
    match rest.strip_prefix('"') {
        Some(quoted) => quoted[..quoted.find('"').unwrap()].to_string(),
        None => rest.split_whitespace().next().unwrap().to_string(),
    }
}

#[test]
fn deadline_recipe_as_documented() {
    let f = Farm::new();
    let b = blocks(section("Deadline 10"), "sh");
    let (render, merge) = (one_line(&b[0]), one_line(&b[1]));
    assert!(render.contains("-frames 0-239 -chunksize 10"), "{render}");
    // Deadline's tasks over 0-5 in chunks of 4: 0-3 and 4-5.
    for (s, e) in chunks(0, 5, 4, true) {
        let args = deadline_option(&render, "arguments")
            .replace("<STARTFRAME%6>", &format!("{s:06}"))
            .replace("<STARTFRAME>", &s.to_string())
            .replace("<ENDFRAME>", &e.to_string());
        let exe = deadline_option(&render, "executable");
        let log = f.sh(&f.local(&format!("{exe} {args}")));
        assert!(log.contains("Progress: 100%"), "{log}");
    }
    assert!(f.out.join("chunks/000004/manifest.json").exists());
    let exe = deadline_option(&merge, "executable");
    let args = deadline_option(&merge, "arguments").replace("<QUOTE>", "\"");
    f.sh(&f.local(&format!("{exe} {args}")));
    f.assert_merged_equals_whole("Deadline");
}

#[test]
fn opencue_recipe_as_documented() {
    let f = Farm::new();
    let b = blocks(section("OpenCue"), "sh");
    assert!(section("OpenCue").contains("chunk size `10`"));
    // OpenCue's last #FRAME_END# runs past the layer's range (issue #1129): 0-3, then 4-7.
    for (s, e) in chunks(0, 5, 4, false) {
        let cmd = b[0]
            .replace("#FRAME_START#", &s.to_string())
            .replace("#FRAME_END#", &e.to_string());
        f.sh(&f.local(&cmd));
    }
    let out = f.sh(&f.local(&b[1]));
    assert!(
        out.contains("2 frame(s) outside --frames left out"),
        "{out}"
    );
    f.assert_merged_equals_whole("OpenCue");
}

/// Flamenco's `frameChunker` as its job compilers use it: the frames in chunks of `size`,
/// each written as `a-b` (or `a`).
const FLAMENCO_STANDINS: &str = r#"
const tasks = [];
function frameChunker(frames, size) {
  const [a, b] = frames.split("-").map(Number);
  const out = [];
  for (let s = a; s <= b; s += size) {
    const e = Math.min(s + size - 1, b);
    out.push(s === e ? `${s}` : `${s}-${e}`);
  }
  return out;
}
const path = { join: (...parts) => parts.join("/") };
const author = {
  Command: (type, params) => ({ type, params }),
  Task: (name, type) => {
    const t = { name, type, commands: [], deps: [] };
    t.addCommand = (c) => t.commands.push(c);
    t.addDependency = (d) => t.deps.push(d.name);
    return t;
  },
};
"#;

#[test]
fn flamenco_recipe_as_documented() {
    let node = Command::new("node").arg("--version").output();
    if !node.is_ok_and(|o| o.status.success()) {
        assert!(
            std::env::var("EYEADAPT_REQUIRE_NODE").as_deref() != Ok("1"),
            "node is required (EYEADAPT_REQUIRE_NODE=1) but not on PATH"
        );
        eprintln!("flamenco recipe skipped: no node on PATH (set EYEADAPT_REQUIRE_NODE=1 to fail)");
        return;
    }
    let f = Farm::new();
    let js = &blocks(section("Flamenco 3"), "js")[0];
    let settings = serde_json::json!({
        "eyeadapt": bin(), "job_file": f.job, "frames": FRAMES,
        "chunk_size": 2, "out": f.out,
    });
    let script = format!(
        "{FLAMENCO_STANDINS}\n{js}\nconst job = {{ settings: {settings}, addTask: (t) => tasks.push(t) }};\n\
         compileJob(job);\nconsole.log(JSON.stringify(tasks));\n"
    );
    let compiled = f.run(Command::new("node").args(["-e", &script]));
    let tasks: Vec<serde_json::Value> = serde_json::from_str(&compiled).unwrap();
    assert_eq!(tasks.len(), 4, "three chunks and the merge: {compiled}");
    // The compiled tasks in job order; the merge, last, depends on the three renders.
    assert_eq!(tasks[3]["deps"].as_array().unwrap().len(), 3);
    for t in &tasks {
        for c in t["commands"].as_array().unwrap() {
            let p = &c["params"];
            assert_eq!(c["type"], "blender-render");
            let strings = |v: &serde_json::Value| -> Vec<String> {
                v.as_array()
                    .unwrap()
                    .iter()
                    .map(|s| s.as_str().unwrap().to_string())
                    .collect()
            };
            let mut cmd = Command::new(p["exe"].as_str().unwrap());
            cmd.args(p["exeArgs"].as_str().unwrap().split_whitespace())
                .args(strings(&p["argsBefore"]))
                .arg(p["blendfile"].as_str().unwrap())
                .args(strings(&p["args"]));
            let log = f.run(&mut cmd);
            if t["name"].as_str().unwrap().starts_with("render-") {
                assert!(
                    log.contains("Saved: '"),
                    "Flamenco reads Saved: lines: {log}"
                );
            }
        }
    }
    f.assert_merged_equals_whole("Flamenco");
}

/// The `args: [...]` flow sequences of a YAML block (JSON-compatible here), with the
/// `command:` line before each.
fn openjd_actions(yaml: &str) -> Vec<(String, Vec<String>)> {
    let mut out = Vec::new();
    let mut rest = yaml;
    while let Some(at) = rest.find("command: ") {
        let line = rest[at + 9..].lines().next().unwrap().trim().to_string();
        let args_at = rest[at..].find("args: [").unwrap() + at + 6;
        let end = rest[args_at..].find("]\n").unwrap() + args_at + 1;
        let args: Vec<String> = serde_json::from_str(&rest[args_at..end]).unwrap();
        out.push((line, args));
        rest = &rest[end..];
    }
    out
}

#[test]
fn openjd_recipe_as_documented() {
    let f = Farm::new();
    let yaml = &blocks(section("Open Job Description"), "yaml")[0];
    assert!(yaml.contains("defaultTaskCount: 10") && yaml.contains("rangeConstraint: CONTIGUOUS"));
    let actions = openjd_actions(&format!("{yaml}\n"));
    assert_eq!(actions.len(), 2, "{actions:?}");
    let fill = |s: &str, chunk: &str| {
        s.replace("{{Param.JobFile}}", f.job.to_str().unwrap())
            .replace("{{Param.OutputDir}}", f.out.to_str().unwrap())
            .replace("{{Param.Frames}}", FRAMES)
            .replace("{{Task.Param.Frame}}", chunk)
    };
    let program = |name: &str| match name {
        "eyeadapt" => bin(),
        other => PathBuf::from(other),
    };
    // CONTIGUOUS chunks of 2 tasks: "0-1", "2-3", "4-5".
    for chunk in ["0-1", "2-3", "4-5"] {
        let (cmd, args) = &actions[0];
        let log = f.run(Command::new(program(cmd)).args(args.iter().map(|a| fill(a, chunk))));
        assert!(log.contains("openjd_progress: 100"), "{log}");
    }
    let (cmd, args) = &actions[1];
    f.run(Command::new(program(cmd)).args(args.iter().map(|a| fill(a, ""))));
    f.assert_merged_equals_whole("OpenJD");
}

/// Slurm: the README's `submit.sh` line, written out with `--dry-run`, then the generated
/// batch scripts run as Slurm would run them (each array task, then the merge job).
/// `tests/slurm/e2e.sh` runs the same through a real Slurm.
#[test]
fn slurm_recipe_as_documented() {
    let f = Farm::new();
    let line = one_line(&blocks(section("Submitting on a real cluster"), "sh")[0]);
    assert!(line.contains("--chunk-size 10 --threads 8"), "{line}");
    let line = f
        .local(&line)
        .replace("--chunk-size 10 --threads 8", "--chunk-size 2 --threads 1");
    let repo = Path::new(env!("CARGO_MANIFEST_DIR"));
    let cmd = format!(
        "cd {} && {line} --frames {FRAMES} --dry-run --exe {}",
        repo.display(),
        bin().display()
    );
    f.sh(&cmd);
    for task in 0..3 {
        f.run(
            Command::new(f.out.join("slurm/render.sh"))
                .env("SLURM_ARRAY_TASK_ID", task.to_string())
                .env("SLURM_ARRAY_JOB_ID", "7"),
        );
    }
    f.run(Command::new(f.out.join("slurm/merge.sh")).env("SLURM_JOB_ID", "8"));
    f.assert_merged_equals_whole("Slurm");
}
