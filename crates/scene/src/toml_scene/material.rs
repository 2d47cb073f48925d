//! `[[materials]]`: BSDF type, its parameters and the emission.
use super::Ctx;
use super::format::MaterialDef;
use crate::{Bsdf, Material, Param, Rgb};

impl Ctx<'_> {
    pub(super) fn material(&mut self, m: &MaterialDef) -> Material {
        let name = m.name.get_ref().clone();
        let kind = m.kind.get_ref().as_str();
        let emission = m
            .emission
            .as_ref()
            .map_or(Rgb::ZERO, |e| self.colour(e, "emission"));
        let allowed: &[&str] = match kind {
            "diffuse" => &["reflectance"],
            "conductor" => &["roughness", "eta", "k", "specular_reflectance"],
            "plastic" => &["reflectance", "roughness", "ior"],
            other => {
                self.error(
                    m.kind.span().start,
                    format!(
                        "unknown material type \"{other}\" (expected diffuse, conductor or plastic)"
                    ),
                );
                return Material::error();
            }
        };
        let present: [(&str, Option<usize>); 6] = [
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
        let reflectance = |cx: &mut Self| -> Rgb {
            match &m.reflectance {
                Some(r) => {
                    let c = cx.colour(r, "reflectance");
                    if c.max_element() > 1.0 {
                        cx.error(
                            r.span().start,
                            format!("reflectance {c:?} exceeds 1: the surface would create energy"),
                        );
                    }
                    c
                }
                None => Rgb::splat(0.5),
            }
        };
        let roughness = |cx: &mut Self| -> f32 {
            match &m.roughness {
                Some(r) => {
                    let a = *r.get_ref();
                    if !(a.is_finite() && (0.0..=1.0).contains(&a)) {
                        cx.error(r.span().start, format!("roughness {a} must be in [0, 1]"));
                        return 0.1;
                    }
                    a
                }
                None => 0.1,
            }
        };
        let bsdf = match kind {
            "diffuse" => Bsdf::Diffuse {
                reflectance: Param::Const(reflectance(self)),
            },
            "conductor" => {
                let alpha = roughness(self);
                // Default: gold, Mitsuba's `Au` at the Rec.709 primaries.
                let eta = m
                    .eta
                    .as_ref()
                    .map_or(Rgb::new(0.143, 0.374, 1.442), |v| self.colour(v, "eta"));
                let k =
                    m.k.as_ref()
                        .map_or(Rgb::new(3.983, 2.386, 1.603), |v| self.colour(v, "k"));
                let specular_reflectance = m
                    .specular_reflectance
                    .as_ref()
                    .map_or(Rgb::ONE, |v| self.colour(v, "specular_reflectance"));
                Bsdf::Conductor {
                    alpha: Param::Const(alpha),
                    eta,
                    k,
                    specular_reflectance: Param::Const(specular_reflectance),
                }
            }
            _ => {
                let ior = m.ior.as_ref().map_or(1.5, |v| {
                    let x = *v.get_ref();
                    if !(x.is_finite() && x > 1.0 && x < 4.0) {
                        self.error(v.span().start, format!("ior {x} must be in (1, 4)"));
                        return 1.5;
                    }
                    x
                });
                Bsdf::Plastic {
                    reflectance: Param::Const(reflectance(self)),
                    alpha: Param::Const(roughness(self).max(0.01)),
                    ior,
                }
            }
        };
        Material {
            name,
            bsdf,
            emission,
        }
    }
}
