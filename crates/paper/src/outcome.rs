//! What a case found: its claims' verdicts, numbers and write-up.
use crate::case_info::CaseInfo;
use crate::study::Study;
use crate::verdict::{ClaimRun, Outcome, Verdict};
use std::collections::BTreeMap;
use std::path::PathBuf;

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
    /// The claims' checks on this run's numbers (one seed, one configuration).
    pub claims: Vec<ClaimRun>,
    /// The claims decided on the baseline configuration over the study's seeds.
    pub verdicts: Vec<Verdict>,
    /// The sensitivity study (every configuration, every seed).
    pub study: Option<Study>,
    /// Contact-sheet file name (relative to the output directory).
    pub sheet: Option<String>,
    /// Sensitivity plot file name (SVG, relative to the output directory).
    pub plot: Option<String>,
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

    /// Every claim holds on the baseline over the seeds.
    pub fn all_hold(&self) -> bool {
        !self.verdicts.is_empty() && self.verdicts.iter().all(|v| v.outcome == Outcome::Holds)
    }
}

/// Everything `eyeadapt paper` produced.
#[derive(Debug)]
pub struct PaperRun {
    pub cases: Vec<CaseReport>,
    pub results_path: PathBuf,
    pub markdown: String,
}
