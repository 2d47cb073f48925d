//! Helpers shared by the tracer's integration tests.
use eyeadapt_tracer::{PathSettings, RenderSettings};

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
