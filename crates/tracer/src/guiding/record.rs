//! Training records: what a path learned about the light arriving at its guided vertices.
//!
//! At each vertex where guiding applies, the path notes the direction it left in, the density
//! it was chosen with, its throughput after the vertex and the radiance the path had gathered
//! so far. Everything the path gathers later arrived along that direction, so when the path
//! ends, (gathered since − gathered before) / throughput is a one-sample estimate of the
//! incident radiance Lᵢ there. The record's value is Y(Lᵢ) / pdf, so that a quadrant's summed
//! values estimate ∫ Y(Lᵢ) dω over it.
//!
//! **MIS-weighted:** an emitter the next segment reaches counts with its MIS weight, as it
//! does in the image, not in full. The guide thus learns the light that direction sampling has
//! to find, and not the small lamps that the light samples already find well: learning those
//! in full sent guided directions after them and measured worse (`docs/benchmarks/guiding.md`).
use super::dtree::to_square;
use super::stree::SdTree;
use crate::emitter::luminance;
use glam::Vec3A;

/// Vertices a path records at most (later ones go unrecorded).
const MAX_VERTICES: usize = 16;

/// One vertex's record in flight.
#[derive(Clone, Copy, Debug, Default)]
struct Pending {
    leaf: u32,
    wi: Vec3A,
    pdf: f32,
    beta: Vec3A,
    before: Vec3A,
}

/// A finished record: a leaf of the spatial tree, the leaf quadrant (its `slot`) of that
/// leaf's quadtree being filled, and the value.
#[derive(Clone, Copy, Debug)]
pub struct Record {
    pub leaf: u32,
    pub slot: u32,
    pub value: f32,
}

/// The records of one path in flight.
#[derive(Clone, Debug, Default)]
pub struct Recorder {
    pending: [Pending; MAX_VERTICES],
    len: usize,
}

impl Recorder {
    /// The path left a guided vertex in spatial leaf `leaf` along `wi` (world), chosen with
    /// density `pdf`, with throughput `beta` afterwards, having gathered `gathered` so far.
    #[inline]
    pub fn push(&mut self, leaf: u32, wi: Vec3A, pdf: f32, beta: Vec3A, gathered: Vec3A) {
        if self.len < MAX_VERTICES {
            self.pending[self.len] = Pending {
                leaf,
                wi,
                pdf,
                beta,
                before: gathered,
            };
            self.len += 1;
        }
    }

    /// The path ended having gathered `gathered`: its records, valued, into `out`, each
    /// leaf's quadrant found in `tree`'s quadtrees being filled.
    pub fn finish(&self, gathered: Vec3A, tree: &SdTree, out: &mut Vec<Record>) {
        for r in &self.pending[..self.len] {
            let li = gathered - r.before;
            let inv = |b: f32| if b > 0.0 { 1.0 / b } else { 0.0 };
            let li = li * Vec3A::new(inv(r.beta.x), inv(r.beta.y), inv(r.beta.z));
            let mut value = luminance(li) / r.pdf;
            if !value.is_finite() || value < 0.0 {
                value = 0.0;
            }
            let slot = tree.leaves[r.leaf as usize].building.slot(to_square(r.wi));
            out.push(Record {
                leaf: r.leaf,
                slot,
                value,
            });
        }
    }
}

/// A pass's records summed per leaf quadrant of the quadtrees being filled, kept apart from
/// the tree so that paths can read the tree while earlier rows' records are added.
#[derive(Clone, Debug)]
pub struct Tally {
    /// Per spatial leaf, the energy of each `4 · node + quadrant` slot.
    sums: Vec<Vec<f64>>,
    records: Vec<u64>,
    /// Records of the pass in all.
    pub total: u64,
}

impl Tally {
    /// An empty tally for the quadtrees `tree` is filling.
    pub fn new(tree: &SdTree) -> Tally {
        Tally {
            sums: tree
                .leaves
                .iter()
                .map(|l| vec![0.0; 4 * l.building.node_count()])
                .collect(),
            records: vec![0; tree.leaves.len()],
            total: 0,
        }
    }

    /// Adds records, in their order (which callers keep fixed, so that the sums do not
    /// depend on threads).
    pub fn add(&mut self, records: &[Record]) {
        for r in records {
            self.records[r.leaf as usize] += 1;
            if r.value > 0.0 {
                self.sums[r.leaf as usize][r.slot as usize] += r.value as f64;
            }
        }
        self.total += records.len() as u64;
    }
}

impl SdTree {
    /// Ends a training pass: the tally into the quadtrees being filled, then
    /// [`SdTree::refine`] with a split threshold for the pass's number of records.
    pub fn learn(&mut self, tally: &Tally, split_above: u64) {
        for ((leaf, sums), &n) in self.leaves.iter_mut().zip(&tally.sums).zip(&tally.records) {
            for (slot, &v) in sums.iter().enumerate() {
                if v > 0.0 {
                    leaf.building.add(slot as u32, v);
                }
            }
            leaf.records += n;
        }
        self.refine(split_above);
    }
}
