//! `eyeadapt sequence` and `eyeadapt merge` (and the job and frame selection `plan` shares).
use crate::args::{MergeArgs, SequenceArgs};
use eyeadapt_report::ReportOptions;
use eyeadapt_sequencer::Failure;
use eyeadapt_sequencer::frames::{FrameSet, parse_chunk_index};
use eyeadapt_sequencer::job::{Job, JobOverrides, load_job};
use eyeadapt_sequencer::progress::LogFormat;
use eyeadapt_sequencer::sequence::{SequenceOptions, plan_frames, run_sequence};
use eyeadapt_sequencer::stop::StopRequest;
use std::path::PathBuf;
use std::sync::Arc;

pub(crate) fn job_of(a: &SequenceArgs) -> Result<Job, Failure> {
    load_job(
        a.job.as_deref(),
        &JobOverrides {
            sampling: a.sampling.sampling(),
            eye_samples: a.eye_samples,
        },
    )
}

pub(crate) fn selection(a: &SequenceArgs, job: &Job) -> Result<Option<FrameSet>, Failure> {
    if let Some(spec) = &a.frames {
        return spec
            .parse::<FrameSet>()
            .map(Some)
            .map_err(|e| Failure::Input(format!("--frames: {e}")));
    }
    if let (Some(s), Some(e)) = (a.start, a.end) {
        // Clamp the end to the job (OpenCue's last #FRAME_END# can run past it).
        let last = job.frames.last().unwrap_or(0);
        if a.step == 0 {
            return Err(Failure::Input("--step must be at least 1".into()));
        }
        if s > e {
            return Err(Failure::Input(format!("--start {s} is after --end {e}")));
        }
        if s > last {
            return Err(Failure::Input(format!(
                "--start {s} is after the job's last frame {last}"
            )));
        }
        let e = e.min(last);
        return FrameSet::from_start_end_step(s, e, a.step)
            .map(Some)
            .map_err(|e| Failure::Input(format!("--start/--end/--step: {e}")));
    }
    Ok(None)
}

fn chunk_spec(a: &SequenceArgs) -> Result<Option<(usize, usize)>, Failure> {
    let Some(size) = a.chunk_size else {
        return Ok(None);
    };
    let index = match &a.chunk_index {
        Some(i) => {
            parse_chunk_index(i).map_err(|e| Failure::Input(format!("--chunk-index: {e}")))?
        }
        None => match std::env::var("SLURM_ARRAY_TASK_ID") {
            Ok(v) => parse_chunk_index(&v)
                .map_err(|e| Failure::Input(format!("$SLURM_ARRAY_TASK_ID: {e}")))?,
            Err(_) => {
                return Err(Failure::Input(
                    "--chunk-size needs --chunk-index or $SLURM_ARRAY_TASK_ID".into(),
                ));
            }
        },
    };
    Ok(Some((size as usize, index)))
}

pub fn run(a: SequenceArgs) -> Result<(), Failure> {
    let job = job_of(&a)?;
    for w in &job.scene.warnings {
        eprintln!("{w}");
    }
    let out = a
        .out
        .clone()
        .unwrap_or_else(|| PathBuf::from("out").join(&job.name));
    let stop = Arc::new(StopRequest::default());
    let log_format = if a.log_format == "openjd" {
        LogFormat::Openjd
    } else {
        LogFormat::Plain
    };
    let opts = SequenceOptions {
        out: out.clone(),
        selection: selection(&a, &job)?,
        chunk: chunk_spec(&a)?,
        force: a.force,
        verify: a.verify,
        log_format,
        plain_progress: a.no_progress_bar,
        stop: Some(stop.clone()),
    };
    let (planned, _) = plan_frames(&job, opts.selection.as_ref(), opts.chunk)?;
    crate::interrupt::watch(stop.clone(), planned.len())?;
    let s = run_sequence(&job, &opts)?;
    let fph = if s.rendered > 0 {
        s.rendered as f64 / s.seconds * 3600.0
    } else {
        0.0
    };
    println!(
        "{}: {} frame(s) rendered, {} already done, in {:.1} s ({:.0} frames/hour) -> {}",
        job.name,
        s.rendered,
        s.skipped,
        s.seconds,
        fph,
        out.display()
    );
    let committed = crate::interrupt::committed_message(s.skipped + s.rendered, s.planned);
    if let Some(signal) = s.stopped.or(stop.requested()) {
        let name = crate::interrupt::signal_name(signal);
        let message = if s.stopped.is_some() {
            format!("stopped by {name}: {committed}")
        } else {
            format!("stopped by {name} before the report: {committed}")
        };
        return Err(Failure::Stopped { signal, message });
    }
    if s.complete && opts.chunk.is_none() && !a.no_report {
        stop.set_reporting();
        let report = ReportOptions {
            progress: crate::cmd_report::progress_lines(log_format, a.no_progress_bar),
            ..Default::default()
        };
        crate::cmd_report::report_unless_current(&out, &report)?;
    }
    Ok(())
}

pub fn merge(a: MergeArgs) -> Result<(), Failure> {
    let frames = match &a.frames {
        Some(spec) => Some(
            spec.parse::<FrameSet>()
                .map_err(|e| Failure::Input(format!("--frames: {e}")))?,
        ),
        None => None,
    };
    let s = eyeadapt_sequencer::merge::merge(&a.dirs, &a.out, frames.as_ref())?;
    let left_out = match s.left_out {
        0 => String::new(),
        n => format!("; {n} frame(s) outside --frames left out"),
    };
    println!(
        "merged {} frame(s) ({}) from {} director{} ({} identical duplicate(s){left_out}) into {}",
        s.frames,
        s.selection,
        s.sources,
        if s.sources == 1 { "y" } else { "ies" },
        s.duplicates,
        a.out.display()
    );
    Ok(())
}
