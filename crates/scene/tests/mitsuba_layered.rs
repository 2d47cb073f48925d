//! Mitsuba 3 XML: the BSDFs built around or beside others (`blendbsdf`, `bumpmap`, `null`),
//! what shadow rays make of masks and null surfaces, `pplastic`, and anisotropic roughness.
use eyeadapt_scene::{
    Bsdf, CutoutShadows, Distribution, Param, Rgb, Scene, SceneError, load_mitsuba_str,
};
use std::path::Path;

fn load(bsdf: &str) -> Result<Scene, SceneError> {
    let body = format!(
        "<scene version=\"3.0.0\">\n{bsdf}\n<shape type=\"cube\"><ref id=\"b\"/></shape>\
         <emitter type=\"constant\"/><sensor type=\"perspective\"><film type=\"hdrfilm\"/></sensor>\n</scene>\n"
    );
    load_mitsuba_str(&body, Path::new("test.xml"), &[])
}

fn bsdf(s: &Scene) -> Bsdf {
    s.materials[0].bsdf.clone()
}

fn error(bsdf: &str) -> String {
    load(bsdf).unwrap_err().to_string()
}

#[test]
fn blendbsdf_mixes_two_nested_bsdfs_by_weight() {
    let s = load(
        r#"<bsdf type="blendbsdf" id="b"><float name="weight" value="0.25"/>
           <bsdf type="diffuse"/><bsdf type="conductor"/></bsdf>"#,
    )
    .unwrap();
    let Bsdf::Blend { weight, bsdfs } = bsdf(&s) else {
        panic!("{:?}", bsdf(&s))
    };
    assert_eq!(weight, Param::Const(0.25));
    assert!(matches!(&bsdfs[0], Bsdf::OneSided(b) if matches!(**b, Bsdf::Diffuse { .. })));
    assert!(matches!(&bsdfs[1], Bsdf::OneSided(b) if matches!(**b, Bsdf::Conductor { .. })));
    // A texture weight; `twosided` reaches into both children.
    let s = load(
        r#"<bsdf type="twosided" id="b"><bsdf type="blendbsdf">
           <texture name="weight" type="checkerboard"/>
           <bsdf type="diffuse"/><bsdf type="diffuse"/></bsdf></bsdf>"#,
    )
    .unwrap();
    let Bsdf::Blend { weight, bsdfs } = bsdf(&s) else {
        panic!()
    };
    assert!(matches!(weight, Param::Texture(_)));
    assert!(bsdfs.iter().all(|b| matches!(b, Bsdf::Diffuse { .. })));
}

#[test]
fn bad_blends_are_errors_at_their_elements() {
    let e = error(
        r#"<bsdf type="blendbsdf" id="b"><float name="weight" value="-0.5"/>
           <bsdf type="diffuse"/><bsdf type="diffuse"/></bsdf>"#,
    );
    assert!(e.contains("test.xml:2") && e.contains("`weight`"), "{e}");
    let e = error(r#"<bsdf type="blendbsdf" id="b"><bsdf type="diffuse"/></bsdf>"#);
    assert!(e.contains("exactly two nested"), "{e}");
}

#[test]
fn bumpmap_takes_its_one_texture_and_scale() {
    let s = load(
        r#"<bsdf type="bumpmap" id="b"><float name="scale" value="0.02"/>
           <texture name="anything" type="checkerboard"/><bsdf type="roughplastic"/></bsdf>"#,
    )
    .unwrap();
    let Bsdf::BumpMap {
        scale, bsdf: inner, ..
    } = bsdf(&s)
    else {
        panic!("{:?}", bsdf(&s))
    };
    assert_eq!(scale, 0.02);
    assert!(matches!(*inner, Bsdf::OneSided(_)));
    let e = error(
        r#"<bsdf type="bumpmap" id="b"><texture name="h" type="checkerboard"/>
           <boolean name="use_shadowing_function" value="false"/><bsdf type="diffuse"/></bsdf>"#,
    );
    assert!(e.contains("use_shadowing_function"), "{e}");
}

#[test]
fn null_is_no_surface() {
    let s = load(r#"<bsdf type="null" id="b"/>"#).unwrap();
    assert_eq!(bsdf(&s), Bsdf::Null);
}

#[test]
fn pplastic_reads_its_rgb_parameters() {
    let s = load(
        r#"<bsdf type="pplastic" id="b"><rgb name="diffuse_reflectance" value="0.05, 0.03, 0.1"/>
           <float name="alpha" value="0.06"/><rgb name="specular_reflectance" value="0"/></bsdf>"#,
    )
    .unwrap();
    let Bsdf::OneSided(inner) = bsdf(&s) else {
        panic!()
    };
    let Bsdf::PPlastic {
        diffuse_reflectance,
        specular_reflectance,
        alpha,
        alpha_v,
        distribution,
        eta,
    } = *inner
    else {
        panic!()
    };
    assert_eq!(diffuse_reflectance, Param::Const(Rgb::new(0.05, 0.03, 0.1)));
    assert_eq!(specular_reflectance, Param::Const(Rgb::ZERO));
    assert_eq!((alpha, alpha_v), (Param::Const(0.06), None));
    assert_eq!(distribution, Distribution::Beckmann);
    assert!(
        (eta - 1.49 / 1.000277).abs() < 1e-6,
        "polypropylene over air: {eta}"
    );
    let e = error(
        r#"<bsdf type="pplastic" id="b"><float name="eta" value="1.5"/><float name="int_ior" value="1.4"/></bsdf>"#,
    );
    assert!(e.contains("either `eta`"), "{e}");
}

#[test]
fn anisotropic_roughness_takes_textures_and_needs_both_halves() {
    let s = load(
        r#"<bsdf type="roughdielectric" id="b"><string name="distribution" value="ggx"/>
           <texture name="alpha_u" type="checkerboard"/><float name="alpha_v" value="0.3"/></bsdf>"#,
    )
    .unwrap();
    let Bsdf::RoughDielectric {
        alpha,
        alpha_v,
        distribution,
        ..
    } = bsdf(&s)
    else {
        panic!("{:?}", bsdf(&s))
    };
    assert!(matches!(alpha, Param::Texture(_)));
    assert_eq!(alpha_v, Some(Param::Const(0.3)));
    assert_eq!(distribution, Distribution::Ggx);
    // Equal halves are isotropic.
    let s = load(
        r#"<bsdf type="roughconductor" id="b"><float name="alpha_u" value="0.2"/><float name="alpha_v" value="0.2"/></bsdf>"#,
    )
    .unwrap();
    let Bsdf::OneSided(inner) = bsdf(&s) else {
        panic!()
    };
    assert!(matches!(*inner, Bsdf::Conductor { alpha_v: None, .. }));
    let e =
        error(r#"<bsdf type="roughconductor" id="b"><float name="alpha_u" value="0.2"/></bsdf>"#);
    assert!(e.contains("together"), "{e}");
    let e = error(
        r#"<bsdf type="roughconductor" id="b"><float name="alpha" value="0.2"/><float name="alpha_u" value="0.2"/><float name="alpha_v" value="0.1"/></bsdf>"#,
    );
    assert!(e.contains("either `alpha`"), "{e}");
}

#[test]
fn shadow_rays_stop_at_masks_as_the_integrator_does() {
    // Mitsuba's `path` and `direct` test shadow rays against every surface (`ray_test`), and
    // a file without an integrator gets eyeadapt's path tracer with the same rule; `volpath`
    // passes them through masks' holes and null surfaces (`eval_null_transmission`).
    let mask = r#"<bsdf type="mask" id="b"><float name="opacity" value="0.3"/><bsdf type="diffuse"/></bsdf>"#;
    for (integrator, expect) in [
        ("", CutoutShadows::Block),
        (r#"<integrator type="path"/>"#, CutoutShadows::Block),
        (r#"<integrator type="direct"/>"#, CutoutShadows::Block),
        (r#"<integrator type="volpath"/>"#, CutoutShadows::Transmit),
        (
            r#"<integrator type="moment"><integrator type="volpath"/></integrator>"#,
            CutoutShadows::Transmit,
        ),
    ] {
        let s = load(&format!("{mask}{integrator}")).unwrap();
        assert_eq!(s.cutout_shadows, expect, "{integrator:?}");
    }
    // TOML and glTF scenes (and scenes built in code) pass them.
    assert_eq!(Scene::default().cutout_shadows, CutoutShadows::Transmit);
}
