//! Bad input: every case exits with code 2 and a message naming the file and the line
//! (`file:line:col:`), and nothing is written.
use std::path::{Path, PathBuf};
use std::process::Command;

fn eyeadapt() -> Command {
    Command::new(env!("CARGO_BIN_EXE_eyeadapt"))
}

const GOOD: &str = r#"
[camera]
position = [0.0, 1.0, 3.0]
look_at = [0.0, 1.0, 0.0]
fov_deg = 45.0
width = 16
height = 12

[[materials]]
name = "white"
type = "diffuse"
reflectance = [0.7, 0.7, 0.7]

[[shapes]]
type = "sphere"
material = "white"
center = [0.0, 1.0, 0.0]
radius = 0.5

[environment]
radiance = [1.0, 1.0, 1.0]
"#;

/// Writes `text` as scene.toml in a fresh directory and renders it; returns (code, stderr, dir).
fn render_scene(text: &str, extra: &[(&str, &[u8])]) -> (i32, String, tempfile::TempDir) {
    let dir = tempfile::tempdir().unwrap();
    let scene = dir.path().join("scene.toml");
    std::fs::write(&scene, text).unwrap();
    for (name, bytes) in extra {
        std::fs::write(dir.path().join(name), bytes).unwrap();
    }
    let out = dir.path().join("out");
    let o = eyeadapt()
        .args([
            "render",
            scene.to_str().unwrap(),
            "--spp",
            "1",
            "--out",
            out.to_str().unwrap(),
        ])
        .output()
        .unwrap();
    (
        o.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&o.stderr).into_owned(),
        dir,
    )
}

/// Asserts exit 2, a `scene.toml:LINE:` location (when `line` is given) and a message part.
fn assert_bad(text: &str, line: Option<usize>, needle: &str) {
    assert_bad_with(text, &[], line, needle);
}

fn assert_bad_with(text: &str, extra: &[(&str, &[u8])], line: Option<usize>, needle: &str) {
    let (code, err, dir) = render_scene(text, extra);
    assert_eq!(code, 2, "exit code for {needle:?}; stderr:\n{err}");
    assert!(
        err.contains("scene.toml"),
        "message must name the file:\n{err}"
    );
    if let Some(l) = line {
        assert!(
            err.contains(&format!("scene.toml:{l}:")),
            "expected line {l}:\n{err}"
        );
    }
    assert!(
        err.to_lowercase().contains(&needle.to_lowercase()),
        "expected {needle:?} in:\n{err}"
    );
    assert!(
        !dir.path().join("out").join("raw.exr").exists(),
        "no output on bad input"
    );
}

fn line_of(text: &str, pat: &str) -> usize {
    text.lines().position(|l| l.contains(pat)).expect(pat) + 1
}

#[test]
fn good_scene_renders() {
    let (code, err, dir) = render_scene(GOOD, &[]);
    assert_eq!(code, 0, "{err}");
    assert!(dir.path().join("out/raw.exr").exists());
}

#[test]
fn bad_toml_syntax() {
    let t = GOOD.replace("fov_deg = 45.0", "fov_deg = = 45.0");
    assert_bad(&t, Some(line_of(&t, "fov_deg")), "");
}

#[test]
fn unknown_field() {
    let t = GOOD.replace("fov_deg = 45.0", "fov_deg = 45.0\nfocal = 3.0");
    assert_bad(&t, Some(line_of(&t, "focal")), "unknown field `focal`");
}

#[test]
fn wrong_type() {
    let t = GOOD.replace("fov_deg = 45.0", "fov_deg = \"wide\"");
    assert_bad(&t, Some(line_of(&t, "fov_deg")), "invalid type");
}

#[test]
fn missing_scene_file() {
    let o = eyeadapt()
        .args(["render", "/nonexistent/dir/scene.toml"])
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("/nonexistent/dir/scene.toml"));
}

#[test]
fn negative_spp_in_file_and_on_the_command_line() {
    let t = GOOD.replace("[environment]", "[render]\nspp = -3\n\n[environment]");
    assert_bad(&t, Some(line_of(&t, "spp = -3")), "spp -3");
    let o = eyeadapt()
        .args(["render", "builtin:cornell-box", "--spp", "0"])
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("--spp"));
}

#[test]
fn zero_size_image() {
    let t = GOOD.replace("width = 16", "width = 0");
    assert_bad(&t, Some(line_of(&t, "width = 0")), "width 0");
}

#[test]
fn degenerate_camera() {
    let t = GOOD.replace("look_at = [0.0, 1.0, 0.0]", "look_at = [0.0, 1.0, 3.0]");
    assert_bad(
        &t,
        Some(line_of(&t, "look_at")),
        "look_at equals its position",
    );
    let t = GOOD.replace("look_at = [0.0, 1.0, 0.0]", "look_at = [0.0, 5.0, 3.0]");
    assert_bad(&t, Some(line_of(&t, "look_at")), "parallel");
}

#[test]
fn nan_and_negative_colours() {
    let t = GOOD.replace(
        "reflectance = [0.7, 0.7, 0.7]",
        "reflectance = [nan, 0.7, 0.7]",
    );
    assert_bad(&t, Some(line_of(&t, "reflectance")), "non-finite");
    let t = GOOD.replace("radiance = [1.0, 1.0, 1.0]", "radiance = [1.0, -1.0, inf]");
    assert_bad(&t, Some(line_of(&t, "radiance")), "environment radiance");
    let t = GOOD.replace(
        "reflectance = [0.7, 0.7, 0.7]",
        "reflectance = [0.7, 1.7, 0.7]",
    );
    assert_bad(&t, Some(line_of(&t, "reflectance")), "exceeds 1");
}

#[test]
fn empty_scene() {
    let t = GOOD.split("[[materials]]").next().unwrap().to_string();
    assert_bad(&t, None, "empty");
}

#[test]
fn missing_and_unreadable_obj() {
    let t = GOOD.replace(
        "type = \"sphere\"\nmaterial = \"white\"\ncenter = [0.0, 1.0, 0.0]\nradius = 0.5",
        "type = \"obj\"\nfile = \"mesh.obj\"",
    );
    assert_bad(&t, Some(line_of(&t, "mesh.obj")), "does not exist");
    // A file that is not an OBJ at all: no triangles.
    assert_bad_with(
        &t,
        &[("mesh.obj", b"\x00\x01\x02garbage\xff\xfe\n")],
        Some(line_of(&t, "mesh.obj")),
        "mesh.obj",
    );
    // Faces indexing vertices that do not exist.
    assert_bad_with(
        &t,
        &[("mesh.obj", b"v 0 0 0\nv 1 0 0\nf 1 2 9\n")],
        Some(line_of(&t, "mesh.obj")),
        "mesh.obj",
    );
}

#[test]
fn every_problem_is_reported_at_once() {
    let t = GOOD
        .replace("fov_deg = 45.0", "fov_deg = 400.0")
        .replace("width = 16", "width = 0")
        .replace("type = \"diffuse\"", "type = \"velvet\"");
    let (code, err, _d) = render_scene(&t, &[]);
    assert_eq!(code, 2);
    for needle in ["fov_deg 400", "width 0", "velvet"] {
        assert!(err.contains(needle), "{needle} missing from:\n{err}");
    }
}

#[test]
fn unknown_material_is_a_warning_and_renders_magenta() {
    let t = GOOD.replace("material = \"white\"", "material = \"whiet\"");
    let (code, err, dir) = render_scene(&t, &[]);
    assert_eq!(code, 0, "{err}");
    assert!(
        err.contains("warning") && err.contains("whiet") && err.contains("scene.toml:"),
        "{err}"
    );
    assert!(dir.path().join("out/raw.exr").exists());
}

#[test]
fn missing_mtl_is_a_warning_naming_the_file() {
    let t = GOOD.replace(
        "type = \"sphere\"\nmaterial = \"white\"\ncenter = [0.0, 1.0, 0.0]\nradius = 0.5",
        "type = \"obj\"\nfile = \"mesh.obj\"",
    );
    let obj = b"mtllib nothere.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl paint\nf 1 2 3\n";
    let (code, err, _d) = render_scene(&t, &[("mesh.obj", obj)]);
    assert_eq!(code, 0, "{err}");
    assert!(
        err.contains("mesh.obj") && err.contains("error material"),
        "{err}"
    );
}

fn job_dir() -> (tempfile::TempDir, PathBuf) {
    let dir = tempfile::tempdir().unwrap();
    let p = dir.path().to_path_buf();
    (dir, p)
}

#[test]
fn bad_job_files_exit_2_with_location() {
    let (_d, dir) = job_dir();
    let cases: [(&str, &str); 5] = [
        (
            "scene = \"builtin:three-rooms\"\nbogus = 1\n",
            "unknown field `bogus`",
        ),
        (
            "scene = \"builtin:three-rooms\"\n[render]\nspp = 0\n",
            "render.spp 0",
        ),
        ("scene = \"builtin:nope\"\n", "no built-in scene"),
        (
            "scene = \"builtin:three-rooms\"\n[estimators]\nlist = [\"eye\", \"psychic\"]\n",
            "psychic",
        ),
        (
            "scene = \"builtin:three-rooms\"\nframes = \"5-x\"\n",
            "invalid number",
        ),
    ];
    for (i, (text, needle)) in cases.iter().enumerate() {
        let job = dir.join(format!("job{i}.toml"));
        std::fs::write(&job, text).unwrap();
        let o = eyeadapt()
            .args([
                "sequence",
                job.to_str().unwrap(),
                "--out",
                dir.join("out").to_str().unwrap(),
            ])
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{text}: {err}");
        assert!(
            err.contains(&format!("job{i}.toml:")),
            "{text}: must name file and line: {err}"
        );
        assert!(err.contains(needle), "{text}: expected {needle}: {err}");
        assert!(!Path::new(&dir.join("out/manifest.json")).exists());
    }
}

#[test]
fn a_scene_file_given_as_job_says_so() {
    let (_d, dir) = job_dir();
    let toml_scene = dir.join("scene.toml");
    std::fs::write(&toml_scene, GOOD).unwrap();
    let xml_scene = PathBuf::from(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/scenes/cornell-box/cornell.xml"
    ));
    for scene in [&toml_scene, &xml_scene] {
        let o = eyeadapt()
            .args([
                "sequence",
                scene.to_str().unwrap(),
                "--out",
                dir.join("out").to_str().unwrap(),
            ])
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{err}");
        assert!(
            err.contains(&format!(
                "{} is a scene file, not a job file; use `eyeadapt render",
                scene.display()
            )) && err.contains("scene = "),
            "{err}"
        );
        assert!(!dir.join("out").exists(), "nothing may be written: {err}");
    }
}

/// Options of `render` are checked before anything is rendered: a bad estimator list, CAT or
/// degree, adaptation options without `--estimators`, or an absurd thread count exit 2 and
/// leave an earlier render's files byte for byte as they were.
#[test]
fn render_options_are_checked_before_anything_is_written() {
    let dir = tempfile::tempdir().unwrap();
    let scene = dir.path().join("scene.toml");
    std::fs::write(&scene, GOOD).unwrap();
    let out = dir.path().join("out");
    let (scene, out_s) = (scene.to_str().unwrap(), out.to_str().unwrap());
    let base = ["render", scene, "--spp", "1", "--out", out_s];
    let ok = eyeadapt()
        .args(base)
        .args(["--estimators", "grey_world"])
        .output()
        .unwrap();
    assert!(
        ok.status.success(),
        "{}",
        String::from_utf8_lossy(&ok.stderr)
    );
    let before: Vec<(String, Vec<u8>)> = ["raw.exr", "preview.png", "adaptation.csv"]
        .iter()
        .map(|f| (f.to_string(), std::fs::read(out.join(f)).unwrap()))
        .collect();
    for (bad, needle) in [
        (
            &["--estimators", "eye,foo"][..],
            "unknown estimator \"foo\"",
        ),
        (&["--estimators", "eye", "--cat", "cat99"][..], "cat99"),
        (&["--estimators", "eye", "--degree", "2"][..], "degree 2"),
        (&["--cat", "cat16"][..], "--estimators"),
        (&["--degree", "0.5"][..], "--estimators"),
        (&["--eye-samples", "64"][..], "--estimators"),
        (&["--threads", "10000"][..], "1024"),
        (&["--threads", "0"][..], "1024"),
    ] {
        let o = eyeadapt().args(base).args(bad).output().unwrap();
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{bad:?}: {err}");
        assert!(err.contains(needle), "{bad:?}: {err}");
        for (f, bytes) in &before {
            assert_eq!(
                &std::fs::read(out.join(f)).unwrap(),
                bytes,
                "{bad:?} changed {f}"
            );
        }
    }
}

/// `-D NAME=VALUE` gives a Mitsuba scene's `$parameters` (as `mitsuba -D`); without it an
/// undefined `$spp` is an error at its attribute; `-D` on a TOML scene or without `=` is a
/// usage error. All exit 2 before anything is written.
#[test]
fn define_gives_mitsuba_parameters_and_is_refused_elsewhere() {
    let dir = tempfile::tempdir().unwrap();
    let xml = dir.path().join("scene.xml");
    std::fs::write(
        &xml,
        "<scene version=\"3.0.0\">\n<sensor type=\"perspective\"><sampler type=\"independent\"><integer name=\"sample_count\" value=\"$spp\"/></sampler><film type=\"hdrfilm\"><integer name=\"width\" value=\"8\"/><integer name=\"height\" value=\"6\"/></film></sensor>\n<shape type=\"sphere\"/><emitter type=\"constant\"/>\n</scene>\n",
    )
    .unwrap();
    let toml = dir.path().join("scene.toml");
    std::fs::write(&toml, GOOD).unwrap();
    let run = |args: &[&str]| {
        let out = dir.path().join("out");
        let o = eyeadapt()
            .arg("render")
            .args(args)
            .arg("--out")
            .arg(&out)
            .output()
            .unwrap();
        (
            o.status.code().unwrap_or(-1),
            String::from_utf8_lossy(&o.stderr).into_owned(),
            out.join("raw.exr").exists(),
        )
    };
    let x = xml.to_str().unwrap();
    let (code, err, written) = run(&[x]);
    assert!(
        code == 2 && err.contains("scene.xml:2:") && err.contains("$spp") && !written,
        "{err}"
    );
    let (code, err, written) = run(&[x, "-D", "spp=2"]);
    assert!(code == 0 && written, "{err}");
    let _ = std::fs::remove_dir_all(dir.path().join("out"));
    let (code, err, written) = run(&[toml.to_str().unwrap(), "-D", "spp=2"]);
    assert!(code == 2 && err.contains("-D") && !written, "{err}");
    let (code, err, written) = run(&[x, "-D", "spp"]);
    assert!(code == 2 && err.contains("NAME=VALUE") && !written, "{err}");
}
