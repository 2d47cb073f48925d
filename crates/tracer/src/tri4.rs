//! Four triangles tested against one ray at once: the BVH's triangles stored four to a block
//! (structure of arrays), so one SSE2 test covers up to four slots of a leaf. Each leaf of a
//! mesh's structure is one block ([`crate::collapse`]), so a node's hit leaves' slot bits
//! split into one 4-bit lane mask per block.
//!
//! The test is Woop, Benthin and Wald's watertight one ("Watertight Ray/Triangle
//! Intersection", JCGT 2013): the vertices, relative to the ray origin, are sheared into a
//! space where the ray runs along +z, and each edge's 2D edge function is computed from its
//! two end points alone. An edge shared by two triangles then gets exactly opposite values in
//! the two (the same products, subtracted the other way round), and a zero counts as inside,
//! so a ray at a shared edge hits at least one of them. Möller–Trumbore (the scalar
//! [`crate::triangle::intersect`], used before) derives one of the three coordinates from the
//! other two and the determinant, and let 1373 of 10 000 rays aimed at such edges of a grid
//! through (`tests`). Its cost: 637.8M instructions for the Cornell-box benchmark against
//! 602.5M for Möller–Trumbore four lanes at a time (661.6M one at a time). Plain SSE2
//! arithmetic, no FMA, so every x86-64 machine gets the same bits; [`Tri4::hit_lane`] is the same arithmetic one lane at a time.
use crate::triangle::SIGN;
use glam::Vec3A;
use obvhs::ray::Ray;
use obvhs::triangle::Triangle;

/// Four triangles' vertices, `v[vertex][axis][lane]`. An empty lane is all zeros: its
/// determinant is 0, so it never hits.
#[derive(Clone, Copy, Debug, Default)]
#[repr(C, align(16))]
pub struct Tri4 {
    v: [[[f32; 4]; 3]; 3],
}

/// What a ray's tests share: the axis permutation that makes the direction's largest
/// component z, the shear that maps the direction onto +z, and the origin, each number
/// repeated in four lanes.
#[derive(Clone, Copy, Debug)]
#[repr(C, align(16))]
pub struct Shear {
    /// x −= sx·z, y −= sy·z; distances scale by sz.
    s: [[f32; 4]; 3],
    /// The origin's components along the axes that become x, y and z.
    o: [[f32; 4]; 3],
    /// The axes that become x, y and z (each < 3).
    k: [usize; 3],
}

impl Shear {
    pub fn new(ray: &Ray) -> Shear {
        let d = ray.direction.to_array();
        let a = ray.direction.abs();
        let kz = if a.x >= a.y && a.x >= a.z {
            0
        } else if a.y >= a.z {
            1
        } else {
            2
        };
        let (kx, ky) = ((kz + 1) % 3, (kz + 2) % 3);
        let sz = 1.0 / d[kz];
        let o = ray.origin.to_array();
        Shear {
            s: [[d[kx] * sz; 4], [d[ky] * sz; 4], [sz; 4]],
            o: [[o[kx]; 4], [o[ky]; 4], [o[kz]; 4]],
            k: [kx, ky, kz],
        }
    }
}

impl Shear {
    /// The axes that become x, y and z.
    pub fn k(&self) -> [usize; 3] {
        self.k
    }

    /// sx, sy and sz.
    pub fn scale(&self) -> [f32; 3] {
        self.s.map(|s| s[0])
    }

    /// The origin's components along the axes that become x, y and z.
    pub fn origin(&self) -> [f32; 3] {
        self.o.map(|o| o[0])
    }
}

impl Tri4 {
    /// Vertex `i` (0 to 2) of the triangle in lane `lane`: x, y, z.
    #[inline(always)]
    pub fn vertex(&self, i: usize, lane: usize) -> [f32; 3] {
        self.v[i].map(|axis| axis[lane])
    }

    /// Puts `tri` into lane `lane`.
    pub fn set(&mut self, lane: usize, tri: &Triangle) {
        for (dst, src) in self.v.iter_mut().zip([tri.v0, tri.v1, tri.v2]) {
            for (axis, value) in dst.iter_mut().zip(src.to_array()) {
                axis[lane] = value;
            }
        }
    }

    /// The triangle in lane `lane`, as it was put in.
    pub fn get(&self, lane: usize) -> Triangle {
        let v = |i: usize| {
            let a = &self.v[i];
            Vec3A::new(a[0][lane], a[1][lane], a[2][lane])
        };
        Triangle {
            v0: v(0),
            v1: v(1),
            v2: v(2),
        }
    }

    /// The lanes among `lanes` (bit i: lane i) that `ray` (with its `shear`) hits within
    /// [tmin, tmax], and the four distances (meaningful in the hit lanes only). Both faces
    /// count.
    #[cfg(target_arch = "x86_64")]
    #[inline(always)]
    pub fn hits(&self, ray: &Ray, shear: &Shear, lanes: u32) -> (u32, [f32; 4]) {
        use std::arch::x86_64::*;
        let [kx, ky, kz] = shear.k;
        // SAFETY: SSE2 is part of the x86_64 baseline; `Tri4` and `Shear` are 16-byte aligned,
        // so every `[f32; 4]` row is an aligned 16-byte load; `Shear::new` makes every k < 3.
        unsafe {
            let (mul, sub) = (_mm_mul_ps, _mm_sub_ps);
            let ld = |row: &[f32; 4]| _mm_load_ps(row.as_ptr());
            let (s, o) = (shear.s.each_ref().map(ld), shear.o.each_ref().map(ld));
            // One vertex relative to the origin, sheared: (x − sx·z, y − sy·z, z) (z is
            // scaled by sz once, in t).
            let vertex = |v: &[[f32; 4]; 3]| {
                let x = sub(ld(v.get_unchecked(kx)), o[0]);
                let y = sub(ld(v.get_unchecked(ky)), o[1]);
                let z = sub(ld(v.get_unchecked(kz)), o[2]);
                (sub(x, mul(s[0], z)), sub(y, mul(s[1], z)), z)
            };
            let (ax, ay, az) = vertex(&self.v[0]);
            let (bx, by, bz) = vertex(&self.v[1]);
            let (cx, cy, cz) = vertex(&self.v[2]);
            // Edge functions: u of edge b→c (weight of v0), v of c→a, w of a→b.
            let u = sub(mul(cx, by), mul(cy, bx));
            let v = sub(mul(ax, cy), mul(ay, cx));
            let w = sub(mul(bx, ay), mul(by, ax));
            let det = _mm_add_ps(_mm_add_ps(u, v), w);
            let t = _mm_add_ps(_mm_add_ps(mul(u, az), mul(v, bz)), mul(w, cz));
            let t = mul(t, s[2]);
            // u, v, w and t made non-negative exactly where they share det's sign.
            let sign_bit = _mm_set1_ps(f32::from_bits(SIGN));
            let sign = _mm_and_ps(det, sign_bit);
            let zero = _mm_setzero_ps();
            let inside = _mm_and_ps(
                _mm_cmpge_ps(_mm_xor_ps(u, sign), zero),
                _mm_and_ps(
                    _mm_cmpge_ps(_mm_xor_ps(v, sign), zero),
                    _mm_cmpge_ps(_mm_xor_ps(w, sign), zero),
                ),
            );
            let abs_det = _mm_andnot_ps(sign_bit, det);
            let t_scaled = _mm_xor_ps(t, sign);
            let near = _mm_cmpge_ps(t_scaled, mul(_mm_set1_ps(ray.tmin), abs_det));
            let far = _mm_cmple_ps(t_scaled, mul(_mm_set1_ps(ray.tmax), abs_det));
            let ok = _mm_and_ps(
                _mm_and_ps(inside, _mm_cmpneq_ps(det, zero)),
                _mm_and_ps(near, far),
            );
            let mask = lanes & _mm_movemask_ps(ok) as u32;
            let mut dist = [f32::INFINITY; 4];
            if mask != 0 {
                _mm_storeu_ps(dist.as_mut_ptr(), _mm_div_ps(t, det));
            }
            (mask, dist)
        }
    }

    #[cfg(not(target_arch = "x86_64"))]
    #[inline(always)]
    pub fn hits(&self, ray: &Ray, shear: &Shear, lanes: u32) -> (u32, [f32; 4]) {
        let mut dist = [f32::INFINITY; 4];
        let mut mask = 0;
        for (lane, d) in dist.iter_mut().enumerate() {
            if lanes >> lane & 1 != 0 {
                *d = self.hit_lane(lane, ray, shear);
                mask |= (d.is_finite() as u32) << lane;
            }
        }
        (mask, dist)
    }

    /// [`Tri4::hits`] for one lane: the distance to the hit, or +∞.
    #[cfg_attr(all(target_arch = "x86_64", not(test)), allow(dead_code))]
    pub fn hit_lane(&self, lane: usize, ray: &Ray, shear: &Shear) -> f32 {
        let [kx, ky, kz] = shear.k;
        let [sx, sy, sz] = shear.s.map(|s| s[0]);
        let [ox, oy, oz] = shear.o.map(|o| o[0]);
        let vertex = |v: &[[f32; 4]; 3]| {
            let (x, y, z) = (v[kx][lane] - ox, v[ky][lane] - oy, v[kz][lane] - oz);
            (x - sx * z, y - sy * z, z)
        };
        let (ax, ay, az) = vertex(&self.v[0]);
        let (bx, by, bz) = vertex(&self.v[1]);
        let (cx, cy, cz) = vertex(&self.v[2]);
        let u = cx * by - cy * bx;
        let v = ax * cy - ay * cx;
        let w = bx * ay - by * ax;
        let det = u + v + w;
        let t = (u * az + v * bz + w * cz) * sz;
        let sign = det.to_bits() & SIGN;
        let flip = |x: f32| f32::from_bits(x.to_bits() ^ sign);
        let abs_det = det.abs();
        let inside = flip(u) >= 0.0 && flip(v) >= 0.0 && flip(w) >= 0.0;
        let t_scaled = flip(t);
        if inside && det != 0.0 && t_scaled >= ray.tmin * abs_det && t_scaled <= ray.tmax * abs_det
        {
            t / det
        } else {
            f32::INFINITY
        }
    }

    /// The closest hit among `lanes` strictly nearer than `ray.tmax`: (distance, lane). Of
    /// equal distances the highest lane wins, as when the scalar loop (highest bit first,
    /// strict `<`) tests them one by one.
    #[inline(always)]
    pub fn closest(&self, ray: &Ray, shear: &Shear, lanes: u32) -> Option<(f32, u32)> {
        let (mut mask, dist) = self.hits(ray, shear, lanes);
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
    pub fn any(&self, ray: &Ray, shear: &Shear, lanes: u32) -> bool {
        let (mask, dist) = self.hits(ray, shear, lanes);
        mask != 0 && (0..4).any(|lane| mask >> lane & 1 != 0 && dist[lane] < ray.tmax)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::accel::{Accel, InputTri};
    use crate::isa::Baseline;
    use crate::sampler::mix64;
    use crate::triangle::tests::{unit, v3};
    use crate::triangle::{intersect, normal_and_area};
    use crate::wide_walk::WalkStack;
    use obvhs::triangle::Triangle;

    /// A random triangle; every 8th has no area (a repeated vertex, or collinear vertices),
    /// every 8th is tiny and every 8th huge.
    fn triangle(r: u64) -> Triangle {
        let scale = [2.0, 2.0, 2.0, 2.0, 2.0, 2e-4, 3e3, 2.0][(r % 8) as usize];
        let (a, b, mut c) = (v3(r, scale), v3(mix64(r), scale), v3(mix64(r ^ 9), scale));
        if r % 8 == 7 {
            c = if r % 16 == 7 { a } else { a + (b - a) * 0.375 };
        }
        Triangle {
            v0: a,
            v1: b,
            v2: c,
        }
    }

    /// A ray from a random origin at barycentric coordinates (of v1, v2) in [-0.25, 1]², or
    /// exactly on an edge or a vertex for one ray in four.
    fn ray_at(tri: &Triangle, r: u64) -> Ray {
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
        let target = tri.v0 + (tri.v1 - tri.v0) * a + (tri.v2 - tri.v0) * b;
        let o = v3(mix64(r ^ 5), 6.0);
        let tmax = if r.is_multiple_of(3) {
            f32::INFINITY
        } else {
            4.0
        };
        let dir = (target - o).normalize_or(Vec3A::X);
        Ray::new(o, dir, 0.0, tmax)
    }

    /// The scalar test of one triangle.
    fn one(tri: &Triangle, ray: &Ray) -> f32 {
        let mut pack = Tri4::default();
        pack.set(0, tri);
        pack.hit_lane(0, ray, &Shear::new(ray))
    }

    #[test]
    fn every_lane_is_the_scalar_test_bit_for_bit() {
        let (mut hits, mut tested) = (0u32, 0u32);
        for k in 0..50_000u64 {
            let r = mix64(k);
            let mut pack = Tri4::default();
            let tris: Vec<Triangle> = (0..4).map(|l| triangle(mix64(r ^ (l + 11)))).collect();
            for (lane, tri) in tris.iter().enumerate() {
                pack.set(lane, tri);
                let back = pack.get(lane);
                assert_eq!([back.v0, back.v1, back.v2], [tri.v0, tri.v1, tri.v2]);
            }
            // Aimed at one of the four; the others are hit or missed by chance.
            let ray = ray_at(&tris[(r >> 8) as usize % 4], r);
            let shear = Shear::new(&ray);
            let lanes = (r >> 16) as u32 & 0xf;
            let (mask, dist) = pack.hits(&ray, &shear, lanes);
            assert_eq!(mask & !lanes, 0, "only the asked lanes");
            for (lane, d) in dist.iter().enumerate() {
                if lanes >> lane & 1 == 0 {
                    continue;
                }
                tested += 1;
                let t = pack.hit_lane(lane, &ray, &shear);
                let hit = mask >> lane & 1 != 0;
                assert_eq!(hit, t.is_finite(), "case {k} lane {lane}: {ray:?}");
                if hit {
                    hits += 1;
                    assert_eq!(d.to_bits(), t.to_bits(), "case {k} lane {lane}");
                }
            }
        }
        assert!(hits > 8_000 && hits < tested / 2, "{hits} hits of {tested}");
    }

    #[test]
    fn agrees_with_moller_trumbore_except_within_rounding_of_an_edge() {
        let (mut hits, mut differ, mut differ_tiny, mut compared) = (0u32, 0u32, 0u32, 0u32);
        for k in 0..200_000u64 {
            let r = mix64(k);
            let tri = triangle(r);
            let ray = ray_at(&tri, r);
            let mt = obvhs::rt_triangle::RtTriangle::from(&tri);
            let (a, b) = (one(&tri, &ray), intersect(&mt, &ray));
            hits += a.is_finite() as u32;
            if r % 16 == 7 {
                assert!(
                    !a.is_finite(),
                    "a triangle with a repeated vertex cannot be hit"
                );
            }
            // Rays aimed at an edge and triangles without an area are coin flips for both.
            if a.is_finite() != b.is_finite() && r % 16 >= 4 && r % 8 != 7 {
                // The watertight test works with the vertices relative to the origin, so it
                // resolves a tiny triangle (2e-4 across, ~3 away) to ~1e-3 of its size.
                if r % 8 == 5 {
                    differ_tiny += 1;
                } else {
                    differ += 1;
                }
            }
            // Distances compared where they are well conditioned: triangles with an area (not
            // the collinear ones, which get a random one from rounding) and rays not grazing.
            let cos = normal_and_area(tri.v1 - tri.v0, tri.v2 - tri.v0)
                .map_or(0.0, |(n, _)| n.dot(ray.direction).abs());
            if a.is_finite() && b.is_finite() && r % 8 != 7 && cos > 0.05 {
                compared += 1;
                // Within rounding of the vertices' distances from the origin (the huge
                // triangles' t are good to ~1e-5 of their size, not of t).
                let size = [tri.v0, tri.v1, tri.v2]
                    .map(|v| (v - ray.origin).length())
                    .into_iter()
                    .fold(1.0, f32::max);
                assert!(
                    (a - b).abs() <= 1e-5 * size,
                    "case {k}: t {a} vs {b} ({size})"
                );
            }
        }
        assert!(
            hits > 40_000 && compared > 30_000,
            "{hits} hits, {compared} compared"
        );
        eprintln!("{hits} hits, {differ} + {differ_tiny} (tiny) hit/miss disagreements");
        // Off the edges the two disagree only where a coordinate rounds across 0; of the
        // ~19 000 rays at tiny triangles, ~1 %.
        assert!(differ <= 20, "{differ} hit/miss disagreements");
        assert!(
            differ_tiny <= 400,
            "{differ_tiny} hit/miss disagreements, tiny triangles"
        );
    }

    #[test]
    fn closest_and_any_follow_tmax_and_ties() {
        // Two coincident triangles in lanes 1 and 3, one nearer in lane 0, an empty lane 2.
        let tri = |z: f32| Triangle {
            v0: Vec3A::new(-1.0, -1.0, z),
            v1: Vec3A::new(1.0, -1.0, z),
            v2: Vec3A::new(0.0, 1.0, z),
        };
        let mut pack = Tri4::default();
        pack.set(0, &tri(1.0));
        pack.set(1, &tri(3.0));
        pack.set(3, &tri(3.0));
        let ray = |tmax: f32| Ray::new(Vec3A::ZERO, Vec3A::Z, 0.0, tmax);
        let closest = |tmax: f32, lanes: u32| {
            let r = ray(tmax);
            pack.closest(&r, &Shear::new(&r), lanes)
        };
        let any = |tmax: f32, lanes: u32| {
            let r = ray(tmax);
            pack.any(&r, &Shear::new(&r), lanes)
        };
        assert_eq!(closest(9.0, 0xf), Some((1.0, 0)));
        // The equally near lanes 1 and 3: the highest wins, as in the one-by-one order.
        assert_eq!(closest(9.0, 0b1110), Some((3.0, 3)));
        assert_eq!(closest(9.0, 0b0010), Some((3.0, 1)));
        // Strictly nearer than tmax; the empty lane never hits.
        assert_eq!(closest(3.0, 0b1110), None);
        assert_eq!(closest(9.0, 0b0100), None);
        assert!(any(1.5, 0b0001));
        assert!(!any(1.0, 0b0001));
        assert!(!any(2.5, 0b1110));
        assert!(any(3.5, 0b1000));
        // From behind, and a ray along -x (another axis order): both faces count.
        let back = Ray::new(Vec3A::new(0.0, 0.0, 5.0), -Vec3A::Z, 0.0, 9.0);
        assert_eq!(pack.closest(&back, &Shear::new(&back), 0xf), Some((2.0, 3)));
        let side = Triangle {
            v0: Vec3A::new(-2.0, -1.0, -1.0),
            v1: Vec3A::new(-2.0, 1.0, -1.0),
            v2: Vec3A::new(-2.0, 0.0, 1.0),
        };
        let x = Ray::new(Vec3A::new(0.0, 0.0, 0.0), -Vec3A::X, 0.0, 9.0);
        assert_eq!(one(&side, &x), 2.0);
    }

    /// A bumpy grid of `n`×`n` cells (every inner edge shared by two triangles) plus random
    /// triangles above it.
    fn terrain(n: usize) -> Vec<InputTri> {
        let p = |i: usize, j: usize| {
            let (x, z) = (
                i as f32 / n as f32 * 4.0 - 2.0,
                j as f32 / n as f32 * 4.0 - 2.0,
            );
            Vec3A::new(x, 0.3 * libm::sinf(2.0 * x) * libm::cosf(3.0 * z), z)
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
        accel_matches_brute_force(Accel::build(&terrain(24)));
    }

    fn accel_matches_brute_force(accel: Accel) {
        let input = terrain(24);
        assert_eq!(accel.triangle_count(), input.len());
        let scalar: Vec<Triangle> = input.iter().map(|t| t.triangle()).collect();
        let mut state = WalkStack::default();
        let (mut hits, mut several) = (0, 0);
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
                .map(|t| one(t, &ray))
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
                assert_eq!(one(&scalar[prim], &ray), h.t, "the slot names the triangle");
                assert_eq!(accel.vertices(h.slot), input[prim].v);
            }
            assert_eq!(accel.unblocked(&ray, &mut state), got.is_none());
            // Every hit once (the see-through shadow rays' walk), and a stop when asked.
            let mut every = Vec::new();
            accel.each_hit_with(Baseline, &ray, &mut state, &mut |h| {
                every.push((accel.info[h.slot as usize].prim, h.t.to_bits()));
                false
            });
            every.sort_unstable();
            let want: Vec<(u32, u32)> = (0..scalar.len() as u32)
                .map(|i| (i, one(&scalar[i as usize], &ray)))
                .filter(|&(_, t)| t < tmax)
                .map(|(i, t)| (i, t.to_bits()))
                .collect();
            assert_eq!(every, want);
            several += (want.len() > 1) as u32;
            let mut seen = 0;
            let stopped = accel.each_hit_with(Baseline, &ray, &mut state, &mut |_| {
                seen += 1;
                true
            });
            assert_eq!((stopped, seen), (got.is_some(), got.is_some() as u32));
        }
        assert!(hits > 2000, "{hits}");
        assert!(several > 200, "{several}");
    }

    #[test]
    fn rays_at_a_shared_edge_hit_one_of_its_triangles() {
        // Rays at points of the grid's inner edges (shared by two triangles), from above.
        let n = 16;
        let input = terrain(n);
        let accel = Accel::build(&input);
        let mut state = WalkStack::default();
        let mut through = 0;
        for k in 0..20_000u64 {
            let r = mix64(k);
            let (i, j) = (
                1 + (r % (n as u64 - 2)) as usize,
                1 + (r >> 8) as usize % (n - 2),
            );
            // Cell (i, j)'s diagonal, or its edge with the cell to its left.
            let cell = 2 * (j * n + i);
            let f = unit(mix64(r ^ 4));
            let edge = if k % 2 == 0 {
                let [a, _, c] = input[cell].v;
                a + (c - a) * f
            } else {
                let [a, _, c] = input[cell + 1].v;
                a + (c - a) * f
            };
            let o = edge + v3(mix64(r ^ 2), 3.0) * Vec3A::new(1.0, 0.0, 1.0) + Vec3A::Y * 2.0;
            let d = (edge - o).normalize();
            let ray = Ray::new(o, d, 0.0, f32::INFINITY);
            let hit = accel.closest(&ray, &mut state);
            through += hit.is_none() as u32;
            assert_eq!(accel.unblocked(&ray, &mut state), hit.is_none());
        }
        // Möller–Trumbore (main before 2026-12-03) let 1373 of the 10 000 rays at the edges
        // between cells through, none of those at the diagonals.
        assert_eq!(through, 0, "rays slipped through shared edges");
    }
}
