//! `dominant`: adapt to the scene's dominant illuminant, after Ward &
//! Eydelberg-Vileshin 2002 (estimators.md §4).
//!
//! WEV02 leaves the choice of dominant source to the user; picking the light
//! with the largest luminous flux is our rule (PROJECT CHOICE, §11 item 3). The
//! renderer computes each light's power, because only it knows areas, textures
//! and the scene's bounding disc:
//!
//! * `by = "flux"` (default, camera-independent): Φ = π·A·Y(L_e) for an area
//!   emitter, 4π·Y(I) for a point light, 2π(1 − cos θ_mid)·Y(I) for a spot,
//!   Y(E)·(bounding-disc area) for a directional light, π·mean Y·(disc area)
//!   for an environment.
//! * `by = "eye"`: the renderer puts each light's share of the §1 Φ_direct term
//!   in `flux_y` instead.
//!
//! Either way this module takes the argmax, breaking ties by the lowest index.
//!
//! ```
//! let opts: eyeadapt_color::DominantOptions = toml::from_str(r#"by = "eye""#).unwrap();
//! assert_eq!(opts.by, eyeadapt_color::DominantBy::Eye);
//! ```

use glam::DVec3;
use serde::{Deserialize, Serialize};

use super::estimate::{Estimate, flags};
use crate::spaces::rgb_to_xyz;

/// One light's emission colour and its power by the chosen rule.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LightPower {
    /// Emission colour (L_e, I or E), linear sRGB, averaged over the surface if textured.
    pub emission_rgb: DVec3,
    /// Power in Y units, by the rule of [`DominantBy`].
    pub flux_y: f64,
}

/// What the renderer puts in [`LightPower::flux_y`].
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum DominantBy {
    /// Luminous flux, independent of the camera.
    #[default]
    Flux,
    /// Each light's contribution to the eye sensor's direct term.
    Eye,
}

/// Options for `dominant`; `Default` is the §10 default (`by = "flux"`).
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct DominantOptions {
    pub by: DominantBy,
}

/// Index of the most powerful light; ties go to the lowest index. Lights with
/// non-finite or non-positive power are never chosen. `None` if none qualifies.
pub fn dominant_light_index(lights: &[LightPower]) -> Option<usize> {
    let mut best: Option<(usize, f64)> = None;
    for (k, l) in lights.iter().enumerate() {
        let phi = l.flux_y;
        if !phi.is_finite() || phi <= 0.0 {
            continue;
        }
        // Strictly greater: an equal later light does not replace an earlier one.
        if best.is_none_or(|(_, b)| phi > b) {
            best = Some((k, phi));
        }
    }
    best.map(|(k, _)| k)
}

/// The dominant light's emission colour as absolute XYZ. Undefined (flag
/// `no_lights`) when no light has positive power. `n_samples` is the number
/// of lights given.
pub fn dominant(lights: &[LightPower]) -> Estimate {
    match dominant_light_index(lights) {
        Some(k) => Estimate::new(rgb_to_xyz(lights[k].emission_rgb), lights.len() as u64),
        None => Estimate::undefined(flags::NO_LIGHTS),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn light(flux_y: f64) -> LightPower {
        LightPower {
            emission_rgb: DVec3::ONE,
            flux_y,
        }
    }

    #[test]
    fn unusable_powers_are_skipped() {
        let ls = [
            light(f64::NAN),
            light(0.0),
            light(-3.0),
            light(f64::INFINITY),
            light(1.0),
        ];
        assert_eq!(dominant_light_index(&ls), Some(4));
        assert_eq!(dominant_light_index(&ls[..4]), None);
        assert_eq!(dominant(&[]).flags, [flags::NO_LIGHTS]);
    }
}
