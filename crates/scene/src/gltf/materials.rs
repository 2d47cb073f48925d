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
//! A metallic value strictly between 0 and 1 and a base colour texture are reported as
//! warnings naming the material's JSON pointer, since those parts are not yet rendered.
use super::read::at;
use crate::{Bsdf, Diagnostic, Distribution, Material, Param, Rgb, Severity};
use std::path::Path;

/// The eyeadapt material of glTF material `m` (its warnings pushed to `warnings`).
pub fn material(file: &Path, m: &gltf::Material, warnings: &mut Vec<Diagnostic>) -> Material {
    let here = m.index().map_or_else(
        || "/materials (default)".to_string(),
        |i| format!("/materials/{i}"),
    );
    let mut warn = |pointer: String, msg: &str| {
        let mut d = at(file, &pointer, msg);
        d.severity = Severity::Warning;
        warnings.push(d);
    };
    let pbr = m.pbr_metallic_roughness();
    let [r, g, b, _alpha] = pbr.base_color_factor();
    let base = Rgb::new(r, g, b).clamp(Rgb::ZERO, Rgb::ONE);
    let metallic = pbr.metallic_factor().clamp(0.0, 1.0);
    let roughness = pbr.roughness_factor().clamp(0.0, 1.0);
    if pbr.base_color_texture().is_some() {
        warn(
            format!("{here}/pbrMetallicRoughness/baseColorTexture"),
            "base colour textures are not read yet; the base colour factor is used",
        );
    }
    if pbr.metallic_roughness_texture().is_some() {
        warn(
            format!("{here}/pbrMetallicRoughness/metallicRoughnessTexture"),
            "metallic-roughness textures are not read yet; the factors are used",
        );
    }
    if metallic > 0.0 && metallic < 1.0 {
        warn(
            format!("{here}/pbrMetallicRoughness/metallicFactor"),
            "a metallic factor between 0 and 1 is rendered as the nearer of dielectric and metal",
        );
    }
    let alpha = roughness * roughness;
    let bsdf = if metallic >= 0.5 {
        Bsdf::Conductor {
            alpha: Param::Const(alpha),
            distribution: Distribution::Ggx,
            eta: Rgb::ZERO,
            k: Rgb::ONE,
            specular_reflectance: Param::Const(base),
        }
    } else if roughness >= 1.0 {
        Bsdf::Diffuse {
            reflectance: Param::Const(base),
        }
    } else {
        Bsdf::Plastic {
            reflectance: Param::Const(base),
            alpha: Param::Const(alpha),
            distribution: Distribution::Ggx,
            ior: 1.5,
        }
    };
    let emission = Rgb::from_array(m.emissive_factor()) * m.emissive_strength().unwrap_or(1.0);
    Material {
        name: m
            .name()
            .map_or_else(|| here.trim_start_matches('/').to_string(), str::to_string),
        bsdf,
        emission: emission.max(Rgb::ZERO),
    }
}
