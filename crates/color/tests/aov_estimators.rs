//! `wcam`, `ncns` and `dominant` on synthetic AOVs whose answer is known:
//! single-illuminant scenes recover the illuminant, the weights follow their
//! formulas, highlights dominate WCAM, and undefined cases say why.

mod common;

use common::{Buffers, assert_rel, assert_vec3, duv, f32x3, xyz_of_f32};
use eyeadapt_color::*;
use glam::DVec3;
use std::f64::consts::PI;

const ORANGE: DVec3 = DVec3::new(1.0, 0.6, 0.3);
const WHITE_ALBEDO: DVec3 = DVec3::splat(0.8);
const RED_ALBEDO: DVec3 = DVec3::new(0.6, 0.1, 0.1);

/// A Lambertian scene lit by one illuminant colour `light` with a spatially
/// varying intensity: E_i = light · k_i, A_i = Y(ρ_i) E_i / π (§2.2 b).
fn lit_scene(light: DVec3, albedo: impl Fn(usize) -> DVec3) -> Buffers {
    let mut b = Buffers::new(16, 12);
    for i in 0..16 * 12 {
        let rho = albedo(i);
        let e = light * (0.5 + (i % 7) as f64 * 0.25);
        b.albedo[i] = f32x3(rho);
        b.irradiance[i] = f32x3(e);
        b.achromatic[i] = f32x3(luminance(rho) * e / PI);
    }
    b
}

#[test]
fn single_illuminant_is_recovered() {
    let white = lit_scene(ORANGE, |_| WHITE_ALBEDO);
    let mixed = lit_scene(
        ORANGE,
        |i| if i % 3 == 0 { RED_ALBEDO } else { WHITE_ALBEDO },
    );
    let want = xyz_of_f32(ORANGE);
    for (name, b) in [("white", &white), ("mixed albedo", &mixed)] {
        for opts in [
            WcamOptions::default(),
            WcamOptions {
                weight: WcamWeight::Power,
                ..Default::default()
            },
            WcamOptions {
                achromatic: WcamAchromatic::Unit,
                ..Default::default()
            },
            WcamOptions {
                normalize_pixels: true,
                ..Default::default()
            },
        ] {
            let est = wcam(&b.aovs(), &opts);
            assert!(est.is_valid(), "{name} {opts:?}: {est:?}");
            assert!(
                duv(est.xyz, want) < 1e-6,
                "wcam {name} {opts:?}: Δu'v' = {}",
                duv(est.xyz, want)
            );
            assert_eq!(est.flags, [flags::RECONSTRUCTION]);
            assert_eq!(est.normalized().y, 1.0);
        }
        let est = ncns(&b.aovs(), &NcnsOptions::default());
        assert!(duv(est.xyz, want) < 1e-6, "ncns {name}");
        assert_eq!(est.flags, [flags::RECONSTRUCTION]);
    }
}

#[test]
fn wcam_weights_follow_the_formulas() {
    // Half white surfaces under light a, half red surfaces under light b.
    let (a, b) = (DVec3::new(0.2, 0.3, 0.9), DVec3::new(0.9, 0.5, 0.1));
    let mut buf = Buffers::new(8, 2);
    for i in 0..16 {
        let (rho, e) = if i < 8 {
            (WHITE_ALBEDO, a)
        } else {
            (RED_ALBEDO, b)
        };
        buf.albedo[i] = f32x3(rho);
        buf.achromatic[i] = f32x3(e);
    }
    let rho = |v: DVec3| DVec3::from_array(f32x3(v).map(|c| c as f64));
    let s_white = luminance(rho(WHITE_ALBEDO));
    let s_red = luminance(rho(RED_ALBEDO)) * (1.0 - (0.6f32 - 0.1f32) as f64 / 0.6f32 as f64);
    let (xa, xb) = (xyz_of_f32(a), xyz_of_f32(b));
    let expect = |wa: f64, wb: f64| (wa * xa + wb * xb) / (wa + wb);

    let lin = wcam(&buf.aovs(), &WcamOptions::default());
    assert_vec3(
        lin.xyz,
        expect(1.0 + 2.0 * s_white, 1.0 + 2.0 * s_red).to_array(),
        1e-6,
        "linear",
    );
    let pow = wcam(
        &buf.aovs(),
        &WcamOptions {
            weight: WcamWeight::Power,
            w: 3.0,
            ..Default::default()
        },
    );
    assert_vec3(
        pow.xyz,
        expect(s_white.powi(3), s_red.powi(3)).to_array(),
        1e-6,
        "power",
    );
    let flat = wcam(
        &buf.aovs(),
        &WcamOptions {
            w: 0.0,
            ..Default::default()
        },
    );
    assert_vec3(
        flat.xyz,
        expect(1.0, 1.0).to_array(),
        1e-6,
        "w = 0 is a plain average",
    );
    assert_eq!(lin.n_samples, 16);
}

#[test]
fn wcam_unit_reflectance_divides_out_the_albedo_luminance() {
    // Uniform irradiance E: `luminance` gives mean_ω(Y(ρ))·E/π, `unit` gives E/π.
    let e = DVec3::new(2.0, 1.5, 1.0);
    let b = lit_scene(e, |i| if i % 2 == 0 { RED_ALBEDO } else { WHITE_ALBEDO });
    let mut b = b;
    b.irradiance.fill(f32x3(e));
    for i in 0..b.albedo.len() {
        let rho = DVec3::from_array(b.albedo[i].map(|c| c as f64));
        b.achromatic[i] = f32x3(luminance(rho) * e / PI);
    }
    let unit = wcam(
        &b.aovs(),
        &WcamOptions {
            achromatic: WcamAchromatic::Unit,
            ..Default::default()
        },
    );
    assert_vec3(
        unit.xyz,
        (rgb_to_xyz(e) / PI).to_array(),
        1e-6,
        "unit = E/π",
    );
}

#[test]
fn wcam_follows_a_highlight() {
    // Dim white-lit walls plus one neutral-albedo pixel holding a strong orange
    // highlight: the radiance-level average follows the highlight (§2.1 item 7).
    let mut b = lit_scene(DVec3::ONE, |_| WHITE_ALBEDO);
    let spot = 5 * 16 + 9;
    b.achromatic[spot] = f32x3(1000.0 * ORANGE);
    let (white, orange) = (rgb_to_xyz(DVec3::ONE), rgb_to_xyz(ORANGE));
    let est = wcam(&b.aovs(), &WcamOptions::default());
    let (d_white, d_orange) = (duv(est.xyz, white), duv(est.xyz, orange));
    assert!(
        d_orange < 0.25 * d_white,
        "Δu'v' to orange {d_orange}, to white {d_white}"
    );
    // Averaging chromaticities instead takes away the highlight's leverage.
    let norm = wcam(
        &b.aovs(),
        &WcamOptions {
            normalize_pixels: true,
            ..Default::default()
        },
    );
    assert!(
        duv(norm.xyz, white) < 0.01,
        "normalized: {}",
        duv(norm.xyz, white)
    );
}

#[test]
fn wcam_ignores_background_and_emitters_by_default() {
    let base = lit_scene(ORANGE, |_| WHITE_ALBEDO);
    let mut b = base.clone();
    b.hit[0] = 0.0; // background: whatever the renderer left in A is ignored
    b.achromatic[0] = [0.0, 50.0, 0.0];
    b.emitter[1] = 1.0; // a directly seen emitter
    b.achromatic[1] = [0.0, 0.0, 80.0];
    let mut reference = base.clone();
    reference.hit[0] = 0.0;
    reference.emitter[1] = 1.0;
    let est = wcam(&b.aovs(), &WcamOptions::default());
    assert_eq!(est, wcam(&reference.aovs(), &WcamOptions::default()));
    assert_eq!(est.n_samples, (16 * 12 - 2) as u64);
    // With include_emitters the emitter pixel counts (and is very blue).
    let incl = wcam(
        &b.aovs(),
        &WcamOptions {
            include_emitters: true,
            ..Default::default()
        },
    );
    assert_eq!(incl.n_samples, (16 * 12 - 1) as u64);
    assert!(duv(incl.xyz, xyz_of_f32(ORANGE)) > 0.01);
}

#[test]
fn wcam_partial_coverage_weighs_in_proportion() {
    let mut b = Buffers::new(2, 1);
    b.albedo.fill(f32x3(WHITE_ALBEDO));
    b.achromatic = vec![[1.0, 0.0, 0.0], [0.0, 0.0, 1.0]];
    b.hit[1] = 0.5;
    let est = wcam(&b.aovs(), &WcamOptions::default());
    let want = (rgb_to_xyz(DVec3::X) + 0.5 * rgb_to_xyz(DVec3::Z)) / 1.5;
    assert_vec3(est.xyz, want.to_array(), 1e-12, "coverage-weighted");
}

#[test]
fn wcam_with_nothing_to_weigh_is_undefined() {
    // Pure red reflectors are saturated, whiteness 0: `power` gives them no weight.
    let mut b = lit_scene(ORANGE, |_| DVec3::new(0.6, 0.0, 0.0));
    let pow = wcam(
        &b.aovs(),
        &WcamOptions {
            weight: WcamWeight::Power,
            ..Default::default()
        },
    );
    assert!(
        !pow.is_valid() && pow.flags.contains(&flags::ZERO_WEIGHT),
        "{pow:?}"
    );
    b.hit.fill(0.0);
    let est = wcam(&b.aovs(), &WcamOptions::default());
    assert!(!est.is_valid(), "{est:?}");
    assert!(est.flags.contains(&flags::ZERO_WEIGHT) && est.flags.contains(&flags::RECONSTRUCTION));
    assert!(est.normalized().is_nan() && est.uv().is_none());
}

#[test]
fn ncns_needs_a_white_surface() {
    let b = lit_scene(ORANGE, |_| DVec3::splat(0.3));
    let est = ncns(&b.aovs(), &NcnsOptions::default());
    assert!(
        !est.is_valid() && est.flags.contains(&flags::NO_WHITE_PIXELS),
        "{est:?}"
    );
    // White surfaces that are emitters do not count either.
    let mut e = lit_scene(ORANGE, |_| WHITE_ALBEDO);
    e.emitter.fill(1.0);
    assert!(
        ncns(&e.aovs(), &NcnsOptions::default())
            .flags
            .contains(&flags::NO_WHITE_PIXELS)
    );
}

#[test]
fn ncns_weights_the_axis_and_the_solid_angle() {
    // 3×3 at 90° vertical fov: centre pixel white under e1, four corners white
    // under e2, the rest not white. Corner: tan²θ = (2/3)² + (2/3)².
    let (e1, e2) = (DVec3::new(1.0, 0.9, 0.8), DVec3::new(0.2, 0.4, 1.0));
    let mut b = Buffers::new(3, 3);
    b.fov_y_deg = 90.0;
    b.albedo.fill(f32x3(RED_ALBEDO));
    b.irradiance.fill([9.0, 0.0, 0.0]);
    b.albedo[4] = f32x3(WHITE_ALBEDO);
    b.irradiance[4] = f32x3(e1);
    for i in [0, 2, 6, 8] {
        b.albedo[i] = f32x3(WHITE_ALBEDO);
        b.irradiance[i] = f32x3(e2);
    }
    let cos_c = 1.0 / (1.0 + 8.0 / 9.0f64).sqrt();
    let theta_deg = libm::atan((8.0 / 9.0f64).sqrt()).to_degrees();
    let check = |opts: NcnsOptions, g: f64, what: &str| {
        let w = g * if opts.solid_angle_weight {
            cos_c.powi(3)
        } else {
            1.0
        };
        let want = (xyz_of_f32(e1) + 4.0 * w * xyz_of_f32(e2)) / (1.0 + 4.0 * w);
        let est = ncns(&b.aovs(), &opts);
        assert_vec3(est.xyz, want.to_array(), 1e-6, what);
        assert_eq!(est.n_samples, 5);
    };
    let gauss = libm::exp(-theta_deg * theta_deg / (2.0 * 15.0 * 15.0));
    check(NcnsOptions::default(), gauss, "gaussian, cos³");
    let cosk = NcnsOptions {
        axis_weight: AxisWeight::CosPower,
        solid_angle_weight: false,
        ..Default::default()
    };
    check(cosk, cos_c.powi(8), "cos^8");
    assert_rel(
        gauss,
        libm::exp(-(theta_deg / 15.0).powi(2) / 2.0),
        1e-12,
        "sanity",
    );
}

#[test]
fn dominant_picks_the_most_powerful_light() {
    let red = DVec3::new(1.0, 0.1, 0.1);
    let green = DVec3::new(0.1, 1.0, 0.1);
    let blue = DVec3::new(0.1, 0.1, 1.0);
    let lights = [
        LightPower {
            emission_rgb: red * 4.0,
            flux_y: 5.0,
        },
        LightPower {
            emission_rgb: green * 4.0,
            flux_y: 9.0,
        },
        LightPower {
            emission_rgb: blue * 4.0,
            flux_y: 2.0,
        },
    ];
    let est = dominant(&lights);
    assert_vec3(
        est.xyz,
        rgb_to_xyz(green * 4.0).to_array(),
        1e-15,
        "absolute XYZ of the emission",
    );
    assert_eq!(est.normalized().y, 1.0);
    assert_eq!(est.n_samples, 3);
    assert!(est.flags.is_empty());
}

#[test]
fn dominant_breaks_ties_by_lowest_index() {
    let l = |c: f64, flux_y| LightPower {
        emission_rgb: DVec3::new(c, 1.0, 1.0),
        flux_y,
    };
    let lights = [l(0.1, 1.0), l(0.2, 7.0), l(0.3, 7.0), l(0.4, 7.0)];
    assert_eq!(dominant_light_index(&lights), Some(1));
    assert_eq!(dominant(&lights).xyz, rgb_to_xyz(DVec3::new(0.2, 1.0, 1.0)));
}
