//! The directional quadtree of "Practical Path Guiding" (Müller et al. 2017, §3.2): a
//! piecewise-constant density over the unit square of cylindrical coordinates (cos θ, φ) of
//! world directions, an equal-area map of the sphere (so a density `p` on the square is
//! `p / 4π` per steradian). Each node splits its square into four quadrants and keeps the
//! energy (the summed training values) that fell into each; a quadrant is either a leaf or
//! another node.
//!
//! Quadrant `q` of a node covers x ∈ [q & 1, (q & 1) + 1) / 2, y ∈ [q >> 1, (q >> 1) + 1) / 2
//! of the node's square. Nodes are stored parent before child, the root first.
use crate::trig::sincos_turns;
use glam::Vec3A;
use std::f32::consts::PI;

/// Deepest level a quadrant may be subdivided to (Müller's 20).
pub const MAX_DEPTH: u32 = 20;

/// What sampling and [`DTree::pdf`] read of a node: half a cache line.
#[derive(Clone, Copy, Debug, Default)]
struct Node {
    /// Index of the node that refines quadrant q, 0 where the quadrant is a leaf.
    child: [u32; 4],
    /// Each quadrant's density relative to the node's, 4 · `sum[q]` / Σ sum (set by
    /// [`DTree::sum_up`]).
    density: [f32; 4],
}

/// A directional quadtree (see the module docs).
#[derive(Clone, Debug)]
pub struct DTree {
    nodes: Vec<Node>,
    /// Energy in each quadrant of each node, apart from the nodes so that sampling's
    /// descents touch less memory.
    sums: Vec<[f64; 4]>,
}

impl Default for DTree {
    fn default() -> Self {
        DTree::new()
    }
}

/// The point of the unit square that stands for unit direction `d`.
#[inline]
pub fn to_square(d: Vec3A) -> [f32; 2] {
    let x = ((d.z.clamp(-1.0, 1.0) + 1.0) * 0.5).min(1.0 - f32::EPSILON * 0.5);
    let mut phi = libm::atan2f(d.y, d.x) * (0.5 / PI);
    if phi < 0.0 {
        phi += 1.0;
    }
    [x, phi.clamp(0.0, 1.0 - f32::EPSILON * 0.5)]
}

/// The unit direction point `p` of the unit square stands for.
#[inline]
pub fn from_square(p: [f32; 2]) -> Vec3A {
    let cos_t = 2.0 * p[0] - 1.0;
    let sin_t = (1.0 - cos_t * cos_t).max(0.0).sqrt();
    let (s, c) = sincos_turns(p[1]);
    Vec3A::new(sin_t * c, sin_t * s, cos_t)
}

/// The quadrant of a node's square that `p` (in that square's [0, 1)² coordinates) lies in,
/// and `p` in the quadrant's own coordinates.
#[inline]
fn descend(p: [f32; 2]) -> (usize, [f32; 2]) {
    let (qx, x) = if p[0] < 0.5 {
        (0, p[0] * 2.0)
    } else {
        (1, p[0] * 2.0 - 1.0)
    };
    let (qy, y) = if p[1] < 0.5 {
        (0, p[1] * 2.0)
    } else {
        (1, p[1] * 2.0 - 1.0)
    };
    (qx | qy << 1, [x.min(1.0), y.min(1.0)])
}

impl DTree {
    /// One node whose four quadrants are empty leaves.
    pub fn new() -> DTree {
        DTree {
            nodes: vec![Node::default()],
            sums: vec![[0.0; 4]],
        }
    }

    /// The total energy.
    #[inline]
    pub fn total(&self) -> f64 {
        self.sums[0].iter().sum()
    }

    /// Whether the tree holds energy to sample from (as of [`DTree::sum_up`]).
    #[inline]
    pub fn has_energy(&self) -> bool {
        self.nodes[0].density != [0.0; 4]
    }

    pub fn node_count(&self) -> usize {
        self.nodes.len()
    }

    /// The leaf quadrant `p` falls in, as `4 · node + quadrant` (what [`DTree::add`] takes).
    #[inline]
    pub fn slot(&self, mut p: [f32; 2]) -> u32 {
        let mut n = 0usize;
        loop {
            let (q, local) = descend(p);
            let c = self.nodes[n].child[q];
            if c == 0 {
                return (4 * n + q) as u32;
            }
            n = c as usize;
            p = local;
        }
    }

    /// Adds `value` to the energy of leaf quadrant `slot` alone; [`DTree::sum_up`] then brings
    /// the nodes above it up to date.
    #[inline]
    pub fn add(&mut self, slot: u32, value: f64) {
        self.sums[slot as usize / 4][slot as usize % 4] += value;
    }

    /// Sets every refined quadrant's energy to the total of the node below it, and the
    /// quadrants' relative densities.
    pub fn sum_up(&mut self) {
        // Children come after their parents: one backward sweep sees each child's total first.
        for n in (0..self.nodes.len()).rev() {
            for q in 0..4 {
                let c = self.nodes[n].child[q] as usize;
                if c != 0 {
                    self.sums[n][q] = self.sums[c].iter().sum();
                }
            }
            let sums = self.sums[n];
            let total: f64 = sums.iter().sum();
            self.nodes[n].density = if total > 0.0 {
                sums.map(|s| (4.0 * s / total) as f32)
            } else {
                [0.0; 4]
            };
        }
    }

    /// The density on the unit square at `p` (0 where no energy fell, and everywhere when
    /// there is none).
    #[inline]
    pub fn pdf(&self, mut p: [f32; 2]) -> f32 {
        let mut n = 0usize;
        let mut f = 1.0f32;
        loop {
            let node = &self.nodes[n];
            let (q, local) = descend(p);
            f *= node.density[q];
            let c = node.child[q];
            if c == 0 || f == 0.0 {
                return f;
            }
            n = c as usize;
            p = local;
        }
    }

    /// The density per steradian towards unit direction `d`.
    #[inline]
    pub fn pdf_dir(&self, d: Vec3A) -> f32 {
        self.pdf(to_square(d)) * (0.25 / PI)
    }

    /// A point of the unit square drawn with density [`DTree::pdf`] from `u` (the tree must
    /// hold energy), and that density. Each level picks the column with `u[0]` and the row
    /// within it with `u[1]`, rescaling each, so the leftover bits place the point inside the
    /// leaf.
    pub fn sample(&self, mut u: [f32; 2]) -> ([f32; 2], f32) {
        let mut n = 0usize;
        let (mut origin, mut size, mut f) = ([0.0f32; 2], 1.0f32, 1.0f32);
        loop {
            let s = self.nodes[n].density;
            let pick = |u: &mut f32, a: f32, b: f32| -> usize {
                let pa = a / (a + b);
                if *u < pa {
                    *u = (*u / pa).min(1.0 - f32::EPSILON * 0.5);
                    0
                } else {
                    *u = ((*u - pa) / (1.0 - pa)).clamp(0.0, 1.0 - f32::EPSILON * 0.5);
                    1
                }
            };
            let qx = pick(&mut u[0], s[0] + s[2], s[1] + s[3]);
            let qy = pick(&mut u[1], s[qx], s[qx + 2]);
            let q = qx | qy << 1;
            f *= s[q];
            size *= 0.5;
            origin[0] += size * qx as f32;
            origin[1] += size * qy as f32;
            let c = self.nodes[n].child[q];
            if c == 0 {
                return ([origin[0] + size * u[0], origin[1] + size * u[1]], f);
            }
            n = c as usize;
        }
    }

    /// The next pass's tree (Müller's `reset`): quadrants holding more than `threshold` of the
    /// total energy are subdivided (down to [`MAX_DEPTH`]), where this tree has no node below
    /// them as well, sharing their energy equally between the new quadrants; the energies
    /// start again from zero.
    pub fn refined(&self, threshold: f64) -> DTree {
        let total = self.total();
        let mut out = DTree::new();
        if total <= 0.0 {
            return out;
        }
        // (node in `out`, this tree's node there or None, its quadrant energies, depth)
        let mut stack = vec![(0usize, Some(0usize), self.sums[0], 1u32)];
        while let Some((at, old, sums, depth)) = stack.pop() {
            for (q, &energy) in sums.iter().enumerate() {
                if depth >= MAX_DEPTH || energy <= total * threshold {
                    continue;
                }
                let c = out.nodes.len();
                out.nodes.push(Node::default());
                out.sums.push([0.0; 4]);
                out.nodes[at].child[q] = c as u32;
                let old_child = old
                    .map(|o| self.nodes[o].child[q] as usize)
                    .filter(|&k| k != 0);
                let child_sums = match old_child {
                    Some(k) => self.sums[k],
                    None => [energy * 0.25; 4],
                };
                stack.push((c, old_child, child_sums, depth + 1));
            }
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_square_map_round_trips_directions() {
        for d in [
            Vec3A::new(0.3, -0.4, 0.866).normalize(),
            Vec3A::new(-1.0, 0.0, 0.0),
            Vec3A::new(0.0, -0.6, -0.8),
        ] {
            let back = from_square(to_square(d));
            assert!((back - d).length() < 1e-5, "{d} → {back}");
        }
    }

    /// A tree learned from a lopsided energy: quadtrees refined twice from values that fall
    /// mostly into one corner of the square and along one edge.
    pub(crate) fn lopsided() -> DTree {
        let mut t = DTree::new();
        let mut h = 12345u64;
        let mut next = || {
            h = crate::sampler::mix64(h);
            (h >> 40) as f32 / (1u64 << 24) as f32
        };
        // A point of the square (mostly in one corner and along one edge) and its value.
        let point = |a: f32, b: f32| {
            if a < 0.6 {
                [0.1 * b, 0.05 + 0.1 * a]
            } else {
                [b, 0.95 * a]
            }
        };
        for _ in 0..3 {
            for _ in 0..20000 {
                let (a, b) = (next(), next());
                t.add(t.slot(point(a, b)), (1.0 + 4.0 * b) as f64);
            }
            t.sum_up();
            t = t.refined(0.01);
        }
        for _ in 0..20000 {
            let (a, b) = (next(), next());
            t.add(t.slot(point(a, b)), 1.0);
        }
        t.sum_up();
        t
    }

    #[test]
    fn the_density_integrates_to_one_and_samples_follow_it() {
        let t = lopsided();
        assert!(t.node_count() > 20, "{} nodes", t.node_count());
        // ∫ pdf over the square, on a fine grid (finer than the deepest leaf needs not be:
        // a midpoint rule over a 512² grid is exact for leaves down to 1/512).
        let n = 512;
        let mut integral = 0.0f64;
        let mut expected = vec![0.0f64; 16 * 16];
        for i in 0..n {
            for j in 0..n {
                let p = [(i as f32 + 0.5) / n as f32, (j as f32 + 0.5) / n as f32];
                let v = t.pdf(p) as f64 / (n * n) as f64;
                integral += v;
                expected[(i * 16 / n) * 16 + j * 16 / n] += v;
            }
        }
        assert!((integral - 1.0).abs() < 2e-3, "∫ pdf = {integral}");
        // Samples land in each of 16 × 16 cells as often as the pdf says (χ², 255 dof).
        let m = 200_000;
        let mut seen = vec![0.0f64; 16 * 16];
        for k in 0..m {
            let u = crate::sampler::SampleStream::new(7, k).next_2d();
            let (p, pdf) = t.sample(u);
            assert!(t.pdf(p) > 0.0, "sampled {p:?} where the pdf is 0");
            assert!((pdf - t.pdf(p)).abs() <= 1e-3 * pdf, "{pdf} ≠ {}", t.pdf(p));
            seen[(p[0] * 16.0) as usize * 16 + (p[1] * 16.0) as usize] += 1.0;
        }
        let chi2: f64 = seen
            .iter()
            .zip(&expected)
            .filter(|(_, e)| **e * m as f64 > 5.0)
            .map(|(o, e)| (o - e * m as f64).powi(2) / (e * m as f64))
            .sum();
        assert!(chi2 < 400.0, "χ² = {chi2}");
    }

    #[test]
    fn a_tree_without_energy_has_no_density() {
        let t = DTree::new();
        assert_eq!(t.pdf([0.3, 0.7]), 0.0);
        assert_eq!(t.total(), 0.0);
    }
}
