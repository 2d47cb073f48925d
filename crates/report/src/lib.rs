//! `eyeadapt report DIR`: temporal-coherence metrics, filtered series, plots and an HTML page
//! for a sequence output directory (estimators.md §7–§8; what everything means: docs/report.md).
//!
//! Steps:
//! 1. read `manifest.json` and `adaptation.csv`; rows whose estimator contains `+` were derived
//!    by an earlier report and are dropped (and recomputed);
//!    The committed frames' rows must be exactly their record in `rows/` (checksummed in the
//!    manifest): a cut or edited CSV is refused (exit 2), as is any bad input below, before
//!    anything is written;
//! 2. apply the job's temporal filters (`settings.temporal_filters`) to every estimator's
//!    series; `adaptation.csv` is rewritten atomically with the other files (step 4): the
//!    committed frames' rows first, as they were, then the derived rows
//!    `<estimator>+<preset>` (same columns);
//! 3. §7.2 metrics of every series (raw and filtered), and §7.3 metrics of the adapted image
//!    sequence, reading the raw EXRs (CAT from the logged whites with the job's `cat` and
//!    `degree`; undefined whites adapt with D65, as the sequencer does);
//! 4. write `coherence.csv`, `coherence_frames.csv`, `plots/*.svg` and `report.html`;
//! 5. with `--video`, encode `video/*.mp4` with ffmpeg when it is on PATH (`--overlay`: with
//!    each frame's number and time).
//!
//! The directory is locked like a sequence run, so a report never races a render writing
//! the same CSV. Running the report twice gives the same files.
mod about;
mod coherence;
mod html;
pub mod locus;
mod metrics_table;
pub mod palette;
mod plots;
mod series;
mod summary;
mod table;
mod video;

pub use coherence::{EstimatorReport, Metric};
pub use series::{Point, Series};
pub use video::{VideoOutcome, label_strip};

use eyeadapt_color::{DEFAULT_SIGMA_S, DEFAULT_STRIDE, TemporalFilter};
use eyeadapt_sequencer::Failure;
use eyeadapt_sequencer::adapt::AdaptationSettings;
use eyeadapt_sequencer::manifest::{CSV, Manifest};
use eyeadapt_sequencer::output::atomic_write_bytes;
use eyeadapt_sequencer::sequence::lock_dir;
use std::collections::BTreeSet;
use std::path::{Path, PathBuf};
use std::sync::Arc;

/// A report step's name and, for steps that count, (done, total).
pub type StepFn = dyn Fn(&str, Option<(usize, usize)>) + Send + Sync;

/// Told where a report is, step by step.
#[derive(Clone)]
pub struct ReportProgress(pub Arc<StepFn>);

impl std::fmt::Debug for ReportProgress {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("ReportProgress")
    }
}

/// What `report` does besides the metrics.
#[derive(Clone, Debug)]
pub struct ReportOptions {
    /// Encode movies with ffmpeg.
    pub video: bool,
    /// With `video`: a strip under every movie naming each frame's number and time.
    pub overlay: bool,
    /// σ of the Gaussian in `hf_rms`, seconds.
    pub sigma_s: f64,
    /// The ffmpeg program (looked up on PATH unless it is a path).
    pub ffmpeg: PathBuf,
    /// Where the report is, for progress displays.
    pub progress: Option<ReportProgress>,
}

impl ReportOptions {
    fn step(&self, name: &str, count: Option<(usize, usize)>) {
        if let Some(p) = &self.progress {
            (p.0)(name, count);
        }
    }
}

impl Default for ReportOptions {
    fn default() -> Self {
        ReportOptions {
            video: false,
            overlay: false,
            sigma_s: DEFAULT_SIGMA_S,
            ffmpeg: PathBuf::from("ffmpeg"),
            progress: None,
        }
    }
}

/// What `report` wrote.
#[derive(Clone, Debug)]
pub struct ReportSummary {
    /// Every series measured, raw then filtered.
    pub estimators: Vec<String>,
    pub frames: usize,
    /// Rows appended to adaptation.csv for the filtered series.
    pub derived_rows: usize,
    /// Lab white luminance of the image metrics; `None` when they were not computed.
    pub y_n: Option<f64>,
    /// Files written (report.html, CSVs, plots), relative to the directory.
    pub files: Vec<String>,
    /// Things the user should know (skipped parts, dropped rows).
    pub notes: Vec<String>,
    pub video: VideoOutcome,
    /// The measured metrics, one per series.
    pub reports: Vec<EstimatorReport>,
}

fn adaptation_of(m: &Manifest) -> AdaptationSettings {
    AdaptationSettings {
        cat: m.settings.cat,
        degree: m.settings.degree,
    }
}

/// Computes the coherence report of the sequence in `dir`.
pub fn report(dir: &Path, opts: &ReportOptions) -> Result<ReportSummary, Failure> {
    let m = checked_manifest(dir, opts)?;
    let _lock = lock_dir(dir)?;
    let adaptation = adaptation_of(&m);
    let presets = series::presets(&m);
    let mut notes = Vec::new();

    // 1. The CSV.
    opts.step("adaptation.csv and temporal filters", None);
    let csv_path = dir.join(CSV);
    let text = eyeadapt_scene::read_input_text(&csv_path)
        .map_err(|e| Failure::input_io("cannot read", &csv_path, &e))?;
    let committed: BTreeSet<u32> = m.frames.keys().copied().collect();
    let tab = table::parse(&text, &csv_path, &committed)?;
    table::check_committed(&tab, dir, &m, &csv_path)?;
    let base = series::base_series(&m, &tab);
    table_notes(&tab, &base, &mut notes);

    // 2. Filters, and the CSV text with the derived rows (written with the other files, once
    // every input has been read and checked).
    let (all, derived_rows, csv) = filter_series(&text, &tab, &base, &presets)?;

    // 3. Metrics.
    let on_frame = |done, total| opts.step("image metrics (raw EXRs)", Some((done, total)));
    let image = series::image_pass(dir, &m, &all, &adaptation, DEFAULT_STRIDE, &on_frame)?;
    let image = match image {
        Ok(p) => Some(p),
        Err(why) => {
            notes.push(format!("image metrics (§7.3) not computed: {why}"));
            None
        }
    };
    let mut reports = Vec::with_capacity(all.len());
    for (k, s) in all.iter().enumerate() {
        reports.push(EstimatorReport {
            name: s.name.clone(),
            base: s.base.clone(),
            filter: s.filter.clone(),
            series: series::metrics_of(s, m.fps, opts.sigma_s)?,
            image: image.as_ref().map(|p| p.metrics[k].clone()),
            steps: series::steps(s),
        });
    }

    // 4. Files: nothing is written before this point.
    opts.step("plots and report.html", None);
    let files = write_files(
        dir,
        csv.as_deref(),
        &Written {
            manifest: &m,
            all: &all,
            reports: &reports,
            presets: &presets,
            image: image.as_ref(),
            notes: &notes,
            sigma_s: opts.sigma_s,
        },
    )?;

    // 5. Video.
    let video = if opts.video {
        opts.step("video (ffmpeg)", None);
        video::videos(dir, &m, &opts.ffmpeg, opts.overlay)?
    } else {
        VideoOutcome::NotRequested
    };

    Ok(ReportSummary {
        estimators: all.iter().map(|s| s.name.clone()).collect(),
        frames: m.frames.len(),
        derived_rows,
        y_n: image.as_ref().map(|p| p.y_n),
        files,
        notes,
        video,
        reports,
    })
}

/// The directory's manifest, checked for what the report needs (and `opts` with it).
fn checked_manifest(dir: &Path, opts: &ReportOptions) -> Result<Manifest, Failure> {
    if !(opts.sigma_s.is_finite() && opts.sigma_s >= 0.0) {
        return Err(Failure::Input(format!(
            "--sigma-s {} must be a number of seconds >= 0",
            opts.sigma_s
        )));
    }
    if dir.exists() && !dir.is_dir() {
        return Err(Failure::Input(format!(
            "{} is not a directory: report takes a sequence output directory (with manifest.json)",
            dir.display()
        )));
    }
    let m = Manifest::load(dir)?.ok_or_else(|| {
        Failure::Input(format!(
            "{}: no manifest.json (not an eyeadapt sequence output)",
            dir.display()
        ))
    })?;
    if m.frames.is_empty() {
        return Err(Failure::Input(format!(
            "{}: no committed frames to report on",
            dir.display()
        )));
    }
    let file = dir.join(eyeadapt_sequencer::manifest::MANIFEST);
    if !(m.fps.is_finite() && m.fps > 0.0) {
        return Err(Failure::Input(format!(
            "{}: manifest fps {} is not positive",
            file.display(),
            m.fps
        )));
    }
    if m.fps > eyeadapt_scene::MAX_FPS {
        return Err(Failure::Input(format!(
            "{}: manifest fps {:e} is above the {} a sequence may have",
            file.display(),
            m.fps,
            eyeadapt_scene::MAX_FPS
        )));
    }
    // The smoothing window (σ·fps frames) is allocated: bound it before anything is read.
    if opts.sigma_s * m.fps > eyeadapt_color::MAX_SIGMA_FRAMES {
        return Err(Failure::Input(format!(
            "--sigma-s {:e} s at the sequence's {} fps ({}) is a Gaussian of σ = {:e} frames, \
             more than the {} frames the report smooths with",
            opts.sigma_s,
            m.fps,
            file.display(),
            opts.sigma_s * m.fps,
            eyeadapt_color::MAX_SIGMA_FRAMES
        )));
    }
    Ok(m)
}

/// Notes on rows left out and on series with undefined whites.
fn table_notes(tab: &table::Table, base: &[Series], notes: &mut Vec<String>) {
    if tab.dropped_uncommitted > 0 {
        notes.push(format!(
            "{} row(s) of frames not committed in the manifest were left out",
            tab.dropped_uncommitted
        ));
    }
    if tab.dropped_duplicates > 0 {
        notes.push(format!(
            "{} duplicate row(s) (same frame and estimator) were left out; the first one counts",
            tab.dropped_duplicates
        ));
    }
    for s in base {
        let n = s.points.iter().filter(|p| p.white.is_some()).count();
        if n < s.points.len() {
            notes.push(format!(
                "{}: {} of {} frame(s) have no defined white (adapted with D65; they split the series)",
                s.name,
                s.points.len() - n,
                s.points.len()
            ));
        }
    }
}

/// Every series, raw then filtered, the number of derived rows, and the new CSV text (the
/// committed rows first, as they were, then the derived rows) when it differs from `text`.
fn filter_series(
    text: &str,
    tab: &table::Table,
    base: &[Series],
    presets: &[TemporalFilter],
) -> Result<(Vec<Series>, usize, Option<String>), Failure> {
    let mut all = base.to_vec();
    let mut derived: Vec<(u32, usize, String)> = Vec::new();
    for f in presets {
        for s in base {
            let (fs, rows) = series::filtered(s, *f, tab)?;
            let order = all.len();
            derived.extend(rows.into_iter().map(|(frame, r)| (frame, order, r)));
            all.push(fs);
        }
    }
    derived.sort_by_key(|(frame, order, _)| (*frame, *order));
    let mut csv = String::with_capacity(text.len() + derived.len() * 200);
    csv.push_str(eyeadapt_sequencer::adapt::CSV_HEADER);
    csv.push('\n');
    for r in &tab.rows {
        csv.push_str(&r.line);
        csv.push('\n');
    }
    for (_, _, r) in &derived {
        csv.push_str(r);
    }
    let n = derived.len();
    Ok((all, n, (csv != text).then_some(csv)))
}

/// What the report's files are made of.
struct Written<'a> {
    manifest: &'a Manifest,
    all: &'a [Series],
    reports: &'a [EstimatorReport],
    presets: &'a [TemporalFilter],
    image: Option<&'a series::ImagePass>,
    notes: &'a [String],
    sigma_s: f64,
}

/// Writes adaptation.csv (when `csv` is new text for it), coherence.csv,
/// coherence_frames.csv, the plots and report.html, all computed before the first write;
/// returns the paths of the report's files relative to `dir`.
fn write_files(dir: &Path, csv: Option<&str>, w: &Written) -> Result<Vec<String>, Failure> {
    let (m, all, reports) = (w.manifest, w.all, w.reports);
    let filters: Vec<String> = w.presets.iter().map(|f| f.to_string()).collect();
    let figures = plots::figures(all, reports, &filters, m.fps, w.image.is_some())?;
    let page = html::page(&html::Page {
        manifest: m,
        reports,
        plots: &figures,
        notes: w.notes,
        y_n: w.image.map(|p| p.y_n),
        omega: w.image.map(|p| (p.width, p.height, p.omega_pixels)),
        sigma_s: w.sigma_s,
    });
    if let Some(csv) = csv {
        atomic_write_bytes(&dir.join(CSV), csv.as_bytes())?;
    }
    let mut files = Vec::new();
    let mut put = |rel: &str, bytes: &[u8]| -> Result<(), Failure> {
        atomic_write_bytes(&dir.join(rel), bytes)?;
        files.push(rel.to_string());
        Ok(())
    };
    put(
        "coherence.csv",
        coherence::coherence_csv(reports).as_bytes(),
    )?;
    put(
        "coherence_frames.csv",
        coherence::frames_csv(all, reports).as_bytes(),
    )?;
    for f in &figures {
        put(&format!("plots/{}.svg", f.file), f.svg.as_bytes())?;
    }
    put("report.html", page.as_bytes())?;
    Ok(files)
}
