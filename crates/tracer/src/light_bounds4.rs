//! The bounds of four light-tree nodes side by side, and their importances at a shading point
//! computed together: one 4-lane vector per quantity (glam's `Vec4`, SSE2 on x86-64), the same
//! operations in every lane and no fused multiply-add, so every x86-64 node gets the same bits.
//!
//! A node's *importance* (Conty Estevez and Kulla 2018; pbrt-v4's `CompactLightBounds`) is a
//! conservative estimate of the irradiance its lights can deliver at x with normal n: power /
//! d² (d the distance to the centre of the box's bounding sphere, clamped at its radius), times
//! cos θ′, the largest emission cosine any of its lights can have towards x (the angle from the
//! cone's axis to x, less the spread θ_o, less the half-angle θ_b the sphere subtends), times the
//! largest receiver cosine towards the sphere (n against the direction to it, less θ_b). The
//! angle differences are taken on cosines and sines (cos(a − b) = cos a cos b + sin a sin b), so
//! there is no trigonometry, only square roots. It is exactly 0 only where no light of the node
//! can deliver anything: x outside every emission cone, or the whole sphere below x's tangent
//! plane.
use crate::light_tree::LightBounds;
use glam::{Vec3A, Vec4};

/// Angles below this (in cosine terms) count as on the boundary: the exact zero tests are made
/// a little generous so that rounding never rejects a light that reaches x.
const SLACK: f32 = 1e-4;

/// Up to four nodes' bounds, precomputed for the importance: bounding-sphere centre and radius
/// instead of the box's corners, and the spread's sine beside its cosine. Lanes without a node
/// have no power, so their importance is 0.
#[derive(Clone, Copy, Debug)]
pub struct Bounds4 {
    cx: Vec4,
    cy: Vec4,
    cz: Vec4,
    radius: Vec4,
    r2: Vec4,
    ax: Vec4,
    ay: Vec4,
    az: Vec4,
    cos_o: Vec4,
    sin_o: Vec4,
    cos_e: Vec4,
    phi: Vec4,
}

impl Bounds4 {
    /// `bounds` (at most four) in lanes 0, 1, ...
    pub fn pack(bounds: &[LightBounds]) -> Bounds4 {
        assert!(bounds.len() <= 4, "{} bounds for four lanes", bounds.len());
        let lane = |f: &dyn Fn(&LightBounds) -> f32, empty: f32| {
            Vec4::from_array(std::array::from_fn(|i| bounds.get(i).map_or(empty, f)))
        };
        let centre = |b: &LightBounds| 0.5 * (b.lo + b.hi);
        let radius = |b: &LightBounds| 0.5 * (b.hi - b.lo).length();
        let radius = lane(&radius, 0.0);
        Bounds4 {
            cx: lane(&|b| centre(b).x, 0.0),
            cy: lane(&|b| centre(b).y, 0.0),
            cz: lane(&|b| centre(b).z, 0.0),
            radius,
            r2: radius * radius,
            ax: lane(&|b| b.axis.x, 0.0),
            ay: lane(&|b| b.axis.y, 0.0),
            az: lane(&|b| b.axis.z, 1.0),
            cos_o: lane(&|b| b.cos_o, 1.0),
            sin_o: lane(&|b| (1.0 - b.cos_o * b.cos_o).max(0.0).sqrt(), 0.0),
            cos_e: lane(&|b| b.cos_e, 1.0),
            phi: lane(&|b| b.phi, 0.0),
        }
    }

    /// The four importances at `x` (normal `n`; none for a point that looks in every
    /// direction). Each is 0 only where nothing inside its node can reach `x`.
    #[inline]
    pub fn importance(&self, x: Vec3A, n: Option<Vec3A>) -> [f32; 4] {
        let (one, zero) = (Vec4::ONE, Vec4::ZERO);
        let (tx, ty, tz) = (
            Vec4::splat(x.x) - self.cx,
            Vec4::splat(x.y) - self.cy,
            Vec4::splat(x.z) - self.cz,
        );
        let d2 = tx * tx + ty * ty + tz * tz;
        // x inside the bounding sphere: every direction and cosine is possible.
        let inside = d2.cmple(self.r2) | d2.cmple(zero);
        let inv_d = one / sqrt(d2);
        // The cone of directions from x that meets the bounding sphere: half-angle θ_b.
        let sin_b = (self.radius * inv_d).min(one);
        let cos_b = sqrt((one - sin_b * sin_b).max(zero));
        // Emitter side: angle from the cone's axis to x, less the spread, less θ_b.
        let cos_w = ((self.ax * tx + self.ay * ty + self.az * tz) * inv_d).clamp(-one, one);
        let (sin_x, cos_x) = sub_angle(sin_of(cos_w), cos_w, self.sin_o, self.cos_o);
        let cos_p = sub_angle(sin_x, cos_x, sin_b, cos_b).1;
        let cos_p = Vec4::select(self.cos_o.cmple(-one), one, cos_p);
        let mut dead = cos_p.cmplt(self.cos_e - Vec4::splat(SLACK));
        // Receiver side: the largest cosine between n and a direction into the sphere.
        let cos_r = match n {
            Some(n) => {
                let dot = Vec4::splat(n.x) * tx + Vec4::splat(n.y) * ty + Vec4::splat(n.z) * tz;
                let cos_i = (-dot * inv_d).clamp(-one, one);
                let c = sub_angle(sin_of(cos_i), cos_i, sin_b, cos_b).1;
                dead |= c.cmplt(Vec4::splat(-SLACK));
                c
            }
            None => one,
        };
        // Floors keep a node that can contribute choosable when rounding takes a cosine to 0.
        let floor = Vec4::splat(1e-3);
        let tiny = Vec4::splat(1e-12);
        let w = self.phi * cos_p.max(floor) * cos_r.max(floor) / d2.max(self.r2).max(tiny);
        let w = Vec4::select(dead, zero, w);
        Vec4::select(inside, self.phi / self.r2.max(tiny), w).to_array()
    }
}

/// Lane-wise square root (correctly rounded, so the same bits as the scalar one).
#[inline(always)]
pub(crate) fn sqrt(v: Vec4) -> Vec4 {
    #[cfg(target_arch = "x86_64")]
    {
        use std::arch::x86_64::_mm_sqrt_ps;
        // SAFETY: SSE2 (and so SSE's sqrtps) is part of the x86_64 baseline.
        Vec4::from(unsafe { _mm_sqrt_ps(v.into()) })
    }
    #[cfg(not(target_arch = "x86_64"))]
    {
        v.sqrt()
    }
}

#[inline(always)]
fn sin_of(cos: Vec4) -> Vec4 {
    sqrt((Vec4::ONE - cos * cos).max(Vec4::ZERO))
}

/// (sin, cos) of max(0, a − b) for angles a, b in [0, π] given by their sines and cosines.
#[inline(always)]
fn sub_angle(sin_a: Vec4, cos_a: Vec4, sin_b: Vec4, cos_b: Vec4) -> (Vec4, Vec4) {
    let none = cos_a.cmpge(cos_b);
    (
        Vec4::select(none, Vec4::ZERO, sin_a * cos_b - cos_a * sin_b),
        Vec4::select(
            none,
            Vec4::ONE,
            (cos_a * cos_b + sin_a * sin_b).min(Vec4::ONE),
        ),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    fn point(at: Vec3A, phi: f32) -> LightBounds {
        LightBounds {
            lo: at,
            hi: at,
            axis: Vec3A::Z,
            cos_o: -1.0,
            cos_e: 0.0,
            phi,
        }
    }

    /// A 1 m square at height 3 emitting downwards (one-sided, Lambertian).
    fn ceiling_square() -> LightBounds {
        LightBounds {
            lo: Vec3A::new(-0.5, 3.0, -0.5),
            hi: Vec3A::new(0.5, 3.0, 0.5),
            axis: -Vec3A::Y,
            cos_o: 1.0,
            cos_e: 0.0,
            phi: 4.0,
        }
    }

    #[test]
    fn a_point_light_counts_its_intensity_over_the_squared_distance_and_nothing_behind() {
        let b = Bounds4::pack(&[point(Vec3A::new(0.0, 2.0, 0.0), 2.0)]);
        let x = Vec3A::ZERO;
        assert_eq!(b.importance(x, Some(Vec3A::Y))[0], 0.5);
        assert_eq!(b.importance(x, None)[0], 0.5);
        // Seen edge-on it keeps the floor's cosine, and below the tangent plane it is out.
        assert_eq!(b.importance(x, Some(Vec3A::X))[0], 0.5e-3);
        assert_eq!(b.importance(x, Some(-Vec3A::Y))[0], 0.0);
        // The empty lanes have no power, wherever x is.
        for x in [
            x,
            Vec3A::ZERO,
            Vec3A::new(1e-20, 0.0, 0.0),
            Vec3A::splat(-7.0),
        ] {
            assert_eq!(&b.importance(x, Some(Vec3A::Y))[1..], &[0.0; 3]);
            assert_eq!(&b.importance(x, None)[1..], &[0.0; 3]);
        }
    }

    #[test]
    fn a_one_sided_emitter_reaches_only_its_front_and_lanes_do_not_mix() {
        let square = ceiling_square();
        let lamp = point(Vec3A::new(4.0, 1.0, 0.0), 1.0);
        let both = Bounds4::pack(&[lamp, square, lamp, square]);
        let below = Vec3A::new(0.2, 0.0, 0.1);
        let above = Vec3A::new(0.2, 5.0, 0.1);
        for (x, n) in [(below, Some(Vec3A::Y)), (above, None), (below, None)] {
            let w = both.importance(x, n);
            // Each lane is what that node gives alone.
            assert_eq!(w[0], Bounds4::pack(&[lamp]).importance(x, n)[0]);
            assert_eq!(w[1], Bounds4::pack(&[square]).importance(x, n)[0]);
            assert_eq!((w[0], w[1]), (w[2], w[3]));
        }
        assert!(both.importance(below, Some(Vec3A::Y))[1] > 0.0);
        // Above the square: behind its emitting side.
        assert_eq!(both.importance(above, None)[1], 0.0);
        // Just below its plane, off to the side, emission at a grazing angle still counts.
        assert!(both.importance(Vec3A::new(3.0, 2.9, 0.0), None)[1] > 0.0);
    }
}
