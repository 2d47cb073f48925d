//! Path guiding, after Müller, Gross and Novák, "Practical Path Guiding for Efficient
//! Light-Transport Simulation" (EGSR 2017): an SD-tree, a binary tree over space whose leaves
//! hold quadtrees over directions ([`SdTree`], `stree.rs`; [`DTree`], `dtree.rs`), learned
//! from training records of the frame's own paths (`record.rs`) and sampled in one-sample MIS
//! with the BSDF (`mixture.rs`).
//!
//! **Per frame, in passes** (`schedule.rs`): a guided frame renders its samples in passes of
//! 1, 2, 4, … samples per pixel, the last taking what is left. Each pass samples from what the
//! passes before learned and records what it saw; between passes the tree is refined and the
//! records become the distribution to sample. Every pass is unbiased, so the frame keeps all
//! samples with equal weight. Nothing is shared between frames: a frame renders the same on
//! any machine of a farm, whatever else that machine rendered.
//!
//! **Where it applies:** at vertices whose BSDF has no delta part and is not a narrow lobe
//! (`mixture::guidable`), opaque and not a pane; the eye sensor (`eye.rs`) is not guided, so
//! its estimates and noise floor are those of the unguided renderer, bit for bit. Off (the
//! default), a frame is bit-identical to what the renderer gave before guiding existed
//! (`tests/guiding.rs` pins it).
//!
//! **Cost:** a guided vertex looks its leaf up, evaluates the quadtree's density for the light
//! sample's MIS weight and for the sampled direction, and, while learning, records; on the
//! built-in scenes, whose few thousand triangles make a vertex cheap, that is +15–120 % CPU
//! per sample (`docs/benchmarks/guiding.md`).
//!
//! **Determinism:** the records of a pass are kept per row and added to the tree in row order
//! after the rows are done, so the learned tree, and with it every pixel, is the same for any
//! thread count.
mod dtree;
mod mixture;
mod record;
mod schedule;
mod stree;

pub use dtree::{DTree, from_square, to_square};
pub use mixture::{guidable, mixture_pdf, sample_guided};
pub use record::{Record, Recorder, Tally};
pub use schedule::{passes, split_threshold};
pub use stree::SdTree;

/// Whether a frame learns and uses a guide.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Guiding {
    /// Plain BSDF sampling, bit for bit what the renderer gave before guiding existed.
    #[default]
    Off,
    /// The SD-tree, learned per frame (see the module docs).
    On,
}
