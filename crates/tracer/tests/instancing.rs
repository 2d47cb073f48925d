//! Instancing: a mesh shared by several instances (the two-level structure) renders the image
//! of the same scene with every instance baked into its own world-space mesh (the flat one),
//! while its structures hold the mesh once.
use eyeadapt_scene::{Camera, Material, Rgb, Scene, Transform, quad_mesh, sphere_mesh};
use eyeadapt_tracer::{PathSettings, RenderSettings, SceneData, View, render};
use glam::{Mat4, Quat, Vec3};

fn placements() -> Vec<Transform> {
    let m = |s: Vec3, angle: f32, t: Vec3| Transform {
        matrix: Mat4::from_scale_rotation_translation(s, Quat::from_rotation_y(angle), t),
    };
    vec![
        m(Vec3::splat(0.3), 0.3, Vec3::new(-0.6, 0.3, 0.0)),
        m(Vec3::new(0.2, 0.5, 0.2), -0.7, Vec3::new(0.1, 0.5, -0.4)),
        // Mirrored: the winding stays, so the front side flips with the space.
        m(Vec3::new(-0.25, 0.25, 0.25), 1.1, Vec3::new(0.7, 0.25, 0.3)),
    ]
}

/// The scene: a floor, a lamp and one sphere mesh (with vertex normals, so shading normals are
/// transformed too) placed three times, either instanced or baked.
fn scene(instanced: bool) -> Scene {
    let mut s = Scene::default();
    let white = s.add_material(Material::diffuse("white", Rgb::splat(0.7)));
    let red = s.add_material(Material::diffuse("red", Rgb::new(0.7, 0.2, 0.1)));
    let mut lamp = Material::diffuse("lamp", Rgb::splat(0.5));
    lamp.emission = Rgb::new(6.0, 5.0, 4.0);
    let lamp = s.add_material(lamp);
    // One placement glows: emission is one-sided, so its front side (mirrored) must agree.
    let mut glow = Material::diffuse("glow", Rgb::splat(0.5));
    glow.emission = Rgb::new(0.5, 1.0, 0.5);
    let glow = s.add_material(glow);
    let materials = [red, red, glow];
    s.add_world_mesh(
        quad_mesh(
            Vec3::new(-2.0, 0.0, 2.0),
            Vec3::new(4.0, 0.0, 0.0),
            Vec3::new(0.0, 0.0, -4.0),
        ),
        Some(white),
    );
    s.add_world_mesh(
        quad_mesh(
            Vec3::new(-0.5, 2.0, -0.5),
            Vec3::new(1.0, 0.0, 0.0),
            Vec3::new(0.0, 0.0, 1.0),
        ),
        Some(lamp),
    );
    let ball = sphere_mesh(Vec3::ZERO, 1.0, 2);
    if instanced {
        let id = s.add_mesh(ball);
        for (t, m) in placements().into_iter().zip(materials) {
            s.add_instance(id, Some(m), t);
        }
    } else {
        for (t, material) in placements().into_iter().zip(materials) {
            let mut m = ball.clone();
            for p in &mut m.positions {
                *p = t.point(*p);
            }
            for n in &mut m.normals {
                *n = t.normal(*n);
            }
            s.add_world_mesh(m, Some(material));
        }
    }
    s.camera = Some(Camera {
        position: Vec3::new(0.0, 1.2, 3.0),
        look_at: Vec3::new(0.0, 0.4, 0.0),
        up: Vec3::Y,
        fov_deg: 50.0,
        width: 40,
        height: 30,
        projection: eyeadapt_scene::Projection::Pinhole,
    });
    s
}

/// Box-filtered renders of `spp` samples, seed 3.
fn settings(spp: u32) -> RenderSettings {
    RenderSettings {
        spp,
        path: PathSettings::default(),
        seed: 3,
        frame: 0,
        filter: eyeadapt_scene::PixelFilter::Box,
        wcam_specular: Default::default(),
        guiding: Default::default(),
    }
}

#[test]
fn instances_render_the_flattened_image() {
    let settings = settings(64);
    let (a, b) = (scene(true), scene(false));
    let (da, db) = (SceneData::new(&a), SceneData::new(&b));
    assert!(da.geometry.is_two_level() && !db.geometry.is_two_level());
    assert_eq!(da.geometry.triangle_count(), db.geometry.triangle_count());
    let view = View::from_camera(a.camera.as_ref().unwrap());
    let (fa, fb) = (render(&da, &view, &settings), render(&db, &view, &settings));
    // The same sample streams follow the same paths; the object-space ray transform only
    // moves hit points by rounding, which can flip a rare path decision.
    let mut diff = 0.0f64;
    let mut total = 0.0f64;
    let mut far = 0;
    for (x, y) in fa.rgb.iter().zip(&fb.rgb) {
        let (x, y) = (Vec3::from(*x), Vec3::from(*y));
        let d = (x - y).abs().max_element() as f64;
        diff += d;
        total += y.max_element() as f64;
        far += (d > 1e-3 * (1.0 + y.max_element() as f64)) as usize;
    }
    assert!(total > 0.0);
    assert!(
        diff / total < 2e-3,
        "mean relative difference {}",
        diff / total
    );
    assert!(
        far * 50 < fa.rgb.len(),
        "{far} of {} pixels differ",
        fa.rgb.len()
    );
    // The mesh is stored once: the instanced structures are smaller than the baked ones.
    assert!(da.geometry.memory_bytes() < db.geometry.memory_bytes());
}

/// A displaced grid of about `n` triangles.
fn grid(n: usize) -> eyeadapt_scene::Mesh {
    let k = ((n / 2) as f64).sqrt().ceil() as u32;
    let mut m = eyeadapt_scene::Mesh::default();
    for j in 0..=k {
        for i in 0..=k {
            let (x, z) = (i as f32 / k as f32, j as f32 / k as f32);
            m.positions.push(Vec3::new(
                x,
                0.05 * libm::sinf(9.0 * x) * libm::cosf(7.0 * z),
                z,
            ));
        }
    }
    for j in 0..k {
        for i in 0..k {
            let v = |a: u32, b: u32| b * (k + 1) + a;
            m.indices.push([v(i, j), v(i, j + 1), v(i + 1, j + 1)]);
            m.indices.push([v(i, j), v(i + 1, j + 1), v(i + 1, j)]);
        }
    }
    m
}

#[test]
fn a_thousand_instances_cost_little_more_than_one() {
    let placed = |count: usize| {
        let mut s = Scene::default();
        let id = s.add_mesh(grid(100_000));
        // Two placements at least, so that both scenes use the two-level layout.
        s.add_instance(id, None, Transform::default());
        for i in 1..count {
            let t = Transform {
                matrix: Mat4::from_translation(Vec3::new((i % 40) as f32, 0.0, (i / 40) as f32)),
            };
            s.add_instance(id, None, t);
        }
        s.environment = Some(Rgb::ONE);
        SceneData::new(&s).geometry.memory_bytes()
    };
    let (two, thousand) = (placed(2), placed(1000));
    eprintln!(
        "100k-triangle mesh: 2 instances {:.1} MB, 1000 instances {:.1} MB",
        two as f64 / 1e6,
        thousand as f64 / 1e6
    );
    assert!(thousand < two + two / 10, "{thousand} bytes vs {two}");
}

#[test]
fn meshes_built_side_by_side_give_the_same_bits_on_any_thread_count() {
    // Several meshes of different sizes, each placed twice: a two-level scene whose meshes'
    // structures are built in parallel.
    let build_and_render = |threads: usize| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap()
            .install(|| {
                let mut s = scene(true);
                for (k, n) in [20_000, 5_000, 12_000].into_iter().enumerate() {
                    let id = s.add_mesh(grid(n));
                    for j in 0..2 {
                        let t = Transform {
                            matrix: Mat4::from_scale_rotation_translation(
                                Vec3::splat(0.3),
                                Quat::from_rotation_y(0.4 * j as f32),
                                Vec3::new(-0.8 + 0.6 * k as f32, 0.05, -0.6 + 1.2 * j as f32),
                            ),
                        };
                        s.add_instance(id, None, t);
                    }
                }
                let data = SceneData::new(&s);
                assert!(data.geometry.is_two_level());
                let mut view = View::from_camera(s.camera.as_ref().unwrap());
                (view.width, view.height) = (24, 16);
                render(&data, &view, &settings(4))
            })
    };
    let (one, three) = (build_and_render(1), build_and_render(3));
    let bits = |f: &eyeadapt_tracer::Frame| {
        f.rgb
            .iter()
            .flat_map(|p| p.map(f32::to_bits))
            .collect::<Vec<_>>()
    };
    assert!(one.rgb.iter().any(|p| p[0] > 0.0));
    assert_eq!(bits(&one), bits(&three));
}
