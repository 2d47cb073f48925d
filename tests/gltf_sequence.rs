//! A job whose scene is a glTF file (`tests/corpus/good/walk.gltf`: an animated camera, a
//! floor and a lamp, no `[camera_path]` in the job) through everything a farm does with it:
//! chunks merged equal one whole run bit for bit, any thread count gives the same bits, a
//! rerun resumes without rendering, and the report reads it.
mod common;

use common::snapshot;
use std::path::Path;
use std::process::Command;

fn eyeadapt() -> Command {
    Command::new(env!("CARGO_BIN_EXE_eyeadapt"))
}

fn run(args: &[&str], dir: &Path) -> String {
    let o = eyeadapt().args(args).current_dir(dir).output().unwrap();
    assert!(
        o.status.success(),
        "eyeadapt {args:?} failed: {}",
        String::from_utf8_lossy(&o.stderr)
    );
    String::from_utf8_lossy(&o.stdout).into_owned() + &String::from_utf8_lossy(&o.stderr)
}

fn sequence(dir: &Path, out: &str, extra: &[&str]) -> String {
    let mut args = vec![
        "sequence",
        "job.toml",
        "--eye-samples",
        "64",
        "--no-report",
        "--log-format",
        "plain",
        "--out",
        out,
    ];
    args.extend_from_slice(extra);
    run(&args, dir)
}

#[test]
fn a_gltf_job_chunks_merges_resumes_and_reports_like_any_other() {
    let t = tempfile::tempdir().unwrap();
    let dir = t.path();
    let repo = Path::new(env!("CARGO_MANIFEST_DIR"));
    std::fs::copy(
        repo.join("tests/corpus/good/walk.gltf"),
        dir.join("walk.gltf"),
    )
    .unwrap();
    std::fs::write(
        dir.join("job.toml"),
        "scene = \"walk.gltf\"\n[render]\nwidth = 16\nheight = 9\nspp = 1\n",
    )
    .unwrap();

    sequence(dir, "whole", &[]);
    let whole = snapshot(&dir.join("whole"));
    let csv = String::from_utf8(whole["adaptation.csv"].clone()).unwrap();
    let frames: std::collections::BTreeSet<&str> = csv
        .lines()
        .skip(1)
        .map(|l| l.split(',').next().unwrap())
        .collect();
    assert_eq!(frames.len(), 25, "the file's 1 s animation at 24 fps");

    for i in 0..3 {
        let idx = i.to_string();
        sequence(
            dir,
            &format!("chunk{i}"),
            &["--chunk-size", "10", "--chunk-index", &idx],
        );
    }
    run(
        &["merge", "chunk0", "chunk1", "chunk2", "--out", "merged"],
        dir,
    );
    let mut merged = snapshot(&dir.join("merged"));
    let mut want = whole.clone();
    merged.remove("manifest.json");
    want.remove("manifest.json");
    assert_eq!(
        want.keys().collect::<Vec<_>>(),
        merged.keys().collect::<Vec<_>>()
    );
    for (k, v) in &want {
        assert!(
            v == &merged[k],
            "merged chunks: {k} differs from the whole run"
        );
    }

    sequence(dir, "one-thread", &["--threads", "1"]);
    assert!(
        snapshot(&dir.join("one-thread")) == whole,
        "--threads 1 gives other bits"
    );

    let again = sequence(dir, "whole", &[]);
    assert!(again.contains("0 frame(s) rendered"), "{again}");
    assert!(
        snapshot(&dir.join("whole")) == whole,
        "a rerun changed the outputs"
    );

    run(&["report", "whole"], dir);
    assert!(dir.join("whole/report.html").is_file());
}

/// Mean of the raw frame's R channel (`frames/raw/frame_NNNNNN.exr`).
fn raw_mean(out: &Path, f: u32) -> f64 {
    use exr::prelude::*;
    let path = out.join(format!("frames/raw/frame_{f:06}.exr"));
    let img = read_first_rgba_layer_from_file(
        &path,
        |res, _| (res.width(), vec![0f32; res.width() * res.height()]),
        |(w, px): &mut (usize, Vec<f32>), pos, (r, _g, _b, _a): (f32, f32, f32, f32)| {
            px[pos.y() * *w + pos.x()] = r
        },
    )
    .unwrap();
    let px = &img.layer_data.channel_data.pixels.1;
    px.iter().map(|&v| f64::from(v)).sum::<f64>() / px.len() as f64
}

#[test]
fn a_moving_lamp_moves_in_every_frame_and_each_frame_stands_alone() {
    let t = tempfile::tempdir().unwrap();
    let dir = t.path();
    let repo = Path::new(env!("CARGO_MANIFEST_DIR"));
    std::fs::copy(
        repo.join("tests/corpus/good/moving-lamp.gltf"),
        dir.join("moving-lamp.gltf"),
    )
    .unwrap();
    std::fs::write(
        dir.join("job.toml"),
        "scene = \"moving-lamp.gltf\"\n[render]\nwidth = 32\nheight = 18\nspp = 4\n\
         [camera_path]\nfps = 4\n",
    )
    .unwrap();
    sequence(dir, "whole", &[]);
    let whole = dir.join("whole");
    // The lamp rises from 1 m to 3 m above the floor over the 5 frames: each is darker.
    let means: Vec<f64> = (0..5).map(|f| raw_mean(&whole, f)).collect();
    assert!(
        means.windows(2).all(|w| w[1] < 0.9 * w[0]),
        "frame means {means:?}"
    );
    // Frame 3 rendered on its own is frame 3 of the whole run, bit for bit.
    sequence(dir, "alone", &["--frames", "3"]);
    let name = "frames/raw/frame_000003.exr";
    assert!(
        std::fs::read(whole.join(name)).unwrap()
            == std::fs::read(dir.join("alone").join(name)).unwrap(),
        "frame 3 alone differs from frame 3 in sequence"
    );
}
