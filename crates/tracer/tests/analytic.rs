//! Renders with known answers: white furnace, closed emitting sphere, determinism across
//! thread counts, and the eye sensor's closed forms (estimators.md §1).
mod common;

use common::settings;
use eyeadapt_scene::{Camera, Light, Material, Mesh, Scene, sphere_mesh};
use eyeadapt_tracer::{EyeSettings, Frame, PathSettings, SceneData, View, eye_sensor, render};
use glam::{DVec3, Vec3};
use std::f64::consts::PI;

fn camera(position: Vec3, look_at: Vec3, w: u32, h: u32) -> Camera {
    Camera {
        position,
        look_at,
        up: Vec3::Y,
        fov_deg: 60.0,
        width: w,
        height: h,
        projection: eyeadapt_scene::Projection::Pinhole,
    }
}

/// Per-pixel mean and standard error over independent seeds.
fn mean_and_se(
    scene: &SceneData,
    view: &View,
    spp: u32,
    seeds: u64,
    max_depth: i32,
) -> Vec<([f64; 3], [f64; 3])> {
    let frames: Vec<Frame> = (0..seeds)
        .map(|s| render(scene, view, &settings(spp, s + 1, max_depth)))
        .collect();
    let n = frames[0].rgb.len();
    (0..n)
        .map(|i| {
            let mut mean = [0.0; 3];
            let mut se = [0.0; 3];
            for c in 0..3 {
                let xs: Vec<f64> = frames.iter().map(|f| f.rgb[i][c] as f64).collect();
                let m = xs.iter().sum::<f64>() / xs.len() as f64;
                let var = xs.iter().map(|x| (x - m).powi(2)).sum::<f64>() / (xs.len() as f64 - 1.0);
                mean[c] = m;
                se[c] = (var / xs.len() as f64).sqrt();
            }
            (mean, se)
        })
        .collect()
}

/// Checks every pixel against `expected`. With hundreds of pixels a 3σ band per pixel fails by
/// chance; 5σ per pixel plus 3σ on the image mean keeps the test both strict and stable.
fn assert_converges(px: &[([f64; 3], [f64; 3])], expected: [f64; 3]) {
    let mut worst = (0.0, 0);
    for (i, (m, se)) in px.iter().enumerate() {
        for c in 0..3 {
            let z = (m[c] - expected[c]).abs() / se[c].max(1e-6 * expected[c]);
            if z > worst.0 {
                worst = (z, i);
            }
        }
    }
    assert!(
        worst.0 < 5.0,
        "pixel {} is {:.2} standard errors off: {:?} vs {expected:?}",
        worst.1,
        worst.0,
        px[worst.1]
    );
    for (c, e) in expected.iter().enumerate() {
        let m = px.iter().map(|p| p.0[c]).sum::<f64>() / px.len() as f64;
        let se = (px.iter().map(|p| p.1[c] * p.1[c]).sum::<f64>()).sqrt() / px.len() as f64;
        assert!(
            (m - e).abs() < 3.0 * se.max(1e-9),
            "image mean {m} vs {e} (se {se})"
        );
    }
}

#[test]
fn white_furnace_renders_one_everywhere() {
    let mut scene = Scene::default();
    let white = scene.add_material(Material::diffuse("white", Vec3::ONE));
    let sphere = sphere_mesh(Vec3::ZERO, 1.0, 3);
    scene.add_world_mesh(sphere, Some(white));
    scene.environment = Some(Vec3::ONE);
    let data = SceneData::new(&scene);
    let view = View::from_camera(&camera(Vec3::new(0.0, 0.3, 4.0), Vec3::ZERO, 16, 12));
    let px = mean_and_se(&data, &view, 8, 16, -1);
    assert_converges(&px, [1.0; 3]);
}

#[test]
fn closed_sphere_converges_to_le_over_one_minus_rho() {
    let rho = Vec3::new(0.5, 0.7, 0.3);
    let le = Vec3::new(1.0, 0.5, 0.25);
    let mut scene = Scene::default();
    let m = scene.add_material(Material {
        emission: le,
        ..Material::diffuse("inside", rho)
    });
    let mut sphere = sphere_mesh(Vec3::ZERO, 2.0, 3);
    // Flat facets: Le/(1-ρ) is exact for any closed polyhedron, but smooth shading normals
    // lose the rays sampled below the geometric surface and bias the answer low.
    sphere.normals.clear();
    // Front (emitting) side facing inwards.
    for t in &mut sphere.indices {
        t.swap(1, 2);
    }
    scene.add_world_mesh(sphere, Some(m));
    let data = SceneData::new(&scene);
    let view = View::from_camera(&camera(
        Vec3::new(0.1, 0.2, 0.3),
        Vec3::new(1.0, 0.0, 0.0),
        12,
        8,
    ));
    let px = mean_and_se(&data, &view, 8, 64, 200);
    let expected = (le / (Vec3::ONE - rho)).as_dvec3().to_array();
    assert_converges(&px, expected);
}

fn cornell() -> Scene {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../scenes/cornell-box/scene.toml");
    eyeadapt_scene::load_scene(&path).expect("cornell box loads")
}

fn pixel_hash(f: &Frame) -> u64 {
    use std::hash::{Hash, Hasher};
    let mut h = std::collections::hash_map::DefaultHasher::new();
    for v in [&f.rgb, &f.albedo, &f.achromatic, &f.irradiance, &f.normal] {
        for p in v.iter() {
            p.map(f32::to_bits).hash(&mut h);
        }
    }
    for v in [&f.depth, &f.emitter, &f.hit] {
        for p in v.iter() {
            p.to_bits().hash(&mut h);
        }
    }
    h.finish()
}

#[test]
fn image_is_bit_identical_for_1_2_and_8_threads() {
    let scene = cornell();
    let data = SceneData::new(&scene);
    let mut view = View::from_camera(scene.camera.as_ref().unwrap());
    view.width = 24;
    view.height = 18;
    let s = settings(4, 7, 8);
    let hashes: Vec<u64> = [1, 2, 8]
        .iter()
        .map(|&t| {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(t)
                .build()
                .unwrap();
            pool.install(|| pixel_hash(&render(&data, &view, &s)))
        })
        .collect();
    assert_eq!(hashes[0], hashes[1]);
    assert_eq!(hashes[0], hashes[2]);
    // And the eye sensor too.
    let eye: Vec<_> = [1, 8]
        .iter()
        .map(|&t| {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(t)
                .build()
                .unwrap();
            pool.install(|| {
                eye_sensor(
                    &data,
                    &view,
                    &EyeSettings {
                        samples: 3000,
                        ..EyeSettings::default()
                    },
                    0,
                    s.path,
                )
            })
        })
        .collect();
    assert_eq!(eye[0], eye[1]);
    // A different seed changes the picture (the hash is not trivially constant).
    assert_ne!(
        hashes[0],
        pixel_hash(&render(&data, &view, &settings(4, 8, 8)))
    );
}

fn eye_view(forward: Vec3) -> View {
    View {
        position: Vec3::new(0.2, -0.1, 0.3),
        forward,
        up: Vec3::Y,
        fov_deg: 50.0,
        width: 64,
        height: 48,
        projection: eyeadapt_scene::Projection::Pinhole,
    }
}

fn eye_reading(scene: &Scene, view: &View, samples: u32, max_depth: i32) -> (DVec3, DVec3) {
    let data = SceneData::new(scene);
    let e = eye_sensor(
        &data,
        view,
        &EyeSettings {
            samples,
            ..EyeSettings::default()
        },
        0,
        PathSettings {
            max_depth,
            rr_depth: 5,
        },
    );
    let se =
        DVec3::new(e.cov_rgb.x_axis.x, e.cov_rgb.y_axis.y, e.cov_rgb.z_axis.z).max(DVec3::ZERO);
    (
        e.mean_rgb,
        DVec3::new(se.x.sqrt(), se.y.sqrt(), se.z.sqrt()),
    )
}

fn assert_within_3se(got: (DVec3, DVec3), expected: DVec3) {
    let (m, se) = got;
    for c in 0..3 {
        let tol = 3.0 * se[c] + 1e-9 * expected[c].abs();
        assert!(
            (m[c] - expected[c]).abs() <= tol,
            "channel {c}: {} vs {} (3 se = {})",
            m[c],
            expected[c],
            3.0 * se[c]
        );
    }
}

#[test]
fn eye_sensor_in_constant_environment_reads_pi_l() {
    let mut scene = Scene::default();
    let l = Vec3::new(0.8, 1.0, 1.3);
    scene.environment = Some(l);
    let got = eye_reading(
        &scene,
        &eye_view(Vec3::new(0.3, 0.2, -1.0).normalize()),
        20_000,
        8,
    );
    assert_within_3se(got, l.as_dvec3() * PI);
}

/// A UV sphere whose rings are aligned with `axis`, so its equator splits directions exactly
/// into the front and back hemispheres; each half gets its own emissive material.
fn split_sphere(
    center: Vec3,
    radius: f32,
    axis: Vec3,
    front: Material,
    back: Material,
    scene: &mut Scene,
) {
    let (n_theta, n_phi) = (32, 64);
    let f = axis.normalize();
    let r = f.any_orthonormal_vector();
    let u = f.cross(r);
    for (half, mat) in [(0, front), (1, back)] {
        let id = scene.add_material(mat);
        let mut mesh = Mesh::default();
        for i in 0..=n_theta / 2 {
            let theta = std::f32::consts::PI * (half * n_theta / 2 + i) as f32 / n_theta as f32;
            for j in 0..n_phi {
                let phi = 2.0 * std::f32::consts::PI * j as f32 / n_phi as f32;
                let d = f * libm::cosf(theta)
                    + (r * libm::cosf(phi) + u * libm::sinf(phi)) * libm::sinf(theta);
                mesh.positions.push(center + d * radius);
            }
        }
        for i in 0..n_theta / 2 {
            for j in 0..n_phi {
                let a = (i * n_phi + j) as u32;
                let b = (i * n_phi + (j + 1) % n_phi) as u32;
                let c = a + n_phi as u32;
                let d = b + n_phi as u32;
                // Wound so the front (emitting) side faces the centre.
                mesh.indices.push([a, b, c]);
                mesh.indices.push([b, d, c]);
            }
        }
        scene.add_world_mesh(mesh, Some(id));
    }
}

#[test]
fn eye_sensor_front_back_split_gives_three_quarters_and_one_quarter() {
    let axis = Vec3::new(0.2, -0.3, 1.0).normalize();
    let lf = Vec3::new(2.0, 1.0, 0.5);
    let lb = Vec3::new(0.25, 0.5, 3.0);
    let mut scene = Scene::default();
    let emitter = |name: &str, le: Vec3| Material {
        emission: le,
        ..Material::diffuse(name, Vec3::ZERO)
    };
    let view = eye_view(axis);
    split_sphere(
        view.position,
        50.0,
        axis,
        emitter("front", lf),
        emitter("back", lb),
        &mut scene,
    );
    // Check the winding faces inwards: the first triangle's normal points at the centre.
    // (Ring 0 collapses to the pole, so take the first triangle with area.)
    let m = &scene.meshes[0];
    let [a, b, c] = m
        .indices
        .iter()
        .map(|t| t.map(|i| m.positions[i as usize]))
        .find(|[a, b, c]| (*b - *a).cross(*c - *a).length() > 1e-3)
        .unwrap();
    assert!(
        (b - a).cross(c - a).dot(view.position - a) > 0.0,
        "split sphere must face inwards"
    );
    let got = eye_reading(&scene, &view, 40_000, 8);
    let expected = lf.as_dvec3() * (3.0 * PI / 4.0) + lb.as_dvec3() * (PI / 4.0);
    assert_within_3se(got, expected);
}

#[test]
fn eye_sensor_inside_closed_sphere_reads_pi_le_over_one_minus_rho() {
    let rho = Vec3::new(0.6, 0.4, 0.2);
    let le = Vec3::new(0.5, 1.0, 2.0);
    let mut scene = Scene::default();
    let m = scene.add_material(Material {
        emission: le,
        ..Material::diffuse("inside", rho)
    });
    let mut sphere = sphere_mesh(Vec3::ZERO, 3.0, 3);
    sphere.normals.clear(); // flat facets, see closed_sphere_converges_to_le_over_one_minus_rho
    for t in &mut sphere.indices {
        t.swap(1, 2);
    }
    scene.add_world_mesh(sphere, Some(m));
    let got = eye_reading(&scene, &eye_view(Vec3::X), 30_000, 200);
    let expected = (le / (Vec3::ONE - rho)).as_dvec3() * PI;
    assert_within_3se(got, expected);
}

#[test]
fn eye_sensor_sees_a_point_light_in_closed_form() {
    let view = eye_view(Vec3::new(0.0, 0.0, -1.0));
    let light_pos = Vec3::new(1.5, 0.7, -0.4);
    let intensity = Vec3::new(3.0, 2.0, 1.0);
    let mut scene = Scene::default();
    scene.lights.push(Light::Point {
        position: light_pos,
        intensity,
    });
    let (m, _) = eye_reading(&scene, &view, 1000, 8);
    let d = (light_pos - view.position).as_dvec3();
    let cos = d.normalize().dot(view.forward.as_dvec3());
    let expected = intensity.as_dvec3() * ((1.0 + cos) / 4.0 / d.length_squared());
    assert!(
        (m - expected).abs().max_element() < 1e-5 * expected.max_element(),
        "{m} vs {expected}"
    );
    // Behind the viewer, the cardioid weight vanishes.
    let behind = View {
        forward: (view.position - light_pos).normalize(),
        ..view
    };
    let (m, _) = eye_reading(&scene, &behind, 1000, 8);
    assert!(m.max_element() < 1e-9, "{m}");
}

#[test]
fn eye_sensor_scales_with_light_colour_per_channel() {
    // Metamorphic: multiplying every emitter's colour by k multiplies the reading by k
    // (same random numbers; white surfaces, so the scaling commutes with transport).
    let k = Vec3::new(0.5, 2.0, 3.0);
    let build = |scale: Vec3| {
        let mut s = cornell();
        for m in &mut s.materials {
            m.emission *= scale;
        }
        for m in &mut s.materials {
            if let eyeadapt_scene::Bsdf::Diffuse { reflectance } = &mut m.bsdf {
                *reflectance = Vec3::splat(0.6).into();
            }
        }
        s
    };
    let view = View::from_camera(cornell().camera.as_ref().unwrap());
    let (a, _) = eye_reading(&build(Vec3::ONE), &view, 4096, 8);
    let (b, _) = eye_reading(&build(k), &view, 4096, 8);
    let ratio = b / a;
    assert!((ratio - k.as_dvec3()).abs().max_element() < 1e-4, "{ratio}");
}
