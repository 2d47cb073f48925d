//! Progress for people and for farm managers.
//!
//! A run starts with one line naming the job, the scene, the frames to do and already done,
//! the output directory and the thread count. On a terminal two indicatif bars follow: the
//! frames, with an ETA from the frames done so far, and the rows of the frame in flight.
//! Otherwise one line per event, in forms existing parsers know, on stdout, flushed per line:
//!
//! | event | `--log-format plain` | `--log-format openjd` |
//! |---|---|---|
//! | start-up, notes | the text | `openjd_status: <text>` |
//! | a frame starts | `Fra:N rendering (i/n)` | `openjd_status: frame N (i/n)` |
//! | inside a frame (each quarter of its rows, and every 2 s) | `Fra:N \| rows r/h \| Remaining:HH:MM:SS \| Progress: P%` | `openjd_progress: P` |
//! | a file is written | `Saved: '<path>'` (Blender, Flamenco) | the same |
//! | a frame is committed | `Fra:N done in … \| d/n frames \| Remaining:HH:MM:SS`, then `Progress: P%` (Deadline's handler) | the same, then `openjd_progress: P` |
//!
//! `P` counts the frames of this run, the one in flight by its rows; `Remaining` is the mean
//! time of the frames done so far times the frames left (before the first frame is done, the
//! frame in flight's rate). Errors go to stderr.
use indicatif::{MultiProgress, ProgressBar, ProgressDrawTarget, ProgressStyle};
use std::io::{IsTerminal, Write};
use std::sync::Mutex;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::{Duration, Instant};

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LogFormat {
    Plain,
    Openjd,
}

/// Longest quiet stretch inside a frame on a farm log.
const TICK: Duration = Duration::from_secs(2);

struct Bars {
    multi: MultiProgress,
    frames: ProgressBar,
    rows: ProgressBar,
}

pub struct Progress {
    bars: Option<Bars>,
    format: LogFormat,
    total: usize,
    done: usize,
    /// Seconds the frames done in this run took.
    frame_seconds: f64,
    /// The frame in flight: number, rows, start.
    frame: u32,
    rows_total: usize,
    rows: AtomicUsize,
    frame_start: Instant,
    /// When the last in-frame line was printed, and the last quarter printed.
    last_line: Mutex<(Instant, usize)>,
}

fn style(template: &str) -> ProgressStyle {
    ProgressStyle::with_template(template).expect("static template")
}

/// `HH:MM:SS`, or `--:--:--` when unknown.
pub fn hms(seconds: Option<f64>) -> String {
    match seconds {
        Some(s) if s.is_finite() && s >= 0.0 => {
            let s = s.round() as u64;
            format!("{:02}:{:02}:{:02}", s / 3600, s / 60 % 60, s % 60)
        }
        _ => "--:--:--".into(),
    }
}

impl Progress {
    /// `total` frames to render in this run; bars only when stderr is a terminal.
    pub fn new(total: usize, format: LogFormat, force_plain: bool) -> Progress {
        let tty = std::io::stderr().is_terminal() && !force_plain;
        let bars = tty.then(|| {
            let multi = MultiProgress::with_draw_target(ProgressDrawTarget::stderr());
            let frames = multi.add(ProgressBar::new(total as u64));
            frames.set_style(style(
                "frames {pos}/{len} [{elapsed_precise}] {bar:30} ETA {prefix} {msg}",
            ));
            frames.set_prefix(hms(None));
            let rows = multi.add(ProgressBar::new(0));
            rows.set_style(style("{prefix:>12} {bar:30} rows {pos}/{len} {msg}"));
            Bars {
                multi,
                frames,
                rows,
            }
        });
        let now = Instant::now();
        Progress {
            bars,
            format,
            total,
            done: 0,
            frame_seconds: 0.0,
            frame: 0,
            rows_total: 0,
            rows: AtomicUsize::new(0),
            frame_start: now,
            last_line: Mutex::new((now, 0)),
        }
    }

    fn line(&self, s: &str) {
        match &self.bars {
            Some(b) => {
                let _ = b.multi.println(s);
            }
            None => {
                let mut out = std::io::stdout().lock();
                let _ = writeln!(out, "{s}");
                let _ = out.flush();
            }
        }
    }

    /// A note (start-up line, resume, stop) as one line of the log's form.
    pub fn note(&self, s: &str) {
        match (self.bars.is_some(), self.format) {
            (false, LogFormat::Openjd) => self.line(&format!("openjd_status: {s}")),
            _ => self.line(s),
        }
    }

    /// Seconds left: the mean of the frames done times the frames left, the frame in flight
    /// counted by `frac` (its share of rows done).
    fn remaining(&self, frac: f64) -> Option<f64> {
        let left = (self.total - self.done) as f64 - frac;
        if self.done > 0 {
            Some(self.frame_seconds / self.done as f64 * left)
        } else if frac > 0.0 {
            Some(self.frame_start.elapsed().as_secs_f64() / frac * left)
        } else {
            None
        }
    }

    fn percent(&self, frac: f64) -> usize {
        if self.total == 0 {
            return 100;
        }
        ((self.done as f64 + frac) * 100.0 / self.total as f64).floor() as usize
    }

    /// Frame `frame` (`index` of this run's frames, from 0) starts; it has `rows` rows.
    pub fn frame_started(&mut self, frame: u32, index: usize, rows: usize) {
        self.frame = frame;
        self.rows_total = rows.max(1);
        self.rows.store(0, Ordering::Relaxed);
        self.frame_start = Instant::now();
        *self.last_line.lock().expect("progress lock") = (self.frame_start, 0);
        match (&self.bars, self.format) {
            (Some(b), _) => {
                b.rows.set_message("");
                b.rows.reset();
                b.rows.set_length(rows as u64);
                b.rows.set_prefix(format!("frame {frame}"));
            }
            (None, LogFormat::Plain) => self.line(&format!(
                "Fra:{frame} rendering ({}/{})",
                index + 1,
                self.total
            )),
            (None, LogFormat::Openjd) => self.line(&format!(
                "openjd_status: frame {frame} ({}/{})",
                index + 1,
                self.total
            )),
        }
    }

    /// One more row of the frame in flight is done (callable from any thread).
    pub fn row_done(&self) {
        let r = self.rows.fetch_add(1, Ordering::Relaxed) + 1;
        let frac = r as f64 / self.rows_total as f64;
        if let Some(b) = &self.bars {
            b.rows.inc(1);
            b.frames.set_prefix(hms(self.remaining(frac)));
            return;
        }
        let quarter = 4 * r / self.rows_total;
        let mut last = self.last_line.lock().expect("progress lock");
        if r >= self.rows_total || (quarter <= last.1 && last.0.elapsed() < TICK) {
            return;
        }
        *last = (Instant::now(), quarter.max(last.1));
        let pct = self.percent(frac);
        match self.format {
            LogFormat::Plain => self.line(&format!(
                "Fra:{} | rows {r}/{} | Remaining:{} | Progress: {pct}%",
                self.frame,
                self.rows_total,
                hms(self.remaining(frac))
            )),
            LogFormat::Openjd => self.line(&format!("openjd_progress: {pct}")),
        }
    }

    /// The image is done and the estimators run.
    pub fn estimating(&self) {
        if let Some(b) = &self.bars {
            b.rows.set_message("estimators (eye sensor)");
        }
    }

    pub fn saved(&self, path: &std::path::Path) {
        if self.bars.is_none() {
            self.line(&format!("Saved: '{}'", path.display()));
        }
    }

    pub fn frame_done(&mut self, frame: u32, seconds: f64, samples_per_s: f64, summary: &str) {
        self.done += 1;
        self.frame_seconds += seconds;
        let pct = self.percent(0.0);
        let eta = hms(self.remaining(0.0));
        match &self.bars {
            Some(b) => {
                b.frames.set_prefix(eta);
                b.frames.set_message(format!(
                    "{:.2} M samples/s  frame {frame}: {summary}",
                    samples_per_s / 1e6
                ));
                b.frames.inc(1);
            }
            None => {
                self.line(&format!(
                    "Fra:{frame} done in {seconds:.2} s ({:.2} M samples/s) {summary} | {}/{} frames | Remaining:{eta}",
                    samples_per_s / 1e6,
                    self.done,
                    self.total
                ));
                match self.format {
                    LogFormat::Plain => self.line(&format!("Progress: {pct}%")),
                    LogFormat::Openjd => self.line(&format!("openjd_progress: {pct}")),
                }
            }
        }
    }

    pub fn finish(&self) {
        if let Some(b) = &self.bars {
            b.rows.finish_and_clear();
            b.frames.finish_and_clear();
            let _ = b.multi.clear();
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hms_and_remaining_time_from_the_frames_done() {
        assert_eq!(hms(Some(3725.4)), "01:02:05");
        assert_eq!(hms(None), "--:--:--");
        assert_eq!(hms(Some(f64::NAN)), "--:--:--");
        let mut p = Progress::new(4, LogFormat::Plain, true);
        assert_eq!(p.remaining(0.0), None);
        p.done = 2;
        p.frame_seconds = 6.0;
        // 3 s per frame, 1.5 frames left.
        assert_eq!(p.remaining(0.5), Some(4.5));
        assert_eq!(p.percent(0.5), 62);
        assert_eq!(Progress::new(0, LogFormat::Plain, true).percent(0.0), 100);
    }
}
