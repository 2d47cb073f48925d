//! Everything around the renderer: outputs (EXR with AOVs, PNG previews, atomic writes), the
//! per-frame pipeline, job files, sequences with resume and merge. The report and the paper
//! harness are the crates above this one (`eyeadapt-report`, `eyeadapt-paper`).
//!
//! [`Failure`] classifies every error into the process exit code.

pub mod adapt;
mod error;
pub mod frames;
pub mod job;
pub mod manifest;
pub mod merge;
pub mod output;
pub mod progress;
pub mod resources;
pub mod sequence;
pub mod still;

pub use crate::error::Failure;
pub use crate::frames::{
    ChunkError, FrameSet, FrameSpecError, FrameSpecErrorKind, MAX_FRAMES, chunk, chunk_count,
    parse_chunk_index,
};
