//! glTF materials and lights on a file written here with its `.bin` and PNGs beside it:
//! textures read into the scene's texture table (base colour sRGB-decoded times the factor,
//! metallic-roughness as α = (factor · G)² per texel, the sampler, `KHR_texture_transform`),
//! glass (`KHR_materials_transmission`, `_ior`, `_volume`), alpha modes, directional lights.
use eyeadapt_scene::{Bsdf, FilterType, Light, Param, Texture, WrapMode, gltf};
use glam::Vec2;
use std::path::Path;

fn srgb_to_linear(c: f32) -> f32 {
    if c <= 0.04045 {
        c / 12.92
    } else {
        libm::powf((c + 0.055) / 1.055, 2.4)
    }
}

/// One textured triangle; `material` is the material's JSON.
fn write_scene(dir: &Path, material: &str) -> std::path::PathBuf {
    let mut bin = Vec::new();
    for v in [[0f32, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]] {
        v.iter().for_each(|x| bin.extend(x.to_le_bytes()));
    }
    for uv in [[0f32, 0.0], [1.0, 0.0], [0.0, 1.0]] {
        uv.iter().for_each(|x| bin.extend(x.to_le_bytes()));
    }
    std::fs::write(dir.join("tri.bin"), &bin).unwrap();
    let mut base = image::RgbImage::new(2, 1);
    base.put_pixel(0, 0, image::Rgb([255, 128, 0]));
    base.put_pixel(1, 0, image::Rgb([0, 0, 255]));
    base.save(dir.join("base.png")).unwrap();
    let mut mr = image::RgbImage::new(2, 1);
    mr.put_pixel(0, 0, image::Rgb([0, 153, 0]));
    mr.put_pixel(1, 0, image::Rgb([255, 255, 0]));
    mr.save(dir.join("mr.png")).unwrap();
    let json = format!(
        r#"{{
  "asset": {{"version": "2.0"}},
  "extensionsUsed": ["KHR_texture_transform", "KHR_materials_transmission", "KHR_materials_ior",
                     "KHR_materials_volume", "KHR_lights_punctual"],
  "extensions": {{"KHR_lights_punctual": {{"lights": [
    {{"type": "directional", "intensity": 1366.0, "color": [1.0, 0.5, 0.25]}}]}}}},
  "scene": 0,
  "scenes": [{{"nodes": [0, 1]}}],
  "nodes": [{{"mesh": 0}},
            {{"rotation": [-0.7071068, 0, 0, 0.7071068], "extensions": {{"KHR_lights_punctual": {{"light": 0}}}}}}],
  "meshes": [{{"primitives": [{{"attributes": {{"POSITION": 0, "TEXCOORD_0": 1}}, "material": 0}}]}}],
  "materials": [{material}],
  "textures": [{{"source": 0}}, {{"source": 1, "sampler": 0}}],
  "samplers": [{{"magFilter": 9728, "wrapS": 33071, "wrapT": 33071}}],
  "images": [{{"uri": "base.png"}}, {{"uri": "mr.png"}}],
  "buffers": [{{"uri": "tri.bin", "byteLength": 60}}],
  "bufferViews": [
    {{"buffer": 0, "byteOffset": 0, "byteLength": 36}},
    {{"buffer": 0, "byteOffset": 36, "byteLength": 24}}
  ],
  "accessors": [
    {{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
      "min": [0, 0, 0], "max": [1, 1, 0]}},
    {{"bufferView": 1, "componentType": 5126, "count": 3, "type": "VEC2"}}
  ]
}}"#
    );
    let path = dir.join("tri.gltf");
    std::fs::write(&path, json).unwrap();
    path
}

fn bitmap(t: &Texture) -> &eyeadapt_scene::Bitmap {
    match t {
        Texture::Bitmap(b) => b,
        other => panic!("not a bitmap: {other:?}"),
    }
}

#[test]
fn base_colour_and_roughness_textures_become_linear_texels() {
    let dir = tempfile::tempdir().unwrap();
    let path = write_scene(
        dir.path(),
        r#"{"pbrMetallicRoughness": {
            "baseColorFactor": [0.5, 1.0, 1.0, 1.0],
            "baseColorTexture": {"index": 0, "extensions": {"KHR_texture_transform":
                {"offset": [0.5, 0.0], "rotation": 1.5707963, "scale": [2.0, 2.0]}}},
            "metallicFactor": 0.0, "roughnessFactor": 0.5,
            "metallicRoughnessTexture": {"index": 1}}}"#,
    );
    let scene = gltf::load_gltf(&path).unwrap();
    let Bsdf::Plastic {
        reflectance: Param::Texture(rt),
        alpha: Param::Texture(at),
        ..
    } = scene.materials[0].bsdf
    else {
        panic!("{:?}", scene.materials[0].bsdf);
    };
    let base = bitmap(&scene.textures[rt.0 as usize]);
    let texel = base.image.texels[0];
    assert!((texel.x - 0.5).abs() < 1e-6, "R: 1.0 times the factor 0.5");
    assert!(
        (texel.y - srgb_to_linear(128.0 / 255.0)).abs() < 1e-6,
        "G decoded from sRGB"
    );
    assert_eq!(texel.z, 0.0);
    assert_eq!(base.image.texels[1], glam::Vec3::new(0.0, 0.0, 1.0));
    // Default sampler: bilinear, repeat. The transform: scale 2, rotate a quarter turn
    // counter-clockwise (u' = u cos - v sin, v' = u sin + v cos), then offset.
    assert_eq!(
        (base.filter, base.wrap),
        (FilterType::Bilinear, WrapMode::Repeat)
    );
    let uv = base.to_uv.transform_point2(Vec2::new(1.0, 0.0));
    assert!((uv - Vec2::new(0.5, 2.0)).length() < 1e-5, "{uv}");
    let uv = base.to_uv.transform_point2(Vec2::new(0.0, 1.0));
    assert!((uv - Vec2::new(-1.5, 0.0)).length() < 1e-5, "{uv}");

    let alpha = bitmap(&scene.textures[at.0 as usize]);
    // G = 153/255 = 0.6, roughness factor 0.5: α = 0.3² (the other texel: G = 1, α = 0.5²).
    assert!(
        (alpha.image.texels[0] - glam::Vec3::splat(0.09))
            .abs()
            .max_element()
            < 1e-6
    );
    assert!(
        (alpha.image.texels[1] - glam::Vec3::splat(0.25))
            .abs()
            .max_element()
            < 1e-6
    );
    // The sampler says NEAREST and CLAMP_TO_EDGE.
    assert_eq!(
        (alpha.filter, alpha.wrap),
        (FilterType::Nearest, WrapMode::Clamp)
    );
    assert!(scene.warnings.is_empty(), "{:?}", scene.warnings);
}

#[test]
fn a_metallic_texture_decides_by_its_mean_and_says_when_it_is_mixed() {
    let dir = tempfile::tempdir().unwrap();
    // mr.png's B channel is 0 and 0: a dielectric whatever the factor says.
    let path = write_scene(
        dir.path(),
        r#"{"pbrMetallicRoughness": {"metallicFactor": 1.0, "metallicRoughnessTexture": {"index": 1}}}"#,
    );
    let scene = gltf::load_gltf(&path).unwrap();
    assert!(
        matches!(scene.materials[0].bsdf, Bsdf::Plastic { .. }),
        "{:?}",
        scene.materials[0].bsdf
    );
    assert!(scene.warnings.is_empty(), "{:?}", scene.warnings);
}

#[test]
fn a_missing_image_is_named_with_its_pointer() {
    let dir = tempfile::tempdir().unwrap();
    let path = write_scene(
        dir.path(),
        r#"{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}"#,
    );
    std::fs::remove_file(dir.path().join("base.png")).unwrap();
    let err = gltf::load_gltf(&path).unwrap_err().to_string();
    assert!(
        err.contains("/images/0/uri") && err.contains("base.png"),
        "{err}"
    );
}

#[test]
fn transmission_makes_thin_glass_or_refracting_glass_with_a_volume() {
    let dir = tempfile::tempdir().unwrap();
    let glass = |extra: &str| {
        let m = format!(
            r#"{{"pbrMetallicRoughness": {{"baseColorFactor": [0.9, 1.0, 0.8, 1.0],
                "metallicFactor": 0.0, "roughnessFactor": 0.0}},
               "extensions": {{"KHR_materials_transmission": {{"transmissionFactor": 1.0}},
                              "KHR_materials_ior": {{"ior": 1.45}}{extra}}}}}"#
        );
        gltf::load_gltf(&write_scene(dir.path(), &m))
            .unwrap()
            .materials[0]
            .bsdf
            .clone()
    };
    // glTF's glass is thin-walled unless a volume gives it thickness.
    match glass("") {
        Bsdf::ThinDielectric {
            eta,
            specular_transmittance,
            ..
        } => {
            assert_eq!(eta, 1.45);
            assert_eq!(specular_transmittance, glam::Vec3::new(0.9, 1.0, 0.8));
        }
        b => panic!("{b:?}"),
    }
    let thick = r#", "KHR_materials_volume": {"thicknessFactor": 0.02}"#;
    assert!(matches!(glass(thick), Bsdf::Dielectric { eta, .. } if eta == 1.45));
}

#[test]
fn alpha_modes_cut_out_or_blend() {
    let dir = tempfile::tempdir().unwrap();
    let bsdf = |m: &str| {
        gltf::load_gltf(&write_scene(dir.path(), m))
            .unwrap()
            .materials[0]
            .bsdf
            .clone()
    };
    let opaque = r#"{"pbrMetallicRoughness": {"baseColorFactor": [1, 1, 1, 0.3]}}"#;
    assert!(
        matches!(bsdf(opaque), Bsdf::Conductor { .. }),
        "OPAQUE ignores alpha"
    );
    let blend =
        r#"{"alphaMode": "BLEND", "pbrMetallicRoughness": {"baseColorFactor": [1, 1, 1, 0.3]}}"#;
    assert!(matches!(bsdf(blend), Bsdf::Mask { opacity: Param::Const(o), .. } if o == 0.3));
    let cut = r#"{"alphaMode": "MASK", "alphaCutoff": 0.5, "pbrMetallicRoughness": {"baseColorFactor": [1, 1, 1, 0.3]}}"#;
    assert!(matches!(bsdf(cut), Bsdf::Mask { opacity: Param::Const(o), .. } if o == 0.0));
    let kept =
        r#"{"alphaMode": "MASK", "pbrMetallicRoughness": {"baseColorFactor": [1, 1, 1, 0.6]}}"#;
    assert!(
        matches!(bsdf(kept), Bsdf::Conductor { .. }),
        "above the default cutoff 0.5"
    );
    // With a texture the opacity is per texel (base.png has no alpha channel: all opaque).
    let textured =
        r#"{"alphaMode": "MASK", "pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}"#;
    let scene = gltf::load_gltf(&write_scene(dir.path(), textured)).unwrap();
    let Bsdf::Mask {
        opacity: Param::Texture(t),
        ..
    } = scene.materials[0].bsdf
    else {
        panic!("{:?}", scene.materials[0].bsdf);
    };
    assert!(
        bitmap(&scene.textures[t.0 as usize])
            .image
            .texels
            .iter()
            .all(|&x| x == glam::Vec3::ONE)
    );
}

#[test]
fn a_directional_light_is_a_sun_of_lux_over_683_down_its_nodes_minus_z() {
    let dir = tempfile::tempdir().unwrap();
    let scene = gltf::load_gltf(&write_scene(dir.path(), "{}")).unwrap();
    // 1366 lux × (1, 0.5, 0.25) / 683 lm/W; the node turns −z to −y: the sun shines down.
    match scene.lights[..] {
        [
            Light::Directional {
                direction,
                irradiance,
            },
        ] => {
            assert!(
                (irradiance - glam::Vec3::new(2.0, 1.0, 0.5))
                    .abs()
                    .max_element()
                    < 1e-5
            );
            assert!(
                (direction - glam::Vec3::NEG_Y).length() < 1e-5,
                "{direction}"
            );
        }
        ref other => panic!("{other:?}"),
    }
}
