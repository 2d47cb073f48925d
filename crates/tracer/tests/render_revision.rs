//! The bits of a set of small renders, pinned to [`RENDER_REVISION`]. A change to the
//! renderer that moves any of them fails here: if the change is meant, raise `RENDER_REVISION`
//! in `crates/tracer/src/revision.rs` (so that output directories rendered by the older binary
//! refuse to be resumed or merged with this one) and retake the pins from the message. An
//! edit of a built-in scene (the interior's window portals) moves its pins but not the revision:
//! the job hash already covers the scene through its fingerprint.
//!
//! The cases cover the renderer's distinct paths: two built-in TOML scenes with textures,
//! glass panes, an environment map, sun, points and spots (box and splatting filter), the
//! Cornell box, a Mitsuba XML scene (rough plastic, smooth glass, a spot), more lights than the
//! direct choice handles (the light tree, in open space and behind walls), and the eye sensor.
mod common;

use common::{builtin_view, frame_hash, settings};
use eyeadapt_scene::{Light, Material, Rgb, Scene, quad_mesh};
use eyeadapt_tracer::{
    EyeSettings, Frame, PathSettings, RENDER_REVISION, SceneData, View, eye_sensor, render,
};
use glam::Vec3;
use std::path::Path;

/// The revision these pins belong to.
const PINNED_REVISION: u32 = 20;

/// A floor lit by 20 point lights of different colours (more than 16: the light tree).
fn many_points() -> (SceneData, View) {
    let mut s = Scene::default();
    let floor = s.add_material(Material::diffuse("floor", Rgb::splat(0.5)));
    let o = Vec3::new(-6.0, -4.0, 0.0);
    s.add_world_mesh(quad_mesh(o, 12.0 * Vec3::X, 8.0 * Vec3::Y), Some(floor));
    for k in 0..20 {
        let (i, j) = ((k % 5) as f32, (k / 5) as f32);
        s.lights.push(Light::Point {
            position: Vec3::new(-4.8 + 2.4 * i, -3.0 + 2.0 * j, 0.5 + 0.1 * k as f32),
            intensity: Rgb::new(0.2 + 0.05 * k as f32, 0.6, 1.0 - 0.04 * k as f32),
        });
    }
    let view = View {
        position: Vec3::new(0.0, 0.0, 3.0),
        forward: -Vec3::Z,
        up: Vec3::Y,
        fov_deg: 100.0,
        width: 20,
        height: 14,
        projection: Default::default(),
    };
    (SceneData::new(&s), view)
}

/// Three rooms with 18 point lights more in room 3 (a light tree whose lights the walls hide
/// from most of the scene: the tree weighed by visibility).
fn rooms_and_tree() -> (SceneData, View) {
    let mut s = eyeadapt_scene::load_builtin("three-rooms").unwrap();
    for k in 0..18 {
        s.lights.push(Light::Point {
            position: Vec3::new(-1.5 + 0.18 * k as f32, 2.5, -12.5),
            intensity: Rgb::splat(1.0),
        });
    }
    let mut view = View::from_camera(s.camera.as_ref().unwrap());
    view.width = 24;
    view.height = 14;
    (SceneData::new(&s), view)
}

fn xml_view(rel: &str, w: u32, h: u32) -> (SceneData, View) {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../..")
        .join(rel);
    let scene = eyeadapt_scene::load_scene_file(&path).unwrap();
    let mut view = View::from_camera(scene.camera.as_ref().unwrap());
    view.width = w;
    view.height = h;
    (SceneData::new(&scene), view)
}

/// The frame's hash, after checking that the case renders light at all (a black frame would
/// pin nothing of the path it is meant to cover).
fn lit_hash(f: &Frame) -> u64 {
    let sum: f32 = f.rgb.iter().map(|p| p[0] + p[1] + p[2]).sum();
    assert!(sum > 0.0 && sum.is_finite());
    frame_hash(f)
}

/// Every case's hash at this revision, in a fixed order.
fn hashes() -> Vec<(&'static str, u64)> {
    let mut out = Vec::new();
    for name in ["interior", "three-rooms", "cornell-box"] {
        let (data, view) = builtin_view(name, 24, 14);
        out.push((name, lit_hash(&render(&data, &view, &settings(8, 3, 8)))));
    }
    let (data, view) = builtin_view("interior", 24, 14);
    let mut tent = settings(8, 3, 8);
    tent.filter = eyeadapt_scene::PixelFilter::Tent { radius: 1.0 };
    out.push((
        "interior, tent filter",
        lit_hash(&render(&data, &view, &tent)),
    ));
    let mut gaussian = settings(8, 3, 8);
    gaussian.filter = eyeadapt_scene::PixelFilter::GAUSSIAN;
    out.push((
        "interior, Gaussian filter",
        lit_hash(&render(&data, &view, &gaussian)),
    ));
    let (data, view) = xml_view("scenes/mitsuba-glass/glass-on-table.xml", 20, 14);
    out.push((
        "glass-on-table.xml",
        lit_hash(&render(&data, &view, &settings(8, 3, 8))),
    ));
    let (data, view) = many_points();
    out.push((
        "20 point lights",
        lit_hash(&render(&data, &view, &settings(8, 3, 8))),
    ));
    let (data, view) = rooms_and_tree();
    out.push((
        "three-rooms, 21 lights",
        lit_hash(&render(&data, &view, &settings(8, 3, 8))),
    ));
    let (data, view) = builtin_view("three-rooms", 24, 14);
    let eye = EyeSettings {
        samples: 1024,
        min_samples: 1024,
        ..Default::default()
    };
    let path = PathSettings {
        max_depth: 8,
        rr_depth: 5,
    };
    let e = eye_sensor(&data, &view, &eye, 0, path);
    let mut h = 0xcbf2_9ce4_8422_2325u64;
    for v in e.mean_rgb.to_array() {
        h = (h ^ v.to_bits()).wrapping_mul(0x100_0000_01b3);
    }
    out.push(("eye sensor, three-rooms", h));
    out
}

#[test]
fn the_render_revision_pins_the_bits_of_every_path_through_the_renderer() {
    let expected: [(&str, u64); 9] = [
        ("interior", 0x917d69732306052a),
        ("three-rooms", 0x259527040737672a),
        ("cornell-box", 0x64c7d8a1b301ca60),
        ("interior, tent filter", 0x762d8de47da5690),
        ("interior, Gaussian filter", 0x2bb80125f582b71c),
        ("glass-on-table.xml", 0x495f8b1e7a24e117),
        ("20 point lights", 0x452bf1637d731048),
        ("three-rooms, 21 lights", 0x7863889956a8724c),
        ("eye sensor, three-rooms", 0xea926154bb242fb7),
    ];
    let got = hashes();
    let retake: String = got
        .iter()
        .map(|(n, h)| format!("        (\"{n}\", {h:#x}),\n"))
        .collect();
    let same = got.len() == expected.len()
        && got
            .iter()
            .zip(&expected)
            .all(|(g, e)| g.0 == e.0 && g.1 == e.1);
    assert!(
        same && RENDER_REVISION == PINNED_REVISION,
        "the renderer's bits (revision {RENDER_REVISION}, pins of revision {PINNED_REVISION}) are:\n{retake}\
         If the change is meant, raise RENDER_REVISION in crates/tracer/src/revision.rs, set \
         PINNED_REVISION to it and paste these pins"
    );
}
