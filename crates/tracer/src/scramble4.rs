//! The last step of a low-discrepancy chunk ([`crate::sampler`]): the four Sobol coordinates
//! of the shuffled index, Owen-scrambled each with its own seed and turned into floats in
//! [0, 1), four lanes at once.
//!
//! Per lane this is `unit(laine_karras(x, seed).reverse_bits())` with `unit(v) = (v >> 8) as
//! f32 · 2⁻²⁴`, bit for bit: integer arithmetic modulo 2³² has one answer, and a 24-bit
//! integer converts to a float exactly. On x86-64 it runs in SSE2 (the baseline), which has no
//! 32-bit lane multiply: the hash keeps lanes 0, 2 and lanes 1, 3 in the low halves of two
//! vectors' 64-bit lanes, where `pmuludq` multiplies them (the high halves carry garbage that
//! no low half ever reads), and the bit reversal works on bytes. The scalar form is the
//! reference the tests compare against, and what other targets run.
use crate::sampler::{REV_SOBOL_BYTES, laine_karras};

/// The Laine–Karras multipliers, in order.
const LK_MUL: [u32; 4] = [0x6c50_b47c, 0xb82f_1e52, 0xc7af_e638, 0x8d22_f6e6];

/// A 32-bit value's top 24 bits as a float in [0, 1), exactly.
#[inline(always)]
pub fn unit(v: u32) -> f32 {
    (v >> 8) as f32 * (1.0 / 16_777_216.0)
}

/// The four Sobol coordinates of the index whose bit reversal is `rev_index` (the shuffled
/// index, in the reversed domain), scrambled with `seeds` and as floats.
#[cfg(target_arch = "x86_64")]
#[inline]
pub fn scramble4(rev_index: u32, seeds: &[u32; 4]) -> [f32; 4] {
    use std::arch::x86_64::*;
    let b = rev_index.to_le_bytes();
    // SAFETY: SSE2 is part of the x86_64 baseline; every load reads one [u32; 4] (16 bytes),
    // unaligned loads, and the store writes one [f32; 4].
    unsafe {
        let row = |k: usize| {
            _mm_loadu_si128(REV_SOBOL_BYTES[k][b[k] as usize].as_ptr() as *const __m128i)
        };
        // Bit-reversed Sobol coordinates (`rev_sobol4`), plus the seeds.
        let x = _mm_xor_si128(_mm_xor_si128(row(0), row(1)), _mm_xor_si128(row(2), row(3)));
        let x = _mm_add_epi32(x, _mm_loadu_si128(seeds.as_ptr() as *const __m128i));
        // Lanes 0, 2 (`e`) and 1, 3 (`o`) in the low halves of the 64-bit lanes.
        let (mut e, mut o) = (x, _mm_srli_epi64::<32>(x));
        let m = LK_MUL.map(|c| _mm_set1_epi32(c as i32));
        // `x ^= x · c`, four times. In assembly because written with `_mm_mul_epu32`, LLVM drops
        // the intrinsic's masking of the high halves (no bit of the result it keeps depends on
        // them) and then, unable to prove them zero, emulates a full 64-bit multiply: two
        // `pmuludq` and three shifts and adds instead of one `pmuludq`.
        std::arch::asm!(
            "movdqa {t}, {e}", "pmuludq {t}, {m0}", "pxor {e}, {t}",
            "movdqa {t}, {o}", "pmuludq {t}, {m0}", "pxor {o}, {t}",
            "movdqa {t}, {e}", "pmuludq {t}, {m1}", "pxor {e}, {t}",
            "movdqa {t}, {o}", "pmuludq {t}, {m1}", "pxor {o}, {t}",
            "movdqa {t}, {e}", "pmuludq {t}, {m2}", "pxor {e}, {t}",
            "movdqa {t}, {o}", "pmuludq {t}, {m2}", "pxor {o}, {t}",
            "movdqa {t}, {e}", "pmuludq {t}, {m3}", "pxor {e}, {t}",
            "movdqa {t}, {o}", "pmuludq {t}, {m3}", "pxor {o}, {t}",
            e = inout(xmm_reg) e,
            o = inout(xmm_reg) o,
            t = out(xmm_reg) _,
            m0 = in(xmm_reg) m[0],
            m1 = in(xmm_reg) m[1],
            m2 = in(xmm_reg) m[2],
            m3 = in(xmm_reg) m[3],
            options(pure, nomem, nostack, preserves_flags),
        );
        let low = _mm_set_epi32(0, -1, 0, -1);
        let h = _mm_or_si128(_mm_and_si128(e, low), _mm_slli_epi64::<32>(o));
        // reverse_bits(h) >> 8 has bytes (low first) r(h2), r(h1), r(h0), 0, r the reversal
        // of a byte's bits: put the bytes there (swap the 16-bit halves, keep h1), then
        // reverse the bits of every byte.
        let swapped = _mm_shufflehi_epi16::<0xb1>(_mm_shufflelo_epi16::<0xb1>(h));
        let mut v = _mm_or_si128(
            _mm_and_si128(swapped, _mm_set1_epi32(0x00ff_00ff)),
            _mm_and_si128(h, _mm_set1_epi32(0x0000_ff00)),
        );
        /// Swaps the bit groups of `S` bits that `mask` and `mask << S` select.
        #[inline(always)]
        unsafe fn swap<const S: i32>(v: __m128i, mask: i32) -> __m128i {
            // SAFETY: SSE2 is part of the x86_64 baseline.
            unsafe {
                let m = _mm_set1_epi32(mask);
                let hi = _mm_and_si128(_mm_srli_epi32::<S>(v), m);
                _mm_or_si128(hi, _mm_slli_epi32::<S>(_mm_and_si128(v, m)))
            }
        }
        v = swap::<4>(v, 0x0f0f_0f0f);
        v = swap::<2>(v, 0x3333_3333);
        v = swap::<1>(v, 0x5555_5555);
        let f = _mm_mul_ps(_mm_cvtepi32_ps(v), _mm_set1_ps(1.0 / 16_777_216.0));
        let mut out = [0f32; 4];
        _mm_storeu_ps(out.as_mut_ptr(), f);
        out
    }
}

#[cfg(not(target_arch = "x86_64"))]
#[inline]
pub fn scramble4(rev_index: u32, seeds: &[u32; 4]) -> [f32; 4] {
    scramble4_scalar(rev_index, seeds)
}

/// [`scramble4`] one lane at a time.
#[cfg_attr(all(target_arch = "x86_64", not(test)), allow(dead_code))]
#[inline]
pub fn scramble4_scalar(rev_index: u32, seeds: &[u32; 4]) -> [f32; 4] {
    let b = rev_index.to_le_bytes();
    std::array::from_fn(|d| {
        let x = (0..4).fold(0, |x, k| x ^ REV_SOBOL_BYTES[k][b[k] as usize][d]);
        unit(laine_karras(x, seeds[d]).reverse_bits())
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sampler::mix64;

    #[test]
    fn lanes_equal_the_scalar_scramble_bit_for_bit() {
        let mut seen = [false; 4];
        for k in 0..200_000u64 {
            let r = mix64(k);
            // Extreme indices and seeds as well as random ones.
            let idx = match k % 5 {
                0 => (k as u32).wrapping_neg(),
                1 => k as u32,
                _ => r as u32,
            };
            let h = mix64(r);
            let seeds = [
                h as u32,
                (h >> 32) as u32,
                (r >> 32) as u32,
                (k as u32) << 7,
            ];
            let a = scramble4(idx, &seeds).map(f32::to_bits);
            let b = scramble4_scalar(idx, &seeds).map(f32::to_bits);
            assert_eq!(a, b, "index {idx:#x} seeds {seeds:x?}");
            for (s, v) in seen.iter_mut().zip(b) {
                // Every lane reaches both halves of [0, 1).
                *s |= f32::from_bits(v) >= 0.5;
            }
        }
        assert_eq!(seen, [true; 4]);
    }

    #[test]
    fn unit_is_exact_and_below_one() {
        assert_eq!(unit(0), 0.0);
        assert_eq!(unit(u32::MAX), 1.0 - 1.0 / 16_777_216.0);
        assert_eq!(unit(0x8000_0000), 0.5);
        assert_eq!(unit(0x0000_01ff), 1.0 / 16_777_216.0);
    }
}
