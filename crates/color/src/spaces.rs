//! Linear sRGB ↔ CIE XYZ, chromaticity coordinates and the sRGB transfer curve
//! (estimators.md §0, §6.1, §6.5).
//!
//! The renderer works in scene-linear RGB with sRGB/Rec.709 primaries and a D65
//! white. The matrices below are the full-precision ones derived from the
//! primaries (colour-science `normalised_primary_matrix`), *not* the 4-decimal
//! ones printed in IEC 61966-2-1: with these, linear RGB (1,1,1) maps to
//! [`D65_XYZ`] to the last bit that matters, so "no adaptation" is an exact
//! identity. Never mix the two sets.

#![allow(
    clippy::excessive_precision,
    reason = "constants are copied digit for digit from estimators.md so they can be audited; they round to the intended f64"
)]

use glam::{DMat3, DVec2, DVec3};

/// Builds a [`DMat3`] from rows, so the constants below read like the spec.
/// (glam stores columns; writing the transpose by hand invites mistakes.)
pub(crate) const fn mat3_from_rows(r: [[f64; 3]; 3]) -> DMat3 {
    DMat3::from_cols(
        DVec3::new(r[0][0], r[1][0], r[2][0]),
        DVec3::new(r[0][1], r[1][1], r[2][1]),
        DVec3::new(r[0][2], r[1][2], r[2][2]),
    )
}

/// Linear sRGB → XYZ (D65), §6.1.
pub const M_RGB_TO_XYZ: DMat3 = mat3_from_rows([
    [0.4123907992659593, 0.3575843393838780, 0.1804807884018343],
    [0.2126390058715103, 0.7151686787677559, 0.0721923153607337],
    [0.0193308187155918, 0.1191947797946259, 0.9505321522496606],
]);

/// XYZ (D65) → linear sRGB, §6.1.
pub const M_XYZ_TO_RGB: DMat3 = mat3_from_rows([
    [3.2409699419045221, -1.5373831775700939, -0.4986107602930034],
    [-0.9692436362808798, 1.8759675015077206, 0.0415550574071756],
    [0.0556300796969936, -0.2039769588889765, 1.0569715142428786],
]);

/// The reference (display) white W_r: D65 from xy = (0.3127, 0.3290) with Y = 1,
/// equal to linear sRGB (1,1,1). Deliberately not CIE 15's (0.95047, 1, 1.08883),
/// which would make RGB (1,1,1) ↔ D65 inexact (§0).
pub const D65_XYZ: DVec3 = DVec3::new(0.9504559270516716, 1.0, 1.0890577507598784);

/// D65 chromaticity used to derive the matrices.
pub const D65_XY: DVec2 = DVec2::new(0.3127, 0.3290);

/// Luminance Y of a linear sRGB triple: the second row of [`M_RGB_TO_XYZ`].
#[inline]
pub fn luminance(rgb: DVec3) -> f64 {
    0.2126390058715103 * rgb.x + 0.7151686787677559 * rgb.y + 0.0721923153607337 * rgb.z
}

/// Luminance of an `f32` AOV pixel, computed in `f64`.
#[inline]
pub fn luminance_f32(rgb: [f32; 3]) -> f64 {
    luminance(to_dvec3(rgb))
}

/// Widens an `f32` AOV pixel to `f64`, the precision every reduction uses.
#[inline]
pub(crate) fn to_dvec3(rgb: [f32; 3]) -> DVec3 {
    DVec3::new(rgb[0] as f64, rgb[1] as f64, rgb[2] as f64)
}

/// Linear sRGB → XYZ.
#[inline]
pub fn rgb_to_xyz(rgb: DVec3) -> DVec3 {
    M_RGB_TO_XYZ * rgb
}

/// XYZ → linear sRGB. Out-of-gamut colours give negative components; they are
/// kept (§0.2, §6.3: clamp only at display encoding).
#[inline]
pub fn xyz_to_rgb(xyz: DVec3) -> DVec3 {
    M_XYZ_TO_RGB * xyz
}

/// CIE 1931 xy. `None` when X+Y+Z ≤ 0 or is not finite (§6.5).
pub fn xyz_to_xy(xyz: DVec3) -> Option<DVec2> {
    let s = xyz.x + xyz.y + xyz.z;
    (s > 0.0 && s.is_finite()).then(|| DVec2::new(xyz.x / s, xyz.y / s))
}

/// XYZ with luminance `y_lum` from a chromaticity. `None` when y ≤ 0.
pub fn xy_to_xyz(xy: DVec2, y_lum: f64) -> Option<DVec3> {
    (xy.y > 0.0 && xy.is_finite()).then(|| {
        DVec3::new(
            xy.x * y_lum / xy.y,
            y_lum,
            (1.0 - xy.x - xy.y) * y_lum / xy.y,
        )
    })
}

/// CIE 1976 u′v′ from XYZ. `None` when X+15Y+3Z ≤ 0 or is not finite (§6.5).
pub fn xyz_to_uv(xyz: DVec3) -> Option<DVec2> {
    let d = xyz.x + 15.0 * xyz.y + 3.0 * xyz.z;
    (d > 0.0 && d.is_finite()).then(|| DVec2::new(4.0 * xyz.x / d, 9.0 * xyz.y / d))
}

/// CIE 1976 u′v′ from xy. `None` when −2x+12y+3 ≤ 0 (§6.5).
pub fn xy_to_uv(xy: DVec2) -> Option<DVec2> {
    let d = -2.0 * xy.x + 12.0 * xy.y + 3.0;
    (d > 0.0 && d.is_finite()).then(|| DVec2::new(4.0 * xy.x / d, 9.0 * xy.y / d))
}

/// Chromaticity distance Δu′v′ = ‖a − b‖₂, the unit of every §7 metric.
#[inline]
pub fn delta_uv(a: DVec2, b: DVec2) -> f64 {
    (a - b).length()
}

/// sRGB transfer curve, linear → encoded (§6.1). No clamping here: callers that
/// display decide how to clamp (see [`crate::hsv_of_linear`]).
pub fn srgb_encode(c: f64) -> f64 {
    if c <= 0.0031308 {
        12.92 * c
    } else {
        1.055 * libm::pow(c, 1.0 / 2.4) - 0.055
    }
}

/// sRGB transfer curve, encoded → linear (§6.1).
pub fn srgb_decode(c: f64) -> f64 {
    if c <= 0.04045 {
        c / 12.92
    } else {
        libm::pow((c + 0.055) / 1.055, 2.4)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn luminance_is_second_row_of_matrix() {
        let rgb = DVec3::new(0.3, 0.5, 0.7);
        assert_eq!(luminance(rgb), rgb_to_xyz(rgb).y);
    }

    #[test]
    fn transfer_curve_round_trips() {
        for i in 0..=100 {
            let c = i as f64 / 100.0;
            assert!((srgb_decode(srgb_encode(c)) - c).abs() < 1e-12, "c = {c}");
        }
    }

    #[test]
    fn undefined_chromaticities_are_none() {
        assert!(xyz_to_xy(DVec3::ZERO).is_none());
        assert!(xyz_to_uv(DVec3::ZERO).is_none());
        assert!(xyz_to_uv(DVec3::splat(f64::NAN)).is_none());
        assert!(xy_to_xyz(DVec2::new(0.3, 0.0), 1.0).is_none());
    }
}
