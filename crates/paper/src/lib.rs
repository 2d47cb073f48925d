//! `eyeadapt paper`: renders the six test cases of Gruson, Ribardière & Cozot 2013 (§5) and
//! checks each of the paper's claims against measured numbers (docs/paper.md).
//!
//! Every case is a job file in `configs/` (embedded here, so the command runs from any
//! directory) over a built-in scene. For each case [`run_case`] renders the job's frames, runs
//! every estimator, writes the per-frame CSV and the raw EXRs into the work directory, measures
//! what the paper measured, and returns a [`CaseReport`]: the claim, a markdown section with the
//! numbers, machine-readable metrics and one verdict per claim. [`run`] does all six cases,
//! writes a contact sheet per case (raw | WCAM | eye, one row per view) and `RESULTS.md`.
//!
//! Output depends only on the seed and the variant (`--quick` or not): no timestamps or
//! timings go into `RESULTS.md` or the sheets, and the renderer is bit-deterministic, so the
//! same seed gives byte-identical files.

mod cases;
mod measure;
mod report;
mod sheet;

pub use crate::measure::{Region, RegionMean, equal_luminance_hsv, region_mean};
pub use crate::report::results_markdown;

use eyeadapt_sequencer::Failure;
use eyeadapt_sequencer::adapt::{Reading, csv_row, estimate_all};
use eyeadapt_sequencer::job::{Job, JobOverrides, load_job};
use eyeadapt_sequencer::output::{atomic_write_bytes, write_exr};
use eyeadapt_tracer::{Frame, RenderSettings, SceneData, View, render};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

/// One test case of the paper.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct CaseInfo {
    pub number: u32,
    /// File-name stem of the contact sheet and work directory.
    pub slug: &'static str,
    pub title: &'static str,
    /// The paper's figures.
    pub figures: &'static str,
    /// Job files (embedded `configs/<name>.toml`), rendered in this order.
    pub jobs: &'static [(&'static str, &'static str)],
    /// Quick variant: (width, height, spp) per job.
    pub quick: &'static [(u32, u32, u32)],
}

/// The six cases of [GRC13] §5.
pub const CASES: &[CaseInfo] = &[
    CaseInfo {
        number: 1,
        slug: "case1-cornell-orange",
        title: "White Cornell box, orange light",
        figures: "Fig. 5",
        jobs: &[(
            "cornell-orange",
            include_str!("../../../configs/cornell-orange.toml"),
        )],
        quick: &[(64, 64, 16)],
    },
    CaseInfo {
        number: 2,
        slug: "case2-one-reflectance",
        title: "Worlds of one reflectance",
        figures: "Fig. 6, 7",
        jobs: &[
            (
                "white-world-orange-light",
                include_str!("../../../configs/white-world-orange-light.toml"),
            ),
            (
                "orange-world-white-light",
                include_str!("../../../configs/orange-world-white-light.toml"),
            ),
        ],
        quick: &[(64, 48, 16), (64, 48, 16)],
    },
    CaseInfo {
        number: 3,
        slug: "case3-cornell-green-floor",
        title: "Cornell box with a green floor, white light, colour checker",
        figures: "Fig. 8",
        jobs: &[(
            "cornell-green-floor",
            include_str!("../../../configs/cornell-green-floor.toml"),
        )],
        quick: &[(128, 128, 16)],
    },
    CaseInfo {
        number: 4,
        slug: "case4-statue-red-spot",
        title: "White statue, red spot light, white ceiling light",
        figures: "Fig. 9",
        jobs: &[(
            "statue-red-spot",
            include_str!("../../../configs/statue-red-spot.toml"),
        )],
        quick: &[(128, 96, 64)],
    },
    CaseInfo {
        number: 5,
        slug: "case5-two-rooms",
        title: "Two rooms (orange, blue), three views",
        figures: "Fig. 10-12",
        jobs: &[("two-rooms", include_str!("../../../configs/two-rooms.toml"))],
        quick: &[(96, 72, 16)],
    },
    CaseInfo {
        number: 6,
        slug: "case6-three-rooms",
        title: "Three-room walkthrough (white, orange, blue)",
        figures: "Fig. 13-15",
        jobs: &[(
            "three-rooms",
            include_str!("../../../configs/three-rooms.toml"),
        )],
        quick: &[(96, 54, 4)],
    },
];

/// What to run and where to write.
#[derive(Clone, Debug)]
pub struct PaperOptions {
    /// Small images and few samples (minutes, not tens of minutes).
    pub quick: bool,
    /// Contact sheets go here (and RESULTS.md unless `results` is given).
    pub out: PathBuf,
    /// Path of RESULTS.md (default `<out>/RESULTS.md`).
    pub results: Option<PathBuf>,
    /// Per-case job files, CSVs and raw EXRs (default `<out>/work`).
    pub work: Option<PathBuf>,
    pub seed: u64,
    /// Case numbers to run (1–6); empty = all.
    pub cases: Vec<u32>,
    /// Eye-sensor paths per frame (default: the jobs' 16 384).
    pub eye_samples: Option<u32>,
    /// Print one line per rendered frame on stderr.
    pub verbose: bool,
}

impl PaperOptions {
    pub fn new(out: PathBuf) -> PaperOptions {
        PaperOptions {
            quick: false,
            out,
            results: None,
            work: None,
            seed: 0,
            cases: Vec::new(),
            eye_samples: None,
            verbose: false,
        }
    }

    pub fn results_path(&self) -> PathBuf {
        self.results
            .clone()
            .unwrap_or_else(|| self.out.join("RESULTS.md"))
    }

    pub fn work_dir(&self) -> PathBuf {
        self.work.clone().unwrap_or_else(|| self.out.join("work"))
    }

    fn selected(&self) -> Result<Vec<&'static CaseInfo>, Failure> {
        if let Some(bad) = self.cases.iter().find(|n| !(1..=6).contains(*n)) {
            return Err(Failure::Input(format!(
                "there is no paper case {bad} (cases are 1 to 6)"
            )));
        }
        Ok(CASES
            .iter()
            .filter(|c| self.cases.is_empty() || self.cases.contains(&c.number))
            .collect())
    }
}

/// One claim of the paper and whether the measurement supports it.
#[derive(Clone, Debug, PartialEq)]
pub struct Verdict {
    pub claim: String,
    /// The operational test applied, with the measured values.
    pub test: String,
    pub holds: bool,
}

/// The outcome of one case.
#[derive(Clone, Debug)]
pub struct CaseReport {
    pub info: &'static CaseInfo,
    /// What the paper says, quoted or closely paraphrased.
    pub paper_claim: String,
    /// Markdown body: setup, tables, notes (no heading).
    pub markdown: String,
    /// Named numbers for tests and tools, e.g. `eye.duv_light`, `orange.eye.hue`.
    pub metrics: BTreeMap<String, f64>,
    pub verdicts: Vec<Verdict>,
    /// Contact-sheet file name (relative to the output directory).
    pub sheet: Option<String>,
}

impl CaseReport {
    /// A metric by name; panics with the list of names when it does not exist.
    pub fn metric(&self, name: &str) -> f64 {
        match self.metrics.get(name) {
            Some(v) => *v,
            None => panic!(
                "case {} has no metric {name} (has: {})",
                self.info.number,
                self.metrics.keys().cloned().collect::<Vec<_>>().join(", ")
            ),
        }
    }

    pub fn all_hold(&self) -> bool {
        self.verdicts.iter().all(|v| v.holds)
    }
}

/// Everything `eyeadapt paper` produced.
#[derive(Debug)]
pub struct PaperRun {
    pub cases: Vec<CaseReport>,
    pub results_path: PathBuf,
    pub markdown: String,
}

/// One rendered frame of a case with its estimates.
pub(crate) struct Shot {
    pub frame: u32,
    pub time: f64,
    pub view: View,
    pub readings: Vec<Reading>,
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

/// The settings of the variant, as RESULTS.md states them.
pub fn variant_description(o: &PaperOptions) -> String {
    let mut s = String::new();
    s.push_str(if o.quick {
        "quick variant (`eyeadapt paper --quick`): small images, few samples; the numbers are noisier than the full run's"
    } else {
        "full variant (`eyeadapt paper`): the job files' resolutions and sample counts"
    });
    s.push_str(&format!(", seed {}", o.seed));
    if let Some(n) = o.eye_samples {
        s.push_str(&format!(", {n} eye-sensor paths per frame"));
    }
    s
}

/// Loads a case's job (the embedded text is written to `<work>/<job>.toml` first, so the
/// work directory records exactly what ran) with the variant's overrides.
fn load_case_job(
    case: &CaseInfo,
    index: usize,
    o: &PaperOptions,
    dir: &Path,
) -> Result<Job, Failure> {
    let (name, text) = case.jobs[index];
    let path = dir.join(format!("{name}.toml"));
    atomic_write_bytes(&path, text.as_bytes())?;
    let mut ov = JobOverrides {
        seed: Some(o.seed),
        eye_samples: o.eye_samples,
        ..Default::default()
    };
    if o.quick {
        let (w, h, spp) = case.quick[index];
        ov.width = Some(w);
        ov.height = Some(h);
        ov.spp = Some(spp);
    }
    load_job(Some(&path), &ov)
}

/// Renders every frame of one job; writes `<dir>/<job>.csv` and, for stills, the raw EXRs.
fn run_job(
    case: &CaseInfo,
    index: usize,
    o: &PaperOptions,
    dir: &Path,
    keep_images: bool,
) -> Result<JobRun, Failure> {
    let name = case.jobs[index].0;
    let job = load_case_job(case, index, o, dir)?;
    let data = SceneData::new(&job.scene);
    let mut csv = String::from(eyeadapt_sequencer::adapt::CSV_HEADER);
    csv.push('\n');
    let mut shots = Vec::new();
    for &f in job.frames.as_slice() {
        let view = job.view(f);
        let settings = RenderSettings {
            spp: job.spp,
            path: job.path_settings,
            seed: job.seed,
            frame: f,
        };
        let image = render(&data, &view, &settings);
        let mut readings = estimate_all(
            &job.estimators,
            &job.estimator_config,
            &data,
            &view,
            &image,
            f,
            job.seed,
            job.path_settings,
        );
        let (extra, diag) = cases::diagnostics(case, &job, &view, &image);
        readings.extend(extra);
        let time = job.time(f);
        for r in &readings {
            csv.push_str(&csv_row(f, time, r, &[], view.position));
        }
        let tiles = sheet::tiles(&image, &readings, &job.adaptation);
        let n = job.frames.len();
        if o.verbose && (n <= 10 || f % 10 == 0 || f as usize + 1 == n) {
            eprintln!(
                "paper case {} {name}: frame {f} of {n} ({}x{}, {} spp) done",
                case.number, job.width, job.height, job.spp
            );
        }
        let image = if keep_images {
            write_exr(&dir.join(format!("{name}_frame_{f:06}.exr")), &image)?;
            Some(image)
        } else {
            None
        };
        shots.push(Shot {
            frame: f,
            time,
            view,
            readings,
            image,
            tiles,
            diag,
        });
    }
    atomic_write_bytes(&dir.join(format!("{name}.csv")), csv.as_bytes())?;
    Ok(JobRun { name, job, shots })
}

/// Runs one case: renders its jobs, measures, judges, writes its contact sheet into `o.out`.
pub fn run_case(number: u32, o: &PaperOptions) -> Result<CaseReport, Failure> {
    let case = CASES
        .iter()
        .find(|c| c.number == number)
        .ok_or_else(|| Failure::Input(format!("there is no paper case {number}")))?;
    let dir = o.work_dir().join(case.slug);
    eyeadapt_sequencer::still::prepare_out_dir(&dir)?;
    eyeadapt_sequencer::still::prepare_out_dir(&o.out)?;
    let keep = case.number != 6;
    let runs = (0..case.jobs.len())
        .map(|i| run_job(case, i, o, &dir, keep))
        .collect::<Result<Vec<_>, _>>()?;
    let mut report = cases::evaluate(case, &runs)?;
    let sheet_name = format!("{}.png", case.slug);
    let rows = cases::sheet_rows(case, &runs, &report);
    sheet::write_sheet(&o.out.join(&sheet_name), &rows)?;
    report.sheet = Some(sheet_name);
    Ok(report)
}

/// Runs the selected cases and writes RESULTS.md.
pub fn run(o: &PaperOptions) -> Result<PaperRun, Failure> {
    let selected = o.selected()?;
    let mut reports = Vec::new();
    for case in selected {
        if o.verbose {
            eprintln!("paper case {}: {}", case.number, case.title);
        }
        reports.push(run_case(case.number, o)?);
    }
    let markdown = results_markdown(o, &reports);
    let results_path = o.results_path();
    atomic_write_bytes(&results_path, markdown.as_bytes())?;
    Ok(PaperRun {
        cases: reports,
        results_path,
        markdown,
    })
}
