//! A light tree: which of many lights next-event estimation samples from a shading point, in
//! time logarithmic in their number (Conty Estevez and Kulla, "Importance Sampling of Many
//! Lights with Adaptive Tree Splitting", 2018; the light BVH of pbrt-v4 and Blender Cycles).
//!
//! Every bounded light (area units, point and spot lights, textured spots, projectors) is a
//! leaf of a binary tree. A node bounds its lights' positions (a box), the directions they
//! emit into (a cone: axis, spread θ_o, and the emission's reach θ_e beyond it) and their
//! summed power. From a shading point x with normal n the node's *importance* is a
//! conservative estimate of the irradiance its lights can deliver: power / d² (d the distance
//! to the box's centre, clamped at the box's half-diagonal), times cos θ′, the largest
//! emission cosine any of its lights can have towards x (the angle to the axis, less the
//! spread, less the angle the box subtends), times the largest receiver cosine towards the box
//! (n against the direction to it, less the angle the box subtends). It is exactly 0 only
//! where no light of the node can deliver anything: x outside every emission cone, or the whole
//! box below x's tangent plane.
//!
//! Choosing walks from the root: at each node one child is taken with probability in
//! proportion to the two children's importances, and the sample number is rescaled to stay
//! uniform. A leaf's importance is its light's own exact one (`light_pick::importance`), so a
//! light that cannot contribute at x is never chosen there, and one that can always keeps a
//! positive probability (every ancestor bounds it): the estimator stays unbiased. The
//! probability of a given light, which MIS needs at emitter hits, is the product of the branch
//! probabilities along its path from the root, recomputed the same way.
//!
//! Lights without a position (directional lights and the environment) stay outside the tree
//! and compete with its root by their own importance. Everything is a pure function of the
//! scene and the shading point: no state, no dependence on threads.
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

/// Angles below this (in cosine terms) count as on the boundary: the exact zero tests are made
/// a little generous so that rounding never rejects a light that reaches x.
const SLACK: f32 = 1e-4;

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

/// What a node's importance reads, precomputed per node: the box's bounding sphere (centre,
/// radius) instead of its corners, and the spread's sine.
#[derive(Clone, Copy, Debug)]
struct Cone {
    centre: Vec3A,
    radius: f32,
    axis: Vec3A,
    cos_o: f32,
    sin_o: f32,
    cos_e: f32,
    phi: f32,
}

impl Cone {
    fn of(b: &LightBounds) -> Cone {
        Cone {
            centre: b.centre(),
            radius: 0.5 * (b.hi - b.lo).length(),
            axis: b.axis,
            cos_o: b.cos_o,
            sin_o: sin_of(b.cos_o),
            cos_e: b.cos_e,
            phi: b.phi,
        }
    }

    /// Conservative irradiance estimate at `x` (normal `n`; none for a point that looks in
    /// every direction). 0 only where nothing inside can reach `x`.
    #[inline]
    fn importance(&self, x: Vec3A, n: Option<Vec3A>) -> f32 {
        let to_x = x - self.centre;
        let d2 = to_x.length_squared();
        let r2 = self.radius * self.radius;
        if d2 <= r2 || d2 <= 0.0 {
            // x inside the bounding sphere: every direction and cosine is possible.
            return self.phi / r2.max(1e-12);
        }
        let inv_d = 1.0 / d2.sqrt();
        // The cone of directions from x that meets the bounding sphere: half-angle θ_b.
        let sin_b = (self.radius * inv_d).min(1.0);
        let cos_b = (1.0 - sin_b * sin_b).max(0.0).sqrt();
        // Emitter side: angle from the cone's axis to x, less the spread, less θ_b.
        let cos_p = if self.cos_o <= -1.0 {
            1.0
        } else {
            let cos_w = (self.axis.dot(to_x) * inv_d).clamp(-1.0, 1.0);
            let (sin_x, cos_x) = sub_angle(sin_of(cos_w), cos_w, self.sin_o, self.cos_o);
            sub_angle(sin_x, cos_x, sin_b, cos_b).1
        };
        if cos_p < self.cos_e - SLACK {
            return 0.0;
        }
        // Receiver side: the largest cosine between n and a direction into the sphere.
        let cos_r = match n {
            Some(n) => {
                let cos_i = (-n.dot(to_x) * inv_d).clamp(-1.0, 1.0);
                let c = sub_angle(sin_of(cos_i), cos_i, sin_b, cos_b).1;
                if c < -SLACK {
                    return 0.0;
                }
                c
            }
            None => 1.0,
        };
        // Floors keep a node that can contribute choosable when rounding takes a cosine to 0.
        self.phi * cos_p.max(1e-3) * cos_r.max(1e-3) / d2.max(r2).max(1e-12)
    }
}

#[inline]
fn sin_of(cos: f32) -> f32 {
    (1.0 - cos * cos).max(0.0).sqrt()
}

/// (sin, cos) of max(0, a − b) for angles a, b in [0, π] given by their sines and cosines.
#[inline]
fn sub_angle(sin_a: f32, cos_a: f32, sin_b: f32, cos_b: f32) -> (f32, f32) {
    if cos_a >= cos_b {
        (0.0, 1.0)
    } else {
        (
            sin_a * cos_b - cos_a * sin_b,
            (cos_a * cos_b + sin_a * sin_b).min(1.0),
        )
    }
}

/// The narrowest cone (of those that grow one to reach the other) containing both cones.
fn cone_union(a: (Vec3A, f32), b: (Vec3A, f32)) -> (Vec3A, f32) {
    let (ta, tb) = (a.1.clamp(-1.0, 1.0).acos(), b.1.clamp(-1.0, 1.0).acos());
    let td = a.0.dot(b.0).clamp(-1.0, 1.0).acos();
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
    let axis = (a.0 * turn.cos() + perp / len * turn.sin()).normalize();
    // A little wider than computed, so that rounding never leaves a child's cone outside.
    (axis, (to + 1e-4).min(std::f32::consts::PI).cos())
}

#[derive(Clone, Copy, Debug)]
struct Node {
    bounds: LightBounds,
    cone: Cone,
    /// A leaf's light (an index into the caller's list), or u32::MAX for an inner node.
    light: u32,
    /// An inner node's second child (its first follows it).
    right: u32,
}

/// A binary tree over bounded lights.
pub struct LightTree {
    nodes: Vec<Node>,
    /// Per light (the caller's index): its path from the root, bit k set where the k-th step
    /// goes to the second child, and the path's length.
    trails: Vec<(u64, u8)>,
}

/// Bits of a trail.
const MAX_DEPTH: usize = 64;

impl LightTree {
    /// The tree over `lights` (the bounds of each, by the caller's index); `None` for none.
    pub fn build(lights: &[LightBounds]) -> Option<LightTree> {
        if lights.is_empty() {
            return None;
        }
        let mut tree = LightTree {
            nodes: Vec::with_capacity(2 * lights.len()),
            trails: vec![(0, 0); lights.len()],
        };
        let mut order: Vec<u32> = (0..lights.len() as u32).collect();
        tree.split(lights, &mut order, 0, 0);
        Some(tree)
    }

    /// Builds the subtree over `ids` (depth `depth`, path `trail`); returns its root's index.
    fn split(&mut self, lights: &[LightBounds], ids: &mut [u32], depth: usize, trail: u64) -> u32 {
        let at = self.nodes.len() as u32;
        // A median split halves the count at every level, so a path is at most
        // ⌈log₂ n⌉ + 1 < 64 steps long and fits the trail's bits.
        debug_assert!(depth < MAX_DEPTH);
        if ids.len() == 1 {
            let k = ids[0];
            self.trails[k as usize] = (trail, depth as u8);
            self.nodes.push(Node {
                bounds: lights[k as usize],
                cone: Cone::of(&lights[k as usize]),
                light: k,
                right: u32::MAX,
            });
            return at;
        }
        // Median split along the longest axis of the lights' centres; ties by index, so the
        // tree is a function of the input order alone.
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
        self.nodes.push(Node {
            bounds: lights[ids[0] as usize],
            cone: Cone::of(&lights[ids[0] as usize]),
            light: u32::MAX,
            right: 0,
        });
        let mid = ids.len() / 2;
        let (left_ids, right_ids) = ids.split_at_mut(mid);
        let left = self.split(lights, left_ids, depth + 1, trail);
        let right = self.split(lights, right_ids, depth + 1, trail | (1 << depth));
        let bounds = self.nodes[left as usize]
            .bounds
            .union(&self.nodes[right as usize].bounds);
        self.nodes[at as usize].bounds = bounds;
        self.nodes[at as usize].cone = Cone::of(&bounds);
        self.nodes[at as usize].right = right;
        at
    }

    /// The root's importance at (`x`, `n`) (all the lights' bounds together).
    pub fn root_importance(&self, x: Vec3A, n: Option<Vec3A>) -> f32 {
        self.nodes[0].cone.importance(x, n)
    }

    /// Importance of node `i` at (`x`, `n`): a leaf's from `leaf(light)`, the light's own.
    #[inline]
    fn node_importance(
        &self,
        i: u32,
        x: Vec3A,
        n: Option<Vec3A>,
        leaf: &impl Fn(usize) -> f32,
    ) -> f32 {
        let node = &self.nodes[i as usize];
        if node.light != u32::MAX {
            leaf(node.light as usize)
        } else {
            node.cone.importance(x, n)
        }
    }

    /// Walks from the root choosing children with `u` (in [0, 1), rescaled at each step):
    /// the chosen light and the probability of that walk, or `None` where no light reaches.
    pub fn pick(
        &self,
        x: Vec3A,
        n: Option<Vec3A>,
        mut u: f32,
        leaf: impl Fn(usize) -> f32,
    ) -> Option<(usize, f32)> {
        let mut i = 0u32;
        let mut p = 1.0f32;
        loop {
            let node = &self.nodes[i as usize];
            if node.light != u32::MAX {
                return Some((node.light as usize, p));
            }
            let (a, b) = (i + 1, node.right);
            let wa = self.node_importance(a, x, n, &leaf);
            let wb = self.node_importance(b, x, n, &leaf);
            let total = wa + wb;
            if total.is_nan() || total <= 0.0 {
                return None;
            }
            let pa = wa / total;
            if u < pa {
                u = (u / pa).min(ONE_BELOW);
                p *= pa;
                i = a;
            } else {
                u = ((u - pa) / (1.0 - pa)).clamp(0.0, ONE_BELOW);
                p *= 1.0 - pa;
                i = b;
            }
        }
    }

    /// Probability that [`LightTree::pick`] at (`x`, `n`) ends at light `k`.
    pub fn prob(&self, k: usize, x: Vec3A, n: Option<Vec3A>, leaf: impl Fn(usize) -> f32) -> f32 {
        let (trail, depth) = self.trails[k];
        let mut i = 0u32;
        let mut p = 1.0f32;
        for step in 0..depth as usize {
            let node = &self.nodes[i as usize];
            let (a, b) = (i + 1, node.right);
            let wa = self.node_importance(a, x, n, &leaf);
            let wb = self.node_importance(b, x, n, &leaf);
            let total = wa + wb;
            if total.is_nan() || total <= 0.0 {
                return 0.0;
            }
            let pa = wa / total;
            if trail >> step & 1 == 0 {
                p *= pa;
                i = a;
            } else {
                p *= 1.0 - pa;
                i = b;
            }
        }
        p
    }
}

/// The largest f32 below 1.
const ONE_BELOW: f32 = 1.0 - f32::EPSILON / 2.0;
