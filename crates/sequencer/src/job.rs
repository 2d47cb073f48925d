//! Job files: what a sequence renders, and how (format: `docs/job-format.md`).
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
use crate::error::Failure;
use crate::frames::FrameSet;
use eyeadapt_scene::{CameraPath, Scene, SourceMap};
use eyeadapt_tracer::{PathSettings, View};
use serde::Deserialize;
use sha2::{Digest, Sha256};
use std::path::{Path, PathBuf};
use toml::Spanned;

/// The built-in demo job (`eyeadapt sequence` with no JOB).
pub const DEMO_JOB: &str = include_str!("../../../configs/demo.toml");

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct JobFile {
    name: Option<String>,
    scene: Spanned<String>,
    seed: Option<Spanned<i64>>,
    frames: Option<Spanned<String>>,
    render: Option<RenderTable>,
    camera_path: Option<Spanned<toml::Value>>,
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
}

/// Temporal adaptation filters applied to the per-frame whites at report time.
#[derive(Clone, Debug, Default, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct TemporalTable {
    /// Presets (`fairchild`, `rinner`, `artistic`) applied to every estimator.
    #[serde(default)]
    pub filters: Vec<String>,
}

/// Which files each frame writes.
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

/// Settings given on the command line; they override the job file and enter the job hash.
#[derive(Clone, Debug, Default)]
pub struct JobOverrides {
    pub width: Option<u32>,
    pub height: Option<u32>,
    pub spp: Option<u32>,
    pub max_depth: Option<i32>,
    pub rr_depth: Option<u32>,
    pub seed: Option<u64>,
    pub eye_samples: Option<u32>,
}

/// A validated job.
pub struct Job {
    pub name: String,
    /// The job file, or `builtin:demo`.
    pub source: String,
    pub scene: Scene,
    pub path: CameraPath,
    pub width: u32,
    pub height: u32,
    pub spp: u32,
    pub path_settings: PathSettings,
    pub seed: u64,
    pub exposure: f32,
    pub estimators: Vec<&'static str>,
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
        }
    }

    pub fn time(&self, f: u32) -> f64 {
        self.path.frame_time(f as usize)
    }
}

/// Loads a job file (or the demo job when `path` is None) and applies the overrides.
pub fn load_job(path: Option<&Path>, o: &JobOverrides) -> Result<Job, Failure> {
    let (text, source, dir) = match path {
        Some(p) => {
            let text = std::fs::read_to_string(p).map_err(|e| match e.kind() {
                std::io::ErrorKind::NotFound
                | std::io::ErrorKind::IsADirectory
                | std::io::ErrorKind::InvalidData => {
                    Failure::Input(format!("{}: cannot read job file: {e}", p.display()))
                }
                _ => Failure::io("cannot read job file", p, &e),
            })?;
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

fn parse_job(text: &str, source: &str, dir: &Path, o: &JobOverrides) -> Result<Job, Failure> {
    let file = PathBuf::from(source);
    let map = SourceMap { file: &file, text };
    let raw: JobFile = toml::from_str(text).map_err(|e| {
        let offset = e.span().map_or(0, |s| s.start);
        Failure::Input(
            map.error(offset, e.message().trim().replace('\n', " "))
                .to_string(),
        )
    })?;
    let mut errors: Vec<String> = Vec::new();
    let err = |errors: &mut Vec<String>, offset: usize, msg: String| {
        errors.push(map.error(offset, msg).to_string())
    };

    // Scene.
    let spec = raw.scene.get_ref();
    let scene_spec = if spec.starts_with("builtin:") {
        spec.clone()
    } else {
        dir.join(spec).display().to_string()
    };
    let scene = match eyeadapt_scene::resolve_scene(&scene_spec) {
        Ok(s) => Some(s),
        Err(e) => {
            err(
                &mut errors,
                raw.scene.span().start,
                format!("scene \"{spec}\" failed to load:"),
            );
            errors.extend(e.diagnostics.iter().map(|d| format!("  {d}")));
            None
        }
    };
    // Render settings.
    let r = raw.render.as_ref();
    let int = |errors: &mut Vec<String>,
               v: Option<&Spanned<i64>>,
               what: &str,
               lo: i64,
               hi: i64|
     -> Option<i64> {
        let v = v?;
        let x = *v.get_ref();
        if (lo..=hi).contains(&x) || (what == "max_depth" && x == -1) {
            Some(x)
        } else {
            errors.push(
                map.error(
                    v.span().start,
                    format!("render.{what} {x} must be between {lo} and {hi}"),
                )
                .to_string(),
            );
            None
        }
    };
    let width = o.width.or(int(
        &mut errors,
        r.and_then(|r| r.width.as_ref()),
        "width",
        1,
        32768,
    )
    .map(|v| v as u32));
    let height = o.height.or(int(
        &mut errors,
        r.and_then(|r| r.height.as_ref()),
        "height",
        1,
        32768,
    )
    .map(|v| v as u32));
    let spp = o.spp.or(int(
        &mut errors,
        r.and_then(|r| r.spp.as_ref()),
        "spp",
        1,
        1 << 24,
    )
    .map(|v| v as u32));
    let max_depth = o.max_depth.or(int(
        &mut errors,
        r.and_then(|r| r.max_depth.as_ref()),
        "max_depth",
        1,
        1024,
    )
    .map(|v| v as i32));
    let rr_depth = o.rr_depth.or(int(
        &mut errors,
        r.and_then(|r| r.rr_depth.as_ref()),
        "rr_depth",
        1,
        1024,
    )
    .map(|v| v as u32));
    let exposure = match r.and_then(|r| r.exposure.as_ref()) {
        Some(e) if e.get_ref().is_finite() && e.get_ref().abs() <= 30.0 => *e.get_ref() as f32,
        Some(e) => {
            err(
                &mut errors,
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
    let seed = match (&o.seed, &raw.seed) {
        (Some(s), _) => *s,
        (None, Some(s)) if *s.get_ref() >= 0 => *s.get_ref() as u64,
        (None, Some(s)) => {
            err(
                &mut errors,
                s.span().start,
                format!("seed {} must be >= 0", s.get_ref()),
            );
            0
        }
        (None, None) => scene.as_ref().and_then(|s| s.render.seed).unwrap_or(0),
    };
    // Estimators and adaptation.
    let mut est_cfg = raw
        .estimators
        .as_ref()
        .map(|e| e.get_ref().clone())
        .unwrap_or_default();
    if let Some(n) = o.eye_samples {
        est_cfg.eye.fix_samples(n);
    }
    let estimators = match est_cfg.validate() {
        Ok(l) => l,
        Err(es) => {
            let at = raw.estimators.as_ref().map_or(0, |e| e.span().start);
            for e in es {
                err(&mut errors, at, e);
            }
            Vec::new()
        }
    };
    let adaptation = match raw
        .adaptation
        .as_ref()
        .map(|a| (a.get_ref().resolve(), a.span().start))
    {
        Some((Ok(a), _)) => a,
        Some((Err(e), at)) => {
            err(&mut errors, at, format!("adaptation: {e}"));
            AdaptationSettings::default()
        }
        None => AdaptationSettings::default(),
    };
    let temporal = raw
        .temporal
        .as_ref()
        .map(|t| t.get_ref().clone())
        .unwrap_or_default();
    for f in &temporal.filters {
        if let Err(e) = f.parse::<eyeadapt_color::TemporalFilter>() {
            let at = raw.temporal.as_ref().map_or(0, |t| t.span().start);
            err(&mut errors, at, format!("temporal.filters: {e}"));
        }
    }
    // Camera path: the job's, else the scene's.
    let path = match (
        &raw.camera_path,
        scene.as_ref().and_then(|s| s.camera_path.clone()),
    ) {
        (Some(v), _) => parse_path(v.get_ref().clone(), &map, v.span().start, &mut errors),
        (None, Some(p)) => Some(p),
        (None, None) => {
            if scene.is_some() {
                err(
                    &mut errors,
                    0,
                    "the job has no [camera_path] and its scene defines none".into(),
                );
            }
            None
        }
    };
    let (Some(scene), Some(path)) = (scene, path) else {
        return Err(Failure::Input(errors.join("\n")));
    };
    let camera = scene.camera.clone();
    let width = width.or(camera.as_ref().map(|c| c.width)).unwrap_or(320);
    let height = height.or(camera.as_ref().map(|c| c.height)).unwrap_or(180);
    let spp = spp.or(scene.render.spp).unwrap_or(16);
    let path_settings = PathSettings {
        max_depth: max_depth.or(scene.render.max_depth).unwrap_or(8),
        rr_depth: rr_depth.or(scene.render.rr_depth).unwrap_or(5),
    };
    let mut frames = FrameSet::from_frames(0..path.frame_count() as u32);
    if let Some(spec) = &raw.frames {
        match spec.get_ref().parse::<FrameSet>() {
            Ok(sel) => {
                let outside: Vec<u32> = sel
                    .as_slice()
                    .iter()
                    .copied()
                    .filter(|f| !frames.contains(*f))
                    .collect();
                if !outside.is_empty() {
                    err(
                        &mut errors,
                        spec.span().start,
                        format!(
                            "frames {:?}… lie outside the camera path's 0-{}",
                            &outside[..outside.len().min(5)],
                            frames.len().saturating_sub(1)
                        ),
                    );
                }
                frames = frames.intersect(&sel);
            }
            Err(e) => err(&mut errors, spec.span().start, e.to_string()),
        }
    }
    if !errors.is_empty() {
        return Err(Failure::Input(errors.join("\n")));
    }
    let name = raw.name.clone().unwrap_or_else(|| {
        Path::new(source)
            .file_stem()
            .map_or("job".into(), |s| s.to_string_lossy().into_owned())
    });
    let mut job = Job {
        name,
        source: source.to_string(),
        scene,
        path,
        width,
        height,
        spp,
        path_settings,
        seed,
        exposure,
        estimators,
        estimator_config: est_cfg,
        adaptation,
        temporal,
        outputs: raw.outputs.unwrap_or_default(),
        frames,
        hash: String::new(),
    };
    job.hash = job_hash(&job);
    Ok(job)
}

/// Deserialises and validates a `[camera_path]` table; every problem as a message.
fn path_from_toml(v: toml::Value) -> Result<CameraPath, Vec<String>> {
    let path: CameraPath = v
        .try_into()
        .map_err(|e: toml::de::Error| vec![e.message().trim().replace('\n', " ")])?;
    path.validate()
        .map_err(|ps| ps.iter().map(|p| p.to_string()).collect::<Vec<_>>())?;
    Ok(path)
}

fn parse_path(
    v: toml::Value,
    map: &SourceMap,
    at: usize,
    errors: &mut Vec<String>,
) -> Option<CameraPath> {
    match path_from_toml(v) {
        Ok(p) => Some(p),
        Err(es) => {
            errors.extend(
                es.iter()
                    .map(|e| map.error(at, format!("camera_path: {e}")).to_string()),
            );
            None
        }
    }
}

/// Fingerprint of everything that changes the rendered bits. Thread count, frame selection,
/// chunking and the output directory are deliberately not part of it.
pub fn job_hash(job: &Job) -> String {
    let mut h = Sha256::new();
    h.update(format!(
        "eyeadapt {} render-v1\n",
        env!("CARGO_PKG_VERSION")
    ));
    h.update(format!(
        "{}x{} spp {} {:?} seed {} exposure {} outputs {:?}\n",
        job.width, job.height, job.spp, job.path_settings, job.seed, job.exposure, job.outputs
    ));
    h.update(format!(
        "{:?}\n{:?}\n{:?}\n{:?}\n",
        job.estimators, job.estimator_config, job.adaptation, job.temporal
    ));
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
