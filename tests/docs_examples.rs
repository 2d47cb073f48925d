//! The examples in the documentation are real: they load and render.
use std::process::Command;

fn fenced_toml(doc: &str) -> Vec<String> {
    let mut out = Vec::new();
    let mut cur: Option<String> = None;
    for line in doc.lines() {
        match (&mut cur, line.trim_start()) {
            (None, l) if l.starts_with("```toml") => cur = Some(String::new()),
            (Some(_), l) if l.starts_with("```") => out.push(cur.take().unwrap()),
            (Some(c), _) => {
                c.push_str(line);
                c.push('\n');
            }
            _ => {}
        }
    }
    out
}

#[test]
fn scene_format_example_loads_and_renders() {
    let doc = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/docs/scene-format.md"))
        .unwrap();
    let example = fenced_toml(&doc)
        .into_iter()
        .next()
        .expect("a toml example");
    let dir = tempfile::tempdir().unwrap();
    std::fs::create_dir(dir.path().join("meshes")).unwrap();
    // The example references an OBJ; give it a small tetrahedron.
    std::fs::write(
        dir.path().join("meshes/statue.obj"),
        "v 0 0 0\nv 0.1 0 0\nv 0 0.1 0\nv 0 0 0.1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n",
    )
    .unwrap();
    let scene = dir.path().join("scene.toml");
    std::fs::write(&scene, &example).unwrap();
    let s = eyeadapt_scene::load_scene(&scene)
        .unwrap_or_else(|e| panic!("documented example fails:\n{e}"));
    assert_eq!(s.lights.len(), 2);
    assert!(s.camera_path.is_some());
    let o = Command::new(env!("CARGO_BIN_EXE_eyeadapt"))
        .args([
            "render",
            scene.to_str().unwrap(),
            "--spp",
            "1",
            "--width",
            "16",
            "--height",
            "16",
        ])
        .args(["--out", dir.path().join("out").to_str().unwrap()])
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
}

#[test]
fn scene_format_sky_example_loads_and_renders() {
    let doc = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/docs/scene-format.md"))
        .unwrap();
    let example = fenced_toml(&doc)
        .into_iter()
        .find(|t| t.contains("\nmap = "))
        .expect("the environment-map example");
    let dir = tempfile::tempdir().unwrap();
    std::fs::create_dir(dir.path().join("skies")).unwrap();
    // An 8 × 4 Radiance HDR sky in the flat (not run-length) form: brighter at the top.
    let mut hdr = b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 4 +X 8\n".to_vec();
    for row in 0..4u8 {
        for _ in 0..8 {
            hdr.extend_from_slice(&[200 - 40 * row, 210 - 40 * row, 250 - 40 * row, 128]);
        }
    }
    std::fs::write(dir.path().join("skies/sky.hdr"), hdr).unwrap();
    let scene = dir.path().join("scene.toml");
    std::fs::write(&scene, &example).unwrap();
    let s = eyeadapt_scene::load_scene(&scene)
        .unwrap_or_else(|e| panic!("documented example fails:\n{e}"));
    let map = s.environment_map.as_ref().expect("an environment map");
    assert_eq!((map.image.width, map.image.height), (8, 4));
    assert!(
        map.image.texels[0].x > map.image.texels[31].x,
        "top row brighter"
    );
    assert!(matches!(
        s.lights[0],
        eyeadapt_scene::Light::Directional { direction, .. } if (direction.length() - 1.0).abs() < 1e-6
    ));
    let out = dir.path().join("out");
    let o = Command::new(env!("CARGO_BIN_EXE_eyeadapt"))
        .args(["render", scene.to_str().unwrap(), "--spp", "2"])
        .args(["--out", out.to_str().unwrap()])
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
}

#[test]
fn job_format_example_parses() {
    let src = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/crates/sequencer/src/job.rs"
    ))
    .unwrap();
    let doc: String = src
        .lines()
        .take_while(|l| l.starts_with("//!"))
        .map(|l| {
            format!(
                "{}\n",
                l.trim_start_matches("//!").strip_prefix(' ').unwrap_or("")
            )
        })
        .collect();
    let example = fenced_toml(&doc)
        .into_iter()
        .next()
        .expect("a toml example in job.rs docs");
    let dir = tempfile::tempdir().unwrap();
    let job = dir.path().join("job.toml");
    std::fs::write(&job, &example).unwrap();
    let o = Command::new(env!("CARGO_BIN_EXE_eyeadapt"))
        .args(["plan", job.to_str().unwrap(), "--chunk-size", "10"])
        .output()
        .unwrap();
    let out = String::from_utf8_lossy(&o.stdout);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(out.contains("EYEADAPT_FRAMES='72'"), "{out}");
    assert!(out.contains("EYEADAPT_CHUNKS='8'"), "{out}");
}

#[test]
fn texture_and_instance_example_loads_and_renders() {
    use eyeadapt_scene::{Bsdf, Param, Texture};
    let doc = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/docs/scene-format.md"))
        .unwrap();
    let example = fenced_toml(&doc)
        .into_iter()
        .find(|t| t.contains("[[instances]]"))
        .expect("the textures and instances example");
    let dir = tempfile::tempdir().unwrap();
    for sub in ["meshes", "textures"] {
        std::fs::create_dir(dir.path().join(sub)).unwrap();
    }
    let mut tiles = image::RgbImage::new(4, 4);
    for (x, y, p) in tiles.enumerate_pixels_mut() {
        *p = image::Rgb(if (x + y) % 2 == 0 {
            [200, 60, 40]
        } else {
            [240, 240, 230]
        });
    }
    tiles.save(dir.path().join("textures/tiles.png")).unwrap();
    // A tetrahedron with texture coordinates and vertex colours.
    std::fs::write(
        dir.path().join("meshes/vase.obj"),
        "v 0 0 0 1 0 0\nv 1 0 0 0 1 0\nv 0 1 0 0 0 1\nv 0 0 1 1 1 0\n\
         vt 0 0\nvt 1 0\nvt 0 1\nvt 1 1\n\
         f 1/1 3/3 2/2\nf 1/1 2/2 4/4\nf 1/1 4/4 3/3\nf 2/2 3/3 4/4\n",
    )
    .unwrap();
    let scene = dir.path().join("scene.toml");
    std::fs::write(&scene, &example).unwrap();
    let s = eyeadapt_scene::load_scene(&scene)
        .unwrap_or_else(|e| panic!("documented example fails:\n{e}"));
    assert_eq!(s.textures.len(), 3);
    assert!(matches!(&s.textures[0], Texture::Bitmap(b) if b.image.width == 4));
    assert!(matches!(
        s.materials[0].bsdf,
        Bsdf::Diffuse {
            reflectance: Param::Texture(_)
        }
    ));
    // Three quads placed once, the vase mesh (a template) twice, sharing one mesh.
    assert_eq!(s.meshes.len(), 4);
    assert_eq!(s.instances.len(), 5);
    let vase = &s.meshes[3];
    assert_eq!(vase.uvs.len(), 4);
    let at = |p: [f32; 3]| {
        vase.positions
            .iter()
            .position(|q| q.to_array() == p)
            .unwrap()
    };
    // vt 0 1 at (0, 1, 0): OBJ's v grows upwards, Mitsuba's down the image.
    assert_eq!(vase.uvs[at([0.0, 1.0, 0.0])].to_array(), [0.0, 0.0]);
    assert_eq!(vase.uvs[at([1.0, 0.0, 0.0])].to_array(), [1.0, 1.0]);
    assert_eq!(vase.colors[at([1.0, 0.0, 0.0])].to_array(), [0.0, 1.0, 0.0]);
    let o = Command::new(env!("CARGO_BIN_EXE_eyeadapt"))
        .args(["render", scene.to_str().unwrap(), "--spp", "2"])
        .args(["--out", dir.path().join("out").to_str().unwrap()])
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
}

/// `eyeadapt plan JOB`'s `KEY='VALUE'` lines.
fn plan(job: &std::path::Path) -> std::collections::HashMap<String, String> {
    let o = Command::new(env!("CARGO_BIN_EXE_eyeadapt"))
        .args(["plan", job.to_str().unwrap()])
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    String::from_utf8_lossy(&o.stdout)
        .lines()
        .filter_map(|l| l.split_once('='))
        .map(|(k, v)| (k.to_string(), v.trim_matches('\'').to_string()))
        .collect()
}

#[test]
fn job_format_doc_lists_the_real_defaults_and_its_example_renders() {
    let doc = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/docs/job-format.md"))
        .unwrap();
    let blocks = fenced_toml(&doc);
    assert_eq!(
        blocks.len(),
        3,
        "a complete example, a typical job and a glTF walkthrough"
    );
    let dir = tempfile::tempdir().unwrap();
    // The complete example spells out every default: it must be the same job as one that
    // names only its scene.
    let complete = dir.path().join("complete.toml");
    std::fs::write(&complete, &blocks[0]).unwrap();
    let minimal = dir.path().join("minimal.toml");
    std::fs::write(&minimal, "scene = \"builtin:three-rooms\"\n").unwrap();
    let (full, bare) = (plan(&complete), plan(&minimal));
    assert_eq!(full["EYEADAPT_JOB_NAME"], "walkthrough");
    assert_eq!(full["EYEADAPT_JOB_HASH"], bare["EYEADAPT_JOB_HASH"]);
    assert_eq!(full["EYEADAPT_FRAMES"], bare["EYEADAPT_FRAMES"]);

    // The glTF walkthrough's keys, on the corpus's small animated file (one second at 24 fps)
    // with its camera and animation named as the example names them.
    let gltf = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/corpus/good/walk.gltf"
    ))
    .unwrap()
    .replace("\"Walk\"", "\"CameraAction\"");
    std::fs::write(dir.path().join("walk.glb"), gltf).unwrap();
    let walk = dir.path().join("walk.toml");
    std::fs::write(&walk, &blocks[2]).unwrap();
    assert_eq!(plan(&walk)["EYEADAPT_FRAMES"], "25");

    // The typical job: 48 of its 49 frames; two of them rendered, tiny.
    let typical = dir.path().join("typical.toml");
    std::fs::write(&typical, &blocks[1]).unwrap();
    assert_eq!(plan(&typical)["EYEADAPT_FRAMES"], "48");
    let out = dir.path().join("out");
    let o = Command::new(env!("CARGO_BIN_EXE_eyeadapt"))
        .args(["sequence", typical.to_str().unwrap(), "--frames", "0-1"])
        .args([
            "--width",
            "8",
            "--height",
            "8",
            "--spp",
            "1",
            "--eye-samples",
            "64",
        ])
        .args([
            "--no-report",
            "--no-progress-bar",
            "--out",
            out.to_str().unwrap(),
        ])
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let csv = std::fs::read_to_string(out.join("adaptation.csv")).unwrap();
    // Header plus one row per frame and estimator.
    assert_eq!(csv.lines().count(), 1 + 2 * 3, "{csv}");
    assert!(out.join("frames/wcam/frame_000001.png").exists());
}

#[test]
fn surface_detail_example_loads_and_renders() {
    use eyeadapt_scene::{Bsdf, Light, Param};
    let doc = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/docs/scene-format.md"))
        .unwrap();
    let example = fenced_toml(&doc)
        .into_iter()
        .find(|t| t.contains("normal_map = "))
        .expect("the surface-detail example");
    let dir = tempfile::tempdir().unwrap();
    std::fs::create_dir(dir.path().join("textures")).unwrap();
    // Bricks: normals tilted along ±x in alternate columns, flat in the mortar rows.
    let normals = image::RgbImage::from_fn(16, 16, |x, y| match (y % 4, x / 4 % 2) {
        (0, _) => image::Rgb([128, 128, 255]),
        (_, 0) => image::Rgb([90, 128, 245]),
        _ => image::Rgb([166, 128, 245]),
    });
    normals
        .save(dir.path().join("textures/bricks_normal.png"))
        .unwrap();
    // A slide: warm on the left, cool on the right, a white bar along the top.
    let slide = image::RgbImage::from_fn(8, 8, |x, y| match (y, x < 4) {
        (0, _) => image::Rgb([255, 255, 255]),
        (_, true) => image::Rgb([255, 140, 40]),
        _ => image::Rgb([40, 120, 255]),
    });
    slide.save(dir.path().join("textures/slide.png")).unwrap();
    let scene = dir.path().join("scene.toml");
    std::fs::write(&scene, &example).unwrap();
    let s = eyeadapt_scene::load_scene(&scene)
        .unwrap_or_else(|e| panic!("documented example fails:\n{e}"));
    assert!(s.warnings.is_empty(), "{:?}", s.warnings);
    assert!(matches!(
        s.materials[0].bsdf,
        Bsdf::Conductor {
            alpha: Param::Const(a),
            alpha_v: Some(Param::Const(b)),
            ..
        } if a == 0.05 && b == 0.4
    ));
    assert!(matches!(&s.materials[1].bsdf, Bsdf::NormalMap { bsdf, .. }
        if matches!(**bsdf, Bsdf::BumpMap { scale, .. } if scale == 0.01)));
    assert!(matches!(
        s.materials[2].bsdf,
        Bsdf::Mask {
            opacity: Param::Texture(_),
            ..
        }
    ));
    assert_eq!(s.emission_textures.len(), 1);
    assert!(matches!(s.lights[0], Light::TexturedSpot { .. }));
    let out = dir.path().join("out");
    let o = Command::new(env!("CARGO_BIN_EXE_eyeadapt"))
        .args(["render", scene.to_str().unwrap(), "--spp", "4"])
        .args(["--out", out.to_str().unwrap()])
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
}
