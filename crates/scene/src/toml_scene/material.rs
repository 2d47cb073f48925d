//! `[[materials]]`: BSDF type, its parameters and the emission.
use super::Ctx;
use super::anisotropic::Alphas;
use super::format::MaterialDef;
use crate::{Bsdf, Distribution, Material, Param, Rgb, TextureId};

/// The keys each material type takes.
fn allowed_keys(kind: &str) -> Option<&'static [&'static str]> {
    Some(match kind {
        "diffuse" => &["reflectance", "reflectance_texture"],
        "conductor" => &[
            "roughness",
            "roughness_texture",
            "roughness_u",
            "roughness_v",
            "roughness_u_texture",
            "roughness_v_texture",
            "eta",
            "k",
            "specular_reflectance",
            "specular_reflectance_texture",
        ],
        "plastic" => &[
            "reflectance",
            "reflectance_texture",
            "roughness",
            "roughness_texture",
            "ior",
        ],
        "dielectric" => &[
            "roughness",
            "roughness_texture",
            "roughness_u",
            "roughness_v",
            "roughness_u_texture",
            "roughness_v_texture",
            "ior",
        ],
        "thin_dielectric" => &["ior"],
        "principled" => super::principled::KEYS,
        _ => return None,
    })
}

/// `reflectance` (default 0.5 grey), which may not exceed 1.
fn reflectance(cx: &mut Ctx<'_>, m: &MaterialDef) -> Rgb {
    let Some(r) = &m.reflectance else {
        return Rgb::splat(0.5);
    };
    let c = cx.colour(r, "reflectance");
    if c.max_element() > 1.0 {
        cx.error(
            r.span().start,
            format!("reflectance {c:?} exceeds 1: the surface would create energy"),
        );
    }
    c
}

impl Ctx<'_> {
    /// The material, and the texture that multiplies its emission (if any).
    pub(super) fn material(&mut self, m: &MaterialDef) -> (Material, Option<TextureId>) {
        let name = m.name.get_ref().clone();
        let kind = m.kind.get_ref().as_str();
        let (emission, emission_texture) = self.emission(m, &name);
        let Some(allowed) = allowed_keys(kind) else {
            self.error(
                m.kind.span().start,
                format!(
                    "unknown material type \"{kind}\" (expected diffuse, conductor, plastic, dielectric, thin_dielectric or principled)"
                ),
            );
            return (Material::error(), None);
        };
        self.check_keys(m, &name, kind, allowed);
        let bsdf = match kind {
            "diffuse" => Bsdf::Diffuse {
                reflectance: self.param(
                    &name,
                    "reflectance_texture",
                    &m.reflectance_texture,
                    m.reflectance.is_some(),
                    |cx| reflectance(cx, m),
                ),
            },
            "conductor" => self.conductor(m, &name),
            "dielectric" | "thin_dielectric" => self.glass(m, kind, &name),
            "principled" => self.principled(m, &name),
            _ => self.plastic(m, &name),
        };
        let bsdf = self.surface(m, &name, bsdf);
        let material = Material {
            name,
            bsdf,
            emission,
        };
        (material, emission_texture)
    }

    /// Every key given that `kind` does not take is an error at the key.
    fn check_keys(&mut self, m: &MaterialDef, name: &str, kind: &str, allowed: &[&str]) {
        let at = |t: &Option<toml::Spanned<String>>| t.as_ref().map(|v| v.span().start);
        let present: [(&str, Option<usize>); 9] = [
            ("reflectance_texture", at(&m.reflectance_texture)),
            ("roughness_texture", at(&m.roughness_texture)),
            (
                "specular_reflectance_texture",
                at(&m.specular_reflectance_texture),
            ),
            (
                "reflectance",
                m.reflectance.as_ref().map(|v| v.span().start),
            ),
            ("roughness", m.roughness.as_ref().map(|v| v.span().start)),
            ("eta", m.eta.as_ref().map(|v| v.span().start)),
            ("k", m.k.as_ref().map(|v| v.span().start)),
            (
                "specular_reflectance",
                m.specular_reflectance.as_ref().map(|v| v.span().start),
            ),
            ("ior", m.ior.as_ref().map(|v| v.span().start)),
        ];
        let typed = super::principled::present(m)
            .into_iter()
            .chain(super::anisotropic::present(m));
        let present = present.into_iter().chain(typed.map(|(k, a)| (k, Some(a))));
        for (key, at) in present {
            if let Some(at) = at
                && !allowed.contains(&key)
            {
                self.error(
                    at,
                    format!("material \"{name}\": key `{key}` does not apply to type \"{kind}\""),
                );
            }
        }
    }

    /// A conductor: GGX `roughness` (or `roughness_u`/`roughness_v`), complex IOR `eta` + i`k` (default gold) and a
    /// `specular_reflectance` tint.
    fn conductor(&mut self, m: &MaterialDef, name: &str) -> Bsdf {
        let Alphas { alpha, alpha_v, .. } = self.alphas(m, name, 0.1);
        // Default: gold, Mitsuba's `Au` at the Rec.709 primaries.
        let eta = m
            .eta
            .as_ref()
            .map_or(Rgb::new(0.143, 0.374, 1.442), |v| self.colour(v, "eta"));
        let k =
            m.k.as_ref()
                .map_or(Rgb::new(3.983, 2.386, 1.603), |v| self.colour(v, "k"));
        let specular_reflectance = self.param(
            name,
            "specular_reflectance_texture",
            &m.specular_reflectance_texture,
            m.specular_reflectance.is_some(),
            |cx| {
                m.specular_reflectance
                    .as_ref()
                    .map_or(Rgb::ONE, |v| cx.colour(v, "specular_reflectance"))
            },
        );
        Bsdf::Conductor {
            alpha,
            alpha_v,
            distribution: Distribution::Ggx,
            eta,
            k,
            specular_reflectance,
        }
    }

    /// A plastic: diffuse `reflectance` under a GGX-rough dielectric coat of `ior` in (1, 4).
    fn plastic(&mut self, m: &MaterialDef, name: &str) -> Bsdf {
        let ior = m.ior.as_ref().map_or(1.5, |v| {
            let x = *v.get_ref();
            if !(x.is_finite() && x > 1.0 && x < 4.0) {
                self.error(v.span().start, format!("ior {x} must be in (1, 4)"));
                return 1.5;
            }
            x
        });
        let reflectance = self.param(
            name,
            "reflectance_texture",
            &m.reflectance_texture,
            m.reflectance.is_some(),
            |cx| reflectance(cx, m),
        );
        let alpha = self.param(
            name,
            "roughness_texture",
            &m.roughness_texture,
            m.roughness.is_some(),
            |cx| cx.alpha_value(&m.roughness, "roughness", 0.1).max(0.01),
        );
        Bsdf::Plastic {
            reflectance,
            alpha,
            distribution: Distribution::Ggx,
            ior,
        }
    }

    /// Glass: `ior` (interior over exterior, default 1.5, positive), and for `dielectric` a
    /// `roughness` (GGX alpha; 0 or absent: smooth) or `roughness_texture`, or
    /// `roughness_u`/`roughness_v`.
    fn glass(&mut self, m: &MaterialDef, kind: &str, name: &str) -> Bsdf {
        let eta = m.ior.as_ref().map_or(1.5, |v| {
            let x = *v.get_ref();
            if !(x.is_finite() && x > 0.0) {
                self.error(v.span().start, format!("ior {x} must be positive"));
                return 1.5;
            }
            x
        });
        let (r, t) = (Rgb::ONE, Rgb::ONE);
        if kind == "thin_dielectric" {
            return Bsdf::ThinDielectric {
                eta,
                specular_reflectance: r,
                specular_transmittance: t,
            };
        }
        let Alphas {
            alpha,
            alpha_v,
            given,
        } = self.alphas(m, name, 0.1);
        if !given || (alpha == Param::Const(0.0) && alpha_v.is_none()) {
            return Bsdf::Dielectric {
                eta,
                specular_reflectance: r,
                specular_transmittance: t,
            };
        }
        if eta == 1.0 {
            let at = m
                .ior
                .as_ref()
                .map_or(m.kind.span().start, |v| v.span().start);
            self.error(at, "a rough dielectric needs an ior other than 1");
        }
        Bsdf::RoughDielectric {
            alpha,
            alpha_v,
            distribution: Distribution::Ggx,
            eta,
            specular_reflectance: r,
            specular_transmittance: t,
        }
    }

    /// A parameter given either as a constant (`constant` reads it) or by texture name
    /// (`texture`, the key `key`, e.g. `reflectance_texture`); both at once, or an unknown
    /// texture, is an error.
    pub(super) fn param<T>(
        &mut self,
        material: &str,
        key: &str,
        texture: &Option<toml::Spanned<String>>,
        constant_given: bool,
        constant: impl FnOnce(&mut Self) -> T,
    ) -> Param<T> {
        let Some(t) = texture else {
            return Param::Const(constant(self));
        };
        if constant_given {
            self.error(
                t.span().start,
                format!(
                    "material \"{material}\": give `{}` or `{key}`, not both",
                    key.trim_end_matches("_texture")
                ),
            );
        }
        match self.texture_ref(&format!("material \"{material}\""), key, t) {
            Some(id) => Param::Texture(id),
            None => Param::Const(constant(self)),
        }
    }
}
