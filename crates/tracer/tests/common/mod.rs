//! Helpers shared by the tracer's integration tests.
#![allow(dead_code)] // each test crate uses some of these

use eyeadapt_tracer::{Frame, PathSettings, RenderSettings, SceneData, View};

/// Box-filtered settings of frame 0 with Russian roulette from 5 segments.
pub fn settings(spp: u32, seed: u64, max_depth: i32) -> RenderSettings {
    RenderSettings {
        spp,
        path: PathSettings {
            max_depth,
            rr_depth: 5,
        },
        seed,
        frame: 0,
        filter: eyeadapt_scene::PixelFilter::Box,
        wcam_specular: Default::default(),
        guiding: Default::default(),
    }
}

/// FNV-1a over every buffer's bits.
pub fn frame_hash(f: &Frame) -> u64 {
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
pub fn builtin_view(name: &str, w: u32, h: u32) -> (SceneData, View) {
    let scene = eyeadapt_scene::load_builtin(name).unwrap();
    let mut view = View::from_camera(scene.camera.as_ref().unwrap());
    view.width = w;
    view.height = h;
    (SceneData::new(&scene), view)
}
