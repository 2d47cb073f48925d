//! `type = "principled"` in TOML scenes: its keys, defaults, texture, the `specular`→IOR
//! mapping, and located errors (bad weights, `ior` with `specular`, its keys on other types).
use eyeadapt_scene::{Bsdf, Param, Principled, Rgb, Scene, load_scene_str};
use std::path::Path;

fn load(material: &str) -> Result<Scene, String> {
    let text = format!(
        "[camera]\nposition = [0.0, 0.0, 3.0]\nlook_at = [0.0, 0.0, 0.0]\nfov_deg = 40.0\nwidth = 8\nheight = 8\n\n\
         [[textures]]\nname = \"checks\"\ntype = \"checkerboard\"\n\n\
         [[materials]]\nname = \"m\"\n{material}\n\n\
         [[shapes]]\ntype = \"sphere\"\nmaterial = \"m\"\n"
    );
    load_scene_str(&text, Path::new("s.toml")).map_err(|e| e.to_string())
}

fn principled(s: &Scene) -> &Principled {
    match &s.materials[0].bsdf {
        Bsdf::Principled(p) => p,
        other => panic!("{other:?}"),
    }
}

#[test]
fn principled_reads_its_keys_with_mitsubas_defaults() {
    let s = load("type = \"principled\"").unwrap();
    assert_eq!(
        *principled(&s),
        Principled::new(Param::Const(Rgb::splat(0.5)))
    );
    let s = load(
        "type = \"principled\"\nbase_color_texture = \"checks\"\nroughness = 0.3\nmetallic = 0.2\n\
         spec_tint = 0.1\nanisotropic = 0.4\nsheen = 0.5\nsheen_tint = 0.6\nclearcoat = 1.0\n\
         clearcoat_gloss = 0.9\nspec_trans = 0.7\nflatness = 0.8\nior = 1.33",
    )
    .unwrap();
    let p = principled(&s);
    assert!(matches!(p.base_color, Param::Texture(_)));
    let got = [
        p.roughness,
        p.metallic,
        p.spec_tint,
        p.anisotropic,
        p.sheen,
        p.sheen_tint,
        p.clearcoat,
        p.clearcoat_gloss,
        p.spec_trans,
        p.flatness,
    ];
    let want = [0.3, 0.2, 0.1, 0.4, 0.5, 0.6, 1.0, 0.9, 0.7, 0.8];
    for (g, w) in got.iter().zip(want) {
        assert_eq!(*g, Param::Const(w));
    }
    assert_eq!(p.eta, 1.33);
    let s = load("type = \"principled\"\nspecular = 0.5").unwrap();
    assert!((principled(&s).eta - 1.5).abs() < 1e-6);
}

#[test]
fn bad_principled_keys_are_errors_at_the_key() {
    for (body, line, msg) in [
        (
            "type = \"principled\"\nmetallic = 1.5",
            15,
            "metallic 1.5 must be in [0, 1]",
        ),
        (
            "type = \"principled\"\nroughness = -0.1",
            15,
            "roughness -0.1 must be in [0, 1]",
        ),
        (
            "type = \"principled\"\nior = -2.0",
            15,
            "ior -2 must be positive",
        ),
        (
            "type = \"principled\"\nior = 1.4\nspecular = 0.5",
            16,
            "give either `ior` or `specular`",
        ),
        (
            "type = \"principled\"\nbase_color = [1.5, 0.0, 0.0]",
            15,
            "base_color",
        ),
        (
            "type = \"diffuse\"\nsheen = 0.5",
            15,
            "key `sheen` does not apply to type \"diffuse\"",
        ),
    ] {
        let e = load(body).unwrap_err();
        assert!(e.contains(&format!("s.toml:{line}:")), "{body}: {e}");
        assert!(e.contains(msg), "{body}: {e}");
    }
}
