//! Four triangles tested against one ray at once: the BVH's triangles stored four to a block
//! (structure of arrays), so one SSE2 Möller–Trumbore test covers up to four slots of a leaf.
//!
//! Each lane does exactly the arithmetic of the scalar [`crate::triangle::intersect`], operation
//! for operation (glam's cross and dot products in the same order, no FMA), so a lane's hit
//! and distance are bit-identical to the scalar test's on the same triangle. A CWBVH node lists
//! up to 24 triangles; [`crate::accel`] lays each node's out from a block boundary, so the
//! node's hit mask splits into one 4-bit lane mask per block.
use crate::triangle::SIGN;
use glam::Vec3A;
use obvhs::ray::Ray;
use obvhs::rt_triangle::RtTriangle;

/// Four triangles in obvhs's [`RtTriangle`] layout (v0, e1 = v0 − v1, e2 = v2 − v0,
/// ng = e1 × e2), one array per component. An empty lane is all zeros: its det is 0, so it
/// never hits.
#[derive(Clone, Copy, Debug, Default)]
#[repr(C, align(16))]
pub struct Tri4 {
    v0: [[f32; 4]; 3],
    e1: [[f32; 4]; 3],
    e2: [[f32; 4]; 3],
    ng: [[f32; 4]; 3],
}

impl Tri4 {
    /// Puts `tri` into lane `lane`.
    pub fn set(&mut self, lane: usize, tri: &RtTriangle) {
        for (dst, src) in [
            (&mut self.v0, tri.v0),
            (&mut self.e1, tri.e1),
            (&mut self.e2, tri.e2),
            (&mut self.ng, tri.ng),
        ] {
            for (axis, value) in dst.iter_mut().zip(src.to_array()) {
                axis[lane] = value;
            }
        }
    }

    /// The triangle in lane `lane`, as it was put in.
    pub fn get(&self, lane: usize) -> RtTriangle {
        let v = |a: &[[f32; 4]; 3]| Vec3A::new(a[0][lane], a[1][lane], a[2][lane]);
        RtTriangle {
            v0: v(&self.v0),
            e1: v(&self.e1),
            e2: v(&self.e2),
            ng: v(&self.ng),
        }
    }

    /// The lanes among `lanes` (bit i: lane i) that `ray` hits within [tmin, tmax], and the
    /// four distances (meaningful in the hit lanes only). Both faces count.
    #[cfg(target_arch = "x86_64")]
    #[inline(always)]
    pub fn hits(&self, ray: &Ray, lanes: u32) -> (u32, [f32; 4]) {
        use std::arch::x86_64::*;
        // SAFETY: SSE2 is part of the x86_64 baseline; `Tri4` is 16-byte aligned, so every
        // `[f32; 4]` row is an aligned 16-byte load.
        unsafe {
            let ld = |a: &[[f32; 4]; 3]| {
                [
                    _mm_load_ps(a[0].as_ptr()),
                    _mm_load_ps(a[1].as_ptr()),
                    _mm_load_ps(a[2].as_ptr()),
                ]
            };
            let o = ray.origin;
            let d = ray.direction;
            let d = [_mm_set1_ps(d.x), _mm_set1_ps(d.y), _mm_set1_ps(d.z)];
            let v0 = ld(&self.v0);
            let ng = ld(&self.ng);
            let (mul, add, sub) = (_mm_mul_ps, _mm_add_ps, _mm_sub_ps);
            // glam's dot3: (x·x′ + y·y′) + z·z′.
            let dot = |a: [__m128; 3], b: [__m128; 3]| {
                add(add(mul(a[0], b[0]), mul(a[1], b[1])), mul(a[2], b[2]))
            };
            let c = [
                sub(v0[0], _mm_set1_ps(o.x)),
                sub(v0[1], _mm_set1_ps(o.y)),
                sub(v0[2], _mm_set1_ps(o.z)),
            ];
            // r = d × c as glam computes it: (d.y c.z − d.z c.y, d.z c.x − d.x c.z, …).
            let r = [
                sub(mul(d[1], c[2]), mul(d[2], c[1])),
                sub(mul(d[2], c[0]), mul(d[0], c[2])),
                sub(mul(d[0], c[1]), mul(d[1], c[0])),
            ];
            let det = dot(ng, d);
            let t = dot(ng, c);
            let sign = _mm_and_ps(det, _mm_set1_ps(f32::from_bits(SIGN)));
            let u = _mm_xor_ps(dot(r, ld(&self.e2)), sign);
            let v = _mm_xor_ps(dot(r, ld(&self.e1)), sign);
            let abs_det = _mm_andnot_ps(_mm_set1_ps(f32::from_bits(SIGN)), det);
            let w = sub(sub(abs_det, u), v);
            let t_scaled = _mm_xor_ps(t, sign);
            // A set sign bit rejects: a −0.0 coordinate counts as outside.
            let outside = _mm_movemask_ps(_mm_or_ps(_mm_or_ps(u, v), w)) as u32;
            let nonzero = _mm_cmpneq_ps(det, _mm_setzero_ps());
            let near = _mm_cmpge_ps(t_scaled, mul(_mm_set1_ps(ray.tmin), abs_det));
            let far = _mm_cmple_ps(t_scaled, mul(_mm_set1_ps(ray.tmax), abs_det));
            let in_range = _mm_movemask_ps(_mm_and_ps(nonzero, _mm_and_ps(near, far))) as u32;
            let mask = lanes & in_range & !outside;
            let mut dist = [f32::INFINITY; 4];
            if mask != 0 {
                _mm_storeu_ps(dist.as_mut_ptr(), _mm_div_ps(t, det));
            }
            (mask, dist)
        }
    }

    #[cfg(not(target_arch = "x86_64"))]
    #[inline(always)]
    pub fn hits(&self, ray: &Ray, lanes: u32) -> (u32, [f32; 4]) {
        let mut dist = [f32::INFINITY; 4];
        let mut mask = 0;
        for (lane, d) in dist.iter_mut().enumerate() {
            if lanes >> lane & 1 != 0 {
                *d = crate::triangle::intersect(&self.get(lane), ray);
                mask |= (d.is_finite() as u32) << lane;
            }
        }
        (mask, dist)
    }

    /// The closest hit among `lanes` strictly nearer than `ray.tmax`: (distance, lane). Of
    /// equal distances the highest lane wins, as when the scalar loop (highest bit first,
    /// strict `<`) tests them one by one.
    #[inline(always)]
    pub fn closest(&self, ray: &Ray, lanes: u32) -> Option<(f32, u32)> {
        let (mut mask, dist) = self.hits(ray, lanes);
        let mut best: Option<(f32, u32)> = None;
        while mask != 0 {
            let lane = 31 - mask.leading_zeros();
            mask &= !(1 << lane);
            let t = dist[lane as usize];
            if t < best.map_or(ray.tmax, |b| b.0) {
                best = Some((t, lane));
            }
        }
        best
    }

    /// True when `ray` hits any of `lanes` strictly nearer than `ray.tmax`.
    #[inline(always)]
    pub fn any(&self, ray: &Ray, lanes: u32) -> bool {
        let (mask, dist) = self.hits(ray, lanes);
        mask != 0 && (0..4).any(|lane| mask >> lane & 1 != 0 && dist[lane] < ray.tmax)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::accel::{Accel, InputTri};
    use crate::sampler::mix64;
    use crate::triangle::intersect;
    use obvhs::cwbvh::Traversal;
    use obvhs::triangle::Triangle;

    fn unit(r: u64) -> f32 {
        (r >> 40) as f32 / (1u64 << 24) as f32
    }

    fn v3(r: u64, scale: f32) -> Vec3A {
        Vec3A::new(
            unit(mix64(r ^ 1)) - 0.5,
            unit(mix64(r ^ 2)) - 0.5,
            unit(mix64(r ^ 3)) - 0.5,
        ) * scale
    }

    /// A random triangle; every 8th has no area (a repeated vertex, or collinear vertices),
    /// every 8th is tiny and every 8th huge.
    fn triangle(r: u64) -> RtTriangle {
        let scale = [2.0, 2.0, 2.0, 2.0, 2.0, 2e-4, 3e3, 2.0][(r % 8) as usize];
        let (a, b, mut c) = (v3(r, scale), v3(mix64(r), scale), v3(mix64(r ^ 9), scale));
        if r % 8 == 7 {
            c = if r % 16 == 7 { a } else { a + (b - a) * 0.375 };
        }
        RtTriangle::from(&Triangle {
            v0: a,
            v1: b,
            v2: c,
        })
    }

    /// A ray from a random origin at barycentric coordinates (of v1, v2) in [-0.25, 1]², or
    /// exactly on an edge or a vertex for one ray in four.
    fn ray_at(tri: &RtTriangle, r: u64) -> Ray {
        let (mut a, mut b) = (
            unit(mix64(r ^ 6)) * 1.25 - 0.25,
            unit(mix64(r ^ 7)) * 1.25 - 0.25,
        );
        match r % 16 {
            0 => a = 0.0,
            1 => b = 0.0,
            2 => b = 1.0 - a,
            3 => (a, b) = (0.0, 0.0),
            _ => {}
        }
        let target = tri.v0 - tri.e1 * a + tri.e2 * b;
        let o = v3(mix64(r ^ 5), 6.0);
        let tmax = if r.is_multiple_of(3) {
            f32::INFINITY
        } else {
            4.0
        };
        let dir = (target - o).normalize_or(Vec3A::X);
        Ray::new(o, dir, 0.0, tmax)
    }

    #[test]
    fn every_lane_is_the_scalar_test_bit_for_bit() {
        let (mut hits, mut tested) = (0u32, 0u32);
        for k in 0..50_000u64 {
            let r = mix64(k);
            let mut pack = Tri4::default();
            let tris: Vec<RtTriangle> = (0..4).map(|l| triangle(mix64(r ^ (l + 11)))).collect();
            for (lane, tri) in tris.iter().enumerate() {
                pack.set(lane, tri);
                assert!(pack.get(lane) == *tri);
            }
            // Aimed at one of the four; the others are hit or missed by chance.
            let ray = ray_at(&tris[(r >> 8) as usize % 4], r);
            let lanes = (r >> 16) as u32 & 0xf;
            let (mask, dist) = pack.hits(&ray, lanes);
            assert_eq!(mask & !lanes, 0, "only the asked lanes");
            for (lane, tri) in tris.iter().enumerate() {
                if lanes >> lane & 1 == 0 {
                    continue;
                }
                tested += 1;
                let t = intersect(tri, &ray);
                let hit = mask >> lane & 1 != 0;
                assert_eq!(hit, t.is_finite(), "case {k} lane {lane}: {ray:?}");
                if hit {
                    hits += 1;
                    assert_eq!(dist[lane].to_bits(), t.to_bits(), "case {k} lane {lane}");
                }
            }
        }
        assert!(hits > 8_000 && hits < tested / 2, "{hits} hits of {tested}");
    }

    #[test]
    fn closest_and_any_follow_tmax_and_ties() {
        // Two coincident triangles in lanes 1 and 3, one nearer in lane 0, an empty lane 2.
        let tri = |z: f32| {
            RtTriangle::from(&Triangle {
                v0: Vec3A::new(-1.0, -1.0, z),
                v1: Vec3A::new(1.0, -1.0, z),
                v2: Vec3A::new(0.0, 1.0, z),
            })
        };
        let mut pack = Tri4::default();
        pack.set(0, &tri(1.0));
        pack.set(1, &tri(3.0));
        pack.set(3, &tri(3.0));
        let ray = |tmax: f32| Ray::new(Vec3A::ZERO, Vec3A::Z, 0.0, tmax);
        assert_eq!(pack.closest(&ray(9.0), 0xf), Some((1.0, 0)));
        // The equally near lanes 1 and 3: the highest wins, as in the one-by-one order.
        assert_eq!(pack.closest(&ray(9.0), 0b1110), Some((3.0, 3)));
        assert_eq!(pack.closest(&ray(9.0), 0b0010), Some((3.0, 1)));
        // Strictly nearer than tmax; the empty lane never hits.
        assert_eq!(pack.closest(&ray(3.0), 0b1110), None);
        assert_eq!(pack.closest(&ray(9.0), 0b0100), None);
        assert!(pack.any(&ray(1.5), 0b0001));
        assert!(!pack.any(&ray(1.0), 0b0001));
        assert!(!pack.any(&ray(2.5), 0b1110));
        assert!(pack.any(&ray(3.5), 0b1000));
    }

    /// A bumpy grid of `n`×`n` cells (every inner edge shared by two triangles) plus random
    /// triangles above it.
    fn terrain(n: usize) -> Vec<InputTri> {
        let p = |i: usize, j: usize| {
            let (x, z) = (
                i as f32 / n as f32 * 4.0 - 2.0,
                j as f32 / n as f32 * 4.0 - 2.0,
            );
            Vec3A::new(x, 0.3 * (2.0 * x).sin() * (3.0 * z).cos(), z)
        };
        let mut tris = Vec::new();
        for j in 0..n {
            for i in 0..n {
                for v in [
                    [p(i, j), p(i + 1, j), p(i + 1, j + 1)],
                    [p(i, j), p(i + 1, j + 1), p(i, j + 1)],
                ] {
                    let prim = tris.len() as u32;
                    tris.push(InputTri {
                        v,
                        instance: 0,
                        prim,
                    });
                }
            }
        }
        for k in 0..200u64 {
            let r = mix64(k ^ 0xabc);
            let c = v3(r, 4.0) + Vec3A::Y * 2.5;
            let v = [c, c + v3(mix64(r), 0.5), c + v3(mix64(r ^ 1), 0.5)];
            let prim = tris.len() as u32;
            tris.push(InputTri {
                v,
                instance: 0,
                prim,
            });
        }
        tris
    }

    #[test]
    fn accel_matches_testing_every_triangle() {
        let input = terrain(24);
        let accel = Accel::build(&input);
        assert_eq!(accel.triangle_count(), input.len());
        let scalar: Vec<RtTriangle> = input
            .iter()
            .map(|t| RtTriangle::from(&t.triangle()))
            .collect();
        let mut state = Traversal::default();
        let mut hits = 0;
        for k in 0..4000u64 {
            let r = mix64(k);
            let o = v3(r, 6.0) + Vec3A::Y * 4.0;
            let target = v3(mix64(r ^ 3), 4.0) * Vec3A::new(1.0, 0.2, 1.0);
            let tmax = if k.is_multiple_of(4) {
                3.0
            } else {
                f32::INFINITY
            };
            let ray = Ray::new(o, (target - o).normalize(), 0.0, tmax);
            let brute = scalar
                .iter()
                .map(|t| intersect(t, &ray))
                .filter(|&t| t < tmax)
                .fold(f32::INFINITY, f32::min);
            let got = accel.closest(&ray, &mut state);
            assert_eq!(
                got.map(|h| h.t.to_bits()),
                brute.is_finite().then(|| brute.to_bits())
            );
            if let Some(h) = got {
                hits += 1;
                let prim = accel.info[h.slot as usize].prim as usize;
                assert_eq!(
                    intersect(&scalar[prim], &ray),
                    h.t,
                    "the slot names the triangle"
                );
                // v1 and v2 come back from the edges, so within rounding.
                for (a, b) in accel.vertices(h.slot).iter().zip(input[prim].v) {
                    assert!((*a - b).abs().max_element() < 1e-6, "{a} vs {b}");
                }
            }
            assert_eq!(accel.unblocked(&ray, &mut state), got.is_none());
        }
        assert!(hits > 2000, "{hits}");
    }
}
