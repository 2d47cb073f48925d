//! Hostile inputs that are not malformed files (those are `tests/corpus/`): paths that are
//! FIFOs, devices or symbolic-link loops, output paths that dangle, and the like. Each must
//! fail within seconds with exit 2 and a message naming the path, never block or hang, and
//! write nothing.
mod common;

use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

fn eyeadapt() -> Command {
    Command::new(env!("CARGO_BIN_EXE_eyeadapt"))
}

/// Runs `cmd` with a time limit; a command that blocks is killed and reported as exit -9.
fn run_limited(cmd: &mut Command, limit: Duration) -> (i32, String, String) {
    let mut child = cmd
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let start = Instant::now();
    while child.try_wait().unwrap().is_none() {
        if start.elapsed() > limit {
            child.kill().unwrap();
            child.wait().unwrap();
            return (-9, String::new(), "(killed: it blocked)".into());
        }
        std::thread::sleep(Duration::from_millis(20));
    }
    let o = child.wait_with_output().unwrap();
    (
        o.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&o.stdout).into_owned(),
        String::from_utf8_lossy(&o.stderr).into_owned(),
    )
}

fn run(cmd: &mut Command) -> (i32, String, String) {
    run_limited(cmd, Duration::from_secs(60))
}

fn mkfifo(p: &Path) {
    let ok = Command::new("mkfifo").arg(p).status().unwrap().success();
    assert!(ok, "mkfifo {}", p.display());
}

fn corpus(rel: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/corpus")
        .join(rel)
}

const SCENE_HEAD: &str = "[camera]\nposition = [0.3, 0.3, 3.0]\nlook_at = [0.3, 0.3, 0.0]\n\
                          fov_deg = 45.0\nwidth = 8\nheight = 6\n\n\
                          [environment]\nradiance = [1.0, 1.0, 1.0]\n\n";

/// Every kind of file a scene or job names, made a FIFO in turn: the run fails at once
/// (exit 2) naming the FIFO, instead of waiting forever for a writer.
#[test]
fn a_fifo_anywhere_an_input_file_belongs_fails_at_once_naming_it() {
    let t = tempfile::tempdir().unwrap();
    let d = t.path();
    let fifo = d.join("pipe.fifo");
    mkfifo(&fifo);
    let write = |name: &str, text: &str| {
        std::fs::write(d.join(name), text).unwrap();
        d.join(name)
    };
    let tri = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    let obj_shape =
        |file: &str| format!("{SCENE_HEAD}[[shapes]]\ntype = \"obj\"\nfile = \"{file}\"\n");
    let textured = format!(
        "{SCENE_HEAD}[[textures]]\nname = \"t\"\ntype = \"bitmap\"\nfile = \"pipe.fifo\"\n\n\
         [[materials]]\nname = \"m\"\ntype = \"diffuse\"\nreflectance_texture = \"t\"\n\n\
         [[shapes]]\ntype = \"sphere\"\nmaterial = \"m\"\ncenter = [0.0, 0.0, 0.0]\nradius = 0.5\n"
    );
    let gltf = std::fs::read_to_string(corpus("gltf/missing-buffer.gltf"))
        .unwrap()
        .replace("absent.bin", "pipe.fifo");
    // (what, command, file written, its text); the command runs on the file.
    std::fs::write(d.join("mtl.obj"), format!("mtllib pipe.fifo\n{tri}")).unwrap();
    let xml =
        |body: &str| format!("<scene version=\"3.0.0\"><emitter type=\"constant\"/>{body}</scene>");
    let files: Vec<(&str, &str, &str, String)> = vec![
        (
            "job's scene",
            "plan",
            "scene-fifo.toml",
            "scene = \"pipe.fifo\"\n".into(),
        ),
        ("OBJ file", "render", "obj.toml", obj_shape("pipe.fifo")),
        ("OBJ mtllib", "render", "mtl.toml", obj_shape("mtl.obj")),
        ("texture", "render", "tex.toml", textured),
        (
            "Mitsuba include",
            "render",
            "inc.xml",
            xml("<include filename=\"pipe.fifo\"/>"),
        ),
        (
            "PLY filename",
            "render",
            "ply.xml",
            xml("<shape type=\"ply\"><string name=\"filename\" value=\"pipe.fifo\"/></shape>"),
        ),
        (
            "CSV camera track",
            "plan",
            "track.toml",
            "scene = \"builtin:three-rooms\"\n[camera_path]\nfile = \"pipe.fifo\"\n".into(),
        ),
        ("glTF buffer", "render", "buf.gltf", gltf),
    ];
    let mut cases = vec![(
        "job file",
        vec!["plan".to_string(), fifo.display().to_string()],
    )];
    for (what, cmd, file, text) in &files {
        cases.push((
            what,
            vec![cmd.to_string(), write(file, text).display().to_string()],
        ));
    }
    let mut failures = Vec::new();
    for (what, args) in &cases {
        let (code, _, err) = run_limited(
            eyeadapt()
                .args(args)
                .args(["--spp", "1", "--out"])
                .arg(d.join("out")),
            Duration::from_secs(20),
        );
        if code != 2 || !err.contains("pipe.fifo") || !err.contains("FIFO") {
            failures.push(format!("{what}: exit {code}\n{err}"));
        }
    }
    assert!(!d.join("out").exists(), "a failed run wrote its output");
    assert!(failures.is_empty(), "{}", failures.join("\n---\n"));
}

/// A job over the corpus's good scene, named `name` (TOML basic-string escapes allowed).
fn named_job(dir: &Path, name: &str) -> PathBuf {
    std::fs::copy(corpus("good/scene.toml"), dir.join("scene.toml")).unwrap();
    let job = dir.join("job.toml");
    std::fs::write(
        &job,
        format!(
            "name = \"{name}\"\nscene = \"scene.toml\"\n[render]\nwidth = 8\nheight = 6\nspp = 1\n\
             [estimators]\nlist = [\"grey_world\"]\n\
             [camera_path]\nfps = 2\nkeyframes = [ {{ time = 0.0, position = [0.0, 1.0, 3.0], look_at = [0.0, 1.0, 0.0] }},\n\
             {{ time = 1.0, position = [0.0, 1.0, 4.0], look_at = [0.0, 1.0, 0.0] }} ]\n"
        ),
    )
    .unwrap();
    job
}

/// A job name is a plain file name: an absolute path, `..`, a separator, `/`, a NUL or other
/// control character is refused (exit 2, at the `name` line) before anything is written, so
/// the default output `out/<name>` can never leave `out/`.
#[test]
fn a_job_name_that_is_not_a_plain_file_name_is_refused() {
    let t = tempfile::tempdir().unwrap();
    let d = t.path();
    let victim = d.join("victim");
    let bad = [
        victim.display().to_string(),
        "/".into(),
        "..".into(),
        ".".into(),
        "".into(),
        "../escape".into(),
        "a/b".into(),
        "a\\\\b".into(),
        "a\\u0000b".into(),
        "line\\nbreak".into(),
    ];
    for name in &bad {
        let job = named_job(d, name);
        for cmd in ["plan", "sequence"] {
            let (code, _, err) = run(eyeadapt().current_dir(d).args([
                cmd,
                job.to_str().unwrap(),
                "--no-report",
                "--no-progress-bar",
            ]));
            assert_eq!(code, 2, "{cmd} with name {name:?}: {err}");
            assert!(
                err.contains("job.toml:1:") && err.contains("one plain file name"),
                "{cmd} with name {name:?}: {err}"
            );
        }
    }
    assert!(!victim.exists() && !d.join("out").exists() && !d.join("escape").exists());
    // A plain name with spaces and punctuation is fine.
    let job = named_job(d, "Shot 12 (take 3)");
    let (code, _, err) = run(eyeadapt().current_dir(d).args([
        "sequence",
        job.to_str().unwrap(),
        "--no-report",
        "--no-progress-bar",
        "--eye-samples",
        "16",
    ]));
    assert_eq!(code, 0, "{err}");
    assert!(d.join("out/Shot 12 (take 3)/manifest.json").exists());
}

/// The stale-temporary cleanup at the start of a run deletes only this program's own
/// temporaries: files a user keeps in the output directory under names that merely look like
/// temporaries (`.notes.tmp-1`, or anything in a directory of their own) survive a resume.
#[test]
fn resuming_deletes_only_our_own_stale_temporaries() {
    let t = tempfile::tempdir().unwrap();
    let d = t.path();
    let job = named_job(d, "clean");
    let out = d.join("out");
    let seq = || {
        run(eyeadapt().args([
            "sequence",
            job.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
            "--no-report",
            "--no-progress-bar",
            "--eye-samples",
            "16",
        ]))
    };
    let (code, _, err) = seq();
    assert_eq!(code, 0, "{err}");
    let keep = [
        ".notes.tmp-1",
        "mine/.draft.png.tmp-7",
        "mine/.manifest.json.tmp-7",
    ];
    for rel in keep {
        std::fs::create_dir_all(out.join(rel).parent().unwrap()).unwrap();
        std::fs::write(out.join(rel), "user data").unwrap();
    }
    // What a killed run leaves: a temporary of a frame file and of the manifest.
    let stale = [
        ".manifest.json.tmp-4242",
        "frames/raw/.frame_000001.exr.tmp-4242",
    ];
    for rel in stale {
        std::fs::write(out.join(rel), "half written").unwrap();
    }
    let (code, _, err) = seq();
    assert_eq!(code, 0, "{err}");
    for rel in keep {
        assert_eq!(
            std::fs::read_to_string(out.join(rel)).ok().as_deref(),
            Some("user data"),
            "{rel} was deleted"
        );
    }
    for rel in stale {
        assert!(!out.join(rel).exists(), "{rel} was left");
    }
}

/// `plan`'s output is `eval`-safe in POSIX sh and bash: a job name full of shell syntax
/// (command substitution, backquotes, quotes, globs, spaces) comes back byte for byte and runs
/// nothing. `--format json` says the same.
#[test]
fn plan_output_is_safe_to_eval_in_sh_and_bash_and_json_says_the_same() {
    let t = tempfile::tempdir().unwrap();
    let d = t.path();
    let hostile = r#"x $(touch pwned1) `touch pwned2` ${HOME} 'q' "dq" ; touch pwned3 * & |"#;
    let job = named_job(d, &hostile.replace('\\', "\\\\").replace('"', "\\\""));
    let exe = env!("CARGO_BIN_EXE_eyeadapt");
    for shell in ["sh", "bash"] {
        let script = format!(
            "eval \"$('{exe}' plan '{}' --chunk-size 2)\" && \
             printf '%s\\n%s\\n%s\\n' \"$EYEADAPT_JOB_NAME\" \"$EYEADAPT_FRAMES\" \"$EYEADAPT_CHUNKS\"",
            job.display()
        );
        let (code, out, err) = run(Command::new(shell).current_dir(d).args(["-c", &script]));
        assert_eq!(code, 0, "{shell}: {err}");
        let lines: Vec<&str> = out.lines().collect();
        assert_eq!(lines, [hostile, "3", "2"], "{shell}");
        for f in ["pwned1", "pwned2", "pwned3"] {
            assert!(
                !d.join(f).exists(),
                "{shell} ran a command from the job name"
            );
        }
    }
    let (code, out, err) = run(eyeadapt().args([
        "plan",
        job.to_str().unwrap(),
        "--chunk-size",
        "2",
        "--format",
        "json",
    ]));
    assert_eq!(code, 0, "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert_eq!(v["job_name"], hostile);
    assert_eq!(
        (v["frames"].as_u64(), v["chunks"].as_u64()),
        (Some(3), Some(2))
    );
    assert_eq!(
        (v["first"].as_u64(), v["last"].as_u64()),
        (Some(0), Some(2))
    );
    assert_eq!(v["job_hash"].as_str().map(str::len), Some(64));
}

/// The demo job's first four frames, tiny, without the report.
fn small_sequence(out: &Path) {
    let (code, _, err) = run(eyeadapt()
        .args([
            "sequence", "--frames", "0-3", "--width", "8", "--height", "6",
        ])
        .args(common::QUICK)
        .arg("--out")
        .arg(out));
    assert_eq!(code, 0, "{err}");
}

/// Every file under `dir` but the lock, with its bytes and modification time.
fn bytes_of(dir: &Path) -> Vec<(String, Vec<u8>, std::time::SystemTime)> {
    let mut v: Vec<_> = common::walk(dir)
        .into_iter()
        .filter(|(rel, _)| !rel.ends_with(".eyeadapt.lock"))
        .map(|(rel, p)| {
            let t = std::fs::metadata(&p).unwrap().modified().unwrap();
            (rel, std::fs::read(&p).unwrap(), t)
        })
        .collect();
    v.sort();
    v
}

/// `report` checks every input before it writes anything: `adaptation.csv` against the
/// committed rows (frames cut from it, `rows/` intact), the raw EXRs against their recorded
/// sizes, `--sigma-s` × fps against the largest smoothing window. Each is exit 2 naming what is
/// wrong, and the directory is left exactly as it was (the CSV is not rewritten with derived
/// rows first).
#[test]
fn report_validates_every_input_before_writing_anything() {
    let t = tempfile::tempdir().unwrap();
    let good = t.path().join("good");
    small_sequence(&good);
    let case = |name: &str, damage: &dyn Fn(&Path), args: &[&str], needles: &[&str]| {
        let dir = t.path().join(name);
        let (code, _, err) = run(Command::new("cp").arg("-a").arg(&good).arg(&dir));
        assert_eq!(code, 0, "{err}");
        damage(&dir);
        let before = bytes_of(&dir);
        let (code, _, err) = run(eyeadapt().arg("report").arg(&dir).args(args));
        assert_eq!(code, 2, "{name}: {err}");
        for n in needles {
            assert!(err.contains(n), "{name}: {n:?} not in {err}");
        }
        assert!(!err.contains("panicked"), "{name}: {err}");
        assert!(before == bytes_of(&dir), "{name}: the failed report wrote");
    };
    case(
        "cut",
        &|d| {
            let csv = std::fs::read_to_string(d.join("adaptation.csv")).unwrap();
            let kept: String = csv
                .lines()
                .filter(|l| !l.starts_with("2,") && !l.starts_with("3,"))
                .map(|l| format!("{l}\n"))
                .collect();
            std::fs::write(d.join("adaptation.csv"), kept).unwrap();
        },
        &[],
        &["adaptation.csv", "2 committed frame(s) (2, 3) differ"],
    );
    case(
        "bad-exr",
        &|d| {
            let p = d.join("frames/raw/frame_000002.exr");
            let bytes = std::fs::read(&p).unwrap();
            std::fs::write(&p, &bytes[..100]).unwrap();
        },
        &[],
        &["frame_000002.exr", "frame 2's raw EXR is 100 bytes"],
    );
    case(
        "sigma",
        &|_| {},
        &["--sigma-s", "1e18"],
        &["--sigma-s 1e18", "more than the 100000 frames"],
    );
    case(
        "fps",
        &|d| {
            let m = std::fs::read_to_string(d.join("manifest.json")).unwrap();
            let m = m.replacen("\"fps\": 24.0", "\"fps\": 1e300", 1);
            std::fs::write(d.join("manifest.json"), m).unwrap();
        },
        &[],
        &["manifest fps 1e300 is above the 10000"],
    );
}

/// Bad paths are bad input (exit 2) with a message that says what the path is, not I/O
/// failures (exit 1): a job file that is a loop of symbolic links or a device, `--out` a
/// symbolic link to nowhere, `report` of a regular file.
#[test]
fn bad_paths_are_bad_input_with_true_messages() {
    let t = tempfile::tempdir().unwrap();
    let d = t.path();
    let lp = d.join("loop.toml");
    std::os::unix::fs::symlink(&lp, &lp).unwrap();
    let dangling = d.join("dangling");
    std::os::unix::fs::symlink(d.join("nowhere/at/all"), &dangling).unwrap();
    let file = d.join("file.txt");
    std::fs::write(&file, "not a directory").unwrap();
    let job = named_job(d, "ok");
    let cases: Vec<(Vec<&str>, &str)> = vec![
        (
            vec!["sequence", lp.to_str().unwrap()],
            "loop of symbolic links",
        ),
        (vec!["sequence", "/dev/zero"], "character device"),
        (
            vec![
                "sequence",
                job.to_str().unwrap(),
                "--out",
                dangling.to_str().unwrap(),
            ],
            "is a symbolic link to",
        ),
        (
            vec![
                "render",
                "builtin:cornell-box",
                "--out",
                dangling.to_str().unwrap(),
            ],
            "which does not exist",
        ),
        (vec!["report", file.to_str().unwrap()], "is not a directory"),
        (
            vec!["plan", job.to_str().unwrap(), "--start", "2", "--end", "1"],
            "--start 2 is after --end 1",
        ),
        (
            vec!["plan", job.to_str().unwrap(), "--start", "5", "--end", "9"],
            "--start 5 is after the job's last frame 2",
        ),
    ];
    for (args, needle) in cases {
        let (code, _, err) = run(eyeadapt().args(&args));
        assert_eq!(code, 2, "{args:?}: {err}");
        assert!(err.contains(needle), "{args:?}: {needle:?} not in {err}");
    }
    assert!(!d.join("nowhere").exists());
}

/// Numbers that only break after arithmetic: `render --exposure=nan`, and a bench with no
/// samples, a depth below -1 or no runs, are usage errors (exit 2), not accepted.
#[test]
fn nonsense_numbers_on_the_command_line_are_refused() {
    for args in [
        &["render", "builtin:cornell-box", "--exposure=nan"][..],
        &["render", "builtin:cornell-box", "--exposure=inf"],
        &["bench", "--spp", "0"],
        &["bench", "--max-depth", "-5"],
        &["bench", "--runs", "0"],
        &["bench", "--size", "0"],
    ] {
        let (code, _, err) = run(eyeadapt().args(args));
        assert_eq!(code, 2, "{args:?}: {err}");
        assert!(err.contains("invalid value"), "{args:?}: {err}");
    }
}

/// A quad with 1e10-long edges under a uniform sky renders as the diffuse plane it is (the
/// white furnace's ρ·L = 0.5 per pixel), not black: its normal used to be the cross product of
/// its edges normalised, whose squared length (1e40) overflows f32.
#[test]
fn a_quad_with_1e10_long_edges_renders_like_any_plane() {
    let t = tempfile::tempdir().unwrap();
    let scene = t.path().join("plane.toml");
    std::fs::write(
        &scene,
        "[camera]\nposition = [0.0, 1.0, 3.0]\nlook_at = [0.0, 0.0, 2.0]\nfov_deg = 45.0\n\
         width = 8\nheight = 6\n\n[[materials]]\nname = \"grey\"\ntype = \"diffuse\"\n\
         reflectance = [0.5, 0.5, 0.5]\n\n[[shapes]]\ntype = \"quad\"\nmaterial = \"grey\"\n\
         corner = [-5e9, 0.0, 5e9]\nu = [1e10, 0.0, 0.0]\nv = [0.0, 0.0, -1e10]\n\n\
         [environment]\nradiance = [1.0, 1.0, 1.0]\n",
    )
    .unwrap();
    let out = t.path().join("out");
    let (code, _, err) = run(eyeadapt()
        .arg("render")
        .arg(&scene)
        .args(["--spp", "64", "--out"])
        .arg(&out));
    assert_eq!(code, 0, "{err}");
    let f = eyeadapt_sequencer::output::read_exr(&out.join("raw.exr")).unwrap();
    let n = f.rgb.len() as f32;
    let mean = f.rgb.iter().map(|p| p[0] + p[1] + p[2]).sum::<f32>() / (3.0 * n);
    assert!((mean - 0.5).abs() < 0.05, "mean radiance {mean}, want 0.5");
    assert!(
        f.hit.iter().all(|h| *h == 1.0),
        "every pixel sees the plane"
    );
    let normal_y = f.normal.iter().map(|p| p[1]).fold(f32::INFINITY, f32::min);
    assert!(
        normal_y > 0.99,
        "first-hit normal is +y, got y = {normal_y}"
    );
}
