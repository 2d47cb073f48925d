//! Light portals change how the environment is sampled, never what the image converges to:
//! renders with and without them agree within their statistical error, also when a portal
//! covers only part of the opening (the rest of the sky arrives by BSDF sampling alone), and
//! a frame with portals has the same bits on any thread count.
mod common;

use common::frame_hash;
use eyeadapt_tracer::{Frame, SceneData, View, render};

/// A closed 4 m room lit by a sky (brighter towards +y) and a sun through one window in its
/// wall x = −2, with `portals` appended.
fn room(portals: &str) -> (SceneData, View) {
    let text = format!(
        r#"
[camera]
position = [1.5, 1.4, 1.5]
look_at = [-1.0, 0.8, -1.0]
fov_deg = 70.0
width = 12
height = 8

[[materials]]
name = "white"
type = "diffuse"
reflectance = [0.7, 0.7, 0.7]

[[shapes]]
type = "box"
material = "white"
min = [-2.0, 0.0, -2.0]
max = [2.0, 3.0, 2.0]

[[lights]]
type = "sun"
direction = [0.6, -0.6, 0.2]
irradiance = [2.0, 1.8, 1.6]

[environment]
radiance = [1.0, 1.2, 1.5]
{portals}"#
    );
    let mut scene =
        eyeadapt_scene::load_scene_str(&text, std::path::Path::new("room.toml")).unwrap();
    // Cut the window out of the box's wall x = −2: y in [0.8, 2.2], z in [−1, 0.6].
    window(&mut scene);
    let mut view = View::from_camera(scene.camera.as_ref().unwrap());
    view.width = 12;
    view.height = 8;
    (SceneData::new(&scene), view)
}

/// Drops the box's wall x = −2 and rebuilds it with an opening, as four quads.
fn window(scene: &mut eyeadapt_scene::Scene) {
    use eyeadapt_scene::quad_mesh;
    use glam::Vec3;
    let m = scene.instances[0].material;
    let mesh = &mut scene.meshes[0];
    let keep: Vec<[u32; 3]> = mesh
        .indices
        .iter()
        .copied()
        .filter(|t| !t.iter().all(|&i| mesh.positions[i as usize].x < -1.999))
        .collect();
    assert_eq!(
        keep.len(),
        mesh.indices.len() - 2,
        "the wall is two triangles"
    );
    mesh.indices = keep;
    let x = -2.0;
    for (corner, u, v) in [
        (
            Vec3::new(x, 0.0, -2.0),
            Vec3::new(0.0, 0.8, 0.0),
            Vec3::new(0.0, 0.0, 4.0),
        ),
        (
            Vec3::new(x, 2.2, -2.0),
            Vec3::new(0.0, 0.8, 0.0),
            Vec3::new(0.0, 0.0, 4.0),
        ),
        (
            Vec3::new(x, 0.8, -2.0),
            Vec3::new(0.0, 1.4, 0.0),
            Vec3::new(0.0, 0.0, 1.0),
        ),
        (
            Vec3::new(x, 0.8, 0.6),
            Vec3::new(0.0, 1.4, 0.0),
            Vec3::new(0.0, 0.0, 1.4),
        ),
    ] {
        scene.add_world_mesh(quad_mesh(corner, u, v), m);
    }
}

const WHOLE_WINDOW: &str =
    "[[portals]]\ncorner = [-2.0, 0.8, -1.0]\nu = [0.0, 1.4, 0.0]\nv = [0.0, 0.0, 1.6]\n";
const HALF_WINDOW: &str =
    "[[portals]]\ncorner = [-2.0, 0.8, -1.0]\nu = [0.0, 1.4, 0.0]\nv = [0.0, 0.0, 0.8]\n";

/// The mean over the image of each render, and its standard error over the renders.
fn mean_and_error(images: &[Frame]) -> (f64, f64) {
    let means: Vec<f64> = images
        .iter()
        .map(|f| f.rgb.iter().flatten().map(|&v| v as f64).sum::<f64>() / (3 * f.rgb.len()) as f64)
        .collect();
    let n = means.len() as f64;
    let m = means.iter().sum::<f64>() / n;
    let var = means.iter().map(|x| (x - m).powi(2)).sum::<f64>() / (n - 1.0);
    (m, (var / n).sqrt())
}

fn renders(portals: &str) -> (f64, f64) {
    let (data, view) = room(portals);
    let images: Vec<Frame> = (0..12)
        .map(|seed| render(&data, &view, &common::settings(32, 200 + seed, 6)))
        .collect();
    mean_and_error(&images)
}

#[test]
fn renders_with_and_without_portals_agree() {
    let (m0, e0) = renders("");
    assert!(m0 > 0.02, "the room is lit: {m0}");
    for (name, portals) in [
        ("whole window", WHOLE_WINDOW),
        ("half the window", HALF_WINDOW),
    ] {
        let (m, e) = renders(portals);
        let z = (m - m0).abs() / (e * e + e0 * e0).sqrt();
        assert!(
            z < 4.0,
            "{name}: {m} ± {e}, without portals {m0} ± {e0}: z = {z}"
        );
    }
}

#[test]
fn a_portal_over_the_window_lowers_the_noise() {
    // Per-pixel variance over seeds, summed: the sky found through the window, not the walls.
    let noise = |portals: &str| -> f64 {
        let (data, view) = room(portals);
        let images: Vec<Frame> = (0..6)
            .map(|seed| render(&data, &view, &common::settings(16, 300 + seed, 6)))
            .collect();
        let n = images.len() as f64;
        (0..images[0].rgb.len())
            .map(|i| {
                let v: Vec<f64> = images.iter().map(|f| f.rgb[i][1] as f64).collect();
                let m = v.iter().sum::<f64>() / n;
                v.iter().map(|x| (x - m).powi(2)).sum::<f64>() / (n - 1.0)
            })
            .sum()
    };
    let (without, with) = (noise(""), noise(WHOLE_WINDOW));
    assert!(
        with < 0.7 * without,
        "variance {with} with the portal, {without} without"
    );
}

#[test]
fn a_frame_with_portals_has_the_same_bits_on_any_thread_count() {
    let (data, view) = room(WHOLE_WINDOW);
    let in_pool = |threads: usize| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap()
            .install(|| render(&data, &view, &common::settings(8, 5, 6)))
    };
    let one = in_pool(1);
    assert_eq!(frame_hash(&one), frame_hash(&in_pool(3)));
    // The portal changes the samples: the frame differs from the one without.
    let (plain, _) = room("");
    assert_ne!(
        frame_hash(&one),
        frame_hash(&render(&plain, &view, &common::settings(8, 5, 6)))
    );
}
