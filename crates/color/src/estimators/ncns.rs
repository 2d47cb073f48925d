//! `ncns`: Neumann, Castro, Neumann & Sbert 2003, "Color appearance in
//! multispectral radiosity" — **a reconstruction** (estimators.md §3, §11).
//!
//! Certain: the reference white is a weighted average of the irradiance on the
//! white surfaces, white surfaces near the camera axis weigh more, and the
//! method needs at least one white surface. The white threshold and the axis
//! weighting function were not retrievable; the ones below are ours. Every
//! estimate carries the `reconstruction` flag.
//!
//! ```
//! let opts: eyeadapt_color::NcnsOptions = toml::from_str(r#"
//! white_min_luminance = 0.6
//! white_max_saturation = 0.1
//! axis_weight = "gaussian"   # exp(−θ²/2σ_a²), or "cos_power": cos^k θ
//! sigma_a_deg = 15.0
//! cos_k = 8.0
//! solid_angle_weight = true  # cos³θ, the pinhole pixel's solid angle
//! "#).unwrap();
//! assert_eq!(opts, eyeadapt_color::NcnsOptions::default());
//! ```

use glam::DVec3;
use serde::{Deserialize, Serialize};

use super::estimate::{Estimate, flags};
use super::frame::FrameAovs;
use super::wcam::albedo_saturation;
use crate::spaces::{luminance, rgb_to_xyz, to_dvec3};

/// How a white pixel's weight falls off with its angle θ from the optical axis.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum AxisWeight {
    /// exp(−θ² / (2 σ_a²)); σ_a = 15° is roughly the central visual field.
    #[default]
    Gaussian,
    /// cos^k θ.
    CosPower,
}

/// NCNS options; `Default` is the §10 defaults.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct NcnsOptions {
    /// A pixel's surface is white when Y(ρ) ≥ this …
    pub white_min_luminance: f64,
    /// … and sat(ρ) ≤ this.
    pub white_max_saturation: f64,
    pub axis_weight: AxisWeight,
    /// σ_a of the Gaussian axis weight, degrees.
    pub sigma_a_deg: f64,
    /// k of the cos^k axis weight.
    pub cos_k: f64,
    /// Multiply by cos³θ so that the image's pixel sampling does not bias the
    /// average towards the edges of a wide field of view.
    pub solid_angle_weight: bool,
}

impl Default for NcnsOptions {
    fn default() -> Self {
        NcnsOptions {
            white_min_luminance: 0.6,
            white_max_saturation: 0.1,
            axis_weight: AxisWeight::Gaussian,
            sigma_a_deg: 15.0,
            cos_k: 8.0,
            solid_angle_weight: true,
        }
    }
}

impl NcnsOptions {
    /// Every problem with the options, as readable lines.
    pub fn validate(&self) -> Result<(), Vec<String>> {
        let mut errs = Vec::new();
        if !self.white_min_luminance.is_finite() {
            errs.push(format!(
                "ncns: white_min_luminance = {} must be finite",
                self.white_min_luminance
            ));
        }
        if !(0.0..=1.0).contains(&self.white_max_saturation) {
            errs.push(format!(
                "ncns: white_max_saturation = {} must be in [0, 1]",
                self.white_max_saturation
            ));
        }
        if !(self.sigma_a_deg.is_finite() && self.sigma_a_deg > 0.0) {
            errs.push(format!(
                "ncns: sigma_a_deg = {} must be > 0",
                self.sigma_a_deg
            ));
        }
        if !(self.cos_k.is_finite() && self.cos_k >= 0.0) {
            errs.push(format!("ncns: cos_k = {} must be ≥ 0", self.cos_k));
        }
        if errs.is_empty() { Ok(()) } else { Err(errs) }
    }

    /// Whether a reflectance belongs to the white set 𝒲.
    pub fn is_white(&self, rho: DVec3) -> bool {
        luminance(rho) >= self.white_min_luminance
            && albedo_saturation(rho) <= self.white_max_saturation
    }

    /// g(θ) · (cos³θ if enabled), from cos θ.
    fn angular_weight(&self, cos_theta: f64) -> f64 {
        let g = match self.axis_weight {
            AxisWeight::Gaussian => {
                let theta = libm::acos(cos_theta.clamp(-1.0, 1.0)).to_degrees();
                libm::exp(-theta * theta / (2.0 * self.sigma_a_deg * self.sigma_a_deg))
            }
            AxisWeight::CosPower => libm::pow(cos_theta.max(0.0), self.cos_k),
        };
        if self.solid_angle_weight {
            g * cos_theta.powi(3)
        } else {
            g
        }
    }
}

/// NCNS estimate: `Σ_{i∈𝒲} g_i cos³θ_i XYZ(E_i) / Σ_{i∈𝒲} g_i cos³θ_i`.
///
/// θ_i is the angle between pixel i's centre ray and the optical axis (pinhole,
/// square pixels, `fov_y_deg`). Each weight is also multiplied by the pixel's
/// non-emitter surface coverage, so background and emitter pixels drop out.
/// Reads `albedo`, `irradiance`, `hit`, `emitter`. Undefined (flag
/// `no_white_pixels`) when no white surface is in view.
///
/// # Panics
/// If one of those buffers is not width × height long, or the options are invalid.
pub fn ncns(aovs: &FrameAovs, opts: &NcnsOptions) -> Estimate {
    if let Err(e) = opts.validate() {
        panic!("{}", e.join("; "));
    }
    aovs.expect_len("albedo", aovs.albedo.len());
    aovs.expect_len("irradiance", aovs.irradiance.len());
    aovs.expect_len("hit", aovs.hit.len());
    aovs.expect_len("emitter", aovs.emitter.len());

    let (mut sum, mut w_sum, mut n, mut dropped) = (DVec3::ZERO, 0.0, 0u64, false);
    for i in 0..aovs.pixel_count() {
        let coverage = aovs.surface_coverage(i, false);
        if coverage <= 0.0 || !opts.is_white(aovs.albedo_at(i)) {
            continue;
        }
        let weight = opts.angular_weight(aovs.cos_axis_angle(i)) * coverage;
        let xyz = rgb_to_xyz(to_dvec3(aovs.irradiance[i]));
        if !xyz.is_finite() {
            dropped = true;
            continue;
        }
        sum += weight * xyz;
        w_sum += weight;
        n += 1;
    }

    let est = if n == 0 {
        Estimate::undefined(flags::NO_WHITE_PIXELS)
    } else if w_sum > 0.0 {
        Estimate::new(sum / w_sum, n)
    } else {
        // White pixels exist but all sit where the weight underflows to 0.
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
    fn white_set_thresholds() {
        let o = NcnsOptions::default();
        assert!(o.is_white(DVec3::splat(0.8)));
        assert!(!o.is_white(DVec3::splat(0.5)), "too dark");
        assert!(!o.is_white(DVec3::new(0.9, 0.9, 0.6)), "too saturated");
    }

    #[test]
    fn axis_weights() {
        let o = NcnsOptions::default();
        assert_eq!(o.angular_weight(1.0), 1.0);
        // At θ = σ_a the Gaussian is e^{-1/2}; cos³ multiplies.
        let c = libm::cos(15f64.to_radians());
        let want = libm::exp(-0.5f64) * c.powi(3);
        assert!((o.angular_weight(c) - want).abs() < 1e-12);
        let p = NcnsOptions {
            axis_weight: AxisWeight::CosPower,
            solid_angle_weight: false,
            ..o
        };
        assert!((p.angular_weight(c) - c.powi(8)).abs() < 1e-15);
    }
}
