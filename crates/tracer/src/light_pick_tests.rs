//! Tests of the light choice: spatial importance for few units, and the light tree's
//! exactness (every light that can contribute keeps a positive probability, none that
//! cannot is chosen, `pick` and `prob` agree bit for bit) and its χ² against `prob`.
use super::*;

fn quad_light(y: f32, z: f32, emission: Vec3A) -> (Vec<AreaTri>, Parallelogram) {
    // 1 m × 1 m at height y, centred on (0, y, z), facing down.
    let o = Vec3A::new(-0.5, y, z - 0.5);
    let e1 = Vec3A::new(1.0, 0.0, 0.0);
    let e2 = Vec3A::new(0.0, 0.0, 1.0);
    let n = e1.cross(e2).normalize(); // −y
    let tri = |v0: Vec3A, a: Vec3A, b: Vec3A| AreaTri {
        v0,
        e1: a - v0,
        e2: b - v0,
        n,
        area: 0.5,
        emission,
        texture: u32::MAX,
        scale: emission,
        uv: [glam::Vec2::ZERO, glam::Vec2::X, glam::Vec2::Y],
    };
    (
        vec![tri(o, o + e1, o + e2), tri(o + e1 + e2, o + e2, o + e1)],
        Parallelogram { o, e1, e2 },
    )
}

fn two_rooms() -> LightPicker {
    let (mut area, q0) = quad_light(3.0, 0.0, Vec3A::ONE);
    let (b, q1) = quad_light(3.0, -6.0, Vec3A::ONE);
    area.extend(b);
    LightPicker::build(&area, &[0, 0, 1, 1], &[q0, q1], &[], None, 10.0)
}

#[test]
fn the_near_light_gets_most_of_the_choices_and_probabilities_sum_to_one() {
    let p = two_rooms();
    assert!(p.is_spatial());
    assert_eq!(p.units.len(), 2);
    let x = Vec3A::new(0.3, 0.0, -0.5);
    let n = Some(Vec3A::Y);
    let (p0, p1) = (p.prob(0, x, n), p.prob(1, x, n));
    assert!((p0 + p1 - 1.0).abs() < 1e-6, "{p0} + {p1}");
    assert!(p0 > 0.8, "near light only gets {p0}");
    // pick agrees with prob, and u sweeps across both units in order.
    let (k, pk) = p.pick(x, n, 0.1).unwrap();
    assert_eq!((k, pk), (0, p0));
    let (k, pk) = p.pick(x, n, 0.999).unwrap();
    assert_eq!((k, pk), (1, p1));
}

#[test]
fn units_that_cannot_contribute_get_nothing() {
    let p = two_rooms();
    // Above both lights: behind their emitting side.
    assert!(p.pick(Vec3A::new(0.0, 4.0, 0.0), None, 0.5).is_none());
    // A floor facing down sees neither light.
    assert!(
        p.pick(Vec3A::new(0.0, 0.0, 0.0), Some(-Vec3A::Y), 0.5)
            .is_none()
    );
    // A wall at z = -3 facing +z sees only the light at z = 0.
    let x = Vec3A::new(0.0, 1.0, -3.0);
    assert_eq!(p.prob(1, x, Some(Vec3A::Z)), 0.0);
    assert_eq!(p.prob(0, x, Some(Vec3A::Z)), 1.0);
    // ... even at the edge of the other light's plane: one corner just above the tangent
    // plane keeps it choosable.
    let x = Vec3A::new(0.0, 1.0, -6.49);
    assert!(p.prob(1, x, Some(Vec3A::Z)) > 0.0);
}

/// 24 quad lights facing every way, 6 points, 6 spots, a directional light and the
/// environment, over a 20 m box: a picker with a tree.
fn many_lights() -> (LightPicker, Vec<AreaTri>) {
    let key = crate::sampler::hash_key(&[5150]);
    let r = |i: u32| crate::sampler::SampleStream::new(key, i).next_2d();
    let unit_dir = |i: u32| {
        let [a, b] = r(i);
        let z = 1.0 - 2.0 * a;
        let s = (1.0 - z * z).max(0.0).sqrt();
        Vec3A::new(
            s * libm::cosf(2.0 * PI * b),
            s * libm::sinf(2.0 * PI * b),
            z,
        )
    };
    let pos = |i: u32| {
        let ([a, b], [c, _]) = (r(i), r(i + 7777));
        Vec3A::new(a, b, c) * 20.0 - 10.0
    };
    let mut area = Vec::new();
    let mut quads = Vec::new();
    let mut quad_of = Vec::new();
    for k in 0..24u32 {
        let n = unit_dir(100 + k);
        let t = n.any_orthonormal_vector();
        let (e1, e2) = (t * 0.5, n.cross(t) * 0.5);
        let o = pos(200 + k);
        let tri = |v0: Vec3A, a: Vec3A, b: Vec3A| AreaTri::new([v0, a, b], Vec3A::ONE).unwrap();
        area.push(tri(o, o + e2, o + e1));
        area.push(tri(o + e1 + e2, o + e1, o + e2));
        quad_of.extend([k, k]);
        quads.push(Parallelogram { o, e1: e2, e2: e1 });
    }
    let mut deltas = Vec::new();
    for k in 0..6u32 {
        deltas.push(DeltaLight::Point {
            position: pos(300 + k),
            intensity: Vec3A::splat(1.0 + k as f32),
        });
        deltas.push(DeltaLight::Spot {
            position: pos(400 + k),
            direction: unit_dir(500 + k),
            intensity: Vec3A::splat(2.0),
            cos_cone: 0.8,
            cos_falloff: 0.9,
            cone: libm::acosf(0.8f32),
            inv_transition: 1.0 / (libm::acosf(0.8f32) - libm::acosf(0.9f32)),
        });
    }
    deltas.push(DeltaLight::Directional {
        direction: -Vec3A::Y,
        irradiance: Vec3A::splat(0.5),
    });
    let p = LightPicker::build(
        &area,
        &quad_of,
        &quads,
        &deltas,
        Some(Vec3A::splat(0.1)),
        20.0,
    );
    (p, area)
}

#[test]
fn the_light_tree_keeps_every_light_that_can_contribute_and_probabilities_exact() {
    let (p, _) = many_lights();
    assert!(p.has_tree() && p.is_spatial());
    assert_eq!(p.units.len(), 24 + 12 + 2);
    let key = crate::sampler::hash_key(&[61]);
    let (mut zeros_right, mut chosen) = (0, 0);
    let (mut kept, mut reachable) = (0.0f64, 0u32);
    for i in 0..3000u32 {
        let mut st = crate::sampler::SampleStream::new(key, i);
        let [a, b] = st.next_2d();
        let [c, d] = st.next_2d();
        let x = Vec3A::new(a, b, c) * 24.0 - 12.0;
        let z = 1.0 - 2.0 * d;
        let phi = 2.0 * PI * st.next_1d();
        let s = (1.0 - z * z).max(0.0).sqrt();
        let n = (i % 3 != 0).then(|| Vec3A::new(s * libm::cosf(phi), s * libm::sinf(phi), z));
        let probs: Vec<f32> = (0..p.units.len()).map(|k| p.prob(k, x, n)).collect();
        let sum: f32 = probs.iter().sum();
        let any = (0..p.units.len()).any(|k| importance(&p.bounds[k], x, n) > 0.0);
        // A walk may end where a node's bounds reach x but none of its children's do:
        // that share of the choices is lost (no light sample), never given to a light
        // that cannot contribute, so the sum is at most 1.
        assert!(sum < 1.0 + 1e-4, "Σ prob = {sum} at {x:?}");
        if any {
            kept += sum as f64;
            reachable += 1;
        } else {
            assert_eq!(sum, 0.0);
        }
        for (k, &pk) in probs.iter().enumerate() {
            let can = importance(&p.bounds[k], x, n) > 0.0;
            // Never 0 where the light can contribute; never chosen where it cannot.
            assert_eq!(pk > 0.0, can, "unit {k} at {x:?} n {n:?}: prob {pk}");
            zeros_right += (!can) as u32;
        }
        for u in [0.0, 0.3, 0.77, 1.0 - f32::EPSILON] {
            if let Some((k, pk)) = p.pick(x, n, u) {
                assert_eq!(pk, probs[k], "pick and prob agree for unit {k}");
                chosen += 1;
            }
        }
    }
    assert!(
        zeros_right > 1000 && chosen > 10_000,
        "{zeros_right} {chosen}"
    );
    let kept = kept / reachable as f64;
    eprintln!("mean share of choices that reach a light: {kept:.4}");
    // 0.933 here, where lights and receivers face every way (in a room far fewer are lost).
    assert!(kept > 0.9, "{kept}");
}

#[test]
fn the_light_tree_chooses_in_proportion_to_its_probabilities() {
    let (p, _) = many_lights();
    let (x, n) = (Vec3A::new(1.0, -2.0, 0.5), Some(Vec3A::new(0.0, 1.0, 0.0)));
    let count = 200_000u32;
    let mut hits = vec![0u32; p.units.len()];
    let mut lost = 0u32;
    let key = crate::sampler::hash_key(&[62]);
    for i in 0..count {
        let u = crate::sampler::SampleStream::new(key, i).next_1d();
        match p.pick(x, n, u) {
            Some((k, _)) => hits[k] += 1,
            None => lost += 1,
        }
    }
    let lost_p = 1.0
        - (0..p.units.len())
            .map(|k| p.prob(k, x, n) as f64)
            .sum::<f64>();
    let e = lost_p * count as f64;
    let mut chi2 = if e > 0.5 {
        (lost as f64 - e).powi(2) / e
    } else {
        0.0
    };
    let mut dof = 0;
    for (k, &h) in hits.iter().enumerate() {
        let e = p.prob(k, x, n) as f64 * count as f64;
        if e > 0.0 {
            chi2 += (h as f64 - e).powi(2) / e;
            dof += 1;
        } else {
            assert_eq!(h, 0, "unit {k} has probability 0 but was chosen");
        }
    }
    // χ² with dof − 1 degrees of freedom; 0.999 quantile below dof + 4.5·√(2·dof).
    let bound = dof as f64 + 4.5 * (2.0 * dof as f64).sqrt();
    assert!(dof > 10 && chi2 < bound, "χ² {chi2:.1} over {dof} units");
}

#[test]
fn one_unit_goes_by_power_and_many_through_a_tree() {
    let (area, q) = quad_light(3.0, 0.0, Vec3A::ONE);
    let one = LightPicker::build(&area, &[0, 0], &[q], &[], None, 10.0);
    assert!(!one.is_spatial());
    assert_eq!(
        one.pick(Vec3A::new(0.0, 4.0, 0.0), None, 0.3),
        Some((0, 1.0))
    );
    let points: Vec<DeltaLight> = (0..=SPATIAL_MAX_UNITS)
        .map(|i| DeltaLight::Point {
            position: Vec3A::new(i as f32, 1.0, 0.0),
            intensity: Vec3A::splat(1.0 + i as f32),
        })
        .collect();
    let many = LightPicker::build(&[], &[], &[], &points, None, 10.0);
    // (More than SPATIAL_MAX_UNITS now choose through a light tree.)
    assert!(many.has_tree());
    let total: f64 = (0..many.units.len()).map(|k| many.power_prob(k)).sum();
    assert!((total - 1.0).abs() < 1e-12);
    assert!(many.power_prob(SPATIAL_MAX_UNITS) > many.power_prob(0));
}

#[test]
fn portals_scale_the_environment_by_the_sky_they_show() {
    use eyeadapt_scene::Portal;
    // A window 1 m × 1 m in the wall z = 0 facing −z (u × v); the room is z < 0.
    let window = [Portal {
        corner: glam::Vec3::new(2.0, 1.0, 0.0),
        u: glam::Vec3::new(0.0, 1.0, 0.0),
        v: glam::Vec3::new(1.0, 0.0, 0.0),
    }];
    let portals = crate::portal::Portals::new(&window);
    let (area, q) = quad_light(3.0, -6.0, Vec3A::ONE);
    let env = Some(Vec3A::splat(0.5));
    let open = LightPicker::build(&area, &[0, 0], &[q], &[], env, 10.0);
    let (area, q) = quad_light(3.0, -6.0, Vec3A::ONE);
    let room = LightPicker::build(&area, &[0, 0], &[q], &[], env, 10.0).through(portals.clone());
    let (x, n) = (Vec3A::new(0.0, 0.0, -4.0), Some(Vec3A::Y));
    let env_unit = open.units.len() - 1;
    let (a, b) = (open.prob(env_unit, x, n), room.prob(env_unit, x, n));
    // The environment's importance shrinks by the window's share of the sky.
    let share = portals.sky_share(x);
    assert!(share < 0.05, "{share}");
    let (wa, wb) = (a / (1.0 - a), b / (1.0 - b));
    assert!((wb / wa - share).abs() < 1e-3 * share, "{wa} {wb} {share}");
    // pick and prob agree, and every unit keeps its probability where it can contribute.
    for u in [0.0, 0.01, 0.5, 0.99] {
        let (k, p) = room.pick(x, n, u).unwrap();
        assert_eq!(p, room.prob(k, x, n));
    }
    assert!(b > 0.0 && (room.prob(0, x, n) + b - 1.0).abs() < 1e-6);
    // Outdoors (no portal serves the point) nothing changes, bit for bit.
    let out = Vec3A::new(0.0, 0.0, 4.0);
    assert_eq!(
        open.prob(env_unit, out, None),
        room.prob(env_unit, out, None)
    );
}

#[test]
fn portals_scale_the_environment_beside_a_light_tree() {
    use eyeadapt_scene::Portal;
    let (p, _) = many_lights();
    let window = [Portal {
        corner: glam::Vec3::new(-1.0, -1.0, 12.0),
        u: glam::Vec3::new(0.0, 2.0, 0.0),
        v: glam::Vec3::new(2.0, 0.0, 0.0),
    }];
    let (q, _) = many_lights();
    let q = q.through(crate::portal::Portals::new(&window));
    let env = p.units.iter().position(|u| *u == Unit::Env).unwrap();
    let (x, n) = (Vec3A::new(1.0, -2.0, 0.5), Some(Vec3A::new(0.0, 0.0, 1.0)));
    let (a, b) = (p.prob(env, x, n), q.prob(env, x, n));
    assert!(b > 0.0 && b < 0.5 * a, "{a} {b}");
    let sum: f32 = (0..q.units.len()).map(|k| q.prob(k, x, n)).sum();
    assert!(sum <= 1.0 + 1e-4, "{sum}");
    for u in [0.0, 0.3, 0.999] {
        if let Some((k, pk)) = q.pick(x, n, u) {
            assert_eq!(pk, q.prob(k, x, n));
        }
    }
}

#[test]
fn behind_portals_the_sun_keeps_its_weight_only_where_its_direction_crosses_one() {
    use eyeadapt_scene::Portal;
    // A window 1 m × 1 m in the wall z = 0 facing −z, x in [2, 3], y in [1, 2]; the sun
    // shines through it along (−1, −1, −2)/√6 (towards the room).
    let window = [Portal {
        corner: glam::Vec3::new(2.0, 1.0, 0.0),
        u: glam::Vec3::new(0.0, 1.0, 0.0),
        v: glam::Vec3::new(1.0, 0.0, 0.0),
    }];
    let direction = Vec3A::new(-1.0, -1.0, -2.0).normalize();
    let sun = [DeltaLight::Directional {
        direction,
        irradiance: Vec3A::splat(5.0),
    }];
    let build = || {
        let (area, q) = quad_light(3.0, -6.0, Vec3A::ONE);
        LightPicker::build(&area, &[0, 0], &[q], &sun, None, 10.0)
    };
    let open = build();
    let room = build().through(crate::portal::Portals::new(&window));
    let n = Some(Vec3A::Y);
    // On the floor (y = 0) the window's sunlight lands 1.5 m in from x ∈ [2, 3] and so on:
    // the point (2, 0, −3) sees the sun through it, (−2, 0, −3) does not.
    let lit = Vec3A::new(1.5, 0.0, -3.0);
    let shade = Vec3A::new(-2.0, 0.0, -3.0);
    assert_eq!(
        crate::portal::Portals::new(&window).lets_through(lit, -direction),
        Some(true)
    );
    assert_eq!(open.prob(1, lit, n), room.prob(1, lit, n), "lit: unchanged");
    let odds = |p: &LightPicker| p.prob(1, shade, n) / p.prob(0, shade, n);
    let ratio = odds(&room) / odds(&open);
    assert!((ratio - BEHIND_PORTALS).abs() < 1e-4, "{ratio}");
    // Still choosable where the portals say no (they may not cover every opening).
    assert!(room.prob(1, shade, n) > 0.0);
    for u in [0.0, 0.02, 0.5, 0.999] {
        let (k, p) = room.pick(shade, n, u).unwrap();
        assert_eq!(p, room.prob(k, shade, n));
    }
}

/// A random quad (`quad`) or triangle light at `o` with edges `e1`, `e2`, facing e1 × e2.
fn area_light(o: Vec3A, e1: Vec3A, e2: Vec3A, emission: Vec3A, quad: bool) -> Vec<AreaTri> {
    let c = e1.cross(e2);
    let tri = |v0: Vec3A, a: Vec3A, b: Vec3A| AreaTri {
        v0,
        e1: a - v0,
        e2: b - v0,
        n: c.normalize(),
        area: 0.5 * c.length(),
        emission,
        texture: u32::MAX,
        scale: emission,
        uv: [glam::Vec2::ZERO, glam::Vec2::X, glam::Vec2::Y],
    };
    let mut t = vec![tri(o, o + e1, o + e2)];
    if quad {
        t.push(tri(o + e1 + e2, o + e2, o + e1));
    }
    t
}

#[test]
fn four_area_units_at_a_time_weigh_bit_for_bit_what_one_does() {
    // A fixed xorshift stream: the same cases on every run.
    let mut s = 0x9e37_79b9_7f4a_7c15u64;
    let mut f = move || {
        s ^= s << 13;
        s ^= s >> 7;
        s ^= s << 17;
        (s >> 40) as f32 / (1u64 << 24) as f32
    };
    let v = |f: &mut dyn FnMut() -> f32, r: f32| {
        Vec3A::new(f() * 2.0 - 1.0, f() * 2.0 - 1.0, f() * 2.0 - 1.0) * r
    };
    // Cases, and among them units weighed 0 and units weighed more.
    let (mut cases, mut zero, mut positive) = (0, 0, 0);
    for scene in 0..60 {
        // 1 ..= 16 area units (and beside them a point light and the sky, up to 16 units).
        let n_area = 1 + scene % 16;
        let (mut area, mut quad_of, mut quads) = (Vec::new(), Vec::new(), Vec::new());
        for k in 0..n_area {
            let (o, e1, e2) = (v(&mut f, 4.0), v(&mut f, 1.5), v(&mut f, 1.5));
            // Some black lights (no power) and axis-aligned ones (exact zeros in the tests).
            let emission = if k % 7 == 3 {
                Vec3A::ZERO
            } else {
                v(&mut f, 5.0).abs()
            };
            let (e1, e2) = if k % 3 == 0 {
                (Vec3A::new(e1.x, 0.0, 0.0), Vec3A::new(0.0, 0.0, e2.z))
            } else {
                (e1, e2)
            };
            let quad = k % 2 == 0;
            let t = area_light(o, e1, e2, emission, quad);
            let q = if quad { quads.len() as u32 } else { u32::MAX };
            if quad {
                quads.push(Parallelogram { o, e1, e2 });
            }
            quad_of.extend(t.iter().map(|_| q));
            area.extend(t);
        }
        let point = DeltaLight::Point {
            position: v(&mut f, 3.0),
            intensity: Vec3A::ONE,
        };
        let others = (16 - n_area).min(2);
        let deltas = if others >= 1 { vec![point] } else { vec![] };
        let env = (others >= 2).then_some(Vec3A::splat(0.3));
        let p = LightPicker::build(&area, &quad_of, &quads, &deltas, env, 10.0);
        assert!(p.is_spatial() && p.area4.len() == n_area);
        // Random points and normals, and points where the exact zero tests are decided: on
        // a unit's plane, at its corners and centre, just in front of and behind it.
        let mut points: Vec<Vec3A> = (0..40).map(|_| v(&mut f, 6.0)).collect();
        for b in &p.bounds {
            if let Bounds::Area(a) = b {
                points.extend(a.corners);
                points.push(a.centre);
                points.push((a.corners[0] + a.corners[1]) * 0.5);
                for h in [1e-6, -1e-6, 1e-3, -1e-3] {
                    points.push(a.centre + a.normal * h);
                    points.push(a.corners[2] + a.normal * h);
                }
                points.push(a.centre + a.normal * 1e20);
            }
        }
        for (i, &x) in points.iter().enumerate() {
            let to_light = match p.bounds[i % n_area] {
                Bounds::Area(a) => a.centre - x,
                _ => unreachable!(),
            };
            let normals = [
                None,
                Some(v(&mut f, 1.0).normalize_or(Vec3A::Y)),
                Some(to_light.normalize_or(Vec3A::Y)),
                Some(-to_light.normalize_or(Vec3A::Y)),
                // Edge-on to the light's plane, and axis-aligned.
                Some(to_light.cross(Vec3A::Y).normalize_or(Vec3A::X)),
                Some(Vec3A::Y),
                Some(-Vec3A::X),
            ];
            for n in normals {
                let mut w = [f32::NAN; SPATIAL_MAX_UNITS];
                p.area4.importances(x, n, &mut w);
                let mut total = 0.0f32;
                for (k, b) in p.bounds.iter().enumerate() {
                    let one = unit_importance(b, x, n, p.behind(x));
                    if k < n_area {
                        assert_eq!(w[k].to_bits(), one.to_bits(), "unit {k} at {x} n {n:?}");
                        *(if one > 0.0 { &mut positive } else { &mut zero }) += 1;
                    }
                    total += one;
                }
                let mut all = [0.0; SPATIAL_MAX_UNITS];
                assert_eq!(p.importances(x, n, &mut all).to_bits(), total.to_bits());
                cases += 1;
            }
        }
    }
    assert!(
        cases > 10_000 && zero > 10_000 && positive > 10_000,
        "{cases} cases, {zero} zero and {positive} positive weights"
    );
}
