//! CIELAB (CIE 15, §6.6) and the CIEDE2000 colour difference (Sharma, Wu &
//! Dalal 2005, §6.7). Both serve the §7(b) metrics on adapted image sequences.

use glam::DVec3;

/// ε = 216/24389: below it the cube root is replaced by a line (CIE 15 exact form).
const EPSILON: f64 = 216.0 / 24389.0;
/// κ = 24389/27.
const KAPPA: f64 = 24389.0 / 27.0;

/// Tolerance, in degrees, for the |h′₂ − h′₁| = 180° branch of CIEDE2000.
///
/// Sharma pair 14 sits exactly on that boundary; depending on the platform's
/// `atan2` the difference comes out as 180 or 180.00000000000003 and the two
/// branches give 4.8045 and 4.7461. Treating anything within 1e-9° as "≤ 180"
/// reproduces Sharma's published value everywhere (PROJECT CHOICE, §6.7).
pub const HUE_BRANCH_TOLERANCE_DEG: f64 = 1e-9;

fn lab_f(t: f64) -> f64 {
    if t > EPSILON {
        libm::cbrt(t)
    } else {
        (KAPPA * t + 16.0) / 116.0
    }
}

/// XYZ → CIELAB (L*, a*, b*) relative to `white` (X_n, Y_n, Z_n).
///
/// `white` carries the absolute scale: pass `Y_n · D65_XYZ` to measure an
/// HDR frame against a fixed luminance (§7.3).
pub fn xyz_to_lab(xyz: DVec3, white: DVec3) -> DVec3 {
    let fx = lab_f(xyz.x / white.x);
    let fy = lab_f(xyz.y / white.y);
    let fz = lab_f(xyz.z / white.z);
    DVec3::new(116.0 * fy - 16.0, 500.0 * (fx - fy), 200.0 * (fy - fz))
}

/// Hue angle in degrees in [0, 360); 0 for the achromatic point, as Sharma specifies.
fn hue_deg(b: f64, a: f64) -> f64 {
    if a == 0.0 && b == 0.0 {
        return 0.0;
    }
    let h = libm::atan2(b, a).to_degrees();
    if h < 0.0 { h + 360.0 } else { h }
}

/// CIEDE2000 ΔE₀₀ between two CIELAB colours, with k_L = k_C = k_H = 1.
///
/// Follows the step numbering of §6.7 / Sharma et al. 2005, except that the two
/// "|h′₂ − h′₁| vs 180°" tests use [`HUE_BRANCH_TOLERANCE_DEG`].
pub fn delta_e_2000(lab1: DVec3, lab2: DVec3) -> f64 {
    let (l1, a1, b1) = (lab1.x, lab1.y, lab1.z);
    let (l2, a2, b2) = (lab2.x, lab2.y, lab2.z);
    const POW25_7: f64 = 6_103_515_625.0; // 25⁷

    // Step 1: chroma-dependent a* rescaling G (compensates the a* axis near neutral).
    let c1 = libm::hypot(a1, b1);
    let c2 = libm::hypot(a2, b2);
    let c_bar7 = ((c1 + c2) / 2.0).powi(7);
    let g = 0.5 * (1.0 - (c_bar7 / (c_bar7 + POW25_7)).sqrt());

    // Step 2: a′, C′, h′.
    let a1p = (1.0 + g) * a1;
    let a2p = (1.0 + g) * a2;
    let c1p = libm::hypot(a1p, b1);
    let c2p = libm::hypot(a2p, b2);
    let h1p = hue_deg(b1, a1p);
    let h2p = hue_deg(b2, a2p);

    // Step 3: differences. The hue difference goes the short way round the circle.
    let dl = l2 - l1;
    let dc = c2p - c1p;
    let c_prod = c1p * c2p;
    let diff = h2p - h1p;
    let within_half_turn = diff.abs() <= 180.0 + HUE_BRANCH_TOLERANCE_DEG;
    let dh = if c_prod == 0.0 {
        0.0
    } else if within_half_turn {
        diff
    } else if diff > 180.0 {
        diff - 360.0
    } else {
        diff + 360.0
    };
    let dh_big = 2.0 * c_prod.sqrt() * libm::sin(dh.to_radians() / 2.0);

    // Step 4: means. The mean hue also goes the short way round.
    let l_bar = (l1 + l2) / 2.0;
    let c_bar = (c1p + c2p) / 2.0;
    let h_sum = h1p + h2p;
    let h_bar = if c_prod == 0.0 {
        h_sum
    } else if within_half_turn {
        h_sum / 2.0
    } else if h_sum < 360.0 {
        (h_sum + 360.0) / 2.0
    } else {
        (h_sum - 360.0) / 2.0
    };

    // Step 5: weighting functions and the blue-region rotation term.
    let cosd = |deg: f64| libm::cos(deg.to_radians());
    let t =
        1.0 - 0.17 * cosd(h_bar - 30.0) + 0.24 * cosd(2.0 * h_bar) + 0.32 * cosd(3.0 * h_bar + 6.0)
            - 0.20 * cosd(4.0 * h_bar - 63.0);
    let d_theta = 30.0 * libm::exp(-((h_bar - 275.0) / 25.0).powi(2));
    let c_bar_p7 = c_bar.powi(7);
    let r_c = 2.0 * (c_bar_p7 / (c_bar_p7 + POW25_7)).sqrt();
    let r_t = -libm::sin((2.0 * d_theta).to_radians()) * r_c;
    let l50 = (l_bar - 50.0).powi(2);
    let s_l = 1.0 + 0.015 * l50 / (20.0 + l50).sqrt();
    let s_c = 1.0 + 0.045 * c_bar;
    let s_h = 1.0 + 0.015 * c_bar * t;

    // Step 6.
    let (tl, tc, th) = (dl / s_l, dc / s_c, dh_big / s_h);
    (tl * tl + tc * tc + th * th + r_t * tc * th).sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn white_is_l100_neutral() {
        let w = DVec3::new(0.95, 1.0, 1.09);
        let lab = xyz_to_lab(w, w);
        assert!((lab.x - 100.0).abs() < 1e-12 && lab.y.abs() < 1e-12 && lab.z.abs() < 1e-12);
    }

    #[test]
    fn lab_f_is_continuous_at_epsilon() {
        let below = (KAPPA * EPSILON + 16.0) / 116.0;
        assert!((below - libm::cbrt(EPSILON)).abs() < 1e-12);
    }

    #[test]
    fn delta_e_is_symmetric_and_zero_on_identity() {
        let a = DVec3::new(50.0, 2.5, 0.0);
        let b = DVec3::new(73.0, 25.0, -18.0);
        assert_eq!(delta_e_2000(a, a), 0.0);
        assert!((delta_e_2000(a, b) - delta_e_2000(b, a)).abs() < 1e-12);
    }
}
