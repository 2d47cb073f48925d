//! Bad samples, not bad files: NaN/Inf samples injected into a loaded job are counted,
//! dropped and flagged; degenerate triangles and zero-area lights make none.
use super::harness::*;

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
