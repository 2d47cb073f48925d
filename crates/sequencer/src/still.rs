//! `eyeadapt render`: one still frame of a scene with its outputs.
use crate::adapt::{AdaptationSettings, CSV_HEADER, EstimatorConfig};
use crate::error::Failure;
use crate::estimator::Estimator;
use crate::manifest::CSV;
use crate::output::atomic_write_bytes;
use crate::pipeline::{
    FileKind, FrameResult, Layout, Outputs, Pipeline, Sampling, WriteSpec, write_images,
};
use eyeadapt_scene::Scene;
use eyeadapt_tracer::{RenderSettings, SceneData, View};
use std::path::{Path, PathBuf};
use std::time::Instant;

/// Command-line overrides of what the scene file suggests.
#[derive(Clone, Debug, Default)]
pub struct StillOptions {
    pub sampling: Sampling,
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
    if let Some(w) = o.sampling.width {
        view.width = w;
    }
    if let Some(h) = o.sampling.height {
        view.height = h;
    }
    Ok((view, o.sampling.render_settings(scene)))
}

pub struct StillResult {
    /// Frame 0 of the pipeline, with the readings of the estimators asked for.
    pub frame: FrameResult,
    pub settings: RenderSettings,
    pub data: SceneData,
    pub bvh_seconds: f64,
    pub exr: PathBuf,
    pub preview: PathBuf,
}

/// Renders the still through the frame pipeline and writes `raw.exr`, `preview.png` and,
/// when `estimators` is not empty, `adapted_<estimator>.png` and `adaptation.csv` into
/// `o.out`.
pub fn render_still(
    scene: &Scene,
    o: &StillOptions,
    estimators: &[Estimator],
    config: &EstimatorConfig,
    adaptation: &AdaptationSettings,
) -> Result<StillResult, Failure> {
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
    let pipeline = Pipeline {
        data: &data,
        settings,
        estimators,
        config,
        adaptation,
    };
    let frame = pipeline.run(0, 0.0, view);
    let spec = WriteSpec {
        layout: Layout::Still,
        outputs: Outputs {
            raw_exr: true,
            raw_png: true,
            adapted_png: !estimators.is_empty(),
            adapted_exr: false,
        },
        exposure: o.exposure,
        adaptation,
    };
    write_images(&o.out, &frame, &spec, |_| {})?;
    if !estimators.is_empty() {
        let csv = format!("{CSV_HEADER}\n{}", frame.rows());
        atomic_write_bytes(&o.out.join(CSV), csv.as_bytes())?;
    }
    Ok(StillResult {
        frame,
        settings,
        data,
        bvh_seconds,
        exr: o.out.join(Layout::Still.path(FileKind::RawExr, 0)),
        preview: o.out.join(Layout::Still.path(FileKind::RawPng, 0)),
    })
}

/// `{"seconds":…, "samples":…, "samples_per_second":…, "bvh_seconds":…}`
pub fn stats_json(r: &StillResult) -> String {
    let s = &r.frame.image.stats;
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
    // A symbolic link that points nowhere (the path or an ancestor): create_dir_all would
    // fail with "file exists"; say what it is.
    if let Some(link) = dir
        .ancestors()
        .find(|a| a.is_symlink() && std::fs::metadata(a).is_err())
    {
        let target = std::fs::read_link(link).unwrap_or_default();
        return Err(Failure::Input(format!(
            "output path {}: {} is a symbolic link to {}, which does not exist",
            dir.display(),
            link.display(),
            target.display()
        )));
    }
    if dir.exists() && !dir.is_dir() {
        return Err(Failure::Input(format!(
            "output path {} exists and is not a directory",
            dir.display()
        )));
    }
    std::fs::create_dir_all(dir).map_err(|e| Failure::io("cannot create output directory", dir, &e))
}
