//! The sequencer turns a job into rendered frames: it plans which frames to render (frame
//! specs, start/end/step ranges, farm chunks: [`FrameSet`], [`chunk`]) and drives the per-frame
//! pipeline and its outputs.

mod frames;

pub use frames::{
    ChunkError, FrameSet, FrameSpecError, FrameSpecErrorKind, MAX_FRAMES, chunk, chunk_count,
    parse_chunk_index,
};
