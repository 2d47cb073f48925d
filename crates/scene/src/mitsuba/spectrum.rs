//! Spectra given as `wavelength:value` pairs or `.spd` files, turned into linear sRGB the way
//! Mitsuba 3's RGB variants (`*_rgb`) do when they load a scene (`docs/mitsuba.md`):
//!
//! - the piecewise-linear spectrum is integrated against the CIE 1931 2° colour-matching
//!   functions (5 nm table, linearly interpolated) with 1000 evenly spaced samples over
//!   360–830 nm, zero outside the spectrum's own range, scaled so that a unit spectrum has
//!   luminance 1;
//! - reflectances (anything but an emitter's radiance or intensity) are weighted by the CIE
//!   D65 illuminant (normalised to luminance 1), so that a flat reflectance stays grey; the
//!   result is clamped to [0, 1]; emitters are not weighted and only clamped at 0;
//! - XYZ → linear sRGB with the Rec. 709 matrix;
//! - a *constant* `<spectrum value="v">` is `v` for reflectances, but for an emitter it is
//!   `v · M · (1, 1, 1)`: the sRGB of an equal-energy spectrum, slightly purple (Mitsuba does
//!   this so that RGB renders match its spectral ones).
use glam::{DMat3, DVec3};

const CIE_MIN: f64 = 360.0;
const CIE_MAX: f64 = 830.0;
/// 1 / ∫ ȳ(λ) dλ over the table (Mitsuba's `MI_CIE_Y_NORMALIZATION`).
const Y_NORMALIZATION: f64 = 1.0 / 106.750_259_399_414_06;
/// Scales the D65 table so that it has luminance 1 (Mitsuba's `MI_CIE_D65_NORMALIZATION`).
const D65_NORMALIZATION: f64 = 1.0 / 98.997_417_518_762_55;

/// CIE XYZ (D65 white) → linear sRGB / Rec. 709.
fn xyz_to_srgb() -> DMat3 {
    DMat3::from_cols_array(&[
        3.240479, -0.969256, 0.055648, -1.537150, 1.875991, -0.204043, -0.498535, 0.041556,
        1.057311,
    ])
}

/// The 5 nm table at `w` nm, linearly interpolated; zero outside 360–830 nm.
fn lookup(table: &[f64; 95], w: f64) -> f64 {
    if !(CIE_MIN..=CIE_MAX).contains(&w) {
        return 0.0;
    }
    let t = (w - CIE_MIN) * (94.0 / (CIE_MAX - CIE_MIN));
    let i = (t as usize).min(93);
    let f = t - i as f64;
    (1.0 - f) * table[i] + f * table[i + 1]
}

/// A spectrum (wavelengths in nm, increasing, at least two) as linear sRGB. `emitter`: the
/// spectrum is a radiance or intensity (no D65 weighting, unbounded above).
pub(crate) fn to_srgb(pairs: &[(f64, f64)], emitter: bool) -> DVec3 {
    let rgb = integrate(pairs, !emitter);
    if emitter {
        rgb.max(DVec3::ZERO)
    } else {
        rgb.clamp(DVec3::ZERO, DVec3::ONE)
    }
}

/// A spectrum of an unbounded non-emitter parameter (a conductor's `eta` and `k`, which
/// Mitsuba reads with `get_unbounded_texture`): D65-weighted like a reflectance, but only
/// clamped at 0.
pub(crate) fn to_srgb_unbounded(pairs: &[(f64, f64)]) -> DVec3 {
    integrate(pairs, true).max(DVec3::ZERO)
}

/// The spectrum integrated to linear sRGB, weighted by D65 when `d65`, not clamped.
fn integrate(pairs: &[(f64, f64)], d65: bool) -> DVec3 {
    const STEPS: usize = 1000;
    let (first, last) = (pairs[0].0, pairs[pairs.len() - 1].0);
    let mut xyz = DVec3::ZERO;
    for i in 0..STEPS {
        let w = CIE_MIN + (i as f64 / (STEPS - 1) as f64) * (CIE_MAX - CIE_MIN);
        if w < first || w > last {
            continue;
        }
        let k = pairs
            .partition_point(|p| p.0 <= w)
            .clamp(1, pairs.len() - 1)
            - 1;
        let ((w0, v0), (w1, v1)) = (pairs[k], pairs[k + 1]);
        let v = ((w - w1) * v0 + (w0 - w) * v1) / (w0 - w1);
        let weight = if d65 {
            lookup(&D65, w) * D65_NORMALIZATION
        } else {
            1.0
        };
        let cmf = DVec3::new(lookup(&CIE_X, w), lookup(&CIE_Y, w), lookup(&CIE_Z, w));
        xyz += cmf * v * weight;
    }
    xyz *= (CIE_MAX - CIE_MIN) * Y_NORMALIZATION / STEPS as f64;
    xyz_to_srgb() * xyz
}

/// A constant spectrum `v` as an emitter's sRGB radiance.
pub(crate) fn uniform_emitter(v: f64) -> DVec3 {
    xyz_to_srgb() * DVec3::splat(v)
}

/// Checks `wavelength:value` pairs: at least two, wavelengths increasing, all finite.
pub(crate) fn check(pairs: &[(f64, f64)]) -> Result<(), String> {
    if pairs.len() < 2 {
        return Err(format!(
            "needs at least two wavelength:value pairs (got {})",
            pairs.len()
        ));
    }
    if pairs.iter().any(|(w, v)| !w.is_finite() || !v.is_finite()) {
        return Err("has a non-finite wavelength or value".into());
    }
    if pairs.windows(2).any(|p| p[1].0 <= p[0].0) {
        return Err("wavelengths must increase".into());
    }
    Ok(())
}

/// `wavelength:value` pairs separated by commas and/or whitespace.
pub(crate) fn parse_pairs(text: &str) -> Result<Vec<(f64, f64)>, String> {
    text.split(|c: char| c == ',' || c.is_whitespace())
        .filter(|t| !t.is_empty())
        .map(|tok| {
            let (w, v) = tok
                .split_once(':')
                .ok_or(format!("\"{tok}\" is not a wavelength:value pair"))?;
            match (w.trim().parse::<f64>(), v.trim().parse::<f64>()) {
                (Ok(w), Ok(v)) => Ok((w, v)),
                _ => Err(format!("\"{tok}\" is not a wavelength:value pair")),
            }
        })
        .collect()
}

/// An `.spd` file: one `wavelength value` pair per line, `#` starts a comment.
pub(crate) fn parse_spd(text: &str) -> Result<Vec<(f64, f64)>, String> {
    let mut out = Vec::new();
    for (n, line) in text.lines().enumerate() {
        let line = line.split('#').next().unwrap_or("");
        let nums: Vec<&str> = line.split_whitespace().collect();
        match nums.as_slice() {
            [] => {}
            [w, v] => match (w.parse::<f64>(), v.parse::<f64>()) {
                (Ok(w), Ok(v)) => out.push((w, v)),
                _ => return Err(format!("line {}: \"{line}\" is not two numbers", n + 1)),
            },
            _ => {
                return Err(format!(
                    "line {}: expected `wavelength value`, got \"{line}\"",
                    n + 1
                ));
            }
        }
    }
    Ok(out)
}

// CIE 1931 2° colour-matching functions x̄, ȳ, z̄ and the CIE D65 illuminant (relative, 100 at
// 560 nm), 360–830 nm in 5 nm steps (CIE 015:2004 tables).
#[rustfmt::skip]
const CIE_X: [f64; 95] = [
    0.0001299, 0.0002321, 0.0004149, 0.0007416, 0.001368, 0.002236, 0.004243, 0.00765,
    0.01431, 0.02319, 0.04351, 0.07763, 0.13438, 0.21477, 0.2839, 0.3285,
    0.34828, 0.34806, 0.3362, 0.3187, 0.2908, 0.2511, 0.19536, 0.1421,
    0.09564, 0.05795001, 0.03201, 0.0147, 0.0049, 0.0024, 0.0093, 0.0291,
    0.06327, 0.1096, 0.1655, 0.2257499, 0.2904, 0.3597, 0.4334499, 0.5120501,
    0.5945, 0.6784, 0.7621, 0.8425, 0.9163, 0.9786, 1.0263, 1.0567,
    1.0622, 1.0456, 1.0026, 0.9384, 0.8544499, 0.7514, 0.6424, 0.5419,
    0.4479, 0.3608, 0.2835, 0.2187, 0.1649, 0.1212, 0.0874, 0.0636,
    0.04677, 0.0329, 0.0227, 0.01584, 0.01135916, 0.008110916, 0.005790346, 0.004109457,
    0.002899327, 0.00204919, 0.001439971, 0.0009999493, 0.0006900786, 0.0004760213, 0.0003323011, 0.0002348261,
    0.0001661505, 0.000117413, 8.307527e-05, 5.870652e-05, 4.150994e-05, 2.935326e-05, 2.067383e-05, 1.455977e-05,
    1.025398e-05, 7.221456e-06, 5.085868e-06, 3.581652e-06, 2.522525e-06, 1.776509e-06, 1.251141e-06,
];
#[rustfmt::skip]
const CIE_Y: [f64; 95] = [
    3.917e-06, 6.965e-06, 1.239e-05, 2.202e-05, 3.9e-05, 6.4e-05, 0.00012, 0.000217,
    0.000396, 0.00064, 0.00121, 0.00218, 0.004, 0.0073, 0.0116, 0.01684,
    0.023, 0.0298, 0.038, 0.048, 0.06, 0.0739, 0.09098, 0.1126,
    0.13902, 0.1693, 0.20802, 0.2586, 0.323, 0.4073, 0.503, 0.6082,
    0.71, 0.7932, 0.862, 0.9148501, 0.954, 0.9803, 0.9949501, 1.0,
    0.995, 0.9786, 0.952, 0.9154, 0.87, 0.8163, 0.757, 0.6949,
    0.631, 0.5668, 0.503, 0.4412, 0.381, 0.321, 0.265, 0.217,
    0.175, 0.1382, 0.107, 0.0816, 0.061, 0.04458, 0.032, 0.0232,
    0.017, 0.01192, 0.00821, 0.005723, 0.004102, 0.002929, 0.002091, 0.001484,
    0.001047, 0.00074, 0.00052, 0.0003611, 0.0002492, 0.0001719, 0.00012, 8.48e-05,
    6e-5, 4.24e-05, 3e-5, 2.12e-05, 1.499e-05, 1.06e-05, 7.4657e-06, 5.2578e-06,
    3.7029e-06, 2.6078e-06, 1.8366e-06, 1.2934e-06, 9.1093e-07, 6.4153e-07, 4.5181e-07,
];
#[rustfmt::skip]
const CIE_Z: [f64; 95] = [
    0.0006061, 0.001086, 0.001946, 0.003486, 0.006450001, 0.01054999, 0.02005001, 0.03621,
    0.06785001, 0.1102, 0.2074, 0.3713, 0.6456, 1.0390501, 1.3856, 1.62296,
    1.74706, 1.7826, 1.77211, 1.7441, 1.6692, 1.5281, 1.28764, 1.0419,
    0.8129501, 0.6162, 0.46518, 0.3533, 0.272, 0.2123, 0.1582, 0.1117,
    0.07824999, 0.05725001, 0.04216, 0.02984, 0.0203, 0.0134, 0.008749999, 0.005749999,
    0.0039, 0.002749999, 0.0021, 0.0018, 0.001650001, 0.0014, 0.0011, 0.001,
    0.0008, 0.0006, 0.00034, 0.00024, 0.00019, 0.0001, 4.999999e-05, 3e-5,
    2e-5, 1e-5, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0,
    0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0,
    0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0,
    0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0,
    0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0,
];
#[rustfmt::skip]
const D65: [f64; 95] = [
    46.6383, 49.3637, 52.0891, 51.0323, 49.9755, 52.3118, 54.6482, 68.7015,
    82.7549, 87.1204, 91.486, 92.4589, 93.4318, 90.057, 86.6823, 95.7736,
    104.865, 110.936, 117.008, 117.41, 117.812, 116.336, 114.861, 115.392,
    115.923, 112.367, 108.811, 109.082, 109.354, 108.578, 107.802, 106.296,
    104.79, 106.239, 107.689, 106.047, 104.405, 104.225, 104.046, 102.023,
    100.0, 98.1671, 96.3342, 96.0611, 95.788, 92.2368, 88.6856, 89.3459,
    90.0062, 89.8026, 89.5991, 88.6489, 87.6987, 85.4936, 83.2886, 83.4939,
    83.6992, 81.863, 80.0268, 80.1207, 80.2146, 81.2462, 82.2778, 80.281,
    78.2842, 74.0027, 69.7213, 70.6652, 71.6091, 72.979, 74.349, 67.9765,
    61.604, 65.7448, 69.8856, 72.4863, 75.087, 69.3398, 63.5927, 55.0054,
    46.4182, 56.6118, 66.8054, 65.0941, 63.3828, 63.8434, 64.304, 61.8779,
    59.4519, 55.7054, 51.959, 54.6998, 57.4406, 58.8765, 60.3125,
];

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn unbounded_parameters_keep_values_above_one() {
        // A conductor's k of 3: flat, D65-weighted, so grey 3 (a reflectance clamps to 1).
        let k = to_srgb_unbounded(&[(300.0, 3.0), (900.0, 3.0)]);
        assert!((k - DVec3::splat(3.0)).abs().max_element() < 0.02, "{k}");
        assert_eq!(to_srgb(&[(300.0, 3.0), (900.0, 3.0)], false), DVec3::ONE);
    }

    #[test]
    fn a_flat_reflectance_stays_grey() {
        let rgb = to_srgb(&[(360.0, 0.5), (830.0, 0.5)], false);
        for c in rgb.to_array() {
            assert!((c - 0.5).abs() < 0.005, "{rgb}");
        }
    }

    #[test]
    fn a_flat_emitter_is_the_equal_energy_colour() {
        // Mitsuba integrates with a step of 470/1000 nm: within 0.3 % of the closed form.
        let rgb = to_srgb(&[(360.0, 2.0), (830.0, 2.0)], true);
        let exact = uniform_emitter(2.0);
        assert!(
            (rgb - exact).abs().max_element() < 0.003 * exact.max_element(),
            "{rgb} {exact}"
        );
        // Equal energy is purple-ish in sRGB: red above green and blue.
        assert!(exact.x > exact.y && exact.x > exact.z, "{exact}");
    }

    #[test]
    fn a_narrow_band_at_600_nm_is_orange_red() {
        let rgb = to_srgb(&[(590.0, 0.0), (600.0, 1.0), (610.0, 0.0)], true);
        assert!(rgb.x > 0.0 && rgb.z == 0.0 && rgb.x > rgb.y, "{rgb}");
    }

    #[test]
    fn pairs_and_spd_files_parse_and_bad_ones_are_refused() {
        assert_eq!(
            parse_pairs("400:0.1, 500:0.2 600:0.3").unwrap(),
            vec![(400.0, 0.1), (500.0, 0.2), (600.0, 0.3)]
        );
        assert!(parse_pairs("400:0.1, 500").is_err());
        assert_eq!(
            parse_spd("# header\n400 1\n\n500 2 # end\n").unwrap(),
            vec![(400.0, 1.0), (500.0, 2.0)]
        );
        assert!(parse_spd("400 1 2\n").is_err());
        assert!(check(&[(500.0, 1.0), (400.0, 1.0)]).is_err());
        assert!(check(&[(500.0, 1.0)]).is_err());
    }
}
