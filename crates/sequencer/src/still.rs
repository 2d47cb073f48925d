//! `eyeadapt render`: one still frame of a scene with its outputs.
use crate::error::Failure;
use crate::output::{write_exr, write_png};
use eyeadapt_scene::Scene;
use eyeadapt_tracer::{Frame, PathSettings, RenderSettings, SceneData, View, render};
use std::path::{Path, PathBuf};
use std::time::Instant;

/// Command-line overrides of what the scene file suggests.
#[derive(Clone, Debug, Default)]
pub struct StillOptions {
    pub spp: Option<u32>,
    pub width: Option<u32>,
    pub height: Option<u32>,
    pub max_depth: Option<i32>,
    pub rr_depth: Option<u32>,
    pub seed: Option<u64>,
    pub exposure: f32,
    pub out: PathBuf,
}

/// Resolved settings plus the view.
pub fn resolve(scene: &Scene, o: &StillOptions) -> Result<(View, RenderSettings), Failure> {
    let camera = scene.camera.as_ref().ok_or_else(|| {
        Failure::Input(format!(
            "{}: the scene has no [camera]",
            scene.source.display()
        ))
    })?;
    let mut view = View::from_camera(camera);
    if let Some(w) = o.width {
        view.width = w;
    }
    if let Some(h) = o.height {
        view.height = h;
    }
    let settings = RenderSettings {
        spp: o.spp.or(scene.render.spp).unwrap_or(64),
        path: PathSettings {
            max_depth: o.max_depth.or(scene.render.max_depth).unwrap_or(8),
            rr_depth: o.rr_depth.or(scene.render.rr_depth).unwrap_or(5),
        },
        seed: o.seed.or(scene.render.seed).unwrap_or(0),
        frame: 0,
        filter: scene.render.filter.unwrap_or_default(),
    };
    Ok((view, settings))
}

pub struct StillResult {
    pub frame: Frame,
    pub view: View,
    pub settings: RenderSettings,
    pub data: SceneData,
    pub bvh_seconds: f64,
    pub exr: PathBuf,
    pub preview: PathBuf,
}

/// Renders the still and writes `raw.exr` and `preview.png` into `o.out`.
pub fn render_still(scene: &Scene, o: &StillOptions) -> Result<StillResult, Failure> {
    let (view, settings) = resolve(scene, o)?;
    crate::resources::check_render(
        &format!("rendering {}", scene.source.display()),
        view.width,
        view.height,
        scene.triangle_count(),
    )?;
    let t = Instant::now();
    let data = SceneData::new(scene);
    let bvh_seconds = t.elapsed().as_secs_f64();
    let frame = render(&data, &view, &settings);
    let exr = o.out.join("raw.exr");
    let preview = o.out.join("preview.png");
    write_exr(&exr, &frame)?;
    write_png(&preview, &frame.rgb, frame.width, frame.height, o.exposure)?;
    Ok(StillResult {
        frame,
        view,
        settings,
        data,
        bvh_seconds,
        exr,
        preview,
    })
}

/// `{"seconds":…, "samples":…, "samples_per_second":…, "bvh_seconds":…}`
pub fn stats_json(r: &StillResult) -> String {
    let s = &r.frame.stats;
    format!(
        "{{\"seconds\": {}, \"samples\": {}, \"samples_per_second\": {}, \"bvh_seconds\": {}, \"invalid_samples\": {}, \"triangles\": {}}}\n",
        s.seconds,
        s.samples,
        s.samples as f64 / s.seconds.max(1e-9),
        r.bvh_seconds,
        s.invalid_samples,
        r.data.geometry.triangle_count()
    )
}

/// Validates an output directory up front: it must be a directory or creatable.
pub fn prepare_out_dir(dir: &Path) -> Result<(), Failure> {
    // The path itself, or (for a directory still to be created) one of its ancestors, may be
    // an existing file: bad usage, named, rather than an I/O failure.
    if let Some(file) = dir.ancestors().find(|a| a.is_file()) {
        return Err(Failure::Input(if file == dir {
            format!(
                "output path {} exists and is not a directory",
                dir.display()
            )
        } else {
            format!(
                "output path {}: {} exists and is not a directory",
                dir.display(),
                file.display()
            )
        }));
    }
    if dir.exists() && !dir.is_dir() {
        return Err(Failure::Input(format!(
            "output path {} exists and is not a directory",
            dir.display()
        )));
    }
    std::fs::create_dir_all(dir).map_err(|e| Failure::io("cannot create output directory", dir, &e))
}

/// Runs the estimators on a rendered still, writes `adapted_<estimator>.png` and
/// `adaptation.csv` into `out`, and returns the readings.
pub fn adapt_still(
    r: &StillResult,
    list: &[&'static str],
    cfg: &crate::adapt::EstimatorConfig,
    adaptation: &crate::adapt::AdaptationSettings,
    out: &Path,
    exposure: f32,
) -> Result<Vec<crate::adapt::Reading>, Failure> {
    use crate::adapt::{CSV_HEADER, apply, cat_matrix, csv_row, estimate_all, white_for_cat};
    let readings = estimate_all(
        list,
        cfg,
        &r.data,
        &r.view,
        &r.frame,
        0,
        r.settings.seed,
        r.settings.path,
    );
    let mut csv = String::from(CSV_HEADER);
    csv.push('\n');
    for reading in &readings {
        let (white, held) = white_for_cat(&reading.estimate, eyeadapt_color::D65_XYZ);
        let adapted = apply(cat_matrix(white, adaptation), &r.frame.rgb);
        write_png(
            &out.join(format!("adapted_{}.png", reading.estimator)),
            &adapted,
            r.frame.width,
            r.frame.height,
            exposure,
        )?;
        let mut extra = Vec::new();
        if held {
            extra.push("held_d65");
        }
        if r.frame.stats.invalid_samples > 0 {
            extra.push("image_nan_dropped");
        }
        csv.push_str(&csv_row(0, 0.0, reading, &extra, r.view.position));
    }
    crate::output::atomic_write_bytes(&out.join("adaptation.csv"), csv.as_bytes())?;
    Ok(readings)
}
