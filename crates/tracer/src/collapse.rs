//! Eight-wide nodes collapsed from obvhs's binary BVH (its PLOC build and reinsertion): a
//! mesh's, with every leaf one block of four triangles ([`crate::tri4::Tri4`]), and the
//! instance level's, with every leaf one instance.
//!
//! obvhs's own collapse (to its compressed CWBVH) runs an optimal cost search over every
//! binary node with eight child counts each, serially, and caps a leaf at three triangles
//! laid out back to back: a 1M-triangle build spent most of its time there, and 40 % of the
//! leaf visits of a walk touched two blocks, with fewer than half the lanes used. Here:
//!
//! 1. Bottom up, each binary subtree of at most four triangles is a leaf where the surface
//!    area heuristic says one block test over its box costs less than keeping its split
//!    (`BLOCK_COST` against `LEVEL_COST` per binary level an eight-wide node stands for).
//! 2. Top down, a node takes its binary children and opens the largest (by surface area)
//!    that is not a leaf, until it has eight or none is left to open (as Embree's BVH8
//!    builders do); its leaf children each get a block of their own, its inner children
//!    nodes of their own: the first breadth first, until 64 subtrees are left, then each of
//!    those depth first on any thread, appended in order.
//!
//! Both passes give the same nodes on any number of threads. The boxes are obvhs's, exact
//! (the triangles' own minima and maxima and their unions), so nothing is rounded: no
//! quantisation, tighter boxes than the CWBVH's.
use crate::wide_bvh::Node8;
use obvhs::bvh2::{Bvh2, node::Bvh2Node};
use rayon::prelude::*;
use std::collections::VecDeque;
use std::sync::atomic::{AtomicU64, Ordering::Relaxed};

/// The cost of testing one block of four triangles, relative to [`LEVEL_COST`].
const BLOCK_COST: f32 = 1.0;

/// The walk's cost per binary level: an eight-wide node stands for three, and its test, the
/// choice of child and the stack cost about two thirds of a block test (callgrind, 1k-triangle
/// closest-hit rays: ~110 + ~150 instructions over 3.8 nodes against ~118 per block). The
/// walk's instructions barely move between 0.1 and 10 (`bench --bvh-triangles`: ±1 %).
const LEVEL_COST: f32 = 0.25;

/// What a leaf holds.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Leaf {
    /// Up to four triangles, one block (a mesh).
    Block,
    /// One primitive (an instance, whose test is a walk of its own).
    Single,
}

impl Leaf {
    /// Primitives a leaf holds at most, and the slots it takes.
    fn max(self) -> u32 {
        match self {
            Leaf::Block => 4,
            Leaf::Single => 1,
        }
    }
}

/// Binary levels below the root that the bottom-up pass splits between threads.
const PARALLEL_LEVELS: u32 = 10;

/// Subtrees at which the top-down pass hands the rest to threads.
const PARALLEL_TASKS: usize = 64;

/// The collapsed nodes (node 0 the root; none for an empty BVH) and, per padded slot, the
/// input primitive there (`u32::MAX` for the padding after a leaf's last triangle). A leaf
/// child's slot bits are its block's lanes, relative to the node's `prim_base`. The same
/// nodes in the same order on any number of threads: the first nodes breadth first, then
/// each subtree left at that point depth first, one after another.
pub fn collapse(bvh: &Bvh2, leaf: Leaf) -> (Vec<Node8>, Vec<u32>) {
    if bvh.nodes.is_empty() || bvh.primitive_indices.is_empty() {
        return (Vec::new(), Vec::new());
    }
    let subs = Subtrees {
        packed: (0..bvh.nodes.len()).map(|_| AtomicU64::new(0)).collect(),
        leaf,
    };
    subtree(bvh, &subs, 0, 0);
    let mut out = Out::default();
    let mut todo = VecDeque::from([Pending {
        parent: u32::MAX,
        child: 0,
        b: 0,
    }]);
    while todo.len() < PARALLEL_TASKS
        && let Some(p) = todo.pop_front()
    {
        out.place(bvh, &subs, p, |q| todo.push_back(q));
    }
    let todo = Vec::from(todo);
    let parts: Vec<Out> = todo
        .par_iter()
        .map(|p| {
            let mut part = Out::default();
            let mut stack = vec![Pending {
                parent: u32::MAX,
                ..*p
            }];
            while let Some(q) = stack.pop() {
                out_place_depth_first(&mut part, bvh, &subs, q, &mut stack);
            }
            part
        })
        .collect();
    // Room for all of it at once: growing step by step copied the nodes again and again.
    out.nodes.reserve(parts.iter().map(|p| p.nodes.len()).sum());
    out.slots.reserve(parts.iter().map(|p| p.slots.len()).sum());
    for (p, part) in todo.iter().zip(parts) {
        out.append(p, part);
    }
    (out.nodes, out.slots)
}

/// [`Out::place`] with the inner children pushed so that the first is placed next.
fn out_place_depth_first(
    out: &mut Out,
    bvh: &Bvh2,
    subs: &Subtrees,
    p: Pending,
    stack: &mut Vec<Pending>,
) {
    let from = stack.len();
    out.place(bvh, subs, p, |q| stack.push(q));
    stack[from..].reverse();
}

/// A binary node still to become an eight-wide node, and where that node is referenced: child
/// `child` of node `parent` (none for a root).
#[derive(Clone, Copy)]
struct Pending {
    parent: u32,
    child: u8,
    b: u32,
}

/// Nodes and slots made so far.
#[derive(Default)]
struct Out {
    nodes: Vec<Node8>,
    slots: Vec<u32>,
}

impl Out {
    /// Makes the eight-wide node of `p`, its leaves' blocks, and hands each inner child on.
    fn place(&mut self, bvh: &Bvh2, subs: &Subtrees, p: Pending, mut inner: impl FnMut(Pending)) {
        let at = self.nodes.len() as u32;
        if p.parent != u32::MAX {
            self.nodes[p.parent as usize].child[p.child as usize] = at;
        }
        let mut kids = [0u32; 8];
        let kids = children(bvh, subs, p.b as usize, &mut kids);
        let mut n = Node8 {
            prim_base: self.slots.len() as u32,
            ..Node8::EMPTY
        };
        let mut blocks = 0;
        for (c, &k) in kids.iter().enumerate() {
            let aabb = bvh.nodes[k as usize].aabb;
            let (lo, hi) = (aabb.min.to_array(), aabb.max.to_array());
            for a in 0..3 {
                n.planes[2 * a][c] = lo[a];
                n.planes[2 * a + 1][c] = hi[a];
            }
            if subs.get(k as usize).leaf {
                let before = self.slots.len();
                leaf_prims(bvh, k as usize, &mut self.slots);
                let count = self.slots.len() - before;
                let size = subs.leaf.max() as usize;
                n.child[c] = ((1 << count) - 1) << (size * blocks);
                n.leaves |= 1 << c;
                blocks += 1;
                self.slots
                    .resize(self.slots.len().next_multiple_of(size), u32::MAX);
            }
        }
        self.nodes.push(n);
        for (c, &k) in kids.iter().enumerate() {
            if !subs.get(k as usize).leaf {
                inner(Pending {
                    parent: at,
                    child: c as u8,
                    b: k,
                });
            }
        }
    }

    /// Appends `part`, made apart (its node 0 the node of `p`), renumbered after what is here.
    fn append(&mut self, p: &Pending, part: Out) {
        let (node_base, slot_base) = (self.nodes.len() as u32, self.slots.len() as u32);
        self.nodes[p.parent as usize].child[p.child as usize] = node_base;
        self.nodes.extend(part.nodes.into_iter().map(|mut n| {
            n.prim_base += slot_base;
            for c in 0..8 {
                if n.leaves >> c & 1 == 0 && n.child[c] != 0 {
                    n.child[c] += node_base;
                }
            }
            n
        }));
        self.slots.extend(part.slots);
    }
}

/// What the bottom-up pass learned of one binary subtree.
#[derive(Clone, Copy, Default)]
struct Subtree {
    count: u32,
    cost: f32,
    leaf: bool,
}

impl Subtree {
    /// A binary leaf (PLOC's hold one primitive each).
    fn of_leaf(node: &Bvh2Node, leaf: Leaf) -> Subtree {
        assert!(
            node.prim_count <= leaf.max(),
            "a binary leaf of {} primitives: PLOC makes leaves of one",
            node.prim_count
        );
        Subtree {
            count: node.prim_count,
            cost: BLOCK_COST * node.aabb.half_area().max(0.0),
            leaf: true,
        }
    }

    /// An inner binary node over subtrees `l` and `r`: a leaf where one block test over its
    /// box costs no more than its split.
    fn of_inner(node: &Bvh2Node, l: Subtree, r: Subtree, max: u32) -> Subtree {
        let area = node.aabb.half_area().max(0.0);
        let count = l.count + r.count;
        let split = LEVEL_COST * area + l.cost + r.cost;
        let leaf = count <= max && BLOCK_COST * area <= split;
        Subtree {
            count: count.min(255),
            cost: if leaf { BLOCK_COST * area } else { split },
            leaf,
        }
    }

    /// Packed for [`Subtrees`]: the cost's bits, the count (at most 255) and the leaf flag.
    fn pack(self) -> u64 {
        self.cost.to_bits() as u64 | (self.count as u64) << 32 | (self.leaf as u64) << 40
    }

    fn unpack(v: u64) -> Subtree {
        Subtree {
            cost: f32::from_bits(v as u32),
            count: (v >> 32) as u32 & 0xff,
            leaf: v >> 40 & 1 == 1,
        }
    }
}

/// Per binary node, its [`Subtree`], written by the threads of the bottom-up pass (each node
/// by the one whose subtree holds it).
struct Subtrees {
    packed: Vec<AtomicU64>,
    leaf: Leaf,
}

impl Subtrees {
    fn get(&self, i: usize) -> Subtree {
        Subtree::unpack(self.packed[i].load(Relaxed))
    }

    fn set(&self, i: usize, s: Subtree) {
        self.packed[i].store(s.pack(), Relaxed);
    }
}

/// Fills `subs` for binary subtree `i` at binary level `level`: its two halves side by side
/// near the root, one thread's walk below [`PARALLEL_LEVELS`].
fn subtree(bvh: &Bvh2, subs: &Subtrees, i: usize, level: u32) -> Subtree {
    let node = &bvh.nodes[i];
    if node.is_leaf() || level >= PARALLEL_LEVELS {
        return subtree_serial(bvh, subs, i);
    }
    let f = node.first_index as usize;
    let (l, r) = rayon::join(
        || subtree(bvh, subs, f, level + 1),
        || subtree(bvh, subs, f + 1, level + 1),
    );
    let s = Subtree::of_inner(node, l, r, subs.leaf.max());
    subs.set(i, s);
    s
}

/// [`subtree`] on one thread, children before parents.
fn subtree_serial(bvh: &Bvh2, subs: &Subtrees, root: usize) -> Subtree {
    let mut stack = vec![(root, false)];
    while let Some((i, children_done)) = stack.pop() {
        let node = &bvh.nodes[i];
        if node.is_leaf() {
            subs.set(i, Subtree::of_leaf(node, subs.leaf));
            continue;
        }
        let first = node.first_index as usize;
        if !children_done {
            stack.extend([(i, true), (first + 1, false), (first, false)]);
            continue;
        }
        subs.set(
            i,
            Subtree::of_inner(node, subs.get(first), subs.get(first + 1), subs.leaf.max()),
        );
    }
    subs.get(root)
}

/// The binary nodes that become the children of the eight-wide node standing for binary
/// node `b`: its two children, the largest inner one opened until there are eight (the root
/// alone when it is a leaf).
fn children<'k>(bvh: &Bvh2, subs: &Subtrees, b: usize, kids: &'k mut [u32; 8]) -> &'k [u32] {
    if subs.get(b).leaf {
        kids[0] = b as u32;
        return &kids[..1];
    }
    let first = bvh.nodes[b].first_index;
    let mut areas = [0.0f32; 8];
    let mut len = 0;
    for k in [first, first + 1] {
        kids[len] = k;
        areas[len] = openable_area(bvh, subs, k);
        len += 1;
    }
    while len < 8 {
        // The largest child that can be opened (a leaf's area is −1).
        let mut j = 0;
        for i in 1..len {
            if areas[i] > areas[j] {
                j = i;
            }
        }
        if areas[j] < 0.0 {
            break;
        }
        let first = bvh.nodes[kids[j] as usize].first_index;
        kids[j] = first;
        areas[j] = openable_area(bvh, subs, first);
        kids[len] = first + 1;
        areas[len] = openable_area(bvh, subs, first + 1);
        len += 1;
    }
    &kids[..len]
}

/// The surface area of binary node `k`, or −1 when it is a leaf (not to be opened).
fn openable_area(bvh: &Bvh2, subs: &Subtrees, k: u32) -> f32 {
    if subs.get(k as usize).leaf {
        -1.0
    } else {
        bvh.nodes[k as usize].aabb.half_area().max(0.0)
    }
}

/// The input primitives of binary subtree `b` (at most a leaf's), in tree order.
fn leaf_prims(bvh: &Bvh2, b: usize, out: &mut Vec<u32>) {
    let node = &bvh.nodes[b];
    let first = node.first_index as usize;
    if node.is_leaf() {
        let ids = &bvh.primitive_indices[first..first + node.prim_count as usize];
        out.extend_from_slice(ids);
    } else {
        leaf_prims(bvh, first, out);
        leaf_prims(bvh, first + 1, out);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3A;
    use obvhs::BvhBuildParams;
    use obvhs::ploc::PlocBuilder;
    use obvhs::triangle::Triangle;

    fn bvh2(tris: &[Triangle]) -> Bvh2 {
        let p = BvhBuildParams::medium_build();
        PlocBuilder::with_capacity(tris.len()).build(
            p.ploc_search_distance,
            tris,
            (0..tris.len() as u32).collect(),
            p.sort_precision,
            p.search_depth_threshold,
        )
    }

    fn strip(n: usize, gap: f32) -> Vec<Triangle> {
        (0..n)
            .map(|i| {
                let x = i as f32 * gap;
                Triangle {
                    v0: Vec3A::new(x, 0.0, 0.0),
                    v1: Vec3A::new(x + 0.5, 0.0, 0.0),
                    v2: Vec3A::new(x, 0.5, 0.1),
                }
            })
            .collect()
    }

    #[test]
    fn every_triangle_is_in_one_leaf_block_and_leaves_hold_at_most_four() {
        for (n, gap) in [
            (1, 1.0),
            (3, 1.0),
            (4, 0.2),
            (5, 1.0),
            (37, 0.3),
            (1000, 0.7),
        ] {
            let tris = strip(n, gap);
            let (nodes, slots) = collapse(&bvh2(&tris), Leaf::Block);
            assert_eq!(slots.len() % 4, 0);
            let mut seen = vec![0; n];
            for s in slots.iter().filter(|&&s| s != u32::MAX) {
                seen[*s as usize] += 1;
            }
            assert!(
                seen.iter().all(|&k| k == 1),
                "{n}: each triangle once: {seen:?}"
            );
            for node in &nodes {
                assert_eq!(node.prim_base % 4, 0);
                for c in 0..8 {
                    if node.leaves & (1 << c) == 0 {
                        continue;
                    }
                    let bits = node.child[c];
                    let block = bits.trailing_zeros() / 4;
                    assert_eq!(bits >> (4 * block) & !0xf, 0, "one block per leaf");
                    let lanes = bits >> (4 * block);
                    assert!(lanes == 1 || lanes == 3 || lanes == 7 || lanes == 15);
                    for lane in 0..lanes.count_ones() {
                        let s = slots[(node.prim_base + 4 * block + lane) as usize];
                        let t = &tris[s as usize];
                        for v in [t.v0, t.v1, t.v2].map(|v| v.to_array()) {
                            for a in 0..3 {
                                assert!(node.planes[2 * a][c] <= v[a]);
                                assert!(node.planes[2 * a + 1][c] >= v[a]);
                            }
                        }
                    }
                }
            }
        }
    }

    #[test]
    fn single_leaves_hold_one_primitive_each_with_no_padding() {
        let tris = strip(300, 0.1);
        let (nodes, slots) = collapse(&bvh2(&tris), Leaf::Single);
        let mut sorted = slots.clone();
        sorted.sort_unstable();
        assert_eq!(
            sorted,
            (0..300).collect::<Vec<u32>>(),
            "every primitive once, no padding"
        );
        let mut leaves = 0;
        for node in &nodes {
            for c in 0..8 {
                if node.leaves >> c & 1 == 1 {
                    assert_eq!(node.child[c].count_ones(), 1);
                    let slot = (node.prim_base + node.child[c].trailing_zeros()) as usize;
                    let t = &tris[slots[slot] as usize];
                    assert!(node.planes[0][c] <= t.v0.x && node.planes[1][c] >= t.v1.x);
                    leaves += 1;
                }
            }
        }
        assert_eq!(leaves, 300);
    }

    #[test]
    fn near_triangles_share_a_leaf_and_far_ones_are_split() {
        // Four triangles close together: one leaf of four, the root's only child.
        let (nodes, _) = collapse(&bvh2(&strip(4, 0.2)), Leaf::Block);
        assert_eq!(nodes.len(), 1);
        assert_eq!(nodes[0].leaves, 1);
        assert_eq!(nodes[0].child[0], 0xf);
        // Two pairs far apart: a leaf box spanning the gap would cost more than two leaves.
        let mut tris = strip(2, 0.2);
        tris.extend(strip(2, 0.2).into_iter().map(|t| Triangle {
            v0: t.v0 + Vec3A::X * 100.0,
            v1: t.v1 + Vec3A::X * 100.0,
            v2: t.v2 + Vec3A::X * 100.0,
        }));
        let (nodes, _) = collapse(&bvh2(&tris), Leaf::Block);
        assert_eq!(nodes.len(), 1);
        assert_eq!(nodes[0].leaves.count_ones(), 2);
    }
}
