//! The part of the fingerprint test for what TOML scenes reach since they took the XML
//! reader's surface detail: anisotropic roughness (`alpha_v`), masks, normal and bump maps.
use super::Change;
use eyeadapt_scene::{Bsdf, Distribution, Material, Param, Rgb, Scene, TextureId};

/// The scene with every type and every variant in it: the base scene and [`materials`].
pub fn full() -> Scene {
    let mut s = super::base();
    s.materials.extend(materials());
    s
}

/// One change of every field of [`full`], by name.
pub fn changes() -> Vec<(&'static str, Change)> {
    let mut all = super::base_changes();
    all.extend(surface_changes());
    all
}

/// Appended to the base scene's materials, so their indices are `FIRST` and `FIRST + 1`.
const FIRST: usize = 3;

/// A masked, normal-mapped, bump-mapped anisotropic conductor, and an anisotropic rough
/// dielectric.
fn materials() -> Vec<Material> {
    let conductor = Bsdf::Conductor {
        alpha: Param::Const(0.1),
        alpha_v: Some(Param::Const(0.3)),
        distribution: Distribution::Ggx,
        eta: Rgb::splat(0.2),
        k: Rgb::splat(3.0),
        specular_reflectance: Param::Const(Rgb::ONE),
    };
    let bumped = Bsdf::BumpMap {
        height: TextureId(1),
        scale: 0.5,
        bsdf: Box::new(conductor),
    };
    let normal_mapped = Bsdf::NormalMap {
        normals: TextureId(0),
        bsdf: Box::new(bumped),
    };
    vec![
        Material {
            name: "surface".into(),
            bsdf: Bsdf::Mask {
                opacity: Param::Texture(TextureId(1)),
                bsdf: Box::new(normal_mapped),
            },
            emission: Rgb::ZERO,
        },
        Material {
            name: "frosted".into(),
            bsdf: Bsdf::RoughDielectric {
                alpha: Param::Const(0.1),
                alpha_v: Some(Param::Texture(TextureId(1))),
                distribution: Distribution::Ggx,
                eta: 1.5,
                specular_reflectance: Rgb::ONE,
                specular_transmittance: Rgb::ONE,
            },
            emission: Rgb::ZERO,
        },
    ]
}

/// The mask of material `FIRST`, and what it wraps, one level at a time.
fn mask(s: &mut Scene) -> (&mut Param<f32>, &mut Bsdf) {
    match &mut s.materials[FIRST].bsdf {
        Bsdf::Mask { opacity, bsdf } => (opacity, bsdf),
        _ => unreachable!(),
    }
}

fn normal_map(s: &mut Scene) -> (&mut TextureId, &mut Bsdf) {
    match mask(s).1 {
        Bsdf::NormalMap { normals, bsdf } => (normals, bsdf),
        _ => unreachable!(),
    }
}

fn bump_map(s: &mut Scene) -> (&mut TextureId, &mut f32, &mut Bsdf) {
    match normal_map(s).1 {
        Bsdf::BumpMap {
            height,
            scale,
            bsdf,
        } => (height, scale, bsdf),
        _ => unreachable!(),
    }
}

fn conductor_alpha_v(s: &mut Scene) -> &mut Option<Param<f32>> {
    match bump_map(s).2 {
        Bsdf::Conductor { alpha_v, .. } => alpha_v,
        _ => unreachable!(),
    }
}

fn dielectric_alpha_v(s: &mut Scene) -> &mut Option<Param<f32>> {
    match &mut s.materials[FIRST + 1].bsdf {
        Bsdf::RoughDielectric { alpha_v, .. } => alpha_v,
        _ => unreachable!(),
    }
}

fn surface_changes() -> Vec<(&'static str, Change)> {
    vec![
        ("mask.opacity", |s| {
            *mask(s).0 = Param::Texture(TextureId(0))
        }),
        ("mask.opacity const", |s| *mask(s).0 = Param::Const(0.5)),
        ("mask removed", |s| {
            let (_, inner) = mask(s);
            let inner = inner.clone();
            s.materials[FIRST].bsdf = inner;
        }),
        ("normal_map.normals", |s| *normal_map(s).0 = TextureId(1)),
        ("normal_map removed", |s| {
            let inner = normal_map(s).1.clone();
            *mask(s).1 = inner;
        }),
        ("bump_map.height", |s| *bump_map(s).0 = TextureId(0)),
        ("bump_map.scale", |s| *bump_map(s).1 = -0.5),
        ("bump_map removed", |s| {
            let inner = bump_map(s).2.clone();
            *normal_map(s).1 = inner;
        }),
        ("conductor.alpha_v", |s| {
            *conductor_alpha_v(s) = Some(Param::Const(0.4))
        }),
        ("conductor.alpha_v texture", |s| {
            *conductor_alpha_v(s) = Some(Param::Texture(TextureId(1)))
        }),
        ("conductor.alpha_v none", |s| *conductor_alpha_v(s) = None),
        ("rough_dielectric.alpha_v", |s| {
            *dielectric_alpha_v(s) = Some(Param::Texture(TextureId(0)))
        }),
        ("rough_dielectric.alpha_v none", |s| {
            *dielectric_alpha_v(s) = None
        }),
    ]
}
