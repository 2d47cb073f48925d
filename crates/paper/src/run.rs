//! Running cases and writing their sheets and RESULTS.md.
use crate::case_info::CASES;
use crate::options::PaperOptions;
use crate::outcome::{CaseReport, PaperRun};
use crate::report::results_markdown;
use crate::shot::run_job;
use crate::{cases, sheet};
use eyeadapt_sequencer::Failure;
use eyeadapt_sequencer::output::atomic_write_bytes;

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
