//! Closest-hit and shadow queries over every triangle of the scene, through an obvhs CWBVH.
//!
//! Triangles are copied into BVH order once (obvhs reports *slots*, not triangle indices), and
//! per-slot shading data lives in parallel arrays, so the hot loop never looks anything up
//! through `primitive_indices`.
use eyeadapt_scene::Scene;
use glam::{Vec2, Vec3A};
use obvhs::BvhBuildParams;
use obvhs::cwbvh::builder::build_cwbvh_from_tris;
use obvhs::cwbvh::{CwBvh, Traversal};
use obvhs::ray::Ray;
use obvhs::rt_triangle::RtTriangle;
use obvhs::triangle::Triangle;
use std::time::Duration;

/// Shading data of one BVH slot.
#[derive(Clone, Copy, Debug)]
pub struct TriInfo {
    /// Unit geometric normal, following the triangle's winding (front side).
    pub ng: Vec3A,
    /// Material index into the tracer's material table.
    pub material: u32,
    /// Index into [`crate::lights::LightSet::area`], or `u32::MAX` when not emissive.
    pub light: u32,
    /// Index into `Accel::normals`, or `u32::MAX` for flat shading.
    pub normals: u32,
}

pub struct Accel {
    bvh: CwBvh,
    tris: Vec<RtTriangle>,
    pub info: Vec<TriInfo>,
    normals: Vec<[Vec3A; 3]>,
    /// Triangles skipped because they have no area (they cannot be hit and must not yield NaN normals).
    pub degenerate: usize,
    pub bounds_min: Vec3A,
    pub bounds_max: Vec3A,
}

/// Per-ray traversal state, reused across the rays of a path.
pub struct RayScratch(Traversal);

/// A surface hit.
#[derive(Clone, Copy, Debug)]
pub struct Hit {
    pub t: f32,
    pub p: Vec3A,
    pub ng: Vec3A,
    pub ns: Vec3A,
    pub info: TriInfo,
}

/// One triangle as the scene gives it, with what the tracer needs to shade it.
pub struct InputTri {
    pub v: [Vec3A; 3],
    pub n: Option<[Vec3A; 3]>,
    pub material: u32,
    pub light: u32,
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
            let n = (t.v[1] - t.v[0]).cross(t.v[2] - t.v[0]);
            if n.length_squared() > 0.0 && n.is_finite() {
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
        let mut normals = Vec::new();
        let mut info = Vec::with_capacity(bvh.primitive_indices.len());
        let mut bvh_tris = Vec::with_capacity(bvh.primitive_indices.len());
        for &i in &bvh.primitive_indices {
            let t = kept[i as usize];
            bvh_tris.push(RtTriangle::from(&tris[i as usize]));
            let ng = (t.v[1] - t.v[0]).cross(t.v[2] - t.v[0]).normalize();
            let normals_idx = match t.n {
                Some(n) if n.iter().all(|x| x.is_finite() && x.length_squared() > 0.5) => {
                    normals.push(n);
                    normals.len() as u32 - 1
                }
                _ => u32::MAX,
            };
            info.push(TriInfo {
                ng,
                material: t.material,
                light: t.light,
                normals: normals_idx,
            });
        }
        Accel {
            bvh,
            tris: bvh_tris,
            info,
            normals,
            degenerate,
            bounds_min: lo,
            bounds_max: hi,
        }
    }

    /// Scratch space for [`Accel::intersect_with`] and [`Accel::unoccluded_with`]; one per
    /// path saves re-initialising obvhs's traversal stack for every ray.
    pub fn scratch(&self) -> RayScratch {
        RayScratch(Traversal::default())
    }

    /// Closest hit along `dir` (unit) from `origin`, within (0, tmax).
    #[inline]
    pub fn intersect(&self, origin: Vec3A, dir: Vec3A, tmax: f32) -> Option<Hit> {
        self.intersect_with(&mut self.scratch(), origin, dir, tmax)
    }

    /// [`Accel::intersect`] with caller-owned scratch space.
    #[inline]
    pub fn intersect_with(
        &self,
        scratch: &mut RayScratch,
        origin: Vec3A,
        dir: Vec3A,
        tmax: f32,
    ) -> Option<Hit> {
        let ray = Ray::new(origin, dir, 0.0, tmax);
        let hit = crate::traverse::closest_hit(
            &self.bvh,
            &self.tris,
            ray,
            &mut scratch.0,
            crate::triangle::intersect,
        )?;
        let slot = hit.primitive_id as usize;
        let info = self.info[slot];
        let p = origin + dir * hit.t;
        let ns = if info.normals == u32::MAX {
            info.ng
        } else {
            let Vec2 { x: u, y: v } = self.tris[slot].compute_barycentric(&ray);
            let n = self.normals[info.normals as usize];
            let ns = (n[0] * (1.0 - u - v) + n[1] * u + n[2] * v).normalize_or_zero();
            if ns == Vec3A::ZERO { info.ng } else { ns }
        };
        Some(Hit {
            t: hit.t,
            p,
            ng: info.ng,
            ns,
            info,
        })
    }

    /// True when nothing blocks the segment from `origin` along `dir` (unit) up to `tmax`.
    #[inline]
    pub fn unoccluded(&self, origin: Vec3A, dir: Vec3A, tmax: f32) -> bool {
        self.unoccluded_with(&mut self.scratch(), origin, dir, tmax)
    }

    /// [`Accel::unoccluded`] with caller-owned scratch space.
    #[inline]
    pub fn unoccluded_with(
        &self,
        scratch: &mut RayScratch,
        origin: Vec3A,
        dir: Vec3A,
        tmax: f32,
    ) -> bool {
        let ray = Ray::new(origin, dir, 0.0, tmax);
        crate::traverse::unoccluded(
            &self.bvh,
            &self.tris,
            ray,
            &mut scratch.0,
            crate::triangle::intersect,
        )
    }

    /// The obvhs structure itself (for diagnostics and the determinism tests).
    pub fn bvh(&self) -> &CwBvh {
        &self.bvh
    }

    pub fn triangle_count(&self) -> usize {
        self.info.len()
    }

    /// Approximate heap size of the structure (BVH nodes, triangles, shading data).
    pub fn memory_bytes(&self) -> usize {
        self.bvh.nodes.len()
            * std::mem::size_of_val(&self.bvh.nodes[..].first().copied().unwrap_or_default())
            + self.bvh.primitive_indices.len() * 4
            + self.tris.len() * std::mem::size_of::<RtTriangle>()
            + self.info.len() * std::mem::size_of::<TriInfo>()
            + self.normals.len() * std::mem::size_of::<[Vec3A; 3]>()
    }
}

/// Flattens the scene's meshes into BVH input; `light_of` gives each emissive mesh triangle's
/// index in the light set, in the same order as `LightSet::build` enumerates them.
pub fn scene_triangles(
    scene: &Scene,
    material_index: impl Fn(Option<eyeadapt_scene::MaterialId>) -> u32,
    emissive: impl Fn(u32) -> bool,
) -> Vec<InputTri> {
    let mut out = Vec::with_capacity(scene.triangle_count());
    let mut next_light = 0u32;
    for inst in &scene.instances {
        let mesh = scene.mesh(inst.mesh);
        let mat = material_index(inst.material);
        let is_light = emissive(mat);
        let m = inst.to_world;
        for tri in &mesh.indices {
            let v = tri.map(|i| Vec3A::from(m.point(mesh.positions[i as usize])));
            let n = (!mesh.normals.is_empty())
                .then(|| tri.map(|i| Vec3A::from(m.normal(mesh.normals[i as usize]))));
            let area2 = (v[1] - v[0]).cross(v[2] - v[0]).length();
            let light = if is_light && area2 > 0.0 && area2.is_finite() {
                next_light += 1;
                next_light - 1
            } else {
                u32::MAX
            };
            out.push(InputTri {
                v,
                n,
                material: mat,
                light,
            });
        }
    }
    out
}
