//! `wcam`: Wilkie & Weidlich 2009, "A Robust Illumination Estimate for Chromatic
//! Adaptation in Rendered Images" — **a reconstruction** (estimators.md §2.2, §11).
//!
//! Only the abstract and introduction of WW09 could be read. What is certain:
//! the renderer re-renders the image with achromatic reflectances at the first
//! vertex; each pixel is weighted by how white its surface is; the adaptation
//! colour is the weighted average of that achromatic image; w = 2 is the
//! authors' optimum; specular highlights of emitters come in and dominate. The
//! exact weight, whiteness and achromatic-reflectance definitions are ours and
//! are configurable; every estimate carries the `reconstruction` flag.
//!
//! The renderer supplies A_i (`FrameAovs::achromatic`) with its own choices for
//! `specular` and for directly seen emission; this module only weights and
//! averages. Job-file form (all keys optional, shown with their defaults):
//!
//! ```
//! let opts: eyeadapt_color::WcamOptions = toml::from_str(r#"
//! w = 2.0
//! weight = "linear"          # or "power"
//! achromatic = "luminance"   # or "unit"
//! normalize_pixels = false
//! include_emitters = false
//! specular = "include"       # or "exclude_delta", "diffuse_only" (renderer-side)
//! "#).unwrap();
//! assert_eq!(opts, eyeadapt_color::WcamOptions::default());
//! ```
//!
//! Open questions kept visible (§2.4): Q1 is the weight `1 + w·s` or `s^w`?
//! Q2 is the achromatic reflectance Y(ρ) or 1? Q3 how did WW09 define
//! whiteness? Q4 did WW09 treat directly seen emitters or the background specially?

use glam::DVec3;
use serde::{Deserialize, Serialize};

use super::estimate::{Estimate, flags};
use super::frame::FrameAovs;
use crate::spaces::{luminance, rgb_to_xyz, to_dvec3};

/// §2.2 d: how whiteness s becomes a pixel weight ω (open question Q1).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum WcamWeight {
    /// ω = 1 + w·s: w = 0 is a plain average; white surfaces get up to (1+w)×.
    #[default]
    Linear,
    /// ω = s^w: only white-ish surfaces count at all.
    Power,
}

/// §2.4 Q2: the achromatic reflectance the renderer substituted.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum WcamAchromatic {
    /// Luminance-preserving grey Y(ρ)·(1,1,1): A_i is used as the renderer gives it.
    #[default]
    Luminance,
    /// Constant white 1. Derived here from the same AOV as A_i / Y(ρ_i); pixels
    /// with Y(ρ_i) ≤ 0 cannot be rescaled and are left out. For a Lambertian
    /// pixel this is exactly E_i/π. With mixed lobes the specular part is
    /// rescaled too, which is an approximation.
    Unit,
}

/// §2.3: how specular first bounces enter A_i. Applied **by the renderer** when
/// it computes `FrameAovs::achromatic`; carried here so one job-file table
/// configures the whole estimator. The averaging below ignores it.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum WcamSpecular {
    #[default]
    Include,
    ExcludeDelta,
    DiffuseOnly,
}

/// WCAM options; `Default` is the §10 defaults.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct WcamOptions {
    /// Influence of the white-object information (paper's optimum: 2).
    pub w: f64,
    pub weight: WcamWeight,
    pub achromatic: WcamAchromatic,
    /// Average chromaticities (each XYZ(A_i)/Y(A_i)) instead of radiance, so
    /// bright pixels stop dominating.
    pub normalize_pixels: bool,
    /// Give pixels that directly see an emitter their full weight (default: the
    /// emitter fraction of each pixel is excluded).
    pub include_emitters: bool,
    /// Renderer-side, see [`WcamSpecular`].
    pub specular: WcamSpecular,
}

impl Default for WcamOptions {
    fn default() -> Self {
        WcamOptions {
            w: 2.0,
            weight: WcamWeight::Linear,
            achromatic: WcamAchromatic::Luminance,
            normalize_pixels: false,
            include_emitters: false,
            specular: WcamSpecular::Include,
        }
    }
}

impl WcamOptions {
    /// Every problem with the options, as readable lines.
    pub fn validate(&self) -> Result<(), Vec<String>> {
        if self.w.is_finite() && self.w >= 0.0 {
            Ok(())
        } else {
            Err(vec![format!("wcam: w = {} must be finite and ≥ 0", self.w)])
        }
    }

    fn pixel_weight(&self, s: f64) -> f64 {
        match self.weight {
            WcamWeight::Linear => 1.0 + self.w * s,
            WcamWeight::Power => libm::pow(s, self.w),
        }
    }
}

/// HSV-style saturation of a reflectance, (max − min)/max; 0 when max ≤ 0.
pub fn albedo_saturation(rho: DVec3) -> f64 {
    let max = rho.max_element();
    if max > 0.0 {
        ((max - rho.min_element()) / max).clamp(0.0, 1.0)
    } else {
        0.0
    }
}

/// §2.2 c (PROJECT CHOICE): s = clamp(Y(ρ), 0, 1) · (1 − sat(ρ)); 1 for a perfect
/// white reflector, falling with chroma and with darkness.
pub fn whiteness(rho: DVec3) -> f64 {
    luminance(rho).clamp(0.0, 1.0) * (1.0 - albedo_saturation(rho))
}

/// WCAM estimate: `Σ ω_i XYZ(A_i) / Σ ω_i` over pixels that show a surface.
///
/// The pixel weight is ω(s_i) times the pixel's surface coverage (`hit`, minus
/// the `emitter` fraction unless `include_emitters`), so background pixels drop
/// out and silhouette pixels count in proportion. Reads `albedo`, `achromatic`,
/// `hit`, `emitter`. Undefined (flag `zero_weight`) when Σ ω = 0.
///
/// # Panics
/// If one of those buffers is not width × height long, or the options are invalid.
pub fn wcam(aovs: &FrameAovs, opts: &WcamOptions) -> Estimate {
    if let Err(e) = opts.validate() {
        panic!("{}", e.join("; "));
    }
    aovs.expect_len("albedo", aovs.albedo.len());
    aovs.expect_len("achromatic", aovs.achromatic.len());
    aovs.expect_len("hit", aovs.hit.len());
    aovs.expect_len("emitter", aovs.emitter.len());

    // Sequential f64 sums in pixel order: the result does not depend on threads.
    let (mut sum, mut w_sum, mut n, mut dropped) = (DVec3::ZERO, 0.0, 0u64, false);
    for i in 0..aovs.pixel_count() {
        let coverage = aovs.surface_coverage(i, opts.include_emitters);
        if coverage <= 0.0 {
            continue;
        }
        let rho = aovs.albedo_at(i);
        let omega = opts.pixel_weight(whiteness(rho)) * coverage;
        if omega.is_nan() || omega <= 0.0 {
            continue;
        }
        let mut a = to_dvec3(aovs.achromatic[i]);
        if opts.achromatic == WcamAchromatic::Unit {
            let y_rho = luminance(rho);
            if y_rho.is_nan() || y_rho <= 0.0 {
                continue;
            }
            a /= y_rho;
        }
        let mut xyz = rgb_to_xyz(a);
        if !xyz.is_finite() || !omega.is_finite() {
            dropped = true;
            continue;
        }
        if opts.normalize_pixels {
            if xyz.y <= 0.0 {
                continue;
            }
            xyz /= xyz.y;
        }
        sum += omega * xyz;
        w_sum += omega;
        n += 1;
    }

    let est = if w_sum > 0.0 {
        Estimate::new(sum / w_sum, n)
    } else {
        Estimate::undefined(flags::ZERO_WEIGHT)
    };
    let est = est.with_flag(flags::RECONSTRUCTION);
    if dropped {
        est.with_flag(flags::DROPPED_NON_FINITE)
    } else {
        est
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn whiteness_of_reference_albedos() {
        assert!((whiteness(DVec3::ONE) - 1.0).abs() < 1e-15);
        assert_eq!(whiteness(DVec3::ZERO), 0.0);
        // A pure red reflector is fully saturated: not white at all.
        assert_eq!(whiteness(DVec3::new(0.9, 0.0, 0.0)), 0.0);
        // Mid grey: whiteness is its luminance.
        assert!((whiteness(DVec3::splat(0.5)) - 0.5).abs() < 1e-15);
    }

    #[test]
    fn weights_follow_the_two_readings() {
        let lin = WcamOptions::default();
        assert_eq!(lin.pixel_weight(0.0), 1.0);
        assert_eq!(lin.pixel_weight(1.0), 3.0);
        let pow = WcamOptions {
            weight: WcamWeight::Power,
            ..lin
        };
        assert_eq!(pow.pixel_weight(0.5), 0.25);
        assert_eq!(pow.pixel_weight(0.0), 0.0);
    }

    #[test]
    fn negative_w_is_rejected() {
        let bad = WcamOptions {
            w: -1.0,
            ..Default::default()
        };
        assert!(bad.validate().is_err());
    }
}
