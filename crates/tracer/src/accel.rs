//! Closest-hit and shadow queries over a set of triangles: obvhs builds a binary BVH, which
//! [`crate::collapse`] turns into eight-wide nodes ([`WideBvh`]) with every leaf one block of
//! four triangles; the queries walk them nearest child first ([`crate::wide_walk`]).
//!
//! Triangles are copied into BVH order once, in blocks of four ([`Tri4`]), each leaf's in a
//! block of its own (padded), and per-slot ids live in a parallel array, so the hot loop never
//! looks anything up through an index list and a leaf is one four-lane test. [`crate::geometry`]
//! puts these together into the scene's two levels.
use crate::collapse::{Leaf, collapse};
use crate::isa::{Baseline, NodeTest, Prefetching};
use crate::traverse_pair::{Walk, walk_pair};
use crate::tri4::{Shear, Tri4};
use crate::triangle::normal_and_area;
use crate::wide_bvh::{Node8, WideBvh};
use crate::wide_walk::{Leaves, WalkStack, walk8};
use glam::{Vec2, Vec3A};
use obvhs::aabb::Aabb;
use obvhs::bvh2::Bvh2;
use obvhs::bvh2::reinsertion::ReinsertionOptimizer;
use obvhs::ploc::PlocBuilder;
use obvhs::ray::Ray;
use obvhs::rt_triangle::RtTriangle;
use obvhs::splits::split_aabbs_preset;
use obvhs::triangle::Triangle;
use obvhs::{Boundable, BvhBuildParams};
use rayon::prelude::*;

/// What one BVH slot holds besides its triangle.
#[derive(Clone, Copy, Debug)]
pub struct TriInfo {
    /// Unit geometric normal in the structure's space, following the winding (front side).
    pub ng: Vec3A,
    /// The [`InputTri::instance`] and [`InputTri::prim`] the slot was built from.
    pub instance: u32,
    pub prim: u32,
}

/// A BVH over triangles, in whatever space they were given (world space for a flattened
/// scene, object space for one mesh of an instanced scene).
pub struct Accel {
    /// Triangles in padded slot order, slot `s` in lane `s % 4` of block `s / 4`.
    packs: Vec<Tri4>,
    /// Per padded slot (padding: zero normal, ids `u32::MAX`).
    pub info: Vec<TriInfo>,
    /// The nodes the queries walk, each leaf child one block of `packs`.
    wide: WideBvh,
    triangles: usize,
    /// Triangles skipped because they have no area (they cannot be hit and must not yield NaN normals).
    pub degenerate: usize,
    pub bounds_min: Vec3A,
    pub bounds_max: Vec3A,
}

/// The closest hit in one [`Accel`]: distance and BVH slot.
#[derive(Clone, Copy, Debug)]
pub struct SlotHit {
    pub t: f32,
    pub slot: u32,
}

/// One triangle to build from, with the ids its hits report.
pub struct InputTri {
    pub v: [Vec3A; 3],
    pub instance: u32,
    pub prim: u32,
}

/// The obvhs build preset for a scene of `n` triangles. Quality pays off only while the build
/// is cheap next to rendering: `medium_build` up to 256k triangles, `fast_build` above, which
/// keeps a 1M-triangle build under a second on 2 cores (`eyeadapt bench --bvh-triangles`,
/// `scripts/bench/bvh-scale.sh`, BENCHMARKS.md).
///
/// Measured 2026-11-22 on the shared 2-core machine (load 3-4, so a 2-thread run often got one
/// core), 1M-triangle terrain, medians of the whole `Accel::build_with` (obvhs + BVH-order
/// copy): `fast` 0.78-0.93 s, `medium` 0.82-1.04 s (over budget under load), `very_fast`
/// 0.69-0.75 s, `fastest` 0.71-0.80 s. Closest-hit rays: `fast` within noise of `medium`, 3-8 %
/// ahead of `very_fast`, 10-15 % ahead of `fastest`. At the Cornell box's 36 triangles every
/// preset builds in under 40 µs and traces alike, so small scenes keep `medium`. (Measured
/// with obvhs's CWBVH; a preset now sets only the PLOC build and the reinsertion, since the
/// tracer collapses the binary BVH itself and ignores the preset's leaf size and collapse cost.)
pub fn build_params(n: usize) -> BvhBuildParams {
    if n <= 256 * 1024 {
        BvhBuildParams::medium_build()
    } else {
        BvhBuildParams::fast_build()
    }
}

impl InputTri {
    /// The positions as obvhs's build input.
    pub fn triangle(&self) -> Triangle {
        Triangle {
            v0: self.v[0],
            v1: self.v[1],
            v2: self.v[2],
        }
    }
}

impl Accel {
    /// Builds with the preset [`build_params`] picks for the size.
    pub fn build(input: &[InputTri]) -> Accel {
        Accel::build_with(input, build_params(input.len()))
    }

    /// Builds with an explicit obvhs preset.
    pub fn build_with(input: &[InputTri], params: BvhBuildParams) -> Accel {
        // Every step side by side, each in input (or slot) order, so the result is the same on
        // any number of threads: the triangles with an area, ...
        let kept: Vec<&InputTri> = input
            .par_iter()
            .filter(|t| unit_normal(t).is_some())
            .collect();
        let degenerate = input.len() - kept.len();
        let tris: Vec<Triangle> = kept.par_iter().map(|t| t.triangle()).collect();
        let empty = (Vec3A::splat(f32::INFINITY), Vec3A::splat(f32::NEG_INFINITY));
        let (lo, hi) = match tris.is_empty() {
            true => (Vec3A::ZERO, Vec3A::ZERO),
            false => tris
                .par_iter()
                .map(|t| (t.v0.min(t.v1).min(t.v2), t.v0.max(t.v1).max(t.v2)))
                .reduce(|| empty, |a, b| (a.0.min(b.0), a.1.max(b.1))),
        };
        let (nodes, slots) = collapse(&binary_bvh(&tris, params), Leaf::Block);
        // ... and each block's triangles and each slot's shading data, from its slots alone.
        let packs: Vec<Tri4> = slots
            .par_chunks(4)
            .map(|block| {
                let mut pack = Tri4::default();
                for (lane, &i) in block.iter().enumerate() {
                    if i != u32::MAX {
                        pack.set(lane, &tris[i as usize]);
                    }
                }
                pack
            })
            .collect();
        // (The normals are found again rather than kept from the filter: keeping them beside
        // `kept` raised a 1M-triangle render's peak memory from 417 to 461 MB.)
        let info: Vec<TriInfo> = slots
            .par_iter()
            .map(|&i| match kept.get(i as usize) {
                Some(t) => TriInfo {
                    ng: unit_normal(t).expect("kept triangles have an area"),
                    instance: t.instance,
                    prim: t.prim,
                },
                None => TriInfo {
                    ng: Vec3A::ZERO,
                    instance: u32::MAX,
                    prim: u32::MAX,
                },
            })
            .collect();
        let triangles = kept.len();
        let wide = WideBvh::from_nodes(nodes);
        Accel {
            packs,
            info,
            wide,
            triangles,
            degenerate,
            bounds_min: lo,
            bounds_max: hi,
        }
    }

    /// The nodes the queries walk and the triangle blocks their leaves name.
    #[inline(always)]
    pub(crate) fn walk_data(&self) -> (&[crate::wide_bvh::Node8], &[Tri4]) {
        (&self.wide.nodes, &self.packs)
    }

    /// Closest hit along `dir` (unit) from `origin`, within (0, tmax).
    #[inline]
    pub fn intersect(&self, origin: Vec3A, dir: Vec3A, tmax: f32) -> Option<SlotHit> {
        self.closest(&Ray::new(origin, dir, 0.0, tmax), &mut WalkStack::default())
    }

    /// The closest hit of `ray` within its (tmin, tmax); `state` is scratch space, reused. Of
    /// equally near hits in one node the highest slot wins, as in obvhs's one-by-one order.
    #[inline]
    pub fn closest(&self, ray: &Ray, state: &mut WalkStack) -> Option<SlotHit> {
        self.closest_with(Baseline, ray, state)
    }

    /// [`Accel::closest`] with the node test `test`.
    #[inline(always)]
    pub fn closest_with(
        &self,
        test: impl NodeTest,
        ray: &Ray,
        state: &mut WalkStack,
    ) -> Option<SlotHit> {
        let mut best = None;
        let shear = Shear::new(ray);
        self.walk::<true>(test, ray, state, self.closest_leaves(&shear, &mut best));
        best
    }

    /// [`Accel::closest_with`] of `ray` and [`Accel::unblocked_with`] of `shadow`, walked
    /// together ([`crate::traverse_pair`]): the same answers as the two calls.
    #[inline(always)]
    pub fn closest_and_unblocked_with(
        &self,
        test: impl NodeTest,
        (ray, state): (&Ray, &mut WalkStack),
        (shadow, shadow_state): (&Ray, &mut WalkStack),
    ) -> (Option<SlotHit>, bool) {
        let (mut best, mut blocked) = (None, false);
        let (shear, shadow_shear) = (Shear::new(ray), Shear::new(shadow));
        let (mut ra, mut rb) = (*ray, *shadow);
        let a = Walk {
            ray: &mut ra,
            stack: state,
            leaves: self.closest_leaves(&shear, &mut best),
        };
        let b = Walk {
            ray: &mut rb,
            stack: shadow_state,
            leaves: self.blocking_leaves(&shadow_shear, &mut blocked),
        };
        if self.wide.prefetch {
            walk_pair(&self.wide, Prefetching(test), a, b);
        } else {
            walk_pair(&self.wide, test, a, b);
        }
        (best, !blocked)
    }

    /// The leaf test of a closest-hit walk.
    #[inline(always)]
    fn closest_leaves<'a>(
        &'a self,
        shear: &'a Shear,
        best: &'a mut Option<SlotHit>,
    ) -> ClosestLeaves<'a> {
        ClosestLeaves {
            packs: &self.packs,
            shear,
            best,
        }
    }

    /// The leaf test of a shadow walk.
    #[inline(always)]
    fn blocking_leaves<'a>(
        &'a self,
        shear: &'a Shear,
        blocked: &'a mut bool,
    ) -> BlockingLeaves<'a> {
        BlockingLeaves {
            packs: &self.packs,
            shear,
            blocked,
        }
    }

    /// [`walk8`] over this structure, nearest child first if `ORDERED`.
    #[inline(always)]
    fn walk<const ORDERED: bool>(
        &self,
        test: impl NodeTest,
        ray: &Ray,
        state: &mut WalkStack,
        leaves: impl Leaves,
    ) {
        if self.wide.prefetch {
            walk8::<ORDERED>(&self.wide, Prefetching(test), &mut { *ray }, state, leaves);
        } else {
            walk8::<ORDERED>(&self.wide, test, &mut { *ray }, state, leaves);
        }
    }

    /// True when nothing blocks the segment from `origin` along `dir` (unit) up to `tmax`.
    #[inline]
    pub fn unoccluded(&self, origin: Vec3A, dir: Vec3A, tmax: f32) -> bool {
        self.unblocked(&Ray::new(origin, dir, 0.0, tmax), &mut WalkStack::default())
    }

    /// True when no triangle blocks `ray` within its (tmin, tmax).
    #[inline]
    pub fn unblocked(&self, ray: &Ray, state: &mut WalkStack) -> bool {
        self.unblocked_with(Baseline, ray, state)
    }

    /// [`Accel::unblocked`] with the node test `test`.
    #[inline(always)]
    pub fn unblocked_with(&self, test: impl NodeTest, ray: &Ray, state: &mut WalkStack) -> bool {
        let mut blocked = false;
        let shear = Shear::new(ray);
        self.walk::<false>(test, ray, state, self.blocking_leaves(&shear, &mut blocked));
        !blocked
    }

    /// Calls `visit` with every triangle `ray` hits within its (tmin, tmax), in walk order
    /// (not by distance), until it returns true; returns whether one did. A triangle is
    /// reported once per walk.
    #[inline(always)]
    pub fn each_hit_with(
        &self,
        test: impl NodeTest,
        ray: &Ray,
        state: &mut WalkStack,
        visit: &mut dyn FnMut(SlotHit) -> bool,
    ) -> bool {
        let mut stopped = false;
        let shear = Shear::new(ray);
        let leaves = EachLeaves {
            packs: &self.packs,
            shear: &shear,
            visit,
            stopped: &mut stopped,
        };
        self.walk::<false>(test, ray, state, leaves);
        stopped
    }

    /// Barycentric coordinates (weights of vertices 1 and 2) of `ray`'s hit with slot `slot`.
    #[inline]
    pub fn barycentric(&self, slot: u32, ray: &Ray) -> Vec2 {
        self.triangle(slot).compute_barycentric(ray)
    }

    /// The vertices of slot `slot`, in the winding the triangle was given.
    #[inline]
    pub fn vertices(&self, slot: u32) -> [Vec3A; 3] {
        let t = self.packs[slot as usize / 4].get(slot as usize % 4);
        [t.v0, t.v1, t.v2]
    }

    fn triangle(&self, slot: u32) -> RtTriangle {
        RtTriangle::from(&self.packs[slot as usize / 4].get(slot as usize % 4))
    }

    /// The nodes the queries walk, the root first (for diagnostics and the determinism tests).
    pub fn nodes(&self) -> &[Node8] {
        &self.wide.nodes
    }

    /// The nodes the queries walk.
    #[cfg(test)]
    pub(crate) fn wide(&self) -> &WideBvh {
        &self.wide
    }

    /// This structure with its walks never prefetching (to compare the two).
    #[cfg(test)]
    pub(crate) fn without_prefetch(mut self) -> Accel {
        self.wide.prefetch = false;
        self
    }

    pub fn triangle_count(&self) -> usize {
        self.triangles
    }

    /// Approximate heap size of the structure (BVH nodes, triangles, slot data).
    pub fn memory_bytes(&self) -> usize {
        self.packs.len() * std::mem::size_of::<Tri4>()
            + self.info.len() * std::mem::size_of::<TriInfo>()
            + self.wide.memory_bytes()
    }
}

/// The leaf test of a closest-hit walk: each hit triangle nearer than the ray's end shortens
/// the ray and becomes `best`.
struct ClosestLeaves<'a> {
    packs: &'a [Tri4],
    shear: &'a Shear,
    best: &'a mut Option<SlotHit>,
}

impl Leaves for ClosestLeaves<'_> {
    #[inline(always)]
    fn visit(&mut self, base: u32, mask: u32, r: &mut Ray) -> bool {
        for_blocks(base, mask, |block, lanes| {
            if let Some((t, lane)) = self.packs[block as usize].closest(r, self.shear, lanes) {
                r.tmax = t;
                *self.best = Some(SlotHit {
                    t,
                    slot: block * 4 + lane,
                });
            }
            false
        })
    }
}

/// The leaf test of a shadow walk: any hit triangle sets `blocked` and stops the walk.
struct BlockingLeaves<'a> {
    packs: &'a [Tri4],
    shear: &'a Shear,
    blocked: &'a mut bool,
}

impl Leaves for BlockingLeaves<'_> {
    #[inline(always)]
    fn visit(&mut self, base: u32, mask: u32, r: &mut Ray) -> bool {
        *self.blocked = for_blocks(base, mask, |block, lanes| {
            self.packs[block as usize].any(r, self.shear, lanes)
        });
        *self.blocked
    }
}

/// The leaf test of an every-hit walk: each hit triangle goes to `visit`, which may stop
/// the walk; the ray is never shortened.
struct EachLeaves<'a> {
    packs: &'a [Tri4],
    shear: &'a Shear,
    visit: &'a mut dyn FnMut(SlotHit) -> bool,
    stopped: &'a mut bool,
}

impl Leaves for EachLeaves<'_> {
    #[inline(always)]
    fn visit(&mut self, base: u32, mask: u32, r: &mut Ray) -> bool {
        *self.stopped = for_blocks(base, mask, |block, lanes| {
            let (mut hit, dist) = self.packs[block as usize].hits(r, self.shear, lanes);
            while hit != 0 {
                let lane = 31 - hit.leading_zeros();
                hit &= !(1 << lane);
                let t = dist[lane as usize];
                if t < r.tmax
                    && (self.visit)(SlotHit {
                        t,
                        slot: block * 4 + lane,
                    })
                {
                    return true;
                }
            }
            false
        });
        *self.stopped
    }
}

/// Calls `test(block, lanes)` for each block of four slots that `mask` (bit i: slot
/// `base + i`, `base` a multiple of 4) touches, highest first, until it returns true; returns
/// whether one did.
#[inline(always)]
fn for_blocks(base: u32, mut mask: u32, mut test: impl FnMut(u32, u32) -> bool) -> bool {
    while mask != 0 {
        let shift = (31 - mask.leading_zeros()) & !3;
        let lanes = (mask >> shift) & 0xf;
        mask &= !(0xf << shift);
        if test((base + shift) / 4, lanes) {
            return true;
        }
    }
    false
}

/// The unit geometric normal of `t` (following its winding), or `None` when it has no area.
fn unit_normal(t: &InputTri) -> Option<Vec3A> {
    normal_and_area(t.v[1] - t.v[0], t.v[2] - t.v[0]).map(|(n, _)| n)
}

/// obvhs's binary BVH of `tris` with `params`: its PLOC build (after its spatial pre-splits
/// when the preset asks for them) and its reinsertion, as its CWBVH builder makes them.
fn binary_bvh(tris: &[Triangle], params: BvhBuildParams) -> Bvh2 {
    if !params.pre_split || tris.is_empty() {
        return binary_bvh_of(tris, params);
    }
    let mut aabbs: Vec<Aabb> = tris.iter().map(Triangle::aabb).collect();
    let largest = aabbs.iter().map(Aabb::half_area).fold(0.0, f32::max);
    let average = aabbs.iter().map(Aabb::half_area).sum::<f32>() / aabbs.len() as f32;
    let mut indices = (0..tris.len() as u32).collect();
    split_aabbs_preset(&mut aabbs, &mut indices, tris, average, largest);
    let mut bvh = ploc(&aabbs, indices, params);
    bvh.uses_spatial_splits = true;
    reinserted(bvh, params)
}

/// obvhs's binary BVH of `prims` (triangles, or the instances' boxes) with `params`, without
/// spatial splits: its PLOC build and its reinsertion.
pub(crate) fn binary_bvh_of<T: Boundable>(prims: &[T], params: BvhBuildParams) -> Bvh2 {
    reinserted(
        ploc(prims, (0..prims.len() as u32).collect(), params),
        params,
    )
}

fn ploc<T: Boundable>(prims: &[T], indices: Vec<u32>, params: BvhBuildParams) -> Bvh2 {
    PlocBuilder::with_capacity(prims.len()).build(
        params.ploc_search_distance,
        prims,
        indices,
        params.sort_precision,
        params.search_depth_threshold,
    )
}

fn reinserted(mut bvh: Bvh2, params: BvhBuildParams) -> Bvh2 {
    ReinsertionOptimizer::default().run(&mut bvh, params.reinsertion_batch_ratio, None);
    bvh
}
