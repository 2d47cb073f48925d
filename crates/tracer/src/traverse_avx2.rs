//! [`crate::traverse`]'s node tests with all eight children in one AVX2 register: the same
//! operations lane for lane (multiply then add, min/max in the same order, the same ordered
//! `<=`), so the masks are bit-identical to the SSE2 ones — `tests` checks this on real nodes
//! and random rays — in about half the instructions. Callers hold an [`crate::isa::Avx2`], made
//! only where the CPU has AVX2, and call these from code compiled for AVX2 (so they inline).
#![cfg(target_arch = "x86_64")]
use crate::traverse::{NODE_EPSILON, box_of, mask_from_lanes, plane_fields};
use glam::Vec3A;
use obvhs::cwbvh::node::CwBvhNode;
use obvhs::ray::Ray;
use std::arch::x86_64::*;

/// [`crate::traverse::node_hits`] (the mask from obvhs's child metadata), eight lanes at once.
///
/// # Safety
/// The CPU must have AVX2.
#[target_feature(enable = "avx2")]
#[inline]
pub unsafe fn node_hits(node: &CwBvhNode, ray: &Ray, oct_inv4: u32) -> u32 {
    let lanes = entered(box_of(node), ray, byte_planes(node));
    mask_from_lanes(node, oct_inv4, _mm256_movemask_ps(lanes) as u32)
}

/// Field `f` of the node's quantised planes for all eight children, widened and converted.
#[target_feature(enable = "avx2")]
#[inline]
fn byte_planes(node: &CwBvhNode) -> impl Fn(usize) -> __m256 {
    let fields = plane_fields(node);
    // SAFETY: the load reads the 8 bytes of a [u8; 8] field; the caller has AVX2.
    move |f| unsafe {
        let v = _mm_loadl_epi64(fields[f].as_ptr() as *const __m128i);
        _mm256_cvtepi32_ps(_mm256_cvtepu8_epi32(v))
    }
}

/// [`crate::traverse`]'s `entered`, all eight children in one register: all ones in the lanes
/// of the children `ray` enters within (ε, tmax).
#[target_feature(enable = "avx2")]
#[inline]
fn entered(
    (extent, origin): (Vec3A, Vec3A),
    ray: &Ray,
    planes: impl Fn(usize) -> __m256,
) -> __m256 {
    let adj_dir = extent * ray.inv_direction;
    let adj_org = (origin - ray.origin) * ray.inv_direction;
    let axis = |a: usize, d: f32, o: f32| {
        let (lo, hi) = (planes(2 * a), planes(2 * a + 1));
        let (d, o) = (_mm256_set1_ps(d), _mm256_set1_ps(o));
        let t = |q: __m256| _mm256_add_ps(_mm256_mul_ps(q, d), o);
        let (a, b) = (t(lo), t(hi));
        (_mm256_min_ps(a, b), _mm256_max_ps(a, b))
    };
    let (nx, fx) = axis(0, adj_dir.x, adj_org.x);
    let (ny, fy) = axis(1, adj_dir.y, adj_org.y);
    let (nz, fz) = axis(2, adj_dir.z, adj_org.z);
    let near = _mm256_max_ps(nx, _mm256_max_ps(ny, nz));
    let far = _mm256_min_ps(fx, _mm256_min_ps(fy, fz));
    let near = _mm256_max_ps(near, _mm256_set1_ps(NODE_EPSILON));
    let far = _mm256_min_ps(far, _mm256_set1_ps(ray.tmax));
    // SSE2's `cmpleps` is the ordered, signalling `<=`.
    _mm256_cmp_ps::<_CMP_LE_OS>(near, far)
}

#[cfg(test)]
#[path = "traverse_avx2_tests.rs"]
mod tests;
