//! The walk of a [`WideBvh`]: nearest child first, with the entry distances on the stack.
//!
//! At each node the eight boxes are tested together ([`crate::wide_test`]). The node's leaf
//! children that the ray enters are handed over together, as slot bits ([`Leaves`]: a mesh
//! tests its triangles four at a time, the instance level each instance's mesh), and may
//! shorten the ray. Of the inner children entered, a lone one is entered directly; several
//! are pushed farthest first, so that the nearest is on top. A popped child is skipped when a
//! hit found since it was pushed is nearer than its box.
//!
//! The order depends only on the distances, which are the same bits on every instruction set,
//! so the walk visits the same nodes in the same order everywhere; of equally near children the
//! later one is entered first. A walk that only asks whether anything is hit (a shadow ray),
//! or wants every hit, gains nothing from the order: it pushes in child order, unsorted
//! (`ORDERED` false; shadow rays 2-5 % fewer instructions). Its leaves never shorten the ray,
//! so every child it pushed is still within reach when popped, and it skips that check
//! (2.6 % fewer). In a structure too large for the core's L2 the inner children entered are
//! prefetched before the node's leaves are tested (a [`crate::isa::Prefetching`] node test,
//! which [`crate::accel`] uses where [`WideBvh::prefetch`] says).
use crate::accel::SlotHit;
use crate::isa::NodeTest;
use crate::prefetch::prefetch;
use crate::wide_bvh::WideBvh;
use crate::wide_test::Slab;
use obvhs::ray::Ray;

/// What a walk does with an entered node's hit leaves: `visit(base, mask, ray)` gets slot
/// `base + i` for each set bit i of `mask`, may shorten `ray.tmax` (the node tests after it
/// see the shorter ray), and returns true to stop the walk. Any such closure is one;
/// [`crate::accel`]'s leaf tests are types of their own whose `visit` is inlined into the walk
/// (a closure's body may stay a call, with the walk's state spilled around it).
pub trait Leaves {
    fn visit(&mut self, base: u32, mask: u32, ray: &mut Ray) -> bool;
}

impl<F: FnMut(u32, u32, &mut Ray) -> bool> Leaves for F {
    #[inline(always)]
    fn visit(&mut self, base: u32, mask: u32, ray: &mut Ray) -> bool {
        self(base, mask, ray)
    }
}

/// A child waiting on the stack: its node index and the distance at which the ray enters it.
#[derive(Clone, Copy, Debug, Default)]
struct Entry {
    node: u32,
    t: f32,
}

/// A walk's stack, kept from ray to ray so that it is allocated once per worker. It grows as
/// a deep structure needs (each level of the current path holds at most seven children).
#[derive(Clone, Debug, Default)]
pub struct WalkStack {
    entries: Vec<Entry>,
}

/// Where a walk stands between two of its steps: the node it enters next and the stack's
/// height. Two cursors on two rays can be stepped in turn ([`crate::traverse_pair`]).
#[derive(Clone, Copy, Debug)]
pub struct Cursor8<T, const ORDERED: bool> {
    node: u32,
    height: usize,
    slab: Slab,
    isa: T,
}

impl<T: NodeTest, const ORDERED: bool> Cursor8<T, ORDERED> {
    /// A walk of `ray` from the root; `None` for an empty structure.
    #[inline(always)]
    pub fn start(bvh: &WideBvh, isa: T, ray: &Ray) -> Option<Cursor8<T, ORDERED>> {
        (!bvh.nodes.is_empty()).then(|| Cursor8 {
            node: 0,
            height: 0,
            slab: Slab::new(ray),
            isa,
        })
    }

    /// One node of the walk: its test, its leaves, the choice of the next node. True when the
    /// walk is over (`leaves` stopped it, or nothing is left); not to be called after that.
    #[inline(always)]
    pub fn step(
        &mut self,
        bvh: &WideBvh,
        ray: &mut Ray,
        stack: &mut WalkStack,
        leaves: &mut impl Leaves,
    ) -> bool {
        let node = &bvh.nodes[self.node as usize];
        let (mask, near) = self.isa.node8(node, &self.slab, ray.tmax);
        let leaf = mask & node.leaves;
        // The inner children entered are asked for before the leaves are tested, so that the
        // next node's lines are on their way while the triangles are (large structures only).
        let mut pre = if T::PREFETCH { mask & !node.leaves } else { 0 };
        while pre != 0 {
            let c = (pre.trailing_zeros() & 7) as usize;
            pre &= pre - 1;
            prefetch_node(bvh, node.child[c]);
        }
        if leaf != 0 {
            let mut slots = 0;
            let mut m = leaf;
            while m != 0 {
                slots |= node.child[(m.trailing_zeros() & 7) as usize];
                m &= m - 1;
            }
            if leaves.visit(node.prim_base, slots, ray) {
                return true;
            }
        }
        let mut inner = mask & !node.leaves;
        if inner != 0 && inner & (inner - 1) == 0 {
            let c = (inner.trailing_zeros() & 7) as usize;
            if !ORDERED || near[c] <= ray.tmax {
                self.node = node.child[c];
                return false;
            }
        } else if inner != 0 {
            if stack.entries.len() < self.height + 8 {
                stack.entries.resize(self.height + 8, Entry::default());
            }
            let (base, e) = (self.height, &mut stack.entries);
            // Insertion into the run pushed here, kept farthest first.
            while inner != 0 {
                let c = (inner.trailing_zeros() & 7) as usize;
                inner &= inner - 1;
                let new = Entry {
                    node: node.child[c],
                    t: near[c],
                };
                let mut j = self.height;
                while ORDERED && j > base && e[j - 1].t < new.t {
                    e[j] = e[j - 1];
                    j -= 1;
                }
                e[j] = new;
                self.height += 1;
            }
        }
        while self.height > 0 {
            self.height -= 1;
            let e = stack.entries[self.height];
            if !ORDERED || e.t <= ray.tmax {
                self.node = e.node;
                return false;
            }
        }
        true
    }
}

/// Asks for node `i`'s first and third cache lines (the adjacent-line prefetcher brings the
/// other two; asking for all four measured no better at 1M triangles).
#[inline(always)]
fn prefetch_node(bvh: &WideBvh, i: u32) {
    let p = bvh.nodes.as_ptr().wrapping_add(i as usize) as *const u8;
    prefetch(p);
    prefetch(p.wrapping_add(128));
}

/// Walks the nodes `ray` enters and hands each entered node's hit leaf slots to `leaves`,
/// which may stop the walk. `ORDERED`: nearest child first, and `leaves` may shorten the ray
/// (a closest-hit walk); otherwise child order, and `leaves` must leave the ray as it is (a
/// shadow or every-hit walk).
#[inline(always)]
pub fn walk8<const ORDERED: bool>(
    bvh: &WideBvh,
    isa: impl NodeTest,
    ray: &mut Ray,
    stack: &mut WalkStack,
    mut leaves: impl Leaves,
) {
    let Some(mut at) = Cursor8::<_, ORDERED>::start(bvh, isa, ray) else {
        return;
    };
    while !at.step(bvh, ray, stack, &mut leaves) {}
}

/// The closest primitive `ray` hits (distance and slot), if any. `prim_hit(slot, ray)` is the
/// distance to primitive `slot` within the ray's current (tmin, tmax), or +∞: for the instance
/// level, the closest hit inside one instance. A node's slots are tested highest first; of
/// equal distances the first tested wins.
#[inline(always)]
pub fn closest_hit8(
    bvh: &WideBvh,
    isa: impl NodeTest,
    ray: Ray,
    stack: &mut WalkStack,
    mut prim_hit: impl FnMut(u32, &Ray) -> f32,
) -> Option<SlotHit> {
    let mut best = None;
    let leaves = |base: u32, mask: u32, r: &mut Ray| {
        each_slot(base, mask, |slot| {
            let t = prim_hit(slot, r);
            if t < r.tmax {
                best = Some(SlotHit { t, slot });
                r.tmax = t;
            }
            false
        })
    };
    walk8::<true>(bvh, isa, &mut { ray }, stack, leaves);
    best
}

/// True when no primitive blocks `ray` within its (tmin, tmax); `prim_hit` as for
/// [`closest_hit8`] (any distance below tmax blocks).
#[inline(always)]
pub fn unoccluded8(
    bvh: &WideBvh,
    isa: impl NodeTest,
    ray: Ray,
    stack: &mut WalkStack,
    mut prim_hit: impl FnMut(u32, &Ray) -> f32,
) -> bool {
    let mut free = true;
    let leaves = |base: u32, mask: u32, r: &mut Ray| {
        let blocked = each_slot(base, mask, |slot| prim_hit(slot, r) < r.tmax);
        free &= !blocked;
        blocked
    };
    walk8::<false>(bvh, isa, &mut { ray }, stack, leaves);
    free
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
#[path = "wide_walk_tests.rs"]
pub(crate) mod tests;
