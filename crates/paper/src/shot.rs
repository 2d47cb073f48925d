//! A case's jobs rendered through the frame pipeline, frame by frame, with their estimates
//! and the case's diagnostics.
use crate::case_info::CaseInfo;
use crate::study::{Config, WCAM_SPECULAR, WCAM_WEIGHT};
use crate::{cases, sheet};
use eyeadapt_color::{Estimate, WcamSpecular, WcamWeight};
use eyeadapt_sequencer::Failure;
use eyeadapt_sequencer::job::{Job, JobOverrides, load_job};
use eyeadapt_sequencer::output::atomic_write_bytes;
use eyeadapt_sequencer::pipeline::{
    FrameResult, FrameScenes, Layout, Outputs, WriteSpec, write_images,
};
use eyeadapt_tracer::{Frame, View};
use std::collections::BTreeMap;
use std::path::Path;

/// One series of a shot: an estimator's reading, or a case's diagnostic estimate.
pub(crate) struct Named {
    pub name: &'static str,
    pub estimate: Estimate,
}

/// One rendered frame of a case with its estimates.
pub(crate) struct Shot {
    pub frame: u32,
    pub time: f64,
    pub view: View,
    /// The estimators' readings, then the case's diagnostics.
    pub readings: Vec<Named>,
    /// Kept for stills; `None` for long sequences (only the sheet tiles are kept).
    pub image: Option<Frame>,
    /// Sheet tiles raw | wcam | eye, 8-bit sRGB, and their size.
    pub tiles: sheet::Tiles,
    /// Per-frame diagnostics of the case (e.g. the bench's share of WCAM in case 6).
    pub diag: BTreeMap<String, f64>,
}

/// A job rendered frame by frame.
pub(crate) struct JobRun {
    pub name: &'static str,
    pub job: Job,
    pub shots: Vec<Shot>,
}

impl JobRun {
    pub fn scene(&self) -> &eyeadapt_scene::Scene {
        &self.job.scene
    }
}

/// What one run of a case's job uses: a configuration of the study, a seed, a size.
pub(crate) struct RunSpec<'a> {
    pub config: &'a Config,
    pub seed: u64,
    /// (width, height, spp) per job of the case; `None`: the jobs' own.
    pub sizes: Option<&'static [(u32, u32, u32)]>,
    pub eye_samples: Option<u32>,
    /// Write the job and scene files, the CSV and the stills' raw EXRs into the directory.
    pub write_files: bool,
    pub verbose: bool,
}

/// `text` with every `{{key}}` of `config` replaced by its value; an error names the first
/// placeholder left unfilled.
pub(crate) fn fill_template(text: &str, config: &Config, what: &str) -> Result<String, Failure> {
    let mut s = text.to_string();
    for (k, v) in &config.fill {
        s = s.replace(&format!("{{{{{k}}}}}"), v);
    }
    match s.find("{{") {
        Some(i) => Err(Failure::Other(format!(
            "{what}: placeholder {} has no value in configuration {:?}",
            &s[i..s[i..].find("}}").map_or(s.len(), |e| i + e + 2)],
            config.labels
        ))),
        None => Ok(s),
    }
}

/// Loads a case's job with the run's configuration and overrides. The job (and its filled
/// scene template) is written to `<dir>/<job>.toml` (`<dir>/scene.toml`) first, so the work
/// directory records exactly what ran.
fn load_case_job(
    case: &CaseInfo,
    index: usize,
    spec: &RunSpec,
    dir: &Path,
) -> Result<Job, Failure> {
    let (name, text, template) = case.jobs[index];
    let text = fill_template(text, spec.config, name)?;
    if let Some(t) = template {
        let scene = fill_template(t, spec.config, &format!("{name} scene"))?;
        atomic_write_bytes(&dir.join("scene.toml"), scene.as_bytes())?;
        for (path, bytes) in case.files {
            let p = dir.join(path);
            if let Some(parent) = p.parent() {
                std::fs::create_dir_all(parent)
                    .map_err(|e| Failure::Other(format!("{}: {e}", parent.display())))?;
            }
            atomic_write_bytes(&p, bytes)?;
        }
    }
    let path = dir.join(format!("{name}.toml"));
    atomic_write_bytes(&path, text.as_bytes())?;
    let mut ov = JobOverrides {
        eye_samples: spec.eye_samples,
        ..Default::default()
    };
    ov.sampling.seed = Some(spec.seed);
    if let Some(&(w, h, spp)) = spec.sizes.and_then(|s| s.get(index)) {
        ov.sampling.width = Some(w);
        ov.sampling.height = Some(h);
        ov.sampling.spp = Some(spp);
    }
    let mut job = load_job(Some(&path), &ov)?;
    if spec.config.get(WCAM_WEIGHT) == Some("power") {
        job.estimator_config.wcam.weight = WcamWeight::Power;
    }
    if spec.config.get(WCAM_SPECULAR) == Some("diffuse_only") {
        job.estimator_config.wcam.specular = WcamSpecular::DiffuseOnly;
    }
    Ok(job)
}

/// Renders every frame of one job; with `spec.write_files`, writes `<dir>/<job>.csv` and, for
/// stills, the raw EXRs.
pub(crate) fn run_job(
    case: &CaseInfo,
    index: usize,
    spec: &RunSpec,
    dir: &Path,
) -> Result<JobRun, Failure> {
    let name = case.jobs[index].0;
    let job = load_case_job(case, index, spec, dir)?;
    // Stills keep their image for the read-outs; the walkthrough only its sheet tiles.
    let keep_images = case.number != 6;
    let scenes = FrameScenes::new(&job.scene);
    let mut csv = String::from(eyeadapt_sequencer::adapt::CSV_HEADER);
    csv.push('\n');
    let mut shots = Vec::new();
    for &f in job.frames.as_slice() {
        let r = scenes.at(job.time(f), |data| {
            job.pipeline(data).run(f, job.time(f), job.view(f))
        });
        let (extra, diag) = cases::diagnostics(case, &job, &r.view, &r.image);
        csv.push_str(&r.rows());
        for d in &extra {
            csv.push_str(&r.row(d.name, &d.estimate));
        }
        let readings: Vec<Named> = r
            .readings
            .iter()
            .map(|x| Named {
                name: x.estimator.name(),
                estimate: x.estimate.clone(),
            })
            .chain(extra)
            .collect();
        let tiles = sheet::tiles(&r.image, &readings, &job.adaptation);
        let n = job.frames.len();
        if spec.verbose && (n <= 10 || f % 10 == 0 || f as usize + 1 == n) {
            eprintln!(
                "paper case {} {name}: frame {f} of {n} ({}x{}, {} spp) done",
                case.number, job.width, job.height, job.spp
            );
        }
        if keep_images && spec.write_files {
            let ws = WriteSpec {
                layout: Layout::Prefixed(name),
                outputs: Outputs {
                    raw_exr: true,
                    raw_png: false,
                    adapted_png: false,
                    adapted_exr: false,
                },
                exposure: job.exposure,
                adaptation: &job.adaptation,
            };
            write_images(dir, &r, &ws, |_| {})?;
        }
        let FrameResult {
            time, view, image, ..
        } = r;
        shots.push(Shot {
            frame: f,
            time,
            view,
            readings,
            image: keep_images.then_some(image),
            tiles,
            diag,
        });
    }
    if spec.write_files {
        atomic_write_bytes(&dir.join(format!("{name}.csv")), csv.as_bytes())?;
    }
    Ok(JobRun { name, job, shots })
}
