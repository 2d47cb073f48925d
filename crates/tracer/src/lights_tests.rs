//! Tests of the light set: light sampling stays exact whatever chooses the light, and quads
//! are sampled as parallelograms.
use super::*;
use crate::sampler::{SampleStream, hash_key};

/// A square light of side `s` at height `h` above the origin, facing down, as two triangles
/// split along either diagonal.
fn square_light(s: f32, h: f32, other_diagonal: bool) -> Vec<[Vec3A; 3]> {
    let c = |x: f32, z: f32| Vec3A::new(x, h, z);
    let (p0, p1, p2, p3) = (
        c(-s / 2.0, -s / 2.0),
        c(s / 2.0, -s / 2.0),
        c(s / 2.0, s / 2.0),
        c(-s / 2.0, s / 2.0),
    );
    // Winding so that e1 × e2 points down (−y): the emitting side faces the origin.
    let tris = if other_diagonal {
        [[p0, p1, p3], [p1, p2, p3]]
    } else {
        [[p0, p1, p2], [p0, p2, p3]]
    };
    tris.to_vec()
}

fn white(tris: &[[Vec3A; 3]]) -> Vec<AreaTri> {
    tris.iter()
        .map(|v| AreaTri::new(*v, Vec3A::ONE).unwrap())
        .collect()
}

/// Irradiance at the origin (normal +y) by light sampling, with `n` stratified samples;
/// `receiver` is the normal given to the light choice.
fn irradiance_with(lights: &LightSet, n: u32, receiver: Option<Vec3A>) -> f64 {
    let key = hash_key(&[7]);
    let normal = Vec3A::Y;
    let mut sum = 0.0f64;
    for i in 0..n {
        let mut st = SampleStream::new(key, i);
        let u_pick = st.next_1d();
        let _ = st.next_1d();
        let u = st.next_2d();
        if let Some(ls) = lights.sample(Vec3A::ZERO, receiver, u_pick, u) {
            if receiver.is_some() {
                assert!(ls.wi.y > 0.0, "a light below the tangent plane was chosen");
            }
            sum += (ls.li.x * ls.wi.dot(normal).max(0.0) / ls.pdf) as f64;
        }
    }
    sum / n as f64
}

fn irradiance(lights: &LightSet, n: u32) -> f64 {
    irradiance_with(lights, n, None)
}

/// Irradiance under a unit-radiance s × s square centred at height h above the receiver:
/// four s/2 × s/2 rectangles with a corner above it, each of form factor
/// (1/2π)[A/√(1+A²)·atan(B/√(1+A²)) + B/√(1+B²)·atan(A/√(1+B²))], A = B = s/2h.
fn square_irradiance(s: f32, h: f32) -> f64 {
    let a = (s / (2.0 * h)) as f64;
    let q = (1.0 + a * a).sqrt();
    let f = (2.0 * a / q * libm::atan(a / q)) / (2.0 * std::f64::consts::PI);
    std::f64::consts::PI * 4.0 * f
}

#[test]
fn choosing_by_shading_point_keeps_light_sampling_exact() {
    // Two lights above the receiver at different heights (so their choice probabilities
    // differ), one under it facing up (below its tangent plane) and one above it facing
    // away: the last two must never be chosen, the first two weighted exactly.
    let mut tris = square_light(1.0, 0.7, false);
    tris.extend(square_light(1.0, 1.5, true));
    let mut under = square_light(1.0, -0.5, false);
    let mut away = square_light(1.0, 1.0, false);
    for t in under.iter_mut().chain(away.iter_mut()) {
        t.swap(1, 2); // facing up
    }
    tris.extend(under);
    tris.extend(away);
    let lights = LightSet::build(white(&tris), &[], None, 10.0, &[]);
    assert!(lights.spatial_choice());
    assert_eq!(lights.parallelogram_count(), 4);
    let exact = square_irradiance(1.0, 0.7) + square_irradiance(1.0, 1.5);
    let e = irradiance_with(&lights, 16_384, Some(Vec3A::Y));
    assert!((e / exact - 1.0).abs() < 3e-3, "E {e} vs exact {exact}");
    // Without a receiver normal the light under the receiver is choosable (and its samples
    // count 0 here), but the estimate of the upper two stays exact.
    let e = irradiance_with(&lights, 16_384, None);
    assert!((e / exact - 1.0).abs() < 1e-2, "E {e} vs exact {exact}");
}

#[test]
fn many_lights_through_the_light_tree_keep_light_sampling_exact() {
    // 24 squares above the receiver (sizes 0.2-1.35 m, heights 0.6-3.4 m) and 8 under it
    // facing up, more than SPATIAL_MAX_UNITS: the choice goes through the tree.
    let mut tris = Vec::new();
    let mut exact = 0.0;
    for k in 0..24 {
        let (s, h) = (0.2 + 0.05 * k as f32, 0.6 + 0.12 * k as f32);
        tris.extend(square_light(s, h, k % 2 == 0));
        exact += square_irradiance(s, h);
    }
    for k in 0..8 {
        let mut under = square_light(1.0, -0.3 - 0.2 * k as f32, false);
        for t in under.iter_mut() {
            t.swap(1, 2);
        }
        tris.extend(under);
    }
    let lights = LightSet::build(white(&tris), &[], None, 10.0, &[]);
    assert!(lights.picker.has_tree());
    for receiver in [Some(Vec3A::Y), None] {
        let e = irradiance_with(&lights, 65_536, receiver);
        assert!(
            (e / exact - 1.0).abs() < 3e-3,
            "receiver {receiver:?}: E {e} vs exact {exact}"
        );
    }
}

#[test]
fn quads_are_sampled_as_parallelograms_with_unchanged_density() {
    let (s, h) = (1.0f32, 0.7f32);
    let exact = square_irradiance(s, h);
    for other in [false, true] {
        let tris = square_light(s, h, other);
        let lights = LightSet::build(white(&tris), &[], None, 10.0, &[]);
        assert_eq!(lights.parallelogram_count(), 1, "diagonal variant {other}");
        let e = irradiance(&lights, 1024);
        assert!((e / exact - 1.0).abs() < 2e-3, "E {e} vs exact {exact}");
    }
    // Two triangles that are not a parallelogram stay triangles.
    let mut tris = square_light(s, h, false);
    tris[1][2] += Vec3A::new(0.1, 0.0, 0.0);
    let lights = LightSet::build(white(&tris), &[], None, 10.0, &[]);
    assert_eq!(lights.parallelogram_count(), 0);
}

#[test]
fn a_parallelogram_is_less_noisy_than_its_halves() {
    // The same 256 stratified samples per estimate, 64 independent estimates: pairing the
    // halves must not add variance (it removes the noise of dealing samples to halves).
    let tris = square_light(1.0, 0.3, false);
    let paired = LightSet::build(white(&tris), &[], None, 10.0, &[]);
    let halves = LightSet::assemble(
        paired.area.clone(),
        vec![u32::MAX; 2],
        Vec::new(),
        Vec::new(),
        None,
        10.0,
    );
    let spread = |l: &LightSet| {
        let xs: Vec<f64> = (0..64u64)
            .map(|k| {
                let key = hash_key(&[k, 99]);
                let mut sum = 0.0;
                for i in 0..256 {
                    let mut st = SampleStream::new(key, i);
                    let u_pick = st.next_1d();
                    let _ = st.next_1d();
                    let u = st.next_2d();
                    if let Some(ls) = l.sample(Vec3A::ZERO, None, u_pick, u) {
                        sum += (ls.li.x * ls.wi.y.max(0.0) / ls.pdf) as f64;
                    }
                }
                sum / 256.0
            })
            .collect();
        let m = xs.iter().sum::<f64>() / xs.len() as f64;
        (xs.iter().map(|x| (x - m).powi(2)).sum::<f64>() / 63.0).sqrt() / m
    };
    let (p, h) = (spread(&paired), spread(&halves));
    eprintln!("relative spread of 256-sample estimates: paired {p:.2e}, halves {h:.2e}");
    assert!(
        p < 0.5 * h,
        "relative spread paired {p:.2e} vs halves {h:.2e}"
    );
}
