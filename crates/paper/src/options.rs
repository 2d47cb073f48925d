//! What `eyeadapt paper` runs and where it writes.
use crate::case_info::{CASES, CaseInfo};
use eyeadapt_sequencer::Failure;
use std::path::PathBuf;

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

    pub(crate) fn selected(&self) -> Result<Vec<&'static CaseInfo>, Failure> {
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

/// The settings of the variant, as RESULTS.md states them.
pub fn variant_description(o: &PaperOptions) -> String {
    let mut s = String::new();
    s.push_str(if o.quick {
        "quick variant (`eyeadapt paper --quick`): small images, few samples and eye-sensor paths, a reduced study with 3 seeds per configuration; the numbers are noisier than the full run's"
    } else {
        "full variant (`eyeadapt paper`): tables from the job files' resolutions and sample counts, verdicts from the sensitivity study at reduced sizes with 4 seeds per configuration"
    });
    s.push_str(&format!(", seed {}", o.seed));
    if let Some(n) = o.eye_samples {
        s.push_str(&format!(", {n} eye-sensor paths per frame"));
    }
    s
}
