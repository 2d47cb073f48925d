//! `eyeadapt report DIR`, also run at the end of a complete `eyeadapt sequence`.
//!
//! Every report leaves `report.stamp`: the checksums of `manifest.json` and `adaptation.csv`
//! as the report left them, the report options and the tool version. A rerun of a finished
//! `sequence` skips the report while the stamp matches and `report.html` is there (nothing
//! changed); `eyeadapt report` always recomputes.
use crate::args::ReportArgs;
use eyeadapt_report::{ReportOptions, ReportProgress, VideoOutcome, report};
use eyeadapt_sequencer::Failure;
use eyeadapt_sequencer::manifest::{CSV, MANIFEST, checksum};
use eyeadapt_sequencer::output::atomic_write_bytes;
use eyeadapt_sequencer::progress::LogFormat;
use indicatif::{ProgressBar, ProgressStyle};
use std::io::IsTerminal;
use std::path::Path;
use std::sync::{Arc, Mutex};

const STAMP: &str = "report.stamp";

pub fn run(a: ReportArgs) -> Result<(), Failure> {
    let opts = ReportOptions {
        video: a.video,
        overlay: a.overlay,
        sigma_s: a.sigma_s,
        progress: progress_lines(LogFormat::Plain, false),
        ..ReportOptions::default()
    };
    write_report(&a.dir, &opts)
}

/// The report's progress: a line per step (`openjd_status: report: …` with `log`
/// openjd), counted steps as a bar on a terminal (unless `no_bar`), else a line at each
/// quarter.
pub fn progress_lines(log: LogFormat, no_bar: bool) -> Option<ReportProgress> {
    let tty = std::io::stderr().is_terminal() && !no_bar;
    let bar: Mutex<Option<(String, ProgressBar, usize)>> = Mutex::new(None);
    let say = move |s: String| match log {
        LogFormat::Plain => println!("report: {s}"),
        LogFormat::Openjd => println!("openjd_status: report: {s}"),
    };
    Some(ReportProgress(Arc::new(move |step, count| {
        let mut bar = bar.lock().expect("report progress lock");
        let Some((done, total)) = count else {
            if let Some((_, b, _)) = bar.take() {
                b.finish_and_clear();
            }
            say(step.to_string());
            return;
        };
        let same = bar.as_ref().is_some_and(|(s, ..)| s == step);
        if !same {
            if let Some((_, b, _)) = bar.take() {
                b.finish_and_clear();
            }
            let b = if tty {
                let b = ProgressBar::new(total as u64);
                b.set_style(
                    ProgressStyle::with_template("report: {msg} {bar:30} {pos}/{len}")
                        .expect("static template"),
                );
                b.set_message(step.to_string());
                b
            } else {
                ProgressBar::hidden()
            };
            *bar = Some((step.to_string(), b, 0));
        }
        let (_, b, quarter) = bar.as_mut().expect("set above");
        b.set_position(done as u64);
        let q = 4 * done / total.max(1);
        if !tty && q > *quarter {
            *quarter = q;
            say(format!("{step} {done}/{total}"));
        }
        if done >= total {
            b.finish_and_clear();
        }
    })))
}

/// What the report of `dir` with `opts` is computed from, as the text of `report.stamp`;
/// `None` when the directory lacks a manifest or CSV.
fn stamp(dir: &Path, opts: &ReportOptions) -> Option<String> {
    let sum = |name: &str| std::fs::read(dir.join(name)).ok().map(|b| checksum(&b));
    Some(format!(
        "eyeadapt {}\nmanifest.json {}\nadaptation.csv {}\nvideo {} overlay {} sigma_s {}\n",
        env!("CARGO_PKG_VERSION"),
        sum(MANIFEST)?,
        sum(CSV)?,
        opts.video,
        opts.overlay,
        opts.sigma_s
    ))
}

/// Writes the report unless `report.stamp` says the one there is from the same inputs.
pub fn report_unless_current(dir: &Path, opts: &ReportOptions) -> Result<(), Failure> {
    let current = dir.join("report.html").is_file()
        && stamp(dir, opts)
            .is_some_and(|s| std::fs::read(dir.join(STAMP)).is_ok_and(|b| b == s.as_bytes()));
    if current {
        println!(
            "report: {} is up to date (nothing changed since it was written; `eyeadapt report {}` redoes it)",
            dir.join("report.html").display(),
            dir.display()
        );
        return Ok(());
    }
    write_report(dir, opts)
}

/// Runs the report and prints what it wrote.
pub fn write_report(dir: &Path, opts: &ReportOptions) -> Result<(), Failure> {
    let t = std::time::Instant::now();
    println!("report: writing the coherence report of {}", dir.display());
    let s = report(dir, opts)?;
    if let Some(text) = stamp(dir, opts) {
        atomic_write_bytes(&dir.join(STAMP), text.as_bytes())?;
    }
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
    // Videos asked for but not made fail the command (exit 1) once everything else is
    // written, so a scripted job cannot succeed without them.
    match &s.video {
        VideoOutcome::NotRequested => Ok(()),
        VideoOutcome::Skipped(why) => Err(Failure::Other(format!("report --video: {why}"))),
        VideoOutcome::Written { files, problems } => {
            for f in files {
                println!("report: wrote {}", f.display());
            }
            match problems.as_slice() {
                [] => Ok(()),
                ps => Err(Failure::Other(format!(
                    "report --video: {} movie(s) not written: {}",
                    ps.len(),
                    ps.join("; ")
                ))),
            }
        }
    }
}
