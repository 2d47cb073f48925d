//! Asking for a cache line before it is needed, so that a load that would miss overlaps the
//! work in between: the walks' next nodes ([`crate::wide_walk`]). A prefetch is a hint: it
//! never faults and changes no result.
//!
//! Measured and not kept: a closest hit's slot record asked for when the hit becomes the
//! closest (its read after the walk fell from 7 % to 4.6 % of the 1M-triangle scene's query
//! samples, but the render call did not move: 1.010× over 9 alternating rounds), as an earlier
//! session found too (BENCHMARKS.md).

/// Asks for the cache line holding `p` (any address; nothing is read).
#[inline(always)]
pub(crate) fn prefetch<T>(p: *const T) {
    #[cfg(target_arch = "x86_64")]
    // SAFETY: a prefetch reads nothing and never faults, whatever the address.
    unsafe {
        use std::arch::x86_64::{_MM_HINT_T0, _mm_prefetch};
        _mm_prefetch::<_MM_HINT_T0>(p as *const i8);
    }
    #[cfg(not(target_arch = "x86_64"))]
    let _ = p;
}
