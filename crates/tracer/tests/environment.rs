//! Environment maps and the sun: the map's sampling density against its own pdf (∫ = 1, a χ²
//! test of sampled directions), a constant map's furnace, and the eye sensor against an
//! independent estimate (a cube map rendered from the eye, integrated with the cardioid).
mod common;

use common::settings;
use eyeadapt_scene::{
    EnvironmentMap, Image, Light, Material, Scene, box_mesh, quad_mesh, sphere_mesh,
};
use eyeadapt_tracer::{
    Environment, EyeSettings, PathSettings, SampleStream, SceneData, View, eye_sensor, hash_key,
    luminance, render,
};
use glam::{DVec3, Mat3, Vec3, Vec3A};
use std::f64::consts::PI;
use std::sync::Arc;

/// A 32 × 16 sky: a blue gradient, a warm horizon band and one bright small patch (a sun-like
/// peak that importance sampling must find), rotated off the axes.
fn sky_map() -> EnvironmentMap {
    let (w, h) = (32u32, 16u32);
    let mut texels = Vec::new();
    for j in 0..h {
        for i in 0..w {
            let v = (j as f32 + 0.5) / h as f32;
            let mut c = Vec3::new(0.2, 0.35, 0.8) * (1.2 - v) + Vec3::new(0.05, 0.02, 0.0);
            if (7..9).contains(&j) {
                c += Vec3::new(0.6, 0.4, 0.2);
            }
            if (i, j) == (5, 4) || (i, j) == (6, 4) {
                c = Vec3::new(40.0, 36.0, 30.0);
            }
            if i == 20 {
                c = Vec3::ZERO; // a black column: never sampled where its cells are black
            }
            texels.push(c);
        }
    }
    EnvironmentMap {
        filename: "sky.exr".into(),
        image: Arc::new(Image {
            width: w,
            height: h,
            texels,
        }),
        scale: 1.5,
        to_world: Mat3::from_rotation_y(0.7) * Mat3::from_rotation_x(0.3),
    }
}

/// Direction of equal-area cell (a, b) of an `na × nb` grid over (φ, z = cos θ), at offsets
/// (s, t) in [0, 1) within the cell.
fn equal_area(a: usize, b: usize, na: usize, nb: usize, s: f64, t: f64) -> Vec3A {
    let phi = 2.0 * PI * (a as f64 + s) / na as f64;
    let z = 1.0 - 2.0 * (b as f64 + t) / nb as f64;
    let r = (1.0 - z * z).max(0.0).sqrt();
    Vec3A::new(
        (r * libm::cos(phi)) as f32,
        (r * libm::sin(phi)) as f32,
        z as f32,
    )
}

#[test]
fn envmap_pdf_integrates_to_one_and_matches_its_samples() {
    let env = Environment::new(None, Some(&sky_map())).unwrap();
    // ∫ pdf dω over the sphere, on a fine equal-area grid (each cell 4π / n).
    let (na, nb, sub) = (64, 32, 8);
    let mut expected = vec![0.0f64; na * nb];
    for b in 0..nb {
        for a in 0..na {
            let mut s = 0.0;
            for k in 0..sub * sub {
                let (x, y) = ((k % sub) as f64 + 0.5, (k / sub) as f64 + 0.5);
                s += env.pdf(equal_area(a, b, na, nb, x / sub as f64, y / sub as f64)) as f64;
            }
            expected[b * na + a] = s / (sub * sub) as f64 * 4.0 * PI / (na * nb) as f64;
        }
    }
    let total: f64 = expected.iter().sum();
    assert!((total - 1.0).abs() < 2e-3, "∫ pdf dω = {total}");
    // χ² of 200 000 sampled directions in the same cells (cells expecting < 5 are pooled).
    let n = 200_000u32;
    let mut counts = vec![0u32; na * nb];
    let mut dropped = 0u32;
    let key = hash_key(&[3, 1, 4]);
    for i in 0..n {
        // Rounding can take a sample onto the edge of a black cell: it is then dropped.
        let Some(s) = env.sample(SampleStream::new(key, i).next_2d()) else {
            dropped += 1;
            continue;
        };
        let w = s.wi;
        assert!(
            env.radiance(w).max_element() > 0.0,
            "a black direction was sampled"
        );
        let phi = libm::atan2(w.y as f64, w.x as f64).rem_euclid(2.0 * PI);
        let a = ((phi / (2.0 * PI) * na as f64) as usize).min(na - 1);
        let b = (((1.0 - w.z as f64) / 2.0 * nb as f64) as usize).min(nb - 1);
        counts[b * na + a] += 1;
    }
    assert!(dropped <= n / 10_000, "{dropped} of {n} samples dropped");
    let (mut chi2, mut dof, mut pooled_e, mut pooled_o) = (0.0, 0usize, 0.0, 0.0);
    for (e, o) in expected.iter().zip(&counts) {
        let e = e * n as f64;
        if e < 5.0 {
            pooled_e += e;
            pooled_o += *o as f64;
        } else {
            chi2 += (*o as f64 - e).powi(2) / e;
            dof += 1;
        }
    }
    if pooled_e > 0.0 {
        chi2 += (pooled_o - pooled_e).powi(2) / pooled_e.max(1.0);
        dof += 1;
    }
    // χ² quantile 0.999 for dof degrees of freedom (Wilson–Hilferty).
    let k = (dof - 1) as f64;
    let q = k * (1.0 - 2.0 / (9.0 * k) + 3.09 * (2.0 / (9.0 * k)).sqrt()).powi(3);
    assert!(chi2 < q, "χ² = {chi2:.1} over {dof} cells, limit {q:.1}");
}

#[test]
fn a_constant_envmap_is_a_white_furnace() {
    let mut map = sky_map();
    let l = Vec3::new(0.7, 0.9, 1.1);
    map.image = Arc::new(Image {
        width: 16,
        height: 8,
        texels: vec![l; 128],
    });
    map.scale = 1.0;
    let mut scene = Scene::default();
    let white = scene.add_material(Material::diffuse("white", Vec3::ONE));
    scene.add_world_mesh(sphere_mesh(Vec3::ZERO, 1.0, 3), Some(white));
    scene.environment_map = Some(map);
    let data = SceneData::new(&scene);
    let view = View {
        position: Vec3::new(0.0, 0.3, 4.0),
        forward: Vec3::new(0.0, -0.3, -4.0).normalize(),
        up: Vec3::Y,
        fov_deg: 40.0,
        width: 12,
        height: 8,
        projection: eyeadapt_scene::Projection::Pinhole,
    };
    let mut sum = DVec3::ZERO;
    let mut worst = 0.0f64;
    let seeds = 16;
    for seed in 0..seeds {
        let f = render(&data, &view, &settings(16, seed, -1));
        for p in &f.rgb {
            let p = Vec3::from_array(*p).as_dvec3();
            sum += p;
            worst = worst.max(((p / l.as_dvec3()) - DVec3::ONE).abs().max_element());
        }
    }
    let mean = sum / (seeds as f64 * 96.0) / l.as_dvec3();
    assert!(
        (mean - DVec3::ONE).abs().max_element() < 2e-3,
        "mean / L = {mean}"
    );
    // Every pixel of every render near L (a white sphere in a uniform sky is invisible).
    assert!(worst < 0.25, "worst pixel off by {worst}");
}

/// Linear sRGB (D65) to CIE xy.
fn xy(rgb: DVec3) -> (f64, f64) {
    let x = 0.412_456_4 * rgb.x + 0.357_576_1 * rgb.y + 0.180_437_5 * rgb.z;
    let y = 0.212_672_9 * rgb.x + 0.715_152_2 * rgb.y + 0.072_175 * rgb.z;
    let z = 0.019_333_9 * rgb.x + 0.119_192 * rgb.y + 0.950_304_1 * rgb.z;
    (x / (x + y + z), y / (x + y + z))
}

/// A courtyard under the sky map and a warm sun: a green-grey ground, a tall orange wall
/// beside the eye and a blue box in front of it; the eye looks across the ground.
fn courtyard() -> (Scene, View, Vec3, Vec3) {
    let mut scene = Scene::default();
    let ground = scene.add_material(Material::diffuse("ground", Vec3::new(0.3, 0.4, 0.25)));
    let wall = scene.add_material(Material::diffuse("wall", Vec3::new(0.8, 0.4, 0.1)));
    let blue = scene.add_material(Material::diffuse("blue", Vec3::new(0.1, 0.2, 0.7)));
    scene.add_world_mesh(
        quad_mesh(
            Vec3::new(-20.0, 0.0, 20.0),
            Vec3::new(40.0, 0.0, 0.0),
            Vec3::new(0.0, 0.0, -40.0),
        ),
        Some(ground),
    );
    scene.add_world_mesh(
        box_mesh(Vec3::new(1.5, 0.0, -6.0), Vec3::new(2.0, 4.0, 3.0)),
        Some(wall),
    );
    scene.add_world_mesh(
        box_mesh(Vec3::new(-1.0, 0.0, -4.0), Vec3::new(0.5, 1.2, -3.0)),
        Some(blue),
    );
    // The sun comes from behind-left of the eye, high enough to clear the wall.
    let sun_dir = Vec3::new(0.5, -0.8, -0.3).normalize();
    let sun_e = Vec3::new(2.0, 1.7, 1.2);
    scene.lights.push(Light::Directional {
        direction: sun_dir,
        irradiance: sun_e,
    });
    scene.environment_map = Some(sky_map());
    let view = View {
        position: Vec3::new(0.0, 1.2, 0.0),
        forward: Vec3::new(0.4, -0.2, -1.0).normalize(),
        up: Vec3::Y,
        fov_deg: 50.0,
        width: 64,
        height: 48,
        projection: eyeadapt_scene::Projection::Pinhole,
    };
    (scene, view, sun_dir, sun_e)
}

/// ∫ L(ω) (1 + cos θ)/4 dω from six 90° renders from the eye (pixel solid angles exact at
/// the pixel centre), plus the sun's direct term E · K, which no camera ray can see.
fn cube_map_estimate(data: &SceneData, view: &View, n: u32, spp: u32, depth: i32) -> DVec3 {
    let axis = view.forward.as_dvec3();
    let faces = [
        (Vec3::X, Vec3::Y),
        (-Vec3::X, Vec3::Y),
        (Vec3::Z, Vec3::Y),
        (-Vec3::Z, Vec3::Y),
        (Vec3::Y, Vec3::Z),
        (-Vec3::Y, Vec3::Z),
    ];
    let mut sum = DVec3::ZERO;
    for (k, (forward, up)) in faces.into_iter().enumerate() {
        let face = View {
            position: view.position,
            forward,
            up,
            fov_deg: 90.0,
            width: n,
            height: n,
            projection: eyeadapt_scene::Projection::Pinhole,
        };
        let img = render(data, &face, &settings(spp, 100 + k as u64, depth));
        let (r, u, f) = face.basis().axes();
        for j in 0..n {
            for i in 0..n {
                let a = 2.0 * (i as f64 + 0.5) / n as f64 - 1.0;
                let b = 1.0 - 2.0 * (j as f64 + 0.5) / n as f64;
                let d = DVec3::from(Vec3::from(f + r * a as f32 + u * b as f32));
                let len2 = 1.0 + a * a + b * b;
                let d_omega = (2.0 / n as f64).powi(2) / libm::pow(len2, 1.5);
                let k = (1.0 + d.normalize().dot(axis)) / 4.0;
                let l = Vec3::from_array(img.rgb[(j * n + i) as usize]).as_dvec3();
                sum += l * k * d_omega;
            }
        }
    }
    sum
}

#[test]
fn eye_sensor_agrees_with_a_cube_map_under_sky_and_sun() {
    let (scene, view, sun_dir, sun_e) = courtyard();
    let data = SceneData::new(&scene);
    let depth = 4;
    let path = PathSettings {
        max_depth: depth,
        rr_depth: 5,
    };
    let e = eye_sensor(
        &data,
        &view,
        &EyeSettings {
            samples: 1 << 17,
            ..EyeSettings::default()
        },
        0,
        path,
    );
    // The sun is seen from the eye (it clears the wall): E · K towards it.
    let k_sun = (1.0 - sun_dir.as_dvec3().dot(view.forward.as_dvec3())) / 4.0;
    let cube = cube_map_estimate(&data, &view, 48, 48, depth) + sun_e.as_dvec3() * k_sun;
    let (ex, ey) = xy(e.mean_rgb);
    let (cx, cy) = xy(cube);
    let dxy = ((ex - cx).powi(2) + (ey - cy).powi(2)).sqrt();
    let lum = |v: DVec3| luminance(Vec3A::from(v.as_vec3())) as f64;
    eprintln!(
        "eye sensor {:?} xy ({ex:.5}, {ey:.5}); cube map {cube:?} xy ({cx:.5}, {cy:.5}); Δxy {dxy:.2e}; Y ratio {:.4}",
        e.mean_rgb,
        lum(e.mean_rgb) / lum(cube)
    );
    assert!(dxy <= 7e-4, "Δxy = {dxy:.2e}");
    assert!((lum(e.mean_rgb) / lum(cube) - 1.0).abs() < 0.01);
}

fn uv(rgb: DVec3) -> (f64, f64) {
    let (x, y) = xy(rgb);
    let d = -2.0 * x + 12.0 * y + 3.0;
    (4.0 * x / d, 9.0 * y / d)
}

/// The audit of issue 22 in code: on the paper's scenes lit by area lights only (no delta light,
/// whose direct term no camera ray sees), the eye sensor and the cube-map integral from its
/// position agree in u′v′ within a few 1e-4 (the audit found 2e-4; with 64² faces at 64 spp
/// the three differ by 7.7e-5, 9.6e-5 and 2.5e-5, so what is left here is the cube map's noise).
#[test]
fn eye_sensor_agrees_with_a_cube_map_in_the_paper_scenes() {
    for name in ["cornell-green-floor", "two-rooms", "three-rooms"] {
        let scene = eyeadapt_scene::load_builtin(name).unwrap();
        let data = SceneData::new(&scene);
        let view = View::from_camera(scene.camera.as_ref().unwrap());
        let depth = 8;
        let path = PathSettings {
            max_depth: depth,
            rr_depth: 5,
        };
        let e = eye_sensor(
            &data,
            &view,
            &EyeSettings {
                samples: 1 << 16,
                ..EyeSettings::default()
            },
            0,
            path,
        );
        let cube = cube_map_estimate(&data, &view, 32, 32, depth);
        let ((eu, ev), (cu, cv)) = (uv(e.mean_rgb), uv(cube));
        let duv = ((eu - cu).powi(2) + (ev - cv).powi(2)).sqrt();
        eprintln!(
            "{name}: eye u′v′ ({eu:.5}, {ev:.5}), cube map ({cu:.5}, {cv:.5}), Δu′v′ {duv:.2e}"
        );
        assert!(duv < 6e-4, "{name}: Δu′v′ = {duv:.2e}");
    }
}
