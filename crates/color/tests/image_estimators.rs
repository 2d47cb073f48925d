//! The §5 colour-constancy estimators on synthetic frames: a colour c times a
//! neutral texture must give back c's chromaticity; masked pixels (emitters,
//! non-finite values) must have no influence at all; options behave as documented.

mod common;

use common::{Buffers, assert_vec3, duv, f32x3, xyz_of_f32};
use eyeadapt_color::*;
use glam::DVec3;

const W: usize = 48;
const H: usize = 36;
const ORANGE: DVec3 = DVec3::new(1.0, 0.6, 0.3);

/// A smooth-plus-rough neutral texture in [0.25, 1.75], deterministic.
fn texture(x: usize, y: usize) -> f64 {
    let (xf, yf) = (x as f64, y as f64);
    let smooth = 0.5 * libm::sin(0.7 * xf + 0.3 * yf) * libm::cos(0.45 * yf - 0.2 * xf);
    let rough = ((x * 7919 + y * 104_729) % 97) as f64 / 97.0 - 0.5;
    1.0 + smooth + 0.5 * rough
}

/// Every pixel is c · t(x, y).
fn textured(c: DVec3) -> Buffers {
    let mut b = Buffers::new(W, H);
    for y in 0..H {
        for x in 0..W {
            b.rgb[y * W + x] = f32x3(c * texture(x, y));
        }
    }
    b
}

type Method = (&'static str, Box<dyn Fn(&FrameAovs) -> Estimate>);

/// Every image estimator and mode, with defaults unless named otherwise.
fn methods() -> Vec<Method> {
    let wp = |mode| WhitePatchOptions {
        mode,
        ..Default::default()
    };
    vec![
        (
            "grey_world",
            Box::new(|a: &FrameAovs| grey_world(a, &Default::default())),
        ),
        (
            "shades_of_grey",
            Box::new(|a: &FrameAovs| shades_of_grey(a, &Default::default())),
        ),
        (
            "general_grey_world σ=2",
            Box::new(|a: &FrameAovs| {
                shades_of_grey(
                    a,
                    &ShadesOfGreyOptions {
                        sigma: 2.0,
                        ..Default::default()
                    },
                )
            }),
        ),
        (
            "white_patch top",
            Box::new(move |a: &FrameAovs| white_patch(a, &wp(WhitePatchMode::TopPercent))),
        ),
        (
            "white_patch pct",
            Box::new(move |a: &FrameAovs| {
                white_patch(a, &wp(WhitePatchMode::PerChannelPercentile))
            }),
        ),
        (
            "white_patch max",
            Box::new(move |a: &FrameAovs| white_patch(a, &wp(WhitePatchMode::Max))),
        ),
        (
            "grey_edge n=1",
            Box::new(|a: &FrameAovs| grey_edge(a, &Default::default())),
        ),
        (
            "grey_edge n=2",
            Box::new(|a: &FrameAovs| {
                grey_edge(
                    a,
                    &GreyEdgeOptions {
                        n: 2,
                        ..Default::default()
                    },
                )
            }),
        ),
        (
            "grey_edge n=1 p=∞ σ=2",
            Box::new(|a: &FrameAovs| {
                grey_edge(
                    a,
                    &GreyEdgeOptions {
                        p: f64::INFINITY,
                        sigma: 2.0,
                        ..Default::default()
                    },
                )
            }),
        ),
    ]
}

#[test]
fn constant_image_gives_its_colour_in_absolute_units() {
    let mut b = Buffers::new(W, H);
    b.rgb.fill(f32x3(3.0 * ORANGE));
    let want = xyz_of_f32(3.0 * ORANGE);
    for est in [
        grey_world(&b.aovs(), &Default::default()),
        shades_of_grey(&b.aovs(), &Default::default()),
        white_patch(&b.aovs(), &Default::default()),
    ] {
        assert!(est.is_valid() && est.flags.is_empty(), "{est:?}");
        assert_vec3(est.xyz, want.to_array(), 1e-12, "absolute XYZ");
        assert_eq!(est.normalized().y, 1.0);
        assert_eq!(est.n_samples, (W * H) as u64);
        assert!(duv(est.normalized(), want) < 1e-12);
    }
}

#[test]
fn textured_image_gives_the_illuminant_chromaticity() {
    let b = textured(ORANGE);
    let want = xyz_of_f32(ORANGE);
    for (name, run) in methods() {
        let est = run(&b.aovs());
        assert!(est.is_valid(), "{name}: {est:?}");
        let d = duv(est.xyz, want);
        assert!(d < 1e-6, "{name}: Δu'v' = {d:e}");
    }
}

#[test]
fn masked_pixels_have_no_influence() {
    let base = textured(ORANGE);
    let bad = [0usize, 5 * W + 7, 5 * W + 8, 20 * W + 30, H * W - 1];
    // Reference: the same pixels flagged as emitters but with ordinary values.
    let mut reference = base.clone();
    for &i in &bad {
        reference.emitter[i] = 1.0;
    }
    // Crazy emitter colours at those pixels.
    let mut crazy = reference.clone();
    for &i in &bad {
        crazy.rgb[i] = [1e6, 0.0, 3e4];
    }
    // Non-finite values at those pixels, not flagged as emitters.
    let mut broken = base.clone();
    for (k, &i) in bad.iter().enumerate() {
        broken.rgb[i] = [
            [f32::NAN, 1.0, 1.0],
            [f32::INFINITY, 0.0, 0.0],
            [1.0, f32::NEG_INFINITY, 0.0],
        ][k % 3];
    }
    for (name, run) in methods() {
        let r = run(&reference.aovs());
        let c = run(&crazy.aovs());
        assert_eq!(
            (r.xyz, r.n_samples),
            (c.xyz, c.n_samples),
            "{name}: emitter values leaked"
        );
        let n = run(&broken.aovs());
        assert_eq!(
            (r.xyz, r.n_samples),
            (n.xyz, n.n_samples),
            "{name}: non-finite values leaked"
        );
        assert!(
            n.flags.contains(&flags::DROPPED_NON_FINITE),
            "{name}: {:?}",
            n.flags
        );
        assert!(duv(c.xyz, xyz_of_f32(ORANGE)) < 1e-6, "{name}");
    }
}

#[test]
fn partial_emitter_pixels_are_masked_too() {
    let mut b = textured(ORANGE);
    b.emitter[3] = 0.25;
    b.rgb[3] = [0.0, 0.0, 1e5];
    let est = grey_world(&b.aovs(), &Default::default());
    assert_eq!(est.n_samples, (W * H - 1) as u64);
    assert!(duv(est.xyz, xyz_of_f32(ORANGE)) < 1e-6);
}

#[test]
fn filtered_methods_drop_the_border() {
    let b = textured(ORANGE);
    // σ = 1: border ⌈σ⌉ + 1 = 2 pixels on each side.
    let est = grey_edge(&b.aovs(), &Default::default());
    assert_eq!(est.n_samples, ((W - 4) * (H - 4)) as u64);
    // σ = 2: 3 pixels.
    let est = grey_edge(
        &b.aovs(),
        &GreyEdgeOptions {
            sigma: 2.0,
            ..Default::default()
        },
    );
    assert_eq!(est.n_samples, ((W - 6) * (H - 6)) as u64);
}

#[test]
fn all_masked_is_undefined() {
    let mut b = textured(ORANGE);
    b.emitter.fill(1.0);
    for (name, run) in methods() {
        let est = run(&b.aovs());
        assert!(
            !est.is_valid() && est.flags.contains(&flags::EMPTY_MASK),
            "{name}: {est:?}"
        );
        assert!(est.normalized().is_nan());
    }
    // A black frame has pixels but no light: every method is zero, hence
    // invalid, and says so.
    let black = Buffers::new(W, H);
    for (name, run) in methods() {
        let est = run(&black.aovs());
        assert!(
            !est.is_valid() && est.flags.contains(&flags::INVALID_XYZ),
            "{name}: {est:?}"
        );
    }
}

#[test]
fn clipping_tames_a_firefly() {
    let grey = DVec3::splat(0.5);
    let mut b = textured(grey);
    b.rgb[W * 10 + 10] = [5e4, 0.0, 0.0];
    let raw = white_patch(
        &b.aovs(),
        &WhitePatchOptions {
            mode: WhitePatchMode::Max,
            ..Default::default()
        },
    );
    let clipped = white_patch(
        &b.aovs(),
        &WhitePatchOptions {
            mode: WhitePatchMode::Max,
            clip_percentile: Some(99.9),
            ..Default::default()
        },
    );
    let (d_raw, d_clipped) = (duv(raw.xyz, grey), duv(clipped.xyz, grey));
    assert!(
        d_raw > 0.1,
        "the firefly should dominate max-RGB: Δu'v' = {d_raw}"
    );
    // Not exactly grey: each channel is clipped at its own 99.9th percentile, and
    // the firefly shifts that rank in red only.
    assert!(
        d_clipped < d_raw / 10.0,
        "Δu'v' raw {d_raw}, clipped {d_clipped}"
    );
}

#[test]
fn huge_exponents_and_values_do_not_overflow() {
    let b = textured(ORANGE * 1e20);
    let opts = ShadesOfGreyOptions {
        p: 500.0,
        ..Default::default()
    };
    let est = shades_of_grey(&b.aovs(), &opts);
    assert!(est.is_valid(), "{est:?}");
    assert!(duv(est.xyz, xyz_of_f32(ORANGE)) < 1e-5);
}

#[test]
fn grey_world_is_the_mean_colour() {
    // Two halves, red and blue: grey-world is their average.
    let mut b = Buffers::new(4, 2);
    for i in 0..8 {
        b.rgb[i] = if i < 4 {
            [0.8, 0.1, 0.1]
        } else {
            [0.1, 0.1, 0.4]
        };
    }
    let est = grey_world(&b.aovs(), &Default::default());
    let mean = (DVec3::new(0.8, 0.1, 0.1) + DVec3::new(0.1, 0.1, 0.4)) / 2.0;
    assert_vec3(
        est.xyz,
        xyz_of_f32(mean).to_array(),
        1e-6,
        "grey-world mean",
    );
}

#[test]
#[should_panic(expected = "grey_edge: n must be 1 or 2")]
fn invalid_options_panic_with_the_reason() {
    let b = textured(ORANGE);
    grey_edge(
        &b.aovs(),
        &GreyEdgeOptions {
            n: 0,
            ..Default::default()
        },
    );
}
