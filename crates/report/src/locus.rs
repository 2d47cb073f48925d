//! The Planckian locus for the chromaticity plots: Kim et al.'s cubic-spline approximation
//! (B. Kang, O. Moon, C. Hong, H. Lee, B. Cho, Y. Kim, "Design of advanced color temperature
//! control system for HDTV applications", J. Korean Phys. Soc. 41(6):865–871, 2002), valid
//! for 1667–25000 K.
//!
//! Against the locus integrated from Planck's law (c₂ = 1.4388·10⁻² m·K) with the CIE 1931 2°
//! colour-matching functions at 1 nm (360–830 nm, colour-science 0.4.7's table), it is within
//! 4·10⁻⁴ Δu′v′ over that range (checked at the temperatures of the tests below) — less than
//! half a MacAdam step, invisible at the scale of the plots.

/// Lowest and highest temperature of the approximation, K.
pub const T_MIN: f64 = 1667.0;
pub const T_MAX: f64 = 25000.0;

/// CIE 1931 xy of a blackbody at `t` kelvin (clamped to [`T_MIN`], [`T_MAX`]).
pub fn planck_xy(t: f64) -> [f64; 2] {
    let t = t.clamp(T_MIN, T_MAX);
    let (t1, t2, t3) = (1e3 / t, 1e6 / (t * t), 1e9 / (t * t * t));
    let x = if t <= 4000.0 {
        -0.2661239 * t3 - 0.2343589 * t2 + 0.8776956 * t1 + 0.179910
    } else {
        -3.0258469 * t3 + 2.1070379 * t2 + 0.2226347 * t1 + 0.240390
    };
    let y = if t <= 2222.0 {
        -1.1063814 * x.powi(3) - 1.34811020 * x * x + 2.18555832 * x - 0.20219683
    } else if t <= 4000.0 {
        -0.9549476 * x.powi(3) - 1.37418593 * x * x + 2.09137015 * x - 0.16748867
    } else {
        3.0817580 * x.powi(3) - 5.87338670 * x * x + 3.75112997 * x - 0.37001483
    };
    [x, y]
}

/// CIE 1976 u′v′ of a blackbody at `t` kelvin.
pub fn planck_uv(t: f64) -> [f64; 2] {
    let [x, y] = planck_xy(t);
    let d = -2.0 * x + 12.0 * y + 3.0;
    [4.0 * x / d, 9.0 * y / d]
}

/// `n` points of the locus from [`T_MIN`] to [`T_MAX`], evenly spaced in 1/T (mired), which
/// spaces them evenly along the curve: `(T, [u′, v′])`.
pub fn locus_uv(n: usize) -> Vec<(f64, [f64; 2])> {
    let (a, b) = (1.0 / T_MIN, 1.0 / T_MAX);
    (0..n)
        .map(|i| {
            let m = a + (b - a) * i as f64 / (n - 1).max(1) as f64;
            let t = 1.0 / m;
            (t, planck_uv(t))
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn close_to_planck_integrated_with_cie_1931_cmfs() {
        // u′v′ from Planck's law × CIE 1931 2° CMFs, 1 nm, 360–830 nm (colour-science 0.4.7).
        let reference = [
            (1667.0, [0.3372012, 0.5407694]),
            (2000.0, [0.3050484, 0.5385987]),
            (2856.0, [0.255953, 0.5242815]),
            (4000.0, [0.2251106, 0.5015811]),
            (6500.0, [0.200449, 0.4655426]),
            (10000.0, [0.1903188, 0.4398971]),
            (25000.0, [0.1829329, 0.4111099]),
        ];
        for (t, want) in reference {
            let got = planck_uv(t);
            let d = libm::hypot(got[0] - want[0], got[1] - want[1]);
            assert!(d < 4e-4, "{t} K: {got:?} vs {want:?} (duv {d})");
        }
    }

    #[test]
    fn locus_runs_from_red_to_blue() {
        let l = locus_uv(50);
        assert_eq!(l.len(), 50);
        assert!((l[0].0 - T_MIN).abs() < 1e-6 && (l[49].0 - T_MAX).abs() < 1e-6);
        assert!(
            l.windows(2).all(|w| w[1].1[0] < w[0].1[0]),
            "u′ falls with T"
        );
    }
}
