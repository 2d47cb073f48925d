//! The structure the renderer walks ([`crate::wide_walk`]): eight-wide nodes with each
//! child's box in full-precision floats and its reference ready to use (an inner child's node
//! index, a leaf child's slot bits), collapsed from obvhs's binary BVH ([`crate::collapse`]):
//! a mesh's and the instance level's.
//!
//! (Before, the renderer walked obvhs's compressed CWBVH, then decoded its nodes to these.) The
//! CWBVH walk spends about as many instructions on its compressed layout (the octant
//! bit tricks that find an inner child's index, the node groups on its stack) as on the box
//! tests themselves, and it cannot order children by distance or drop a pushed child that a
//! nearer hit has since put out of reach. With plain references and float boxes the walk
//! needs neither trick: it tests the eight boxes, keeps the entry distances, and pushes the
//! children nearest last.

/// One node: its eight children's boxes, and what each child is.
#[derive(Clone, Copy, Debug, PartialEq)]
#[repr(C, align(64))]
pub struct Node8 {
    /// Min x, max x, min y, max y, min z, max z of the eight children, child c in lane c. An
    /// empty child's minima are +∞ and its maxima −∞, so no ray enters it.
    pub(crate) planes: [[f32; 8]; 6],
    /// An inner child's node index; a leaf child's slot bits (bit i: slot `prim_base + i`; a
    /// mesh leaf's are one block's four, an instance leaf's one); 0 for an empty child.
    pub(crate) child: [u32; 8],
    /// The first slot of the node's leaf children (a multiple of 4 in a mesh's).
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

/// The nodes of one structure (node 0 is the root; none when it is empty).
#[derive(Clone, Debug, Default)]
pub struct WideBvh {
    pub(crate) nodes: Vec<Node8>,
    /// Whether the walks prefetch the inner children they enter ([`PREFETCH_MIN_BYTES`]). A
    /// mesh's walks ([`crate::accel`]) follow it; the instance level's do not look at it (no
    /// scene measured has a top level that large).
    pub(crate) prefetch: bool,
}

/// The size of nodes from which the walks prefetch the inner children a node test enters,
/// before testing its leaves ([`crate::isa::Prefetching`]): a structure this large is mostly
/// outside the core's L2, and a child's node arrives while the leaves are tested (the
/// 1M-triangle suite scene's render call −5 to −6 %, matpreview's −3 to +0.5 %; 1M-triangle
/// incoherent rays +6 to +22 %, shadow rays +18 to +27 %). Below it the nodes stay cached and
/// the prefetches are only instructions (the 1 000-triangle ray sets up to 8 % slower).
pub(crate) const PREFETCH_MIN_BYTES: usize = 256 << 10;

impl WideBvh {
    /// The nodes [`crate::collapse`] made.
    pub(crate) fn from_nodes(nodes: Vec<Node8>) -> WideBvh {
        let prefetch = nodes.len() * std::mem::size_of::<Node8>() >= PREFETCH_MIN_BYTES;
        WideBvh { nodes, prefetch }
    }

    pub fn memory_bytes(&self) -> usize {
        self.nodes.len() * std::mem::size_of::<Node8>()
    }
}

/// The planes of eight empty children.
const EMPTY: [[f32; 8]; 6] = {
    let (lo, hi) = ([f32::INFINITY; 8], [f32::NEG_INFINITY; 8]);
    [lo, hi, lo, hi, lo, hi]
};
