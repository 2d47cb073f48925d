//! The Minkowski-norm colour-constancy framework of van de Weijer, Gevers &
//! Gijsenij, "Edge-based color constancy", IEEE TIP 16(9) 2007 (§5), and the
//! three named methods built on it: `grey_world`, `shades_of_grey`, `grey_edge`.
//!
//! ```text
//! e_c ∝ ( Σ_{x∈𝓜} |D^n_σ f_c(x)|^p )^{1/p}
//! ```
//!
//! on the raw linear frame. The reference normalises e to unit length; here the
//! Minkowski *mean* is returned instead, converted to XYZ, so that grey-world
//! gives the image's mean colour in absolute units. Only the direction of e
//! matters, and both forms have the same one. p = ∞ is the max.
//!
//! A `grey_edge` table in a job file (`shades_of_grey` takes `p`, `sigma`,
//! default 0, and `clip_percentile`; `grey_world` only `clip_percentile`):
//!
//! ```
//! let opts: eyeadapt_color::GreyEdgeOptions = toml::from_str(r#"
//! n = 1
//! p = 6.0
//! sigma = 1.0
//! clip_percentile = 99.9     # optional; absent = no clipping
//! "#).unwrap();
//! let defaults = eyeadapt_color::GreyEdgeOptions::default();
//! assert_eq!(opts, eyeadapt_color::GreyEdgeOptions { clip_percentile: Some(99.9), ..defaults });
//! ```

use glam::DVec3;
use serde::{Deserialize, Serialize};

use super::estimate::{Estimate, flags};
use super::frame::FrameAovs;
use super::gaussian::{derivative_magnitude, kernel_radius};
use super::masked_image::MaskedImage;
use crate::spaces::rgb_to_xyz;

/// One point (n, p, σ) of the framework.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MinkowskiParams {
    /// Derivative order n: 0 (pixel values), 1 (edges) or 2.
    pub order: u8,
    /// Minkowski exponent p > 0; `f64::INFINITY` means max.
    pub p: f64,
    /// Gaussian scale σ in pixels; 0 means no filtering (only with n = 0).
    pub sigma: f64,
    /// Clip each channel at this percentile of 𝓜 first.
    pub clip_percentile: Option<f64>,
}

impl MinkowskiParams {
    /// Every problem with the parameters, as readable lines (`who` names the method).
    pub fn validate(&self, who: &str) -> Result<(), Vec<String>> {
        let mut errs = Vec::new();
        if self.order > 2 {
            errs.push(format!(
                "{who}: derivative order n = {} must be 0, 1 or 2",
                self.order
            ));
        }
        if self.p.is_nan() || self.p <= 0.0 {
            errs.push(format!("{who}: p = {} must be > 0 (inf for max)", self.p));
        }
        if !(self.sigma.is_finite() && self.sigma >= 0.0) {
            errs.push(format!(
                "{who}: sigma = {} must be finite and ≥ 0",
                self.sigma
            ));
        } else if self.order > 0 && self.sigma <= 0.0 {
            errs.push(format!(
                "{who}: derivatives (n = {}) need sigma > 0",
                self.order
            ));
        }
        if let Some(q) = self.clip_percentile
            && !(q > 0.0 && q <= 100.0)
        {
            errs.push(format!("{who}: clip_percentile = {q} must be in (0, 100]"));
        }
        if errs.is_empty() { Ok(()) } else { Err(errs) }
    }
}

/// Minkowski mean of `values` under `mask`, overflow-safe for large p: values
/// are divided by their maximum before being raised to p.
pub(crate) fn minkowski_mean(values: &[f64], mask: &[bool], p: f64) -> f64 {
    let masked = || {
        values
            .iter()
            .zip(mask)
            .filter(|(_, m)| **m)
            .map(|(v, _)| v.abs())
    };
    let max = masked().fold(0.0, f64::max);
    if max == 0.0 || p.is_infinite() {
        return max;
    }
    // Integer exponents (the usual 1, 5, 6) avoid `powf`, which dominates the
    // cost on large frames; the choice depends only on p, so it is deterministic.
    let int_p = (p.fract() == 0.0 && p <= 64.0).then_some(p as i32);
    let (mut sum, mut n) = (0.0, 0usize);
    for v in masked() {
        let t = v / max;
        sum += match int_p {
            Some(1) => t,
            Some(k) => t.powi(k),
            None => libm::pow(t, p),
        };
        n += 1;
    }
    let mean = sum / n as f64;
    if int_p == Some(1) {
        max * mean
    } else {
        max * libm::pow(mean, 1.0 / p)
    }
}

/// The general framework. Reads `rgb` and `emitter`.
///
/// # Panics
/// If the parameters are invalid or a buffer has the wrong length.
pub fn minkowski(aovs: &FrameAovs, params: &MinkowskiParams) -> Estimate {
    if let Err(e) = params.validate("minkowski") {
        panic!("{}", e.join("; "));
    }
    let mut img = MaskedImage::new(aovs, params.clip_percentile);
    let filtered = params.order > 0 || params.sigma > 0.0;
    if filtered {
        img.dilate_exclusion(kernel_radius(params.sigma));
        img.exclude_border(params.sigma.ceil() as usize + 1);
    }
    let n = img.count();
    let est = if n == 0 {
        Estimate::undefined(flags::EMPTY_MASK)
    } else {
        let mut e = DVec3::ZERO;
        for c in 0..3 {
            let plane = &img.planes[c];
            e[c] = if filtered {
                let mag =
                    derivative_magnitude(plane, img.width, img.height, params.sigma, params.order);
                minkowski_mean(&mag, &img.mask, params.p)
            } else {
                minkowski_mean(plane, &img.mask, params.p)
            };
        }
        Estimate::new(rgb_to_xyz(e), n as u64)
    };
    if img.dropped_non_finite {
        est.with_flag(flags::DROPPED_NON_FINITE)
    } else {
        est
    }
}

/// `grey_world` (Buchsbaum 1980): the mean colour over 𝓜 (n = 0, p = 1).
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct GreyWorldOptions {
    pub clip_percentile: Option<f64>,
}

/// `shades_of_grey` (Finlayson & Trezzi 2004): n = 0, p = 6. A σ > 0 turns it
/// into the "general grey-world" of the framework.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct ShadesOfGreyOptions {
    pub p: f64,
    pub sigma: f64,
    pub clip_percentile: Option<f64>,
}

impl Default for ShadesOfGreyOptions {
    fn default() -> Self {
        ShadesOfGreyOptions {
            p: 6.0,
            sigma: 0.0,
            clip_percentile: None,
        }
    }
}

/// `grey_edge` (van de Weijer et al. 2007): n = 1, p = 6, σ = 1 by default.
/// (OpenCV xphoto and the toolbox demo use n = 1, p = 5, σ = 2.)
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct GreyEdgeOptions {
    /// Derivative order: 1 or 2.
    pub n: u8,
    pub p: f64,
    pub sigma: f64,
    pub clip_percentile: Option<f64>,
}

impl Default for GreyEdgeOptions {
    fn default() -> Self {
        GreyEdgeOptions {
            n: 1,
            p: 6.0,
            sigma: 1.0,
            clip_percentile: None,
        }
    }
}

impl GreyWorldOptions {
    pub fn params(&self) -> MinkowskiParams {
        MinkowskiParams {
            order: 0,
            p: 1.0,
            sigma: 0.0,
            clip_percentile: self.clip_percentile,
        }
    }

    pub fn validate(&self) -> Result<(), Vec<String>> {
        self.params().validate("grey_world")
    }
}

impl ShadesOfGreyOptions {
    pub fn params(&self) -> MinkowskiParams {
        MinkowskiParams {
            order: 0,
            p: self.p,
            sigma: self.sigma,
            clip_percentile: self.clip_percentile,
        }
    }

    pub fn validate(&self) -> Result<(), Vec<String>> {
        self.params().validate("shades_of_grey")
    }
}

impl GreyEdgeOptions {
    pub fn params(&self) -> MinkowskiParams {
        MinkowskiParams {
            order: self.n,
            p: self.p,
            sigma: self.sigma,
            clip_percentile: self.clip_percentile,
        }
    }

    pub fn validate(&self) -> Result<(), Vec<String>> {
        let mut errs = self
            .params()
            .validate("grey_edge")
            .err()
            .unwrap_or_default();
        if self.n == 0 {
            errs.insert(
                0,
                "grey_edge: n must be 1 or 2 (use shades_of_grey for n = 0)".into(),
            );
        }
        if errs.is_empty() { Ok(()) } else { Err(errs) }
    }
}

fn run(aovs: &FrameAovs, checked: Result<(), Vec<String>>, params: MinkowskiParams) -> Estimate {
    if let Err(e) = checked {
        panic!("{}", e.join("; "));
    }
    minkowski(aovs, &params)
}

/// Grey-world estimate. Reads `rgb`, `emitter`. Panics on invalid options.
pub fn grey_world(aovs: &FrameAovs, opts: &GreyWorldOptions) -> Estimate {
    run(aovs, opts.validate(), opts.params())
}

/// Shades-of-grey estimate. Reads `rgb`, `emitter`. Panics on invalid options.
pub fn shades_of_grey(aovs: &FrameAovs, opts: &ShadesOfGreyOptions) -> Estimate {
    run(aovs, opts.validate(), opts.params())
}

/// Grey-edge estimate. Reads `rgb`, `emitter`. Panics on invalid options.
pub fn grey_edge(aovs: &FrameAovs, opts: &GreyEdgeOptions) -> Estimate {
    run(aovs, opts.validate(), opts.params())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn minkowski_mean_limits() {
        let v = [1.0, 2.0, 3.0, 100.0];
        let m = [true, true, true, false];
        assert!((minkowski_mean(&v, &m, 1.0) - 2.0).abs() < 1e-15);
        assert_eq!(minkowski_mean(&v, &m, f64::INFINITY), 3.0);
        let p2 = ((1.0 + 4.0 + 9.0) / 3.0f64).sqrt();
        assert!((minkowski_mean(&v, &m, 2.0) - p2).abs() < 1e-14);
        // Huge values and huge p do not overflow; the mean tends to the max.
        let big = [1e300, 5e299];
        let r = minkowski_mean(&big, &[true, true], 1000.0);
        assert!(r.is_finite() && (r / 1e300 - 1.0).abs() < 1e-3);
    }

    #[test]
    fn validation_lists_every_problem() {
        let bad = GreyEdgeOptions {
            n: 0,
            p: -1.0,
            sigma: f64::NAN,
            clip_percentile: Some(120.0),
        };
        let errs = bad.validate().unwrap_err();
        assert_eq!(errs.len(), 4, "{errs:?}");
        assert!(GreyEdgeOptions::default().validate().is_ok());
        assert!(
            ShadesOfGreyOptions {
                p: f64::INFINITY,
                ..Default::default()
            }
            .validate()
            .is_ok()
        );
    }
}
