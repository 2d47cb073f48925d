//! Which node test the walks run: the x86-64 baseline's SSE2 one (two halves of four
//! children), or, on CPUs that have AVX2, the same test on all eight children of a
//! [`crate::wide_bvh::Node8`] in one 256-bit register ([`crate::wide_test`]). Both give the
//! same masks and entry distances bit for bit (the same IEEE operations in the same order, one
//! lane per child, and never FMA), so the walks visit the same nodes in the same order and a
//! farm that mixes old and new nodes still writes the same frames; `tests/cpu_features.rs`
//! renders with each and compares the files.
//!
//! The ray queries that take the wide test are also compiled with BMI1, BMI2, LZCNT and POPCNT
//! (integer bit operations every AVX2 CPU has: the walk's bit scans and masks in one
//! instruction each), so the CPU must report those too.
//!
//! The choice is made once per process: AVX2 when the CPU reports it, unless the environment
//! sets `EYEADAPT_SIMD=baseline` (for that comparison, and to rule the wide path out when
//! chasing a problem).
use crate::wide_bvh::Node8;
use crate::wide_test::Slab;
use std::sync::OnceLock;

/// The node test of one instruction set.
pub trait NodeTest: Copy {
    /// Whether the walks prefetch the inner children a node test enters ([`Prefetching`]).
    const PREFETCH: bool = false;

    /// [`crate::wide_test`]'s box test of a [`Node8`]: the children entered within (ε, tmax)
    /// and their entry distances.
    fn node8(self, node: &Node8, slab: &Slab, tmax: f32) -> (u32, [f32; 8]);
}

/// The x86-64 baseline's node tests (two SSE2 halves of four children).
#[derive(Clone, Copy, Debug)]
pub struct Baseline;

impl NodeTest for Baseline {
    #[inline(always)]
    fn node8(self, node: &Node8, slab: &Slab, tmax: f32) -> (u32, [f32; 8]) {
        crate::wide_test::node8_sse2(node, slab, tmax)
    }
}

/// `T`'s node test, with the walks prefetching the inner children it enters before the node's
/// leaves are tested ([`crate::wide_walk`]), for structures mostly outside the core's L2
/// ([`crate::wide_bvh::WideBvh::prefetch`]). A type of its own, so that a walk of a small
/// structure carries no trace of it (a per-step check of a flag cost three rooms 1.3–2.2 %).
#[derive(Clone, Copy, Debug)]
pub struct Prefetching<T>(pub T);

impl<T: NodeTest> NodeTest for Prefetching<T> {
    const PREFETCH: bool = true;

    #[inline(always)]
    fn node8(self, node: &Node8, slab: &Slab, tmax: f32) -> (u32, [f32; 8]) {
        self.0.node8(node, slab, tmax)
    }
}

/// The AVX2 node tests. A value exists only where the CPU has AVX2 ([`wide`]): holding one is
/// the proof that calling them is sound.
#[derive(Clone, Copy, Debug)]
pub struct Avx2(());

#[cfg(target_arch = "x86_64")]
impl NodeTest for Avx2 {
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
