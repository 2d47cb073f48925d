//! Closest-hit and any-hit traversal of an obvhs CWBVH with eyeadapt's own node test: the
//! top level of an instanced scene (each mesh's own structure is walked by
//! [`crate::wide_walk`]).
//!
//! obvhs's node test turns each child's 6 quantised plane bytes into floats one at a time (48
//! scalar conversions per node), which made node tests a quarter of all instructions on the
//! Cornell box. Here the bytes of four children are widened and converted together (SSE2
//! unpack + `cvtdq2ps`), and the near/far planes are chosen with min/max instead of branches.
//! The arithmetic is otherwise the same operation for operation (multiply then add, the same
//! min/max order, the same epsilon), so the hit masks are bit-identical to obvhs's
//! `CwBvhNode::intersect_ray` — `tests` checks this on random rays and real nodes — with one
//! deliberate exception: a direction component of −0.0 (obvhs's `d < 0.0` test calls it
//! positive while its 1/d is negative, so obvhs takes the far plane as the near one and misses
//! the node; min/max takes the right one). The traversal loop ([`walk`]) is obvhs's `traverse!`
//! macro, except that it hands over a node's hit triangles together, so that leaves can be
//! tested four at a time ([`crate::tri4`]), and that the node test is the caller's choice
//! ([`walk_with`]).
use crate::isa::NodeTest;
use glam::UVec2;
#[cfg(target_arch = "x86_64")]
use glam::Vec3A;
use obvhs::cwbvh::node::CwBvhNode;
use obvhs::cwbvh::{CwBvh, Traversal};
use obvhs::faststack::FastStack;
use obvhs::ray::{Ray, RayHit};

/// obvhs's lower bound on a child's entry distance (its `node::EPSILON`).
pub(crate) const NODE_EPSILON: f32 = 0.0001;

/// A node's quantised child planes: min x, max x, min y, max y, min z, max z, 8 children each.
#[inline(always)]
pub(crate) fn plane_fields(node: &CwBvhNode) -> [&[u8; 8]; 6] {
    [
        &node.child_min_x,
        &node.child_max_x,
        &node.child_min_y,
        &node.child_max_y,
        &node.child_min_z,
        &node.child_max_z,
    ]
}

/// Bitmask of the node's children that `ray` enters within (ε, tmax), in obvhs's hit-mask
/// encoding (child bits shifted by their traversal priority or primitive offset).
#[cfg(target_arch = "x86_64")]
#[inline(always)]
pub fn node_hits(node: &CwBvhNode, ray: &Ray, oct_inv4: u32) -> u32 {
    mask_by_meta(
        node,
        oct_inv4,
        entered(box_of(node), ray, byte_planes(node)),
    )
}

/// Field `f` of the node's quantised planes (min x, max x, min y, max y, min z, max z) of
/// children 0-3 and 4-7, widened and converted to floats.
#[cfg(target_arch = "x86_64")]
#[inline(always)]
fn byte_planes(
    node: &CwBvhNode,
) -> impl Fn(usize) -> (std::arch::x86_64::__m128, std::arch::x86_64::__m128) {
    use std::arch::x86_64::*;
    let fields = plane_fields(node);
    // SAFETY: SSE2 is part of the x86_64 baseline; the loads read 8 bytes of [u8; 8] fields.
    move |f| unsafe {
        let v = _mm_loadl_epi64(fields[f].as_ptr() as *const __m128i);
        let zero = _mm_setzero_si128();
        let w = _mm_unpacklo_epi8(v, zero);
        (
            _mm_cvtepi32_ps(_mm_unpacklo_epi16(w, zero)),
            _mm_cvtepi32_ps(_mm_unpackhi_epi16(w, zero)),
        )
    }
}

/// The node's quantisation step per axis and its origin, decoded.
#[cfg(target_arch = "x86_64")]
#[inline(always)]
pub(crate) fn box_of(node: &CwBvhNode) -> (Vec3A, Vec3A) {
    (node.compute_extent(), Vec3A::from(node.p))
}

/// The node test: for children 0-3 and 4-7, all ones in the lanes of the children `ray`
/// enters within (ε, tmax), with `extent` and `origin` the node's ([`box_of`]) and
/// `planes(f)` giving field `f` (min x, max x, min y, max y, min z, max z) of children 0-3 and
/// 4-7 as floats.
#[cfg(target_arch = "x86_64")]
#[inline(always)]
fn entered(
    (extent, origin): (Vec3A, Vec3A),
    ray: &Ray,
    planes: impl Fn(usize) -> (std::arch::x86_64::__m128, std::arch::x86_64::__m128),
) -> [std::arch::x86_64::__m128; 2] {
    use std::arch::x86_64::*;
    let adj_dir = extent * ray.inv_direction;
    let adj_org = (origin - ray.origin) * ray.inv_direction;
    // SAFETY: SSE2 is part of the x86_64 baseline.
    unsafe {
        // For one axis: entry and exit distances of both halves. With a finite ray (obvhs
        // makes every 1/direction finite) t = q·d + o is monotonic in q under rounding, so
        // min/max picks exactly the plane a sign test would.
        let axis = |a: usize, d: f32, o: f32| {
            let (lo0, lo1) = planes(2 * a);
            let (hi0, hi1) = planes(2 * a + 1);
            let (d, o) = (_mm_set1_ps(d), _mm_set1_ps(o));
            let t = |q: __m128| _mm_add_ps(_mm_mul_ps(q, d), o);
            let (a0, b0, a1, b1) = (t(lo0), t(hi0), t(lo1), t(hi1));
            (
                [_mm_min_ps(a0, b0), _mm_min_ps(a1, b1)],
                [_mm_max_ps(a0, b0), _mm_max_ps(a1, b1)],
            )
        };
        let (nx, fx) = axis(0, adj_dir.x, adj_org.x);
        let (ny, fy) = axis(1, adj_dir.y, adj_org.y);
        let (nz, fz) = axis(2, adj_dir.z, adj_org.z);
        let eps = _mm_set1_ps(NODE_EPSILON);
        let tmax = _mm_set1_ps(ray.tmax);
        [0, 1].map(|h| {
            let near = _mm_max_ps(nx[h], _mm_max_ps(ny[h], nz[h]));
            let far = _mm_min_ps(fx[h], _mm_min_ps(fy[h], fz[h]));
            let near = _mm_max_ps(near, eps);
            let far = _mm_min_ps(far, tmax);
            _mm_cmple_ps(near, far)
        })
    }
}

/// The hit mask of the children entered (`lanes`, from [`entered`]), the way obvhs makes it:
/// each entered child's bits from `get_child_and_index_bits`, one child at a time.
#[cfg(target_arch = "x86_64")]
#[inline(always)]
fn mask_by_meta(node: &CwBvhNode, oct_inv4: u32, lanes: [std::arch::x86_64::__m128; 2]) -> u32 {
    use std::arch::x86_64::_mm_movemask_ps;
    // SAFETY: SSE2 is part of the x86_64 baseline.
    let m = unsafe { _mm_movemask_ps(lanes[0]) | _mm_movemask_ps(lanes[1]) << 4 } as u32;
    mask_from_lanes(node, oct_inv4, m)
}

/// The hit mask of the children whose bits are set in `m` (bit c: child c entered), the way
/// obvhs makes it: each entered child's bits from `get_child_and_index_bits`, one at a time.
#[inline(always)]
pub(crate) fn mask_from_lanes(node: &CwBvhNode, oct_inv4: u32, mut m: u32) -> u32 {
    let (child_bits8, bit_index8) = node.get_child_and_index_bits(oct_inv4);
    let mut hit_mask = 0;
    while m != 0 {
        let c = m.trailing_zeros() * 8;
        m &= m - 1;
        hit_mask |= (((child_bits8 >> c) as u32) & 0xff) << (((bit_index8 >> c) as u32) & 0xff);
    }
    hit_mask
}

#[cfg(not(target_arch = "x86_64"))]
#[inline(always)]
pub fn node_hits(node: &CwBvhNode, ray: &Ray, oct_inv4: u32) -> u32 {
    node.intersect_ray(ray, oct_inv4)
}

/// The number of set bits of each byte: the x86-64 baseline has no POPCNT, so `count_ones`
/// is a dozen instructions and a lookup is one ([`NodeTest::ones8`] of the baseline; the
/// AVX2 queries, compiled with POPCNT, count with it: a shorter chain from node to node).
pub(crate) const ONES: [u8; 256] = {
    let mut t = [0; 256];
    let mut i = 0;
    while i < 256 {
        t[i] = (i as u32).count_ones() as u8;
        i += 1;
    }
    t
};

/// Walks the nodes `ray` enters (node test: `test`'s metadata form), in obvhs's order (its
/// `traverse!` macro, step for step), and hands each entered node's hit leaf triangles to
/// `leaves(base, mask, ray)`: slot `base + i` for each set bit i of `mask` (at most 24 bits).
/// `leaves` may shorten `ray.tmax` (the node tests after it see the shorter ray) and returns
/// true to stop the walk.
///
/// `state` is scratch space, reset here: reusing one per path saves zeroing obvhs's 256-byte
/// traversal stack for every ray (a `memset` call, 2 % of a Cornell-box render).
#[inline(always)]
pub fn walk(
    bvh: &CwBvh,
    test: impl NodeTest,
    ray: &mut Ray,
    state: &mut Traversal,
    leaves: impl Leaves,
) {
    walk_with(
        bvh,
        test,
        ray,
        state,
        |i, r, oct| test.meta(&bvh.nodes[i], r, oct),
        leaves,
    );
}

/// What a walk does with an entered node's hit triangles: `visit(base, mask, ray)` gets slot
/// `base + i` for each set bit i of `mask`, may shorten `ray.tmax`, and returns true to stop
/// the walk. Any such closure is one; [`crate::accel`]'s leaf tests are types of their own
/// whose `visit` is inlined into the walk (a closure's body may stay a call, with the walk's
/// state spilled around it).
pub trait Leaves {
    fn visit(&mut self, base: u32, mask: u32, ray: &mut Ray) -> bool;
}

impl<F: FnMut(u32, u32, &mut Ray) -> bool> Leaves for F {
    #[inline(always)]
    fn visit(&mut self, base: u32, mask: u32, ray: &mut Ray) -> bool {
        self(base, mask, ray)
    }
}

/// [`walk`] with its node test given: `hits(i, ray, oct_inv4)` is [`node_hits`] of node `i`
/// (or a test that gives the same masks).
#[inline(always)]
pub fn walk_with(
    bvh: &CwBvh,
    isa: impl NodeTest,
    ray: &mut Ray,
    state: &mut Traversal,
    hits: impl Fn(usize, &Ray, u32) -> u32,
    mut leaves: impl Leaves,
) {
    let Some(mut at) = Cursor::start(bvh, isa, ray, state) else {
        return;
    };
    while !at.step(bvh, ray, state, &hits, &mut leaves) {}
}

/// Where a [`walk_with`] stands between two of its steps: the node group it is in and the
/// leaf triangles it has still to hand over. Two cursors on two rays can be stepped in turn
/// ([`crate::traverse_pair`]); each walks exactly as it would alone.
#[derive(Clone, Copy)]
pub struct Cursor<T> {
    /// (first child node, child hit bits in the top byte | imask).
    nodes: UVec2,
    /// (first slot, slot bits).
    prims: UVec2,
    oct_inv4: u32,
    /// Whose bit counts the walk uses ([`NodeTest::ones8`]).
    isa: T,
}

impl<T: NodeTest> Cursor<T> {
    /// A walk of `ray` from the root, `state` reset for it; `None` for an empty structure.
    #[inline(always)]
    pub fn start(bvh: &CwBvh, isa: T, ray: &Ray, state: &mut Traversal) -> Option<Cursor<T>> {
        if bvh.nodes.is_empty() {
            return None;
        }
        state.reinit(ray.direction);
        Some(Cursor {
            nodes: UVec2::new(0, 0x8000_0000),
            prims: UVec2::ZERO,
            oct_inv4: state.oct_inv4,
            isa,
        })
    }

    /// One round of the walk (obvhs's `traverse!` loop body): the pending leaves, then one
    /// node; true when the walk is over (`leaves` stopped it, or nothing is left). Not to be
    /// called again after it returned true.
    #[inline(always)]
    pub fn step(
        &mut self,
        bvh: &CwBvh,
        ray: &mut Ray,
        state: &mut Traversal,
        hits: &impl Fn(usize, &Ray, u32) -> u32,
        leaves: &mut impl Leaves,
    ) -> bool {
        if self.prims.y != 0 && leaves.visit(self.prims.x, self.prims.y, ray) {
            return true;
        }
        self.prims = UVec2::ZERO;
        if self.nodes.y & 0xff00_0000 != 0 {
            let hits_imask = self.nodes.y;
            // `| 1` tells the compiler the value is not 0 (a bit of the top byte is set), so
            // this is one `bsr` without the baseline's zero fix-up.
            let child_bit = 31 - (hits_imask | 1).leading_zeros();
            self.nodes.y &= !(1u32 << child_bit);
            if self.nodes.y & 0xff00_0000 != 0 {
                state.stack.push(self.nodes);
            }
            let slot_index = (child_bit - 24) ^ (self.oct_inv4 & 0xff);
            // The inner children before this one: imask bits below its slot (a byte).
            let relative_index = self
                .isa
                .ones8(hits_imask & !(u32::MAX << slot_index) & 0xff);
            let index = (self.nodes.x + relative_index) as usize;
            let node = &bvh.nodes[index];
            let hit_mask = hits(index, ray, self.oct_inv4);
            self.nodes = UVec2::new(
                node.child_base_idx,
                (hit_mask & 0xff00_0000) | node.imask as u32,
            );
            self.prims = UVec2::new(node.primitive_base_idx, hit_mask & 0x00ff_ffff);
        } else {
            self.nodes = UVec2::ZERO;
        }
        if self.prims.y == 0 && self.nodes.y & 0xff00_0000 == 0 {
            if state.stack.is_empty() {
                return true;
            }
            self.nodes = state.stack.pop_fast();
        }
        false
    }
}

/// The closest primitive `ray` hits (slot and distance), if any. `prim_hit(slot, ray)` is the
/// distance to primitive `slot` within the ray's current (tmin, tmax), or +∞: for a top-level
/// structure the closest hit inside one instance. Slots are tested highest bit first.
#[inline(always)]
pub fn closest_hit(
    bvh: &CwBvh,
    test: impl NodeTest,
    ray: Ray,
    state: &mut Traversal,
    mut prim_hit: impl FnMut(u32, &Ray) -> f32,
) -> Option<RayHit> {
    let mut traverse_ray = ray;
    let mut hit = RayHit::none();
    walk(
        bvh,
        test,
        &mut traverse_ray,
        state,
        |base, mask, r: &mut Ray| {
            each_slot(base, mask, |slot| {
                let t = prim_hit(slot, r);
                if t < r.tmax {
                    hit.primitive_id = slot;
                    hit.t = t;
                    r.tmax = t;
                }
                false
            })
        },
    );
    (hit.t < ray.tmax).then_some(hit)
}

/// True when no primitive blocks `ray` within its (tmin, tmax); `prim_hit` and `state` as for
/// [`closest_hit`] (any finite distance below tmax blocks).
#[inline(always)]
pub fn unoccluded(
    bvh: &CwBvh,
    test: impl NodeTest,
    ray: Ray,
    state: &mut Traversal,
    mut prim_hit: impl FnMut(u32, &Ray) -> f32,
) -> bool {
    let mut miss = true;
    let mut ray = ray;
    walk(bvh, test, &mut ray, state, |base, mask, r: &mut Ray| {
        let blocked = each_slot(base, mask, |slot| prim_hit(slot, r) < r.tmax);
        miss &= !blocked;
        blocked
    });
    miss
}

/// Calls `visit(base + i)` for each set bit i of `mask`, highest first, until it returns true;
/// returns whether one did.
#[inline(always)]
fn each_slot(base: u32, mut mask: u32, mut visit: impl FnMut(u32) -> bool) -> bool {
    while mask != 0 {
        let bit = 31 - mask.leading_zeros();
        mask &= !(1 << bit);
        if visit(base + bit) {
            return true;
        }
    }
    false
}

#[cfg(test)]
#[path = "traverse_tests.rs"]
mod tests;
