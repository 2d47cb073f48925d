//! Dielectric BSDF plugins: dielectric, thindielectric, roughdielectric, and the IORs they
//! (and plastics) accept: a number or a name from Mitsuba's table.
use super::Builder;
use crate::mitsuba::xml::{Obj, Value};
use crate::{Bsdf, Param, Rgb};

/// Named IORs accepted by Mitsuba's `int_ior`/`ext_ior` (Mitsuba's `ior.h` table).
const IORS: &[(&str, f64)] = &[
    ("vacuum", 1.0),
    ("helium", 1.000036),
    ("hydrogen", 1.000132),
    ("air", 1.000277),
    ("carbon dioxide", 1.00045),
    ("water", 1.3330),
    ("acetone", 1.36),
    ("ethanol", 1.361),
    ("carbon tetrachloride", 1.461),
    ("glycerol", 1.4729),
    ("benzene", 1.501),
    ("silicone oil", 1.52045),
    ("bromine", 1.661),
    ("water ice", 1.31),
    ("fused quartz", 1.458),
    ("pyrex", 1.470),
    ("acrylic glass", 1.49),
    ("polypropylene", 1.49),
    ("bk7", 1.5046),
    ("sodium chloride", 1.544),
    ("amber", 1.55),
    ("pet", 1.5750),
    ("diamond", 2.419),
];

impl<'t> Builder<'t> {
    pub(super) fn ior(&mut self, o: &'t Obj, name: &str, default: f64) -> f64 {
        let Some(p) = self.prop(o, name) else {
            return default;
        };
        match &p.value {
            Value::Float(x) => *x,
            Value::Integer(i) => *i as f64,
            Value::Str(s) => match IORS.iter().find(|(n, _)| n.eq_ignore_ascii_case(s)) {
                Some((_, v)) => *v,
                None => {
                    self.error(
                        p.at,
                        format!(
                            "{}: unknown IOR name \"{s}\" (known: {})",
                            o.describe(),
                            IORS.iter().map(|i| i.0).collect::<Vec<_>>().join(", ")
                        ),
                    );
                    default
                }
            },
            _ => {
                self.wrong_type(o, p, "a <float> or <string>");
                default
            }
        }
    }

    /// `dielectric`, `thindielectric` or `roughdielectric` (`o.kind`), with Mitsuba's defaults
    /// (`int_ior` "bk7", `ext_ior` "air"; rough: alpha 0.1, Beckmann).
    pub(super) fn dielectric(&mut self, o: &'t Obj) -> Bsdf {
        let int_ior = self.ior(o, "int_ior", 1.5046);
        let ext_ior = self.ior(o, "ext_ior", 1.000277);
        for (name, x) in [("int_ior", int_ior), ("ext_ior", ext_ior)] {
            if !(x.is_finite() && x > 0.0) {
                let at = self.prop(o, name).map_or(o.at, |p| p.at);
                self.error(
                    at,
                    format!("{}: {name} = {x} must be positive", o.describe()),
                );
            }
        }
        let eta = (int_ior / ext_ior) as f32;
        let specular_reflectance = self.unit_colour(o, "specular_reflectance");
        let specular_transmittance = self.unit_colour(o, "specular_transmittance");
        match o.kind.as_str() {
            "thindielectric" => Bsdf::ThinDielectric {
                eta,
                specular_reflectance,
                specular_transmittance,
            },
            "roughdielectric" => {
                let super::rough::Roughness {
                    alpha,
                    alpha_v,
                    distribution,
                } = self.roughness_uv(o, "roughdielectric");
                if int_ior == ext_ior {
                    self.error(
                        o.at,
                        format!("{}: int_ior and ext_ior must differ (a rough interface without refraction has no microfacet normal)", o.describe()),
                    );
                }
                Bsdf::RoughDielectric {
                    alpha,
                    alpha_v,
                    distribution,
                    eta,
                    specular_reflectance,
                    specular_transmittance,
                }
            }
            _ => Bsdf::Dielectric {
                eta,
                specular_reflectance,
                specular_transmittance,
            },
        }
    }

    /// A constant colour factor in [0, 1] (default 1); a texture here is an error.
    fn unit_colour(&mut self, o: &'t Obj, name: &str) -> Rgb {
        let c = match self.colour_param(o, name) {
            Some(Param::Const(c)) => c,
            Some(Param::Texture(_)) => {
                let at = self.prop(o, name).map_or(o.at, |p| p.at);
                self.error(
                    at,
                    format!(
                        "{}: a texture for `{name}` is not supported (use a constant)",
                        o.describe()
                    ),
                );
                Rgb::ONE
            }
            None => Rgb::ONE,
        };
        if c.max_element() > 1.0 || c.min_element() < 0.0 {
            let at = self.prop(o, name).map_or(o.at, |p| p.at);
            self.error(
                at,
                format!(
                    "parameter `{name}` of {} is {c:?}: it must be in [0, 1]",
                    o.describe()
                ),
            );
        }
        c
    }
}
