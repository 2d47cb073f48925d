//! Sampling a bilinear patch over the unit square: the density proportional to
//! `(1−x)(1−y)·w₀₀ + x(1−y)·w₁₀ + (1−x)y·w₀₁ + xy·w₁₁` of four non-negative corner values, by
//! inverting the marginal in y and then the conditional in x, each linear (as in PBRT-v4's
//! `SampleBilinear`). An environment map's radiance is bilinear between texel centres, so
//! drawing within a cell this way makes radiance / density nearly constant across a bright
//! texel, where a uniform draw inside the cell leaves a ratio that varies from its peak to zero
//! (a relative variance of 7/9 for a lone bright texel).

/// Corner values in the order `[w₀₀, w₁₀, w₀₁, w₁₁]` (x then y).
pub type Corners = [f32; 4];

/// `x` in [0, 1) with density proportional to `(1−x)·a + x·b` (a, b ≥ 0, not both 0), from
/// the uniform `u`.
#[inline]
pub fn sample_linear(u: f32, a: f32, b: f32) -> f32 {
    if u == 0.0 && a == 0.0 {
        return 0.0;
    }
    // The root of the CDF's quadratic in the form that loses no precision as a → b.
    let x = u * (a + b) / (a + ((1.0 - u) * a * a + u * b * b).sqrt());
    x.min(1.0 - f32::EPSILON / 2.0)
}

/// The bilinear interpolation of `w` at `p`.
#[cfg(test)]
pub fn bilerp(p: [f32; 2], w: &Corners) -> f32 {
    let [x, y] = p;
    (1.0 - y) * ((1.0 - x) * w[0] + x * w[1]) + y * ((1.0 - x) * w[2] + x * w[3])
}

/// A point of the unit square with density `pdf` (the tests' reference) from the uniform pair `u`.
#[inline]
pub fn sample(u: [f32; 2], w: &Corners) -> [f32; 2] {
    let y = sample_linear(u[1], w[0] + w[1], w[2] + w[3]);
    let x = sample_linear(
        u[0],
        (1.0 - y) * w[0] + y * w[2],
        (1.0 - y) * w[1] + y * w[3],
    );
    [x, y]
}

/// The density of [`sample`] at `p` (0 where every corner is 0). The environment map folds
/// the division into its rows' scale factors and blends the corners with its radiance; this
/// is the reference its tests compare with.
#[cfg(test)]
pub fn pdf(p: [f32; 2], w: &Corners) -> f32 {
    let sum = w[0] + w[1] + w[2] + w[3];
    if sum > 0.0 {
        4.0 * bilerp(p, w) / sum
    } else {
        0.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sampler::{SampleStream, hash_key};

    #[test]
    fn sample_linear_inverts_the_cdf() {
        for (a, b) in [
            (1.0f32, 1.0),
            (0.0, 3.0),
            (5.0, 0.0),
            (0.2, 7.0),
            (1e-6, 1.0),
        ] {
            for k in 0..=100 {
                let u = k as f32 / 100.0;
                let x = sample_linear(u, a, b);
                // CDF of (1−x)a + xb, normalised: (a·x + (b−a)·x²/2) / ((a + b)/2).
                let cdf = (a * x + 0.5 * (b - a) * x * x) / (0.5 * (a + b));
                assert!((0.0..1.0).contains(&x), "{a} {b} {u}: {x}");
                assert!(
                    (cdf - u).abs() < 2e-5,
                    "{a} {b}: cdf({x}) = {cdf}, want {u}"
                );
            }
        }
    }

    /// 8 × 8 histogram of 64k samples against the density's integral over each bin.
    #[test]
    fn samples_follow_the_density() {
        for w in [
            [1.0f32, 0.0, 0.0, 0.0],
            [0.1, 4.0, 2.0, 0.5],
            [3.0, 3.0, 3.0, 3.0],
        ] {
            let n = 1 << 16;
            let mut bins = [0u32; 64];
            let key = hash_key(&[7]);
            for i in 0..n {
                let mut s = SampleStream::new(key, i);
                let p = sample(s.next_2d(), &w);
                bins[(p[1] * 8.0) as usize * 8 + (p[0] * 8.0) as usize] += 1;
            }
            for (b, &count) in bins.iter().enumerate() {
                let (bx, by) = ((b % 8) as f32, (b / 8) as f32);
                // Midpoint rule on a 16 × 16 grid inside the bin (the density is bilinear).
                let mut mass = 0.0;
                for s in 0..256 {
                    let p = [
                        (bx + ((s % 16) as f32 + 0.5) / 16.0) / 8.0,
                        (by + ((s / 16) as f32 + 0.5) / 16.0) / 8.0,
                    ];
                    mass += pdf(p, &w) / (256.0 * 64.0);
                }
                let want = mass * n as f32;
                let tol = 4.0 * want.sqrt() + 3.0;
                assert!(
                    (count as f32 - want).abs() <= tol,
                    "{w:?} bin {b}: {count} samples, expected {want:.1}"
                );
            }
        }
    }

    #[test]
    fn the_density_integrates_to_one_and_is_zero_without_weight() {
        let w = [0.3f32, 2.0, 0.0, 1.1];
        let mut total = 0.0f64;
        for s in 0..10_000 {
            let p = [
                ((s % 100) as f32 + 0.5) / 100.0,
                ((s / 100) as f32 + 0.5) / 100.0,
            ];
            total += pdf(p, &w) as f64 / 10_000.0;
        }
        assert!((total - 1.0).abs() < 1e-4, "{total}");
        assert_eq!(pdf([0.5, 0.5], &[0.0; 4]), 0.0);
    }
}
