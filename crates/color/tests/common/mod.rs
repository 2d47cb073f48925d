//! Helpers shared by the integration tests: tolerant comparisons that print
//! both values, and owned synthetic AOV buffers.

#![allow(dead_code, reason = "each test binary uses a different subset")]

use eyeadapt_color::FrameAovs;
use glam::{DMat3, DVec2, DVec3};

/// The spec's default oracle tolerance (estimators.md: "1e-6 relative").
pub const REL: f64 = 1e-6;

/// |a − b| ≤ rel·|b| (+ a tiny absolute floor for expected zeros).
#[track_caller]
pub fn assert_rel(actual: f64, expected: f64, rel: f64, what: &str) {
    let tol = rel * expected.abs() + 1e-12;
    assert!(
        (actual - expected).abs() <= tol,
        "{what}: got {actual:.12}, expected {expected:.12} (|diff| = {:.3e} > {tol:.3e})",
        (actual - expected).abs()
    );
}

#[track_caller]
pub fn assert_vec3(actual: DVec3, expected: [f64; 3], rel: f64, what: &str) {
    for c in 0..3 {
        assert_rel(
            actual[c],
            expected[c],
            rel,
            &format!("{what}[{c}] (got {actual:?})"),
        );
    }
}

#[track_caller]
pub fn assert_vec2(actual: DVec2, expected: [f64; 2], rel: f64, what: &str) {
    for c in 0..2 {
        assert_rel(
            actual[c],
            expected[c],
            rel,
            &format!("{what}[{c}] (got {actual:?})"),
        );
    }
}

/// Compares a matrix with rows as printed in the spec.
#[track_caller]
pub fn assert_rows(m: DMat3, rows: [[f64; 3]; 3], rel: f64, what: &str) {
    for (r, row) in rows.iter().enumerate() {
        assert_vec3(m.row(r), *row, rel, &format!("{what} row {r}"));
    }
}

/// Δu′v′ between an estimate's XYZ and a reference XYZ.
pub fn duv(a: DVec3, b: DVec3) -> f64 {
    let ua = eyeadapt_color::xyz_to_uv(a).expect("defined u'v'");
    let ub = eyeadapt_color::xyz_to_uv(b).expect("defined u'v'");
    eyeadapt_color::delta_uv(ua, ub)
}

/// Owned buffers behind a [`FrameAovs`]. Defaults: every pixel hits a
/// non-emitting surface, everything else zero.
#[derive(Clone)]
pub struct Buffers {
    pub width: usize,
    pub height: usize,
    pub rgb: Vec<[f32; 3]>,
    pub albedo: Vec<[f32; 3]>,
    pub achromatic: Vec<[f32; 3]>,
    pub irradiance: Vec<[f32; 3]>,
    pub emitter: Vec<f32>,
    pub hit: Vec<f32>,
    pub fov_y_deg: f64,
}

impl Buffers {
    pub fn new(width: usize, height: usize) -> Self {
        let n = width * height;
        Buffers {
            width,
            height,
            rgb: vec![[0.0; 3]; n],
            albedo: vec![[0.0; 3]; n],
            achromatic: vec![[0.0; 3]; n],
            irradiance: vec![[0.0; 3]; n],
            emitter: vec![0.0; n],
            hit: vec![1.0; n],
            fov_y_deg: 60.0,
        }
    }

    pub fn aovs(&self) -> FrameAovs<'_> {
        FrameAovs {
            width: self.width,
            height: self.height,
            rgb: &self.rgb,
            albedo: &self.albedo,
            achromatic: &self.achromatic,
            irradiance: &self.irradiance,
            emitter: &self.emitter,
            hit: &self.hit,
            fov_y_deg: self.fov_y_deg,
        }
    }
}

pub fn f32x3(v: DVec3) -> [f32; 3] {
    [v.x as f32, v.y as f32, v.z as f32]
}

/// The XYZ an f32-stored linear RGB colour really has (what the estimators see).
pub fn xyz_of_f32(v: DVec3) -> DVec3 {
    let s = f32x3(v);
    eyeadapt_color::rgb_to_xyz(DVec3::new(s[0] as f64, s[1] as f64, s[2] as f64))
}
