//! The structure the renderer walks ([`crate::wide_walk`]): eight-wide nodes with each
//! child's box in full-precision floats and its reference ready to use (an inner child's node
//! index, a leaf child's slot bits). A mesh's nodes are collapsed from obvhs's binary BVH
//! ([`crate::collapse`]); the instance level's are obvhs's CWBVH topology (its build, its
//! eight-wide nodes and its leaves) with each node's child boxes decoded once into floats,
//! rounded outward ([`WideBvh::of`]).
//!
//! The CWBVH walk spends about as many instructions on its compressed layout (the octant
//! bit tricks that find an inner child's index, the node groups on its stack) as on the box
//! tests themselves, and it cannot order children by distance or drop a pushed child that a
//! nearer hit has since put out of reach. With plain references and float boxes the walk
//! needs neither trick: it tests the eight boxes, keeps the entry distances, and pushes the
//! children nearest last.
use obvhs::cwbvh::CwBvh;
use obvhs::cwbvh::node::CwBvhNode;

/// One node: its eight children's boxes, and what each child is.
#[derive(Clone, Copy, Debug, PartialEq)]
#[repr(C, align(64))]
pub struct Node8 {
    /// Min x, max x, min y, max y, min z, max z of the eight children, child c in lane c. An
    /// empty child's minima are +∞ and its maxima −∞, so no ray enters it.
    pub(crate) planes: [[f32; 8]; 6],
    /// An inner child's node index; a leaf child's slot bits (bit i: slot `prim_base + i`;
    /// below bit 24 in a CWBVH's node, one block's four bits in a mesh's); 0 for an empty
    /// child.
    pub(crate) child: [u32; 8],
    /// The first slot of the node's leaf children (a multiple of 4 in [`crate::Accel`]).
    pub(crate) prim_base: u32,
    /// Bit c: child c is a leaf.
    pub(crate) leaves: u32,
}

impl Node8 {
    /// A node of eight empty children.
    pub(crate) const EMPTY: Node8 = Node8 {
        planes: EMPTY,
        child: [0; 8],
        prim_base: 0,
        leaves: 0,
    };
}

/// A CWBVH's nodes as [`Node8`]s, in the same order (node 0 is the root).
#[derive(Clone, Debug, Default)]
pub struct WideBvh {
    pub(crate) nodes: Vec<Node8>,
}

impl WideBvh {
    /// The nodes of `bvh`, whose `primitive_base_idx` are the slots the leaves are to report.
    pub fn of(bvh: &CwBvh) -> WideBvh {
        WideBvh {
            nodes: bvh.nodes.iter().map(node8).collect(),
        }
    }

    /// Nodes made elsewhere (a mesh's, [`crate::collapse`]).
    pub(crate) fn from_nodes(nodes: Vec<Node8>) -> WideBvh {
        WideBvh { nodes }
    }

    pub fn memory_bytes(&self) -> usize {
        self.nodes.len() * std::mem::size_of::<Node8>()
    }
}

/// Whether a CWBVH child's metadata names an inner node (obvhs: 24 + its slot, so bits 3 and
/// 4 are both set), not a leaf (its slot offset, below 24, and its count in the top 3 bits).
fn is_inner(meta: u8) -> bool {
    meta & (meta << 1) & 0x10 != 0
}

/// The planes of eight empty children.
const EMPTY: [[f32; 8]; 6] = {
    let (lo, hi) = ([f32::INFINITY; 8], [f32::NEG_INFINITY; 8]);
    [lo, hi, lo, hi, lo, hi]
};

fn node8(n: &CwBvhNode) -> Node8 {
    let mut out = Node8 {
        prim_base: n.primitive_base_idx,
        ..Node8::EMPTY
    };
    let e = n.compute_extent().to_array();
    let p = n.p.to_array();
    let q = [
        &n.child_min_x,
        &n.child_max_x,
        &n.child_min_y,
        &n.child_max_y,
        &n.child_min_z,
        &n.child_max_z,
    ];
    for (c, &meta) in n.child_meta.iter().enumerate() {
        if meta == 0 {
            continue;
        }
        if is_inner(meta) {
            out.child[c] = n.child_node_index(c);
        } else {
            out.child[c] = ((meta as u32 >> 5) & 7) << (meta & 31);
            out.leaves |= 1 << c;
        }
        for a in 0..3 {
            // The quantised plane is p + q·e exactly (e is a power of two, q a byte); its
            // float is rounded outward, so the box still holds everything the child holds.
            let at = |k: usize| p[a] as f64 + q[k][c] as f64 * e[a] as f64;
            out.planes[2 * a][c] = round_down(at(2 * a));
            out.planes[2 * a + 1][c] = round_up(at(2 * a + 1));
        }
    }
    out
}

/// The largest float not above `x`.
fn round_down(x: f64) -> f32 {
    let f = x as f32;
    if f as f64 > x { f.next_down() } else { f }
}

/// The smallest float not below `x`.
fn round_up(x: f64) -> f32 {
    let f = x as f32;
    if (f as f64) < x { f.next_up() } else { f }
}
