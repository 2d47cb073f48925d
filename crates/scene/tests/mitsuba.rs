//! Mitsuba 3 XML loading: the Cornell box against its TOML twin, parameters, transforms,
//! field-of-view axes, the supported plugins, and located errors for unsupported scenes.
use eyeadapt_scene::{
    Bsdf, Distribution, FilterType, Light, Param, PixelFilter, Projection, RenderDefaults, Scene,
    SceneError, Texture, TextureId, WrapMode, load_mitsuba, load_mitsuba_str, load_scene,
    load_scene_file, mitsuba_vertical_fov,
};
use glam::Vec3;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

fn repo() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

fn xml(body: &str) -> String {
    format!("<scene version=\"3.0.0\">\n{body}\n</scene>\n")
}

/// The BSDF inside a one-sided wrapper (Mitsuba's BSDFs outside `twosided` are one-sided).
fn one_sided(b: &Bsdf) -> Bsdf {
    match b {
        Bsdf::OneSided(inner) => (**inner).clone(),
        other => panic!("not one-sided: {other:?}"),
    }
}

fn load(body: &str) -> Result<Scene, SceneError> {
    load_mitsuba_str(&xml(body), Path::new("test.xml"), &[])
}

/// 1-based line of the first occurrence of `needle` in `text`.
fn line_of(text: &str, needle: &str) -> usize {
    let i = text
        .find(needle)
        .unwrap_or_else(|| panic!("{needle} not in text"));
    text[..i].matches('\n').count() + 1
}

/// Total area per material, keyed by what the material is (not its name).
fn area_by_material(s: &Scene) -> BTreeMap<String, f64> {
    let mut out = BTreeMap::new();
    for inst in &s.instances {
        let (m, mat) = (s.mesh(inst.mesh), s.material(inst.material));
        let key = format!("{:?} emits {:?}", mat.bsdf, mat.emission);
        *out.entry(key).or_insert(0.0) += m.area();
    }
    out
}

fn triangles(s: &Scene) -> Vec<[f32; 9]> {
    let mut out: Vec<[f32; 9]> = s
        .meshes
        .iter()
        .flat_map(|m| {
            m.indices.iter().map(move |t| {
                let mut v = t.map(|i| m.positions[i as usize].to_array());
                v.sort_by(|a, b| a.partial_cmp(b).unwrap());
                let mut flat = [0.0; 9];
                for (k, p) in v.iter().flatten().enumerate() {
                    flat[k] = *p;
                }
                flat
            })
        })
        .collect();
    out.sort_by(|a, b| a.partial_cmp(b).unwrap());
    out
}

fn emissive_area(s: &Scene) -> f64 {
    s.instances
        .iter()
        .filter(|i| s.material(i.material).is_emissive())
        .map(|i| s.mesh(i.mesh).area())
        .sum()
}

#[test]
fn cornell_xml_matches_the_toml_camera_render_settings_and_light() {
    let x = load_scene_file(&repo().join("scenes/cornell-box/cornell.xml")).unwrap();
    let t = load_scene(&repo().join("scenes/cornell-box/scene.toml")).unwrap();
    assert!(x.warnings.is_empty(), "{:?}", x.warnings);
    let (xc, tc) = (x.camera.clone().unwrap(), t.camera.clone().unwrap());
    assert!(xc.position.distance(tc.position) < 1e-6);
    assert!(xc.forward().distance(tc.forward()) < 1e-6);
    assert!(
        xc.basis().0.distance(tc.basis().0) < 1e-6,
        "same image right vector"
    );
    assert!((xc.fov_deg - tc.fov_deg).abs() < 1e-4);
    assert_eq!((xc.width, xc.height), (tc.width, tc.height));
    // The XML names the box filter the TOML scene gets by default.
    assert_eq!(x.render.filter, Some(PixelFilter::Box));
    assert_eq!(
        RenderDefaults {
            filter: None,
            ..x.render.clone()
        },
        t.render,
        "spp 64, max_depth 8, rr_depth 5"
    );
    let (xa, ta) = (emissive_area(&x), emissive_area(&t));
    assert!(
        (xa - 0.105 * 0.130).abs() < 1e-7 && (xa - ta).abs() < 1e-7,
        "{xa} vs {ta}"
    );
    let light = |s: &Scene| {
        s.instances
            .iter()
            .map(|i| s.material(i.material))
            .find(|m| m.is_emissive())
            .unwrap()
            .clone()
    };
    assert_eq!(light(&x).emission, light(&t).emission);
    assert_eq!(light(&x).bsdf, light(&t).bsdf);
}

#[test]
fn cornell_xml_and_toml_have_the_same_triangles_per_material() {
    let x = load_mitsuba(&repo().join("scenes/cornell-box/cornell.xml"), &[]).unwrap();
    let t = load_scene(&repo().join("scenes/cornell-box/scene.toml")).unwrap();
    let (xa, ta) = (area_by_material(&x), area_by_material(&t));
    assert_eq!(xa.keys().collect::<Vec<_>>(), ta.keys().collect::<Vec<_>>());
    for (k, a) in &xa {
        assert!(
            (a - ta[k]).abs() < 1e-6 * a.max(1.0),
            "{k}: {a} vs {}",
            ta[k]
        );
    }
    let (xt, tt) = (triangles(&x), triangles(&t));
    assert_eq!(xt.len(), tt.len());
    for (a, b) in xt.iter().zip(&tt) {
        let d = a
            .iter()
            .zip(b)
            .map(|(p, q)| (p - q).abs())
            .fold(0.0, f32::max);
        assert!(d < 1e-5, "{a:?} vs {b:?}");
    }
    // The XML shares one material per BSDF id; the light got its own emissive one.
    assert_eq!(x.materials.len(), 4);
    // Same front sides: the light faces down in both.
    for s in [&x, &t] {
        let lamp = s
            .instances
            .iter()
            .find(|i| s.material(i.material).is_emissive())
            .unwrap();
        let m = s.mesh(lamp.mesh);
        let [a, b, c] = m.indices[0].map(|i| m.positions[i as usize]);
        assert!((b - a).cross(c - a).y < 0.0);
    }
}

#[test]
fn parameters_come_from_defaults_and_caller_overrides() {
    let path = repo().join("scenes/cornell-box/cornell.xml");
    let s = load_mitsuba(
        &path,
        &[("spp", "256"), ("res", "128"), ("sampler", "ldsampler")],
    )
    .unwrap();
    assert_eq!(s.render.spp, Some(256));
    assert_eq!(s.camera.unwrap().width, 128);
    assert_eq!(s.render.max_depth, Some(8), "the file's default stays");

    let text = xml(
        "<default name=\"r\" value=\"0.25\"/>\n<bsdf type=\"diffuse\" id=\"a\"><rgb name=\"reflectance\" value=\"$r, $r, 0.5\"/></bsdf>\n<shape type=\"cube\"><ref id=\"a\"/></shape>\n<emitter type=\"point\"><rgb name=\"intensity\" value=\"$missing\"/></emitter>",
    );
    let e = load_mitsuba_str(&text, Path::new("p.xml"), &[]).unwrap_err();
    assert_eq!(e.diagnostics.len(), 1, "{e}");
    let d = &e.diagnostics[0];
    assert_eq!(d.line, line_of(&text, "$missing"));
    assert!(d.message.contains("`$missing`"), "{e}");
    let s = load_mitsuba_str(&text, Path::new("p.xml"), &[("missing", "3")]).unwrap();
    assert_eq!(
        one_sided(&s.materials[0].bsdf),
        Bsdf::Diffuse {
            reflectance: Vec3::new(0.25, 0.25, 0.5).into()
        }
    );
    assert!(matches!(s.lights[0], Light::Point { intensity, .. } if intensity == Vec3::splat(3.0)));
}

fn point_light_at(transform: &str) -> Vec3 {
    let s = load(&format!(
        "<emitter type=\"point\"><transform name=\"to_world\">{transform}</transform></emitter>"
    ))
    .unwrap();
    match s.lights[0] {
        Light::Point { position, .. } => position,
        _ => unreachable!(),
    }
}

#[test]
fn transform_operations_apply_in_document_order() {
    // Translate first, then rotate about +y by 90°: (1, 0, 0) → (0, 0, -1).
    let p = point_light_at("<translate x=\"1\"/><rotate y=\"1\" angle=\"90\"/>");
    assert!(p.distance(Vec3::new(0.0, 0.0, -1.0)) < 1e-6, "{p}");
    // The other order leaves the translation alone.
    let p = point_light_at("<rotate value=\"0, 1, 0\" angle=\"90\"/><translate value=\"1 0 0\"/>");
    assert!(p.distance(Vec3::X) < 1e-6, "{p}");
    // Scale after translate scales the offset; before it does not.
    let p = point_light_at("<translate x=\"1\" y=\"2\"/><scale value=\"3\"/>");
    assert!(p.distance(Vec3::new(3.0, 6.0, 0.0)) < 1e-6, "{p}");
    let p = point_light_at("<scale x=\"3\"/><translate x=\"1\" y=\"2\"/>");
    assert!(p.distance(Vec3::new(1.0, 2.0, 0.0)) < 1e-6, "{p}");
    // A row-major matrix, then a translation.
    let p = point_light_at(
        "<matrix value=\"1 0 0 5  0 1 0 6  0 0 1 7  0 0 0 1\"/><translate z=\"1\"/>",
    );
    assert!(p.distance(Vec3::new(5.0, 6.0, 8.0)) < 1e-6, "{p}");
    // Shapes too: a rectangle scaled, rotated to face +y, then lifted.
    let s = load(
        "<shape type=\"rectangle\"><transform name=\"to_world\"><scale x=\"2\"/><rotate x=\"1\" angle=\"-90\"/><translate y=\"1\"/></transform><emitter type=\"area\"/></shape>",
    )
    .unwrap();
    let m = &s.meshes[0];
    assert!((m.area() - 8.0).abs() < 1e-5);
    assert!(m.positions.iter().all(|p| (p.y - 1.0).abs() < 1e-6));
    let [a, b, c] = m.indices[0].map(|i| m.positions[i as usize]);
    assert!(
        (b - a).cross(c - a).normalize().distance(Vec3::Y) < 1e-6,
        "+z turned to +y"
    );
    // A mirroring transform keeps the winding, so the front side turns round (as in Mitsuba).
    let s = load(
        "<shape type=\"rectangle\"><transform name=\"to_world\"><scale x=\"-1\"/></transform><emitter type=\"area\"/></shape>",
    )
    .unwrap();
    let m = &s.meshes[0];
    let [a, b, c] = m.indices[0].map(|i| m.positions[i as usize]);
    assert!((b - a).cross(c - a).normalize().distance(-Vec3::Z) < 1e-6);
}

#[test]
fn fov_axis_converts_to_vertical_fov_like_mitsuba() {
    // (axis, width, height, Mitsuba 3.9's x_fov for fov = 40), from mi.traverse(sensor).
    let cases = [
        ("x", 400, 200, 40.0),
        ("y", 400, 200, 72.10477),
        ("y", 200, 400, 20.62821),
        ("diagonal", 400, 200, 36.06479),
        ("diagonal", 200, 400, 18.49019),
        ("smaller", 400, 200, 72.10477),
        ("smaller", 200, 400, 40.0),
        ("larger", 400, 200, 40.0),
        ("larger", 200, 400, 20.62821),
    ];
    for (axis, w, h, x_fov) in cases {
        let s = load(&format!(
            "<sensor type=\"perspective\"><float name=\"fov\" value=\"40\"/><string name=\"fov_axis\" value=\"{axis}\"/><film type=\"hdrfilm\"><integer name=\"width\" value=\"{w}\"/><integer name=\"height\" value=\"{h}\"/><rfilter type=\"box\"/></film></sensor><emitter type=\"constant\"/>"
        ))
        .unwrap();
        let v = s.camera.unwrap().fov_deg as f64;
        let x =
            2.0 * libm::atan(libm::tan((v / 2.0).to_radians()) * w as f64 / h as f64).to_degrees();
        assert!((x - x_fov).abs() < 1e-3, "{axis} {w}x{h}: {x} vs {x_fov}");
    }
    assert!((mitsuba_vertical_fov(40.0, "y", 2.0).unwrap() - 40.0).abs() < 1e-9);
    assert!(mitsuba_vertical_fov(40.0, "z", 2.0).is_none());
    // No fov: Mitsuba's 50 mm lens on 35 mm film, along the 43.27 mm diagonal; 768×576 film
    // by default. The x angles are Mitsuba 3.9.1's own `x_fov` for these films.
    let s = load("<sensor type=\"perspective\"/><emitter type=\"constant\"/>").unwrap();
    let c = s.camera.unwrap();
    assert_eq!((c.width, c.height), (768, 576));
    let x = 2.0 * libm::atan(libm::tan((c.fov_deg as f64 / 2.0).to_radians()) * 768.0 / 576.0);
    assert!(
        (x.to_degrees() - 38.184_84).abs() < 1e-3,
        "{}",
        x.to_degrees()
    );
    for (w, h, lens, x_fov) in [
        (64, 64, "", 34.022_06),
        (100, 50, "", 42.311_72),
        (768, 576, "35mm", 52.622_54),
    ] {
        let lens = if lens.is_empty() {
            String::new()
        } else {
            format!("<string name=\"focal_length\" value=\"{lens}\"/>")
        };
        let s = load(&format!("<sensor type=\"perspective\">{lens}<film type=\"hdrfilm\"><integer name=\"width\" value=\"{w}\"/><integer name=\"height\" value=\"{h}\"/></film></sensor><emitter type=\"constant\"/>")).unwrap();
        let v = s.camera.unwrap().fov_deg as f64;
        let x = 2.0 * libm::atan(libm::tan((v / 2.0).to_radians()) * w as f64 / h as f64);
        assert!(
            (x.to_degrees() - x_fov).abs() < 1e-3,
            "{w}x{h} {lens}: {}",
            x.to_degrees()
        );
    }
}

#[test]
fn supported_plugins_load() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(
        dir.path().join("tri.ply"),
        "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n",
    )
    .unwrap();
    let text = xml(r#"
    <integrator type="path"><integer name="max_depth" value="-1"/></integrator>
    <sensor type="perspective">
        <float name="fov" value="50"/><float name="near_clip" value="0.1"/><float name="far_clip" value="100"/>
        <transform name="to_world"><lookat origin="0, 1, 5" target="0, 1, 0" up="0, 1, 0"/></transform>
        <sampler type="stratified"><integer name="sample_count" value="16"/><integer name="seed" value="7"/></sampler>
        <film type="hdrfilm"><integer name="width" value="64"/><integer name="height" value="32"/><string name="pixel_format" value="rgb"/><rfilter type="box"/></film>
    </sensor>
    <bsdf type="twosided" id="gold"><bsdf type="roughconductor"><string name="material" value="Au"/><float name="alpha" value="0.2"/><string name="distribution" value="ggx"/></bsdf></bsdf>
    <bsdf type="plastic" id="shiny"><rgb name="diffuse_reflectance" value="0.2, 0.4, 0.6"/><string name="int_ior" value="bk7"/></bsdf>
    <bsdf type="roughplastic" id="matte"><spectrum name="diffuse_reflectance" value="0.3"/><float name="alpha" value="0.3"/><string name="distribution" value="ggx"/><float name="int_ior" value="1.6"/></bsdf>
    <shape type="ply"><string name="filename" value="tri.ply"/><ref id="matte"/></shape>
    <shape type="sphere"><point name="center" x="1" y="2" z="3"/><float name="radius" value="0.5"/><ref id="gold"/></shape>
    <shape type="cube"><boolean name="flip_normals" value="true"/><ref id="shiny"/></shape>
    <shape type="sphere"><transform name="to_world"><scale value="0.1"/></transform><emitter type="area"><rgb name="radiance" value="1, 2, 3"/></emitter></shape>
    <emitter type="spot"><transform name="to_world"><lookat origin="0, 4, 0" target="0, 0, 0" up="1, 0, 0"/></transform><rgb name="intensity" value="10"/><float name="cutoff_angle" value="40"/></emitter>
    <emitter type="point"><point name="position" value="1, 2, 3"/></emitter>
    <emitter type="constant"><rgb name="radiance" value="0.1"/></emitter>
    "#);
    let s = load_mitsuba_str(&text, &dir.path().join("all.xml"), &[]).unwrap();
    assert_eq!(s.warnings.len(), 1, "{:?}", s.warnings);
    assert!(s.warnings[0].message.contains("smooth coating"));
    assert_eq!(s.render.spp, Some(16));
    assert_eq!(s.render.seed, Some(7));
    assert_eq!(s.render.max_depth, Some(-1));
    assert_eq!(s.render.rr_depth, Some(5), "Mitsuba's default");
    assert_eq!(s.meshes.len(), 4);
    assert_eq!(s.meshes[0].triangle_count(), 1);
    assert_eq!(
        s.meshes[0].normals.len(),
        3,
        "Mitsuba smooths meshes without normals"
    );
    assert!(
        s.meshes[0]
            .normals
            .iter()
            .all(|n| n.distance(Vec3::Z) < 1e-6)
    );
    let sphere = &s.meshes[1];
    let (lo, hi) = sphere.positions.iter().fold(
        (Vec3::splat(f32::MAX), Vec3::splat(f32::MIN)),
        |(lo, hi), p| (lo.min(*p), hi.max(*p)),
    );
    assert!(((lo + hi) / 2.0).distance(Vec3::new(1.0, 2.0, 3.0)) < 1e-4);
    // Inside a `twosided`: not wrapped.
    match s.material(s.instances[1].material).bsdf.clone() {
        Bsdf::Conductor { alpha, eta, .. } => {
            assert_eq!(alpha, 0.2.into());
            assert!((eta.x - 0.143).abs() < 1e-3, "Mitsuba's Au: {eta}");
        }
        b => panic!("{b:?}"),
    }
    match one_sided(&s.material(s.instances[2].material).bsdf) {
        Bsdf::Plastic { ior, alpha, .. } => {
            assert!((ior - 1.5046 / 1.000277).abs() < 1e-5);
            // A smooth `plastic`: alpha 0, the smooth interface's energy terms.
            assert_eq!(alpha, 0.0.into());
        }
        b => panic!("{b:?}"),
    }
    // flip_normals turns the cube's faces inwards.
    let cube = &s.meshes[2];
    let [a, b, c] = cube.indices[0].map(|i| cube.positions[i as usize]);
    assert!((b - a).cross(c - a).dot((a + b + c) / 3.0) < 0.0);
    let lamp = s.material(s.instances[3].material);
    assert_eq!(lamp.emission, Vec3::new(1.0, 2.0, 3.0));
    assert_eq!(
        one_sided(&lamp.bsdf),
        Bsdf::Diffuse {
            reflectance: Vec3::splat(0.5).into()
        },
        "Mitsuba's default BSDF"
    );
    match s.lights[0] {
        Light::Spot {
            position,
            direction,
            cone_deg,
            falloff_deg,
            ..
        } => {
            assert_eq!(position, Vec3::new(0.0, 4.0, 0.0));
            assert!(direction.distance(-Vec3::Y) < 1e-6);
            assert_eq!((cone_deg, falloff_deg), (40.0, 30.0));
        }
        _ => panic!(),
    }
    assert_eq!(s.environment, Some(Vec3::splat(0.1)));
    let cam = s.camera.unwrap();
    assert!((cam.fov_deg as f64 - mitsuba_vertical_fov(50.0, "x", 2.0).unwrap()).abs() < 1e-4);
}

#[test]
fn anisotropic_roughness_is_kept_not_approximated() {
    let s = load(
        "<shape type=\"cube\"><bsdf type=\"roughconductor\"><float name=\"alpha_u\" value=\"0.1\"/><float name=\"alpha_v\" value=\"0.4\"/></bsdf></shape><emitter type=\"constant\"/><sensor type=\"perspective\"><film type=\"hdrfilm\"/></sensor>",
    )
    .unwrap();
    let all: Vec<String> = s.warnings.iter().map(|w| w.to_string()).collect();
    assert!(all.is_empty(), "{all:#?}");
    match one_sided(&s.materials[0].bsdf) {
        Bsdf::Conductor { alpha, alpha_v, .. } => {
            assert_eq!(alpha, Param::Const(0.1));
            assert_eq!(alpha_v, Some(Param::Const(0.4)));
        }
        other => panic!("{other:?}"),
    }
    // No <rfilter>: Mitsuba's default Gaussian.
    assert_eq!(s.render.filter, Some(PixelFilter::GAUSSIAN));
}

#[test]
fn reconstruction_filters_take_mitsubas_parameters() {
    let filter = |rfilter: &str| {
        load(&format!(
            "<sensor type=\"perspective\"><film type=\"hdrfilm\">{rfilter}</film></sensor><emitter type=\"constant\"/>"
        ))
        .map(|s| s.render.filter)
    };
    assert_eq!(
        filter("<rfilter type=\"box\"/>").unwrap(),
        Some(PixelFilter::Box)
    );
    assert_eq!(
        filter("<rfilter type=\"tent\"/>").unwrap(),
        Some(PixelFilter::Tent { radius: 1.0 })
    );
    assert_eq!(
        filter("<rfilter type=\"gaussian\"><float name=\"stddev\" value=\"0.25\"/></rfilter>")
            .unwrap(),
        Some(PixelFilter::Gaussian {
            stddev: 0.25,
            radius: 1.0
        })
    );
    let e = filter("<rfilter type=\"lanczos\"/>")
        .unwrap_err()
        .to_string();
    assert!(e.contains("<rfilter type=\"lanczos\">"), "{e}");
}

/// Loads a fixture of `scenes/mitsuba-unsupported/` and checks that each `(needle, words)`
/// has an error on the needle's line that mentions every word.
fn expect_errors(file: &str, expected: &[(&str, &[&str])]) {
    let path = repo().join("scenes/mitsuba-unsupported").join(file);
    let text = std::fs::read_to_string(&path).unwrap();
    let e = load_scene_file(&path).expect_err(file);
    let errors: Vec<_> = e
        .diagnostics
        .iter()
        .filter(|d| d.severity == eyeadapt_scene::Severity::Error)
        .collect();
    for (needle, words) in expected {
        let line = line_of(&text, needle);
        let hit = errors
            .iter()
            .find(|d| d.line == line && words.iter().all(|w| d.message.contains(w)));
        assert!(
            hit.is_some(),
            "{file}: no error on line {line} mentioning {words:?}; got:\n{e}"
        );
        let d = hit.unwrap();
        assert!(d.col > 0);
        assert!(
            d.to_string()
                .starts_with(&format!("{}:{line}:", path.display()))
        );
    }
    assert_eq!(
        errors.len(),
        expected.len(),
        "{file}: unexpected extra errors:\n{e}"
    );
}

#[test]
fn a_missing_texture_file_is_reported_at_its_filename() {
    expect_errors(
        "textured-floor.xml",
        &[(
            "textures/checker.png",
            &["cannot read image", "checker.png"],
        )],
    );
}

#[test]
fn a_missing_envmap_file_is_reported_at_its_filename() {
    expect_errors(
        "sky-envmap.xml",
        &[(
            "value=\"skies/kloppenheim_06_4k.exr\"",
            &["kloppenheim_06_4k.exr", "does not exist"],
        )],
    );
}

#[test]
fn dielectrics_load_with_mitsubas_iors_and_included_files() {
    let glass = load_scene_file(&repo().join("scenes/mitsuba-glass/glass-on-table.xml")).unwrap();
    let by_name = |s: &Scene, n: &str| {
        s.materials
            .iter()
            .find(|m| m.name == n)
            .unwrap()
            .bsdf
            .clone()
    };
    match by_name(&glass, "glass") {
        Bsdf::Dielectric { eta, .. } => assert!((eta - (1.5046 / 1.000277) as f32).abs() < 1e-6),
        b => panic!("{b:?}"),
    }
    assert!(matches!(by_name(&glass, "table"), Bsdf::OneSided(_)));
    // The window's materials come from an included file.
    let window = load_scene_file(&repo().join("scenes/mitsuba-glass/window-include.xml")).unwrap();
    match by_name(&window, "window-glass") {
        Bsdf::ThinDielectric { eta, .. } => assert!((eta - 1.5 / 1.000277) < 1e-6),
        b => panic!("{b:?}"),
    }
    let rough = load(
        "<shape type=\"cube\"><bsdf type=\"roughdielectric\"><float name=\"alpha\" value=\"0.2\"/><string name=\"int_ior\" value=\"water\"/><float name=\"ext_ior\" value=\"1\"/></bsdf></shape><emitter type=\"constant\"/>",
    )
    .unwrap();
    assert_eq!(
        rough.materials[0].bsdf,
        Bsdf::RoughDielectric {
            alpha: 0.2.into(),
            alpha_v: None,
            distribution: Distribution::Beckmann,
            eta: 1.333,
            specular_reflectance: Vec3::ONE,
            specular_transmittance: Vec3::ONE,
        },
        "Mitsuba's default distribution is Beckmann"
    );
}

#[test]
fn masks_and_normal_maps_wrap_their_bsdf_and_twosided_reaches_inside() {
    let s = load(
        "<shape type=\"cube\"><bsdf type=\"twosided\"><bsdf type=\"mask\"><float name=\"opacity\" value=\"0.3\"/><bsdf type=\"normalmap\"><texture name=\"normalmap\" type=\"checkerboard\"/><bsdf type=\"diffuse\"/></bsdf></bsdf></bsdf></shape><emitter type=\"constant\"/>",
    )
    .unwrap();
    assert_eq!(
        s.materials[0].bsdf,
        Bsdf::Mask {
            opacity: 0.3.into(),
            bsdf: Box::new(Bsdf::NormalMap {
                normals: TextureId(0),
                bsdf: Box::new(Bsdf::Diffuse {
                    reflectance: Vec3::splat(0.5).into()
                }),
            }),
        }
    );
}

#[test]
fn bad_iors_and_masks_are_errors_at_their_elements() {
    for (bsdf, words) in [
        (
            "<bsdf type=\"dielectric\"><float name=\"int_ior\" value=\"0\"/></bsdf>",
            &["int_ior = 0 must be positive"][..],
        ),
        (
            "<bsdf type=\"thindielectric\"><float name=\"ext_ior\" value=\"-1\"/></bsdf>",
            &["ext_ior = -1 must be positive"],
        ),
        (
            "<bsdf type=\"roughdielectric\"><string name=\"int_ior\" value=\"glass\"/></bsdf>",
            &["unknown IOR name \"glass\"", "bk7"],
        ),
        (
            "<bsdf type=\"roughdielectric\"><float name=\"int_ior\" value=\"1.2\"/><float name=\"ext_ior\" value=\"1.2\"/></bsdf>",
            &["must differ"],
        ),
        (
            "<bsdf type=\"mask\"><float name=\"opacity\" value=\"1.5\"/><bsdf type=\"diffuse\"/></bsdf>",
            &["`opacity`", "outside [0, 1]"],
        ),
        ("<bsdf type=\"mask\"/>", &["needs one nested <bsdf>"]),
        (
            "<bsdf type=\"normalmap\"><bsdf type=\"diffuse\"/></bsdf>",
            &["needs a <texture name=\"normalmap\">"],
        ),
    ] {
        let text = xml(&format!(
            "<shape type=\"cube\">\n{bsdf}\n</shape><emitter type=\"constant\"/>"
        ));
        let e = load_mitsuba_str(&text, Path::new("bad.xml"), &[]).unwrap_err();
        let line = line_of(&text, bsdf);
        assert!(
            e.diagnostics
                .iter()
                .any(|d| d.line == line && words.iter().all(|w| d.to_string().contains(w))),
            "{words:?}: {e}"
        );
    }
}

#[test]
fn every_problem_of_a_file_is_reported_at_once() {
    expect_errors(
        "hair-and-spectra.xml",
        &[
            (
                "<shape type=\"hair\"",
                &["<shape type=\"hair\">", "unsupported"],
            ),
            ("head.ply", &["head.ply"]),
            (
                "\"roughness\"",
                &["<float name=\"roughness\">", "<bsdf type=\"plastic\">"],
            ),
        ],
    );
}

#[test]
fn unknown_elements_attributes_and_references_are_located() {
    let text = xml(
        "<shape type=\"cube\" colour=\"red\">\n<ref id=\"nowhere\"/>\n</shape>\n<medium type=\"homogeneous\"/>\n<lamp/>\n<emitter type=\"area\"/>\n<bsdf type=\"diffuse\"><texture type=\"checkerboard\" name=\"reflectance\"/></bsdf>",
    );
    let e = load_mitsuba_str(&text, Path::new("u.xml"), &[]).unwrap_err();
    let lines: Vec<(usize, &str)> = e
        .diagnostics
        .iter()
        .map(|d| (d.line, d.message.as_str()))
        .collect();
    let has = |needle: &str, word: &str| {
        let l = line_of(&text, needle);
        assert!(
            lines.iter().any(|(dl, m)| *dl == l && m.contains(word)),
            "{needle}/{word}: {e}"
        );
    };
    has("colour=", "`colour`");
    has("nowhere", "nowhere");
    has("<medium", "<medium type=\"homogeneous\">");
    has("<lamp", "<lamp>");
    has("<emitter type=\"area\"", "nested in a <shape>");
}

/// Writes `files` (name, content) into a fresh directory and loads the first one.
fn load_files(files: &[(&str, &str)]) -> (tempfile::TempDir, Result<Scene, SceneError>) {
    let dir = tempfile::tempdir().unwrap();
    for (name, text) in files {
        let p = dir.path().join(name);
        std::fs::create_dir_all(p.parent().unwrap()).unwrap();
        std::fs::write(p, text).unwrap();
    }
    let r = load_mitsuba(&dir.path().join(files[0].0), &[]);
    (dir, r)
}

const LIT_CUBE: &str =
    "<shape type=\"cube\"><ref id=\"white\"/></shape><emitter type=\"constant\"/>";

#[test]
fn includes_are_relative_to_the_including_file_and_name_their_own_lines() {
    let (_d, s) = load_files(&[
        (
            "main.xml",
            &xml(&format!(
                "<include filename=\"parts/bsdfs.xml\"/>\n{LIT_CUBE}"
            )),
        ),
        (
            "parts/bsdfs.xml",
            &xml("<include filename=\"more/white.xml\"/>"),
        ),
        (
            "parts/more/white.xml",
            &xml(
                "<bsdf type=\"diffuse\" id=\"white\"><rgb name=\"reflectance\" value=\"0.25\"/></bsdf>",
            ),
        ),
    ]);
    let s = s.unwrap();
    assert_eq!(
        one_sided(&s.material(s.instances[0].material).bsdf),
        Bsdf::Diffuse {
            reflectance: Vec3::splat(0.25).into()
        }
    );
    let (_d, e) = load_files(&[
        (
            "main.xml",
            &xml(&format!("<include filename=\"inc.xml\"/>\n{LIT_CUBE}")),
        ),
        (
            "inc.xml",
            "<scene version=\"3.0.0\">\n\n<bsdf type=\"diffuse\" id=\"white\"><float name=\"bogus\" value=\"1\"/></bsdf>\n</scene>",
        ),
    ]);
    let e = e.unwrap_err();
    let d = &e.diagnostics[0];
    assert!(d.file.ends_with("inc.xml") && d.line == 3, "{e}");
    assert!(d.message.contains("bogus"), "{e}");
}

#[test]
fn include_cycles_depth_and_missing_files_are_errors() {
    let (_d, e) = load_files(&[
        ("a.xml", &xml("<include filename=\"b.xml\"/>")),
        ("b.xml", &xml("<include filename=\"a.xml\"/>")),
    ]);
    let e = e.unwrap_err().to_string();
    assert!(
        e.contains("cyclic <include>") && e.contains("b.xml:2:1"),
        "{e}"
    );
    let chain: Vec<(String, String)> = (0..18)
        .map(|i| {
            (
                format!("f{i}.xml"),
                xml(&format!("<include filename=\"f{}.xml\"/>", i + 1)),
            )
        })
        .chain([("f18.xml".to_string(), xml(LIT_CUBE))])
        .collect();
    let files: Vec<(&str, &str)> = chain
        .iter()
        .map(|(a, b)| (a.as_str(), b.as_str()))
        .collect();
    let (_d, e) = load_files(&files);
    let e = e.unwrap_err().to_string();
    assert!(e.contains("more than 16 includes deep"), "{e}");
    // 16 deep is fine (the only error is the BSDF no file defines).
    let (_d, e) = load_files(&files[2..]);
    let e = e.unwrap_err().to_string();
    assert!(!e.contains("includes deep") && e.contains("white"), "{e}");
    let (_d, e) = load_files(&[("m.xml", &xml("<include filename=\"nope.xml\"/>"))]);
    let e = e.unwrap_err().to_string();
    assert!(e.contains("m.xml:2:1") && e.contains("nope.xml"), "{e}");
}

#[test]
fn path_folders_resolve_file_names_and_aliases_name_objects() {
    let ply = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
    let (_d, s) = load_files(&[
        (
            "m.xml",
            &xml(
                "<path value=\"meshes\"/>\n<bsdf type=\"diffuse\" id=\"a\"/>\n<alias id=\"a\" as=\"white\"/>\n<shape type=\"ply\"><string name=\"filename\" value=\"tri.ply\"/><ref id=\"white\"/></shape><emitter type=\"constant\"/>",
            ),
        ),
        ("meshes/tri.ply", ply),
    ]);
    let s = s.unwrap();
    assert_eq!(s.meshes[0].indices.len(), 1);
    let (_d, e) = load_files(&[(
        "m.xml",
        &xml(&format!(
            "<path value=\"gone\"/>\n<alias id=\"x\" as=\"y\"/>\n{LIT_CUBE}"
        )),
    )]);
    let e = e.unwrap_err().to_string();
    assert!(e.contains("m.xml:2:1") && e.contains("gone"), "{e}");
    assert!(
        e.contains("m.xml:3:1") && e.contains("<alias id=\"x\">"),
        "{e}"
    );
}

#[test]
fn top_level_emitters_and_bsdfs_are_referenced_by_id_and_ref_cycles_are_errors() {
    let s = load(
        "<emitter type=\"area\" id=\"lamp\"><rgb name=\"radiance\" value=\"4\"/></emitter>\n<bsdf type=\"diffuse\" id=\"w\"/>\n<shape type=\"rectangle\"><ref name=\"bsdf\" id=\"w\"/><ref id=\"lamp\"/></shape>",
    )
    .unwrap();
    assert_eq!(
        s.material(s.instances[0].material).emission,
        Vec3::splat(4.0)
    );
    let e = load(&format!(
        "<bsdf type=\"twosided\" id=\"a\"><ref id=\"b\"/></bsdf>\n<bsdf type=\"twosided\" id=\"b\"><ref id=\"a\"/></bsdf>\n<bsdf type=\"twosided\" id=\"me\"><ref id=\"me\"/></bsdf>\n{LIT_CUBE}<bsdf type=\"diffuse\" id=\"white\"/>"
    ))
    .unwrap_err()
    .to_string();
    assert!(e.contains("circular reference a -> b -> a"), "{e}");
    assert!(e.contains("circular reference me -> me"), "{e}");
}

#[test]
fn spectra_become_rgb_as_in_mitsubas_rgb_variants() {
    let s = load(
        "<shape type=\"cube\"><bsdf type=\"diffuse\"><spectrum name=\"reflectance\" value=\"400:0.5, 700:0.5\"/></bsdf>\n<emitter type=\"area\"><spectrum name=\"radiance\" value=\"2\"/></emitter></shape>",
    )
    .unwrap();
    let m = s.material(s.instances[0].material);
    let Bsdf::Diffuse {
        reflectance: Param::Const(reflectance),
    } = one_sided(&m.bsdf)
    else {
        panic!()
    };
    // Flat over 400-700 nm only: nearly grey, a little less than 0.5 (the tails are cut off).
    assert!(
        (reflectance - Vec3::splat(0.48)).abs().max_element() < 0.03,
        "{reflectance}"
    );
    // A constant emitted spectrum is equal energy: 2 · XYZ→sRGB · (1, 1, 1).
    let expect = Vec3::new(1.204794, 0.948292, 0.908916) * 2.0;
    assert!(
        (m.emission - expect).abs().max_element() < 1e-4,
        "{}",
        m.emission
    );
}

#[test]
fn pinhole_focus_distance_and_a_whole_film_crop_change_nothing() {
    let body = |extra_sensor: &str, extra_film: &str| {
        format!(
            "<sensor type=\"perspective\">{extra_sensor}<film type=\"hdrfilm\"><integer name=\"width\" value=\"32\"/><integer name=\"height\" value=\"16\"/><string name=\"pixel_format\" value=\"rgba\"/>{extra_film}<rfilter type=\"box\"/></film></sensor>{LIT_CUBE}<bsdf type=\"diffuse\" id=\"white\"/>"
        )
    };
    let plain = load(&body("", "")).unwrap();
    let same = load(&body(
        "<float name=\"focus_distance\" value=\"3\"/>",
        "<integer name=\"crop_offset_x\" value=\"0\"/><integer name=\"crop_width\" value=\"32\"/><integer name=\"crop_height\" value=\"16\"/>",
    ))
    .unwrap();
    assert_eq!(plain.camera, same.camera);
    let e = load(&body("", "<integer name=\"crop_width\" value=\"8\"/>"))
        .unwrap_err()
        .to_string();
    assert!(e.contains("crop_width 8 crops the film"), "{e}");
}

#[test]
fn disk_and_cylinder_are_placed_as_in_mitsuba() {
    let s = load(
        "<shape type=\"disk\"><transform name=\"to_world\"><scale value=\"2\"/></transform></shape>\n<shape type=\"cylinder\"><point name=\"p0\" value=\"1, 0, 0\"/><point name=\"p1\" value=\"1, 0, 2\"/><float name=\"radius\" value=\"0.5\"/></shape><emitter type=\"constant\"/>",
    )
    .unwrap();
    let pi = std::f64::consts::PI;
    assert!((s.meshes[0].area() / (4.0 * pi) - 1.0).abs() < 1e-5);
    let cyl = &s.meshes[1];
    assert!((cyl.area() / (2.0 * pi) - 1.0).abs() < 1e-5, "2π·r·length");
    for p in &cyl.positions {
        let r = Vec3::new(p.x - 1.0, p.y, 0.0).length();
        assert!(
            (r - 0.5).abs() < 1e-3 && (-1e-6..=2.0 + 1e-6).contains(&p.z),
            "{p}"
        );
    }
    // Along +z Mitsuba's frame is the identity: φ = 0 is +x, where u = 0.
    let i = cyl
        .positions
        .iter()
        .position(|p| (p.x - 1.5).abs() < 1e-3 && p.y.abs() < 1e-6 && p.z > 1.0)
        .unwrap();
    assert_eq!(cyl.uvs[i], glam::Vec2::new(0.0, 1.0));
}

#[test]
fn textures_fill_reflectances_and_roughness() {
    let dir = tempfile::tempdir().unwrap();
    image::RgbImage::from_raw(2, 1, vec![255, 0, 0, 0, 0, 255])
        .unwrap()
        .save(dir.path().join("t.png"))
        .unwrap();
    let text = xml(
        "<texture type=\"bitmap\" id=\"tex\"><string name=\"filename\" value=\"t.png\"/><boolean name=\"raw\" value=\"true\"/><string name=\"filter_type\" value=\"nearest\"/><string name=\"wrap_mode\" value=\"clamp\"/><transform name=\"to_uv\"><scale x=\"2\" y=\"3\"/></transform></texture>\n<shape type=\"cube\"><bsdf type=\"diffuse\"><ref name=\"reflectance\" id=\"tex\"/></bsdf></shape>\n<shape type=\"cube\"><bsdf type=\"roughconductor\"><string name=\"distribution\" value=\"ggx\"/><ref name=\"alpha\" id=\"tex\"/><texture type=\"checkerboard\" name=\"specular_reflectance\"><rgb name=\"color0\" value=\"0.9\"/></texture></bsdf></shape>\n<shape type=\"cube\"><bsdf type=\"diffuse\"><texture type=\"mesh_attribute\" name=\"reflectance\"><string name=\"name\" value=\"vertex_color\"/></texture></bsdf></shape><emitter type=\"constant\"/>",
    );
    let path = dir.path().join("s.xml");
    std::fs::write(&path, &text).unwrap();
    let s = load_mitsuba(&path, &[]).unwrap();
    assert_eq!(s.textures.len(), 3, "the referenced bitmap once");
    let Texture::Bitmap(b) = &s.textures[0] else {
        panic!("{:?}", s.textures[0])
    };
    assert!(b.raw && b.filter == FilterType::Nearest && b.wrap == WrapMode::Clamp);
    assert_eq!(b.image.texels, vec![Vec3::X, Vec3::Z]);
    assert_eq!(
        b.to_uv.transform_point2(glam::Vec2::ONE),
        glam::Vec2::new(2.0, 3.0)
    );
    let mat = |i: usize| one_sided(&s.material(s.instances[i].material).bsdf);
    assert_eq!(
        mat(0),
        Bsdf::Diffuse {
            reflectance: Param::Texture(TextureId(0))
        }
    );
    let Bsdf::Conductor {
        alpha,
        specular_reflectance,
        ..
    } = mat(1)
    else {
        panic!()
    };
    assert_eq!(alpha, Param::Texture(TextureId(0)));
    assert_eq!(specular_reflectance, Param::Texture(TextureId(1)));
    assert!(matches!(
        s.textures[1],
        Texture::Checkerboard { color0, color1, .. } if color0 == Vec3::splat(0.9) && color1 == Vec3::splat(0.2)
    ));
    assert!(matches!(s.textures[2], Texture::MeshAttribute { .. }));
}

#[test]
fn bad_texture_files_and_textures_where_constants_belong_are_errors() {
    let e = load("<shape type=\"cube\"><bsdf type=\"diffuse\"><texture type=\"bitmap\" name=\"reflectance\"><string name=\"filename\" value=\"missing.png\"/></texture></bsdf></shape><emitter type=\"constant\"/>")
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("test.xml:2:") && e.contains("missing.png"),
        "{e}"
    );
    let e = load("<shape type=\"cube\"/><emitter type=\"point\"><texture type=\"checkerboard\" name=\"intensity\"/></emitter>")
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("<texture type=\"checkerboard\">") && e.contains("here"),
        "{e}"
    );
}

#[test]
fn instances_share_the_meshes_of_their_shapegroup() {
    let s = load(
        "<shape type=\"shapegroup\" id=\"g\"><shape type=\"cube\"><bsdf type=\"diffuse\"/></shape><shape type=\"sphere\"><float name=\"radius\" value=\"0.5\"/></shape></shape>\n<shape type=\"instance\"><ref id=\"g\"/></shape>\n<shape type=\"instance\"><ref id=\"g\"/><transform name=\"to_world\"><translate x=\"5\"/></transform></shape><emitter type=\"constant\"/>",
    )
    .unwrap();
    assert_eq!(s.meshes.len(), 2, "the group's meshes once");
    assert_eq!(s.instances.len(), 4);
    assert_eq!(s.instances[0].mesh, s.instances[2].mesh);
    assert_eq!(
        s.instances[2].to_world.point(Vec3::ZERO),
        Vec3::new(5.0, 0.0, 0.0)
    );
    let e = load("<shape type=\"instance\"><ref id=\"nope\"/></shape><emitter type=\"constant\"/>")
        .unwrap_err()
        .to_string();
    assert!(e.contains("test.xml:2:") && e.contains("nope"), "{e}");
}

#[test]
fn direct_and_wrapped_integrators_render_with_the_path_tracer() {
    let scene = |integrator: &str| {
        load(&format!(
            "{integrator}<shape type=\"sphere\"/><emitter type=\"constant\"/>"
        ))
    };
    let s = scene("<integrator type=\"direct\"/>").unwrap();
    assert_eq!(s.render.max_depth, Some(2));
    assert!(s.warnings.is_empty(), "{:?}", s.warnings);
    let s = scene("<integrator type=\"direct\"><integer name=\"emitter_samples\" value=\"0\"/><integer name=\"bsdf_samples\" value=\"4\"/></integrator>").unwrap();
    assert_eq!(s.render.max_depth, Some(2));
    assert!(
        s.warnings[0].message.contains("emitter sampling on"),
        "{:?}",
        s.warnings
    );
    for (kind, inner_depth) in [("moment", 3), ("aov", 4)] {
        let s = scene(&format!(
            "<integrator type=\"{kind}\"><string name=\"aovs\" value=\"dd.y:depth\"/><integrator type=\"path\"><integer name=\"max_depth\" value=\"{inner_depth}\"/></integrator></integrator>"
        ));
        let s = match (kind, s) {
            // `moment` has no `aovs` parameter in Mitsuba either: it is left unread.
            ("moment", Err(e)) => {
                assert!(e.to_string().contains("aovs"), "{e}");
                continue;
            }
            (_, s) => s.unwrap(),
        };
        assert_eq!(s.render.max_depth, Some(inner_depth));
        assert!(
            s.warnings[0]
                .message
                .contains(&format!("<integrator type=\"{kind}\">")),
            "{:?}",
            s.warnings
        );
    }
    let s =
        scene("<integrator type=\"moment\"><integrator type=\"direct\"/></integrator>").unwrap();
    assert_eq!(s.render.max_depth, Some(2));
    let s = scene(
        "<integrator type=\"ptracer\"><integer name=\"max_depth\" value=\"5\"/></integrator>",
    )
    .unwrap();
    assert_eq!(s.render.max_depth, Some(5));
    assert!(s.warnings[0].message.contains("ptracer"));
    // Without media, volpath is path (with a warning); with them it is refused.
    let s = scene("<integrator type=\"volpath\"/>").unwrap();
    assert_eq!(s.render.max_depth, Some(-1));
    assert!(s.warnings[0].message.contains("no participating media"));
    let e = load("<integrator type=\"volpath\"/><shape type=\"sphere\"><medium type=\"homogeneous\" name=\"interior\"/></shape><emitter type=\"constant\"/>")
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("unsupported <integrator type=\"volpath\"> with participating media"),
        "{e}"
    );
}

#[test]
fn thinlens_and_orthographic_sensors_load() {
    let film = "<film type=\"hdrfilm\"><integer name=\"width\" value=\"40\"/><integer name=\"height\" value=\"20\"/></film>";
    let s = load(&format!("<sensor type=\"thinlens\"><float name=\"fov\" value=\"30\"/><float name=\"aperture_radius\" value=\"0.2\"/><float name=\"focus_distance\" value=\"5.9\"/>{film}</sensor><emitter type=\"constant\"/>")).unwrap();
    let c = s.camera.unwrap();
    assert_eq!(
        c.projection,
        Projection::ThinLens {
            aperture_radius: 0.2,
            focus_distance: 5.9
        }
    );
    let e = load("<sensor type=\"thinlens\"><float name=\"aperture_radius\" value=\"0.2\"/></sensor><emitter type=\"constant\"/>").unwrap_err().to_string();
    assert!(e.contains("focus_distance"), "{e}");
    // The orthographic view is [−1, 1] across, [−1, 1] / aspect up, scaled by to_world.
    let s = load(&format!("<sensor type=\"orthographic\"><transform name=\"to_world\"><scale x=\"2\" y=\"3\"/><lookat origin=\"0, 0, 5\" target=\"0, 0, 0\" up=\"0, 1, 0\"/></transform>{film}</sensor><emitter type=\"constant\"/>")).unwrap();
    let c = s.camera.unwrap();
    assert_eq!(
        c.projection,
        Projection::Orthographic {
            half_width: 2.0,
            half_height: 1.5
        }
    );
    assert!((c.position - Vec3::new(0.0, 0.0, 5.0)).length() < 1e-6);
    let e = load("<sensor type=\"orthographic\"><float name=\"fov\" value=\"30\"/></sensor><emitter type=\"constant\"/>").unwrap_err().to_string();
    assert!(e.contains("fov"), "{e}");
}
