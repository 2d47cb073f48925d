//! Triangle helpers: normal and area, and the scalar Möller–Trumbore test that the BVH's
//! leaves used before their watertight four-lane test ([`crate::tri4`]), kept as the reference
//! the tests compare that with. Möller–Trumbore on obvhs's [`RtTriangle`] layout
//! (v0, e1 = v0 − v1, e2 = v2 − v0, ng = e1 × e2), with the division deferred to accepted hits.
//!
//! obvhs's `RtTriangle::intersect` computes 1/det before it knows whether the ray hits, so
//! every test waits on a division (the largest single cost of a Cornell-box frame in `perf`).
//! Here the barycentric and distance tests compare the undivided numerators against det's sign
//! and magnitude, and only a hit divides. The tests are the same inequalities, so hits agree
//! with obvhs's except where a barycentric coordinate or t sits within rounding of its bound.
use glam::Vec3A;
use obvhs::ray::Ray;
use obvhs::rt_triangle::RtTriangle;

/// The unit normal (direction `e1 × e2`) and the area of the triangle with edges `e1`, `e2`,
/// or `None` when it has no area or is not finite. Where the cross product's squared length
/// fits in f32 this is `(c.normalize(), |c|/2)` of `c = e1 × e2`, as always. Beyond (edges of
/// 1e10 give a cross product of 1e20 whose square, 1e40, is infinite, and the normal came out
/// zero: the surface rendered black) both come from the edges scaled to at most 1 in every
/// component; the area itself is infinite past edges of about 2.6e19.
pub fn normal_and_area(e1: Vec3A, e2: Vec3A) -> Option<(Vec3A, f32)> {
    let c = e1.cross(e2);
    let len2 = c.length_squared();
    if len2.is_finite() {
        return (len2 > 0.0 && c.is_finite()).then(|| (c.normalize(), 0.5 * c.length()));
    }
    let s = e1.abs().max_element().max(e2.abs().max_element());
    if !s.is_finite() {
        return None;
    }
    let c = (e1 / s).cross(e2 / s);
    let len = c.length();
    (len > 0.0).then(|| (c / len, 0.5 * len * s * s))
}

#[cfg(test)]
mod normal_tests {
    use super::*;

    #[test]
    fn long_edges_keep_their_normal_and_area() {
        let (n, a) =
            normal_and_area(Vec3A::new(1e10, 0.0, 0.0), Vec3A::new(0.0, 0.0, -1e10)).unwrap();
        assert_eq!(n, Vec3A::Y);
        assert!((a / 5e19 - 1.0).abs() < 1e-6, "{a}");
        let (n, a) = normal_and_area(Vec3A::X, Vec3A::Y).unwrap();
        assert_eq!((n, a), (Vec3A::Z, 0.5));
        assert!(normal_and_area(Vec3A::X, Vec3A::X * 2.0).is_none());
        assert!(normal_and_area(Vec3A::X * f32::INFINITY, Vec3A::Y).is_none());
    }
}

/// The sign bit of an f32.
pub(crate) const SIGN: u32 = 0x8000_0000;

/// Distance along `ray` to its hit with `tri` within [tmin, tmax], or +∞. Both faces count.
/// The leaves' test before the watertight [`crate::tri4::Tri4::hits`] replaced it, kept as the
/// reference its tests compare with.
#[cfg_attr(all(target_arch = "x86_64", not(test)), allow(dead_code))]
#[inline(always)]
pub fn intersect(tri: &RtTriangle, ray: &Ray) -> f32 {
    let c = tri.v0 - ray.origin;
    let r = ray.direction.cross(c);
    let det = tri.ng.dot(ray.direction);
    let t = tri.ng.dot(c);
    // u·det, v·det and t·det, made non-negative exactly where u, v and t are (det's sign
    // flipped into them).
    let sign = det.to_bits() & SIGN;
    let flip = |x: f32| f32::from_bits(x.to_bits() ^ sign);
    let u = flip(r.dot(tri.e2));
    let v = flip(r.dot(tri.e1));
    let abs_det = det.abs();
    let w = abs_det - u - v;
    let t_scaled = flip(t);
    // A set sign bit rejects, as in obvhs: a −0.0 coordinate counts as outside.
    let inside = (u.to_bits() | v.to_bits() | w.to_bits()) & SIGN == 0;
    if det != 0.0 && inside && t_scaled >= ray.tmin * abs_det && t_scaled <= ray.tmax * abs_det {
        t / det
    } else {
        f32::INFINITY
    }
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use crate::sampler::mix64;
    use glam::Vec3A;
    use obvhs::triangle::Triangle;

    pub(crate) fn unit(r: u64) -> f32 {
        (r >> 40) as f32 / (1u64 << 24) as f32
    }

    /// A pseudo-random point in the cube of side `scale` around the origin.
    pub(crate) fn v3(r: u64, scale: f32) -> Vec3A {
        Vec3A::new(
            unit(mix64(r ^ 1)) - 0.5,
            unit(mix64(r ^ 2)) - 0.5,
            unit(mix64(r ^ 3)) - 0.5,
        ) * scale
    }

    #[test]
    fn agrees_with_obvhs_except_within_rounding_of_an_edge() {
        let (mut hits, mut differ) = (0u32, 0u32);
        for k in 0..200_000u64 {
            let r = mix64(k);
            let tri = RtTriangle::from(&Triangle {
                v0: v3(r, 2.0),
                v1: v3(mix64(r), 2.0),
                v2: v3(mix64(r ^ 9), 2.0),
            });
            let o = v3(mix64(r ^ 5), 6.0);
            // Aim at barycentric coordinates in [-0.25, 1], so that about half of the rays hit
            // (v1 = v0 - e1, v2 = v0 + e2).
            let (a, b) = (
                unit(mix64(r ^ 6)) * 1.25 - 0.25,
                unit(mix64(r ^ 7)) * 1.25 - 0.25,
            );
            let target = tri.v0 - tri.e1 * a + tri.e2 * b;
            let tmax = if k % 3 == 0 { f32::INFINITY } else { 4.0 };
            let ray = Ray::new(o, (target - o).normalize(), 0.0, tmax);
            let (a, b) = (intersect(&tri, &ray), tri.intersect(&ray));
            hits += a.is_finite() as u32;
            if a.is_finite() != b.is_finite() {
                differ += 1;
                continue;
            }
            if a.is_finite() {
                assert!((a - b).abs() <= 1e-5 * b.abs().max(1.0), "t {a} vs {b}");
            }
        }
        assert!(hits > 50_000, "rays must hit ({hits})");
        eprintln!("{hits} hits, {differ} hit/miss disagreements with obvhs");
        // Disagreements only where a coordinate rounds across 0: a few in a million.
        assert!(differ <= 20, "{differ} hit/miss disagreements");
    }

    #[test]
    fn range_and_faces() {
        let tri = RtTriangle::from(&Triangle {
            v0: Vec3A::new(-1.0, -1.0, 2.0),
            v1: Vec3A::new(1.0, -1.0, 2.0),
            v2: Vec3A::new(0.0, 1.0, 2.0),
        });
        let o = Vec3A::ZERO;
        let toward = |tmin: f32, tmax: f32| intersect(&tri, &Ray::new(o, Vec3A::Z, tmin, tmax));
        assert_eq!(toward(0.0, f32::INFINITY), 2.0);
        assert_eq!(toward(0.0, 1.9), f32::INFINITY);
        assert_eq!(toward(2.1, 9.0), f32::INFINITY);
        // From behind (the other face) and away from it.
        let back = Ray::new(Vec3A::new(0.0, 0.0, 4.0), -Vec3A::Z, 0.0, f32::INFINITY);
        assert_eq!(intersect(&tri, &back), 2.0);
        let away = Ray::new(o, -Vec3A::Z, 0.0, f32::INFINITY);
        assert_eq!(intersect(&tri, &away), f32::INFINITY);
        // Parallel to the plane.
        let parallel = Ray::new(Vec3A::new(0.0, 0.0, 2.0), Vec3A::X, 0.0, f32::INFINITY);
        assert_eq!(intersect(&tri, &parallel), f32::INFINITY);
    }
}
