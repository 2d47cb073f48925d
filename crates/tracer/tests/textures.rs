//! Textured materials as the estimators see them: the albedo AOV follows the texture.
use eyeadapt_scene::{Camera, Material, Rgb, Scene, quad_mesh};
use eyeadapt_tracer::{PathSettings, RenderSettings, SceneData, View, render};
use glam::Vec3;

#[test]
fn the_albedo_aov_reads_textured_reflectance() {
    // A floor seen from straight above, its reflectance a 2×2 checkerboard over the quad's UVs:
    // the albedo AOV (what WCAM and NCNS read as the surface colour) shows both colours.
    let mut s = Scene::default();
    let check = s.add_texture(eyeadapt_scene::Texture::Checkerboard {
        color0: Rgb::new(0.8, 0.1, 0.1),
        color1: Rgb::new(0.1, 0.1, 0.8),
        to_uv: glam::Affine2::IDENTITY,
    });
    let floor = s.add_material(Material {
        name: "floor".into(),
        bsdf: eyeadapt_scene::Bsdf::Diffuse {
            reflectance: eyeadapt_scene::Param::Texture(check),
        },
        emission: Rgb::ZERO,
    });
    s.add_world_mesh(
        quad_mesh(
            Vec3::new(-1.0, 0.0, 1.0),
            Vec3::new(2.0, 0.0, 0.0),
            Vec3::new(0.0, 0.0, -2.0),
        ),
        Some(floor),
    );
    s.environment = Some(Rgb::ONE);
    let view = View::from_camera(&Camera {
        position: Vec3::new(0.0, 3.0, 0.0),
        look_at: Vec3::ZERO,
        up: Vec3::new(0.0, 0.0, -1.0),
        fov_deg: 30.0,
        width: 16,
        height: 16,
        projection: eyeadapt_scene::Projection::Pinhole,
    });
    let settings = RenderSettings {
        spp: 4,
        path: PathSettings::default(),
        seed: 1,
        frame: 0,
        filter: Default::default(),
        wcam_specular: Default::default(),
        guiding: Default::default(),
    };
    let f = render(&SceneData::new(&s), &view, &settings);
    // Quad UV (0, 0) is at (−1, 0, 1): the image's bottom-left (up is −z). u < ½ and v < ½
    // there: color0. Pixel rows run top to bottom.
    let at = |x: usize, y: usize| Vec3::from(f.albedo[y * 16 + x]);
    assert!((at(3, 12) - Vec3::new(0.8, 0.1, 0.1)).abs().max_element() < 1e-5);
    assert!((at(12, 12) - Vec3::new(0.1, 0.1, 0.8)).abs().max_element() < 1e-5);
    assert!((at(12, 3) - Vec3::new(0.8, 0.1, 0.1)).abs().max_element() < 1e-5);
    assert!((at(3, 3) - Vec3::new(0.1, 0.1, 0.8)).abs().max_element() < 1e-5);
}
