//! Sine and cosine of the angles the samplers draw: `2π·u` for a uniform `u` (azimuths of
//! BSDF, light, lens and eye-sensor samples) and `π/4·t` for `t` in [−1, 1] (the concentric
//! disk mapping); and [`atan2_turns`], the environment map's longitude and colatitude.
//! Written out here rather than called from a math library for two reasons:
//!
//! - **The same bits on every node.** The platform libm is not: glibc 2.41 replaced several
//!   `f32` functions, and glibc picks an FMA or a non-FMA variant of `sincosf` by CPU. These
//!   are plain `f64` multiplies and adds (Rust never fuses them), rounded once to `f32`.
//! - **Cost.** The angle is already reduced (a turn is split into quarters exactly, `u − q/4`
//!   has no rounding error), so one polynomial pair replaces two full `sinf`/`cosf` calls.
//!
//! Accuracy: the Taylor series of sin and cos of `π/4·t` to the `t⁹` and `t¹⁰` terms, summed
//! in `f64`, is within 2·10⁻⁹ of the true value on [−1, 1], far below half an `f32` ulp of the
//! result, so the `f32` result is the correctly rounded value except within 2·10⁻⁹ of a
//! rounding boundary (`tests` checks ≤ 1 ulp against `f64` references).

use std::f64::consts::FRAC_PI_4;

/// `c[k] = (−1)^k (π/4)^(2k+1) / (2k+1)!`: sin(π/4·t) = Σ `c[k]` t^(2k+1).
const SIN: [f64; 5] = series(1);
/// `c[k] = (−1)^k (π/4)^(2k) / (2k)!`: cos(π/4·t) = Σ `c[k]` t^(2k).
const COS: [f64; 6] = series(0);

/// The alternating series' coefficients, odd (`first` = 1) or even (0) powers.
const fn series<const N: usize>(first: u32) -> [f64; N] {
    let mut c = [0.0; N];
    let mut k = 0;
    while k < N {
        let n = 2 * k as u32 + first;
        let mut term = 1.0;
        let mut i = 1;
        while i <= n {
            term = term * FRAC_PI_4 / i as f64;
            i += 1;
        }
        c[k] = if k % 2 == 0 { term } else { -term };
        k += 1;
    }
    c
}

/// `(sin(π/4·t), cos(π/4·t))` for `t` in [−1, 1].
#[inline(always)]
pub fn sincos_quarter_pi(t: f32) -> (f32, f32) {
    let t = t as f64;
    let t2 = t * t;
    let s = t * (SIN[0] + t2 * (SIN[1] + t2 * (SIN[2] + t2 * (SIN[3] + t2 * SIN[4]))));
    let c = COS[0] + t2 * (COS[1] + t2 * (COS[2] + t2 * (COS[3] + t2 * (COS[4] + t2 * COS[5]))));
    (s as f32, c as f32)
}

/// `(sin(2π·u), cos(2π·u))` for finite `u` with |u| < 2²¹ (samplers pass [0, 1]).
#[inline(always)]
pub fn sincos_turns(u: f32) -> (f32, f32) {
    // The nearest quarter turn q/4 and the rest r = u − q/4 in [−1/8, 1/8]: both exact (q/4
    // and u share u's ulp grid and r is smaller than u), and so is 8r.
    let q = (4.0 * u).round_ties_even();
    let r = u - 0.25 * q;
    let (s, c) = sincos_quarter_pi(8.0 * r);
    match (q as i32) & 3 {
        0 => (s, c),
        1 => (c, -s),
        2 => (-s, -c),
        _ => (-c, s),
    }
}

/// `c[k]` of the odd polynomial `t · Σ c[k] t^(2k)` for atan(t) / 2π on [0, 1]: a minimax fit
/// of the relative error (weighted least squares iterated to equal ripple, in `f64` against
/// `arctan`), 2.4·10⁻⁹ at most, a twentieth of an `f32` ulp.
const ATAN_TURNS: [f64; 10] = [
    0.159_154_942_715_950_68,
    -0.053_051_568_680_239_344,
    0.031_828_230_165_660_484,
    -0.022_698_581_341_750_72,
    0.017_414_825_212_281_965,
    -0.013_333_019_763_925_86,
    0.009_159_867_629_882_376,
    -0.004_902_855_546_350_148_5,
    0.001_707_321_883_185_576_2,
    -0.000_279_162_570_924_904_04,
];

/// `atan2(y, x) / 2π` in turns, in [−1/2, 1/2], for finite `y` and `x` (0 for the origin):
/// the environment map's longitude and colatitude. Like the sines above, plain `f64`
/// multiplies and adds and one division (libm's `atan2f` and `acosf`, a sixth of an
/// environment sample's instructions, branch through several ranges and reductions). Within
/// 2.4·10⁻⁹ of the true value relative to it, so rounded to `f32` within an ulp. The sign of
/// a zero `y` is not kept (−0 gives +0 or +1/2, where `atan2` gives −0 or −π).
#[inline(always)]
pub fn atan2_turns(y: f64, x: f64) -> f64 {
    let (ax, ay) = (x.abs(), y.abs());
    // The octant: t = tan of the angle to the nearer axis, in [0, 1].
    let steep = ay > ax;
    let (lo, hi) = if steep { (ax, ay) } else { (ay, ax) };
    let t = if hi > 0.0 { lo / hi } else { 0.0 };
    let s = t * t;
    let c = &ATAN_TURNS;
    let p = c[8] + s * c[9];
    let p = c[4] + s * (c[5] + s * (c[6] + s * (c[7] + s * p)));
    let p = c[0] + s * (c[1] + s * (c[2] + s * (c[3] + s * p)));
    let mut a = t * p;
    if steep {
        a = 0.25 - a;
    }
    if x < 0.0 {
        a = 0.5 - a;
    }
    if y < 0.0 { -a } else { a }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Distance in f32 ulps between `got` and the reference `want` (computed in f64).
    fn ulps(got: f32, want: f64) -> f64 {
        let w = want as f32;
        let ulp = (f32::from_bits(w.abs().to_bits() + 1) - w.abs()) as f64;
        (got as f64 - want).abs() / ulp.max(f32::MIN_POSITIVE as f64)
    }

    #[test]
    #[allow(clippy::disallowed_methods)] // the platform's f64 sin/cos as the reference
    fn quarter_pi_is_within_one_ulp_of_the_true_values() {
        let mut worst = (0.0f64, 0.0f64);
        for i in 0..=200_000 {
            let t = -1.0 + 2.0 * i as f32 / 200_000.0;
            let (s, c) = sincos_quarter_pi(t);
            let a = FRAC_PI_4 * t as f64;
            worst.0 = worst.0.max(ulps(s, a.sin()));
            worst.1 = worst.1.max(ulps(c, a.cos()));
        }
        assert!(worst.0 <= 1.0 && worst.1 <= 1.0, "worst ulps {worst:?}");
    }

    #[test]
    #[allow(clippy::disallowed_methods)]
    fn turns_are_within_one_ulp_and_exact_at_quarter_turns() {
        let tau = std::f64::consts::TAU;
        let mut worst = 0.0f64;
        for i in 0..=400_000u32 {
            // The whole unit interval, its ends and a few turns either side.
            let u = -3.0 + 7.0 * i as f32 / 400_000.0;
            let (s, c) = sincos_turns(u);
            let a = tau * u as f64;
            // Near a zero of sin or cos an ulp of the result is tiny: compare against the
            // absolute error an f32 angle of this size carries instead.
            let tol = (u.abs() as f64 * tau * f32::EPSILON as f64).max(1e-30);
            for (got, want) in [(s, a.sin()), (c, a.cos())] {
                let e = ulps(got, want).min((got as f64 - want).abs() / tol);
                worst = worst.max(e);
            }
        }
        assert!(worst <= 1.0, "worst {worst}");
        for (u, s, c) in [
            (0.0, 0.0, 1.0),
            (0.25, 1.0, 0.0),
            (0.5, 0.0, -1.0),
            (0.75, -1.0, 0.0),
            (1.0, 0.0, 1.0),
        ] {
            let (gs, gc) = sincos_turns(u);
            assert_eq!((gs, gc), (s, c), "u = {u}");
        }
    }

    /// Against the platform's `f64` atan2 over all directions and near the axes and
    /// diagonals (both octants of each), and as acos(y) = atan2(√(1 − y²), y) over [−1, 1].
    #[test]
    #[allow(clippy::disallowed_methods)]
    fn atan2_turns_is_within_an_ulp_of_atan2() {
        let tau = std::f64::consts::TAU;
        let mut worst = 0.0f64;
        let mut check = |y: f32, x: f32| {
            let got = atan2_turns(y as f64, x as f64);
            let want = (y as f64).atan2(x as f64) / tau;
            // −0 may give +0 and −1/2 may give +1/2.
            let want = if y == 0.0 { want.abs() } else { want };
            worst = worst.max(ulps(got as f32, want));
        };
        for i in 0..1_000_000u32 {
            let a = tau * i as f64 / 1_000_000.0;
            let (s, c) = (a.sin() as f32, a.cos() as f32);
            check(s, c);
            check(1e-6 * s, c);
            check(s, 1e-6 * c);
            check(1e20 * s, 1e20 * c);
        }
        for (y, x) in [(0.0, 1.0), (1.0, 0.0), (-1.0, 0.0), (1.0, 1.0), (-1.0, 1.0)] {
            check(y, x);
            check(y, -x);
        }
        assert!(worst <= 1.0, "worst {worst}");
        assert_eq!(atan2_turns(0.0, 0.0), 0.0);
        assert_eq!(atan2_turns(0.0, -0.0), 0.0);
        assert_eq!(atan2_turns(0.0, -1.0), 0.5);
        assert_eq!(atan2_turns(1.0, 0.0), 0.25);
        assert_eq!(atan2_turns(-1.0, 0.0), -0.25);
        let mut worst_acos = 0.0f64;
        for i in 0..=1_000_000u32 {
            let y = (-1.0 + 2.0 * i as f64 / 1_000_000.0) as f32 as f64;
            let got = (2.0 * atan2_turns((1.0 - y * y).sqrt(), y)) as f32;
            worst_acos = worst_acos.max(ulps(got, y.acos() / std::f64::consts::PI));
        }
        assert!(worst_acos <= 1.0, "acos: worst {worst_acos} ulps");
    }

    #[test]
    fn the_coefficients_are_the_series() {
        assert_eq!(SIN[0], FRAC_PI_4);
        assert_eq!(COS[0], 1.0);
        assert!((SIN[1] + FRAC_PI_4.powi(3) / 6.0).abs() < 1e-17);
        assert!((COS[5] + FRAC_PI_4.powi(10) / 3_628_800.0).abs() < 1e-22);
    }
}
