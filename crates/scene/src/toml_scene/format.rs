//! The TOML file as serde sees it: stage one of two-stage configuration (the raw shape of the
//! file, every key known, locations kept with `Spanned`). the sibling modules validate it into [`Scene`].
//!
//! Materials, shapes and lights are flat structs keyed by `type` rather than internally tagged
//! enums, because serde buffers tagged enums and would drop the spans that error messages need.
//!
//! [`Scene`]: crate::Scene
use serde::Deserialize;
use toml::Spanned;

pub type V3 = Spanned<[f32; 3]>;

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SceneFile {
    pub camera: Option<Spanned<CameraDef>>,
    pub render: Option<RenderDef>,
    #[serde(default)]
    pub textures: Vec<Spanned<TextureDef>>,
    #[serde(default)]
    pub materials: Vec<Spanned<MaterialDef>>,
    #[serde(default)]
    pub shapes: Vec<Spanned<ShapeDef>>,
    #[serde(default)]
    pub instances: Vec<Spanned<InstanceDef>>,
    #[serde(default)]
    pub lights: Vec<Spanned<LightDef>>,
    pub environment: Option<Spanned<EnvironmentDef>>,
    #[serde(default)]
    pub portals: Vec<Spanned<PortalDef>>,
    /// Validated by the camera-path module; kept raw here.
    pub camera_path: Option<Spanned<toml::Value>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CameraDef {
    pub position: V3,
    pub look_at: V3,
    pub up: Option<V3>,
    pub fov_deg: Spanned<f32>,
    pub width: Spanned<i64>,
    pub height: Spanned<i64>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RenderDef {
    pub spp: Option<Spanned<i64>>,
    pub max_depth: Option<Spanned<i64>>,
    pub rr_depth: Option<Spanned<i64>>,
    pub seed: Option<Spanned<i64>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MaterialDef {
    pub name: Spanned<String>,
    #[serde(rename = "type")]
    pub kind: Spanned<String>,
    pub reflectance: Option<V3>,
    pub emission: Option<V3>,
    pub roughness: Option<Spanned<f32>>,
    pub eta: Option<V3>,
    pub k: Option<V3>,
    pub specular_reflectance: Option<V3>,
    pub ior: Option<Spanned<f32>>,
    pub reflectance_texture: Option<Spanned<String>>,
    pub roughness_texture: Option<Spanned<String>>,
    pub specular_reflectance_texture: Option<Spanned<String>>,
    // Anisotropic roughness (`anisotropic.rs`): conductor and dielectric.
    pub roughness_u: Option<Spanned<f32>>,
    pub roughness_v: Option<Spanned<f32>>,
    pub roughness_u_texture: Option<Spanned<String>>,
    pub roughness_v_texture: Option<Spanned<String>>,
    // Any type (`surface.rs`): normal and bump maps, opacity, textured emission.
    pub normal_map: Option<Spanned<String>>,
    pub bump_map: Option<Spanned<String>>,
    pub bump_scale: Option<Spanned<f32>>,
    pub opacity: Option<Spanned<f32>>,
    pub opacity_texture: Option<Spanned<String>>,
    pub emission_texture: Option<Spanned<String>>,
    // `principled` only (`principled.rs`); it also takes roughness(_texture) and ior.
    pub base_color: Option<V3>,
    pub base_color_texture: Option<Spanned<String>>,
    pub metallic: Option<Spanned<f32>>,
    pub specular: Option<Spanned<f32>>,
    pub spec_tint: Option<Spanned<f32>>,
    pub anisotropic: Option<Spanned<f32>>,
    pub sheen: Option<Spanned<f32>>,
    pub sheen_tint: Option<Spanned<f32>>,
    pub clearcoat: Option<Spanned<f32>>,
    pub clearcoat_gloss: Option<Spanned<f32>>,
    pub spec_trans: Option<Spanned<f32>>,
    pub flatness: Option<Spanned<f32>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TextureDef {
    pub name: Spanned<String>,
    #[serde(rename = "type")]
    pub kind: Spanned<String>,
    pub file: Option<Spanned<String>>,
    pub raw: Option<Spanned<bool>>,
    pub filter: Option<Spanned<String>>,
    pub wrap: Option<Spanned<String>>,
    pub uv_scale: Option<Spanned<[f32; 2]>>,
    pub uv_offset: Option<Spanned<[f32; 2]>>,
    pub color0: Option<V3>,
    pub color1: Option<V3>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub struct InstanceDef {
    pub shape: Spanned<String>,
    pub material: Option<Spanned<String>>,
    pub transform: Option<Spanned<TransformDef>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ShapeDef {
    #[serde(rename = "type")]
    pub kind: Spanned<String>,
    pub material: Option<Spanned<String>>,
    pub file: Option<Spanned<String>>,
    pub corner: Option<V3>,
    pub u: Option<V3>,
    pub v: Option<V3>,
    pub min: Option<V3>,
    pub max: Option<V3>,
    pub center: Option<V3>,
    pub radius: Option<Spanned<f32>>,
    pub subdivisions: Option<Spanned<i64>>,
    pub flip_normals: Option<bool>,
    pub transform: Option<Spanned<TransformDef>>,
    /// Names the shape for `[[instances]]`.
    pub name: Option<Spanned<String>>,
    /// True: the shape is only placed by instances, not where it is defined.
    pub template: Option<bool>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TransformDef {
    pub translate: Option<[f32; 3]>,
    /// Axis (x, y, z) and angle in degrees.
    pub rotate: Option<[f32; 4]>,
    /// A number (uniform) or `[sx, sy, sz]`.
    pub scale: Option<toml::Value>,
    /// Row-major 4×4; exclusive with the other keys.
    pub matrix: Option<[[f32; 4]; 4]>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LightDef {
    #[serde(rename = "type")]
    pub kind: Spanned<String>,
    pub position: Option<V3>,
    pub look_at: Option<V3>,
    pub direction: Option<V3>,
    pub intensity: Option<V3>,
    pub irradiance: Option<V3>,
    pub cone_deg: Option<Spanned<f32>>,
    pub falloff_deg: Option<Spanned<f32>>,
    /// A spot's beam image (a texture name) and the up direction that orients it.
    pub texture: Option<Spanned<String>>,
    pub up: Option<V3>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub struct EnvironmentDef {
    pub radiance: Option<V3>,
    /// A lat-long image file, relative to the scene file.
    pub map: Option<Spanned<String>>,
    pub scale: Option<Spanned<f32>>,
    pub transform: Option<Spanned<TransformDef>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PortalDef {
    pub corner: Option<V3>,
    pub u: Option<V3>,
    pub v: Option<V3>,
}
