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
//! | `merge/` | `NAME/` (a chunk output) | `eyeadapt merge GOOD_CHUNK CASE --frames 0-3` into a good merge |
//! | `xml/` | `NAME.xml` | `eyeadapt render CASE` (Mitsuba 3 XML) into the good render |
//! | `gltf/` | `NAME.gltf` | `eyeadapt render CASE` (glTF 2.0) into the good render |
//! | `report/` | `NAME.csv` / `NAME.manifest` | `eyeadapt report` of a good sequence with that CSV / manifest patch |
//! | `fuzz-regressions/` | inputs the fuzzers once crashed on | see `fuzz_regressions` below |
mod common;

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

fn copy_dir(from: &Path, to: &Path) {
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
            .args(["--frames", "0-3", "--out"])
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
        .chain(cases("gltf", "gltf"))
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
        let (code, err) = run(cmd.args(["--frames", "0-3", "--out"]).arg(&merge_out));
        outcomes.push(check(&case, code, &err, &x));
    }

    // Report: a copy of the good sequence, reported once (so its report files exist), then
    // per case a fresh copy with a broken adaptation.csv (`NAME.csv`) or a patched
    // manifest.json (`NAME.manifest`: lines `FROM => TO`). The failed report must change
    // nothing in it.
    let report_good = root.join("report-good");
    copy_dir(&seq_out, &report_good);
    must(eyeadapt().arg("report").arg(&report_good));
    let mut report_cases = cases("report", "csv");
    report_cases.extend(cases("report", "manifest"));
    for (case, path, x) in report_cases {
        let dir = root.join("report-cases").join(path.file_name().unwrap());
        copy_dir(&report_good, &dir);
        if path.extension().is_some_and(|e| e == "csv") {
            std::fs::copy(&path, dir.join("adaptation.csv")).unwrap();
        } else {
            let mut m = std::fs::read_to_string(dir.join("manifest.json")).unwrap();
            for l in std::fs::read_to_string(&path).unwrap().lines() {
                let (from, to) = l.split_once(" => ").unwrap();
                assert!(m.contains(from), "{case}: {from:?} not in the manifest");
                m = m.replace(from, to);
            }
            std::fs::write(dir.join("manifest.json"), m).unwrap();
        }
        let before = snapshot(&dir);
        let (code, err) = run(eyeadapt().arg("report").arg(&dir));
        let mut o = check(&case, code, &err, &x);
        let after = snapshot(&dir);
        let changed: Vec<&String> = before
            .keys()
            .chain(after.keys())
            .filter(|k| before.get(*k) != after.get(*k) && !k.ends_with(".eyeadapt.lock"))
            .collect();
        if !changed.is_empty() {
            o.problems
                .push(format!("the failed report changed {changed:?}"));
        }
        outcomes.push(o);
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

/// A job over the corpus's good scene whose camera path looks at the sphere in frame 0 and
/// away from everything (into the environment) in frame 1.
const TWO_VIEW_JOB: &str = r#"
name = "nan"
scene = "scene.toml"
[render]
width = 8
height = 6
spp = 2
[estimators]
list = ["eye", "grey_world", "white_patch"]
[estimators.eye]
samples = 64
[camera_path]
fps = 1
keyframes = [ { time = 0.0, position = [0.0, 1.0, 3.0], look_at = [0.0, 1.0, 0.0] },
              { time = 1.0, position = [0.0, 1.0, 3.0], look_at = [0.0, 1.0, 6.0] } ]
"#;

/// NaN/Inf samples cannot come from a scene the loaders accept, so this injects them: a point
/// light of infinite intensity added to a loaded job. Every surface hit then has an infinite
/// direct term. The film must drop and count those samples, the frame that sees surfaces must
/// say so in the `flags` of each of its CSV rows (`image_nan_dropped`) and in the manifest,
/// and the frame that sees only the environment must not.
#[test]
fn nan_samples_are_counted_dropped_and_flagged_per_frame() {
    use eyeadapt_sequencer::job::{JobOverrides, load_job};
    use eyeadapt_sequencer::sequence::{SequenceOptions, run_sequence};
    let t = tempfile::tempdir().unwrap();
    std::fs::copy(
        corpus().join("good/scene.toml"),
        t.path().join("scene.toml"),
    )
    .unwrap();
    let job_file = t.path().join("job.toml");
    std::fs::write(&job_file, TWO_VIEW_JOB).unwrap();
    let mut job = load_job(Some(&job_file), &JobOverrides::default()).unwrap();
    job.scene.lights.push(eyeadapt_scene::Light::Point {
        position: eyeadapt_scene::Rgb::new(0.0, 3.0, 1.0),
        intensity: eyeadapt_scene::Rgb::splat(f32::INFINITY),
    });
    let out = t.path().join("out");
    let opts = SequenceOptions {
        out: out.clone(),
        selection: None,
        chunk: None,
        force: false,
        verify: false,
        log_format: eyeadapt_sequencer::progress::LogFormat::Plain,
        plain_progress: true,
        stop: None,
    };
    let s = run_sequence(&job, &opts).unwrap();
    assert_eq!(s.rendered, 2);
    let m = eyeadapt_sequencer::manifest::Manifest::load(&out)
        .unwrap()
        .unwrap();
    let dropped = |f: u32| m.frames[&f].invalid_samples;
    assert!(
        dropped(0) > 0,
        "frame 0 sees lit surfaces: samples must be dropped"
    );
    assert!(dropped(0) < 8 * 6 * 2, "sky pixels stay valid");
    assert_eq!(dropped(1), 0, "frame 1 sees only the environment");
    let csv = std::fs::read_to_string(out.join("adaptation.csv")).unwrap();
    let header: Vec<&str> = csv.lines().next().unwrap().split(',').collect();
    let flags_col = header.iter().position(|h| *h == "flags").unwrap();
    let rows: Vec<Vec<&str>> = csv
        .lines()
        .skip(1)
        .map(|l| l.split(',').collect())
        .collect();
    assert_eq!(rows.len(), 2 * 3);
    for r in &rows {
        let flagged = r[flags_col].split(';').any(|f| f == "image_nan_dropped");
        assert_eq!(
            flagged,
            r[0] == "0",
            "frame {} {}: flags {:?}",
            r[0],
            r[2],
            r[flags_col]
        );
    }
    // The image itself holds no NaN or Inf: the dropped samples are simply not averaged in.
    for f in [0, 1] {
        let frame =
            eyeadapt_sequencer::output::read_exr(&out.join(format!("frames/raw/frame_{f:06}.exr")))
                .unwrap();
        for v in [
            &frame.rgb,
            &frame.albedo,
            &frame.irradiance,
            &frame.achromatic,
        ] {
            assert!(v.iter().flatten().all(|x| x.is_finite()), "frame {f}");
        }
    }

    // The still path reports the same flag.
    let mut scene = eyeadapt_scene::load_scene(&t.path().join("scene.toml")).unwrap();
    scene.lights.push(job.scene.lights.last().unwrap().clone());
    let still_out = t.path().join("still");
    std::fs::create_dir_all(&still_out).unwrap();
    let mut o = eyeadapt_sequencer::still::StillOptions {
        out: still_out.clone(),
        ..Default::default()
    };
    o.sampling.spp = Some(2);
    let r = eyeadapt_sequencer::still::render_still(
        &scene,
        &o,
        &[eyeadapt_sequencer::Estimator::GreyWorld],
        &job.estimator_config,
        &job.adaptation,
    )
    .unwrap();
    assert!(r.frame.image.stats.invalid_samples > 0);
    let csv = std::fs::read_to_string(still_out.join("adaptation.csv")).unwrap();
    assert!(
        csv.lines().nth(1).unwrap().contains("image_nan_dropped"),
        "{csv}"
    );
}

/// Degenerate triangles (collinear, repeated vertices, all emissive) and lights whose area is
/// zero or underflows (emissive spheres of radius 1e-30 and 1e-9, whose triangles' areas are
/// 0 or subnormal in f32) must not produce a single NaN: no dropped sample, finite AOVs, a
/// valid eye-sensor estimate.
#[test]
fn degenerate_triangles_and_zero_area_lights_do_not_make_nan() {
    let t = tempfile::tempdir().unwrap();
    let d = t.path();
    std::fs::write(
        d.join("degenerate.obj"),
        "mtllib degenerate.mtl\nusemtl lamp\n\
         v 0 2 0\nv 1 2 0\nv 2 2 0\nv 0 2 1\n\
         f 1 2 3\nf 1 1 4\nf 4 4 4\nf 1 2 1\n",
    )
    .unwrap();
    std::fs::write(
        d.join("degenerate.mtl"),
        "newmtl lamp\nKd 0 0 0\nKe 20 20 20\n",
    )
    .unwrap();
    let scene = r#"
[camera]
position = [0.0, 1.0, 3.0]
look_at = [0.0, 1.0, 0.0]
fov_deg = 60.0
width = 16
height = 12

[[materials]]
name = "white"
type = "diffuse"
reflectance = [0.7, 0.7, 0.7]

[[materials]]
name = "lamp"
type = "diffuse"
reflectance = [0.0, 0.0, 0.0]
emission = [10.0, 10.0, 10.0]

[[shapes]]
type = "box"
material = "white"
min = [-2.0, -0.1, -2.0]
max = [2.0, 0.0, 2.0]

[[shapes]]
type = "sphere"
material = "white"
center = [0.0, 0.7, 0.0]
radius = 0.5

[[shapes]]
type = "sphere"
material = "lamp"
center = [0.5, 2.0, 0.0]
radius = 1e-30

[[shapes]]
type = "sphere"
material = "lamp"
center = [-0.5, 2.0, 0.0]
radius = 1e-9

[[shapes]]
type = "quad"
material = "lamp"
corner = [-0.5, 2.5, -0.5]
u = [1.0, 0.0, 0.0]
v = [0.0, 0.0, 1.0]

[[shapes]]
type = "obj"
file = "degenerate.obj"
"#;
    std::fs::write(d.join("scene.toml"), scene).unwrap();
    let out = d.join("out");
    let o = eyeadapt()
        .args([
            "render",
            d.join("scene.toml").to_str().unwrap(),
            "--spp",
            "16",
        ])
        .args([
            "--estimators",
            "eye,dominant,grey_world",
            "--eye-samples",
            "4096",
        ])
        .arg("--stats-json")
        .arg(d.join("stats.json"))
        .arg("--out")
        .arg(&out)
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(o.status.success(), "{err}");
    assert!(!err.contains("NaN or infinite"), "{err}");
    let stats = std::fs::read_to_string(d.join("stats.json")).unwrap();
    assert!(stats.contains("\"invalid_samples\": 0,"), "{stats}");
    let f = eyeadapt_sequencer::output::read_exr(&out.join("raw.exr")).unwrap();
    for v in [&f.rgb, &f.albedo, &f.irradiance, &f.achromatic, &f.normal] {
        assert!(v.iter().flatten().all(|x| x.is_finite()));
    }
    assert!(
        f.depth
            .iter()
            .chain(&f.emitter)
            .chain(&f.hit)
            .all(|x| x.is_finite())
    );
    let lit: f32 = f.rgb.iter().flatten().sum();
    assert!(lit > 0.0, "the quad light lights the scene");
    let csv = std::fs::read_to_string(out.join("adaptation.csv")).unwrap();
    for row in csv.lines().skip(1) {
        assert!(!row.contains("NaN") && !row.contains("inf"), "{row}");
        assert!(!row.contains("dropped_non_finite"), "{row}");
        assert!(row.contains(",1,"), "valid estimate expected: {row}");
    }
}

/// The fuzz targets' checks (`fuzz/fuzz_targets/checks.rs`), run here on every input kept in
/// `tests/corpus/fuzz-regressions/TARGET/`: inputs that once crashed a target, and a few seeds.
#[path = "../fuzz/fuzz_targets/checks.rs"]
mod checks;

#[test]
fn fuzz_regressions_no_longer_crash() {
    type Check = fn(&[u8]);
    let targets: [(&str, Check); 4] = [
        ("scene_toml", checks::scene_toml),
        ("obj", checks::obj),
        ("frame_spec", checks::frame_spec),
        ("mitsuba_xml", checks::mitsuba_xml),
    ];
    let mut ran = 0;
    let mut crashed = Vec::new();
    for (target, check) in targets {
        let dir = corpus().join("fuzz-regressions").join(target);
        let Ok(entries) = std::fs::read_dir(&dir) else {
            continue;
        };
        let mut files: Vec<PathBuf> = entries.map(|e| e.unwrap().path()).collect();
        files.sort();
        for f in files {
            let data = std::fs::read(&f).unwrap();
            if std::panic::catch_unwind(|| check(&data)).is_err() {
                crashed.push(f.display().to_string());
            }
            ran += 1;
        }
    }
    println!("fuzz regressions: {ran} inputs, {} crashed", crashed.len());
    assert!(crashed.is_empty(), "still crashing: {crashed:?}");
}

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
    let chunk = |i: usize| {
        let d = root.join(format!("c{i}"));
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

/// Found by the `obj` fuzz target: tobj 4.0.5 panics (exit 101) on an MTL colour line with
/// fewer than three numbers. Like any malformed MTL it now only costs the material: a warning
/// naming `file.mtl:LINE`, and the error material.
#[test]
fn short_mtl_colour_line_is_a_warning_not_a_panic() {
    let t = tempfile::tempdir().unwrap();
    let d = t.path();
    std::fs::write(
        d.join("mesh.obj"),
        "mtllib mesh.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl paint\nf 1 2 3\n",
    )
    .unwrap();
    for line in ["Kd 0.5 0.5", "Ke 1", "Ka", "Ks 0 0"] {
        std::fs::write(d.join("mesh.mtl"), format!("newmtl paint\n{line}\n")).unwrap();
        std::fs::write(
            d.join("scene.toml"),
            "[camera]\nposition = [0.3, 0.3, 3.0]\nlook_at = [0.3, 0.3, 0.0]\nfov_deg = 45.0\n\
             width = 8\nheight = 6\n\n[[shapes]]\ntype = \"obj\"\nfile = \"mesh.obj\"\n\n\
             [environment]\nradiance = [1.0, 1.0, 1.0]\n",
        )
        .unwrap();
        let (code, err) = run(eyeadapt()
            .arg("render")
            .arg(d.join("scene.toml"))
            .args(RENDER)
            .arg("--out")
            .arg(d.join("out")));
        assert_eq!(code, 0, "{line}: {err}");
        assert!(
            err.contains("mesh.mtl:2:") && err.contains("needs three numbers"),
            "{line}: {err}"
        );
    }
}
