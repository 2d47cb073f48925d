//! A light tree: which of many lights next-event estimation samples from a shading point, in
//! time logarithmic in their number (Conty Estevez and Kulla, "Importance Sampling of Many
//! Lights with Adaptive Tree Splitting", 2018; the light BVH of pbrt-v4 and Blender Cycles).
//!
//! Every bounded light (area units, point and spot lights, textured spots, projectors) is a
//! leaf. A node bounds its lights' positions (a box), the directions they emit into (a cone:
//! axis, spread θ_o, and the emission's reach θ_e beyond it) and their summed power; from a
//! shading point its *importance* is a conservative estimate of the irradiance its lights can
//! deliver there ([`crate::light_bounds4`]), exactly 0 only where none of them can.
//!
//! The tree is built binary (median splits along the longest axis of the lights' centres) and
//! then collapsed to eight children a node: each node takes its binary children and keeps
//! opening the one with the most lights until it has eight. A node's children are evaluated
//! together, two independent four-lane vector computations (the second only where the node
//! has more than four children). A walk is a chain of dependent steps, each waiting on its
//! node's square roots and division; eight children a node make the chain a third shorter
//! than four did (27 lights: two steps instead of three), and the two halves of a node overlap
//! in the core.
//!
//! Choosing walks from the root: at each node one child is taken with probability in
//! proportion to the children's importances, and the sample number is rescaled to stay
//! uniform. A leaf's weight comes from the caller, given the leaf's bound: `light_pick` keeps
//! the bound for an area light that passes its exact tests (x in front of it, part of it above
//! x's tangent plane) and uses a delta light's own importance, so a light that cannot
//! contribute at x is never chosen there, and one that can always keeps a positive
//! probability (every ancestor bounds it): the estimator stays unbiased. The
//! probability of a given light, which MIS needs at emitter hits, is the product of the branch
//! probabilities along its path from the root, recomputed the same way (the same bits).
//!
//! Lights without a position (directional lights and the environment) stay outside the tree
//! and compete with its root by their own importance. Everything is a pure function of the
//! scene and the shading point: no state, no dependence on threads.
use crate::light_bounds4::Bounds4;
use glam::Vec3A;

/// Where a node's lights are and where they shine.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LightBounds {
    pub lo: Vec3A,
    pub hi: Vec3A,
    /// Cone of emission directions: unit axis and cos of the spread θ_o (−1: every direction).
    pub axis: Vec3A,
    pub cos_o: f32,
    /// Cos of θ_e, how far beyond the spread emission reaches (0 for Lambertian emitters, 1
    /// for a spot's hard cone).
    pub cos_e: f32,
    /// Summed power weight (radiance × area or intensity, in luminance).
    pub phi: f32,
}

impl LightBounds {
    /// The bounds of both `self` and `other`.
    pub fn union(&self, other: &LightBounds) -> LightBounds {
        let (axis, cos_o) = cone_union((self.axis, self.cos_o), (other.axis, other.cos_o));
        LightBounds {
            lo: self.lo.min(other.lo),
            hi: self.hi.max(other.hi),
            axis,
            cos_o,
            cos_e: self.cos_e.min(other.cos_e),
            phi: self.phi + other.phi,
        }
    }

    fn centre(&self) -> Vec3A {
        0.5 * (self.lo + self.hi)
    }
}

/// The narrowest cone (of those that grow one to reach the other) containing both cones.
fn cone_union(a: (Vec3A, f32), b: (Vec3A, f32)) -> (Vec3A, f32) {
    let (ta, tb) = (
        libm::acosf(a.1.clamp(-1.0, 1.0)),
        libm::acosf(b.1.clamp(-1.0, 1.0)),
    );
    let td = libm::acosf(a.0.dot(b.0).clamp(-1.0, 1.0));
    if (tb - ta).abs() >= std::f32::consts::PI || td + tb <= ta {
        return if ta >= tb { a } else { b };
    }
    if td + ta <= tb {
        return b;
    }
    let to = 0.5 * (ta + td + tb);
    if to >= std::f32::consts::PI {
        return (a.0, -1.0);
    }
    // Turn a's axis towards b's by to − ta, in the plane of the two.
    let perp = b.0 - a.0 * a.0.dot(b.0);
    let len = perp.length();
    if len <= 1e-6 {
        return (a.0, -1.0);
    }
    let turn = to - ta;
    let axis = (a.0 * libm::cosf(turn) + perp / len * libm::sinf(turn)).normalize();
    // A little wider than computed, so that rounding never leaves a child's cone outside.
    (axis, libm::cosf((to + 1e-4).min(std::f32::consts::PI)))
}

/// A binary node while building: its bounds, how many lights it holds, and a leaf's light
/// (`u32::MAX` for an inner node, whose first child follows it and whose second is `right`).
struct Binary {
    bounds: LightBounds,
    count: u32,
    light: u32,
    right: u32,
}

/// A child of a node that is a leaf: its light, with this bit set.
const LEAF: u32 = 1 << 31;

/// Children a node has at most.
const WIDTH: usize = 8;

/// A node of the eight-wide tree.
#[derive(Clone, Copy, Debug)]
struct Node {
    /// The children's bounds, one lane each: children 0-3 in the first, 4-7 in the second.
    bounds: [Bounds4; 2],
    /// Each child: a node's index, or `LEAF | light`; `u32::MAX` past the last (there are 2
    /// to 8, or 1 for a root over one light).
    child: [u32; WIDTH],
    /// Bit j set where child j is a leaf.
    leaves: u8,
}

impl Node {
    /// The children's importances at (`x`, `n`): a leaf's is `leaf(light, its bound)`; 0
    /// past the last child (lanes without a node have no power; a node of at most four
    /// children skips the second half).
    /// Each is then multiplied by its lane's factor in `f` (the node's eight, if any).
    #[inline]
    fn weights(
        &self,
        x: Vec3A,
        n: Option<Vec3A>,
        leaf: &impl Fn(usize, f32) -> f32,
        f: Option<&[f32]>,
    ) -> [f32; WIDTH] {
        let lo = self.bounds[0].importance(x, n);
        let hi = if self.child[4] == u32::MAX {
            [0.0; 4]
        } else {
            self.bounds[1].importance(x, n)
        };
        let mut w = [lo[0], lo[1], lo[2], lo[3], hi[0], hi[1], hi[2], hi[3]];
        let mut leaves = self.leaves;
        while leaves != 0 {
            let j = leaves.trailing_zeros() as usize;
            leaves &= leaves - 1;
            w[j] = leaf((self.child[j] & !LEAF) as usize, w[j]);
        }
        if let Some(f) = f {
            for (wj, fj) in w.iter_mut().zip(f) {
                *wj *= fj;
            }
        }
        w
    }
}

/// The sum of a node's weights, in a fixed order.
#[inline]
fn sum(w: &[f32; WIDTH]) -> f32 {
    ((w[0] + w[1]) + (w[2] + w[3])) + ((w[4] + w[5]) + (w[6] + w[7]))
}

/// An eight-wide tree over bounded lights.
pub struct LightTree {
    nodes: Vec<Node>,
    /// The root's own bounds (all the lights'), in lane 0.
    top: Bounds4,
    /// Per light (the caller's index): its path from the root, three bits a step (the
    /// child's lane, step k in bits 3k to 3k + 2), and the path's length.
    trails: Vec<(u128, u8)>,
}

/// Steps a trail holds.
const MAX_DEPTH: usize = 32;

impl LightTree {
    /// The tree over `lights` (the bounds of each, by the caller's index); `None` for none.
    pub fn build(lights: &[LightBounds]) -> Option<LightTree> {
        if lights.is_empty() {
            return None;
        }
        // Light indices carry the LEAF bit beside them.
        assert!(lights.len() < LEAF as usize, "{} lights", lights.len());
        let mut binary = Vec::with_capacity(2 * lights.len());
        let mut order: Vec<u32> = (0..lights.len() as u32).collect();
        split(lights, &mut order, &mut binary);
        let mut tree = LightTree {
            nodes: Vec::with_capacity(lights.len()),
            top: Bounds4::pack(&[binary[0].bounds]),
            trails: vec![(0, 0); lights.len()],
        };
        tree.collapse(&binary, 0, 0, 0);
        Some(tree)
    }

    /// Adds the eight-wide node over binary node `b`'s subtree (at depth `depth`, path
    /// `trail`), and its descendants; returns its index.
    fn collapse(&mut self, binary: &[Binary], b: u32, depth: usize, trail: u128) -> u32 {
        // Binary median splits halve the count at every level and a node here is at least one
        // binary level below its parent, so a path is at most ⌈log₂ n⌉ + 1 ≤ 32 steps long
        // (96 bits of a trail).
        debug_assert!(depth < MAX_DEPTH);
        let inner = |k: u32| binary[k as usize].light == u32::MAX;
        let mut kids = vec![b];
        if inner(b) {
            kids = vec![b + 1, binary[b as usize].right];
        }
        // Open the inner child with the most lights (the first of equals) until there are eight.
        while kids.len() < WIDTH {
            let Some(j) = (0..kids.len())
                .filter(|&j| inner(kids[j]))
                .max_by_key(|&j| (binary[kids[j] as usize].count, std::cmp::Reverse(j)))
            else {
                break;
            };
            let k = kids[j];
            kids[j] = k + 1;
            kids.insert(j + 1, binary[k as usize].right);
        }
        let bounds: Vec<LightBounds> = kids.iter().map(|&k| binary[k as usize].bounds).collect();
        let at = self.nodes.len() as u32;
        let (lo, hi) = bounds.split_at(bounds.len().min(4));
        self.nodes.push(Node {
            bounds: [Bounds4::pack(lo), Bounds4::pack(hi)],
            child: [u32::MAX; WIDTH],
            leaves: 0,
        });
        for (j, &k) in kids.iter().enumerate() {
            let path = trail | (j as u128) << (3 * depth);
            let child = if inner(k) {
                self.collapse(binary, k, depth + 1, path)
            } else {
                let light = binary[k as usize].light;
                self.trails[light as usize] = (path, depth as u8 + 1);
                self.nodes[at as usize].leaves |= 1 << j;
                LEAF | light
            };
            self.nodes[at as usize].child[j] = child;
        }
        at
    }

    /// Per node, eight lane factors from per-light factors `light`: a leaf lane's is its
    /// light's, an inner lane's the largest of its subtree's (a node's lanes at `8 × node`;
    /// lanes without a child 0). With them, [`LightTree::pick`] weighs a subtree by the most
    /// any of its lights keeps, so no light's chance falls below its own factor's share.
    pub fn lane_factors(&self, light: impl Fn(usize) -> f32) -> Vec<f32> {
        let mut f = vec![0.0f32; WIDTH * self.nodes.len()];
        // Children come after their parent (`collapse`): from the last node back, a child's
        // lanes are done before its parent reads them.
        for (i, node) in self.nodes.iter().enumerate().rev() {
            for (j, &c) in node.child.iter().enumerate() {
                f[WIDTH * i + j] = match c {
                    u32::MAX => 0.0,
                    c if c & LEAF != 0 => light((c & !LEAF) as usize),
                    c => f[WIDTH * c as usize..WIDTH * (c as usize + 1)]
                        .iter()
                        .fold(0.0, |a: f32, &b| a.max(b)),
                };
            }
        }
        f
    }

    /// The root's importance at (`x`, `n`) (all the lights' bounds together).
    pub fn root_importance(&self, x: Vec3A, n: Option<Vec3A>) -> f32 {
        self.top.importance(x, n)[0]
    }

    /// Walks from the root choosing children with `u` (in [0, 1), rescaled at each step):
    /// the chosen light and the probability of that walk, or `None` where no light reaches.
    /// With `lanes` ([`LightTree::lane_factors`]) each child's weight is multiplied by its
    /// lane's factor.
    pub fn pick(
        &self,
        x: Vec3A,
        n: Option<Vec3A>,
        mut u: f32,
        leaf: impl Fn(usize, f32) -> f32,
        lanes: Option<&[f32]>,
    ) -> Option<(usize, f32)> {
        let mut i = 0usize;
        let mut p = 1.0f32;
        loop {
            let node = &self.nodes[i];
            let w = node.weights(x, n, &leaf, lanes.map(|f| &f[WIDTH * i..WIDTH * (i + 1)]));
            let total = sum(&w);
            if total.is_nan() || total <= 0.0 {
                return None;
            }
            // The first child whose running sum passes the target; where rounding leaves the
            // target at or above the sum, the last child that can contribute.
            let target = u * total;
            let (mut lane, mut before, mut acc) = (0, 0.0f32, 0.0f32);
            for (j, &wj) in w.iter().enumerate() {
                if wj > 0.0 {
                    (lane, before) = (j, acc);
                    acc += wj;
                    if target < acc {
                        break;
                    }
                }
            }
            p *= w[lane] / total;
            u = ((target - before) / w[lane]).clamp(0.0, ONE_BELOW);
            let c = node.child[lane];
            if c & LEAF != 0 {
                return Some(((c & !LEAF) as usize, p));
            }
            i = c as usize;
        }
    }

    /// Probability that [`LightTree::pick`] at (`x`, `n`) ends at light `k`.
    pub fn prob(
        &self,
        k: usize,
        x: Vec3A,
        n: Option<Vec3A>,
        leaf: impl Fn(usize, f32) -> f32,
        lanes: Option<&[f32]>,
    ) -> f32 {
        let (trail, depth) = self.trails[k];
        let mut i = 0usize;
        let mut p = 1.0f32;
        for step in 0..depth as usize {
            let node = &self.nodes[i];
            let w = node.weights(x, n, &leaf, lanes.map(|f| &f[WIDTH * i..WIDTH * (i + 1)]));
            let total = sum(&w);
            let lane = (trail >> (3 * step) & 7) as usize;
            if total.is_nan() || total <= 0.0 || w[lane] <= 0.0 {
                return 0.0;
            }
            p *= w[lane] / total;
            i = node.child[lane] as usize;
        }
        p
    }
}

/// Appends the binary tree over `ids` to `nodes`, root first.
fn split(lights: &[LightBounds], ids: &mut [u32], nodes: &mut Vec<Binary>) {
    if ids.len() == 1 {
        nodes.push(Binary {
            bounds: lights[ids[0] as usize],
            count: 1,
            light: ids[0],
            right: u32::MAX,
        });
        return;
    }
    // Median split along the longest axis of the lights' centres; ties by index, so the tree
    // is a function of the input order alone.
    let (mut lo, mut hi) = (Vec3A::splat(f32::INFINITY), Vec3A::splat(f32::NEG_INFINITY));
    for &k in ids.iter() {
        let c = lights[k as usize].centre();
        lo = lo.min(c);
        hi = hi.max(c);
    }
    let ext = hi - lo;
    let axis = if ext.x >= ext.y && ext.x >= ext.z {
        0
    } else if ext.y >= ext.z {
        1
    } else {
        2
    };
    ids.sort_by(|&a, &b| {
        let (ca, cb) = (
            lights[a as usize].centre()[axis],
            lights[b as usize].centre()[axis],
        );
        ca.total_cmp(&cb).then(a.cmp(&b))
    });
    let at = nodes.len();
    nodes.push(Binary {
        bounds: lights[ids[0] as usize],
        count: ids.len() as u32,
        light: u32::MAX,
        right: 0,
    });
    let (left_ids, right_ids) = ids.split_at_mut(ids.len() / 2);
    split(lights, left_ids, nodes);
    let right = nodes.len();
    split(lights, right_ids, nodes);
    nodes[at].bounds = nodes[at + 1].bounds.union(&nodes[right].bounds);
    nodes[at].right = right as u32;
}

/// The largest f32 below 1.
const ONE_BELOW: f32 = 1.0 - f32::EPSILON / 2.0;

#[cfg(test)]
#[path = "light_tree_tests.rs"]
mod tests;
