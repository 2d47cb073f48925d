//! Path guiding (`guiding/`): off, a render keeps the bits it had before guiding existed.
use eyeadapt_tracer::{Frame, Guiding, SceneData, View, render};

mod common;

/// FNV-1a over every buffer's bits.
fn frame_hash(f: &Frame) -> u64 {
    let mut h = 0xcbf2_9ce4_8422_2325u64;
    let mut eat = |x: u32| {
        for b in x.to_le_bytes() {
            h = (h ^ b as u64).wrapping_mul(0x100_0000_01b3);
        }
    };
    for buf in [&f.rgb, &f.albedo, &f.achromatic, &f.irradiance, &f.normal] {
        buf.iter().flatten().for_each(|v| eat(v.to_bits()));
    }
    for buf in [&f.depth, &f.emitter, &f.hit] {
        buf.iter().for_each(|v| eat(v.to_bits()));
    }
    h
}

/// A small view of a built-in scene from its own camera.
fn builtin_view(name: &str, w: u32, h: u32) -> (SceneData, View) {
    let scene = eyeadapt_scene::load_builtin(name).unwrap();
    let mut view = View::from_camera(scene.camera.as_ref().unwrap());
    view.width = w;
    view.height = h;
    (SceneData::new(&scene), view)
}

#[test]
fn guiding_off_keeps_the_bits_of_the_renderer_before_guiding() {
    // The hashes were taken at c0287d6, before `guiding/` existed, and held to 3d94600; the
    // watertight triangle test after it (tri4.rs) moves every hit by rounding, so they were
    // re-taken then (before: interior 0x2eeccc3f0ccd8f02, three rooms 0x9629a96366653ff, tent
    // 0x7f437538961887f3).
    for (name, expected) in [
        ("interior", 0xb3a00db144de68f2),
        ("three-rooms", 0x366713b6e48fa7b9),
    ] {
        let (data, view) = builtin_view(name, 24, 14);
        let f = render(&data, &view, &common::settings(8, 3, 8));
        assert_eq!(frame_hash(&f), expected, "{name}");
    }
    // A splatting filter takes the other accumulation path.
    let (data, view) = builtin_view("interior", 24, 14);
    let mut s = common::settings(8, 3, 8);
    s.filter = eyeadapt_scene::PixelFilter::Tent { radius: 1.0 };
    let f = render(&data, &view, &s);
    assert_eq!(frame_hash(&f), 0x7227de9143a57fd4, "tent");
}

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
