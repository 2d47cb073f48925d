//! Everything around the renderer: outputs (EXR with AOVs, PNG previews, atomic writes), the
//! per-frame pipeline, job files, sequences with resume and merge, and reports.
//!
//! [`Failure`] classifies every error into the process exit code.

pub mod adapt;
mod error;
pub mod output;
pub mod still;

pub use crate::error::Failure;
