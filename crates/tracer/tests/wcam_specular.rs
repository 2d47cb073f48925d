//! The WCAM re-render's specular modes (estimators.md §2.3): on Lambertian surfaces all three
//! give the same bits; on a glossy plastic `diffuse_only` drops the coating's highlight and
//! nothing else; `exclude_delta` drops what is seen in a mirror.
use eyeadapt_tracer::{AchromaticSpecular, Frame, SceneData, View, render};
use std::path::Path;

mod common;

/// A floor of material `floor`, a tall grey back wall, a small area light above and a grey sky, seen from
/// where the floor shows the light's mirror image (at z ≈ 0.5).
fn scene(floor: &str) -> eyeadapt_scene::Scene {
    let text = format!(
        r#"
[camera]
position = [0.0, 1.0, 2.0]
look_at = [0.0, 0.2, 0.0]
fov_deg = 50.0
width = 16
height = 16

[environment]
radiance = [0.5, 0.5, 0.5]

[[materials]]
name = "diffuse"
type = "diffuse"
reflectance = [0.5, 0.3, 0.2]

[[materials]]
name = "plastic"
type = "plastic"
reflectance = [0.5, 0.3, 0.2]
roughness = 0.05
ior = 1.5

[[materials]]
name = "mirror"
type = "conductor"
roughness = 0.0

[[materials]]
name = "wall"
type = "diffuse"
reflectance = [0.6, 0.6, 0.6]

[[materials]]
name = "light"
type = "diffuse"
reflectance = [0.0, 0.0, 0.0]
emission = [10.0, 10.0, 10.0]

[[shapes]]
type = "quad"
material = "{floor}"
corner = [-2.0, 0.0, -2.0]
u = [0.0, 0.0, 4.0]
v = [4.0, 0.0, 0.0]

[[shapes]]
type = "quad"
material = "wall"
corner = [-2.0, 0.0, -2.0]
u = [4.0, 0.0, 0.0]
v = [0.0, 8.0, 0.0]

[[shapes]]
type = "quad"
material = "light"
corner = [-0.3, 1.0, -1.3]
u = [0.6, 0.0, 0.0]
v = [0.0, 0.0, 0.6]
"#
    );
    eyeadapt_scene::load_scene_str(&text, Path::new("wcam_specular.toml")).unwrap()
}

fn shoot(floor: &str, mode: AchromaticSpecular) -> Frame {
    let s = scene(floor);
    let view = View::from_camera(s.camera.as_ref().unwrap());
    let settings = eyeadapt_tracer::RenderSettings {
        wcam_specular: mode,
        guiding: Default::default(),
        ..common::settings(16, 1, 4)
    };
    render(&SceneData::new(&s), &view, &settings)
}

fn lum(c: [f32; 3]) -> f32 {
    eyeadapt_tracer::luminance(glam::Vec3A::from(c))
}

#[test]
fn every_mode_gives_the_same_bits_on_lambertian_surfaces() {
    let include = shoot("diffuse", AchromaticSpecular::Include);
    for mode in [
        AchromaticSpecular::ExcludeDelta,
        AchromaticSpecular::DiffuseOnly,
    ] {
        let f = shoot("diffuse", mode);
        assert_eq!(f.achromatic, include.achromatic, "{mode:?}");
        assert_eq!(f.rgb, include.rgb, "{mode:?}");
    }
    assert!(include.achromatic.iter().any(|&a| lum(a) > 0.0));
}

#[test]
fn diffuse_only_drops_a_plastic_highlight_and_keeps_its_base() {
    let include = shoot("plastic", AchromaticSpecular::Include);
    let exclude = shoot("plastic", AchromaticSpecular::ExcludeDelta);
    let diffuse = shoot("plastic", AchromaticSpecular::DiffuseOnly);
    // A rough coating has no delta lobe.
    assert_eq!(exclude.achromatic, include.achromatic);
    // The beauty image and the other AOVs do not depend on the mode.
    assert_eq!(diffuse.rgb, include.rgb);
    assert_eq!(diffuse.irradiance, include.irradiance);
    // Same samples, and Y(f) = spec + Y(f_d) ≥ Y(f_d) on each of them.
    let (mut peak_ratio, mut base) = (0.0f32, 0.0f32);
    for (a, d) in include.achromatic.iter().zip(&diffuse.achromatic) {
        let (a, d) = (lum(*a), lum(*d));
        assert!(d <= a * (1.0 + 1e-5) + 1e-9, "{d} > {a}");
        base += d;
        if d > 0.0 {
            peak_ratio = peak_ratio.max(a / d);
        }
    }
    assert!(base > 0.0);
    // The light's mirror image on the floor: the highlight dwarfs the base there.
    assert!(peak_ratio > 2.5, "{peak_ratio}");
}

#[test]
fn exclude_delta_drops_what_a_mirror_shows() {
    let include = shoot("mirror", AchromaticSpecular::Include);
    let exclude = shoot("mirror", AchromaticSpecular::ExcludeDelta);
    let diffuse = shoot("mirror", AchromaticSpecular::DiffuseOnly);
    assert_eq!(exclude.rgb, include.rgb);
    let (w, h) = (include.width, include.height);
    // The middle of the bottom row sees only the floor, which mirrors the wall.
    let bottom = (h - 1) * w + w / 4..h * w - w / 4;
    assert!(bottom.clone().all(|i| lum(include.achromatic[i]) > 0.0));
    assert!(bottom.clone().all(|i| exclude.achromatic[i] == [0.0; 3]));
    assert!(bottom.clone().all(|i| diffuse.achromatic[i] == [0.0; 3]));
    // The wall seen directly (top row) keeps its re-render.
    for i in 0..w {
        assert_eq!(exclude.achromatic[i], include.achromatic[i]);
    }
}
