//! A software prefetch: a hint that a value will be read soon, given where its address is
//! known well before the read (an environment map's texel once its cell is drawn, a
//! triangle's record once it is the closest hit so far), so that a cache miss overlaps the
//! work in between instead of stalling the read. It changes no value.

/// Hints the processor to load `v[k]`'s cache line into all cache levels; nothing when `k` is
/// out of bounds, or off x86-64.
#[inline(always)]
pub(crate) fn prefetch<T>(v: &[T], k: usize) {
    #[cfg(target_arch = "x86_64")]
    if let Some(x) = v.get(k) {
        // SAFETY: SSE is part of the x86_64 baseline; a prefetch reads nothing into the
        // program and cannot fault, and the address is that of a live element.
        unsafe {
            use std::arch::x86_64::{_MM_HINT_T0, _mm_prefetch};
            _mm_prefetch::<_MM_HINT_T0>(x as *const T as *const i8);
        }
    }
    #[cfg(not(target_arch = "x86_64"))]
    let _ = (v, k);
}
