//! `eyeadapt render SCENE`.
use crate::args::RenderArgs;
use eyeadapt_sequencer::Failure;
use eyeadapt_sequencer::still::{StillOptions, prepare_out_dir, render_still, stats_json};

pub fn run(a: RenderArgs) -> Result<(), Failure> {
    let scene = eyeadapt_scene::resolve_scene(&a.scene)?;
    for w in &scene.warnings {
        eprintln!("{w}");
    }
    prepare_out_dir(&a.out)?;
    let s = &a.sampling;
    let opts = StillOptions {
        spp: s.spp,
        width: s.width,
        height: s.height,
        max_depth: s.max_depth,
        rr_depth: s.rr_depth,
        seed: s.seed,
        exposure: a.exposure,
        out: a.out.clone(),
    };
    let r = render_still(&scene, &opts)?;
    let st = &r.frame.stats;
    println!(
        "rendered {}x{} at {} spp (max_depth {}) in {:.3} s: {:.3} M samples/s; BVH {} triangles in {:.3} s",
        r.view.width,
        r.view.height,
        r.settings.spp,
        r.settings.path.max_depth,
        st.seconds,
        st.samples as f64 / st.seconds.max(1e-9) / 1e6,
        r.data.geometry.triangle_count(),
        r.bvh_seconds
    );
    if st.invalid_samples > 0 {
        eprintln!(
            "warning: {} samples were NaN or infinite and were dropped",
            st.invalid_samples
        );
    }
    println!("Saved: '{}'", r.exr.display());
    println!("Saved: '{}'", r.preview.display());
    if let Some(list) = &a.adapt.estimators {
        let (list, cfg, adaptation) = crate::adapt_cli::resolve(list, &a.adapt)?;
        let readings = eyeadapt_sequencer::still::adapt_still(
            &r,
            &list,
            &cfg,
            &adaptation,
            &a.out,
            a.exposure,
        )?;
        crate::adapt_cli::print_table(&readings, &adaptation);
        println!("Saved: '{}'", a.out.join("adaptation.csv").display());
    }
    if let Some(p) = &a.stats_json {
        eyeadapt_sequencer::output::atomic_write_bytes(p, stats_json(&r).as_bytes())?;
    }
    Ok(())
}
