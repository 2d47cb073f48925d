//! The geometry's ray queries: the closest hit, the shadow test, and the two walked together.
//! Each dispatches once per ray into a copy compiled for AVX2 where the CPU has it
//! ([`crate::isa`]), whose node tests give the baseline's masks bit for bit.
use super::{Geometry, Hit, Levels, RayScratch, object_ray};
use crate::accel::{Accel, SlotHit};
#[cfg(target_arch = "x86_64")]
use crate::isa::Avx2;
use crate::isa::{Baseline, NodeTest};
use glam::Vec3A;
use obvhs::ray::Ray;

impl Geometry {
    /// The closest hit along `dir` (unit) from `origin` within (0, tmax).
    #[inline]
    pub fn intersect_with(
        &self,
        scratch: &mut RayScratch,
        origin: Vec3A,
        dir: Vec3A,
        tmax: f32,
    ) -> Option<Hit> {
        let ray = Ray::new(origin, dir, 0.0, tmax);
        #[cfg(target_arch = "x86_64")]
        if let Some(avx2) = crate::isa::wide() {
            // SAFETY: an `Avx2` exists only where the CPU has AVX2.
            return unsafe { self.intersect_avx2(avx2, scratch, ray) };
        }
        self.intersect_in(Baseline, scratch, ray)
    }

    /// The closest hits of eight rays from `origin[l]` along `dir[l]` (unit), for the lanes of
    /// `active`: one packet walk ([`crate::packet`]) in a flat structure, eight walks in two
    /// levels. A packet's answers are its own (see `packet.rs`), the same on every machine.
    pub fn intersect8(
        &self,
        scratch: &mut RayScratch,
        origin: [Vec3A; 8],
        dir: [Vec3A; 8],
        active: u32,
    ) -> [Option<Hit>; 8] {
        match &self.levels {
            Levels::Flat(a) => a
                .intersect8_reusing(&mut scratch.packet, origin, dir, active)
                .map(|h| h.map(|h| flat_hit(a, h))),
            Levels::Two { .. } => std::array::from_fn(|l| match active >> l & 1 {
                0 => None,
                _ => self.intersect_with(scratch, origin[l], dir[l], f32::INFINITY),
            }),
        }
    }

    /// [`Geometry::intersect_in`] compiled for AVX2, so that its node tests inline.
    ///
    /// # Safety
    /// The CPU must have AVX2.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2,bmi1,bmi2,lzcnt,popcnt")]
    unsafe fn intersect_avx2(&self, avx2: Avx2, scratch: &mut RayScratch, ray: Ray) -> Option<Hit> {
        self.intersect_in(avx2, scratch, ray)
    }

    /// [`Geometry::intersect_with`] with the node test `test`.
    #[inline(always)]
    fn intersect_in(&self, test: impl NodeTest, scratch: &mut RayScratch, ray: Ray) -> Option<Hit> {
        match &self.levels {
            Levels::Flat(a) => a
                .closest_with(test, &ray, &mut scratch.bottom)
                .map(|h| flat_hit(a, h)),
            Levels::Two {
                top,
                top_instance,
                meshes,
            } => {
                let mut best = (0u32, 0u32);
                let bottom = &mut scratch.bottom;
                let h =
                    crate::wide_walk::closest_hit8(top, test, ray, &mut scratch.top, |k, r| {
                        let i = top_instance[k as usize];
                        let inst = &self.instances[i as usize];
                        let local = object_ray(inst, r);
                        match meshes[inst.mesh as usize].closest_with(test, &local, bottom) {
                            Some(h) => {
                                best = (i, h.slot);
                                h.t
                            }
                            None => f32::INFINITY,
                        }
                    })?;
                let (instance, slot) = best;
                let prim = meshes[self.instances[instance as usize].mesh as usize].info
                    [slot as usize]
                    .prim;
                Some(Hit {
                    t: h.t,
                    instance,
                    prim,
                    slot,
                })
            }
        }
    }

    /// True when nothing blocks the segment from `origin` along `dir` (unit) up to `tmax`.
    #[inline]
    pub fn unoccluded_with(
        &self,
        scratch: &mut RayScratch,
        origin: Vec3A,
        dir: Vec3A,
        tmax: f32,
    ) -> bool {
        let ray = Ray::new(origin, dir, 0.0, tmax);
        #[cfg(target_arch = "x86_64")]
        if let Some(avx2) = crate::isa::wide() {
            // SAFETY: an `Avx2` exists only where the CPU has AVX2.
            return unsafe { self.unoccluded_avx2(avx2, scratch, ray) };
        }
        self.unoccluded_in(Baseline, scratch, ray)
    }

    /// [`Geometry::unoccluded_in`] compiled for AVX2, so that its node tests inline.
    ///
    /// # Safety
    /// The CPU must have AVX2.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2,bmi1,bmi2,lzcnt,popcnt")]
    unsafe fn unoccluded_avx2(&self, avx2: Avx2, scratch: &mut RayScratch, ray: Ray) -> bool {
        self.unoccluded_in(avx2, scratch, ray)
    }

    /// [`Geometry::unoccluded_with`] with the node test `test`.
    #[inline(always)]
    fn unoccluded_in(&self, test: impl NodeTest, scratch: &mut RayScratch, ray: Ray) -> bool {
        match &self.levels {
            Levels::Flat(a) => a.unblocked_with(test, &ray, &mut scratch.bottom),
            Levels::Two {
                top,
                top_instance,
                meshes,
            } => {
                let bottom = &mut scratch.bottom;
                crate::wide_walk::unoccluded8(top, test, ray, &mut scratch.top, |k, r| {
                    let inst = &self.instances[top_instance[k as usize] as usize];
                    let local = object_ray(inst, r);
                    if meshes[inst.mesh as usize].unblocked_with(test, &local, bottom) {
                        f32::INFINITY
                    } else {
                        f32::NEG_INFINITY
                    }
                })
            }
        }
    }

    /// Calls `visit` with every surface hit along `dir` (unit) from `origin` within
    /// (0, tmax), in no particular order, until it returns true; returns whether one did
    /// (the see-through shadow rays of `shadow.rs`: any opaque hit ends them).
    pub fn each_hit(
        &self,
        scratch: &mut RayScratch,
        origin: Vec3A,
        dir: Vec3A,
        tmax: f32,
        visit: &mut dyn FnMut(Hit) -> bool,
    ) -> bool {
        let ray = Ray::new(origin, dir, 0.0, tmax);
        #[cfg(target_arch = "x86_64")]
        if let Some(avx2) = crate::isa::wide() {
            // SAFETY: an `Avx2` exists only where the CPU has AVX2.
            return unsafe { self.each_hit_avx2(avx2, scratch, ray, visit) };
        }
        self.each_hit_in(Baseline, scratch, ray, visit)
    }

    /// [`Geometry::each_hit_in`] compiled for AVX2.
    ///
    /// # Safety
    /// The CPU must have AVX2.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2,bmi1,bmi2,lzcnt,popcnt")]
    unsafe fn each_hit_avx2(
        &self,
        avx2: Avx2,
        scratch: &mut RayScratch,
        ray: Ray,
        visit: &mut dyn FnMut(Hit) -> bool,
    ) -> bool {
        self.each_hit_in(avx2, scratch, ray, visit)
    }

    #[inline(always)]
    fn each_hit_in(
        &self,
        test: impl NodeTest,
        scratch: &mut RayScratch,
        ray: Ray,
        visit: &mut dyn FnMut(Hit) -> bool,
    ) -> bool {
        match &self.levels {
            Levels::Flat(a) => a.each_hit_with(test, &ray, &mut scratch.bottom, &mut |h| {
                visit(flat_hit(a, h))
            }),
            Levels::Two {
                top,
                top_instance,
                meshes,
            } => {
                let bottom = &mut scratch.bottom;
                !crate::wide_walk::unoccluded8(top, test, ray, &mut scratch.top, |k, r| {
                    let instance = top_instance[k as usize];
                    let inst = &self.instances[instance as usize];
                    let mesh = &meshes[inst.mesh as usize];
                    let local = object_ray(inst, r);
                    let stopped = mesh.each_hit_with(test, &local, bottom, &mut |h| {
                        visit(Hit {
                            t: h.t,
                            instance,
                            prim: mesh.info[h.slot as usize].prim,
                            slot: h.slot,
                        })
                    });
                    if stopped {
                        f32::NEG_INFINITY
                    } else {
                        f32::INFINITY
                    }
                })
            }
        }
    }

    /// [`Geometry::intersect_with`] of `ray` (origin, direction, tmax) and
    /// [`Geometry::unoccluded_with`] of `shadow`, the two walked together where there is one
    /// level ([`crate::traverse_pair`]); the same answers as the two calls.
    pub fn intersect_and_unoccluded(
        &self,
        scratch: &mut RayScratch,
        ray: (Vec3A, Vec3A, f32),
        shadow: (Vec3A, Vec3A, f32),
    ) -> (Option<Hit>, bool) {
        let ray = Ray::new(ray.0, ray.1, 0.0, ray.2);
        let shadow = Ray::new(shadow.0, shadow.1, 0.0, shadow.2);
        #[cfg(target_arch = "x86_64")]
        if let Some(avx2) = crate::isa::wide() {
            // SAFETY: an `Avx2` exists only where the CPU has AVX2.
            return unsafe { self.intersect_and_unoccluded_avx2(avx2, scratch, ray, shadow) };
        }
        self.intersect_and_unoccluded_in(Baseline, scratch, ray, shadow)
    }

    /// [`Geometry::intersect_and_unoccluded_in`] compiled for AVX2.
    ///
    /// # Safety
    /// The CPU must have AVX2.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2,bmi1,bmi2,lzcnt,popcnt")]
    unsafe fn intersect_and_unoccluded_avx2(
        &self,
        avx2: Avx2,
        scratch: &mut RayScratch,
        ray: Ray,
        shadow: Ray,
    ) -> (Option<Hit>, bool) {
        self.intersect_and_unoccluded_in(avx2, scratch, ray, shadow)
    }

    #[inline(always)]
    fn intersect_and_unoccluded_in(
        &self,
        test: impl NodeTest,
        scratch: &mut RayScratch,
        ray: Ray,
        shadow: Ray,
    ) -> (Option<Hit>, bool) {
        let Levels::Flat(a) = &self.levels else {
            let hit = self.intersect_in(test, scratch, ray);
            return (hit, self.unoccluded_in(test, scratch, shadow));
        };
        let (h, free) = a.closest_and_unblocked_with(
            test,
            (&ray, &mut scratch.bottom),
            (&shadow, &mut scratch.shadow),
        );
        (h.map(|h| flat_hit(a, h)), free)
    }
}

/// The [`Hit`] of a one-level structure's slot hit.
#[inline(always)]
fn flat_hit(a: &Accel, h: SlotHit) -> Hit {
    let info = a.info[h.slot as usize];
    Hit {
        t: h.t,
        instance: info.instance,
        prim: info.prim,
        slot: h.slot,
    }
}
