//! `eyeadapt render SCENE`.
use crate::args::RenderArgs;
use eyeadapt_sequencer::Failure;
use eyeadapt_sequencer::still::{StillOptions, prepare_out_dir, render_still, stats_json};

pub fn run(a: RenderArgs) -> Result<(), Failure> {
    // Every option is checked before anything is rendered or written.
    let (estimators, cfg, adaptation) = match &a.adapt.estimators {
        Some(list) => crate::adapt_cli::resolve(list, &a.adapt)?,
        None => Default::default(),
    };
    let scene = if a.define.is_empty() {
        eyeadapt_scene::resolve_scene(&a.scene)?
    } else {
        let path = std::path::Path::new(&a.scene);
        if !eyeadapt_scene::is_mitsuba_path(path) {
            return Err(Failure::Input(format!(
                "-D gives parameters of Mitsuba XML scenes; {} is not one",
                a.scene
            )));
        }
        let pairs: Vec<(&str, &str)> = a
            .define
            .iter()
            .map(|(n, v)| (n.as_str(), v.as_str()))
            .collect();
        eyeadapt_scene::load_mitsuba(path, &pairs)?
    };
    for w in &scene.warnings {
        eprintln!("{w}");
    }
    prepare_out_dir(&a.out)?;
    let opts = StillOptions {
        sampling: a.sampling.sampling(),
        exposure: a.exposure,
        out: a.out.clone(),
    };
    let r = render_still(&scene, &opts, &estimators, &cfg, &adaptation)?;
    let st = &r.frame.image.stats;
    println!(
        "rendered {}x{} at {} spp (max_depth {}) in {:.3} s: {:.3} M samples/s; BVH {} triangles in {:.3} s",
        r.frame.view.width,
        r.frame.view.height,
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
    if !estimators.is_empty() {
        crate::adapt_cli::print_table(&r.frame.readings, &adaptation);
        println!("Saved: '{}'", a.out.join("adaptation.csv").display());
    }
    if let Some(p) = &a.stats_json {
        eyeadapt_sequencer::output::atomic_write_bytes(p, stats_json(&r).as_bytes())?;
    }
    Ok(())
}
