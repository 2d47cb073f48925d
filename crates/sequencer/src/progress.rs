//! Progress for people and for farm managers.
//!
//! On a terminal: an indicatif bar (frames, ETA, samples/s). Otherwise one line per event in
//! forms existing parsers know: `Fra:N …` and `Saved: '<path>'` (Blender, Flamenco),
//! `Progress: P%` (Deadline's stdout handler), or with `--log-format openjd` the OpenJD
//! directives `openjd_progress: P` and `openjd_status: …`. Farm lines go to stdout, flushed
//! per line; errors go to stderr.
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use std::io::{IsTerminal, Write};

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LogFormat {
    Plain,
    Openjd,
}

pub struct Progress {
    bar: Option<ProgressBar>,
    format: LogFormat,
    total: usize,
    done: usize,
}

impl Progress {
    /// `total` frames to render in this run; a bar only when stderr is a terminal.
    pub fn new(total: usize, format: LogFormat, force_plain: bool) -> Progress {
        let tty = std::io::stderr().is_terminal() && !force_plain;
        let bar = tty.then(|| {
            let b = ProgressBar::with_draw_target(Some(total as u64), ProgressDrawTarget::stderr());
            b.set_style(
                ProgressStyle::with_template(
                    "{spinner} frames {pos}/{len} [{elapsed_precise}] eta {eta} {msg}",
                )
                .expect("static template"),
            );
            b
        });
        Progress {
            bar,
            format,
            total,
            done: 0,
        }
    }

    fn line(&self, s: &str) {
        if let Some(b) = &self.bar {
            b.suspend(|| println!("{s}"));
        } else {
            let mut out = std::io::stdout().lock();
            let _ = writeln!(out, "{s}");
            let _ = out.flush();
        }
    }

    pub fn frame_started(&self, frame: u32, index: usize) {
        if self.bar.is_none() {
            match self.format {
                LogFormat::Plain => self.line(&format!(
                    "Fra:{frame} rendering ({}/{})",
                    index + 1,
                    self.total
                )),
                LogFormat::Openjd => self.line(&format!(
                    "openjd_status: frame {frame} ({}/{})",
                    index + 1,
                    self.total
                )),
            }
        }
    }

    pub fn saved(&self, path: &std::path::Path) {
        if self.bar.is_none() {
            self.line(&format!("Saved: '{}'", path.display()));
        }
    }

    pub fn frame_done(&mut self, frame: u32, seconds: f64, samples_per_s: f64, summary: &str) {
        self.done += 1;
        let pct = (self.done * 100).checked_div(self.total).unwrap_or(100);
        match &self.bar {
            Some(b) => {
                b.set_message(format!(
                    "{:.2} M samples/s  frame {frame}: {summary}",
                    samples_per_s / 1e6
                ));
                b.inc(1);
            }
            None => {
                self.line(&format!(
                    "Fra:{frame} done in {seconds:.2} s ({:.2} M samples/s) {summary}",
                    samples_per_s / 1e6
                ));
                match self.format {
                    LogFormat::Plain => self.line(&format!("Progress: {pct}%")),
                    LogFormat::Openjd => self.line(&format!("openjd_progress: {pct}")),
                }
            }
        }
    }

    pub fn note(&self, s: &str) {
        self.line(s);
    }

    pub fn finish(&self) {
        if let Some(b) = &self.bar {
            b.finish_and_clear();
        }
    }
}
