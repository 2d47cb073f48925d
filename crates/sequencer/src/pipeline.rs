//! The one per-frame pipeline of `render`, `sequence` and `paper`: render → estimate → adapt →
//! write. The commands differ only in where the files go ([`Layout`](crate::pipeline::Layout)) and in what they do
//! around a frame (resume and the manifest for `sequence`, measurements for `paper`), so the
//! same frame gives the same pixels and the same CSV rows whichever command rendered it.
use crate::adapt::{
    AdaptationSettings, EstimatorConfig, Reading, apply, cat_matrix, csv_row, estimate_all,
    white_for_cat,
};
use crate::error::Failure;
use crate::estimator::Estimator;
use crate::output::{write_exr, write_png};
use eyeadapt_color::Estimate;
use eyeadapt_scene::Scene;
use eyeadapt_tracer::{
    Frame, Guiding, PathSettings, RenderSettings, SceneData, View, render_with_progress,
};
use rayon::prelude::*;
use serde::Deserialize;
use std::path::Path;

/// Samples per pixel when neither the command line, the job nor the scene says.
pub const DEFAULT_SPP: u32 = 64;

/// Sampling settings given on the command line or in a job file; unset fields fall back to
/// the next source ([`Sampling::or`]), then to the scene's `[render]`, then to the defaults
/// (64 spp, max_depth 8, rr_depth 5, seed 0).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Sampling {
    pub width: Option<u32>,
    pub height: Option<u32>,
    pub spp: Option<u32>,
    pub max_depth: Option<i32>,
    pub rr_depth: Option<u32>,
    pub seed: Option<u64>,
    /// Path guiding (off unless set).
    pub guiding: Option<Guiding>,
}

impl Sampling {
    /// Each field from `self`, else from `fallback`.
    pub fn or(self, fallback: Sampling) -> Sampling {
        Sampling {
            width: self.width.or(fallback.width),
            height: self.height.or(fallback.height),
            spp: self.spp.or(fallback.spp),
            max_depth: self.max_depth.or(fallback.max_depth),
            rr_depth: self.rr_depth.or(fallback.rr_depth),
            seed: self.seed.or(fallback.seed),
            guiding: self.guiding.or(fallback.guiding),
        }
    }

    /// The renderer's settings for frame 0, after the scene's suggestions and the defaults.
    pub fn render_settings(&self, scene: &Scene) -> RenderSettings {
        RenderSettings {
            spp: self.spp.or(scene.render.spp).unwrap_or(DEFAULT_SPP),
            path: PathSettings {
                max_depth: self.max_depth.or(scene.render.max_depth).unwrap_or(8),
                rr_depth: self.rr_depth.or(scene.render.rr_depth).unwrap_or(5),
            },
            seed: self.seed.or(scene.render.seed).unwrap_or(0),
            frame: 0,
            filter: scene.render.filter.unwrap_or_default(),
            wcam_specular: Default::default(),
            guiding: self.guiding.unwrap_or_default(),
        }
    }
}

/// Which files each frame writes (the job file's `[outputs]` table).
#[derive(Clone, Copy, Debug, Deserialize, PartialEq, Eq, Hash)]
#[serde(deny_unknown_fields, default)]
pub struct Outputs {
    pub raw_exr: bool,
    pub raw_png: bool,
    pub adapted_png: bool,
    pub adapted_exr: bool,
}

impl Default for Outputs {
    fn default() -> Self {
        Outputs {
            raw_exr: true,
            raw_png: true,
            adapted_png: true,
            adapted_exr: false,
        }
    }
}

/// The render data of each frame's scene: built once when nothing in the scene moves, built
/// for each frame's time when instances or lights are animated (each frame from its time
/// alone, so chunks and resumed runs get the same bits).
pub struct FrameScenes<'a> {
    scene: &'a Scene,
    still: Option<SceneData>,
}

impl<'a> FrameScenes<'a> {
    pub fn new(scene: &'a Scene) -> FrameScenes<'a> {
        FrameScenes {
            scene,
            still: (!scene.is_animated()).then(|| SceneData::new(scene)),
        }
    }

    /// Runs `f` on the render data of the scene at time `t`.
    pub fn at<R>(&self, t: f64, f: impl FnOnce(&SceneData) -> R) -> R {
        match &self.still {
            Some(data) => f(data),
            None => f(&SceneData::new(&self.scene.at_time(t))),
        }
    }
}

/// What every frame of a run shares.
pub struct Pipeline<'a> {
    pub data: &'a SceneData,
    /// Frame 0's settings; [`Pipeline::run`] sets the frame number.
    pub settings: RenderSettings,
    pub estimators: &'a [Estimator],
    pub config: &'a EstimatorConfig,
    pub adaptation: &'a AdaptationSettings,
}

/// Where a frame's work is, for progress displays.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FrameStep {
    /// One more row of pixels is rendered.
    Row,
    /// The image is done; the estimators (the eye sensor traces rays) run.
    Estimating,
}

/// One frame, rendered and estimated.
pub struct FrameResult {
    pub number: u32,
    pub time: f64,
    pub view: View,
    pub image: Frame,
    pub readings: Vec<Reading>,
}

impl Pipeline<'_> {
    /// Renders frame `number` (its sample keys) seen from `view` and runs every estimator.
    pub fn run(&self, number: u32, time: f64, view: View) -> FrameResult {
        self.run_with_progress(number, time, view, &|_| {})
    }

    /// [`Pipeline::run`], telling `step` (from any thread) about each finished row and when
    /// the estimators start.
    pub fn run_with_progress(
        &self,
        number: u32,
        time: f64,
        view: View,
        step: &(dyn Fn(FrameStep) + Sync),
    ) -> FrameResult {
        let settings = RenderSettings {
            frame: number,
            ..self.settings
        };
        let image = render_with_progress(self.data, &view, &settings, &|| step(FrameStep::Row));
        step(FrameStep::Estimating);
        let readings = estimate_all(
            self.estimators,
            self.config,
            self.data,
            &view,
            &image,
            number,
            settings.seed,
            settings.path,
        );
        FrameResult {
            number,
            time,
            view,
            image,
            readings,
        }
    }
}

impl FrameResult {
    /// The CSV row of any estimate of this frame (also the paper's diagnostic ones), with the
    /// flags the pipeline adds: `held_d65` when the white is undefined and the frame adapts
    /// with D65, `image_nan_dropped` when the render dropped NaN/Inf samples.
    pub fn row(&self, name: &str, estimate: &Estimate) -> String {
        let mut extra: Vec<&str> = Vec::new();
        if white_for_cat(estimate, eyeadapt_color::D65_XYZ).1 {
            extra.push("held_d65");
        }
        if self.image.stats.invalid_samples > 0 {
            extra.push("image_nan_dropped");
        }
        csv_row(
            self.number,
            self.time,
            name,
            estimate,
            &extra,
            self.view.position,
        )
    }

    /// The rows of every reading, in order.
    pub fn rows(&self) -> String {
        self.readings
            .iter()
            .map(|r| self.row(r.estimator.name(), &r.estimate))
            .collect()
    }

    /// The image adapted with a reading's white. Undefined whites adapt with D65 (never the
    /// previous frame's white), so every frame's output depends on that frame alone and
    /// chunked runs match whole runs.
    pub fn adapted(&self, r: &Reading, a: &AdaptationSettings) -> Vec<[f32; 3]> {
        let (white, _) = white_for_cat(&r.estimate, eyeadapt_color::D65_XYZ);
        apply(cat_matrix(white, a), &self.image.rgb)
    }
}

/// `frame_000123.ext`.
pub fn frame_name(f: u32, ext: &str) -> String {
    format!("frame_{f:06}.{ext}")
}

/// One file a frame can write.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FileKind {
    RawExr,
    RawPng,
    AdaptedPng(Estimator),
    AdaptedExr(Estimator),
}

/// Where a command puts a frame's files, relative to its output directory.
#[derive(Clone, Copy, Debug)]
pub enum Layout<'a> {
    /// `render`: `raw.exr`, `preview.png`, `adapted_<estimator>.png`.
    Still,
    /// `sequence`: `frames/raw/frame_N.exr`, `frames/<estimator>/frame_N.png`.
    Sequence,
    /// `paper`: `<job>_frame_N.exr` in the case's work directory.
    Prefixed(&'a str),
}

impl Layout<'_> {
    pub fn path(&self, kind: FileKind, f: u32) -> String {
        match (self, kind) {
            (Layout::Still, FileKind::RawExr) => "raw.exr".into(),
            (Layout::Still, FileKind::RawPng) => "preview.png".into(),
            (Layout::Still, FileKind::AdaptedPng(e)) => format!("adapted_{e}.png"),
            (Layout::Still, FileKind::AdaptedExr(e)) => format!("adapted_{e}.exr"),
            (Layout::Sequence, FileKind::RawExr) => format!("frames/raw/{}", frame_name(f, "exr")),
            (Layout::Sequence, FileKind::RawPng) => format!("frames/raw/{}", frame_name(f, "png")),
            (Layout::Sequence, FileKind::AdaptedPng(e)) => {
                format!("frames/{e}/{}", frame_name(f, "png"))
            }
            (Layout::Sequence, FileKind::AdaptedExr(e)) => {
                format!("frames/{e}/{}", frame_name(f, "exr"))
            }
            (Layout::Prefixed(p), FileKind::RawExr) => format!("{p}_{}", frame_name(f, "exr")),
            (Layout::Prefixed(p), FileKind::RawPng) => format!("{p}_{}", frame_name(f, "png")),
            (Layout::Prefixed(p), FileKind::AdaptedPng(e)) => {
                format!("{p}_{e}_{}", frame_name(f, "png"))
            }
            (Layout::Prefixed(p), FileKind::AdaptedExr(e)) => {
                format!("{p}_{e}_{}", frame_name(f, "exr"))
            }
        }
    }
}

/// How a frame's images are written.
#[derive(Clone, Copy, Debug)]
pub struct WriteSpec<'a> {
    pub layout: Layout<'a>,
    pub outputs: Outputs,
    /// Preview exposure in stops (PNGs only).
    pub exposure: f32,
    pub adaptation: &'a AdaptationSettings,
}

/// Writes a frame's images into `out` (each atomically): the raw EXR and PNG, then each
/// reading's adapted PNG and EXR, as `spec.outputs` asks. The files are encoded in parallel
/// (the raw EXR's compression alone was 2 % of a demo frame's instructions and the nine PNGs
/// 1 %, on one core while the others waited); `saved` is called with each file's path relative
/// to `out` in the order above, and the first failure in that order is the one returned.
pub fn write_images(
    out: &Path,
    r: &FrameResult,
    spec: &WriteSpec,
    mut saved: impl FnMut(String),
) -> Result<(), Failure> {
    let o = spec.outputs;
    let mut files: Vec<(FileKind, Option<&Reading>)> = Vec::new();
    if o.raw_exr {
        files.push((FileKind::RawExr, None));
    }
    if o.raw_png {
        files.push((FileKind::RawPng, None));
    }
    for reading in &r.readings {
        if o.adapted_png {
            files.push((FileKind::AdaptedPng(reading.estimator), Some(reading)));
        }
        if o.adapted_exr {
            files.push((FileKind::AdaptedExr(reading.estimator), Some(reading)));
        }
    }
    let written: Vec<Result<String, Failure>> = files
        .par_iter()
        .map(|&(kind, reading)| write_one(out, r, spec, kind, reading))
        .collect();
    for w in written {
        saved(w?);
    }
    Ok(())
}

/// One of [`write_images`]' files: its path relative to `out`.
fn write_one(
    out: &Path,
    r: &FrameResult,
    spec: &WriteSpec,
    kind: FileKind,
    reading: Option<&Reading>,
) -> Result<String, Failure> {
    let img = &r.image;
    let rel = spec.layout.path(kind, r.number);
    let adapted = reading.map(|reading| r.adapted(reading, spec.adaptation));
    let rgb = adapted.as_deref().unwrap_or(&img.rgb);
    match kind {
        FileKind::RawExr => write_exr(&out.join(&rel), img)?,
        FileKind::AdaptedExr(_) => {
            let adapted = Frame {
                rgb: rgb.to_vec(),
                ..img.clone()
            };
            write_exr(&out.join(&rel), &adapted)?
        }
        FileKind::RawPng | FileKind::AdaptedPng(_) => {
            write_png(&out.join(&rel), rgb, img.width, img.height, spec.exposure)?
        }
    }
    Ok(rel)
}
