//! Path guiding (`guiding/`): unbiased, deterministic, and off by default (the bits of a
//! render without guiding are pinned in `render_revision.rs`; until the watertight triangle
//! test of render revision 4 they were still the bits of the renderer before `guiding/`
//! existed).
use common::frame_hash;
use eyeadapt_tracer::{Frame, Guiding, SceneData, View, render};

mod common;

/// Two rooms joined by a doorway; the only light, a small lamp under the far room's ceiling,
/// reaches the near room, where the camera stands, only through the doorway: light that
/// arrives after bounces, the case guiding is for.
fn two_rooms(w: u32, h: u32) -> (SceneData, View) {
    let text = r#"
[camera]
position = [0.0, 1.5, -0.3]
look_at = [0.6, 1.0, -4.0]
fov_deg = 60.0
width = 16
height = 9

[[materials]]
name = "wall"
type = "diffuse"
reflectance = [0.7, 0.7, 0.7]

[[materials]]
name = "red"
type = "diffuse"
reflectance = [0.7, 0.2, 0.1]

[[materials]]
name = "light"
type = "diffuse"
reflectance = [0.0, 0.0, 0.0]
emission = [60.0, 55.0, 50.0]

[[shapes]]
type = "quad"
material = "wall"
corner = [-2.0, 0.0, -8.0]
u = [0.0, 0.0, 8.0]
v = [4.0, 0.0, 0.0]

[[shapes]]
type = "quad"
material = "wall"
corner = [-2.0, 3.0, -8.0]
u = [4.0, 0.0, 0.0]
v = [0.0, 0.0, 8.0]

[[shapes]]
type = "quad"
material = "red"
corner = [-2.0, 0.0, -8.0]
u = [0.0, 3.0, 0.0]
v = [0.0, 0.0, 8.0]

[[shapes]]
type = "quad"
material = "wall"
corner = [2.0, 0.0, -8.0]
u = [0.0, 0.0, 8.0]
v = [0.0, 3.0, 0.0]

[[shapes]]
type = "quad"
material = "wall"
corner = [-2.0, 0.0, 0.0]
u = [0.0, 3.0, 0.0]
v = [4.0, 0.0, 0.0]

[[shapes]]
type = "quad"
material = "wall"
corner = [-2.0, 0.0, -8.0]
u = [4.0, 0.0, 0.0]
v = [0.0, 3.0, 0.0]

[[shapes]]
type = "box"
material = "wall"
min = [-2.0, 0.0, -4.05]
max = [0.5, 3.0, -3.95]

[[shapes]]
type = "box"
material = "wall"
min = [1.5, 0.0, -4.05]
max = [2.0, 3.0, -3.95]

[[shapes]]
type = "box"
material = "wall"
min = [0.5, 2.0, -4.05]
max = [1.5, 3.0, -3.95]

[[shapes]]
type = "quad"
material = "light"
corner = [-1.0, 2.95, -7.0]
u = [0.5, 0.0, 0.0]
v = [0.0, 0.0, 0.5]
"#;
    let scene =
        eyeadapt_scene::load_scene_str(text, std::path::Path::new("two_rooms.toml")).unwrap();
    let mut view = View::from_camera(scene.camera.as_ref().unwrap());
    view.width = w;
    view.height = h;
    (SceneData::new(&scene), view)
}

fn guided(spp: u32, seed: u64) -> eyeadapt_tracer::RenderSettings {
    let mut s = common::settings(spp, seed, 8);
    s.guiding = Guiding::On;
    s
}

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

#[test]
fn guided_and_unguided_renders_agree_on_light_that_arrives_through_a_doorway() {
    let (data, view) = two_rooms(12, 8);
    // Independent renders (different seeds): each image mean is one estimate.
    let renders = |guiding: Guiding| -> Vec<Frame> {
        (0..12)
            .map(|seed| {
                let mut s = common::settings(64, 100 + seed, 8);
                s.guiding = guiding;
                render(&data, &view, &s)
            })
            .collect()
    };
    let (m_off, e_off) = mean_and_error(&renders(Guiding::Off));
    let (m_on, e_on) = mean_and_error(&renders(Guiding::On));
    let z = (m_on - m_off).abs() / (e_off * e_off + e_on * e_on).sqrt();
    assert!(
        z < 4.0,
        "guided {m_on} ± {e_on}, unguided {m_off} ± {e_off}: z = {z}"
    );
    assert!(m_off > 0.01, "the near room is lit: {m_off}");
}

#[test]
fn a_guided_frame_has_the_same_bits_on_any_thread_count_and_twice() {
    let (data, view) = two_rooms(20, 12);
    let in_pool = |threads: usize| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap()
            .install(|| render(&data, &view, &guided(16, 5)))
    };
    let one = in_pool(1);
    let three = in_pool(3);
    assert_eq!(frame_hash(&one), frame_hash(&three));
    assert_eq!(frame_hash(&three), frame_hash(&in_pool(3)));
    // Guiding changes the samples: the frame differs from the unguided one.
    let off = render(&data, &view, &common::settings(16, 5, 8));
    assert_ne!(frame_hash(&one), frame_hash(&off));
}

#[test]
fn a_guided_frame_does_not_depend_on_the_frames_rendered_before_it() {
    // A farm chunk renders frame 7 after frames 0-6, or alone: the guide is learned anew.
    let (data, view) = two_rooms(12, 8);
    let frame = |f: u32| {
        let mut s = guided(8, 2);
        s.frame = f;
        render(&data, &view, &s)
    };
    let alone = frame(7);
    for f in 0..3 {
        frame(f);
    }
    assert_eq!(frame_hash(&alone), frame_hash(&frame(7)));
}
