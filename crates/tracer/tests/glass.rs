//! Transmission through the integrator: glass in a uniform environment shows the environment
//! unchanged (the white furnace through refraction, with the 1/η² radiance scaling in and
//! out), Mitsuba's one-sided BSDFs are black from behind, masks let light through, and the
//! AOVs behind glass read the first non-specular hit.
use eyeadapt_scene::{
    Bsdf, Camera, Distribution, Material, Param, Rgb, Scene, quad_mesh, sphere_mesh,
};
use eyeadapt_tracer::{Frame, PathSettings, RenderSettings, SceneData, View, render};
use glam::Vec3;

fn material(s: &mut Scene, bsdf: Bsdf) -> eyeadapt_scene::MaterialId {
    s.add_material(Material {
        name: "m".into(),
        bsdf,
        emission: Rgb::ZERO,
    })
}

fn glass(eta: f32) -> Bsdf {
    Bsdf::Dielectric {
        eta,
        specular_reflectance: Rgb::ONE,
        specular_transmittance: Rgb::ONE,
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
        seed: 3,
        frame: 0,
        filter: Default::default(),
        wcam_specular: Default::default(),
        guiding: Default::default(),
    };
    render(&SceneData::new(s), &view, &settings)
}

fn mean(v: &[impl Copy + Into<Vec3>]) -> Vec3 {
    v.iter().map(|&x| x.into()).sum::<Vec3>() / v.len() as f32
}

#[test]
fn glass_in_a_uniform_environment_shows_the_environment() {
    for bsdf in [
        glass(1.5),
        Bsdf::ThinDielectric {
            eta: 1.5,
            specular_reflectance: Rgb::ONE,
            specular_transmittance: Rgb::ONE,
        },
    ] {
        let mut s = Scene::default();
        let m = material(&mut s, bsdf.clone());
        s.add_world_mesh(sphere_mesh(Vec3::ZERO, 1.0, 4), Some(m));
        s.environment = Some(Rgb::ONE);
        let f = shoot(&s, 64, 64);
        let l = mean(&f.rgb);
        assert!((l - Vec3::ONE).abs().max_element() < 0.01, "{bsdf:?}: {l}");
    }
    // A rough interface loses the energy of single-scattering microfacets, but only a little.
    let mut s = Scene::default();
    let m = material(
        &mut s,
        Bsdf::RoughDielectric {
            alpha: Param::Const(0.3),
            alpha_v: None,
            distribution: Distribution::Beckmann,
            eta: 1.5,
            specular_reflectance: Rgb::ONE,
            specular_transmittance: Rgb::ONE,
        },
    );
    s.add_world_mesh(sphere_mesh(Vec3::ZERO, 1.0, 4), Some(m));
    s.environment = Some(Rgb::ONE);
    let l = mean(&shoot(&s, 64, 64).rgb);
    assert!(l.max_element() < 1.0 + 0.01 && l.min_element() > 0.9, "{l}");
}

#[test]
fn one_sided_backs_are_black_and_masks_let_light_through() {
    // A quad facing away from the camera (its front is −z) in front of a white environment.
    let quad = quad_mesh(
        Vec3::new(-2.0, -2.0, 0.0),
        Vec3::new(0.0, 4.0, 0.0),
        Vec3::new(4.0, 0.0, 0.0),
    );
    let white = Bsdf::Diffuse {
        reflectance: Param::Const(Rgb::splat(0.5)),
    };
    let render_with = |bsdf: Bsdf| {
        let mut s = Scene::default();
        let m = material(&mut s, bsdf);
        s.add_world_mesh(quad.clone(), Some(m));
        s.environment = Some(Rgb::ONE);
        mean(&shoot(&s, 16, 8).rgb)
    };
    let two_sided = render_with(white.clone());
    assert!(
        (two_sided - Vec3::splat(0.5)).abs().max_element() < 0.02,
        "{two_sided}"
    );
    let one_sided = render_with(Bsdf::OneSided(Box::new(white.clone())));
    assert_eq!(one_sided, Vec3::ZERO);
    // A mask of opacity ¼: a quarter of the diffuse surface, three quarters of the sky.
    let mask = render_with(Bsdf::Mask {
        opacity: Param::Const(0.25),
        bsdf: Box::new(white),
    });
    let expect = 0.25 * 0.5 + 0.75;
    assert!(
        (mask - Vec3::splat(expect)).abs().max_element() < 0.02,
        "{mask}"
    );
}

#[test]
fn aovs_behind_glass_read_the_first_non_specular_hit() {
    // A diffuse wall at z = −1 behind a thin pane at z = 0.5, lit by the environment.
    let mut s = Scene::default();
    let wall = material(
        &mut s,
        Bsdf::Diffuse {
            reflectance: Param::Const(Rgb::new(0.6, 0.4, 0.2)),
        },
    );
    let pane = material(
        &mut s,
        Bsdf::ThinDielectric {
            eta: 1.5,
            specular_reflectance: Rgb::ONE,
            specular_transmittance: Rgb::ONE,
        },
    );
    let quad = |z: f32| {
        quad_mesh(
            Vec3::new(-3.0, -3.0, z),
            Vec3::new(6.0, 0.0, 0.0),
            Vec3::new(0.0, 6.0, 0.0),
        )
    };
    s.add_world_mesh(quad(-1.0), Some(wall));
    s.add_world_mesh(quad(0.5), Some(pane));
    s.environment = Some(Rgb::ONE);
    let f = shoot(&s, 256, 8);
    // Seen through the pane with probability T (≈ 0.92 at normal incidence, 2R/(1+R) reflected).
    let albedo = mean(&f.albedo);
    let t = 1.0 - 2.0 * 0.04 / 1.04;
    let expect = Vec3::new(0.6, 0.4, 0.2) * t;
    assert!(
        (albedo - expect).abs().max_element() < 0.03,
        "{albedo} vs {expect}"
    );
    // The depth is the wall's (5, along the undeflected ray) where the path went through,
    // the pane's (3.5) where it was reflected to the sky.
    let centre = f.depth[8 * 16 + 8];
    let expect = t * 5.0 + (1.0 - t) * 3.5;
    assert!((centre - expect).abs() < 0.1, "{centre} vs {expect}");
}

#[test]
fn a_normal_map_turns_the_shading_normal() {
    // A floor facing the camera, lit by a point light off to +x: a normal map that tilts the
    // normals towards +x brightens it, one that tilts them away darkens it, a flat one
    // (rgb ½, ½, 1) changes nothing.
    let floor = quad_mesh(
        Vec3::new(-2.0, -2.0, 0.0),
        Vec3::new(4.0, 0.0, 0.0),
        Vec3::new(0.0, 4.0, 0.0),
    );
    let lit = |normal: Option<Rgb>| {
        let mut s = Scene::default();
        let diffuse = Bsdf::Diffuse {
            reflectance: Param::Const(Rgb::splat(0.5)),
        };
        let bsdf = match normal {
            None => diffuse,
            Some(c) => {
                let t = s.add_texture(eyeadapt_scene::Texture::Checkerboard {
                    color0: c,
                    color1: c,
                    to_uv: glam::Affine2::IDENTITY,
                });
                Bsdf::NormalMap {
                    normals: t,
                    bsdf: Box::new(diffuse),
                }
            }
        };
        let m = material(&mut s, bsdf);
        s.add_world_mesh(floor.clone(), Some(m));
        s.lights.push(eyeadapt_scene::Light::Point {
            position: Vec3::new(3.0, 0.0, 1.0),
            intensity: Rgb::splat(10.0),
        });
        mean(&shoot(&s, 4, 2).rgb).x
    };
    let plain = lit(None);
    let flat = lit(Some(Rgb::new(0.5, 0.5, 1.0)));
    // Tangent +x is ∂p/∂u, which runs along the quad's u edge (+x).
    let towards = lit(Some(Rgb::new(0.85, 0.5, 0.85)));
    let away = lit(Some(Rgb::new(0.15, 0.5, 0.85)));
    assert!((flat - plain).abs() < 1e-4 * plain, "{flat} vs {plain}");
    assert!(
        towards > 1.2 * plain && away < 0.8 * plain,
        "{away} < {plain} < {towards}"
    );
}
