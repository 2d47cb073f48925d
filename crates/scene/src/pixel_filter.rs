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

    /// The 1D weight at offset `x` (pixels) from the pixel centre.
    pub fn eval(&self, x: f32) -> f32 {
        self.weights().eval(x)
    }

    /// The filter with what its weights share worked out once (the Gaussian's value at its
    /// radius): what a film keeps while it splats samples.
    pub fn weights(&self) -> FilterWeights {
        let floor = match *self {
            PixelFilter::Gaussian { stddev, radius } => gaussian(stddev, radius),
            _ => 0.0,
        };
        FilterWeights {
            filter: *self,
            floor,
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

/// A [`PixelFilter`] ready to weigh samples: [`PixelFilter::weights`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FilterWeights {
    filter: PixelFilter,
    /// The Gaussian's `exp(−r²/2σ²)` (0 for the other filters).
    floor: f32,
}

impl FilterWeights {
    /// [`PixelFilter::eval`]: the 1D weight at offset `x` (pixels) from the pixel centre.
    #[inline]
    pub fn eval(&self, x: f32) -> f32 {
        match self.filter {
            PixelFilter::Box => {
                if x.abs() <= 0.5 {
                    1.0
                } else {
                    0.0
                }
            }
            PixelFilter::Tent { radius } => (1.0 - x.abs() / radius).max(0.0),
            PixelFilter::Gaussian { stddev, radius } => {
                if x.abs() >= radius {
                    0.0
                } else {
                    (gaussian(stddev, x) - self.floor).max(0.0)
                }
            }
        }
    }
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
}
