//! Closest-hit and shadow queries over a set of triangles, through an obvhs CWBVH.
//!
//! Triangles are copied into BVH order once (obvhs reports *slots*, not triangle indices), and
//! per-slot ids live in a parallel array, so the hot loop never looks anything up through
//! `primitive_indices`. [`crate::geometry`] puts these together into the scene's two levels.
use crate::triangle::normal_and_area;
use glam::{Vec2, Vec3A};
use obvhs::BvhBuildParams;
use obvhs::cwbvh::builder::build_cwbvh_from_tris;
use obvhs::cwbvh::{CwBvh, Traversal};
use obvhs::ray::Ray;
use obvhs::rt_triangle::RtTriangle;
use obvhs::triangle::Triangle;
use std::time::Duration;

/// What one BVH slot holds besides its triangle.
#[derive(Clone, Copy, Debug)]
pub struct TriInfo {
    /// Unit geometric normal in the structure's space, following the winding (front side).
    pub ng: Vec3A,
    /// The [`InputTri::instance`] and [`InputTri::prim`] the slot was built from.
    pub instance: u32,
    pub prim: u32,
}

/// An obvhs CWBVH over triangles, in whatever space they were given (world space for a
/// flattened scene, object space for one mesh of an instanced scene).
pub struct Accel {
    bvh: CwBvh,
    /// Triangles in BVH slot order.
    pub(crate) tris: Vec<RtTriangle>,
    pub info: Vec<TriInfo>,
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
/// preset builds in under 40 µs and traces alike, so small scenes keep `medium`.
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
        let mut kept = Vec::with_capacity(input.len());
        let mut degenerate = 0;
        for t in input {
            if normal_and_area(t.v[1] - t.v[0], t.v[2] - t.v[0]).is_some() {
                kept.push(t);
            } else {
                degenerate += 1;
            }
        }
        let tris: Vec<Triangle> = kept.iter().map(|t| t.triangle()).collect();
        let (mut lo, mut hi) = (Vec3A::splat(f32::INFINITY), Vec3A::splat(f32::NEG_INFINITY));
        for t in &tris {
            for v in [t.v0, t.v1, t.v2] {
                lo = lo.min(v);
                hi = hi.max(v);
            }
        }
        if tris.is_empty() {
            lo = Vec3A::ZERO;
            hi = Vec3A::ZERO;
        }
        let bvh = build_cwbvh_from_tris(&tris, params, &mut Duration::default());
        let mut info = Vec::with_capacity(bvh.primitive_indices.len());
        let mut bvh_tris = Vec::with_capacity(bvh.primitive_indices.len());
        for &i in &bvh.primitive_indices {
            let t = kept[i as usize];
            bvh_tris.push(RtTriangle::from(&tris[i as usize]));
            info.push(TriInfo {
                ng: normal_and_area(t.v[1] - t.v[0], t.v[2] - t.v[0])
                    .expect("kept triangles have an area")
                    .0,
                instance: t.instance,
                prim: t.prim,
            });
        }
        Accel {
            bvh,
            tris: bvh_tris,
            info,
            degenerate,
            bounds_min: lo,
            bounds_max: hi,
        }
    }

    /// Closest hit along `dir` (unit) from `origin`, within (0, tmax).
    #[inline]
    pub fn intersect(&self, origin: Vec3A, dir: Vec3A, tmax: f32) -> Option<SlotHit> {
        self.closest(&Ray::new(origin, dir, 0.0, tmax), &mut Traversal::default())
    }

    /// The closest hit of `ray` within its (tmin, tmax); `state` is scratch space, reused.
    #[inline]
    pub fn closest(&self, ray: &Ray, state: &mut Traversal) -> Option<SlotHit> {
        let tris = &self.tris;
        crate::traverse::closest_hit(&self.bvh, *ray, state, |i, r| {
            crate::triangle::intersect(&tris[i as usize], r)
        })
        .map(|h| SlotHit {
            t: h.t,
            slot: h.primitive_id,
        })
    }

    /// True when nothing blocks the segment from `origin` along `dir` (unit) up to `tmax`.
    #[inline]
    pub fn unoccluded(&self, origin: Vec3A, dir: Vec3A, tmax: f32) -> bool {
        self.unblocked(&Ray::new(origin, dir, 0.0, tmax), &mut Traversal::default())
    }

    /// True when no triangle blocks `ray` within its (tmin, tmax).
    #[inline]
    pub fn unblocked(&self, ray: &Ray, state: &mut Traversal) -> bool {
        let tris = &self.tris;
        crate::traverse::unoccluded(&self.bvh, *ray, state, |i, r| {
            crate::triangle::intersect(&tris[i as usize], r)
        })
    }

    /// Barycentric coordinates (weights of vertices 1 and 2) of `ray`'s hit with slot `slot`.
    #[inline]
    pub fn barycentric(&self, slot: u32, ray: &Ray) -> Vec2 {
        self.tris[slot as usize].compute_barycentric(ray)
    }

    /// The vertices of slot `slot`, in the winding the triangle was given.
    #[inline]
    pub fn vertices(&self, slot: u32) -> [Vec3A; 3] {
        let t = &self.tris[slot as usize];
        [t.v0, t.v0 - t.e1, t.v0 + t.e2]
    }

    /// The obvhs structure itself (for diagnostics and the determinism tests).
    pub fn bvh(&self) -> &CwBvh {
        &self.bvh
    }

    pub fn triangle_count(&self) -> usize {
        self.info.len()
    }

    /// Approximate heap size of the structure (BVH nodes, triangles, slot data).
    pub fn memory_bytes(&self) -> usize {
        self.bvh.nodes.len()
            * std::mem::size_of_val(&self.bvh.nodes[..].first().copied().unwrap_or_default())
            + self.bvh.primitive_indices.len() * 4
            + self.tris.len() * std::mem::size_of::<RtTriangle>()
            + self.info.len() * std::mem::size_of::<TriInfo>()
    }
}
