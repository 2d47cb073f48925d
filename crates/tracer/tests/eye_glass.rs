//! The eye sensor behind glass: its reading against an independent estimate, a cube map of
//! camera renders from the eye integrated with the cardioid (1 + cos θ)/4, plus the delta
//! lights' direct terms computed here in closed form (a sun or a point light, through a pane
//! with the pane's Fresnel transmittance written out below, not the tracer's). Three cases,
//! each under a sky map: the sun seen directly past a solid glass sphere; the sun through a
//! tilted window pane; a warm area lamp and a point light behind a pane.
//!
//! The tests run with small budgets (about a second each). `EYE_GLASS_FULL=1` raises them for
//! the figures of the note (`scripts/bench/eye-glass.sh` prints them).
mod common;

use common::settings;
use eyeadapt_scene::{Bsdf, EnvironmentMap, Image, Light, Material, Scene, quad_mesh, sphere_mesh};
use eyeadapt_tracer::{EyeSettings, PathSettings, SceneData, View, eye_sensor, luminance, render};
use glam::{DVec3, Mat3, Vec3, Vec3A};
use std::sync::Arc;

const DEPTH: i32 = 5;

/// (eye paths, cube face size, cube spp) for the tests, or for the note.
fn budget() -> (u32, u32, u32) {
    if std::env::var_os("EYE_GLASS_FULL").is_some() {
        (1 << 21, 96, 256)
    } else {
        (1 << 17, 32, 48)
    }
}

/// A 64 × 32 sky: zenith blue to a pale horizon, a darker ground half, a soft bright glow.
fn sky() -> EnvironmentMap {
    let (w, h) = (64u32, 32u32);
    let mut texels = Vec::new();
    for j in 0..h {
        for i in 0..w {
            let v = (j as f32 + 0.5) / h as f32;
            let c = if v < 0.5 {
                Vec3::new(0.25, 0.45, 0.95).lerp(Vec3::new(0.8, 0.85, 0.9), (2.0 * v).powi(2))
            } else {
                Vec3::new(0.3, 0.27, 0.22)
            };
            let glow = if (10..13).contains(&i) && (6..9).contains(&j) {
                Vec3::new(12.0, 10.0, 7.0)
            } else {
                Vec3::ZERO
            };
            texels.push(c + glow);
        }
    }
    EnvironmentMap {
        filename: "sky.exr".into(),
        image: Arc::new(Image {
            width: w,
            height: h,
            texels,
        }),
        scale: 1.0,
        to_world: Mat3::from_rotation_y(0.4),
    }
}

fn pane_material(s: &mut Scene) -> eyeadapt_scene::MaterialId {
    s.add_material(Material {
        name: "pane".into(),
        bsdf: Bsdf::ThinDielectric {
            eta: 1.5,
            specular_reflectance: Vec3::ONE,
            specular_transmittance: Vec3::ONE,
        },
        emission: Vec3::ZERO,
    })
}

/// Unpolarised Fresnel reflectance of one interface at incidence cos θ, IOR `eta`.
fn fresnel(cos_i: f64, eta: f64) -> f64 {
    let sin_t2 = (1.0 - cos_i * cos_i) / (eta * eta);
    if sin_t2 >= 1.0 {
        return 1.0;
    }
    let cos_t = (1.0 - sin_t2).sqrt();
    let rs = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
    let rp = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
    0.5 * (rs * rs + rp * rp)
}

/// A thin pane's straight-through transmittance: 1 − 2R/(1 + R).
fn pane_t(cos_i: f64) -> f64 {
    let r = fresnel(cos_i.abs(), 1.5);
    1.0 - 2.0 * r / (1.0 + r)
}

/// A square quad of side `size` centred at `c` with unit normal `n`.
fn square(c: Vec3, n: Vec3, size: f32) -> eyeadapt_scene::Mesh {
    let a = n.any_orthonormal_vector() * size;
    let b = n.cross(a).normalize() * size;
    quad_mesh(c - 0.5 * (a + b), a, b)
}

/// A ground, an orange wall and a blue block under the sky; the eye at (0, 1.2, 0).
fn courtyard() -> (Scene, View) {
    let mut s = Scene::default();
    let ground = s.add_material(Material::diffuse("ground", Vec3::new(0.3, 0.4, 0.25)));
    let wall = s.add_material(Material::diffuse("wall", Vec3::new(0.8, 0.4, 0.1)));
    let blue = s.add_material(Material::diffuse("blue", Vec3::new(0.1, 0.2, 0.7)));
    s.add_world_mesh(
        quad_mesh(
            Vec3::new(-20.0, 0.0, 20.0),
            Vec3::new(40.0, 0.0, 0.0),
            Vec3::new(0.0, 0.0, -40.0),
        ),
        Some(ground),
    );
    s.add_world_mesh(
        eyeadapt_scene::box_mesh(Vec3::new(1.5, 0.0, -6.0), Vec3::new(2.0, 4.0, 3.0)),
        Some(wall),
    );
    s.add_world_mesh(
        eyeadapt_scene::box_mesh(Vec3::new(-1.0, 0.0, -4.0), Vec3::new(0.5, 1.2, -3.0)),
        Some(blue),
    );
    s.environment_map = Some(sky());
    let view = View {
        position: Vec3::new(0.0, 1.2, 0.0),
        forward: Vec3::new(0.4, -0.2, -1.0).normalize(),
        up: Vec3::Y,
        fov_deg: 50.0,
        width: 8,
        height: 8,
        projection: eyeadapt_scene::Projection::Pinhole,
    };
    (s, view)
}

/// ∫ L(ω) (1 + cos θ)/4 dω over six 90° camera renders from the eye (pixel solid angles
/// exact at the pixel centre). Delta lights are not in it: no camera ray sees them.
fn cube_map(data: &SceneData, view: &View, n: u32, spp: u32) -> DVec3 {
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
        let img = render(data, &face, &settings(spp, 200 + k as u64, DEPTH));
        let (r, u, f) = face.basis().axes();
        for j in 0..n {
            for i in 0..n {
                let a = 2.0 * (i as f64 + 0.5) / n as f64 - 1.0;
                let b = 1.0 - 2.0 * (j as f64 + 0.5) / n as f64;
                let d = DVec3::from(Vec3::from(f + r * a as f32 + u * b as f32));
                let d_omega = (2.0 / n as f64).powi(2) / libm::pow(1.0 + a * a + b * b, 1.5);
                let kern = (1.0 + d.normalize().dot(axis)) / 4.0;
                let l = Vec3::from_array(img.rgb[(j * n + i) as usize]).as_dvec3();
                sum += l * kern * d_omega;
            }
        }
    }
    sum
}

fn xy(rgb: DVec3) -> (f64, f64) {
    let x = 0.412_456_4 * rgb.x + 0.357_576_1 * rgb.y + 0.180_437_5 * rgb.z;
    let y = 0.212_672_9 * rgb.x + 0.715_152_2 * rgb.y + 0.072_175 * rgb.z;
    let z = 0.019_333_9 * rgb.x + 0.119_192 * rgb.y + 0.950_304_1 * rgb.z;
    (x / (x + y + z), y / (x + y + z))
}

/// The sensor against the cube map plus `delta` (the delta lights' terms); asserts
/// Δxy ≤ 7e-4 and luminance within 1.5 %, and prints both for the note.
fn check(name: &str, scene: &Scene, view: &View, delta: DVec3) {
    let (eye_n, face, spp) = budget();
    let data = SceneData::new(scene);
    let e = eye_sensor(
        &data,
        view,
        &EyeSettings {
            samples: eye_n,
            ..EyeSettings::default()
        },
        0,
        PathSettings {
            max_depth: DEPTH,
            rr_depth: 5,
        },
    );
    let cube = cube_map(&data, view, face, spp) + delta;
    let (ex, ey) = xy(e.mean_rgb);
    let (cx, cy) = xy(cube);
    let dxy = ((ex - cx).powi(2) + (ey - cy).powi(2)).sqrt();
    let lum = |v: DVec3| luminance(Vec3A::from(v.as_vec3())) as f64;
    let ratio = lum(e.mean_rgb) / lum(cube);
    eprintln!(
        "{name}: eye xy ({ex:.5}, {ey:.5}), cube map xy ({cx:.5}, {cy:.5}), Δxy {dxy:.2e}, \
         Y eye/cube {ratio:.4}, delta lights {:.1} % of Y (eye {eye_n} paths, cube 6×{face}² px \
         × {spp} spp)",
        100.0 * lum(delta) / lum(cube)
    );
    assert!(dxy <= 7e-4, "{name}: Δxy = {dxy:.2e}");
    assert!((ratio - 1.0).abs() < 0.015, "{name}: Y ratio {ratio}");
}

/// Cardioid weight of a direction towards `to` (unit) for the gaze `view.forward`.
fn kern(view: &View, to: Vec3) -> f64 {
    (1.0 + to.as_dvec3().dot(view.forward.as_dvec3())) / 4.0
}

#[test]
fn sun_seen_directly_past_a_glass_sphere() {
    let (mut s, view) = courtyard();
    // Solid glass off to the right of the gaze: the eye sees the sky refracted through it.
    let glass = s.add_material(Material {
        name: "glass".into(),
        bsdf: Bsdf::Dielectric {
            eta: 1.5,
            specular_reflectance: Vec3::ONE,
            specular_transmittance: Vec3::ONE,
        },
        emission: Vec3::ZERO,
    });
    s.add_world_mesh(sphere_mesh(Vec3::new(0.9, 1.0, -1.6), 0.45, 3), Some(glass));
    let travel = Vec3::new(0.5, -0.8, -0.3).normalize();
    let e_sun = Vec3::new(2.0, 1.7, 1.2);
    s.lights.push(Light::Directional {
        direction: travel,
        irradiance: e_sun,
    });
    // Nothing stands between the eye and the sun (behind-left, high).
    let delta = e_sun.as_dvec3() * kern(&view, -travel);
    check("sun seen directly (glass sphere in view)", &s, &view, delta);
}

#[test]
fn sun_through_a_window_pane() {
    let (mut s, view) = courtyard();
    let pane = pane_material(&mut s);
    let travel = Vec3::new(0.5, -0.8, -0.3).normalize();
    let to_sun = -travel;
    let e_sun = Vec3::new(2.0, 1.7, 1.2);
    s.lights.push(Light::Directional {
        direction: travel,
        irradiance: e_sun,
    });
    // A large pane 0.6 m from the eye towards the sun, tilted 35° off the sun's direction:
    // the sun, much of the sky behind the eye and its reflection all go through it.
    let n = (Mat3::from_axis_angle(Vec3::Y.cross(to_sun).normalize(), 35f32.to_radians()) * to_sun)
        .normalize();
    s.add_world_mesh(square(view.position + to_sun * 0.6, n, 8.0), Some(pane));
    let t = pane_t(n.dot(to_sun) as f64);
    let delta = e_sun.as_dvec3() * kern(&view, to_sun) * t;
    check("sun through a pane", &s, &view, delta);
}

#[test]
fn lamps_behind_a_pane() {
    let (mut s, view) = courtyard();
    let pane = pane_material(&mut s);
    let lamp = s.add_material(Material {
        name: "lamp".into(),
        bsdf: Bsdf::Diffuse {
            reflectance: eyeadapt_scene::Param::Const(Vec3::splat(0.5)),
        },
        emission: Vec3::new(9.0, 5.0, 1.8),
    });
    // A warm area lamp facing the eye, 2 m ahead-left, and a point light beside it, both
    // behind a pane that stands 0.8 m in front of the eye, turned 25° about the vertical.
    let gaze = view.forward;
    let lamp_c = view.position + Vec3::new(-0.5, 0.2, -2.0);
    let to_eye = (view.position - lamp_c).normalize();
    s.add_world_mesh(square(lamp_c, to_eye, 0.7), Some(lamp));
    let point = view.position + Vec3::new(0.4, 0.5, -1.8);
    let intensity = Vec3::new(1.5, 1.0, 0.5);
    s.lights.push(Light::Point {
        position: point,
        intensity,
    });
    let n = Mat3::from_rotation_y(25f32.to_radians()) * Vec3::Z;
    s.add_world_mesh(square(view.position + gaze * 0.8, n, 6.0), Some(pane));
    let d = point - view.position;
    let w = d.normalize();
    let t = pane_t(n.dot(w) as f64);
    let delta = intensity.as_dvec3() / d.length_squared() as f64 * kern(&view, w) * t;
    check("lamp and point light behind a pane", &s, &view, delta);
}
