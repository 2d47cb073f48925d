//! The training schedule of a guided frame (Müller et al. 2017, §5.1): passes of 1, 2, 4, …
//! samples per pixel while the last, which keeps what is left, gets at least twice the one
//! before; and the record count above which a spatial leaf splits.

/// The samples per pixel of each pass of a `spp`-sample frame; they add up to `spp`.
pub fn passes(spp: u32) -> Vec<u32> {
    let mut out = Vec::new();
    let (mut used, mut n) = (0u32, 1u32);
    while spp - used >= n && spp - used - n >= 2 * n {
        out.push(n);
        used += n;
        n *= 2;
    }
    if spp > used {
        out.push(spp - used);
    }
    out
}

/// Records per spatial leaf above which it splits, after a pass that made `records`: c·√N,
/// so that the number of leaves grows as the square root of the training data (Müller's
/// c·√(2ᵏ) for passes of 2ᵏ samples per pixel), and each leaf keeps enough records to learn
/// its directions from.
pub fn split_threshold(records: u64) -> u64 {
    const C: f64 = 4.0;
    ((records as f64).sqrt() * C).max(256.0) as u64
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn passes_double_and_the_last_keeps_the_rest() {
        assert_eq!(passes(1), [1]);
        assert_eq!(passes(4), [1, 3]);
        assert_eq!(passes(16), [1, 2, 4, 9]);
        assert_eq!(passes(64), [1, 2, 4, 8, 16, 33]);
        assert_eq!(passes(0), Vec::<u32>::new());
        for spp in 1..300 {
            assert_eq!(passes(spp).iter().sum::<u32>(), spp);
        }
    }
}
