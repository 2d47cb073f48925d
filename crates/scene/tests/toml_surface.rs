//! The TOML forms of what the Mitsuba XML reader already had: anisotropic roughness
//! (`roughness_u`/`roughness_v`), normal and bump maps, opacity masks, a spot carrying a
//! texture and a textured area emission. Each TOML form gives the same scene data as its XML
//! form; bad values are errors at the key.
use eyeadapt_scene::{Bsdf, Light, Param, Rgb, Scene, load_mitsuba_str, load_scene_str};
use std::path::{Path, PathBuf};

/// A folder holding `n.png`, a 2 × 2 image (read raw as a normal map, sRGB as a beam image).
fn folder(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("eyeadapt-tomlsurf-{name}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let img = image::RgbImage::from_fn(2, 2, |x, y| {
        image::Rgb([100 + 50 * x as u8, 128 + 40 * y as u8, 255])
    });
    img.save(dir.join("n.png")).unwrap();
    dir
}

const CAMERA: &str = "[camera]\nposition = [0.0, 0.0, 3.0]\nlook_at = [0.0, 0.0, 0.0]\nfov_deg = 40.0\nwidth = 8\nheight = 8\n";

/// A TOML scene: the camera, `textures` (lines), one material `m` (its lines after the
/// name), a quad with it, and `rest`.
fn toml(dir: &Path, textures: &str, material: &str, rest: &str) -> Result<Scene, String> {
    let text = text(textures, material, rest);
    load_scene_str(&text, &dir.join("test.toml")).map_err(|e| e.to_string())
}

fn text(textures: &str, material: &str, rest: &str) -> String {
    format!(
        "{CAMERA}\n{textures}\n[[materials]]\nname = \"m\"\n{material}\n\n\
         [[shapes]]\ntype = \"quad\"\nmaterial = \"m\"\n\n{rest}\n"
    )
}

fn xml(dir: &Path, body: &str) -> Scene {
    let text = format!("<scene version=\"3.0.0\">\n{body}\n</scene>\n");
    load_mitsuba_str(&text, &dir.join("test.xml"), &[]).unwrap_or_else(|e| panic!("{e}"))
}

/// `x`'s Debug form with every `TextureId(n)` replaced by the texture it names, so that scenes
/// whose texture tables are in another order compare equal.
fn canon(s: &Scene, x: &impl std::fmt::Debug) -> String {
    let text = format!("{x:?}");
    let mut out = String::new();
    let mut rest = text.as_str();
    while let Some(i) = rest.find("TextureId(") {
        out.push_str(&rest[..i]);
        let tail = &rest[i + "TextureId(".len()..];
        let end = tail.find(')').unwrap();
        let id: usize = tail[..end].parse().unwrap();
        out.push_str(&format!("{:?}", s.textures[id]));
        rest = &tail[end + 1..];
    }
    out.push_str(rest);
    // A zero's sign is not content (glam's uv transforms differ in it).
    out.replace("-0.0", "0.0")
}

/// The BSDF of the XML scene's only shape.
fn xml_bsdf(s: &Scene) -> &Bsdf {
    &s.material(s.instances[0].material).bsdf
}

#[test]
fn anisotropic_roughness_matches_xml_alpha_u_and_alpha_v() {
    let dir = folder("aniso");
    let checks = "[[textures]]\nname = \"c\"\ntype = \"checkerboard\"\ncolor0 = [0.1, 0.1, 0.1]\ncolor1 = [0.3, 0.3, 0.3]\n";
    let xml_checks = "<texture type=\"checkerboard\" name=\"alpha_v\"><rgb name=\"color0\" value=\"0.1\"/><rgb name=\"color1\" value=\"0.3\"/></texture>";
    let cases = [
        (
            "type = \"conductor\"\nroughness_u = 0.1\nroughness_v = 0.4\neta = [0.2, 0.9, 1.1]\nk = [3.9, 2.4, 2.1]",
            "<bsdf type=\"twosided\"><bsdf type=\"roughconductor\"><string name=\"distribution\" value=\"ggx\"/><float name=\"alpha_u\" value=\"0.1\"/><float name=\"alpha_v\" value=\"0.4\"/><rgb name=\"eta\" value=\"0.2, 0.9, 1.1\"/><rgb name=\"k\" value=\"3.9, 2.4, 2.1\"/></bsdf></bsdf>".to_string(),
        ),
        (
            "type = \"conductor\"\nroughness_u = 0.2\nroughness_v_texture = \"c\"\neta = [0.2, 0.9, 1.1]\nk = [3.9, 2.4, 2.1]",
            format!("<bsdf type=\"twosided\"><bsdf type=\"roughconductor\"><string name=\"distribution\" value=\"ggx\"/><float name=\"alpha_u\" value=\"0.2\"/>{xml_checks}<rgb name=\"eta\" value=\"0.2, 0.9, 1.1\"/><rgb name=\"k\" value=\"3.9, 2.4, 2.1\"/></bsdf></bsdf>"),
        ),
        (
            "type = \"dielectric\"\nior = 1.5\nroughness_u = 0.05\nroughness_v = 0.3",
            "<bsdf type=\"roughdielectric\"><string name=\"distribution\" value=\"ggx\"/><float name=\"alpha_u\" value=\"0.05\"/><float name=\"alpha_v\" value=\"0.3\"/><float name=\"int_ior\" value=\"1.5\"/><float name=\"ext_ior\" value=\"1\"/></bsdf>".to_string(),
        ),
        // Equal values are the isotropic surface, as in the XML.
        (
            "type = \"dielectric\"\nior = 1.5\nroughness_u = 0.2\nroughness_v = 0.2",
            "<bsdf type=\"roughdielectric\"><string name=\"distribution\" value=\"ggx\"/><float name=\"alpha\" value=\"0.2\"/><float name=\"int_ior\" value=\"1.5\"/><float name=\"ext_ior\" value=\"1\"/></bsdf>".to_string(),
        ),
    ];
    for (t, x) in cases {
        let a = toml(&dir, checks, t, "").unwrap_or_else(|e| panic!("{t}: {e}"));
        let b = xml(&dir, &format!("<shape type=\"rectangle\">{x}</shape>"));
        assert_eq!(
            canon(&a, &a.materials[0].bsdf),
            canon(&b, xml_bsdf(&b)),
            "{t}"
        );
    }
    let s = toml(
        &dir,
        "",
        "type = \"conductor\"\nroughness_u = 0.1\nroughness_v = 0.4",
        "",
    )
    .unwrap();
    assert!(matches!(
        s.materials[0].bsdf,
        Bsdf::Conductor {
            alpha: Param::Const(0.1),
            alpha_v: Some(Param::Const(0.4)),
            ..
        }
    ));
}

#[test]
fn normal_map_bump_map_and_mask_match_the_xml_wrappers() {
    let dir = folder("wrap");
    let textures = "[[textures]]\nname = \"n\"\ntype = \"bitmap\"\nfile = \"n.png\"\nraw = true\n\n\
                    [[textures]]\nname = \"h\"\ntype = \"checkerboard\"\nuv_scale = [4.0, 4.0]\n\n\
                    [[textures]]\nname = \"o\"\ntype = \"checkerboard\"\ncolor0 = [1.0, 1.0, 1.0]\ncolor1 = [0.0, 0.0, 0.0]\n";
    let t = "type = \"diffuse\"\nreflectance = [0.6, 0.5, 0.4]\nnormal_map = \"n\"\nbump_map = \"h\"\nbump_scale = 0.5\nopacity_texture = \"o\"";
    let x = "<bsdf type=\"twosided\"><bsdf type=\"mask\">\
             <texture type=\"checkerboard\" name=\"opacity\"><rgb name=\"color0\" value=\"1\"/><rgb name=\"color1\" value=\"0\"/></texture>\
             <bsdf type=\"normalmap\"><texture type=\"bitmap\" name=\"normalmap\"><string name=\"filename\" value=\"n.png\"/><boolean name=\"raw\" value=\"true\"/></texture>\
             <bsdf type=\"bumpmap\"><texture type=\"checkerboard\" name=\"height\"><transform name=\"to_uv\"><scale value=\"4\"/></transform></texture><float name=\"scale\" value=\"0.5\"/>\
             <bsdf type=\"diffuse\"><rgb name=\"reflectance\" value=\"0.6, 0.5, 0.4\"/></bsdf></bsdf></bsdf></bsdf></bsdf>";
    let a = toml(&dir, textures, t, "").unwrap();
    let b = xml(&dir, &format!("<shape type=\"rectangle\">{x}</shape>"));
    assert!(
        matches!(&a.materials[0].bsdf, Bsdf::Mask { bsdf, .. } if matches!(**bsdf, Bsdf::NormalMap { .. }))
    );
    assert_eq!(canon(&a, &a.materials[0].bsdf), canon(&b, xml_bsdf(&b)));
    // A constant opacity on a conductor.
    let a = toml(&dir, "", "type = \"conductor\"\nroughness = 0.0\nopacity = 0.3\neta = [0.0, 0.0, 0.0]\nk = [1.0, 1.0, 1.0]", "").unwrap();
    let b = xml(
        &dir,
        "<shape type=\"rectangle\"><bsdf type=\"mask\"><float name=\"opacity\" value=\"0.3\"/><bsdf type=\"twosided\"><bsdf type=\"conductor\"/></bsdf></bsdf></shape>",
    );
    assert_eq!(canon(&a, &a.materials[0].bsdf), canon(&b, xml_bsdf(&b)));
}

#[test]
fn a_textured_spot_and_a_textured_emission_match_the_xml_emitters() {
    let dir = folder("lights");
    let textures = "[[textures]]\nname = \"slide\"\ntype = \"bitmap\"\nfile = \"n.png\"\n";
    let spot = "[[lights]]\ntype = \"spot\"\nposition = [0.5, 2.0, 0.0]\nlook_at = [0.0, 0.0, 0.25]\nup = [0.0, 0.0, 1.0]\n\
                intensity = [4.0, 3.0, 2.0]\ncone_deg = 30.0\nfalloff_deg = 20.0\ntexture = \"slide\"\n";
    let a = toml(
        &dir,
        textures,
        "type = \"diffuse\"\nemission_texture = \"slide\"",
        spot,
    )
    .unwrap();
    let b = xml(
        &dir,
        "<shape type=\"rectangle\"><emitter type=\"area\"><texture type=\"bitmap\" name=\"radiance\"><string name=\"filename\" value=\"n.png\"/></texture></emitter></shape>\
         <emitter type=\"spot\"><transform name=\"to_world\"><lookat origin=\"0.5, 2, 0\" target=\"0, 0, 0.25\" up=\"0, 0, 1\"/></transform>\
         <rgb name=\"intensity\" value=\"4, 3, 2\"/><float name=\"cutoff_angle\" value=\"30\"/><float name=\"beam_width\" value=\"20\"/>\
         <texture type=\"bitmap\" name=\"texture\"><string name=\"filename\" value=\"n.png\"/></texture></emitter>",
    );
    assert_eq!(canon(&a, &a.lights), canon(&b, &b.lights));
    assert!(matches!(a.lights[0], Light::TexturedSpot { .. }));
    // The emitting material: radiance 1 times the texture.
    let emission = |s: &Scene| {
        let m = s.instances[0].material.unwrap();
        let t = s.emission_texture(m).expect("an emission texture");
        (s.materials[m.0 as usize].emission, canon(s, &t))
    };
    assert_eq!(emission(&a), emission(&b));
    assert_eq!(emission(&a).0, Rgb::ONE);
}

#[test]
fn bad_surface_and_light_keys_are_errors_at_the_key() {
    let dir = folder("errors");
    let textures = "[[textures]]\nname = \"c\"\ntype = \"checkerboard\"\n\n\
                    [[textures]]\nname = \"vc\"\ntype = \"vertex_color\"\n";
    // (material, more, the text on the line of the error, message)
    for (material, rest, marker, msg) in [
        (
            "type = \"conductor\"\nroughness = 0.1\nroughness_u = 0.1\nroughness_v = 0.2",
            "",
            "roughness = 0.1",
            "give either `roughness` or `roughness_u` and `roughness_v`, not both",
        ),
        (
            "type = \"conductor\"\nroughness_v = 0.2",
            "",
            "roughness_v = 0.2",
            "`roughness_v` needs `roughness_u` too",
        ),
        (
            "type = \"dielectric\"\nroughness_u = 1.5\nroughness_v = 0.2",
            "",
            "roughness_u = 1.5",
            "roughness_u 1.5 must be in [0, 1]",
        ),
        (
            "type = \"plastic\"\nroughness_u = 0.1",
            "",
            "roughness_u = 0.1",
            "key `roughness_u` does not apply to type \"plastic\"",
        ),
        (
            "type = \"conductor\"\nroughness_u = 0.1\nroughness_v_texture = \"nope\"",
            "",
            "roughness_v_texture",
            "`roughness_v_texture` names an unknown texture \"nope\"",
        ),
        (
            "type = \"diffuse\"\nnormal_map = \"nope\"",
            "",
            "normal_map",
            "`normal_map` names an unknown texture \"nope\"",
        ),
        (
            "type = \"diffuse\"\nbump_scale = 2.0",
            "",
            "bump_scale",
            "`bump_scale` needs a `bump_map`",
        ),
        (
            "type = \"diffuse\"\nbump_map = \"c\"\nbump_scale = nan",
            "",
            "bump_scale",
            "bump_scale NaN must be finite",
        ),
        (
            "type = \"diffuse\"\nopacity = 1.5",
            "",
            "opacity = 1.5",
            "opacity 1.5 must be in [0, 1]",
        ),
        (
            "type = \"diffuse\"\nopacity = 0.5\nopacity_texture = \"c\"",
            "",
            "opacity_texture",
            "give `opacity` or `opacity_texture`, not both",
        ),
        (
            "type = \"diffuse\"\nemission = [1.0, 1.0, 1.0]\nemission_texture = \"c\"",
            "",
            "emission_texture",
            "give `emission` or `emission_texture`, not both",
        ),
        (
            "type = \"diffuse\"\nemission_texture = \"vc\"",
            "",
            "emission_texture",
            "`emission_texture` \"vc\" is a vertex_color texture",
        ),
        (
            "type = \"diffuse\"",
            "[[lights]]\ntype = \"spot\"\nposition = [0.0, 2.0, 0.0]\nlook_at = [0.0, 0.0, 0.0]\nintensity = [1.0, 1.0, 1.0]\ntexture = \"c\"",
            "[[lights]]",
            "`up` is parallel to the beam",
        ),
        (
            "type = \"diffuse\"",
            "[[lights]]\ntype = \"spot\"\nposition = [0.0, 2.0, 0.0]\nlook_at = [0.0, 0.0, 0.0]\nintensity = [1.0, 1.0, 1.0]\nup = [0.0, 0.0, 1.0]",
            "up = ",
            "key `up` orients a `texture`",
        ),
        (
            "type = \"diffuse\"",
            "[[lights]]\ntype = \"spot\"\nposition = [0.0, 2.0, 0.0]\nlook_at = [0.0, 0.0, 0.0]\nintensity = [1.0, 1.0, 1.0]\ntexture = \"vc\"\nup = [1.0, 0.0, 0.0]",
            "texture = \"vc\"",
            "`texture` \"vc\" is a vertex_color texture",
        ),
        (
            "type = \"diffuse\"",
            "[[lights]]\ntype = \"point\"\nposition = [0.0, 2.0, 0.0]\nintensity = [1.0, 1.0, 1.0]\ntexture = \"c\"",
            "texture = ",
            "point light: key `texture` applies to a spot only",
        ),
    ] {
        let all = text(textures, material, rest);
        let line = 1 + all[..all.find(marker).unwrap()].matches('\n').count();
        let e = toml(&dir, textures, material, rest).unwrap_err();
        assert!(
            e.contains(&format!("test.toml:{line}:")),
            "{material} {rest}: {e}"
        );
        assert!(e.contains(msg), "{material} {rest}: {e}");
    }
}

#[test]
fn portals_warn_only_without_an_environment_or_a_sun() {
    let dir = folder("portal-warning");
    let portal =
        "[[portals]]\ncorner = [0.0, 0.0, 1.0]\nu = [1.0, 0.0, 0.0]\nv = [0.0, 1.0, 0.0]\n";
    let sun =
        "[[lights]]\ntype = \"sun\"\ndirection = [0.0, -1.0, 0.0]\nirradiance = [1.0, 1.0, 1.0]\n";
    let sky = "[environment]\nradiance = [0.5, 0.5, 0.5]\n";
    let m = "type = \"diffuse\"\nreflectance = [0.5, 0.5, 0.5]";
    let warned = |rest: &str| {
        let s = toml(&dir, "", m, rest).unwrap();
        s.warnings
            .iter()
            .filter(|w| w.message.contains("portals without"))
            .count()
    };
    assert_eq!(warned(portal), 1);
    assert_eq!(warned(&format!("{sun}{portal}")), 0);
    assert_eq!(warned(&format!("{sky}{portal}")), 0);
}
