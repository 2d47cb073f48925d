//! The keys every material type takes besides its BSDF's: the surface detail that wraps the
//! BSDF (Mitsuba's `normalmap`, `bumpmap` and `mask`) and the emission, a colour or a
//! texture (Mitsuba's `area` emitter with a textured `radiance`).
//!
//! - `normal_map = "name"`: a tangent-space normal map (RGB in [0, 1] is 2·rgb − 1 in the frame
//!   of ∂p/∂u and the shading normal); its bitmap should be `raw = true`.
//! - `bump_map = "name"`, `bump_scale` (default 1, finite): a height field (the texture's
//!   value as a number) times `bump_scale` displaces the surface along its normal.
//! - `opacity` in [0, 1] or `opacity_texture = "name"`: a cut-out, 0 = a hole.
//! - `emission_texture = "name"` instead of `emission`: radiance read from a texture.
//!
//! Built inside out: the bump map perturbs the normal-mapped normal, and the mask decides
//! first whether there is a surface at all: `Mask(NormalMap(BumpMap(bsdf)))`.
use super::format::MaterialDef;
use super::{Ctx, TextureKind};
use crate::{Bsdf, Rgb, TextureId};
use toml::Spanned;

impl Ctx<'_> {
    /// `emission` (a colour, default black) or `emission_texture` (the texture, times 1).
    pub(super) fn emission(&mut self, m: &MaterialDef, name: &str) -> (Rgb, Option<TextureId>) {
        let owner = format!("material \"{name}\"");
        let Some(t) = &m.emission_texture else {
            let e = m.emission.as_ref();
            return (e.map_or(Rgb::ZERO, |e| self.colour(e, "emission")), None);
        };
        if m.emission.is_some() {
            self.error(
                t.span().start,
                format!("{owner}: give `emission` or `emission_texture`, not both"),
            );
        }
        let Some(id) = self.texture_ref(&owner, "emission_texture", t) else {
            return (Rgb::ZERO, None);
        };
        if self.texture_kind(id) == TextureKind::VertexColor {
            // Light sampling reads a texture by UV alone.
            self.error(
                t.span().start,
                format!("{owner}: `emission_texture` \"{}\" is a vertex_color texture, which an emitter cannot use (use a bitmap or checkerboard)", t.get_ref()),
            );
            return (Rgb::ZERO, None);
        }
        (Rgb::ONE, Some(id))
    }

    /// `bsdf` wrapped in the normal map, bump map and mask the material gives.
    pub(super) fn surface(&mut self, m: &MaterialDef, name: &str, bsdf: Bsdf) -> Bsdf {
        let owner = format!("material \"{name}\"");
        let mut bsdf = bsdf;
        if let Some(scale) = &m.bump_scale
            && m.bump_map.is_none()
        {
            self.error(
                scale.span().start,
                format!("{owner}: `bump_scale` needs a `bump_map`"),
            );
        }
        if let Some(t) = &m.bump_map
            && let Some(height) = self.texture_ref(&owner, "bump_map", t)
        {
            let scale = self.bump_scale(&m.bump_scale);
            bsdf = Bsdf::BumpMap {
                height,
                scale,
                bsdf: Box::new(bsdf),
            };
        }
        if let Some(t) = &m.normal_map
            && let Some(normals) = self.texture_ref(&owner, "normal_map", t)
        {
            if self.texture_kind(normals) == TextureKind::SrgbBitmap {
                self.warning(
                    t.span().start,
                    format!("{owner}: `normal_map` \"{}\" is sRGB-decoded; normal maps store plain values (give the texture `raw = true`)", t.get_ref()),
                );
            }
            bsdf = Bsdf::NormalMap {
                normals,
                bsdf: Box::new(bsdf),
            };
        }
        if m.opacity.is_some() || m.opacity_texture.is_some() {
            let opacity = self.param(
                name,
                "opacity_texture",
                &m.opacity_texture,
                m.opacity.is_some(),
                |cx| cx.opacity(&m.opacity),
            );
            bsdf = Bsdf::Mask {
                opacity,
                bsdf: Box::new(bsdf),
            };
        }
        bsdf
    }

    /// `bump_scale`: finite (negative inverts the relief), default 1.
    fn bump_scale(&mut self, v: &Option<Spanned<f32>>) -> f32 {
        let Some(v) = v else { return 1.0 };
        let x = *v.get_ref();
        if !x.is_finite() {
            self.error(v.span().start, format!("bump_scale {x} must be finite"));
            return 1.0;
        }
        x
    }

    /// `opacity` in [0, 1] (1 when absent or bad).
    fn opacity(&mut self, v: &Option<Spanned<f32>>) -> f32 {
        let Some(v) = v else { return 1.0 };
        let x = *v.get_ref();
        if !(x.is_finite() && (0.0..=1.0).contains(&x)) {
            self.error(v.span().start, format!("opacity {x} must be in [0, 1]"));
            return 1.0;
        }
        x
    }
}
