//! An [`Accel`]'s ray queries as the renderer runs them, for callers that hold a structure of
//! their own (`eyeadapt bench --bvh-triangles`): the AVX2 node test where the CPU has it
//! ([`crate::isa::wide`]) and the caller's traversal state reused from ray to ray, as
//! [`crate::Geometry`]'s queries do. The answers are those of [`Accel::intersect`] and
//! [`Accel::unoccluded`], bit for bit.
use crate::accel::{Accel, SlotHit};
#[cfg(target_arch = "x86_64")]
use crate::isa::Avx2;
use crate::isa::Baseline;
use crate::packet::PacketStack;
use crate::wide_walk::WalkStack;
use glam::Vec3A;
use obvhs::ray::Ray;

impl Accel {
    /// The closest hits of eight rays from `origin[l]` along `dir[l]` (unit) within (0, ∞), for
    /// the lanes of `active`, walked as one packet ([`crate::packet`]) with `stack` reused.
    pub fn intersect8_reusing(
        &self,
        stack: &mut PacketStack,
        origin: [Vec3A; 8],
        dir: [Vec3A; 8],
        active: u32,
    ) -> [Option<SlotHit>; 8] {
        let rays = std::array::from_fn(|l| Ray::new(origin[l], dir[l], 0.0, f32::INFINITY));
        self.closest8(&rays, active, stack)
    }

    /// [`Accel::intersect`] with `state` reused and the wide node test where there is one.
    pub fn intersect_reusing(
        &self,
        state: &mut WalkStack,
        origin: Vec3A,
        dir: Vec3A,
        tmax: f32,
    ) -> Option<SlotHit> {
        let ray = Ray::new(origin, dir, 0.0, tmax);
        #[cfg(target_arch = "x86_64")]
        if let Some(avx2) = crate::isa::wide() {
            // SAFETY: an `Avx2` exists only where the CPU has AVX2.
            return unsafe { self.closest_avx2(avx2, &ray, state) };
        }
        self.closest_with(Baseline, &ray, state)
    }

    /// [`Accel::unoccluded`] with `state` reused and the wide node test where there is one.
    pub fn unoccluded_reusing(
        &self,
        state: &mut WalkStack,
        origin: Vec3A,
        dir: Vec3A,
        tmax: f32,
    ) -> bool {
        let ray = Ray::new(origin, dir, 0.0, tmax);
        #[cfg(target_arch = "x86_64")]
        if let Some(avx2) = crate::isa::wide() {
            // SAFETY: an `Avx2` exists only where the CPU has AVX2.
            return unsafe { self.unblocked_avx2(avx2, &ray, state) };
        }
        self.unblocked_with(Baseline, &ray, state)
    }

    /// # Safety
    /// The CPU must have AVX2 (and what [`crate::isa::has_avx2`] checks with it).
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2,bmi1,bmi2,lzcnt,popcnt")]
    unsafe fn closest_avx2(&self, avx2: Avx2, ray: &Ray, state: &mut WalkStack) -> Option<SlotHit> {
        self.closest_with(avx2, ray, state)
    }

    /// # Safety
    /// As for [`Accel::closest_avx2`].
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2,bmi1,bmi2,lzcnt,popcnt")]
    unsafe fn unblocked_avx2(&self, avx2: Avx2, ray: &Ray, state: &mut WalkStack) -> bool {
        self.unblocked_with(avx2, ray, state)
    }
}
