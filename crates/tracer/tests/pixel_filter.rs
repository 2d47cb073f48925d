//! Reconstruction filters: the beauty image under tent and Gaussian filters is deterministic
//! for any thread count (and more than 32 rows, so that it crosses the film's row blocks),
//! keeps a constant image constant, and blurs an edge.
use eyeadapt_scene::{Camera, Material, PixelFilter, Scene, quad_mesh};
use eyeadapt_tracer::{Frame, PathSettings, RenderSettings, SceneData, View, render};
use glam::Vec3;

fn settings(filter: PixelFilter) -> RenderSettings {
    RenderSettings {
        spp: 4,
        path: PathSettings {
            max_depth: 2,
            rr_depth: 5,
        },
        seed: 3,
        frame: 0,
        filter,
        wcam_specular: Default::default(),
        guiding: Default::default(),
    }
}

/// A black quad covering the left half of the view, in front of a white environment.
fn half_black() -> (SceneData, View) {
    let mut scene = Scene::default();
    let black = scene.add_material(Material::diffuse("black", Vec3::ZERO));
    let quad = quad_mesh(
        Vec3::new(-10.0, -10.0, 0.0),
        Vec3::new(10.0, 0.0, 0.0),
        Vec3::new(0.0, 20.0, 0.0),
    );
    scene.add_world_mesh(quad, Some(black));
    scene.environment = Some(Vec3::ONE);
    let view = View::from_camera(&Camera {
        position: Vec3::new(0.0, 0.0, 5.0),
        look_at: Vec3::ZERO,
        up: Vec3::Y,
        fov_deg: 40.0,
        width: 16,
        height: 40,
        projection: eyeadapt_scene::Projection::Pinhole,
    });
    (SceneData::new(&scene), view)
}

fn bits(f: &Frame) -> Vec<[u32; 3]> {
    f.rgb.iter().map(|p| p.map(f32::to_bits)).collect()
}

#[test]
fn filtered_images_are_bit_identical_for_1_2_and_8_threads() {
    let (data, view) = half_black();
    for filter in [PixelFilter::GAUSSIAN, PixelFilter::Tent { radius: 1.0 }] {
        let images: Vec<_> = [1, 2, 8]
            .iter()
            .map(|&t| {
                let pool = rayon::ThreadPoolBuilder::new()
                    .num_threads(t)
                    .build()
                    .unwrap();
                pool.install(|| bits(&render(&data, &view, &settings(filter))))
            })
            .collect();
        assert_eq!(images[0], images[1], "{filter:?}");
        assert_eq!(images[0], images[2], "{filter:?}");
    }
}

#[test]
fn filters_keep_a_constant_image_and_blur_an_edge() {
    let (data, view) = half_black();
    let boxed = render(&data, &view, &settings(PixelFilter::Box));
    let gauss = render(&data, &view, &settings(PixelFilter::GAUSSIAN));
    let row = 20 * 16;
    for x in [0, 1, 2, 3, 12, 13, 14, 15] {
        // Far from the edge (x = 8) every sample agrees: weights cancel exactly.
        assert!(
            (gauss.rgb[row + x][0] - boxed.rgb[row + x][0]).abs() < 1e-6,
            "{x}"
        );
    }
    // Next to the edge the filter mixes in the other side: the first white column is darker
    // and the last black one lighter than with the box.
    assert!(gauss.rgb[row + 8][0] < boxed.rgb[row + 8][0]);
    assert!(gauss.rgb[row + 7][0] > boxed.rgb[row + 7][0]);
    // The AOVs stay per-pixel means.
    assert_eq!(gauss.hit, boxed.hit);
}
