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
//! - `KHR_materials_transmission` (factor ≥ ½) makes glass of `KHR_materials_ior` (default
//!   1.5) tinted by the base colour: without `KHR_materials_volume` glTF's glass is
//!   thin-walled, so a smooth one is a `thindielectric` (a pane: light leaves undeflected), and
//!   with a volume a refracting `dielectric`; a rough one (roughness > 0) is a
//!   `roughdielectric` with α = roughness²;
//! - alpha: `MASK` cuts the surface out where base colour alpha (texture × factor) is below
//!   `alphaCutoff`, `BLEND` lets light through in proportion to 1 − alpha (a `mask`);
//! - `normalTexture` (with its `scale`) bends the shading normal in glTF's tangent space, a
//!   `normalmap` around the BSDF (tangents from the UVs; a `KHR_texture_transform` on a
//!   normal texture is not read: the `gltf` crate does not give it).
//!
//! What is not rendered yet is reported as a warning naming the material's JSON pointer: a
//! metallic or transmission value strictly between 0 and 1, emissive textures, a
//! transmission texture (its factor is used), rough thin-walled glass (rendered as a rough
//! interface).
use super::read::{GltfFile, at};
use super::textures::{TexRef, Textures, Use};
use crate::{Bsdf, Diagnostic, Distribution, Material, Param, Rgb, Scene, Severity};

/// What every part of one material's reading shares.
struct Ctx<'a, 'f> {
    file: &'f GltfFile,
    textures: &'a mut Textures<'f>,
    scene: &'a mut Scene,
    warnings: &'a mut Vec<Diagnostic>,
    /// The material's JSON pointer.
    here: String,
}

impl Ctx<'_, '_> {
    fn warn(&mut self, field: &str, msg: &str) {
        let mut d = at(&self.file.path, &format!("{}/{field}", self.here), msg);
        d.severity = Severity::Warning;
        self.warnings.push(d);
    }

    fn texture<T>(
        &mut self,
        info: &gltf::texture::Info,
        usage: Use,
        field: &str,
    ) -> Result<Param<T>, Diagnostic> {
        let pointer = format!("{}/{field}", self.here);
        let id = self
            .textures
            .get(self.scene, info, usage, &pointer, self.warnings)?;
        Ok(Param::Texture(id))
    }
}

/// The eyeadapt material of glTF material `m` (its warnings pushed to `warnings`); textures
/// it reads are added to `scene`'s table.
pub fn material<'f>(
    file: &'f GltfFile,
    m: &gltf::Material,
    textures: &mut Textures<'f>,
    scene: &mut Scene,
    warnings: &mut Vec<Diagnostic>,
) -> Result<Material, Diagnostic> {
    let here = m.index().map_or_else(
        || "/materials (default)".to_string(),
        |i| format!("/materials/{i}"),
    );
    let mut cx = Ctx {
        file,
        textures,
        scene,
        warnings,
        here: here.clone(),
    };
    for (present, field, what) in [(
        m.emissive_texture().is_some(),
        "emissiveTexture",
        "emissive textures are not read yet; the emissive factor is used",
    )] {
        if present {
            cx.warn(field, what);
        }
    }
    let surface = surface(&mut cx, m)?;
    let surface = with_normal_map(&mut cx, m, surface)?;
    let bsdf = with_alpha(&mut cx, m, surface)?;
    let emission = Rgb::from_array(m.emissive_factor()) * m.emissive_strength().unwrap_or(1.0);
    Ok(Material {
        name: m
            .name()
            .map_or_else(|| here.trim_start_matches('/').to_string(), str::to_string),
        bsdf,
        emission: emission.max(Rgb::ZERO),
    })
}

/// `bsdf` shaded with the material's normal texture, if it has one: glTF's tangent space is
/// (∂p/∂u, n × ∂p/∂u, n) for UVs that are not mirrored, the frame [`Bsdf::NormalMap`] uses
/// (tangents are derived per triangle from the UVs, not read from a `TANGENT` attribute).
fn with_normal_map(cx: &mut Ctx, m: &gltf::Material, bsdf: Bsdf) -> Result<Bsdf, Diagnostic> {
    let Some(nt) = m.normal_texture() else {
        return Ok(bsdf);
    };
    let pointer = format!("{}/normalTexture", cx.here);
    let reference = TexRef {
        texture: nt.texture(),
        tex_coord: nt.tex_coord(),
        transform: None,
    };
    let usage = Use::Normal(nt.scale().to_bits());
    let normals = cx
        .textures
        .get(cx.scene, reference, usage, &pointer, cx.warnings)?;
    Ok(Bsdf::NormalMap {
        normals,
        bsdf: Box::new(bsdf),
    })
}

/// The opaque (or glass) BSDF of the metallic-roughness parameters.
fn surface(cx: &mut Ctx, m: &gltf::Material) -> Result<Bsdf, Diagnostic> {
    let pbr = m.pbr_metallic_roughness();
    let [r, g, b, _alpha] = pbr.base_color_factor();
    let base = Rgb::new(r, g, b).clamp(Rgb::ZERO, Rgb::ONE);
    let mut metallic = pbr.metallic_factor().clamp(0.0, 1.0);
    let roughness = pbr.roughness_factor().clamp(0.0, 1.0);
    let base_param = match pbr.base_color_texture() {
        Some(info) => {
            let usage = Use::BaseColor(base.to_array().map(f32::to_bits));
            let pointer = format!("{}/pbrMetallicRoughness/baseColorTexture", cx.here);
            Param::Texture(
                cx.textures
                    .get(cx.scene, &info, usage, &pointer, cx.warnings)?,
            )
        }
        None => Param::Const(base),
    };
    let mut alpha = Param::Const(roughness * roughness);
    let mut rough_everywhere = roughness >= 1.0;
    let mut smooth_everywhere = roughness <= 0.0;
    if let Some(info) = pbr.metallic_roughness_texture() {
        let field = "pbrMetallicRoughness/metallicRoughnessTexture";
        let (g_lo, g_hi) = cx.textures.channel_range(&info, 1)?;
        rough_everywhere = roughness * g_lo >= 1.0;
        smooth_everywhere = roughness * g_hi <= 0.0;
        alpha = cx.texture(&info, Use::Alpha(roughness.to_bits()), field)?;
        let (b_lo, b_hi) = cx.textures.channel_range(&info, 2)?;
        if metallic * b_lo < 0.5 && metallic * b_hi >= 0.5 {
            cx.warn(
                field,
                "the texture is metal in places and dielectric in others; its mean metallic \
                 decides for the whole material",
            );
        }
        metallic *= cx.textures.channel_mean(&info, 2)?;
    }
    if metallic > 0.0 && metallic < 1.0 {
        cx.warn(
            "pbrMetallicRoughness/metallicFactor",
            "a metallic value between 0 and 1 is rendered as the nearer of dielectric and metal",
        );
    }
    if metallic >= 0.5 {
        return Ok(Bsdf::Conductor {
            alpha,
            alpha_v: None,
            distribution: Distribution::Ggx,
            eta: Rgb::ZERO,
            k: Rgb::ONE,
            specular_reflectance: base_param,
        });
    }
    if let Some(glass) = glass(cx, m, base, alpha, smooth_everywhere) {
        return Ok(glass);
    }
    Ok(if rough_everywhere {
        Bsdf::Diffuse {
            reflectance: base_param,
        }
    } else {
        Bsdf::Plastic {
            reflectance: base_param,
            alpha,
            distribution: Distribution::Ggx,
            ior: 1.5,
        }
    })
}

/// The glass of `KHR_materials_transmission`, when the material transmits (factor ≥ ½).
fn glass(
    cx: &mut Ctx,
    m: &gltf::Material,
    tint: Rgb,
    alpha: Param<f32>,
    smooth: bool,
) -> Option<Bsdf> {
    let t = m.transmission()?;
    let factor = t.transmission_factor().clamp(0.0, 1.0);
    if t.transmission_texture().is_some() {
        cx.warn(
            "extensions/KHR_materials_transmission/transmissionTexture",
            "transmission textures are not read yet; the transmission factor is used",
        );
    }
    if factor > 0.0 && factor < 1.0 {
        cx.warn(
            "extensions/KHR_materials_transmission/transmissionFactor",
            "a transmission value between 0 and 1 is rendered as the nearer of opaque and glass",
        );
    }
    if factor < 0.5 {
        return None;
    }
    // glTF: ior ≥ 1 (0 is allowed and means no Fresnel term at all; eyeadapt takes 1.5 there).
    let ior = m
        .ior()
        .filter(|i| i.is_finite() && *i >= 1.0)
        .unwrap_or(1.5);
    let thin = m.volume().is_none_or(|v| v.thickness_factor() <= 0.0);
    Some(match (smooth, thin) {
        (true, true) => Bsdf::ThinDielectric {
            eta: ior,
            specular_reflectance: Rgb::ONE,
            specular_transmittance: tint,
        },
        (true, false) => Bsdf::Dielectric {
            eta: ior,
            specular_reflectance: Rgb::ONE,
            specular_transmittance: tint,
        },
        (false, _) => {
            if thin {
                cx.warn(
                    "extensions/KHR_materials_transmission",
                    "rough thin-walled glass is rendered as a rough refracting interface",
                );
            }
            Bsdf::RoughDielectric {
                alpha,
                alpha_v: None,
                distribution: Distribution::Ggx,
                eta: ior,
                specular_reflectance: Rgb::ONE,
                specular_transmittance: tint,
            }
        }
    })
}

/// `surface` cut out by glTF's alpha: MASK at `alphaCutoff`, BLEND in proportion.
fn with_alpha(cx: &mut Ctx, m: &gltf::Material, surface: Bsdf) -> Result<Bsdf, Diagnostic> {
    use gltf::material::AlphaMode;
    let pbr = m.pbr_metallic_roughness();
    let a = pbr.base_color_factor()[3].clamp(0.0, 1.0);
    let cutoff = match m.alpha_mode() {
        AlphaMode::Opaque => return Ok(surface),
        AlphaMode::Mask => Some(m.alpha_cutoff().unwrap_or(0.5)),
        AlphaMode::Blend => None,
    };
    let opacity = match pbr.base_color_texture() {
        Some(info) => {
            let usage = Use::Opacity {
                factor: a.to_bits(),
                cutoff: cutoff.map(f32::to_bits),
            };
            cx.texture(&info, usage, "pbrMetallicRoughness/baseColorTexture")?
        }
        None => Param::Const(match cutoff {
            Some(c) => f32::from(u8::from(a >= c)),
            None => a,
        }),
    };
    Ok(match opacity {
        Param::Const(o) if o >= 1.0 => surface,
        _ => Bsdf::Mask {
            opacity,
            bsdf: Box::new(surface),
        },
    })
}
