//! A piecewise-constant density over the unit square, from non-negative weights on an
//! `nu × nv` grid of cells: sampled by inverting the marginal CDF over rows, then the row's
//! conditional CDF, so that each cell is reached in proportion to its weight and uniformly
//! within it (pbrt's `PiecewiseConstant2D`, built here without its code).
//!
//! Conditional CDFs are per row (single precision is enough within a row); the marginal is in
//! double precision, so a map of millions of cells keeps its small rows.
//!
//! Each CDF has a guide table (Chen and Asau's index table): for G, a power of two, entry k
//! is where the inversion of target (k / G) · total lands, so a sample u starts its search
//! between the entries of ⌊u·G⌋ and ⌊u·G⌋ + 1 — a few neighbouring values instead of a binary
//! search over the whole CDF, whose first steps missed the cache on every environment-map
//! sample (a third of `LightSet::sample`'s cycles on matpreview). The result is the full
//! search's, bit for bit: k / G is exact and rounding a product by the same total is
//! monotonic, so the bracket always holds the answer.

#[cfg(test)]
use crate::fmath::cell_index;
use crate::fmath::cell_index_f64;

pub struct Distribution2D {
    nu: usize,
    nv: usize,
    /// Row-major, per row the running sum of its weights (the last entry is the row's total).
    row_cdf: Vec<f32>,
    /// Running sum of the row totals.
    marginal: Vec<f64>,
    /// Per row, `row_guide_len + 1` guide entries (see the module's text).
    row_guide: Vec<u32>,
    row_guide_len: usize,
    /// The marginal's guide, `marginal_guide.len() − 1` a power of two.
    marginal_guide: Vec<u32>,
}

/// Guide-table size for a CDF of `n` entries: about one entry per four values, a power of two.
fn guide_len(n: usize) -> usize {
    (n / 4).max(1).next_power_of_two()
}

/// The guide table of `cdf` with `g` (a power of two) intervals: entry k is the full
/// inversion's index for target (k / g) · total, the last one `cdf.len()`.
fn guide<T: Copy + Into<f64>>(cdf: &[T], total: f64, g: usize, out: &mut Vec<u32>) {
    let mut i = 0;
    for k in 0..=g {
        let target = (k as f64 / g as f64) * total;
        while i < cdf.len() && cdf[i].into() <= target {
            i += 1;
        }
        out.push(i as u32);
    }
}

/// `invert` (the tests' reference) for target `u · total` (u in [0, 1)), starting from the guide table.
#[inline]
fn invert_guided<T: Copy + Into<f64>>(
    cdf: &[T],
    guide: &[u32],
    u: f32,
    total: f64,
) -> (usize, f64) {
    let g = guide.len() - 1;
    let target = u as f64 * total;
    // g + 1 guide entries (a small power of two): g fits in u32, whose f64 is exact.
    let k = cell_index_f64(u as f64 * g as u32 as f64, g);
    let (lo, hi) = (guide[k] as usize, (guide[k + 1] as usize).min(cdf.len()));
    let p = lo + cdf[lo..hi].partition_point(|&c| c.into() <= target);
    finish_inversion(cdf, target, p)
}

/// Index of the first entry of the increasing `cdf` above `target`, and how far `target` lies
/// into that entry's step, in [0, 1).
#[inline]
#[cfg(test)]
fn invert<T: Copy + Into<f64>>(cdf: &[T], target: f64) -> (usize, f64) {
    finish_inversion(cdf, target, cdf.partition_point(|&c| c.into() <= target))
}

/// The entry and fraction of `invert` from the partition point `p` of `target` in `cdf`.
#[inline]
fn finish_inversion<T: Copy + Into<f64>>(cdf: &[T], target: f64, p: usize) -> (usize, f64) {
    let k = p.min(cdf.len() - 1);
    let lo = if k == 0 { 0.0 } else { cdf[k - 1].into() };
    let width = cdf[k].into() - lo;
    let frac = if width > 0.0 {
        ((target - lo) / width).clamp(0.0, 1.0 - f64::EPSILON)
    } else {
        0.0
    };
    (k, frac)
}

impl Distribution2D {
    /// The density of `weights` (row-major, `nv` rows of `nu`); `None` when they sum to 0 or
    /// are not all finite and non-negative.
    pub fn new(weights: &[f32], nu: usize, nv: usize) -> Option<Distribution2D> {
        assert_eq!(weights.len(), nu * nv, "one weight per cell");
        if nu == 0 || nv == 0 || weights.iter().any(|w| !(w.is_finite() && *w >= 0.0)) {
            return None;
        }
        let mut row_cdf = Vec::with_capacity(weights.len());
        let mut marginal = Vec::with_capacity(nv);
        let mut total = 0.0f64;
        for row in weights.chunks_exact(nu) {
            let mut acc = 0.0f64;
            for w in row {
                acc += *w as f64;
                row_cdf.push(acc as f32);
            }
            total += acc;
            marginal.push(total);
        }
        if !(total > 0.0 && total.is_finite()) {
            return None;
        }
        let row_guide_len = guide_len(nu);
        let mut row_guide = Vec::with_capacity(nv * (row_guide_len + 1));
        for row in row_cdf.chunks_exact(nu) {
            guide(row, row[nu - 1] as f64, row_guide_len, &mut row_guide);
        }
        let mut marginal_guide = Vec::with_capacity(guide_len(nv) + 1);
        guide(&marginal, total, guide_len(nv), &mut marginal_guide);
        Some(Distribution2D {
            nu,
            nv,
            row_cdf,
            marginal,
            row_guide,
            row_guide_len,
            marginal_guide,
        })
    }

    fn total(&self) -> f64 {
        self.marginal[self.nv - 1]
    }

    fn row(&self, j: usize) -> &[f32] {
        &self.row_cdf[j * self.nu..(j + 1) * self.nu]
    }

    /// Weight of cell (i, j).
    #[cfg(test)]
    fn weight(&self, i: usize, j: usize) -> f64 {
        let row = self.row(j);
        let lo = if i == 0 { 0.0 } else { row[i - 1] as f64 };
        row[i] as f64 - lo
    }

    /// The cell (i, j) that `u` leads to, and how far into it along u and v, in [0, 1).
    #[inline]
    fn invert(&self, u: [f32; 2]) -> ([usize; 2], [f64; 2]) {
        let (j, fv) = invert_guided(&self.marginal, &self.marginal_guide, u[1], self.total());
        let row = self.row(j);
        let g = self.row_guide_len + 1;
        let guide = &self.row_guide[j * g..(j + 1) * g];
        let (i, fu) = invert_guided(row, guide, u[0], row[self.nu - 1] as f64);
        ([i, j], [fu, fv])
    }

    /// A cell drawn in proportion to its weight with `u` (never one of weight 0), and a point
    /// uniform over it as fractions in [0, 1) along u and v: for a caller that redraws the
    /// point inside the cell (the environment map), what `Distribution2D::sample` (the tests') gives
    /// without the divisions back to the unit square and the density lookup it does not need.
    #[inline]
    pub fn sample_cell(&self, u: [f32; 2]) -> ([usize; 2], [f32; 2]) {
        let (cell, f) = self.invert(u);
        (cell, f.map(|x| (x as f32).min(1.0 - f32::EPSILON / 2.0)))
    }

    /// A point of the unit square drawn from the density with `u`, and its density there.
    #[cfg(test)]
    pub fn sample(&self, u: [f32; 2]) -> ([f32; 2], f32) {
        let ([i, j], [fu, fv]) = self.invert(u);
        // Below 1 after rounding to single precision; the density is the one `pdf` reports
        // at the rounded point (they differ only where rounding crosses a cell's edge).
        let below_one = |x: f64| (x as f32).min(1.0 - f32::EPSILON / 2.0);
        let p = [
            below_one((i as f64 + fu) / self.nu as f64),
            below_one((j as f64 + fv) / self.nv as f64),
        ];
        (p, self.pdf(p))
    }

    /// Density at point `p` of the unit square (the cell's, constant within it). The
    /// environment map folds it into its rows' scale factors; this is the reference its tests
    /// compare with.
    #[cfg(test)]
    pub fn pdf(&self, p: [f32; 2]) -> f32 {
        let i = cell_index(p[0] * self.nu as f32, self.nu);
        let j = cell_index(p[1] * self.nv as f32, self.nv);
        (self.weight(i, j) / self.total() * (self.nu * self.nv) as f64) as f32
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sampler::{SampleStream, hash_key};

    #[test]
    fn cells_are_reached_in_proportion_to_their_weight() {
        // 4 × 3 cells, one of them empty; χ² of the cell counts of 60 000 samples.
        let w = [1.0, 2.0, 0.0, 4.0, 0.5, 0.5, 3.0, 1.0, 8.0, 0.25, 0.25, 2.5];
        let d = Distribution2D::new(&w, 4, 3).unwrap();
        let total: f32 = w.iter().sum();
        let n = 60_000u32;
        let mut counts = [0u32; 12];
        let key = hash_key(&[41]);
        for s in 0..n {
            let (p, pdf) = d.sample(SampleStream::new(key, s).next_2d());
            assert!(
                (0.0..1.0).contains(&p[0]) && (0.0..1.0).contains(&p[1]),
                "{p:?}"
            );
            assert_eq!(pdf, d.pdf(p), "sample and pdf agree at {p:?}");
            let cell = (p[1] * 3.0) as usize * 4 + (p[0] * 4.0) as usize;
            counts[cell] += 1;
        }
        assert_eq!(counts[2], 0, "an empty cell is never sampled");
        let chi2: f64 = (0..12)
            .filter(|&k| w[k] > 0.0)
            .map(|k| {
                let e = n as f64 * (w[k] / total) as f64;
                (counts[k] as f64 - e).powi(2) / e
            })
            .sum();
        // 10 degrees of freedom: the 0.999 quantile is 29.6.
        assert!(chi2 < 29.6, "χ² = {chi2}, counts {counts:?}");
        // The density integrates to 1 over the square (midpoint rule per cell is exact).
        let integral: f64 = (0..12)
            .map(|k| d.pdf([((k % 4) as f32 + 0.5) / 4.0, ((k / 4) as f32 + 0.5) / 3.0]) as f64)
            .sum::<f64>()
            / 12.0;
        assert!((integral - 1.0).abs() < 1e-6, "∫ pdf = {integral}");
    }

    fn same_inversion<T: Copy + Into<f64>>(cdf: &[T], guide: &[u32], u: f32, total: f64) {
        let a = invert_guided(cdf, guide, u, total);
        let b = invert(cdf, u as f64 * total);
        let n = cdf.len();
        assert_eq!((a.0, a.1.to_bits()), (b.0, b.1.to_bits()), "n {n}, u {u}");
    }

    #[test]
    fn guided_inversion_is_the_full_search_bit_for_bit() {
        // CDFs with empty cells, runs of equal values and a dynamic range of 1e12, in both
        // precisions, against the plain binary search at a million points (and the ends).
        let key = hash_key(&[77]);
        for (n, case) in [
            (1usize, 0u64),
            (3, 1),
            (17, 2),
            (1000, 3),
            (4096, 4),
            (4099, 5),
        ] {
            let weights: Vec<f32> = (0..n)
                .map(|i| {
                    let r = SampleStream::new(key, (case * 10_000 + i as u64) as u32).next_1d();
                    match i % 5 {
                        0 => 0.0,
                        1 => 1e-6 * r,
                        2 => 1e6 * r,
                        _ => r,
                    }
                })
                .collect();
            let mut acc = 0.0f64;
            let cdf64: Vec<f64> = weights
                .iter()
                .map(|w| {
                    acc += *w as f64;
                    acc
                })
                .collect();
            let cdf32: Vec<f32> = cdf64.iter().map(|c| *c as f32).collect();
            let (t64, t32) = (cdf64[n - 1], cdf32[n - 1] as f64);
            if t64 <= 0.0 {
                continue;
            }
            let (mut g64, mut g32) = (Vec::new(), Vec::new());
            guide(&cdf64, t64, guide_len(n), &mut g64);
            guide(&cdf32, t32, guide_len(n), &mut g32);
            let ends = [0.0, f32::EPSILON, 0.25, 0.5, 1.0 - f32::EPSILON / 2.0];
            let us = (0..200_000u32).map(|s| SampleStream::new(key ^ case, s).next_1d());
            for u in ends.into_iter().chain(us) {
                same_inversion(&cdf64, &g64, u, t64);
                same_inversion(&cdf32, &g32, u, t32);
            }
        }
    }

    /// The cell and fractions are the sampled point's, cell for cell, and no empty cell is
    /// ever drawn, even at the ends of u's range.
    #[test]
    fn sample_cell_is_the_sampled_points_cell() {
        let w = [0.0, 2.0, 0.0, 4.0, 0.5, 0.0, 3.0, 1.0, 8.0, 0.0, 0.25, 0.0];
        let d = Distribution2D::new(&w, 4, 3).unwrap();
        let key = hash_key(&[43]);
        let ends = [0.0, 1.0 - f32::EPSILON / 2.0];
        let corners = ends.iter().flat_map(|&a| ends.map(|b| [a, b]));
        for u in corners.chain((0..20_000).map(|s| SampleStream::new(key, s).next_2d())) {
            let ([i, j], f) = d.sample_cell(u);
            assert!(w[j * 4 + i] > 0.0, "{u:?}: empty cell ({i}, {j})");
            assert!(f.iter().all(|x| (0.0..1.0).contains(x)), "{f:?}");
            let (p, _) = d.sample(u);
            let q = [(i as f32 + f[0]) / 4.0, (j as f32 + f[1]) / 3.0];
            assert!(
                (q[0] - p[0]).abs() < 1e-6 && (q[1] - p[1]).abs() < 1e-6,
                "{q:?} {p:?}"
            );
        }
    }

    #[test]
    fn no_weight_no_distribution() {
        assert!(Distribution2D::new(&[0.0; 6], 3, 2).is_none());
        assert!(Distribution2D::new(&[1.0, f32::NAN], 2, 1).is_none());
        assert!(Distribution2D::new(&[1.0, -1.0], 2, 1).is_none());
    }
}
