//! The film's reconstruction filter: how each camera sample is spread over nearby pixels
//! (Mitsuba's `rfilter`). A pixel is the filter-weighted mean of the samples around it.
//!
//! ```toml
//! # Mitsuba XML only: <rfilter type="box"/>, <rfilter type="tent"/>, <rfilter type="gaussian"/>
//! ```

/// A separable reconstruction filter; offsets are in pixels.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub enum PixelFilter {
    /// Each sample counts for its own pixel only (the per-pixel mean).
    #[default]
    Box,
    /// `max(0, 1 − |x| / radius)` (Mitsuba's default radius 1).
    Tent { radius: f32 },
    /// `max(0, exp(−x²/2σ²) − exp(−r²/2σ²))` (Mitsuba's default σ 0.5, r = 4σ).
    Gaussian { stddev: f32, radius: f32 },
}

impl PixelFilter {
    /// Mitsuba's `gaussian` with its defaults.
    pub const GAUSSIAN: PixelFilter = PixelFilter::Gaussian {
        stddev: 0.5,
        radius: 2.0,
    };

    /// The 1D weight at offset `x` (pixels) from the pixel centre, exactly as defined
    /// (the film splats with [`FilterWeights::eval`], the Gaussian's tabulated form).
    pub fn eval(&self, x: f32) -> f32 {
        match *self {
            PixelFilter::Box => box_weight(x),
            PixelFilter::Tent { radius } => tent_weight(radius, x),
            PixelFilter::Gaussian { stddev, radius } => {
                if x.abs() >= radius {
                    0.0
                } else {
                    (gaussian(stddev, x) - gaussian(stddev, radius)).max(0.0)
                }
            }
        }
    }

    /// The filter ready to weigh samples, with what its weights share worked out once (the
    /// Gaussian's table): what a film keeps while it splats samples.
    pub fn weights(&self) -> FilterWeights {
        let (table, scale) = match *self {
            // A radius of 0 (or less) weighs nothing: a table of zeros, read at its first entry.
            PixelFilter::Gaussian { radius, .. } => {
                let table = (0..=GAUSSIAN_TABLE)
                    .map(|k| match k < GAUSSIAN_TABLE && radius > 0.0 {
                        true => self.eval(radius * k as f32 / GAUSSIAN_TABLE as f32),
                        false => 0.0,
                    })
                    .collect();
                let scale = if radius > 0.0 {
                    GAUSSIAN_TABLE as f32 / radius
                } else {
                    0.0
                };
                (table, scale)
            }
            _ => (Vec::new(), 0.0),
        };
        FilterWeights {
            filter: *self,
            table,
            scale,
        }
    }

    /// How far it reaches: a sample in pixel `x` touches pixels `x − reach ..= x + reach`.
    pub fn reach(&self) -> usize {
        let radius = match *self {
            PixelFilter::Box => 0.5,
            PixelFilter::Tent { radius } | PixelFilter::Gaussian { radius, .. } => radius,
        };
        (radius - 0.5).max(0.0).ceil() as usize
    }
}

/// Intervals of the Gaussian's table over [0, radius]. Linear interpolation between its
/// entries is within 2e-6 of the exact weight (the interval squared × the largest second
/// derivative / 8: (2/1024)² × 4 / 8 = 1.9e-6 for Mitsuba's σ 0.5, r 2), where the weights near 1 are
/// what they scale; a lookup is a dozen instructions against `expf`'s fifty (the filter's
/// `exp` was 4 % of a Gaussian-filtered render's instructions). 4 KiB: it stays in L1.
const GAUSSIAN_TABLE: usize = 1024;

/// A [`PixelFilter`] ready to weigh samples: [`PixelFilter::weights`].
#[derive(Clone, Debug, PartialEq)]
pub struct FilterWeights {
    filter: PixelFilter,
    /// The Gaussian's [`PixelFilter::eval`] at `GAUSSIAN_TABLE + 1` evenly spaced |x| in
    /// [0, radius], the last 0 (all 0 for a radius of 0; empty for the other filters).
    table: Vec<f32>,
    /// `GAUSSIAN_TABLE / radius`: |x| in table intervals (0 for a radius of 0).
    scale: f32,
}

impl FilterWeights {
    /// The 1D weight at offset `x` (pixels) from the pixel centre: [`PixelFilter::eval`], the
    /// Gaussian's interpolated in its table.
    #[inline]
    pub fn eval(&self, x: f32) -> f32 {
        match self.filter {
            PixelFilter::Box => box_weight(x),
            PixelFilter::Tent { radius } => tent_weight(radius, x),
            PixelFilter::Gaussian { .. } => {
                let t = x.abs() * self.scale;
                // Also 0 for a NaN offset.
                if t.is_nan() || t >= GAUSSIAN_TABLE as f32 {
                    return 0.0;
                }
                // t is in [0, GAUSSIAN_TABLE): k + 1 is in the table. Through i32: a float's
                // saturating cast to usize is a dozen instructions more on x86-64's baseline.
                let k = t as i32 as usize;
                let f = t - k as f32;
                let (a, b) = (self.table[k], self.table[k + 1]);
                a + (b - a) * f
            }
        }
    }
}

fn box_weight(x: f32) -> f32 {
    if x.abs() <= 0.5 { 1.0 } else { 0.0 }
}

fn tent_weight(radius: f32, x: f32) -> f32 {
    (1.0 - x.abs() / radius).max(0.0)
}

/// `exp(−t²/2σ²)`.
fn gaussian(stddev: f32, t: f32) -> f32 {
    libm::expf(-t * t / (2.0 * stddev * stddev))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn weights_and_reach_follow_mitsubas_definitions() {
        let tent = PixelFilter::Tent { radius: 1.0 };
        assert_eq!(
            (tent.eval(0.0), tent.eval(0.25), tent.eval(1.0)),
            (1.0, 0.75, 0.0)
        );
        assert_eq!(tent.reach(), 1);
        let g = PixelFilter::GAUSSIAN;
        let e = |t: f32| libm::expf(-t * t / 0.5);
        assert!((g.eval(0.5) - (e(0.5) - e(2.0))).abs() < 1e-7);
        assert_eq!(g.eval(2.0), 0.0);
        assert_eq!(g.reach(), 2);
        assert_eq!(PixelFilter::Box.reach(), 0);
    }

    #[test]
    fn the_tabulated_gaussian_stays_within_its_stated_error() {
        for filter in [
            PixelFilter::GAUSSIAN,
            PixelFilter::Gaussian {
                stddev: 1.0,
                radius: 4.0,
            },
        ] {
            let w = filter.weights();
            let PixelFilter::Gaussian { stddev, radius } = filter else {
                unreachable!()
            };
            // (interval)² × max |f''| / 8, f'' of exp(−x²/2σ²) at most 1/σ²; plus rounding.
            let h = radius / GAUSSIAN_TABLE as f32;
            let bound = h * h / (8.0 * stddev * stddev) + 1e-7;
            let mut worst = 0f32;
            for k in 0..=100_000 {
                let x = -1.1 * radius + 2.2 * radius * k as f32 / 100_000.0;
                let err = (w.eval(x) - filter.eval(x)).abs();
                worst = worst.max(err);
                assert!(w.eval(x) >= 0.0 && w.eval(x) <= 1.0);
            }
            assert!(worst <= bound, "{filter:?}: {worst} > {bound}");
            assert!(worst > 0.0, "a table is not the exact filter");
            // Symmetric, exact at the centre and 0 at and beyond the radius, and for NaN.
            assert_eq!(w.eval(0.3), w.eval(-0.3));
            assert_eq!(w.eval(0.0), filter.eval(0.0));
            assert_eq!((w.eval(radius), w.eval(radius * 1.5)), (0.0, 0.0));
            assert_eq!(w.eval(f32::NAN), 0.0);
        }
        // The other filters are not tabulated: their weights are the definition's.
        let tent = PixelFilter::Tent { radius: 1.5 };
        for x in [-2.0, -0.7, 0.0, 0.2, 1.49] {
            assert_eq!(tent.weights().eval(x), tent.eval(x));
            assert_eq!(PixelFilter::Box.weights().eval(x), PixelFilter::Box.eval(x));
        }
        // A Gaussian of radius 0 weighs nothing, as its definition does.
        let none = PixelFilter::Gaussian {
            stddev: 0.5,
            radius: 0.0,
        };
        for x in [-1.0, 0.0, 0.3, f32::NAN] {
            assert_eq!(none.weights().eval(x), 0.0);
            assert_eq!(none.eval(x), 0.0);
        }
    }
}
