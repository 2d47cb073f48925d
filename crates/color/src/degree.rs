//! Degree of adaptation D (§6.4): how completely the observer discounts the
//! illuminant, from the surround and the adapting luminance L_A.
//!
//! The project default is D = 1 ("discount the illuminant"), as \[GRC13\] used for
//! all comparisons; these functions are for when the user asks for D to be
//! computed. Renderer radiance has an arbitrary scale, so L_A in cd/m² needs a
//! user-supplied `cd_per_unit` upstream of this module.

use serde::{Deserialize, Serialize};

/// Viewing surround of CIECAM02; it sets the factor F (and c, N_c).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Surround {
    #[default]
    Average,
    Dim,
    Dark,
}

impl Surround {
    /// Maximum degree of adaptation F.
    pub const fn f(self) -> f64 {
        match self {
            Surround::Average => 1.0,
            Surround::Dim => 0.9,
            Surround::Dark => 0.8,
        }
    }

    /// Impact of surround c (CIECAM02; not used by the CAT itself).
    pub const fn c(self) -> f64 {
        match self {
            Surround::Average => 0.69,
            Surround::Dim => 0.59,
            Surround::Dark => 0.525,
        }
    }

    /// Chromatic induction factor N_c (CIECAM02; not used by the CAT itself).
    pub const fn n_c(self) -> f64 {
        self.f()
    }
}

/// Which formula turns (F, L_A) into D. Job-file key `d_model`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum DegreeModel {
    /// CIECAM02 / CAM16 (CIE 159:2004), the default.
    #[default]
    Cie02,
    /// The older CIECAM97s form printed as \[GRC13\] Eq. 2. Only for reproducing
    /// that equation; do not pair it with CAT02 otherwise.
    Cie97s,
}

impl DegreeModel {
    /// D for this model, clamped to [0, 1].
    pub fn degree(self, surround: Surround, l_a: f64) -> f64 {
        match self {
            DegreeModel::Cie02 => degree_of_adaptation(surround.f(), l_a),
            DegreeModel::Cie97s => degree_cie97s(surround.f(), l_a),
        }
    }
}

/// The sRGB viewing condition's adapting luminance, 20 % of a 64/π cd/m² white.
pub const L_A_SRGB: f64 = 64.0 / std::f64::consts::PI * 0.2;

/// CIECAM02: `D = F · [1 − (1/3.6) · exp((−L_A − 42)/92)]`, clamped to [0, 1].
pub fn degree_of_adaptation(f: f64, l_a: f64) -> f64 {
    (f * (1.0 - (1.0 / 3.6) * libm::exp((-l_a - 42.0) / 92.0))).clamp(0.0, 1.0)
}

/// CIECAM97s, \[GRC13\] Eq. 2: `D = F · [1 − 1/(1 + 2 L_A^{1/4} + L_A²/300)]`,
/// clamped to [0, 1].
pub fn degree_cie97s(f: f64, l_a: f64) -> f64 {
    let l_a = l_a.max(0.0);
    (f * (1.0 - 1.0 / (1.0 + 2.0 * libm::pow(l_a, 0.25) + l_a * l_a / 300.0))).clamp(0.0, 1.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn clamped_to_unit_interval() {
        assert_eq!(degree_of_adaptation(1.0, -1e6), 0.0);
        assert_eq!(degree_of_adaptation(2.0, 1e6), 1.0);
        assert_eq!(degree_cie97s(1.0, 0.0), 0.0);
    }

    #[test]
    fn surround_factors() {
        let fs: Vec<f64> = [Surround::Average, Surround::Dim, Surround::Dark]
            .iter()
            .map(|s| s.f())
            .collect();
        assert_eq!(fs, [1.0, 0.9, 0.8]);
        assert_eq!(Surround::Dim.c(), 0.59);
    }

    #[test]
    fn model_dispatch() {
        let d = DegreeModel::Cie97s.degree(Surround::Average, 318.31);
        assert_eq!(d, degree_cie97s(1.0, 318.31));
        assert_eq!(DegreeModel::default(), DegreeModel::Cie02);
    }
}
