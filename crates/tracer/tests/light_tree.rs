//! The light tree (`light_tree.rs`) through the whole renderer: a floor under 24 small lamps
//! and 4 point lights (more than the 16 lights the spatial choice handles directly, so the
//! choice goes through the tree). The frame and the eye sensor are the same bits on any thread
//! count, and the floor's brightness is the sum of what each light gives it alone.
mod common;

use common::settings;
use eyeadapt_scene::{Bsdf, Light, Material, Param, Rgb, Scene, quad_mesh};
use eyeadapt_tracer::{EyeSettings, Frame, PathSettings, SceneData, View, eye_sensor, render};
use glam::Vec3;

/// Lamp `k` of 24 (0.2 m squares facing down, in a 6 × 4 grid 1.5–2.5 m up) or point `k` of
/// 4, alone (`only`) or all of them.
fn scene(only: Option<usize>) -> Scene {
    let mut s = Scene::default();
    let floor = s.add_material(Material::diffuse("floor", Rgb::splat(0.5)));
    s.add_world_mesh(
        quad_mesh(
            Vec3::new(-6.0, -4.0, 0.0),
            Vec3::new(12.0, 0.0, 0.0),
            Vec3::new(0.0, 8.0, 0.0),
        ),
        Some(floor),
    );
    for k in 0..28 {
        if only.is_some_and(|o| o != k) {
            continue;
        }
        let (i, j) = ((k % 6) as f32, ((k / 6) % 4) as f32);
        let at = Vec3::new(-5.0 + 2.0 * i, -3.0 + 2.0 * j, 1.5 + 0.04 * k as f32);
        if k < 24 {
            let m = s.add_material(Material {
                name: format!("lamp{k}"),
                bsdf: Bsdf::Diffuse {
                    reflectance: Param::Const(Rgb::ZERO),
                },
                emission: Rgb::new(2.0 + k as f32 * 0.3, 3.0, 4.0),
            });
            // Facing down (−z).
            s.add_world_mesh(
                quad_mesh(at, Vec3::new(0.0, 0.2, 0.0), Vec3::new(0.2, 0.0, 0.0)),
                Some(m),
            );
        } else {
            s.lights.push(Light::Point {
                position: at + Vec3::new(1.0, 1.0, 0.5),
                intensity: Rgb::splat(0.5),
            });
        }
    }
    s
}

fn view() -> View {
    View {
        position: Vec3::new(0.0, 0.0, 1.2),
        forward: -Vec3::Z,
        up: Vec3::Y,
        fov_deg: 100.0,
        width: 24,
        height: 16,
        projection: Default::default(),
    }
}

/// Direct light only (max depth 2), so that lights add up exactly.
fn shoot(s: &Scene, spp: u32) -> Frame {
    render(&SceneData::new(s), &view(), &settings(spp, 5, 2))
}

fn mean(f: &Frame) -> f64 {
    f.rgb.iter().map(|p| p[1] as f64).sum::<f64>() / f.rgb.len() as f64
}

#[test]
fn many_lights_are_the_same_bits_on_any_thread_count() {
    let s = scene(None);
    let on = |threads: usize| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap()
            .install(|| {
                let data = SceneData::new(&s);
                let eye = EyeSettings {
                    samples: 2048,
                    min_samples: 2048,
                    ..Default::default()
                };
                let path = PathSettings {
                    max_depth: 8,
                    rr_depth: 5,
                };
                (
                    render(&data, &view(), &settings(8, 3, 8)),
                    eye_sensor(&data, &view(), &eye, 0, path),
                )
            })
    };
    let (frame, eye) = on(1);
    assert!(mean(&frame) > 0.0 && eye.mean_rgb.y > 0.0);
    let (frame3, eye3) = on(3);
    assert_eq!(frame.rgb, frame3.rgb);
    assert_eq!(eye.mean_rgb, eye3.mean_rgb);
}

#[test]
fn many_lights_add_up_to_each_light_alone() {
    // Direct light on the floor: the frame with all 28 lights against the sum of 28 frames
    // with one light each (each of those a single unit, chosen always).
    let all = mean(&shoot(&scene(None), 256));
    let sum: f64 = (0..28).map(|k| mean(&shoot(&scene(Some(k)), 64))).sum();
    eprintln!("all lights {all:.5}, sum of each alone {sum:.5}");
    assert!(
        sum > 0.0 && (all / sum - 1.0).abs() < 0.01,
        "{all} vs {sum}"
    );
}
