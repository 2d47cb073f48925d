//! The previews' 8-bit sRGB byte of a linear value in [0, 1], by table: the same byte as
//! `(srgb_encode(v) · 255 + 0.5) as u8`, without its `powf` (which was a fifth of a 1080p
//! sequence frame's CPU time at low sample counts: ten previews of two million pixels).
//!
//! The byte is a step function of v that rises by one at each of 255 thresholds, found once
//! by bisection over the floats with the formula itself, so the table agrees with it exactly
//! wherever the formula is monotonic (the tests compare both near every threshold and across
//! [0, 1]). Between two thresholds v moves by at least 1 / (255 · 12.92) = 3.0e-4 (the
//! curve's slope is at most its linear segment's 12.92; the power segment's is 12.7 at its
//! foot and falls), more than a 1/4096 bucket, so a bucket holds at most one threshold: the
//! byte is the bucket's first byte, plus one past the threshold.
use std::sync::OnceLock;

/// Buckets of [0, 1].
const BUCKETS: usize = 4096;

struct Table {
    /// The byte at the start of each bucket, k / BUCKETS (one more for v = 1).
    first: [u8; BUCKETS + 1],
    /// `thresholds[b]`: the least v whose byte exceeds b; +∞ for b = 255.
    thresholds: [f32; 256],
}

/// IEC 61966-2-1 encoding of one linear value in [0, 1].
pub fn srgb_encode(c: f32) -> f32 {
    if c <= 0.003_130_8 {
        12.92 * c
    } else {
        1.055 * libm::powf(c, 1.0 / 2.4) - 0.055
    }
}

/// The byte by the formula: what the table reproduces.
fn byte_by_formula(v: f32) -> u8 {
    (srgb_encode(v) * 255.0 + 0.5) as u8
}

fn table() -> &'static Table {
    static TABLE: OnceLock<Table> = OnceLock::new();
    TABLE.get_or_init(|| {
        let mut thresholds = [f32::INFINITY; 256];
        for (b, t) in thresholds.iter_mut().enumerate().take(255) {
            // The least float in [0, 1] whose byte exceeds b (bisection over the bit patterns,
            // which order non-negative floats as their values).
            let (mut lo, mut hi) = (0u32, 1f32.to_bits());
            while lo < hi {
                let mid = lo + (hi - lo) / 2;
                if byte_by_formula(f32::from_bits(mid)) > b as u8 {
                    hi = mid;
                } else {
                    lo = mid + 1;
                }
            }
            *t = f32::from_bits(lo);
        }
        let mut first = [0u8; BUCKETS + 1];
        for (k, f) in first.iter_mut().enumerate() {
            *f = byte_by_formula(k as f32 / BUCKETS as f32);
        }
        Table { first, thresholds }
    })
}

/// `(srgb_encode(v) · 255 + 0.5) as u8` of each of `values`, all in [0, 1].
pub fn srgb8_all(values: impl Iterator<Item = f32>) -> Vec<u8> {
    let t = table();
    values.map(|v| lookup(t, v)).collect()
}

/// The byte of v in [0, 1] from the table.
#[inline(always)]
fn lookup(t: &Table, v: f32) -> u8 {
    // v · 4096 is exact; v in [0, 1] puts the bucket in 0 ..= BUCKETS.
    let k = ((v * BUCKETS as f32) as usize).min(BUCKETS);
    let b = t.first[k];
    b + (v >= t.thresholds[b as usize]) as u8
}

#[cfg(test)]
mod tests {
    use super::*;

    fn srgb8(v: f32) -> u8 {
        lookup(table(), v)
    }

    #[test]
    fn the_table_gives_the_formulas_byte_near_every_threshold_and_across_the_range() {
        let t = table();
        // The thresholds rise, one per byte, and the formula steps there.
        for b in 0..255usize {
            let x = t.thresholds[b];
            assert!(x > 0.0 && x <= 1.0, "{b}: {x}");
            assert_eq!(byte_by_formula(x), b as u8 + 1, "at threshold {b}");
            let below = f32::from_bits(x.to_bits() - 1);
            assert_eq!(byte_by_formula(below), b as u8, "below threshold {b}");
            if b > 0 {
                assert!(t.thresholds[b - 1] < x);
                // Farther apart than a bucket (the module's argument).
                assert!(x - t.thresholds[b - 1] > 1.0 / BUCKETS as f32, "{b}");
            }
            // 512 floats on either side of each threshold.
            for d in 0..512 {
                for v in [
                    f32::from_bits(x.to_bits() + d),
                    f32::from_bits(x.to_bits() - 1 - d),
                ] {
                    let v = v.min(1.0);
                    assert_eq!(srgb8(v), byte_by_formula(v), "v = {v:e}");
                }
            }
        }
        // Every 97th float of [0, 1] (11 million of them), and the ends.
        let mut bits = 0u32;
        while bits <= 1f32.to_bits() {
            let v = f32::from_bits(bits);
            assert_eq!(srgb8(v), byte_by_formula(v), "v = {v:e}");
            bits += 97;
        }
        assert_eq!((srgb8(0.0), srgb8(1.0)), (0, 255));
        let all = srgb8_all([0.0, 0.214_041_14, 1.0].into_iter());
        assert_eq!(all, [0, 128, 255]);
    }
}
