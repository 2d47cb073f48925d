//! Which node tests the walks run: the x86-64 baseline's SSE2 ones, or, on CPUs that have
//! AVX2, the same tests on all eight children in one 256-bit register ([`crate::wide_test`]
//! for each mesh's [`crate::wide_bvh::Node8`]s, [`crate::traverse_avx2`] for the CWBVH over
//! the instances).
//! Both give the same hit masks bit for bit (the same IEEE operations in the same order, one
//! lane per child, and never FMA), so a farm that mixes old and new nodes still writes the same
//! frames; `tests/cpu_features.rs` renders with each and compares the files.
//!
//! The ray queries that take the wide test are also compiled with BMI1, BMI2, LZCNT and POPCNT
//! (integer bit operations every AVX2 CPU has: the walk's shifts, masks and bit scans in one
//! instruction each; matpreview −1.4 % instructions), so the CPU must report those too.
//!
//! The choice is made once per process: AVX2 when the CPU reports it, unless the environment
//! sets `EYEADAPT_SIMD=baseline` (for that comparison, and to rule the wide path out when
//! chasing a problem).
use crate::wide_bvh::Node8;
use crate::wide_test::Slab;
use obvhs::cwbvh::node::CwBvhNode;
use obvhs::ray::Ray;
use std::sync::OnceLock;

/// The node tests of one instruction set.
pub trait NodeTest: Copy {
    /// [`crate::traverse`]'s CWBVH node test: the same mask as obvhs's
    /// `CwBvhNode::intersect_ray`.
    fn meta(self, node: &CwBvhNode, ray: &Ray, oct_inv4: u32) -> u32;
    /// The number of set bits of `byte` (below 256): the walk's count of a node's inner
    /// children before the one it enters.
    fn ones8(self, byte: u32) -> u32;
    /// [`crate::wide_test`]'s box test of a [`Node8`]: the children entered within (ε, tmax)
    /// and their entry distances.
    fn node8(self, node: &Node8, slab: &Slab, tmax: f32) -> (u32, [f32; 8]);
}

/// The x86-64 baseline's node tests (two SSE2 halves of four children).
#[derive(Clone, Copy, Debug)]
pub struct Baseline;

impl NodeTest for Baseline {
    #[inline(always)]
    fn meta(self, node: &CwBvhNode, ray: &Ray, oct_inv4: u32) -> u32 {
        crate::traverse::node_hits(node, ray, oct_inv4)
    }
    #[inline(always)]
    fn ones8(self, byte: u32) -> u32 {
        crate::traverse::ONES[(byte & 0xff) as usize] as u32
    }
    #[inline(always)]
    fn node8(self, node: &Node8, slab: &Slab, tmax: f32) -> (u32, [f32; 8]) {
        crate::wide_test::node8_sse2(node, slab, tmax)
    }
}

/// The AVX2 node tests. A value exists only where the CPU has AVX2 ([`wide`]): holding one is
/// the proof that calling them is sound.
#[derive(Clone, Copy, Debug)]
pub struct Avx2(());

#[cfg(target_arch = "x86_64")]
impl NodeTest for Avx2 {
    #[inline(always)]
    fn meta(self, node: &CwBvhNode, ray: &Ray, oct_inv4: u32) -> u32 {
        // SAFETY: an `Avx2` is only made where the CPU has AVX2.
        unsafe { crate::traverse_avx2::node_hits(node, ray, oct_inv4) }
    }
    #[inline(always)]
    fn ones8(self, byte: u32) -> u32 {
        // One POPCNT where inlined into the ray queries compiled with it (geometry/query.rs,
        // accel_wide.rs); the portable count elsewhere. The same number either way.
        (byte & 0xff).count_ones()
    }
    #[inline(always)]
    fn node8(self, node: &Node8, slab: &Slab, tmax: f32) -> (u32, [f32; 8]) {
        // SAFETY: an `Avx2` is only made where the CPU has AVX2.
        unsafe { crate::wide_test::node8_avx2(node, slab, tmax) }
    }
}

/// The AVX2 node tests when this process uses them: the CPU has AVX2 and `EYEADAPT_SIMD`
/// ([`simd_setting`]) does not say `baseline` (a value it rejects counts as `auto` here; the
/// command line refuses it before it starts).
pub fn wide() -> Option<Avx2> {
    static WIDE: OnceLock<bool> = OnceLock::new();
    let on = *WIDE.get_or_init(|| simd_setting().unwrap_or(true) && has_avx2());
    on.then_some(Avx2(()))
}

/// What the environment's `EYEADAPT_SIMD` asks for: `Ok(true)` the AVX2 node tests where the
/// CPU has them (unset, empty or `auto`), `Ok(false)` the baseline's (`baseline`), and an error
/// naming the variable and its accepted values for anything else.
pub fn simd_setting() -> Result<bool, String> {
    match std::env::var_os("EYEADAPT_SIMD") {
        None => Ok(true),
        Some(v) => match v.to_str() {
            Some("" | "auto") => Ok(true),
            Some("baseline") => Ok(false),
            _ => Err(format!(
                "environment variable EYEADAPT_SIMD: {v:?} is not one of auto, baseline"
            )),
        },
    }
}

/// Whether the CPU has AVX2 and the bit-operation extensions the wide queries are compiled
/// with (an `Avx2` made from this alone is sound; [`wide`] also asks the environment).
pub fn has_avx2() -> bool {
    #[cfg(target_arch = "x86_64")]
    {
        std::arch::is_x86_feature_detected!("avx2")
            && std::arch::is_x86_feature_detected!("bmi1")
            && std::arch::is_x86_feature_detected!("bmi2")
            && std::arch::is_x86_feature_detected!("lzcnt")
            && std::arch::is_x86_feature_detected!("popcnt")
    }
    #[cfg(not(target_arch = "x86_64"))]
    {
        false
    }
}

/// An [`Avx2`] whenever the CPU has it, whatever the environment says (for tests that compare
/// the two node tests).
#[cfg(test)]
pub fn avx2() -> Option<Avx2> {
    has_avx2().then_some(Avx2(()))
}
