//! Eight `f32` lanes, one per ray of a packet ([`crate::packet`]): the operations the packet
//! walk needs, in one AVX2 register where the CPU has it and in two SSE2 halves on the x86-64
//! baseline (elsewhere, one lane at a time). Every operation is the same IEEE operation lane for
//! lane (never FMA; `min` and `max` return the second operand unless the first is strictly
//! less or greater, as `minps`/`maxps` do), so the three give the same bits and a packet walk
//! gives the same answers on every machine of a farm.

/// Eight lanes of `f32`; comparisons give lane masks (all bits set where true).
pub trait F8: Copy {
    fn splat(x: f32) -> Self;
    fn load(a: &[f32; 8]) -> Self;
    fn store(self) -> [f32; 8];
    fn add(self, b: Self) -> Self;
    fn sub(self, b: Self) -> Self;
    fn mul(self, b: Self) -> Self;
    fn div(self, b: Self) -> Self;
    /// `self < b ? self : b`, lane by lane.
    fn min(self, b: Self) -> Self;
    /// `self > b ? self : b`, lane by lane.
    fn max(self, b: Self) -> Self;
    fn le(self, b: Self) -> Self;
    fn lt(self, b: Self) -> Self;
    fn ge(self, b: Self) -> Self;
    /// Unordered `!=` (true where either lane is NaN).
    fn ne(self, b: Self) -> Self;
    fn and(self, b: Self) -> Self;
    fn xor(self, b: Self) -> Self;
    /// `!self & b`.
    fn andnot(self, b: Self) -> Self;
    /// `b` where `mask` is set, else `self`.
    fn blend(self, b: Self, mask: Self) -> Self;
    /// Bit l: the sign bit of lane l.
    fn movemask(self) -> u32;
    /// The lanes whose bit is set in `bits`, as a mask.
    fn mask_of(bits: u32) -> Self;
}

#[cfg(target_arch = "x86_64")]
pub use x86::{Avx2F8, Sse2F8};

#[cfg(target_arch = "x86_64")]
mod x86 {
    use super::F8;
    use std::arch::x86_64::*;

    /// Eight lanes in one AVX2 register. Its operations may only run where the CPU has AVX2:
    /// the packet walk uses it only inside a function compiled for AVX2, reached through
    /// [`crate::isa::wide`].
    #[derive(Clone, Copy, Debug)]
    pub struct Avx2F8(__m256);

    macro_rules! avx {
        ($($name:ident => $op:ident),*) => {$(
            #[inline(always)]
            fn $name(self, b: Self) -> Self {
                // SAFETY: only reached on CPUs with AVX2 (the type's text).
                Avx2F8(unsafe { $op(self.0, b.0) })
            }
        )*};
    }

    macro_rules! avx_cmp {
        ($($name:ident => $pred:ident),*) => {$(
            #[inline(always)]
            fn $name(self, b: Self) -> Self {
                // SAFETY: only reached on CPUs with AVX2 (the type's text).
                Avx2F8(unsafe { _mm256_cmp_ps::<$pred>(self.0, b.0) })
            }
        )*};
    }

    impl F8 for Avx2F8 {
        #[inline(always)]
        fn splat(x: f32) -> Self {
            // SAFETY: as for every operation of the type.
            Avx2F8(unsafe { _mm256_set1_ps(x) })
        }
        #[inline(always)]
        fn load(a: &[f32; 8]) -> Self {
            // SAFETY: an unaligned load of eight floats from an array of eight.
            Avx2F8(unsafe { _mm256_loadu_ps(a.as_ptr()) })
        }
        #[inline(always)]
        fn store(self) -> [f32; 8] {
            let mut a = [0.0; 8];
            // SAFETY: an unaligned store of eight floats into an array of eight.
            unsafe { _mm256_storeu_ps(a.as_mut_ptr(), self.0) };
            a
        }
        avx!(add => _mm256_add_ps, sub => _mm256_sub_ps, mul => _mm256_mul_ps,
             div => _mm256_div_ps, min => _mm256_min_ps, max => _mm256_max_ps,
             and => _mm256_and_ps, xor => _mm256_xor_ps, andnot => _mm256_andnot_ps);
        // SSE2's `cmpleps` and `cmpltps` are the ordered, signalling `<=` and `<`, `cmpgeps`
        // is `cmpleps` with the operands swapped, `cmpneqps` the unordered `!=`.
        avx_cmp!(le => _CMP_LE_OS, lt => _CMP_LT_OS, ge => _CMP_GE_OS, ne => _CMP_NEQ_UQ);
        #[inline(always)]
        fn blend(self, b: Self, mask: Self) -> Self {
            // SAFETY: as above.
            Avx2F8(unsafe { _mm256_blendv_ps(self.0, b.0, mask.0) })
        }
        #[inline(always)]
        fn movemask(self) -> u32 {
            // SAFETY: as above.
            unsafe { _mm256_movemask_ps(self.0) as u32 }
        }
        #[inline(always)]
        fn mask_of(bits: u32) -> Self {
            // SAFETY: as above.
            unsafe {
                let lane = _mm256_setr_epi32(1, 2, 4, 8, 16, 32, 64, 128);
                let set = _mm256_and_si256(_mm256_set1_epi32(bits as i32), lane);
                Avx2F8(_mm256_castsi256_ps(_mm256_cmpeq_epi32(set, lane)))
            }
        }
    }

    /// Eight lanes in two SSE2 registers (lanes 0–3, 4–7): the x86-64 baseline's.
    #[derive(Clone, Copy, Debug)]
    pub struct Sse2F8(__m128, __m128);

    macro_rules! sse {
        ($($name:ident => $op:ident),*) => {$(
            #[inline(always)]
            fn $name(self, b: Self) -> Self {
                // SAFETY: SSE2 is part of the x86_64 baseline.
                unsafe { Sse2F8($op(self.0, b.0), $op(self.1, b.1)) }
            }
        )*};
    }

    impl F8 for Sse2F8 {
        #[inline(always)]
        fn splat(x: f32) -> Self {
            // SAFETY: SSE2 is part of the x86_64 baseline.
            unsafe { Sse2F8(_mm_set1_ps(x), _mm_set1_ps(x)) }
        }
        #[inline(always)]
        fn load(a: &[f32; 8]) -> Self {
            // SAFETY: two unaligned loads of four floats from an array of eight.
            unsafe { Sse2F8(_mm_loadu_ps(a.as_ptr()), _mm_loadu_ps(a.as_ptr().add(4))) }
        }
        #[inline(always)]
        fn store(self) -> [f32; 8] {
            let mut a = [0.0; 8];
            // SAFETY: two unaligned stores of four floats into an array of eight.
            unsafe {
                _mm_storeu_ps(a.as_mut_ptr(), self.0);
                _mm_storeu_ps(a.as_mut_ptr().add(4), self.1);
            }
            a
        }
        sse!(add => _mm_add_ps, sub => _mm_sub_ps, mul => _mm_mul_ps, div => _mm_div_ps,
             min => _mm_min_ps, max => _mm_max_ps, and => _mm_and_ps, xor => _mm_xor_ps,
             andnot => _mm_andnot_ps, le => _mm_cmple_ps, lt => _mm_cmplt_ps,
             ge => _mm_cmpge_ps, ne => _mm_cmpneq_ps);
        #[inline(always)]
        fn blend(self, b: Self, mask: Self) -> Self {
            // SAFETY: SSE2 is part of the x86_64 baseline (no `blendvps` there: and/or).
            unsafe {
                let pick = |a: __m128, b: __m128, m: __m128| {
                    _mm_or_ps(_mm_and_ps(m, b), _mm_andnot_ps(m, a))
                };
                Sse2F8(pick(self.0, b.0, mask.0), pick(self.1, b.1, mask.1))
            }
        }
        #[inline(always)]
        fn movemask(self) -> u32 {
            // SAFETY: SSE2 is part of the x86_64 baseline.
            unsafe { (_mm_movemask_ps(self.0) | _mm_movemask_ps(self.1) << 4) as u32 }
        }
        #[inline(always)]
        fn mask_of(bits: u32) -> Self {
            // SAFETY: SSE2 is part of the x86_64 baseline.
            unsafe {
                let half = |b: u32| {
                    let lane = _mm_setr_epi32(1, 2, 4, 8);
                    let set = _mm_and_si128(_mm_set1_epi32(b as i32), lane);
                    _mm_castsi128_ps(_mm_cmpeq_epi32(set, lane))
                };
                Sse2F8(half(bits & 0xf), half(bits >> 4 & 0xf))
            }
        }
    }
}

/// Eight lanes one at a time, for targets other than x86-64.
#[cfg(not(target_arch = "x86_64"))]
#[derive(Clone, Copy, Debug)]
pub struct ScalarF8([f32; 8]);

#[cfg(not(target_arch = "x86_64"))]
impl ScalarF8 {
    #[inline(always)]
    fn zip(self, b: Self, f: impl Fn(f32, f32) -> f32) -> Self {
        ScalarF8(std::array::from_fn(|l| f(self.0[l], b.0[l])))
    }
    #[inline(always)]
    fn cmp(self, b: Self, f: impl Fn(f32, f32) -> bool) -> Self {
        self.zip(b, |x, y| {
            if f(x, y) {
                f32::from_bits(u32::MAX)
            } else {
                0.0
            }
        })
    }
    #[inline(always)]
    fn bits(self, b: Self, f: impl Fn(u32, u32) -> u32) -> Self {
        self.zip(b, |x, y| f32::from_bits(f(x.to_bits(), y.to_bits())))
    }
}

#[cfg(not(target_arch = "x86_64"))]
impl F8 for ScalarF8 {
    fn splat(x: f32) -> Self {
        ScalarF8([x; 8])
    }
    fn load(a: &[f32; 8]) -> Self {
        ScalarF8(*a)
    }
    fn store(self) -> [f32; 8] {
        self.0
    }
    fn add(self, b: Self) -> Self {
        self.zip(b, |x, y| x + y)
    }
    fn sub(self, b: Self) -> Self {
        self.zip(b, |x, y| x - y)
    }
    fn mul(self, b: Self) -> Self {
        self.zip(b, |x, y| x * y)
    }
    fn div(self, b: Self) -> Self {
        self.zip(b, |x, y| x / y)
    }
    fn min(self, b: Self) -> Self {
        self.zip(b, |x, y| if x < y { x } else { y })
    }
    fn max(self, b: Self) -> Self {
        self.zip(b, |x, y| if x > y { x } else { y })
    }
    fn le(self, b: Self) -> Self {
        self.cmp(b, |x, y| x <= y)
    }
    fn lt(self, b: Self) -> Self {
        self.cmp(b, |x, y| x < y)
    }
    fn ge(self, b: Self) -> Self {
        self.cmp(b, |x, y| x >= y)
    }
    fn ne(self, b: Self) -> Self {
        self.cmp(b, |x, y| x != y)
    }
    fn and(self, b: Self) -> Self {
        self.bits(b, |x, y| x & y)
    }
    fn xor(self, b: Self) -> Self {
        self.bits(b, |x, y| x ^ y)
    }
    fn andnot(self, b: Self) -> Self {
        self.bits(b, |x, y| !x & y)
    }
    fn blend(self, b: Self, mask: Self) -> Self {
        ScalarF8(std::array::from_fn(|l| {
            if mask.0[l].to_bits() >> 31 != 0 {
                b.0[l]
            } else {
                self.0[l]
            }
        }))
    }
    fn movemask(self) -> u32 {
        (0..8).fold(0, |m, l| m | (self.0[l].to_bits() >> 31) << l)
    }
    fn mask_of(bits: u32) -> Self {
        ScalarF8(std::array::from_fn(|l| {
            if bits >> l & 1 != 0 {
                f32::from_bits(u32::MAX)
            } else {
                0.0
            }
        }))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sampler::mix64;

    /// Values that exercise signs, zeros, infinities and equal lanes.
    fn value(k: u64) -> f32 {
        let r = mix64(k);
        match r % 8 {
            0 => 0.0,
            1 => -0.0,
            2 => f32::INFINITY,
            3 => f32::NEG_INFINITY,
            4 => 1.5,
            _ => (r >> 40) as f32 / 65536.0 - 128.0,
        }
    }

    /// Every operation of the AVX2 lanes gives the SSE2 lanes' bits (where the CPU has AVX2).
    #[cfg(target_arch = "x86_64")]
    #[test]
    fn avx2_and_sse2_lanes_agree_bit_for_bit() {
        // Whatever EYEADAPT_SIMD says: the comparison only needs the CPU to have AVX2.
        if crate::isa::avx2().is_none() {
            eprintln!("no AVX2 on this CPU: nothing to compare");
            return;
        }
        fn all<V: F8>(a: [f32; 8], b: [f32; 8], bits: u32) -> Vec<[u32; 8]> {
            let (x, y) = (V::load(&a), V::load(&b));
            let m = V::mask_of(bits);
            [
                x.add(y),
                x.sub(y),
                x.mul(y),
                x.div(y),
                x.min(y),
                x.max(y),
                x.le(y),
                x.lt(y),
                x.ge(y),
                x.ne(y),
                x.and(y),
                x.xor(y),
                x.andnot(y),
                x.blend(y, m),
                m,
                V::splat(a[3]),
            ]
            .iter()
            .map(|v| v.store().map(f32::to_bits))
            .chain([[x.le(y).movemask(); 8]])
            .collect()
        }
        for k in 0..20_000u64 {
            let a: [f32; 8] = std::array::from_fn(|l| value(k * 16 + l as u64));
            let b: [f32; 8] = std::array::from_fn(|l| value(k * 16 + 8 + l as u64));
            let bits = mix64(k) as u32 & 0xff;
            assert_eq!(
                all::<Avx2F8>(a, b, bits),
                all::<Sse2F8>(a, b, bits),
                "case {k}"
            );
        }
    }
}
