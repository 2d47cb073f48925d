//! `type = "principled"`: Mitsuba's principled BSDF (`crate::Principled`) in TOML scenes.
//! `base_color` (or `base_color_texture`), `roughness` (or `roughness_texture`), the weights
//! `metallic`, `specular`, `spec_tint`, `anisotropic`, `sheen`, `sheen_tint`, `clearcoat`,
//! `clearcoat_gloss`, `spec_trans`, `flatness` (each in [0, 1]), and `ior` (positive; give
//! either `ior` or `specular`). Defaults are Mitsuba's.
use super::Ctx;
use super::format::MaterialDef;
use crate::{Bsdf, Param, Principled, Rgb};
use toml::Spanned;

/// The keys a principled material takes.
pub(super) const KEYS: &[&str] = &[
    "base_color",
    "base_color_texture",
    "roughness",
    "roughness_texture",
    "metallic",
    "specular",
    "spec_tint",
    "anisotropic",
    "sheen",
    "sheen_tint",
    "clearcoat",
    "clearcoat_gloss",
    "spec_trans",
    "flatness",
    "ior",
];

/// The principled keys given (name, offset), for the check that other types do not take them.
pub(super) fn present(m: &MaterialDef) -> Vec<(&'static str, usize)> {
    let at = |v: &Option<Spanned<f32>>| v.as_ref().map(|v| v.span().start);
    [
        ("base_color", m.base_color.as_ref().map(|v| v.span().start)),
        (
            "base_color_texture",
            m.base_color_texture.as_ref().map(|v| v.span().start),
        ),
        ("metallic", at(&m.metallic)),
        ("specular", at(&m.specular)),
        ("spec_tint", at(&m.spec_tint)),
        ("anisotropic", at(&m.anisotropic)),
        ("sheen", at(&m.sheen)),
        ("sheen_tint", at(&m.sheen_tint)),
        ("clearcoat", at(&m.clearcoat)),
        ("clearcoat_gloss", at(&m.clearcoat_gloss)),
        ("spec_trans", at(&m.spec_trans)),
        ("flatness", at(&m.flatness)),
    ]
    .into_iter()
    .filter_map(|(k, at)| at.map(|a| (k, a)))
    .collect()
}

impl Ctx<'_> {
    /// A weight in [0, 1] (`default` when absent or bad, reported at the value).
    fn weight(&mut self, v: &Option<Spanned<f32>>, key: &str, default: f32) -> f32 {
        let Some(v) = v else { return default };
        let x = *v.get_ref();
        if !(x.is_finite() && (0.0..=1.0).contains(&x)) {
            self.error(v.span().start, format!("{key} {x} must be in [0, 1]"));
            return default;
        }
        x
    }

    pub(super) fn principled(&mut self, m: &MaterialDef, name: &str) -> Bsdf {
        let base_color = self.param(
            name,
            "base_color_texture",
            &m.base_color_texture,
            m.base_color.is_some(),
            |cx| {
                let Some(v) = &m.base_color else {
                    return Rgb::splat(0.5);
                };
                let c = cx.colour(v, "base_color");
                if c.max_element() > 1.0 {
                    cx.error(
                        v.span().start,
                        format!("base_color {c:?} exceeds 1: the surface would create energy"),
                    );
                }
                c
            },
        );
        let mut p = Principled::new(base_color);
        p.roughness = self.param(
            name,
            "roughness_texture",
            &m.roughness_texture,
            m.roughness.is_some(),
            |cx| cx.weight(&m.roughness, "roughness", 0.5),
        );
        let w = |cx: &mut Self, v, key, d| Param::Const(cx.weight(v, key, d));
        p.metallic = w(self, &m.metallic, "metallic", 0.0);
        p.spec_tint = w(self, &m.spec_tint, "spec_tint", 0.0);
        p.anisotropic = w(self, &m.anisotropic, "anisotropic", 0.0);
        p.sheen = w(self, &m.sheen, "sheen", 0.0);
        p.sheen_tint = w(self, &m.sheen_tint, "sheen_tint", 0.0);
        p.clearcoat = w(self, &m.clearcoat, "clearcoat", 0.0);
        p.clearcoat_gloss = w(self, &m.clearcoat_gloss, "clearcoat_gloss", 0.0);
        p.spec_trans = w(self, &m.spec_trans, "spec_trans", 0.0);
        p.flatness = w(self, &m.flatness, "flatness", 0.0);
        let transmits = p.transmits();
        p.eta = match (&m.ior, &m.specular) {
            (Some(_), Some(s)) => {
                self.error(
                    s.span().start,
                    format!("material \"{name}\": give either `ior` or `specular`, not both"),
                );
                1.5
            }
            (Some(v), None) => {
                let x = *v.get_ref();
                if !(x.is_finite() && x > 0.0) {
                    self.error(v.span().start, format!("ior {x} must be positive"));
                    1.5
                } else if transmits && x == 1.0 {
                    // As Mitsuba: microfacet transmission needs refraction.
                    1.001
                } else {
                    x
                }
            }
            (None, s) => {
                let s = self.weight(s, "specular", 0.5);
                let s = if transmits && s == 0.0 { 1e-3 } else { s };
                Principled::eta_of_specular(s as f64) as f32
            }
        };
        Bsdf::Principled(Box::new(p))
    }
}
