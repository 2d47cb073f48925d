//! `eyeadapt bench`: samples/s on a scene (the Cornell box by default), median of N runs.
use crate::args::BenchArgs;
use eyeadapt_sequencer::Failure;
use eyeadapt_tracer::{PathSettings, RenderSettings, SceneData, View, render};
use std::time::Instant;

pub fn run(a: BenchArgs) -> Result<(), Failure> {
    let scene = eyeadapt_scene::resolve_scene(&a.scene)?;
    let camera = scene
        .camera
        .as_ref()
        .ok_or_else(|| Failure::Input("the bench scene has no camera".into()))?;
    // The same memory check as a render, before the BVH is built.
    eyeadapt_sequencer::resources::check_render(
        &format!("the bench of {}", a.scene),
        a.size,
        a.size,
        scene.triangle_count(),
    )?;
    let t = Instant::now();
    let data = SceneData::new(&scene);
    let bvh = t.elapsed().as_secs_f64();
    let mut view = View::from_camera(camera);
    view.width = a.size;
    view.height = a.size;
    let mut times = Vec::new();
    let mut samples = 0;
    for run in 0..a.runs {
        let s = RenderSettings {
            spp: a.spp,
            path: PathSettings {
                max_depth: a.max_depth,
                rr_depth: 5,
            },
            seed: run as u64,
            frame: 0,
            filter: eyeadapt_scene::PixelFilter::Box,
            wcam_specular: Default::default(),
            guiding: Default::default(),
        };
        let f = render(&data, &view, &s);
        samples = f.stats.samples;
        times.push(f.stats.seconds);
        println!(
            "run {}: {:.3} s, {:.3} M samples/s",
            run + 1,
            f.stats.seconds,
            f.stats.samples as f64 / f.stats.seconds / 1e6
        );
    }
    times.sort_by(f64::total_cmp);
    let median = times[times.len() / 2];
    println!(
        "{}: {}x{} at {} spp, max_depth {}, {} threads: median {:.3} s = {:.3} M samples/s (BVH build {:.4} s, {} triangles)",
        a.scene,
        a.size,
        a.size,
        a.spp,
        a.max_depth,
        rayon::current_num_threads(),
        median,
        samples as f64 / median / 1e6,
        bvh,
        data.geometry.triangle_count()
    );
    Ok(())
}
