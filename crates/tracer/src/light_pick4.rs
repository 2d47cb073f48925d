//! The area units of the spatial light choice ([`crate::light_pick`]), four side by side, and
//! their importances at a shading point computed together: one 4-lane vector per quantity
//! (glam's `Vec4`, SSE2 on x86-64).
//!
//! Every lane is bit for bit the one-unit importance of `light_pick` (the light choice and so
//! the renders must not move): the same IEEE operations in the same order — dot products as
//! glam's `(x·x′ + y·y′) + z·z′`, divisions where it divides, no fused multiply-add, no
//! reciprocal instead of a division — and its branches as lane selects. `min` and `max` keep
//! the varying value first, so a NaN there gives the constant as `f32::min`/`max` do. The one
//! thing precomputed, max(radius², 1e-12), is the same value either way: the maximum of values
//! none of which is NaN or −0.
use crate::light_bounds4::sqrt;
use glam::{BVec4A, Vec3A, Vec4};

/// What the importance needs of one area unit (a quad light or an emissive triangle).
#[derive(Clone, Copy, Debug)]
pub struct AreaUnit {
    pub centre: Vec3A,
    /// Bounding-sphere radius around `centre`.
    pub radius: f32,
    /// Emitting side.
    pub normal: Vec3A,
    /// The vertices (a triangle repeats its last one).
    pub corners: [Vec3A; 4],
    /// Area × luminance of the emitted radiance.
    pub power: f32,
}

/// Four units, one per lane, coordinates split into x, y, z vectors. Lanes without a unit
/// have a zero normal, so they are behind their own plane everywhere and weigh 0.
#[derive(Clone, Copy, Debug)]
struct Lanes {
    centre: [Vec4; 3],
    normal: [Vec4; 3],
    corners: [[Vec4; 3]; 4],
    radius: Vec4,
    /// max(radius², 1e-12): the floor of the squared distance.
    floor_d2: Vec4,
    power: Vec4,
}

/// The area units of a spatial light choice, four to a [`Lanes`].
#[derive(Clone, Debug, Default)]
pub struct AreaUnits4 {
    lanes: Vec<Lanes>,
    len: usize,
}

impl AreaUnits4 {
    pub fn pack(units: &[AreaUnit]) -> AreaUnits4 {
        let lanes = units
            .chunks(4)
            .map(|c| {
                let lane = |f: &dyn Fn(&AreaUnit) -> f32| {
                    Vec4::from_array(std::array::from_fn(|i| c.get(i).map_or(0.0, f)))
                };
                let xyz = |f: &dyn Fn(&AreaUnit) -> Vec3A| {
                    [lane(&|u| f(u).x), lane(&|u| f(u).y), lane(&|u| f(u).z)]
                };
                Lanes {
                    centre: xyz(&|u| u.centre),
                    normal: xyz(&|u| u.normal),
                    corners: std::array::from_fn(|k| xyz(&|u| u.corners[k])),
                    radius: lane(&|u| u.radius),
                    floor_d2: lane(&|u| (u.radius * u.radius).max(1e-12)),
                    power: lane(&|u| u.power),
                }
            })
            .collect();
        AreaUnits4 {
            lanes,
            len: units.len(),
        }
    }

    /// How many units there are.
    pub fn len(&self) -> usize {
        self.len
    }

    /// The units' importances at `x` (normal `n`) into `w`, four at a time from its start:
    /// `w` must have room for the units rounded up to a multiple of four, and the entries
    /// after the last unit are left with unspecified values for the caller to overwrite.
    #[inline]
    pub fn importances(&self, x: Vec3A, n: Option<Vec3A>, w: &mut [f32]) {
        for (out, l) in w.chunks_exact_mut(4).zip(&self.lanes) {
            out.copy_from_slice(&l.importance(x, n).to_array());
        }
    }
}

/// cos(max(0, θ − β)) lane by lane, as `light_pick`'s `widened_cos`.
#[inline(always)]
fn widened_cos(cos_t: Vec4, sin_b: Vec4, cos_b: Vec4) -> Vec4 {
    let sin_t = sqrt((Vec4::ONE - cos_t * cos_t).max(Vec4::ZERO));
    Vec4::select(cos_t.cmpge(cos_b), Vec4::ONE, cos_t * cos_b + sin_t * sin_b)
}

/// `a · b` with glam's order of additions.
#[inline(always)]
fn dot(a: [Vec4; 3], b: [Vec4; 3]) -> Vec4 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

#[inline(always)]
fn sub(a: [Vec4; 3], b: [Vec4; 3]) -> [Vec4; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

impl Lanes {
    /// The four importances (see `light_pick::importance`, its `Bounds::Area` arm).
    #[inline(always)]
    fn importance(&self, x: Vec3A, n: Option<Vec3A>) -> Vec4 {
        let zero = Vec4::ZERO;
        let xs = [Vec4::splat(x.x), Vec4::splat(x.y), Vec4::splat(x.z)];
        // Behind (or in) the emitting plane.
        let front = dot(sub(xs, self.centre), self.normal);
        let mut dead = front.cmple(zero);
        let to = sub(self.centre, xs);
        let d2 = dot(to, to);
        let d = sqrt(d2);
        let sin_b = (self.radius / d).min(Vec4::ONE);
        let cos_b = sqrt((Vec4::ONE - sin_b * sin_b).max(zero));
        let cos_e = widened_cos(front / d, sin_b, cos_b);
        let cos_r = match n {
            Some(n) => {
                let ns = [Vec4::splat(n.x), Vec4::splat(n.y), Vec4::splat(n.z)];
                // The whole unit below the receiver's tangent plane.
                let below = self.corners.iter().fold(BVec4A::splat(true), |all, c| {
                    all & dot(sub(*c, xs), ns).cmple(zero)
                });
                dead |= below;
                widened_cos(dot(ns, to) / d, sin_b, cos_b)
            }
            None => Vec4::ONE,
        };
        let floor = Vec4::splat(1e-3);
        let w = self.power * cos_e.max(floor) * cos_r.max(floor) / d2.max(self.floor_d2);
        Vec4::select(dead, zero, w)
    }
}
