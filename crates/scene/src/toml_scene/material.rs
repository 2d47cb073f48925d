//! `[[materials]]`: BSDF type, its parameters and the emission.
use super::Ctx;
use super::format::MaterialDef;
use crate::{Bsdf, Distribution, Material, Param, Rgb};

/// The keys each material type takes.
fn allowed_keys(kind: &str) -> Option<&'static [&'static str]> {
    Some(match kind {
        "diffuse" => &["reflectance", "reflectance_texture"],
        "conductor" => &[
            "roughness",
            "roughness_texture",
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
        "dielectric" => &["roughness", "roughness_texture", "ior"],
        "thin_dielectric" => &["ior"],
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

/// `roughness` (default 0.1), in [0, 1].
fn roughness(cx: &mut Ctx<'_>, m: &MaterialDef) -> f32 {
    let Some(r) = &m.roughness else {
        return 0.1;
    };
    let a = *r.get_ref();
    if !(a.is_finite() && (0.0..=1.0).contains(&a)) {
        cx.error(r.span().start, format!("roughness {a} must be in [0, 1]"));
        return 0.1;
    }
    a
}

impl Ctx<'_> {
    pub(super) fn material(&mut self, m: &MaterialDef) -> Material {
        let name = m.name.get_ref().clone();
        let kind = m.kind.get_ref().as_str();
        let emission = m
            .emission
            .as_ref()
            .map_or(Rgb::ZERO, |e| self.colour(e, "emission"));
        let Some(allowed) = allowed_keys(kind) else {
            self.error(
                m.kind.span().start,
                format!(
                    "unknown material type \"{kind}\" (expected diffuse, conductor, plastic, dielectric or thin_dielectric)"
                ),
            );
            return Material::error();
        };
        self.check_keys(m, &name, kind, allowed);
        let bsdf = match kind {
            "diffuse" => Bsdf::Diffuse {
                reflectance: self.param(
                    &name,
                    &m.reflectance_texture,
                    m.reflectance.is_some(),
                    |cx| reflectance(cx, m),
                ),
            },
            "conductor" => self.conductor(m, &name),
            "dielectric" | "thin_dielectric" => self.glass(m, kind, &name, |cx| roughness(cx, m)),
            _ => self.plastic(m, &name),
        };
        Material {
            name,
            bsdf,
            emission,
        }
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

    /// A conductor: GGX `roughness`, complex IOR `eta` + i`k` (default gold) and a
    /// `specular_reflectance` tint.
    fn conductor(&mut self, m: &MaterialDef, name: &str) -> Bsdf {
        let alpha = self.param(name, &m.roughness_texture, m.roughness.is_some(), |cx| {
            roughness(cx, m)
        });
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
            alpha_v: None,
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
            &m.reflectance_texture,
            m.reflectance.is_some(),
            |cx| reflectance(cx, m),
        );
        let alpha = self.param(name, &m.roughness_texture, m.roughness.is_some(), |cx| {
            roughness(cx, m).max(0.01)
        });
        Bsdf::Plastic {
            reflectance,
            alpha,
            distribution: Distribution::Ggx,
            ior,
        }
    }

    /// Glass: `ior` (interior over exterior, default 1.5, positive), and for `dielectric` a
    /// `roughness` (GGX alpha; 0 or absent: smooth) or `roughness_texture`.
    fn glass(
        &mut self,
        m: &MaterialDef,
        kind: &str,
        name: &str,
        roughness: impl FnOnce(&mut Self) -> f32,
    ) -> Bsdf {
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
        let alpha = self.param(name, &m.roughness_texture, m.roughness.is_some(), roughness);
        if alpha == Param::Const(0.0) || (m.roughness.is_none() && m.roughness_texture.is_none()) {
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
            alpha_v: None,
            distribution: Distribution::Ggx,
            eta,
            specular_reflectance: r,
            specular_transmittance: t,
        }
    }

    /// A parameter given either as a constant (`constant` reads it) or by `texture` name; both
    /// at once, or an unknown texture, is an error.
    fn param<T>(
        &mut self,
        material: &str,
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
                format!("material \"{material}\": give a constant or a texture, not both"),
            );
        }
        match self.textures.get(t.get_ref()) {
            Some(Some(id)) => Param::Texture(*id),
            Some(None) => Param::Const(constant(self)),
            None => {
                self.error(
                    t.span().start,
                    format!(
                        "material \"{material}\": unknown texture \"{}\" (textures are defined in [[textures]])",
                        t.get_ref()
                    ),
                );
                Param::Const(constant(self))
            }
        }
    }
}
