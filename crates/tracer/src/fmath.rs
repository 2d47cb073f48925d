//! Exact, inlined forms of rounding functions that the x86-64 baseline (SSE2, no `roundss`)
//! compiles to out-of-line library calls: `f32::floor` is a call into compiler-builtins'
//! `floorf` (about 40 instructions with the call) on every environment-map lookup and every
//! checkerboard test. These give the library's result bit for bit, for every input.
//!
//! Likewise a float-to-`usize` cast is a dozen instructions there (two truncations, a
//! subtraction and two compare-and-selects for the unsigned 64-bit range), where a cell
//! index clamped below `n ≤ 2³¹` needs only the 32-bit truncation: [`cell_index`] and
//! [`cell_index_f64`] give the `usize` cast's clamped index for every input.

/// `x.floor()`, bit for bit (signed zeros, NaN and infinities included), without a call.
#[inline(always)]
pub fn floor(x: f32) -> f32 {
    // From 2^23 up every f32 is an integer; NaN and ±∞ pass through, as in `floorf`.
    if x.is_nan() || x.abs() >= 8_388_608.0 {
        return x;
    }
    // Truncation towards zero is exact below 2^23; a negative non-integer steps down one.
    let t = x as i32 as f32;
    let f = if t > x { t - 1.0 } else { t };
    // floor(x) always carries x's sign (−0.0 stays −0.0, −0.5 gives −1.0).
    f.copysign(x)
}

/// `(x as usize).min(n - 1)` for `1 ≤ n ≤ 2³¹`, for every x (NaN and negatives give 0, as
/// the saturating cast does; from 2³¹ up both give n − 1).
#[inline(always)]
pub fn cell_index(x: f32, n: usize) -> usize {
    debug_assert!((1..=1 << 31).contains(&n));
    ((x as i32).max(0) as usize).min(n - 1)
}

/// [`cell_index`] for an f64.
#[inline(always)]
pub fn cell_index_f64(x: f64, n: usize) -> usize {
    debug_assert!((1..=1 << 31).contains(&n));
    ((x as i32).max(0) as usize).min(n - 1)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn same(x: f32) {
        assert_eq!(
            floor(x).to_bits(),
            x.floor().to_bits(),
            "floor({x:e}) bits {:#x}",
            x.to_bits()
        );
    }

    /// Every 251st bit pattern (both signs, subnormals, the 2^23 edge, NaNs, infinities).
    #[test]
    fn floor_is_floorf_across_the_bit_patterns() {
        let mut b = 0u32;
        loop {
            same(f32::from_bits(b));
            match b.checked_add(251) {
                Some(n) => b = n,
                None => break,
            }
        }
    }

    #[test]
    fn floor_is_floorf_at_the_edges() {
        let edges = [
            0.0,
            -0.0,
            0.5,
            -0.5,
            1.0,
            -1.0,
            1.0 - f32::EPSILON / 2.0,
            -(1.0 - f32::EPSILON / 2.0),
            8_388_607.5,
            -8_388_607.5,
            8_388_608.0,
            -8_388_608.0,
            16_777_217.0,
            f32::MIN_POSITIVE,
            -f32::MIN_POSITIVE,
            f32::from_bits(1),
            -f32::from_bits(1),
            f32::MAX,
            f32::MIN,
            f32::INFINITY,
            f32::NEG_INFINITY,
            f32::NAN,
            -2.5e9,
            2.5e9,
        ];
        for x in edges {
            same(x);
            same(f32::from_bits(x.to_bits().wrapping_add(1)));
            same(f32::from_bits(x.to_bits().wrapping_sub(1)));
        }
    }

    /// The 32-bit index is the clamped `usize` cast across the bit patterns and sizes,
    /// including the largest allowed size and values around it.
    #[test]
    fn cell_index_is_the_clamped_usize_cast() {
        let ns = [1usize, 2, 7, 512, 1 << 20, (1 << 31) - 1, 1 << 31];
        let mut b = 0u32;
        loop {
            let x = f32::from_bits(b);
            for n in ns {
                assert_eq!(cell_index(x, n), (x as usize).min(n - 1), "{x:e} n {n}");
                let d = x as f64;
                assert_eq!(cell_index_f64(d, n), (d as usize).min(n - 1), "{d:e} n {n}");
            }
            match b.checked_add(4099) {
                Some(n) => b = n,
                None => break,
            }
        }
        for d in [
            2147483647.5f64,
            2147483648.0,
            4294967296.5,
            -0.5,
            -1e300,
            1e300,
            f64::NAN,
        ] {
            for n in ns {
                assert_eq!(cell_index_f64(d, n), (d as usize).min(n - 1), "{d:e} n {n}");
            }
        }
    }
}
