//! The spatial half of the SD-tree (Müller et al. 2017, §3.1): a binary tree over a cube
//! around the scene, each level halving its box along x, y, z in turn. Each leaf holds two
//! directional quadtrees: the one paths sample from during a pass (learned in the passes
//! before), and the one the pass's training records fill.
//!
//! Between passes ([`SdTree::refine`]) a leaf that received more records than the threshold
//! is split, both halves starting from copies of its quadtrees; then every leaf's filled
//! quadtree becomes the one to sample from, and the next pass fills a refined, empty copy.
use super::dtree::DTree;
use glam::Vec3A;

/// The energy share above which a quadrant is subdivided (Müller's ρ = 0.01).
const DTREE_THRESHOLD: f64 = 0.01;

/// Deepest level of the spatial tree.
const MAX_SPATIAL_DEPTH: u32 = 48;

#[derive(Clone, Copy, Debug)]
enum SNode {
    /// Halves along axis `depth % 3`: children below and above the midpoint.
    Split([u32; 2]),
    /// Index into the leaves.
    Leaf(u32),
}

/// A leaf's quadtrees and how many records the current pass gave it.
#[derive(Clone, Debug, Default)]
pub struct SLeaf {
    pub sampling: DTree,
    pub building: DTree,
    pub records: u64,
    depth: u32,
}

/// The spatio-directional tree.
#[derive(Clone, Debug)]
pub struct SdTree {
    min: Vec3A,
    inv_size: f32,
    nodes: Vec<SNode>,
    pub leaves: Vec<SLeaf>,
}

impl SdTree {
    /// One leaf over the cube that holds the box `min`..`max` (a little enlarged), with empty
    /// quadtrees: the first pass samples the BSDF alone.
    pub fn new(min: Vec3A, max: Vec3A) -> SdTree {
        let size = (max - min).max_element().max(1e-3) * 1.02;
        let centre = (min + max) * 0.5;
        SdTree {
            min: centre - Vec3A::splat(size * 0.5),
            inv_size: 1.0 / size,
            nodes: vec![SNode::Leaf(0)],
            leaves: vec![SLeaf::default()],
        }
    }

    /// The leaf whose box holds `p` (points outside the cube go to the nearest box).
    #[inline]
    pub fn leaf_at(&self, p: Vec3A) -> u32 {
        let mut x = ((p - self.min) * self.inv_size).clamp(Vec3A::ZERO, Vec3A::ONE);
        let mut n = 0usize;
        let mut axis = 0usize;
        loop {
            match self.nodes[n] {
                SNode::Leaf(l) => return l,
                SNode::Split(c) => {
                    let v = x[axis];
                    let (side, v) = if v < 0.5 {
                        (0, v * 2.0)
                    } else {
                        (1, v * 2.0 - 1.0)
                    };
                    x[axis] = v;
                    n = c[side] as usize;
                    axis = (axis + 1) % 3;
                }
            }
        }
    }

    /// Ends a pass: splits leaves that received more than `split_above` records (each half
    /// counting half of them, recursively), makes the filled quadtrees the ones to sample from
    /// and gives every leaf a refined, empty quadtree to fill next.
    pub fn refine(&mut self, split_above: u64) {
        let mut n = 0;
        while n < self.nodes.len() {
            if let SNode::Leaf(l) = self.nodes[n] {
                let leaf = &mut self.leaves[l as usize];
                if leaf.records > split_above && leaf.depth < MAX_SPATIAL_DEPTH {
                    leaf.records /= 2;
                    leaf.depth += 1;
                    let twin = leaf.clone();
                    let first = self.nodes.len() as u32;
                    self.leaves.push(twin);
                    self.nodes.push(SNode::Leaf(l));
                    self.nodes.push(SNode::Leaf(self.leaves.len() as u32 - 1));
                    self.nodes[n] = SNode::Split([first, first + 1]);
                }
            }
            n += 1;
        }
        for leaf in &mut self.leaves {
            leaf.building.sum_up();
            leaf.sampling = std::mem::take(&mut leaf.building);
            leaf.building = leaf.sampling.refined(DTREE_THRESHOLD);
            leaf.records = 0;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_busy_leaf_splits_into_halves_along_x_first() {
        let mut t = SdTree::new(Vec3A::ZERO, Vec3A::ONE);
        t.leaves[0].records = 100;
        t.refine(30);
        // 100 → two of 50 → four of 25: the root splits along x, then each half along y.
        assert_eq!(t.leaves.len(), 4);
        let a = t.leaf_at(Vec3A::new(0.1, 0.1, 0.5));
        let b = t.leaf_at(Vec3A::new(0.9, 0.1, 0.5));
        let c = t.leaf_at(Vec3A::new(0.1, 0.9, 0.5));
        let d = t.leaf_at(Vec3A::new(0.1, 0.1, 0.9));
        assert!(a != b && a != c && b != c);
        assert_eq!(a, d, "z is not split yet");
        assert!(t.leaves.iter().all(|l| l.records == 0));
    }
}
