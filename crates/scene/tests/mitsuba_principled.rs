//! Mitsuba 3 XML `principled` and `principledthin` (defaults, textures for weights, the
//! `specular`→IOR mapping, which side is black, located errors for bad values), and the OBJ
//! texture coordinates their textured test scenes need.
use eyeadapt_scene::{Bsdf, Param, Principled, PrincipledThin, Rgb, Scene, load_mitsuba_str};
use std::path::Path;

fn load(bsdf: &str) -> Result<Scene, String> {
    let text = format!(
        "<scene version=\"3.0.0\">\n{bsdf}\n<shape type=\"sphere\"><ref id=\"m\"/></shape>\n</scene>\n"
    );
    load_mitsuba_str(&text, Path::new("test.xml"), &[]).map_err(|e| e.to_string())
}

fn bsdf(s: &Scene) -> &Bsdf {
    &s.materials[0].bsdf
}

#[test]
fn principled_defaults_are_mitsubas_and_it_is_one_sided() {
    let s = load(r#"<bsdf type="principled" id="m"/>"#).unwrap();
    let Bsdf::OneSided(inner) = bsdf(&s) else {
        panic!(
            "a principled that cannot transmit is one-sided: {:?}",
            bsdf(&s)
        )
    };
    let Bsdf::Principled(p) = &**inner else {
        panic!("{inner:?}")
    };
    assert_eq!(**p, Principled::new(Param::Const(Rgb::splat(0.5))));
    assert!((p.eta - 1.5).abs() < 1e-6);
    // In a twosided both sides are the front.
    let s = load(r#"<bsdf type="twosided" id="m"><bsdf type="principled"/></bsdf>"#).unwrap();
    assert!(matches!(bsdf(&s), Bsdf::Principled(_)));
}

#[test]
fn principled_reads_every_weight_textures_included() {
    let s = load(
        r#"<bsdf type="principled" id="m">
            <rgb name="base_color" value="0.2, 0.8, 0.1"/>
            <float name="roughness" value="0.15"/>
            <texture name="metallic" type="checkerboard">
                <float name="color0" value="0.7"/><float name="color1" value="0.1"/>
            </texture>
            <float name="spec_tint" value="0.1"/>
            <float name="anisotropic" value="0.2"/>
            <float name="sheen" value="0.3"/>
            <float name="sheen_tint" value="0.4"/>
            <float name="clearcoat" value="0.5"/>
            <float name="clearcoat_gloss" value="0.6"/>
            <float name="spec_trans" value="0.7"/>
            <float name="flatness" value="0.8"/>
            <float name="specular" value="0.7"/>
        </bsdf>"#,
    )
    .unwrap();
    // It transmits: it has a back side of its own.
    let Bsdf::Principled(p) = bsdf(&s) else {
        panic!("{:?}", bsdf(&s))
    };
    assert_eq!(p.base_color, Param::Const(Rgb::new(0.2, 0.8, 0.1)));
    assert!(matches!(p.metallic, Param::Texture(_)));
    let weights = [
        p.roughness,
        p.spec_tint,
        p.anisotropic,
        p.sheen,
        p.sheen_tint,
        p.clearcoat,
        p.clearcoat_gloss,
        p.spec_trans,
        p.flatness,
    ];
    let expect = [0.15, 0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8];
    for (w, e) in weights.iter().zip(expect) {
        assert_eq!(*w, Param::Const(e));
    }
    let eta = 2.0 / (1.0 - (0.08f64 * 0.7).sqrt()) - 1.0;
    assert!((p.eta as f64 - eta).abs() < 1e-6, "{}", p.eta);
}

#[test]
fn principled_thin_reads_eta_and_diff_trans() {
    let s = load(
        r#"<bsdf type="principledthin" id="m">
            <rgb name="base_color" value="0.7, 0.1, 0.1"/>
            <texture name="diff_trans" type="checkerboard">
                <float name="color0" value="0.4"/><float name="color1" value="1.4"/>
            </texture>
            <float name="spec_trans" value="0.3"/>
            <float name="eta" value="1.33"/>
        </bsdf>"#,
    )
    .unwrap();
    let Bsdf::PrincipledThin(p) = bsdf(&s) else {
        panic!("thin sheets look the same from both sides: {:?}", bsdf(&s))
    };
    assert!(matches!(p.diff_trans, Param::Texture(_)));
    assert_eq!(p.eta, Param::Const(1.33));
    assert_eq!(p.spec_trans, Param::Const(0.3));
    let d = PrincipledThin::new(Param::Const(Rgb::splat(0.5)));
    assert_eq!(d.eta, Param::Const(1.5));
}

#[test]
fn bad_values_are_errors_at_their_line_naming_the_field() {
    for (bsdf, line, msg) in [
        (
            "<float name=\"roughness\" value=\"-0.1\"/>",
            2,
            "`roughness` of <bsdf type=\"principled\" id=\"m\"> is -0.1, outside [0, 1]",
        ),
        ("<float name=\"eta\" value=\"-1\"/>", 2, "`eta`"),
        ("<float name=\"metallic\" value=\"1.5\"/>", 2, "`metallic`"),
        (
            "<rgb name=\"base_color\" value=\"2, 0, 0\"/>",
            2,
            "`base_color`",
        ),
        ("<float name=\"specular\" value=\"2\"/>", 2, "`specular`"),
        (
            "<float name=\"eta\" value=\"1.4\"/><float name=\"specular\" value=\"0.5\"/>",
            2,
            "either `eta` or `specular`",
        ),
    ] {
        let e = load(&format!(
            "<bsdf type=\"principled\" id=\"m\">\n{bsdf}\n</bsdf>"
        ))
        .unwrap_err();
        assert!(e.contains(&format!("test.xml:{}:", line + 1)), "{e}");
        assert!(e.contains(msg), "{e}");
    }
    let e =
        load("<bsdf type=\"principledthin\" id=\"m\">\n<float name=\"eta\" value=\"0\"/>\n</bsdf>")
            .unwrap_err();
    assert!(e.contains("test.xml:3:") && e.contains("`eta`"), "{e}");
}

/// An OBJ's texture coordinates are flipped once by default (v → 1 − v, Mitsuba's
/// `flip_tex_coords`), not twice; with the flag off they are the file's.
#[test]
fn obj_texture_coordinates_are_flipped_once() {
    let dir = std::env::temp_dir().join(format!("eyeadapt-obj-uv-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let obj = dir.join("tri.obj");
    std::fs::write(
        &obj,
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0.25\nvt 1 0.25\nvt 0 1\nf 1/1 2/2 3/3\n",
    )
    .unwrap();
    for (flag, v) in [
        ("", 0.75),
        ("<boolean name=\"flip_tex_coords\" value=\"false\"/>", 0.25),
    ] {
        let text = format!(
            "<scene version=\"3.0.0\"><shape type=\"obj\"><string name=\"filename\" value=\"{}\"/>{flag}</shape></scene>",
            obj.display()
        );
        let s = load_mitsuba_str(&text, &dir.join("s.xml"), &[]).unwrap();
        assert!(
            (s.meshes[0].uvs[0].y - v).abs() < 1e-6,
            "{flag}: {:?}",
            s.meshes[0].uvs
        );
    }
    std::fs::remove_dir_all(&dir).ok();
}
