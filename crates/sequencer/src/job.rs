//! Job files: what a sequence renders, and how. Every key with its default: `docs/job-format.md`.
//!
//! ```toml
//! name = "demo"
//! scene = "builtin:three-rooms"     # a path relative to this file, or builtin:NAME
//! seed = 0
//! frames = "0-71"                   # optional default selection; the CLI's --frames narrows it
//!
//! [render]
//! width = 320
//! height = 180
//! spp = 16
//! max_depth = 8                     # Mitsuba's convention
//! rr_depth = 5
//! exposure = 0.0                    # preview PNG exposure in stops
//! guiding = "off"                   # "on": path guiding learned per frame (tracer guiding/)
//!
//! [camera_path]                     # optional here if the scene has one
//! fps = 24
//! keyframes = [ { time = 0.0, position = [0, 1.6, 0], look_at = [0, 1.5, -1] },
//!               { time = 3.0, position = [0, 1.6, -6], look_at = [0, 1.5, -7] } ]
//!
//! [estimators]                      # see adapt.rs
//! list = ["all"]
//! [adaptation]
//! cat = "cat02"
//! degree = 1.0
//!
//! [outputs]
//! raw_exr = true                    # frames/raw/frame_NNNNNN.exr (beauty + AOVs)
//! raw_png = true                    # frames/raw/frame_NNNNNN.png (unadapted preview)
//! adapted_png = true                # frames/<estimator>/frame_NNNNNN.png
//! adapted_exr = false               # frames/<estimator>/frame_NNNNNN.exr (adapted beauty)
//! ```
//!
//! Unknown keys are errors. Every problem is reported as `file:line:col: message`.
use crate::adapt::{AdaptationConfig, AdaptationSettings, EstimatorConfig};
use crate::camera_motion::{CameraPathTable, camera_motion};
use crate::error::Failure;
use crate::estimator::Estimator;
use crate::frames::FrameSet;
use crate::pipeline::{Outputs, Pipeline, Sampling};
use eyeadapt_scene::{CameraMotion, Scene, SourceMap};
use eyeadapt_tracer::{AchromaticSpecular, Guiding, PathSettings, RenderSettings, SceneData, View};
use serde::Deserialize;
use sha2::{Digest, Sha256};
use std::path::{Path, PathBuf};
use toml::Spanned;

/// The built-in demo job (`eyeadapt sequence` with no JOB).
pub const DEMO_JOB: &str = include_str!("../../../configs/demo.toml");

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct JobFile {
    name: Option<Spanned<String>>,
    scene: Spanned<String>,
    seed: Option<Spanned<i64>>,
    frames: Option<Spanned<String>>,
    render: Option<RenderTable>,
    camera_path: Option<Spanned<CameraPathTable>>,
    estimators: Option<Spanned<EstimatorConfig>>,
    adaptation: Option<Spanned<AdaptationConfig>>,
    temporal: Option<Spanned<TemporalTable>>,
    outputs: Option<Outputs>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RenderTable {
    width: Option<Spanned<i64>>,
    height: Option<Spanned<i64>>,
    spp: Option<Spanned<i64>>,
    max_depth: Option<Spanned<i64>>,
    rr_depth: Option<Spanned<i64>>,
    exposure: Option<Spanned<f64>>,
    guiding: Option<Spanned<String>>,
}

/// Temporal adaptation filters applied to the per-frame whites at report time.
#[derive(Clone, Debug, Default, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct TemporalTable {
    /// Presets (`fairchild`, `rinner`, `artistic`) applied to every estimator.
    #[serde(default)]
    pub filters: Vec<String>,
}

/// Settings given on the command line; they override the job file and enter the job hash.
#[derive(Clone, Debug, Default)]
pub struct JobOverrides {
    pub sampling: Sampling,
    pub eye_samples: Option<u32>,
}

/// A validated job.
pub struct Job {
    pub name: String,
    /// The job file, or `builtin:demo`.
    pub source: String,
    pub scene: Scene,
    /// The camera's motion: keyframes, a glTF animation or a CSV track.
    pub path: CameraMotion,
    pub width: u32,
    pub height: u32,
    pub spp: u32,
    pub path_settings: PathSettings,
    /// Path guiding; in the hash only when on, so that jobs without it keep their hashes.
    pub guiding: Guiding,
    pub seed: u64,
    pub exposure: f32,
    pub estimators: Vec<Estimator>,
    pub estimator_config: EstimatorConfig,
    pub adaptation: AdaptationSettings,
    pub temporal: TemporalTable,
    pub outputs: Outputs,
    /// Every frame of the camera path (0-based), narrowed by the job's `frames` key.
    pub frames: FrameSet,
    /// SHA-256 over everything that changes the output (settings, geometry, poses).
    pub hash: String,
}

impl Job {
    /// The camera of frame `f`.
    pub fn view(&self, f: u32) -> View {
        let pose = self.path.sample(self.path.frame_time(f as usize));
        View {
            position: pose.position.as_vec3(),
            forward: pose.forward.as_vec3(),
            up: pose.up.as_vec3(),
            fov_deg: pose.fov_deg.unwrap_or_else(|| {
                self.scene
                    .camera
                    .as_ref()
                    .map_or(60.0, |c| c.fov_deg as f64)
            }) as f32,
            width: self.width,
            height: self.height,
            projection: self
                .scene
                .camera
                .as_ref()
                .map_or(eyeadapt_scene::Projection::Pinhole, |c| c.projection),
        }
    }

    pub fn time(&self, f: u32) -> f64 {
        self.path.frame_time(f as usize)
    }

    /// The frame pipeline of this job over the scene's render data.
    pub fn pipeline<'a>(&'a self, data: &'a SceneData) -> Pipeline<'a> {
        Pipeline {
            data,
            settings: RenderSettings {
                spp: self.spp,
                path: self.path_settings,
                seed: self.seed,
                frame: 0,
                filter: self.scene.render.filter.unwrap_or_default(),
                wcam_specular: renderer_specular(self.estimator_config.wcam.specular),
                guiding: self.guiding,
            },
            estimators: &self.estimators,
            config: &self.estimator_config,
            adaptation: &self.adaptation,
        }
    }
}

/// The renderer's side of `estimators.wcam.specular` (estimators.md §2.3): the WCAM re-render
/// is made while tracing.
pub fn renderer_specular(s: eyeadapt_color::WcamSpecular) -> AchromaticSpecular {
    match s {
        eyeadapt_color::WcamSpecular::Include => AchromaticSpecular::Include,
        eyeadapt_color::WcamSpecular::ExcludeDelta => AchromaticSpecular::ExcludeDelta,
        eyeadapt_color::WcamSpecular::DiffuseOnly => AchromaticSpecular::DiffuseOnly,
    }
}

/// Loads a job file (or the demo job when `path` is None) and applies the overrides.
pub fn load_job(path: Option<&Path>, o: &JobOverrides) -> Result<Job, Failure> {
    let (text, source, dir) = match path {
        Some(p) => {
            // Only a regular file is read: a FIFO would block, /dev/zero never ends.
            let text = eyeadapt_scene::read_input_text(p)
                .map_err(|e| Failure::input_io("cannot read job file", p, &e))?;
            (
                text,
                p.display().to_string(),
                p.parent().unwrap_or(Path::new(".")).to_path_buf(),
            )
        }
        None => (
            DEMO_JOB.to_string(),
            "builtin:demo".to_string(),
            PathBuf::from("."),
        ),
    };
    parse_job(&text, &source, &dir, o)
}

/// A scene file (TOML scene or Mitsuba XML) given where a job file belongs, told apart from a
/// broken job file: XML, or TOML without a `scene` key but with a scene's top-level tables.
fn looks_like_scene_file(text: &str) -> bool {
    if text.trim_start().starts_with('<') {
        return true;
    }
    const SCENE_KEYS: [&str; 5] = ["camera", "materials", "shapes", "lights", "environment"];
    text.parse::<toml::Table>()
        .is_ok_and(|t| !t.contains_key("scene") && SCENE_KEYS.iter().any(|k| t.contains_key(*k)))
}

/// Problems found while checking a job file, each located `file:line:col`.
struct Problems<'a> {
    map: SourceMap<'a>,
    errors: Vec<String>,
}

impl Problems<'_> {
    fn at(&mut self, offset: usize, msg: String) {
        self.errors.push(self.map.error(offset, msg).to_string());
    }

    /// An integer setting `render.<what>` in `lo..=hi` (`max_depth` also takes -1).
    fn int(&mut self, v: Option<&Spanned<i64>>, what: &str, lo: i64, hi: i64) -> Option<i64> {
        let v = v?;
        let x = *v.get_ref();
        if (lo..=hi).contains(&x) || (what == "max_depth" && x == -1) {
            Some(x)
        } else {
            self.at(
                v.span().start,
                format!("render.{what} {x} must be between {lo} and {hi}"),
            );
            None
        }
    }
}

fn parse_job(text: &str, source: &str, dir: &Path, o: &JobOverrides) -> Result<Job, Failure> {
    if looks_like_scene_file(text) {
        return Err(Failure::Input(format!(
            "{source} is a scene file, not a job file; use `eyeadapt render {source}` or name it \
             as `scene = \"…\"` in a job (docs/job-format.md)"
        )));
    }
    let file = PathBuf::from(source);
    let map = SourceMap { file: &file, text };
    let raw: JobFile = toml::from_str(text).map_err(|e| {
        let offset = e.span().map_or(0, |s| s.start);
        Failure::Input(
            map.error(offset, e.message().trim().replace('\n', " "))
                .to_string(),
        )
    })?;
    let mut p = Problems {
        map,
        errors: Vec::new(),
    };
    let scene = load_scene(&raw.scene, dir, &mut p);
    let (sampling, exposure) = render_table(raw.render.as_ref(), &mut p);
    let seed = job_seed(o, raw.seed.as_ref(), scene.as_ref(), &mut p);
    let sampling = o.sampling.or(sampling);
    let (estimators, estimator_config) = estimators(raw.estimators.as_ref(), o, &mut p);
    let adaptation = adaptation(raw.adaptation.as_ref(), &mut p);
    let temporal = temporal(raw.temporal.as_ref(), &mut p);
    let path = scene.as_ref().and_then(|s| {
        let scene_path = scene_location(raw.scene.get_ref(), dir);
        match camera_motion(raw.camera_path.as_ref(), s, Path::new(&scene_path), dir) {
            Ok(m) => Some(m),
            Err(problems) => {
                for (offset, msg) in problems {
                    p.at(offset, msg);
                }
                None
            }
        }
    });
    let (Some(mut scene), Some(path)) = (scene, path) else {
        return Err(Failure::Input(p.errors.join("\n")));
    };
    crate::camera_motion::play_with_camera(&mut scene, &path);
    let camera = scene.camera.clone();
    let width = sampling
        .width
        .or(camera.as_ref().map(|c| c.width))
        .unwrap_or(320);
    let height = sampling
        .height
        .or(camera.as_ref().map(|c| c.height))
        .unwrap_or(180);
    let settings = sampling.render_settings(&scene);
    let frames = job_frames(raw.frames.as_ref(), &path, &mut p);
    if !p.errors.is_empty() {
        return Err(Failure::Input(p.errors.join("\n")));
    }
    let name = job_name(raw.name.as_ref(), source, &mut p);
    if !p.errors.is_empty() {
        return Err(Failure::Input(p.errors.join("\n")));
    }
    let mut job = Job {
        name,
        source: source.to_string(),
        scene,
        path,
        width,
        height,
        spp: settings.spp,
        path_settings: settings.path,
        guiding: settings.guiding,
        seed,
        exposure,
        estimators,
        estimator_config,
        adaptation,
        temporal,
        outputs: raw.outputs.unwrap_or_default(),
        frames,
        hash: String::new(),
    };
    job.hash = job_hash(&job);
    Ok(job)
}

/// The job's `name` (else the job file's stem), which names its default output directory
/// `out/<name>`: a plain relative identifier, so that it can never point elsewhere.
fn job_name(given: Option<&Spanned<String>>, source: &str, p: &mut Problems) -> String {
    let (name, at) = match given {
        Some(n) => (n.get_ref().clone(), n.span().start),
        None => (
            Path::new(source)
                .file_stem()
                .map_or("job".into(), |s| s.to_string_lossy().into_owned()),
            0,
        ),
    };
    if let Err(why) = check_name(&name) {
        let whose = if given.is_some() {
            "name"
        } else {
            "the job's name (its file name, as no `name` is given)"
        };
        p.at(
            at,
            format!(
                "{whose} {name:?} {why}; it names the output directory out/<name>, so it must \
                 be one plain file name"
            ),
        );
    }
    name
}

/// Why `name` is not a plain relative identifier, if it is not.
fn check_name(name: &str) -> Result<(), &'static str> {
    if name.is_empty() {
        Err("is empty")
    } else if name == "." || name == ".." {
        Err("is a directory reference")
    } else if name.contains(['/', '\\']) {
        Err("contains a path separator")
    } else if name.chars().any(char::is_control) {
        Err("contains a control character")
    } else if name.len() > 200 {
        Err("is longer than 200 bytes")
    } else {
        Ok(())
    }
}

/// Where the job's `scene` is: `builtin:NAME` as it is, a file relative to the job file.
fn scene_location(given: &str, dir: &Path) -> String {
    if given.starts_with("builtin:") {
        given.to_string()
    } else {
        dir.join(given).display().to_string()
    }
}

/// The scene (its path relative to the job file), if it loads.
fn load_scene(spec: &Spanned<String>, dir: &Path, p: &mut Problems) -> Option<Scene> {
    let given = spec.get_ref();
    let scene_spec = scene_location(given, dir);
    match eyeadapt_scene::resolve_scene(&scene_spec) {
        Ok(s) => Some(s),
        Err(e) => {
            p.at(
                spec.span().start,
                format!("scene \"{given}\" failed to load:"),
            );
            p.errors
                .extend(e.diagnostics.iter().map(|d| format!("  {d}")));
            None
        }
    }
}

/// The `[render]` table: sampling (its seed comes from the top-level key) and exposure.
fn render_table(r: Option<&RenderTable>, p: &mut Problems) -> (Sampling, f32) {
    let sampling = Sampling {
        width: p
            .int(r.and_then(|r| r.width.as_ref()), "width", 1, 32768)
            .map(|v| v as u32),
        height: p
            .int(r.and_then(|r| r.height.as_ref()), "height", 1, 32768)
            .map(|v| v as u32),
        spp: p
            .int(r.and_then(|r| r.spp.as_ref()), "spp", 1, 1 << 24)
            .map(|v| v as u32),
        max_depth: p
            .int(r.and_then(|r| r.max_depth.as_ref()), "max_depth", 1, 1024)
            .map(|v| v as i32),
        rr_depth: p
            .int(r.and_then(|r| r.rr_depth.as_ref()), "rr_depth", 1, 1024)
            .map(|v| v as u32),
        seed: None,
        guiding: r
            .and_then(|r| r.guiding.as_ref())
            .and_then(|g| match g.get_ref().as_str() {
                "off" => Some(Guiding::Off),
                "on" => Some(Guiding::On),
                other => {
                    p.at(
                        g.span().start,
                        format!("render.guiding \"{other}\" must be \"off\" or \"on\""),
                    );
                    None
                }
            }),
    };
    let exposure = match r.and_then(|r| r.exposure.as_ref()) {
        Some(e) if e.get_ref().is_finite() && e.get_ref().abs() <= 30.0 => *e.get_ref() as f32,
        Some(e) => {
            p.at(
                e.span().start,
                format!(
                    "render.exposure {} must be a finite number of stops in [-30, 30]",
                    e.get_ref()
                ),
            );
            0.0
        }
        None => 0.0,
    };
    (sampling, exposure)
}

/// The command line's seed, else the job's, else the scene's, else 0.
fn job_seed(
    o: &JobOverrides,
    seed: Option<&Spanned<i64>>,
    scene: Option<&Scene>,
    p: &mut Problems,
) -> u64 {
    match (o.sampling.seed, seed) {
        (Some(s), _) => s,
        (None, Some(s)) if *s.get_ref() >= 0 => *s.get_ref() as u64,
        (None, Some(s)) => {
            p.at(s.span().start, format!("seed {} must be >= 0", s.get_ref()));
            0
        }
        (None, None) => scene.and_then(|s| s.render.seed).unwrap_or(0),
    }
}

fn estimators(
    table: Option<&Spanned<EstimatorConfig>>,
    o: &JobOverrides,
    p: &mut Problems,
) -> (Vec<Estimator>, EstimatorConfig) {
    let mut cfg = table.map(|e| e.get_ref().clone()).unwrap_or_default();
    if let Some(n) = o.eye_samples {
        cfg.eye.fix_samples(n);
    }
    let list = match cfg.validate() {
        Ok(l) => l,
        Err(es) => {
            let at = table.map_or(0, |e| e.span().start);
            for e in es {
                p.at(at, e);
            }
            Vec::new()
        }
    };
    (list, cfg)
}

fn adaptation(table: Option<&Spanned<AdaptationConfig>>, p: &mut Problems) -> AdaptationSettings {
    match table.map(|a| (a.get_ref().resolve(), a.span().start)) {
        Some((Ok(a), _)) => a,
        Some((Err(e), at)) => {
            p.at(at, format!("adaptation: {e}"));
            AdaptationSettings::default()
        }
        None => AdaptationSettings::default(),
    }
}

fn temporal(table: Option<&Spanned<TemporalTable>>, p: &mut Problems) -> TemporalTable {
    let temporal = table.map(|t| t.get_ref().clone()).unwrap_or_default();
    for f in &temporal.filters {
        if let Err(e) = f.parse::<eyeadapt_color::TemporalFilter>() {
            let at = table.map_or(0, |t| t.span().start);
            p.at(at, format!("temporal.filters: {e}"));
        }
    }
    temporal
}

/// Every frame of the camera path, narrowed by the job's `frames` key.
fn job_frames(spec: Option<&Spanned<String>>, path: &CameraMotion, p: &mut Problems) -> FrameSet {
    let all = FrameSet::from_frames(0..path.frame_count() as u32);
    let Some(spec) = spec else {
        return all;
    };
    match spec.get_ref().parse::<FrameSet>() {
        Ok(sel) => match all.narrow(&sel) {
            Ok(frames) => frames,
            Err(outside) => {
                let first: Vec<u32> = outside.iter().take(5).collect();
                p.at(
                    spec.span().start,
                    format!(
                        "frames {first:?}… lie outside the camera path's 0-{}",
                        all.len().saturating_sub(1)
                    ),
                );
                all
            }
        },
        Err(e) => {
            p.at(spec.span().start, e.to_string());
            all
        }
    }
}

/// Fingerprint of everything that changes the rendered bits. Thread count, frame selection,
/// chunking and the output directory are deliberately not part of it.
pub fn job_hash(job: &Job) -> String {
    let mut h = Sha256::new();
    h.update(format!(
        "eyeadapt {} render-v{}\n",
        env!("CARGO_PKG_VERSION"),
        eyeadapt_tracer::RENDER_REVISION
    ));
    h.update(format!(
        "{}x{} spp {} {:?} seed {} exposure {} outputs {:?}\n",
        job.width, job.height, job.spp, job.path_settings, job.seed, job.exposure, job.outputs
    ));
    h.update(format!(
        "{:?}\n{:?}\n{:?}\n{:?}\n",
        // The names, as the hash has always covered them.
        job.estimators.iter().map(|e| e.name()).collect::<Vec<_>>(),
        job.estimator_config,
        job.adaptation,
        job.temporal
    ));
    if job.guiding != Guiding::Off {
        h.update(format!("guiding {:?}\n", job.guiding));
    }
    h.update(format!("scene {}\n", job.scene.fingerprint()));
    for f in 0..job.path.frame_count() {
        let v = job.view(f as u32);
        h.update(format!(
            "{f} {} {:?} {:?} {:?} {}\n",
            job.time(f as u32),
            v.position.to_array(),
            v.forward.to_array(),
            v.up.to_array(),
            v.fov_deg
        ));
    }
    hex(&h.finalize()[..])
}

pub fn hex(bytes: &[u8]) -> String {
    bytes.iter().map(|b| format!("{b:02x}")).collect()
}
