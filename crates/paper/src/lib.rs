//! `eyeadapt paper`: renders the six test cases of Gruson, Ribardière & Cozot 2013 (§5) and
//! checks each of the paper's claims against measured numbers (docs/paper.md).
//!
//! Every case is a job file in `configs/` (embedded here, so the command runs from any
//! directory) over a built-in scene. For each case [`run_case`] renders the job's frames, runs
//! every estimator, writes the per-frame CSV and the raw EXRs into the work directory, measures
//! what the paper measured, and returns a [`CaseReport`]: the claim, a markdown section with the
//! numbers, machine-readable metrics and the checks of every claim. Every case is also run
//! over a sensitivity study (what the paper's text leaves open, several seeds per
//! configuration): its verdicts — holds, does not hold, within noise — carry margins and
//! standard errors, and each claim a robustness fraction. [`run`](fn@run) does all six cases, writes
//! a contact sheet and a sensitivity plot per case and `RESULTS.md`.
//!
//! Output depends only on the seed and the variant (`--quick` or not): no timestamps or
//! timings go into `RESULTS.md` or the sheets, and the renderer is bit-deterministic, so the
//! same seed gives byte-identical files.

/// The six cases: job files and quick sizes.
mod case_info;
/// What each case measures and judges, one file per case.
mod cases;
/// Each case's sensitivity grid.
mod grids;
/// Image regions and their mean colours.
mod measure;
/// What to run and where to write.
mod options;
/// A case's verdicts, numbers and write-up.
mod outcome;
/// The sensitivity plot (SVG).
mod plot;
/// RESULTS.md.
mod report;
/// Running cases: render, measure, judge, write.
mod run;
/// Contact sheets (raw | WCAM | eye).
mod sheet;
/// A case's jobs rendered frame by frame through the pipeline.
mod shot;
/// The sensitivity study: parameters the paper leaves open, their grid, robustness.
mod study;
/// Claims, checks, and verdicts with their uncertainty.
mod verdict;

pub use crate::case_info::{CASES, CaseInfo};
pub use crate::grids::case_grid;
pub use crate::measure::{Region, RegionMean, equal_luminance_hsv, region_mean};
pub use crate::options::{PaperOptions, variant_description};
pub use crate::outcome::{CaseReport, PaperRun};
pub use crate::report::results_markdown;
pub use crate::run::{run, run_case};
pub(crate) use crate::shot::{JobRun, Named, Shot};
pub use crate::study::{Config, Level, Param, Study};
pub use crate::verdict::{Check, CheckStat, ClaimRun, Outcome, Verdict, decide};
