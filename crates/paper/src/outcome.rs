//! What a case found: its claims' verdicts, numbers and write-up.
use crate::case_info::CaseInfo;
use std::collections::BTreeMap;
use std::path::PathBuf;

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
