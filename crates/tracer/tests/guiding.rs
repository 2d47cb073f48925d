//! Path guiding (`guiding/`): off, a render keeps the bits it had before guiding existed.
use eyeadapt_tracer::{Frame, SceneData, View, render};

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
    // The hashes were taken at c0287d6, before `guiding/` existed.
    for (name, expected) in [
        ("interior", 0x2eeccc3f0ccd8f02),
        ("three-rooms", 0x9629a96366653ff),
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
    assert_eq!(frame_hash(&f), 0x7f437538961887f3, "tent");
}
