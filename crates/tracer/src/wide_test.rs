//! The box test of a [`Node8`]: which of its eight children a ray enters within (ε, tmax), and
//! from what distance. The x86-64 baseline runs it as two SSE2 halves of four children, AVX2
//! CPUs in one register; both do the same IEEE operations lane for lane (a subtraction, a
//! multiplication, max/min, an ordered `<=`; never FMA), so masks and distances agree bit for
//! bit and a farm that mixes CPUs writes the same frames.
//!
//! The near and far planes of each axis are chosen once per ray from the sign of 1/d
//! ([`Slab`]), as Embree and PBRT do, so a node costs two operations per plane and no min/max
//! to sort them. The far distance is scaled up by a few ulps (Ize, "Robust BVH Ray Traversal",
//! JCGT 2013) so that rounding never drops a box the ray grazes.
use crate::wide_bvh::Node8;
use obvhs::ray::Ray;

/// What the box test needs of a ray, made once per walk.
#[derive(Clone, Copy, Debug)]
pub struct Slab {
    origin: [f32; 3],
    /// 1/d as obvhs makes it (finite, with the sign of d, −0 counting as negative).
    inv: [f32; 3],
    /// Per axis: the plane row (below 6) the ray enters by (min where 1/d ≥ 0, max otherwise)
    /// and the one it leaves by. `far` is `near ^ 1`, kept rather than derived at each node:
    /// deriving it cost 0.8 % more instructions per closest-hit ray.
    near: [u32; 3],
    far: [u32; 3],
}

/// The least entry distance of a child (obvhs's node `EPSILON`, which the walk has kept).
pub(crate) const NODE_EPSILON: f32 = 0.0001;

/// 1 + 2γ₃ rounded up: the far distance's allowance for the rounding of (plane − o)·(1/d).
pub(crate) const FAR_SCALE: f32 = 1.0 + 4.0 * f32::EPSILON;

impl Slab {
    #[inline(always)]
    pub fn new(ray: &Ray) -> Slab {
        let inv = ray.inv_direction.to_array();
        // The sign bit is 1/d < 0: obvhs's 1/d is never ±0.
        let near = [0, 1, 2].map(|a| 2 * a as u32 + (inv[a].to_bits() >> 31));
        Slab {
            origin: ray.origin.to_array(),
            inv,
            near,
            far: near.map(|n| n ^ 1),
        }
    }
}

/// Bit c set where the ray enters child c within (ε, tmax), and the entry distances (lane c:
/// child c's; meaningful where its bit is set).
#[cfg(target_arch = "x86_64")]
#[inline(always)]
pub fn node8_sse2(node: &Node8, s: &Slab, tmax: f32) -> (u32, [f32; 8]) {
    use std::arch::x86_64::*;
    let mut near_out = [0.0f32; 8];
    let mut mask = 0;
    // SAFETY: SSE2 is part of the x86_64 baseline; the rows a `Slab` names are below 6; each
    // load reads 4 of a row's 8 floats (`Node8` is 64-byte aligned, each row 32 bytes, so the
    // loads are aligned).
    unsafe {
        for h in 0..2 {
            let t = |row: u32, a: usize| {
                // `row` is below 6 (`Slab::new`).
                let q = _mm_load_ps(node.planes.get_unchecked(row as usize).as_ptr().add(4 * h));
                _mm_mul_ps(
                    _mm_sub_ps(q, _mm_set1_ps(s.origin[a])),
                    _mm_set1_ps(s.inv[a]),
                )
            };
            let near = _mm_max_ps(
                _mm_max_ps(t(s.near[0], 0), t(s.near[1], 1)),
                _mm_max_ps(t(s.near[2], 2), _mm_set1_ps(NODE_EPSILON)),
            );
            let far = _mm_min_ps(t(s.far[0], 0), _mm_min_ps(t(s.far[1], 1), t(s.far[2], 2)));
            let far = _mm_min_ps(_mm_mul_ps(far, _mm_set1_ps(FAR_SCALE)), _mm_set1_ps(tmax));
            mask |= (_mm_movemask_ps(_mm_cmple_ps(near, far)) as u32) << (4 * h);
            _mm_storeu_ps(near_out.as_mut_ptr().add(4 * h), near);
        }
    }
    (mask, near_out)
}

/// [`node8_sse2`] with all eight children in one AVX2 register: the same mask and distances.
///
/// # Safety
/// The CPU must have AVX2.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
#[inline]
pub unsafe fn node8_avx2(node: &Node8, s: &Slab, tmax: f32) -> (u32, [f32; 8]) {
    use std::arch::x86_64::*;
    // SAFETY: the rows a `Slab` names are below 6; each row is 8 floats, 32-byte aligned
    // (`Node8` is 64-byte aligned).
    let row = |r: u32| unsafe { _mm256_load_ps(node.planes.get_unchecked(r as usize).as_ptr()) };
    let (o, inv) = (s.origin, s.inv);
    let (ox, oy, oz) = (
        _mm256_set1_ps(o[0]),
        _mm256_set1_ps(o[1]),
        _mm256_set1_ps(o[2]),
    );
    let (ix, iy, iz) = (
        _mm256_set1_ps(inv[0]),
        _mm256_set1_ps(inv[1]),
        _mm256_set1_ps(inv[2]),
    );
    let nx = _mm256_mul_ps(_mm256_sub_ps(row(s.near[0]), ox), ix);
    let ny = _mm256_mul_ps(_mm256_sub_ps(row(s.near[1]), oy), iy);
    let nz = _mm256_mul_ps(_mm256_sub_ps(row(s.near[2]), oz), iz);
    let fx = _mm256_mul_ps(_mm256_sub_ps(row(s.far[0]), ox), ix);
    let fy = _mm256_mul_ps(_mm256_sub_ps(row(s.far[1]), oy), iy);
    let fz = _mm256_mul_ps(_mm256_sub_ps(row(s.far[2]), oz), iz);
    let near = _mm256_max_ps(
        _mm256_max_ps(nx, ny),
        _mm256_max_ps(nz, _mm256_set1_ps(NODE_EPSILON)),
    );
    let far = _mm256_min_ps(fx, _mm256_min_ps(fy, fz));
    let far = _mm256_min_ps(
        _mm256_mul_ps(far, _mm256_set1_ps(FAR_SCALE)),
        _mm256_set1_ps(tmax),
    );
    // SSE2's `cmpleps` is the ordered, signalling `<=`.
    let mask = _mm256_movemask_ps(_mm256_cmp_ps::<_CMP_LE_OS>(near, far)) as u32;
    // SAFETY: a 256-bit vector and an array of 8 floats are the same size.
    (mask, unsafe {
        std::mem::transmute::<__m256, [f32; 8]>(near)
    })
}

/// The same test one child at a time, for targets without SSE2.
#[cfg(not(target_arch = "x86_64"))]
#[inline(always)]
pub fn node8_sse2(node: &Node8, s: &Slab, tmax: f32) -> (u32, [f32; 8]) {
    let mut near_out = [0.0f32; 8];
    let mut mask = 0;
    for c in 0..8 {
        let t = |row: u32, a: usize| (node.planes[row as usize][c] - s.origin[a]) * s.inv[a];
        let near = t(s.near[0], 0)
            .max(t(s.near[1], 1))
            .max(t(s.near[2], 2).max(NODE_EPSILON));
        let far = t(s.far[0], 0).min(t(s.far[1], 1).min(t(s.far[2], 2)));
        let far = (far * FAR_SCALE).min(tmax);
        mask |= ((near <= far) as u32) << c;
        near_out[c] = near;
    }
    (mask, near_out)
}
