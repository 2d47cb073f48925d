//! `eyeadapt report DIR`, also run at the end of a complete `eyeadapt sequence`.
use crate::args::ReportArgs;
use eyeadapt_report::{ReportOptions, VideoOutcome, report};
use eyeadapt_sequencer::Failure;
use std::path::Path;

pub fn run(a: ReportArgs) -> Result<(), Failure> {
    let opts = ReportOptions {
        video: a.video,
        sigma_s: a.sigma_s,
        ..ReportOptions::default()
    };
    write_report(&a.dir, &opts)
}

/// Runs the report and prints what it wrote.
pub fn write_report(dir: &Path, opts: &ReportOptions) -> Result<(), Failure> {
    let t = std::time::Instant::now();
    let s = report(dir, opts)?;
    for n in &s.notes {
        println!("report: note: {n}");
    }
    println!(
        "report: {} series ({} derived rows) over {} frame(s) in {:.1} s -> {}",
        s.estimators.len(),
        s.derived_rows,
        s.frames,
        t.elapsed().as_secs_f64(),
        dir.join("report.html").display()
    );
    match &s.video {
        VideoOutcome::NotRequested => {}
        VideoOutcome::Skipped(why) => println!("report: {why}"),
        VideoOutcome::Written { files, problems } => {
            for f in files {
                println!("report: wrote {}", f.display());
            }
            for p in problems {
                println!("report: video problem: {p}");
            }
        }
    }
    Ok(())
}
