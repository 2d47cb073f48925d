//! BSDFs built around others, through the integrator, in a uniform environment (radiance 1)
//! where the answers are known: a blend renders as the blend of its reflectances, a null
//! surface is invisible, and a bump map keeps a white surface within the furnace bound.
use eyeadapt_scene::{
    Bitmap, Bsdf, Camera, FilterType, Image, Material, Param, Rgb, Scene, Texture, WrapMode,
    quad_mesh, sphere_mesh,
};
use eyeadapt_tracer::{Frame, PathSettings, RenderSettings, SceneData, View, render};
use glam::{Affine2, Vec3};
use std::sync::Arc;

fn material(s: &mut Scene, bsdf: Bsdf) -> eyeadapt_scene::MaterialId {
    s.add_material(Material {
        name: "m".into(),
        bsdf,
        emission: Rgb::ZERO,
    })
}

fn diffuse(r: f32) -> Bsdf {
    Bsdf::Diffuse {
        reflectance: Param::Const(Rgb::splat(r)),
    }
}

/// Renders `s` from (0, 0, 4) towards the origin, 16 × 16 px.
fn shoot(s: &Scene, spp: u32, max_depth: i32) -> Frame {
    let view = View::from_camera(&Camera {
        position: Vec3::new(0.0, 0.0, 4.0),
        look_at: Vec3::ZERO,
        up: Vec3::Y,
        fov_deg: 30.0,
        width: 16,
        height: 16,
        projection: Default::default(),
    });
    let settings = RenderSettings {
        spp,
        path: PathSettings {
            max_depth,
            rr_depth: 50,
        },
        seed: 5,
        frame: 0,
        filter: Default::default(),
        wcam_specular: Default::default(),
        guiding: Default::default(),
    };
    render(&SceneData::new(s), &view, &settings)
}

fn mean(f: &Frame) -> Vec3 {
    f.rgb.iter().map(|&x| Vec3::from(x)).sum::<Vec3>() / f.rgb.len() as f32
}

/// A sphere of `bsdf` in the environment, direct light only (each sphere pixel shows the
/// BSDF's albedo).
fn sphere_in_furnace(bsdf: Bsdf) -> Vec3 {
    let mut s = Scene::default();
    let m = material(&mut s, bsdf);
    s.add_world_mesh(sphere_mesh(Vec3::ZERO, 1.0, 4), Some(m));
    s.environment = Some(Rgb::ONE);
    mean(&shoot(&s, 64, 2))
}

#[test]
fn a_blend_renders_as_the_blend_of_its_bsdfs() {
    let blend = Bsdf::Blend {
        weight: Param::Const(0.25),
        bsdfs: Box::new([diffuse(0.8), diffuse(0.2)]),
    };
    let (a, b) = (sphere_in_furnace(blend), sphere_in_furnace(diffuse(0.65)));
    assert!((a - b).abs().max_element() < 0.01, "{a} vs {b}");
    // Weight 0 and 1 are the children.
    for (w, r) in [(0.0, 0.8), (1.0, 0.2)] {
        let blend = Bsdf::Blend {
            weight: Param::Const(w),
            bsdfs: Box::new([diffuse(0.8), diffuse(0.2)]),
        };
        let (a, b) = (sphere_in_furnace(blend), sphere_in_furnace(diffuse(r)));
        assert!((a - b).abs().max_element() < 1e-3, "weight {w}: {a} vs {b}");
    }
}

#[test]
fn a_null_surface_is_invisible() {
    let scene = |with_null: bool| {
        let mut s = Scene::default();
        let m = material(&mut s, diffuse(0.5));
        s.add_world_mesh(sphere_mesh(Vec3::ZERO, 1.0, 4), Some(m));
        if with_null {
            let n = material(&mut s, Bsdf::Null);
            // A pane between the camera and the sphere, covering the whole view.
            let q = quad_mesh(
                Vec3::new(-2.0, -2.0, 2.0),
                Vec3::new(4.0, 0.0, 0.0),
                Vec3::new(0.0, 4.0, 0.0),
            );
            s.add_world_mesh(q, Some(n));
        }
        s.environment = Some(Rgb::ONE);
        s
    };
    let (a, b) = (
        mean(&shoot(&scene(true), 64, 8)),
        mean(&shoot(&scene(false), 64, 8)),
    );
    assert!((a - b).abs().max_element() < 0.01, "{a} vs {b}");
    // Alone in the environment, it shows the environment exactly.
    let mut s = Scene::default();
    let n = material(&mut s, Bsdf::Null);
    s.add_world_mesh(sphere_mesh(Vec3::ZERO, 1.0, 3), Some(n));
    s.environment = Some(Rgb::ONE);
    let l = mean(&shoot(&s, 4, 8));
    assert!((l - Vec3::ONE).abs().max_element() < 1e-6, "{l}");
}

#[test]
fn a_bumped_white_surface_stays_below_the_furnace_bound() {
    // A ramp h = u (rising along x, 32 texels), bilinear: a constant slope over the quad.
    let ramp = Image {
        width: 32,
        height: 1,
        texels: (0..32).map(|i| Rgb::splat(i as f32 / 31.0)).collect(),
    };
    let render_quad = |bump: Option<f32>| {
        let mut s = Scene::default();
        let h = s.add_texture(Texture::Bitmap(Bitmap {
            filename: "ramp".into(),
            image: Arc::new(ramp.clone()),
            raw: true,
            filter: FilterType::Bilinear,
            wrap: WrapMode::Clamp,
            to_uv: Affine2::IDENTITY,
        }));
        let bsdf = match bump {
            Some(scale) => Bsdf::BumpMap {
                height: h,
                scale,
                bsdf: Box::new(diffuse(1.0)),
            },
            None => diffuse(1.0),
        };
        let m = material(&mut s, bsdf);
        let q = quad_mesh(
            Vec3::new(-3.0, -3.0, 0.0),
            Vec3::new(6.0, 0.0, 0.0),
            Vec3::new(0.0, 6.0, 0.0),
        );
        s.add_world_mesh(q, Some(m));
        s.environment = Some(Rgb::ONE);
        mean(&shoot(&s, 64, 2))
    };
    let flat = render_quad(None);
    assert!((flat - Vec3::ONE).abs().max_element() < 0.01, "{flat}");
    // h rises by `scale` over the quad (∂h/∂u = scale, u spanning 6 units), tilting the
    // normal: the surface loses the light from below the quad's plane and the shadowing
    // term's share, but never gains.
    for scale in [1.0, 4.0] {
        let bumped = render_quad(Some(scale));
        assert!(
            bumped.max_element() <= 1.0 + 0.01 && bumped.min_element() > 0.5,
            "scale {scale}: {bumped}"
        );
        assert!(
            bumped.x < flat.x - 0.005,
            "scale {scale}: {bumped} vs {flat}"
        );
    }
}
