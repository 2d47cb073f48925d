//! Chromatic adaptation transforms (§6.2, §6.3): the von Kries family of
//! "sharpened cone" matrices and the corresponding-colour transform that maps
//! the scene's adaptation white to the display white.
//!
//! The transform is always built with the `Y_w / Y_r` factor, so an estimate may
//! come in at any absolute scale: only its chromaticity (and D) matters. The
//! result is a plain 3×3 matrix, computed once per frame and applied to every
//! pixel; negative RGB afterwards is kept (clamping belongs to display encoding).

#![allow(
    clippy::excessive_precision,
    reason = "constants are copied digit for digit from estimators.md so they can be audited; they round to the intended f64"
)]

use std::fmt;
use std::str::FromStr;

use glam::{DMat3, DVec3};
use serde::{Deserialize, Serialize};

use crate::spaces::{M_RGB_TO_XYZ, M_XYZ_TO_RGB, mat3_from_rows};

/// Which XYZ → "cone" matrix the von Kries scaling happens in.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Cat {
    /// CIECAM02's CAT02, the paper's choice and the project default.
    #[default]
    Cat02,
    /// CAM16's CAT16.
    Cat16,
    /// Bradford, as used by pbrt-v4 and Blender white balance.
    Bradford,
    /// Hunt–Pointer–Estévez normalised to D65 (CIE 109-1994), i.e. classic von Kries.
    VonKries,
}

const CAT02: DMat3 = mat3_from_rows([
    [0.7328, 0.4296, -0.1624],
    [-0.7036, 1.6975, 0.0061],
    [0.0030, 0.0136, 0.9834],
]);
const CAT02_INV: DMat3 = mat3_from_rows([
    [1.0961238208355142, -0.2788690002182873, 0.1827451793827730],
    [0.4543690419753592, 0.4735331543074118, 0.0720978037172291],
    [-0.0096276087384294, -0.0056980312161134, 1.0153256399545427],
]);
const CAT16: DMat3 = mat3_from_rows([
    [0.401288, 0.650173, -0.051461],
    [-0.250268, 1.204414, 0.045854],
    [-0.002079, 0.048952, 0.953127],
]);
const CAT16_INV: DMat3 = mat3_from_rows([
    [1.8620678550872329, -1.0112546305316843, 0.1491867754444517],
    [0.3875265432361372, 0.6214474419314753, -0.0089739851676125],
    [-0.0158414988493339, -0.0341229380285156, 1.0499644368778496],
]);
const BRADFORD: DMat3 = mat3_from_rows([
    [0.8951, 0.2664, -0.1614],
    [-0.7502, 1.7135, 0.0367],
    [0.0389, -0.0685, 1.0296],
]);
const BRADFORD_INV: DMat3 = mat3_from_rows([
    [0.9869929054667123, -0.1470542564209901, 0.1599626516637312],
    [0.4323052697233944, 0.5183602715367774, 0.0492912282128556],
    [-0.0085286645751773, 0.0400428216540849, 0.9684866957875500],
]);
const HPE_D65: DMat3 = mat3_from_rows([
    [0.40024, 0.70760, -0.08081],
    [-0.22630, 1.16532, 0.04570],
    [0.0, 0.0, 0.91822],
]);
const HPE_D65_INV: DMat3 = mat3_from_rows([
    [1.8599363874558399, -1.1293816185800916, 0.2198974095961933],
    [0.3611914362417675, 0.6388124632850422, -0.0000063705968386],
    [0.0, 0.0, 1.0890636230968613],
]);

impl Cat {
    /// Every variant, in a fixed order (for tests and help texts).
    pub const ALL: [Cat; 4] = [Cat::Cat02, Cat::Cat16, Cat::Bradford, Cat::VonKries];

    /// The name used in job files, the CLI and the CSV.
    pub const fn name(self) -> &'static str {
        match self {
            Cat::Cat02 => "cat02",
            Cat::Cat16 => "cat16",
            Cat::Bradford => "bradford",
            Cat::VonKries => "vonkries",
        }
    }

    /// XYZ → cone-like response matrix M.
    pub const fn matrix(self) -> DMat3 {
        match self {
            Cat::Cat02 => CAT02,
            Cat::Cat16 => CAT16,
            Cat::Bradford => BRADFORD,
            Cat::VonKries => HPE_D65,
        }
    }

    /// M⁻¹, the float64 inverses of §6.2 (not recomputed at run time, so every
    /// build uses bit-identical constants).
    pub const fn inverse(self) -> DMat3 {
        match self {
            Cat::Cat02 => CAT02_INV,
            Cat::Cat16 => CAT16_INV,
            Cat::Bradford => BRADFORD_INV,
            Cat::VonKries => HPE_D65_INV,
        }
    }
}

impl fmt::Display for Cat {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// Error for an unknown CAT name; its message lists the valid names.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct UnknownCat(pub String);

impl fmt::Display for UnknownCat {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let names: Vec<&str> = Cat::ALL.iter().map(|c| c.name()).collect();
        write!(
            f,
            "unknown CAT `{}`; valid names are: {}",
            self.0,
            names.join(", ")
        )
    }
}

impl std::error::Error for UnknownCat {}

impl FromStr for Cat {
    type Err = UnknownCat;

    /// Accepts the names of [`Cat::name`], case-insensitively.
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        let wanted = s.trim().to_ascii_lowercase();
        Cat::ALL
            .into_iter()
            .find(|c| c.name() == wanted)
            .ok_or_else(|| UnknownCat(s.to_string()))
    }
}

/// Per-channel cone gains of §6.3: `D · (Y_w/Y_r) · ρ_r/ρ_w + (1 − D)`.
fn cone_gains(cat: Cat, white_src: DVec3, white_dst: DVec3, d: f64) -> DVec3 {
    let m = cat.matrix();
    let rho_w = m * white_src;
    let rho_r = m * white_dst;
    // The Y ratio makes the gains independent of the estimate's absolute scale,
    // for every D, not only D = 1.
    let y_ratio = white_src.y / white_dst.y;
    d * y_ratio * rho_r / rho_w + DVec3::splat(1.0 - d)
}

/// The §6.3 adaptation transform as a 3×3 matrix on XYZ:
/// `M⁻¹ · diag(D·(Y_w/Y_r)·ρ_r/ρ_w + 1 − D) · M`.
///
/// `white_src_xyz` is the scene's adaptation white W (any scale),
/// `white_dst_xyz` the reference white W_r (normally [`crate::D65_XYZ`]) and `d`
/// the degree of adaptation in [0, 1]. With W = W_r it is the identity for every
/// D; with D = 0 it is the identity for every W. A white with a zero or negative
/// cone response gives a non-finite matrix: callers adapt only with valid
/// estimates (§0) and can check `is_finite()`.
pub fn adaptation_matrix_xyz(
    cat: Cat,
    white_src_xyz: DVec3,
    white_dst_xyz: DVec3,
    d: f64,
) -> DMat3 {
    let gains = cone_gains(cat, white_src_xyz, white_dst_xyz, d);
    cat.inverse() * DMat3::from_diagonal(gains) * cat.matrix()
}

/// The same transform on linear sRGB: `M_XYZ→RGB · T · M_RGB→XYZ` (T_RGB of §6.3).
/// The whites are still given in XYZ, as the estimators return them.
pub fn adaptation_matrix_rgb(
    cat: Cat,
    white_src_xyz: DVec3,
    white_dst_xyz: DVec3,
    d: f64,
) -> DMat3 {
    M_XYZ_TO_RGB * adaptation_matrix_xyz(cat, white_src_xyz, white_dst_xyz, d) * M_RGB_TO_XYZ
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn inverses_match_forward_matrices() {
        for cat in Cat::ALL {
            let id = cat.inverse() * cat.matrix();
            assert!(id.abs_diff_eq(DMat3::IDENTITY, 1e-12), "{cat}: {id:?}");
        }
    }

    #[test]
    fn names_round_trip_and_errors_list_choices() {
        for cat in Cat::ALL {
            assert_eq!(cat.to_string().parse::<Cat>(), Ok(cat));
        }
        assert_eq!("  Bradford ".parse::<Cat>(), Ok(Cat::Bradford));
        let err = "cat97".parse::<Cat>().unwrap_err().to_string();
        assert!(
            err.contains("cat97") && err.contains("cat02, cat16, bradford, vonkries"),
            "{err}"
        );
    }

    #[test]
    fn default_is_cat02() {
        assert_eq!(Cat::default(), Cat::Cat02);
    }
}
