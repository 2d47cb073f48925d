//! Everything around the renderer: outputs (EXR with AOVs, PNG previews, atomic writes), the
//! per-frame pipeline, job files, sequences with resume and merge. The report and the paper
//! harness are the crates above this one (`eyeadapt-report`, `eyeadapt-paper`).
//!
//! Data flows `job` → `frames` (which frames) → `pipeline` (each frame: the tracer's render,
//! `adapt`'s estimators and CAT, `output`'s files) → `sequence`/`still` → `manifest`.

/// The adaptation step: estimator options, running the estimators, CATs, CSV rows.
pub mod adapt;
/// A job's `[camera_path]`: keyframes, a CSV track or a glTF camera.
pub mod camera_motion;
/// [`Failure`]: every error, classified into the process exit code.
mod error;
/// [`Estimator`]: the estimators by name.
pub mod estimator;
/// An EXR written with its blocks compressed on the current rayon pool.
mod exr_blocks;
/// [`FrameSet`]: frame specs, narrowing, chunks for farms.
pub mod frames;
/// Job files: what a sequence renders, and how.
pub mod job;
/// `manifest.json`: committed frames with their files' checksums.
pub mod manifest;
/// `eyeadapt merge`: chunk outputs joined into one sequence.
pub mod merge;
/// Files: EXR with AOVs, PNG previews, atomic writes.
pub mod output;
/// The one per-frame pipeline: render → estimate → adapt → write.
pub mod pipeline;
/// Progress bars on a terminal, farm-log lines elsewhere.
pub mod progress;
/// The memory check before a render starts.
pub mod resources;
/// `eyeadapt sequence`: frames rendered with resume.
pub mod sequence;
/// The run settings the manifest records.
pub mod settings;
/// The previews' 8-bit sRGB bytes, by table.
mod srgb8;
/// `eyeadapt render`: one still.
pub mod still;
/// [`stop::StopRequest`]: a signal asks a running sequence to stop after the frame in flight.
pub mod stop;

pub use crate::error::Failure;
pub use crate::estimator::Estimator;
pub use crate::frames::{
    ChunkError, FrameSet, FrameSpecError, FrameSpecErrorKind, MAX_FRAMES, parse_chunk_index,
};
