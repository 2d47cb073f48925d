//! Running cases: the main run (tables, contact sheet), the sensitivity study (verdicts), and
//! writing the sheets, plots and RESULTS.md.
use crate::case_info::{CASES, CaseInfo};
use crate::options::PaperOptions;
use crate::outcome::{CaseReport, PaperRun};
use crate::report::results_markdown;
use crate::shot::{RunSpec, run_job};
use crate::study::{self, Config, Study};
use crate::verdict::{ClaimRun, decide};
use crate::{cases, plot, sheet};
use eyeadapt_sequencer::Failure;
use eyeadapt_sequencer::output::atomic_write_bytes;
use std::fmt::Write;
use std::path::Path;

/// Renders a case's jobs with one configuration and seed and measures them.
fn measure(case: &'static CaseInfo, spec: &RunSpec, dir: &Path) -> Result<CaseReport, Failure> {
    eyeadapt_sequencer::still::prepare_out_dir(dir)?;
    let runs = (0..case.jobs.len())
        .map(|i| run_job(case, i, spec, dir))
        .collect::<Result<Vec<_>, _>>()?;
    let mut report = cases::evaluate(case, &runs)?;
    if spec.write_files {
        let rows = cases::sheet_rows(case, &runs, &report);
        let name = format!("{}.png", case.slug);
        report.sheet = Some(name);
        // The caller writes the sheet into the output directory (see `run_case`).
        sheet::write_sheet(&dir.join("sheet.png"), &rows)?;
    }
    Ok(report)
}

/// Runs one case: the main run (baseline configuration, `o.seed`; the jobs' sizes, or the
/// quick ones) for the tables and contact sheet, then every configuration of the study with
/// every seed for the verdicts. Writes the sheet and the sensitivity plot into `o.out` and the
/// study's numbers to `<work>/<case>/study.csv`.
pub fn run_case(number: u32, o: &PaperOptions) -> Result<CaseReport, Failure> {
    let case = CASES
        .iter()
        .find(|c| c.number == number)
        .ok_or_else(|| Failure::Input(format!("there is no paper case {number}")))?;
    let dir = o.work_dir().join(case.slug);
    eyeadapt_sequencer::still::prepare_out_dir(&dir)?;
    eyeadapt_sequencer::still::prepare_out_dir(&o.out)?;
    let (params, configs) = crate::grids::case_grid(number, o.quick);
    let seeds = study::seeds(o.quick, o.seed);
    let eye = o.eye_samples.or(o.quick.then_some(case.quick_eye));
    let main_spec = RunSpec {
        config: &configs[0],
        seed: o.seed,
        sizes: if o.quick { Some(case.quick) } else { case.full },
        eye_samples: eye,
        write_files: true,
        verbose: o.verbose,
    };
    let mut report = measure(case, &main_spec, &dir)?;
    std::fs::rename(
        dir.join("sheet.png"),
        o.out.join(format!("{}.png", case.slug)),
    )
    .map_err(|e| Failure::Other(format!("moving {}'s contact sheet: {e}", case.slug)))?;
    let mut verdicts = Vec::new();
    let mut csv = String::from("config,seed,claim,check,value,bound,needs\n");
    for (ci, config) in configs.iter().enumerate() {
        let mut runs: Vec<Vec<ClaimRun>> = Vec::new();
        for &seed in &seeds {
            // The quick variant's main run is the baseline at the study's size: reuse it.
            let claims = if o.quick && ci == 0 && seed == o.seed {
                report.claims.clone()
            } else {
                let spec = RunSpec {
                    config,
                    seed,
                    sizes: Some(if o.quick { case.quick } else { case.study }),
                    eye_samples: if o.quick {
                        eye
                    } else {
                        o.eye_samples.or(case.study_eye)
                    },
                    write_files: false,
                    verbose: false,
                };
                let sub = dir
                    .join("study")
                    .join(config.slug())
                    .join(format!("s{seed}"));
                measure(case, &spec, &sub)?.claims
            };
            study_rows(&mut csv, config, &params, seed, &claims);
            runs.push(claims);
        }
        if o.verbose {
            eprintln!(
                "paper case {}: configuration {} of {} ({}) done",
                case.number,
                ci + 1,
                configs.len(),
                config.describe(&params)
            );
        }
        verdicts.push((config.clone(), decide(&runs)));
    }
    atomic_write_bytes(&dir.join("study.csv"), csv.as_bytes())?;
    let st = Study {
        params,
        configs: verdicts,
        seeds,
    };
    let svg = plot::sensitivity_svg(case, &st);
    let plot_name = format!("{}-sensitivity.svg", case.slug);
    atomic_write_bytes(&o.out.join(&plot_name), svg.as_bytes())?;
    report.verdicts = st.baseline().to_vec();
    report.study = Some(st);
    report.plot = Some(plot_name);
    Ok(report)
}

fn study_rows(
    csv: &mut String,
    config: &Config,
    params: &[study::Param],
    seed: u64,
    claims: &[ClaimRun],
) {
    let q = |s: &str| format!("\"{}\"", s.replace('"', "\"\""));
    for c in claims {
        for k in &c.checks {
            let _ = writeln!(
                csv,
                "{},{seed},{},{},{:e},{:e},{}",
                q(&config.describe(params)),
                q(&c.claim),
                q(&k.what),
                k.value,
                k.bound,
                if k.above { "above" } else { "below" }
            );
        }
    }
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
