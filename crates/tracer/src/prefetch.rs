//! Asking for a cache line before it is needed, so that a load that would miss overlaps the
//! work in between: the walks' next nodes ([`crate::wide_walk`]) and a closest hit's slot
//! record ([`crate::accel`]). A prefetch is a hint: it never faults and changes no result.

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
