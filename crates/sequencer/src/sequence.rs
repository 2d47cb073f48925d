//! `eyeadapt sequence`: render a camera path frame by frame, resumable and farm-friendly.
//!
//! Per frame, in this order: render; run every estimator; write the raw EXR/PNG and the
//! adapted images (each to a temporary name, then renamed); write the frame's CSV rows to
//! `rows/frame_NNNNNN.csv`; append the same rows to `adaptation.csv` in one `write` call; then
//! atomically rewrite `manifest.json` with the frame's files and checksums. Only then is the
//! frame committed. A SIGKILL during the append can still cut it short (Linux ends a write to
//! a regular file early when a fatal signal arrives between two of its pages), but only the
//! rows of the uncommitted frame in flight: the committed frames' rows before them are whole.
//!
//! On start, frames in the manifest whose files are intact are skipped, and `adaptation.csv`
//! is rebuilt from the committed frames' row files if it holds anything else (rows of the
//! frame that was in flight when a run was killed). A job whose hash differs from the
//! directory's manifest is refused unless `--force`.
use crate::adapt::{CSV_HEADER, Reading};
use crate::error::Failure;
use crate::frames::FrameSet;
use crate::job::Job;
use crate::manifest::{CSV, FileEntry, FrameEntry, Manifest, file_entry};
use crate::output::atomic_write_bytes;
use crate::pipeline::{
    FrameResult, FrameScenes, FrameStep, Layout, WriteSpec, frame_name, write_images,
};
use crate::progress::{LogFormat, Progress};
use crate::settings::RunSettings;
use crate::stop::StopRequest;
use eyeadapt_tracer::SceneData;
use rayon::prelude::*;
use std::fs::OpenOptions;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::time::Instant;

#[derive(Clone, Debug)]
pub struct SequenceOptions {
    pub out: PathBuf,
    /// `--frames` / `--start --end --step`: narrows the job's frames.
    pub selection: Option<FrameSet>,
    /// `--chunk-size N --chunk-index I`.
    pub chunk: Option<(usize, usize)>,
    pub force: bool,
    /// Re-hash committed files on resume instead of checking sizes only.
    pub verify: bool,
    pub log_format: LogFormat,
    pub plain_progress: bool,
    /// Checked before each frame: a signal handler's request to stop.
    pub stop: Option<Arc<StopRequest>>,
}

#[derive(Clone, Debug, Default)]
pub struct SequenceSummary {
    pub planned: usize,
    pub rendered: usize,
    pub skipped: usize,
    pub seconds: f64,
    pub render_seconds: f64,
    /// Every frame of the job's selection is committed in this directory.
    pub complete: bool,
    /// The signal that stopped the run before all its frames were done.
    pub stopped: Option<i32>,
}

/// (frames this run is responsible for, the job's whole selection): the job's frames
/// narrowed by `selection`, then chunk `(size, index)` of them.
pub fn plan_frames(
    job: &Job,
    selection: Option<&FrameSet>,
    chunk_spec: Option<(usize, usize)>,
) -> Result<(FrameSet, FrameSet), Failure> {
    let all = match selection {
        Some(sel) => job.frames.narrow(sel).map_err(|outside| {
            Failure::Input(format!(
                "--frames selects {} frame(s) outside the job's frames {} (first: {})",
                outside.len(),
                job.frames,
                outside.first().unwrap_or_default()
            ))
        })?,
        None => job.frames.clone(),
    };
    if all.is_empty() {
        return Err(Failure::Input("the frame selection is empty".into()));
    }
    let planned = match chunk_spec {
        Some((size, index)) => all
            .chunk(size, index)
            .map_err(|e| Failure::Input(e.to_string()))?,
        None => all.clone(),
    };
    Ok((planned, all))
}

/// Number of chunks of `size` for the selection (for `eyeadapt plan`).
pub fn plan_chunks(frames: &FrameSet, size: usize) -> Result<usize, Failure> {
    frames
        .chunk_count(size)
        .map_err(|e| Failure::Input(e.to_string()))
}

/// Holds an exclusive lock on the output directory for the life of the run.
pub struct DirLock {
    _file: std::fs::File,
}

pub fn lock_dir(dir: &Path) -> Result<DirLock, Failure> {
    let p = dir.join(".eyeadapt.lock");
    let file = OpenOptions::new()
        .create(true)
        .truncate(false)
        .write(true)
        .open(&p)
        .map_err(|e| Failure::io("cannot create lock file", &p, &e))?;
    match file.try_lock() {
        Ok(()) => Ok(DirLock { _file: file }),
        Err(std::fs::TryLockError::WouldBlock) => Err(Failure::Transient(format!(
            "another eyeadapt process is writing to {}",
            dir.display()
        ))),
        Err(std::fs::TryLockError::Error(e)) => Err(Failure::io("cannot lock", &p, &e)),
    }
}

/// The full CSV text of a directory's committed frames, in frame order.
pub fn csv_from_rows(dir: &Path, m: &Manifest) -> Result<String, Failure> {
    let mut csv = String::from(CSV_HEADER);
    csv.push('\n');
    for f in m.frames.keys() {
        let p = dir.join("rows").join(frame_name(*f, "csv"));
        let rows = std::fs::read_to_string(&p)
            .map_err(|e| Failure::io("cannot read committed rows", &p, &e))?;
        csv.push_str(&rows);
    }
    Ok(csv)
}

/// Rewrites adaptation.csv from the row files unless it already holds exactly that, or that
/// followed by rows a report derived from it (estimator names with `+`, such as
/// `eye+fairchild`; only `report` writes them), so that a rerun which renders nothing leaves
/// a finished directory's CSV, and so its report, as they are.
pub fn sync_csv(dir: &Path, m: &Manifest) -> Result<bool, Failure> {
    let want = csv_from_rows(dir, m)?;
    let p = dir.join(CSV);
    let derived_tail = |rest: &[u8]| {
        rest.is_empty()
            || std::str::from_utf8(rest).is_ok_and(|t| {
                t.ends_with('\n')
                    && t.lines()
                        .all(|l| l.split(',').nth(2).is_some_and(|e| e.contains('+')))
            })
    };
    if std::fs::read(&p)
        .is_ok_and(|have| have.strip_prefix(want.as_bytes()).is_some_and(derived_tail))
    {
        return Ok(false);
    }
    atomic_write_bytes(&p, want.as_bytes())?;
    Ok(true)
}

fn new_manifest(job: &Job, planned: &FrameSet) -> Manifest {
    Manifest {
        format: crate::manifest::FORMAT,
        tool: format!("eyeadapt {}", env!("CARGO_PKG_VERSION")),
        job_name: job.name.clone(),
        job_source: job.source.clone(),
        job_hash: job.hash.clone(),
        planned: planned.to_string(),
        job_frames: job.frames.to_string(),
        estimators: job.estimators.iter().map(|s| s.to_string()).collect(),
        fps: job.path.fps(),
        settings: RunSettings::of_job(job),
        frames: Default::default(),
    }
}

/// Renders the planned frames of `job` into `o.out`.
pub fn run_sequence(job: &Job, o: &SequenceOptions) -> Result<SequenceSummary, Failure> {
    let start = Instant::now();
    let (planned, all) = plan_frames(job, o.selection.as_ref(), o.chunk)?;
    // Before the output directory is touched: a frame that cannot fit in memory fails now.
    crate::resources::check_render(
        &format!("the job {}", job.source),
        job.width,
        job.height,
        job.scene.triangle_count(),
    )?;
    crate::still::prepare_out_dir(&o.out)?;
    let _lock = lock_dir(&o.out)?;
    crate::output::remove_stale_temps(&o.out)?;
    let (mut m, damaged) = open_manifest(job, o, &planned)?;
    m.save(&o.out)?;
    sync_csv(&o.out, &m)?;

    let todo: Vec<u32> = planned
        .iter()
        .filter(|f| !m.frames.contains_key(f))
        .collect();
    let mut summary = SequenceSummary {
        planned: planned.len(),
        skipped: planned.len() - todo.len(),
        ..Default::default()
    };
    let mut progress = Progress::new(todo.len(), o.log_format, o.plain_progress);
    progress.note(&startup_line(job, o, &planned, todo.len(), summary.skipped));
    if !damaged.is_empty() {
        progress.note(&format!(
            "re-rendering {} frame(s) whose files were missing or damaged: {}",
            damaged.len(),
            damaged
        ));
    }
    let stop = o.stop.as_deref();
    if let Some(s) = stop {
        s.set_committed(summary.skipped);
    }
    if !todo.is_empty() {
        let scenes = FrameScenes::new(&job.scene);
        for (i, &f) in todo.iter().enumerate() {
            if let Some(sig) = stop.and_then(StopRequest::requested) {
                summary.stopped = Some(sig);
                break;
            }
            progress.frame_started(f, i, job.height as usize);
            let t = Instant::now();
            let (entry, r) = scenes.at(job.time(f), |data| {
                render_frame(job, data, f, &o.out, &progress)
            })?;
            let (readings, frame) = (&r.readings, &r.image);
            commit(&o.out, &mut m, f, entry)?;
            summary.rendered += 1;
            if let Some(s) = stop {
                s.set_committed(summary.skipped + summary.rendered);
            }
            summary.render_seconds += frame.stats.seconds;
            let total = t.elapsed().as_secs_f64();
            let msg = eye_message(readings, total);
            progress.frame_done(
                f,
                total,
                frame.stats.samples as f64 / frame.stats.seconds.max(1e-9),
                &msg,
            );
        }
    }
    progress.finish();
    // Rows appended in a resumed run may follow frames committed later by another order:
    // leave the CSV sorted by frame.
    sync_csv(&o.out, &m)?;
    summary.complete = all.iter().all(|f| m.frames.contains_key(&f));
    summary.seconds = start.elapsed().as_secs_f64();
    Ok(summary)
}

/// The run's first line: job, scene, frames to do and done, output directory, threads.
fn startup_line(
    job: &Job,
    o: &SequenceOptions,
    planned: &FrameSet,
    todo: usize,
    done: usize,
) -> String {
    let threads = rayon::current_num_threads();
    format!(
        "eyeadapt sequence: job \"{}\" ({}), scene {}, frames {planned}: {todo} to do, {done} already done, output {}, {threads} thread{}",
        job.name,
        job.source,
        job.scene.source.display(),
        o.out.display(),
        if threads == 1 { "" } else { "s" }
    )
}

/// The directory's manifest for this run (a new one unless it holds this job's frames) with
/// the frames whose files are gone or damaged forgotten (they will be rendered again), and
/// those frames.
fn open_manifest(
    job: &Job,
    o: &SequenceOptions,
    planned: &FrameSet,
) -> Result<(Manifest, FrameSet), Failure> {
    let mut m = match Manifest::load(&o.out)? {
        Some(m) if m.job_hash == job.hash => Manifest {
            format: crate::manifest::FORMAT,
            planned: planned.to_string(),
            job_frames: job.frames.to_string(),
            ..m
        },
        Some(m) if !o.force => {
            return Err(Failure::Input(format!(
                "{} holds frames of job \"{}\" ({}, hash {}…) but this job hashes to {}…: refusing to mix outputs. \
                 Use another --out, or --force to discard the old frames' records and start over",
                o.out.display(),
                m.job_name,
                m.job_source,
                // The old manifest is input: its hash may be short or not even ASCII.
                m.job_hash.get(..12).unwrap_or(&m.job_hash),
                crate::manifest::short_hash(&job.hash)
            )));
        }
        _ => new_manifest(job, planned),
    };
    // Forget frames whose files are gone or damaged; they will be rendered again.
    let damaged = FrameSet::from_frames(
        m.frames
            .keys()
            .copied()
            .filter(|f| !m.frame_intact(&o.out, *f, o.verify)),
    );
    for f in damaged.iter() {
        m.frames.remove(&f);
    }
    Ok((m, damaged))
}

/// Commits a rendered frame: appends its rows to adaptation.csv in one write, then saves the
/// manifest listing it.
fn commit(out: &Path, m: &mut Manifest, f: u32, entry: FrameEntry) -> Result<(), Failure> {
    let rows = std::fs::read(out.join("rows").join(frame_name(f, "csv")))
        .map_err(|e| Failure::io("cannot read back rows", out, &e))?;
    let csv = out.join(CSV);
    let csv_len = std::fs::metadata(&csv).map(|md| md.len());
    m.frames.insert(f, entry);
    if let Err(e) = append(&csv, &rows).and_then(|()| m.save(out)) {
        // The frame is not committed (the manifest on disk does not list it): cut the
        // CSV back to the committed frames' rows, so that a failed run (disk full in
        // the append or the manifest write) leaves no torn or uncommitted row behind.
        // Truncating needs no free space.
        m.frames.remove(&f);
        if let Ok(len) = csv_len {
            let _ = OpenOptions::new()
                .write(true)
                .open(&csv)
                .and_then(|file| file.set_len(len));
        }
        return Err(e);
    }
    Ok(())
}

/// The frame log's note on the eye sensor: its u′v′ and its share of the frame's time.
fn eye_message(readings: &[Reading], total: f64) -> String {
    match readings
        .iter()
        .find(|r| r.estimator == crate::Estimator::Eye)
    {
        Some(r) => {
            let uv = r.estimate.uv().map_or("undefined".into(), |uv| {
                format!("({:.4}, {:.4})", uv.x, uv.y)
            });
            let share = 100.0 * r.seconds / total.max(1e-9);
            format!(
                "eye u'v' = {uv}; eye sensor {:.3} s = {share:.2} % of the frame",
                r.seconds
            )
        }
        None => String::new(),
    }
}

fn append(path: &Path, bytes: &[u8]) -> Result<(), Failure> {
    let mut f = OpenOptions::new()
        .append(true)
        .open(path)
        .map_err(|e| Failure::io("cannot open for append", path, &e))?;
    // One write call for all of the frame's rows. A kill can still end it short at a page
    // boundary; the frame is not committed then, and the next run rebuilds the CSV.
    f.write_all(bytes)
        .map_err(|e| Failure::io("cannot append to", path, &e))?;
    f.sync_data()
        .map_err(|e| Failure::io("cannot sync", path, &e))
}

/// Renders and writes one frame through the pipeline; returns its manifest entry.
fn render_frame(
    job: &Job,
    data: &SceneData,
    f: u32,
    out: &Path,
    progress: &Progress,
) -> Result<(FrameEntry, FrameResult), Failure> {
    let r = job
        .pipeline(data)
        .run_with_progress(f, job.time(f), job.view(f), &|step| match step {
            FrameStep::Row => progress.row_done(),
            FrameStep::Estimating => progress.estimating(),
        });
    let mut files: Vec<String> = Vec::new();
    let spec = WriteSpec {
        layout: Layout::Sequence,
        outputs: job.outputs,
        exposure: job.exposure,
        adaptation: &job.adaptation,
    };
    write_images(out, &r, &spec, |rel| {
        progress.saved(&out.join(&rel));
        files.push(rel);
    })?;
    let rel = format!("rows/{}", frame_name(f, "csv"));
    atomic_write_bytes(&out.join(&rel), r.rows().as_bytes())?;
    files.push(rel);
    // Checksums of the frame's files, one per thread (sha256 of a demo frame's files is 1 % of
    // its instructions).
    let entries: Vec<FileEntry> = files
        .par_iter()
        .map(|rel| file_entry(out, rel))
        .collect::<Result<_, _>>()?;
    let entry = FrameEntry {
        time_s: r.time,
        files: entries,
        invalid_samples: r.image.stats.invalid_samples,
    };
    Ok((entry, r))
}
