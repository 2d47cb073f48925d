//! glTF metallic-roughness materials as eyeadapt materials.
//!
//! The mapping, chosen so that the common Blender exports (diffuse walls, glossy floors,
//! metals, lamps) render as authored with the BSDFs eyeadapt has:
//! - `metallic < 0.5`: a dielectric — Lambertian `diffuse` when `roughness = 1`, else
//!   `plastic` (GGX coating of IOR 1.5, glTF's fixed dielectric F0 of 0.04, with
//!   α = roughness², glTF's convention) over the base colour;
//! - `metallic ≥ 0.5`: a GGX `conductor` with α = roughness² whose reflectance is the base
//!   colour (the base colour *is* F0 for glTF metals), on a conductor of complex IOR that
//!   reflects everything (Mitsuba's `none` material: η = 0, k = 1);
//! - `emissiveFactor × KHR_materials_emissive_strength` is the emitted radiance, as Blender
//!   writes an Emission strength S (W·sr⁻¹·m⁻², Cycles' radiance unit) into the file.
//!
//! - textures (`textures`): the base colour texture multiplies the base colour factor; the
//!   metallic-roughness texture's G channel times the roughness factor gives a per-texel α; its
//!   B channel (metallic) cannot switch the BSDF per texel, so its mean times the metallic
//!   factor decides between dielectric and metal, with a warning when the texture holds both;
//! - the occlusion texture is ignored on purpose: ambient occlusion is what a path tracer
//!   computes, baking it in again would darken twice.
//!
//! What is not rendered yet is reported as a warning naming the material's JSON pointer: a
//! metallic value strictly between 0 and 1, emissive and normal textures, alpha modes.
use super::read::{GltfFile, at};
use super::textures::{Textures, Use};
use crate::{Bsdf, Diagnostic, Material, Param, Rgb, Scene, Severity};

/// The eyeadapt material of glTF material `m` (its warnings pushed to `warnings`); textures
/// it reads are added to `scene`'s table.
pub fn material(
    file: &GltfFile,
    m: &gltf::Material,
    textures: &mut Textures,
    scene: &mut Scene,
    warnings: &mut Vec<Diagnostic>,
) -> Result<Material, Diagnostic> {
    let here = m.index().map_or_else(
        || "/materials (default)".to_string(),
        |i| format!("/materials/{i}"),
    );
    let warn = |warnings: &mut Vec<Diagnostic>, pointer: String, msg: &str| {
        let mut d = at(&file.path, &pointer, msg);
        d.severity = Severity::Warning;
        warnings.push(d);
    };
    let pbr = m.pbr_metallic_roughness();
    let [r, g, b, _alpha] = pbr.base_color_factor();
    let base = Rgb::new(r, g, b).clamp(Rgb::ZERO, Rgb::ONE);
    let mut metallic = pbr.metallic_factor().clamp(0.0, 1.0);
    let roughness = pbr.roughness_factor().clamp(0.0, 1.0);
    let pointer = format!("{here}/pbrMetallicRoughness");
    let base_param = match pbr.base_color_texture() {
        Some(info) => Param::Texture(textures.get(
            scene,
            &info,
            Use::BaseColor(base.to_array().map(f32::to_bits)),
            &format!("{pointer}/baseColorTexture"),
            warnings,
        )?),
        None => Param::Const(base),
    };
    let mut alpha = Param::Const(roughness * roughness);
    let mut rough_everywhere = roughness >= 1.0;
    if let Some(info) = pbr.metallic_roughness_texture() {
        let at_mr = format!("{pointer}/metallicRoughnessTexture");
        let (g_lo, _) = textures.channel_range(&info, 1)?;
        rough_everywhere = roughness * g_lo >= 1.0;
        alpha = Param::Texture(textures.get(
            scene,
            &info,
            Use::Alpha(roughness.to_bits()),
            &at_mr,
            warnings,
        )?);
        let (b_lo, b_hi) = textures.channel_range(&info, 2)?;
        if metallic * b_lo < 0.5 && metallic * b_hi >= 0.5 {
            warn(
                warnings,
                at_mr.clone(),
                "the texture is metal in places and dielectric in others; its mean metallic \
                 decides for the whole material",
            );
        }
        metallic *= textures.channel_mean(&info, 2)?;
    }
    if metallic > 0.0 && metallic < 1.0 {
        warn(
            warnings,
            format!("{pointer}/metallicFactor"),
            "a metallic value between 0 and 1 is rendered as the nearer of dielectric and metal",
        );
    }
    for (present, field, what) in [
        (
            m.emissive_texture().is_some(),
            "emissiveTexture",
            "emissive textures are not read yet; the emissive factor is used",
        ),
        (
            m.normal_texture().is_some(),
            "normalTexture",
            "normal maps are not read yet; the mesh's normals are used",
        ),
        (
            m.alpha_mode() != gltf::material::AlphaMode::Opaque,
            "alphaMode",
            "alpha modes other than OPAQUE are rendered as OPAQUE",
        ),
    ] {
        if present {
            warn(warnings, format!("{here}/{field}"), what);
        }
    }
    let bsdf = if metallic >= 0.5 {
        Bsdf::Conductor {
            alpha,
            eta: Rgb::ZERO,
            k: Rgb::ONE,
            specular_reflectance: base_param,
        }
    } else if rough_everywhere {
        Bsdf::Diffuse {
            reflectance: base_param,
        }
    } else {
        Bsdf::Plastic {
            reflectance: base_param,
            alpha,
            ior: 1.5,
        }
    };
    let emission = Rgb::from_array(m.emissive_factor()) * m.emissive_strength().unwrap_or(1.0);
    Ok(Material {
        name: m
            .name()
            .map_or_else(|| here.trim_start_matches('/').to_string(), str::to_string),
        bsdf,
        emission: emission.max(Rgb::ZERO),
    })
}
