//! A glTF normal texture bends the shading normal the way glTF defines its tangent space:
//! red along +u, green along the image's up (n × ∂p/∂u for UVs that are not mirrored), blue
//! along the surface normal. A floor whose normal texture tilts every normal 45° towards one
//! side is lit by a sun from 45° on that side (the light arrives along the bent normal: the
//! flat floor's brightness × √2) and from the opposite side (grazing the bent normal: black).
use eyeadapt_scene::gltf::load_gltf;
use eyeadapt_tracer::{PathSettings, RenderSettings, SceneData, View, render};
use glam::Vec3;
use std::path::Path;

/// A 2 × 2 quad at z = 0 facing +z (u along +x, glTF v down the image, i.e. along −y), seen
/// from z = 2 by the file's camera, lit by a sun whose node has `rotation`; the material has
/// the 1 × 1 normal texture `normal` (8-bit RGB) when given.
fn write(dir: &Path, normal: Option<[u8; 3]>, rotation: [f32; 4]) -> std::path::PathBuf {
    let mut bin = Vec::new();
    for v in [
        [-1f32, -1.0, 0.0],
        [1.0, -1.0, 0.0],
        [1.0, 1.0, 0.0],
        [-1.0, 1.0, 0.0],
    ] {
        v.iter().for_each(|x| bin.extend(x.to_le_bytes()));
    }
    for uv in [[0f32, 1.0], [1.0, 1.0], [1.0, 0.0], [0.0, 0.0]] {
        uv.iter().for_each(|x| bin.extend(x.to_le_bytes()));
    }
    for i in [0u16, 1, 2, 0, 2, 3] {
        bin.extend(i.to_le_bytes());
    }
    std::fs::write(dir.join("quad.bin"), &bin).unwrap();
    let texture = match normal {
        Some(c) => {
            image::RgbImage::from_pixel(1, 1, image::Rgb(c))
                .save(dir.join("normal.png"))
                .unwrap();
            r#", "normalTexture": {"index": 0}"#
        }
        None => "",
    };
    let [x, y, z, w] = rotation;
    let json = format!(
        r#"{{
  "asset": {{"version": "2.0"}},
  "extensionsUsed": ["KHR_lights_punctual"],
  "extensions": {{"KHR_lights_punctual": {{"lights": [{{"type": "directional", "intensity": 683.0}}]}}}},
  "scene": 0,
  "scenes": [{{"nodes": [0, 1, 2]}}],
  "nodes": [{{"mesh": 0}},
            {{"rotation": [{x}, {y}, {z}, {w}], "extensions": {{"KHR_lights_punctual": {{"light": 0}}}}}},
            {{"camera": 0, "translation": [0, 0, 2]}}],
  "cameras": [{{"type": "perspective", "perspective": {{"yfov": 0.5, "aspectRatio": 1.0, "znear": 0.01}}}}],
  "meshes": [{{"primitives": [{{"attributes": {{"POSITION": 0, "TEXCOORD_0": 1}}, "indices": 2, "material": 0}}]}}],
  "materials": [{{"pbrMetallicRoughness": {{"baseColorFactor": [0.5, 0.5, 0.5, 1.0],
                  "metallicFactor": 0.0, "roughnessFactor": 1.0}}{texture}}}],
  "textures": [{{"source": 0}}],
  "images": [{{"uri": "normal.png"}}],
  "buffers": [{{"uri": "quad.bin", "byteLength": 92}}],
  "bufferViews": [
    {{"buffer": 0, "byteOffset": 0, "byteLength": 48}},
    {{"buffer": 0, "byteOffset": 48, "byteLength": 32}},
    {{"buffer": 0, "byteOffset": 80, "byteLength": 12}}
  ],
  "accessors": [
    {{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3",
      "min": [-1, -1, 0], "max": [1, 1, 0]}},
    {{"bufferView": 1, "componentType": 5126, "count": 4, "type": "VEC2"}},
    {{"bufferView": 2, "componentType": 5123, "count": 6, "type": "SCALAR"}}
  ]
}}"#
    );
    let path = dir.join("quad.gltf");
    std::fs::write(&path, json).unwrap();
    path
}

/// The mean red value of the quad rendered with direct light only, 8 × 8 px.
fn brightness(normal: Option<[u8; 3]>, rotation: [f32; 4]) -> f32 {
    let dir = tempfile::tempdir().unwrap();
    let mut scene = load_gltf(&write(dir.path(), normal, rotation)).unwrap();
    assert!(scene.warnings.is_empty(), "{:?}", scene.warnings);
    let mut camera = scene.camera.clone().expect("the file's camera");
    (camera.width, camera.height) = (8, 8);
    scene.camera = Some(camera.clone());
    let settings = RenderSettings {
        spp: 4,
        path: PathSettings {
            max_depth: 2,
            rr_depth: 50,
        },
        seed: 1,
        frame: 0,
        filter: Default::default(),
        wcam_specular: Default::default(),
        guiding: Default::default(),
    };
    let f = render(
        &SceneData::new(&scene),
        &View::from_camera(&camera),
        &settings,
    );
    f.rgb.iter().map(|&c| Vec3::from(c).x).sum::<f32>() / f.rgb.len() as f32
}

/// A quarter turn's half: the sun node turned 45° about `axis` (its −z is the light's way).
fn turned(axis: Vec3, degrees: f32) -> [f32; 4] {
    glam::Quat::from_axis_angle(axis, degrees.to_radians()).to_array()
}

#[test]
fn a_normal_texture_tilts_the_shading_normal_along_u_and_up_the_image() {
    // Sun from +x, 45° above the floor: −z turned about +y by 45° is (−sin 45°, 0, −cos 45°).
    let from_plus_x = turned(Vec3::Y, 45.0);
    let from_minus_x = turned(Vec3::Y, -45.0);
    // Sun from +y (the image's up on this quad), 45° above: −z turned about +x by −45°.
    let from_plus_y = turned(Vec3::X, -45.0);
    let from_minus_y = turned(Vec3::X, 45.0);
    let flat = brightness(None, from_plus_x);
    // E = 683 lux / 683 = 1 W/m² at normal incidence: L = 0.5 / π · cos 45°.
    let expected = 0.5 / std::f32::consts::PI * std::f32::consts::FRAC_1_SQRT_2;
    assert!((flat / expected - 1.0).abs() < 1e-3, "{flat} vs {expected}");
    assert!((brightness(None, from_minus_x) / flat - 1.0).abs() < 1e-3);
    // Normals tilted 45° towards +u (+x): (0.707, 0, 0.707) stored as (n + 1) / 2.
    let towards_u = Some([218, 128, 218]);
    let lit = brightness(towards_u, from_plus_x);
    assert!((lit / flat - 2f32.sqrt()).abs() < 0.02, "{lit} / {flat}");
    let grazing = brightness(towards_u, from_minus_x);
    assert!(grazing / flat < 0.02, "{grazing} / {flat}");
    // Tilted towards the image's up (+y here).
    let towards_up = Some([128, 218, 218]);
    let lit = brightness(towards_up, from_plus_y);
    assert!((lit / flat - 2f32.sqrt()).abs() < 0.02, "{lit} / {flat}");
    let grazing = brightness(towards_up, from_minus_y);
    assert!(grazing / flat < 0.02, "{grazing} / {flat}");
}
