//! The value every estimator returns: an absolute XYZ adaptation colour plus
//! the bookkeeping the per-frame CSV needs (§0, §0.2).

use glam::{DVec2, DVec3};
use serde::Serialize;

use crate::spaces::{xyz_to_rgb, xyz_to_uv, xyz_to_xy};

/// Flag strings an [`Estimate`] can carry. They go verbatim into the CSV
/// `flags` column, so they are stable identifiers, not prose.
pub mod flags {
    /// The estimator is a reconstruction of a method whose original text could
    /// not be read (WCAM, NCNS: estimators.md §2.2, §3, §11). Always present on
    /// their estimates so that outputs say so.
    pub const RECONSTRUCTION: &str = "reconstruction";
    /// No pixel passed the estimator's mask.
    pub const EMPTY_MASK: &str = "empty_mask";
    /// Pixels passed the mask but the weights summed to zero (WCAM, §2.2 e).
    pub const ZERO_WEIGHT: &str = "zero_weight";
    /// NCNS found no white surface in view (§3).
    pub const NO_WHITE_PIXELS: &str = "no_white_pixels";
    /// `dominant` was given no light with positive, finite flux (§4).
    pub const NO_LIGHTS: &str = "no_lights";
    /// The result has Y ≤ 0 or a non-finite component (§0).
    pub const INVALID_XYZ: &str = "invalid_xyz";
    /// Some pixels had non-finite values and were left out (informational).
    pub const DROPPED_NON_FINITE: &str = "dropped_non_finite";
}

/// An adaptation-colour estimate.
///
/// `xyz` is absolute: whatever scale the estimator's inputs had (radiance for
/// WCAM, irradiance for NCNS, an image statistic for the colour-constancy
/// methods). Only its chromaticity is meaningful to the CAT, and logs use
/// [`Estimate::normalized`] (Y = 1). An estimate that is not
/// [`valid`](Estimate::is_valid) must not be used to adapt (§0: hold the
/// previous white, or D65 on frame 0); its flags say why.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Estimate {
    /// Absolute XYZ, before Y normalisation. NaN when undefined.
    pub xyz: DVec3,
    /// Monte-Carlo standard error of (u′, v′), when the estimator can give one.
    pub std_err_uv: Option<[f64; 2]>,
    /// How many samples (pixels, lights, paths) contributed.
    pub n_samples: u64,
    /// Stable identifiers from [`flags`].
    pub flags: Vec<&'static str>,
}

impl Estimate {
    /// An estimate from a computed XYZ. If it turns out invalid (Y ≤ 0, or not
    /// finite) the [`flags::INVALID_XYZ`] flag is added, so no undefined value
    /// goes out unflagged.
    pub fn new(xyz: DVec3, n_samples: u64) -> Self {
        let mut e = Estimate {
            xyz,
            std_err_uv: None,
            n_samples,
            flags: Vec::new(),
        };
        if !e.is_valid() {
            e.flags.push(flags::INVALID_XYZ);
        }
        e
    }

    /// An undefined estimate (NaN XYZ) with the reason.
    pub fn undefined(reason: &'static str) -> Self {
        Estimate {
            xyz: DVec3::NAN,
            std_err_uv: None,
            n_samples: 0,
            flags: vec![reason],
        }
    }

    /// Adds a flag (once).
    pub fn with_flag(mut self, flag: &'static str) -> Self {
        if !self.flags.contains(&flag) {
            self.flags.push(flag);
        }
        self
    }

    /// §0: defined when Y > 0 and every component is finite.
    pub fn is_valid(&self) -> bool {
        self.xyz.is_finite() && self.xyz.y > 0.0
    }

    /// XYZ scaled to Y = 1, or NaN when the estimate is not valid (the CSV logs NaN).
    pub fn normalized(&self) -> DVec3 {
        if self.is_valid() {
            self.xyz / self.xyz.y
        } else {
            DVec3::NAN
        }
    }

    /// CIE 1976 u′v′, `None` when not valid.
    pub fn uv(&self) -> Option<DVec2> {
        self.is_valid().then(|| xyz_to_uv(self.xyz)).flatten()
    }

    /// CIE 1931 xy, `None` when not valid.
    pub fn xy(&self) -> Option<DVec2> {
        self.is_valid().then(|| xyz_to_xy(self.xyz)).flatten()
    }

    /// Linear sRGB of the normalised white (may be negative; never clamped, §0.2).
    pub fn rgb_linear(&self) -> DVec3 {
        xyz_to_rgb(self.normalized())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::spaces::D65_XYZ;

    #[test]
    fn normalisation_and_validity() {
        let e = Estimate::new(D65_XYZ * 3.0, 5);
        assert!(e.is_valid() && e.flags.is_empty());
        assert!((e.normalized() - D65_XYZ).abs().max_element() < 1e-15);
        assert!((e.rgb_linear() - DVec3::ONE).abs().max_element() < 1e-12);

        let z = Estimate::new(DVec3::new(0.1, 0.0, 0.1), 1);
        assert!(!z.is_valid() && z.flags == [flags::INVALID_XYZ]);
        assert!(z.normalized().is_nan() && z.uv().is_none());

        let u = Estimate::undefined(flags::EMPTY_MASK).with_flag(flags::EMPTY_MASK);
        assert_eq!(u.flags, [flags::EMPTY_MASK]);
        assert!(!u.is_valid());
    }
}
