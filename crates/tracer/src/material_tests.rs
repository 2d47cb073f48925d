//! Unit tests of `material.rs`.
use super::*;

fn material(bsdf: SceneBsdf) -> Material {
    Material {
        name: "m".into(),
        bsdf,
        emission: Rgb::ZERO,
    }
}

fn diffuse() -> SceneBsdf {
    SceneBsdf::Diffuse {
        reflectance: Param::Const(Rgb::splat(0.5)),
    }
}

fn pane() -> SceneBsdf {
    SceneBsdf::ThinDielectric {
        eta: 1.5,
        specular_reflectance: Rgb::ONE,
        specular_transmittance: Rgb::ONE,
    }
}

fn blend(a: SceneBsdf, b: SceneBsdf) -> SceneBsdf {
    SceneBsdf::Blend {
        weight: Param::Const(0.0),
        bsdfs: Box::new([a, b]),
    }
}

/// The shadow rays' shortcut (`shadow.rs`) skips the interaction of a material that
/// `may_pass` calls opaque: it must see a pane or a cutout at any depth of blends, even
/// one a blend weight of 0 never selects.
#[test]
fn may_pass_finds_every_see_through_leaf() {
    let mut scene = Scene::default();
    let cases = [
        (diffuse(), [false, false]),
        (pane(), [true, true]),
        (SceneBsdf::Null, [false, true]),
        (
            SceneBsdf::Mask {
                opacity: Param::Const(0.5),
                bsdf: Box::new(diffuse()),
            },
            [false, true],
        ),
        (blend(diffuse(), diffuse()), [false, false]),
        (blend(diffuse(), blend(diffuse(), pane())), [true, true]),
        (blend(SceneBsdf::Null, diffuse()), [false, true]),
    ];
    let ids: Vec<u32> = cases
        .iter()
        .map(|(b, _)| scene.add_material(material(b.clone())).0)
        .collect();
    let materials = Materials::new(&scene);
    for ((bsdf, want), id) in cases.iter().zip(ids) {
        for (cutouts, want) in [false, true].into_iter().zip(want) {
            assert_eq!(
                materials.may_pass(id, cutouts),
                *want,
                "{bsdf:?}, cutouts {cutouts}"
            );
        }
    }
}
