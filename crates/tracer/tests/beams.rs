//! Emitters that vary across their surface or beam, against closed forms: a projector's
//! irradiance on a plane, a textured spot's image, a textured area light seen directly, by
//! light sampling and through MIS at a diffuse floor, and the eye sensor's reading of a
//! projector.
mod common;

use common::settings;
use eyeadapt_scene::{
    Bsdf, Camera, FilterType, Image, Light, Material, Param, Projection, Rgb, Scene, Texture,
    WrapMode, quad_mesh,
};
use eyeadapt_tracer::{EyeSettings, PathSettings, SceneData, View, eye_sensor, render};
use glam::{Mat3, Vec3, Vec3A};
use std::sync::Arc;

/// A 2 × 1 image: red on the left (u < ½), green on the right, read nearest.
fn red_green() -> Texture {
    Texture::Bitmap(eyeadapt_scene::Bitmap {
        filename: "rg.png".into(),
        image: Arc::new(Image {
            width: 2,
            height: 1,
            texels: vec![Rgb::new(1.0, 0.0, 0.0), Rgb::new(0.0, 1.0, 0.0)],
        }),
        raw: true,
        filter: FilterType::Nearest,
        wrap: WrapMode::Clamp,
        to_uv: glam::Affine2::IDENTITY,
    })
}

/// A white diffuse 8 × 8 floor in z = 0 facing +z.
fn floor(s: &mut Scene) {
    let white = s.add_material(Material::diffuse("white", Rgb::ONE));
    s.add_world_mesh(
        quad_mesh(
            Vec3::new(-4.0, -4.0, 0.0),
            Vec3::new(8.0, 0.0, 0.0),
            Vec3::new(0.0, 8.0, 0.0),
        ),
        Some(white),
    );
}

/// Looking down −z: x to the right in the world is the light's +x, y up is its −y.
fn down() -> Mat3 {
    Mat3::from_cols(Vec3::X, Vec3::NEG_Y, Vec3::NEG_Z)
}

/// Irradiance at `x` on the floor (normal +z) from the only light, by one light sample.
fn irradiance(data: &SceneData, x: Vec3) -> Vec3A {
    let x = Vec3A::from(x);
    match data.lights.sample(x, Some(Vec3A::Z), 0.5, [0.3, 0.7]) {
        Some(ls) => ls.li * ls.wi.z.max(0.0) / ls.pdf,
        None => Vec3A::ZERO,
    }
}

#[test]
fn a_projector_lights_a_plane_facing_it_with_pi_scale_e_inside_its_frustum() {
    // One unit above the floor, 90° across (t = 1): the frustum meets the floor in [−1, 1]².
    // Mitsuba's factor π·scale·E/(z²·cos θ) times the floor's cos θ is π·scale·E everywhere.
    for (irradiance_param, textures) in [
        (Param::Const(Rgb::new(0.5, 1.0, 2.0)), vec![]),
        (
            Param::Texture(eyeadapt_scene::TextureId(0)),
            vec![red_green()],
        ),
    ] {
        let mut s = Scene {
            textures,
            ..Scene::default()
        };
        floor(&mut s);
        s.lights.push(Light::Projector {
            position: Vec3::new(0.0, 0.0, 1.0),
            frame: down(),
            irradiance: irradiance_param,
            scale: 3.0,
            tan_half_fov_x: 1.0,
            aspect: 1.0,
        });
        let data = SceneData::new(&s);
        let pi3 = 3.0 * std::f32::consts::PI;
        let expect = |x: f32| match irradiance_param {
            Param::Const(c) => Vec3A::from(c) * pi3,
            // u = ½(1 − x): the left texel (red) for x > 0.
            Param::Texture(_) if x > 0.0 => Vec3A::new(pi3, 0.0, 0.0),
            Param::Texture(_) => Vec3A::new(0.0, pi3, 0.0),
        };
        for p in [
            Vec3::new(0.1, 0.2, 0.0),
            Vec3::new(-0.9, 0.5, 0.0),
            Vec3::new(0.7, -0.95, 0.0),
        ] {
            let e = irradiance(&data, p);
            assert!(
                (e - expect(p.x)).abs().max_element() < 1e-4 * pi3 * 2.0,
                "{p}: {e} vs {}",
                expect(p.x)
            );
        }
        // Outside the frustum, and behind the projector: nothing.
        assert_eq!(irradiance(&data, Vec3::new(1.2, 0.0, 0.0)), Vec3A::ZERO);
        assert_eq!(irradiance(&data, Vec3::new(0.0, 0.0, 2.0)), Vec3A::ZERO);
        // The rendered floor (ρ = 1) is scale·E inside the frustum, black outside.
        let view = View::from_camera(&Camera {
            position: Vec3::new(0.0, 0.0, 3.0),
            look_at: Vec3::ZERO,
            up: Vec3::Y,
            fov_deg: 60.0,
            width: 12,
            height: 12,
            projection: Projection::Pinhole,
        });
        let f = render(&data, &view, &settings(4, 1, 2));
        let (w, tan) = (12.0, libm::tanf(30f32.to_radians()));
        for (i, px) in f.rgb.iter().enumerate() {
            // Pixel centre on the floor (the camera looks down −z with +y up).
            let (cx, cy) = ((i % 12) as f32 + 0.5, (i / 12) as f32 + 0.5);
            let (x, y) = (
                (2.0 * cx / w - 1.0) * tan * 3.0,
                (1.0 - 2.0 * cy / w) * tan * 3.0,
            );
            // Pixels on a frustum or texel edge mix both sides.
            if (x.abs() - 1.0).abs() < 0.3 || (y.abs() - 1.0).abs() < 0.3 || x.abs() < 0.3 {
                continue;
            }
            let want = if x.abs() < 1.0 && y.abs() < 1.0 {
                expect(x) / std::f32::consts::PI
            } else {
                Vec3A::ZERO
            };
            // Shadow rays leave 1e-4 above the floor: the light is that much nearer.
            assert!(
                (Vec3A::from(*px) - want).abs().max_element() < 1e-3 * want.max_element().max(1.0),
                "pixel {i} ({x}, {y}): {px:?} vs {want}"
            );
        }
    }
}

#[test]
fn a_textured_spot_throws_its_image_across_the_cone() {
    // Cone 45° (tan 1), one unit above the floor: uv = ½ + ½·(x, −y) on the floor; inside the
    // beam width the intensity is I·tex / d², the irradiance I·tex·cos θ / d².
    let mut s = Scene {
        textures: vec![red_green()],
        ..Scene::default()
    };
    floor(&mut s);
    s.lights.push(Light::TexturedSpot {
        position: Vec3::new(0.0, 0.0, 1.0),
        frame: down(),
        intensity: Rgb::splat(2.0),
        cone_deg: 45.0,
        falloff_deg: 40.0,
        texture: eyeadapt_scene::TextureId(0),
    });
    let data = SceneData::new(&s);
    for (p, colour) in [
        (Vec3::new(0.3, 0.1, 0.0), Vec3A::new(0.0, 1.0, 0.0)),
        (Vec3::new(-0.3, -0.2, 0.0), Vec3A::new(1.0, 0.0, 0.0)),
    ] {
        let d2 = p.x * p.x + p.y * p.y + 1.0;
        let want = colour * (2.0 / d2 / d2.sqrt());
        let e = irradiance(&data, p);
        assert!((e - want).abs().max_element() < 1e-5, "{p}: {e} vs {want}");
    }
    // Beyond the cutoff: nothing.
    assert_eq!(irradiance(&data, Vec3::new(1.2, 0.0, 0.0)), Vec3A::ZERO);
}

/// A unit-radiance-scale square light of side 1, one unit above the origin, facing down, its
/// radiance a 2 × 2 checkerboard of `c0` and `c1` over its UVs.
fn checkered_light(c0: Rgb, c1: Rgb) -> Scene {
    let mut s = Scene::default();
    floor(&mut s);
    let check = s.add_texture(Texture::Checkerboard {
        color0: c0,
        color1: c1,
        to_uv: glam::Affine2::IDENTITY,
    });
    let lamp = s.add_material(Material {
        name: "lamp".into(),
        bsdf: Bsdf::Diffuse {
            reflectance: Param::Const(Rgb::ZERO),
        },
        emission: Rgb::ONE,
    });
    s.emission_textures.push((lamp, check));
    // Winding so that the front side faces −z.
    s.add_world_mesh(
        quad_mesh(
            Vec3::new(-0.5, -0.5, 1.0),
            Vec3::new(0.0, 1.0, 0.0),
            Vec3::new(1.0, 0.0, 0.0),
        ),
        Some(lamp),
    );
    s
}

/// Irradiance under a unit-radiance s × s square centred at height h above the receiver.
fn square_irradiance(s: f64, h: f64) -> f64 {
    let a = s / (2.0 * h);
    let q = (1.0 + a * a).sqrt();
    4.0 * (2.0 * a / q * libm::atan(a / q)) / 2.0
}

#[test]
fn a_textured_area_light_delivers_its_mean_radiance_under_its_centre() {
    // By symmetry each quadrant of the light (two of c0, two of c1) gives a quarter of the
    // square's form factor at the point below its centre.
    let (c0, c1) = (Rgb::new(4.0, 1.0, 0.0), Rgb::new(0.0, 1.0, 2.0));
    let s = checkered_light(c0, c1);
    let data = SceneData::new(&s);
    let e_unit = square_irradiance(1.0, 1.0);
    let want = (c0 + c1).as_dvec3() * 0.5 * e_unit;
    // Light sampling alone (stratified over the quad's area).
    let n = 1 << 14;
    let mut sum = glam::DVec3::ZERO;
    for i in 0..n {
        let (a, b) = (
            (i % 128) as f32 / 128.0 + 1.0 / 256.0,
            (i / 128) as f32 / 128.0 + 1.0 / 256.0,
        );
        if let Some(ls) = data.lights.sample(Vec3A::ZERO, Some(Vec3A::Z), 0.5, [a, b]) {
            sum += Vec3::from(ls.li * ls.wi.z / ls.pdf).as_dvec3();
        }
    }
    let e = sum / n as f64;
    assert!(
        (e - want).abs().max_element() < 2e-3 * want.max_element(),
        "{e} vs {want}"
    );
    // The floor's radiance below the centre (ρ = 1: E/π), rendered with light sampling and
    // BSDF sampling combined by MIS, through a camera that sees only that point.
    let view = View::from_camera(&Camera {
        position: Vec3::new(0.0, 0.0, 0.5),
        look_at: Vec3::ZERO,
        up: Vec3::Y,
        fov_deg: 0.5,
        width: 4,
        height: 4,
        projection: Projection::Pinhole,
    });
    let f = render(&data, &view, &settings(4096, 3, 2));
    let mean = f
        .rgb
        .iter()
        .fold(glam::DVec3::ZERO, |a, p| a + Vec3::from(*p).as_dvec3())
        / 16.0;
    let want = want / std::f64::consts::PI;
    assert!(
        (mean - want).abs().max_element() < 5e-3 * want.max_element(),
        "{mean} vs {want}"
    );
    // Seen directly: the texture's own values (the camera below looks up at the light's
    // quadrants; the light's u runs along y, v along x).
    let up = View::from_camera(&Camera {
        position: Vec3::new(0.0, 0.0, 0.5),
        look_at: Vec3::new(0.0, 0.0, 1.0),
        up: Vec3::Y,
        fov_deg: 60.0,
        width: 8,
        height: 8,
        projection: Projection::Pinhole,
    });
    let f = render(&data, &up, &settings(4, 1, 1));
    let seen: Vec<Vec3> = [(1, 1), (6, 1), (1, 6), (6, 6)]
        .iter()
        .map(|&(x, y)| Vec3::from(f.rgb[y * 8 + x]))
        .collect();
    for v in &seen {
        assert!(
            (*v - c0).abs().max_element() < 1e-5 || (*v - c1).abs().max_element() < 1e-5,
            "{v} is neither colour"
        );
    }
    assert_ne!(seen[0], seen[1], "neighbouring quadrants differ");
    assert_eq!(seen[0], seen[3], "opposite quadrants agree");
}

#[test]
fn the_eye_sensor_reads_a_projector_it_faces() {
    // The eye half a unit below a projector, gazing at it: the only light arrives along the
    // gaze (kernel ½), irradiance π·scale·E/(z²·cos θ) with z = ½, cos θ = 1.
    let mut s = Scene::default();
    s.add_world_mesh(
        quad_mesh(
            Vec3::new(50.0, 50.0, 50.0),
            Vec3::new(0.1, 0.0, 0.0),
            Vec3::new(0.0, 0.1, 0.0),
        ),
        None,
    );
    s.textures = vec![red_green()];
    s.lights.push(Light::Projector {
        position: Vec3::new(0.0, 0.0, 1.0),
        frame: down(),
        irradiance: Param::Texture(eyeadapt_scene::TextureId(0)),
        scale: 1.0,
        tan_half_fov_x: 1.0,
        aspect: 1.0,
    });
    let data = SceneData::new(&s);
    // Just off the axis towards −x: u = ½(1 + 0.02/0.5) > ½, the right texel (green).
    let view = View::from_camera(&Camera {
        position: Vec3::new(-0.01, 0.0, 0.5),
        look_at: Vec3::new(-0.01, 0.0, 1.0),
        up: Vec3::Y,
        fov_deg: 60.0,
        width: 4,
        height: 4,
        projection: Projection::Pinhole,
    });
    let est = eye_sensor(
        &data,
        &view,
        &EyeSettings {
            samples: 256,
            min_samples: 256,
            ..Default::default()
        },
        0,
        PathSettings::default(),
    );
    let d = Vec3::new(0.01, 0.0, 0.5);
    let cos = d.z / d.length();
    let k = (1.0 + cos) / 4.0;
    let want = std::f64::consts::PI / (0.25 * cos as f64) * k as f64;
    let m = est.mean_rgb;
    assert!(m.x.abs() < 1e-9 && m.z.abs() < 1e-9, "{m}");
    assert!((m.y - want).abs() < 1e-4 * want, "{} vs {want}", m.y);
}
