//! BSDF plugins: diffuse, conductor, roughconductor, plastic, roughplastic, twosided.
use super::Builder;
use crate::mitsuba::presets::CONDUCTOR_PRESETS;
use crate::mitsuba::xml::{ChildKind, Obj, Value};
use crate::{Bsdf, Param, Rgb};

const BSDFS: &str = "diffuse, conductor, roughconductor, plastic, roughplastic and twosided";
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

/// A BSDF as built from XML, before it becomes a material.
#[derive(Clone, Debug)]
pub(crate) struct BuiltBsdf {
    pub bsdf: Bsdf,
    /// The id, or a description of the inline element.
    pub name: String,
}

impl<'t> Builder<'t> {
    pub(super) fn bsdf_by_id(&mut self, id: &str, at: usize) -> Option<BuiltBsdf> {
        if let Some(i) = self.building.iter().position(|b| b == id) {
            let chain = self.building[i..].join(" -> ");
            self.error(
                at,
                format!("<ref id=\"{id}\">: circular reference {chain} -> {id}"),
            );
            return None;
        }
        if let Some(b) = self.bsdfs.get(id) {
            return b.clone();
        }
        let o = self.resolve(id, at)?;
        if o.tag != "bsdf" {
            if o.tag != "texture" {
                self.error(
                    at,
                    format!("<ref id=\"{id}\"> names a <{}>, expected a <bsdf>", o.tag),
                );
            }
            return None;
        }
        let b = self.bsdf(o);
        self.bsdfs.insert(id.to_string(), b.clone());
        b
    }

    /// Builds `o`; while it is being built its id (if any) is on [`Builder::building`].
    pub(super) fn bsdf(&mut self, o: &'t Obj) -> Option<BuiltBsdf> {
        if let Some(id) = &o.id {
            self.building.push(id.clone());
        }
        let b = self.bsdf_plugin(o);
        if o.id.is_some() {
            self.building.pop();
        }
        b
    }

    fn bsdf_plugin(&mut self, o: &'t Obj) -> Option<BuiltBsdf> {
        let name =
            o.id.clone()
                .unwrap_or_else(|| format!("{} at line {}", o.describe(), self.sources.line(o.at)));
        let bsdf = match o.kind.as_str() {
            "twosided" => return self.twosided(o),
            "diffuse" => {
                let reflectance = self.reflectance(o, "reflectance");
                Bsdf::Diffuse { reflectance }
            }
            "conductor" | "roughconductor" => self.conductor(o),
            "plastic" | "roughplastic" => self.plastic(o),
            _ => {
                self.unsupported(o, BSDFS);
                return None;
            }
        };
        self.finish(o);
        Some(BuiltBsdf { bsdf, name })
    }

    /// A reflectance in [0, 1] (default 0.5), or a texture.
    pub(super) fn reflectance(&mut self, o: &'t Obj, name: &str) -> Param<Rgb> {
        let c = match self.colour_param(o, name) {
            Some(Param::Texture(t)) => return Param::Texture(t),
            Some(Param::Const(c)) => c,
            None => Rgb::splat(0.5),
        };
        if c.max_element() > 1.0 {
            let at = self.prop(o, name).map_or(o.at, |p| p.at);
            self.error(
                at,
                format!(
                    "parameter `{name}` of {} is {c:?}: a reflectance above 1 creates energy",
                    o.describe()
                ),
            );
        }
        Param::Const(c)
    }

    /// eyeadapt is always two-sided, so `twosided` just unwraps its one BSDF.
    pub(super) fn twosided(&mut self, o: &'t Obj) -> Option<BuiltBsdf> {
        let inner: Vec<_> = o
            .children
            .iter()
            .filter(|c| match &c.kind {
                ChildKind::Obj(b) => b.tag == "bsdf",
                ChildKind::Ref(_) => true,
            })
            .collect();
        for c in &inner {
            c.used.set(true);
        }
        let result = match inner.as_slice() {
            [c] => match &c.kind {
                ChildKind::Obj(b) => self.bsdf(b),
                ChildKind::Ref(id) => self.bsdf_by_id(id, c.at),
            },
            [] => {
                self.error(o.at, format!("{} needs one nested <bsdf>", o.describe()));
                None
            }
            _ => {
                self.error(
                    o.at,
                    format!("unsupported {} with different front and back BSDFs: eyeadapt surfaces scatter the same on both sides", o.describe()),
                );
                None
            }
        };
        self.finish(o);
        result.map(|b| BuiltBsdf {
            name: o.id.clone().unwrap_or(b.name),
            bsdf: b.bsdf,
        })
    }

    /// The roughness of a `rough` plugin (a constant or a texture), 0 for the smooth one.
    fn alpha(&mut self, o: &'t Obj, rough: &str) -> Param<f32> {
        if o.kind != rough {
            return Param::Const(0.0);
        }
        match self.float_texture(o, "alpha") {
            Some(Some(t)) => {
                // Still reads `distribution` and `sample_visible`.
                self.roughness(o, 0.1);
                Param::Texture(t)
            }
            Some(None) => Param::Const(0.1),
            None => Param::Const(self.roughness(o, 0.1)),
        }
    }

    /// `alpha` (or equal `alpha_u`/`alpha_v`) and `distribution` of rough plugins.
    pub(super) fn roughness(&mut self, o: &'t Obj, default: f64) -> f32 {
        // Mitsuba's roughplastic is isotropic: there `alpha_u` is an unknown parameter.
        let anisotropic = o.kind == "roughconductor" && self.prop(o, "alpha_u").is_some();
        let alpha = match (self.prop(o, "alpha").is_some(), anisotropic) {
            (true, _) => self.float_in(o, "alpha", 0.0..=1.0).unwrap_or(default),
            (false, true) => {
                let u = self.float_in(o, "alpha_u", 0.0..=1.0).unwrap_or(default);
                let v = self.float_in(o, "alpha_v", 0.0..=1.0).unwrap_or(u);
                if (u - v).abs() > 1e-6 {
                    self.warning(
                        o.at,
                        format!("{}: anisotropic roughness (alpha_u {u}, alpha_v {v}) approximated by the isotropic alpha {}", o.describe(), (u * v).sqrt()),
                    );
                }
                (u * v).sqrt()
            }
            (false, false) => default,
        };
        match self.string(o, "distribution") {
            Some(("ggx", _)) => {}
            Some(("beckmann", at)) => self.warning(
                at,
                format!("{}: the Beckmann distribution is approximated by GGX with the same alpha", o.describe()),
            ),
            Some((other, at)) => self.error(
                at,
                format!("{}: unknown distribution \"{other}\" (expected ggx or beckmann)", o.describe()),
            ),
            None => self.warning(
                o.at,
                format!("{}: Mitsuba's default Beckmann distribution is approximated by GGX with the same alpha (say <string name=\"distribution\" value=\"ggx\"/> to match exactly)", o.describe()),
            ),
        }
        // Accepted: eyeadapt always samples visible normals.
        self.boolean(o, "sample_visible");
        alpha as f32
    }

    pub(super) fn conductor(&mut self, o: &'t Obj) -> Bsdf {
        let alpha = self.alpha(o, "roughconductor");
        let material = self.string(o, "material");
        let has_eta = self.prop(o, "eta").is_some() || self.prop(o, "k").is_some();
        let (eta, k) = match material {
            Some((name, at)) if has_eta => {
                self.error(
                    at,
                    format!(
                        "{}: give either `material` (\"{name}\") or `eta`/`k`, not both",
                        o.describe()
                    ),
                );
                (Rgb::ZERO, Rgb::ONE)
            }
            Some((name, at)) => match CONDUCTOR_PRESETS.iter().find(|(n, _, _)| *n == name) {
                Some((_, eta, k)) => (Rgb::from_array(*eta), Rgb::from_array(*k)),
                None => {
                    self.error(
                        at,
                        format!(
                            "{}: unknown conductor material \"{name}\" (known: {})",
                            o.describe(),
                            CONDUCTOR_PRESETS
                                .iter()
                                .map(|p| p.0)
                                .collect::<Vec<_>>()
                                .join(", ")
                        ),
                    );
                    (Rgb::ZERO, Rgb::ONE)
                }
            },
            // Mitsuba's default material "none": a perfect mirror (eta 0, k 1).
            None => (
                self.colour(o, "eta").unwrap_or(Rgb::ZERO),
                self.colour(o, "k").unwrap_or(Rgb::ONE),
            ),
        };
        let specular_reflectance = self
            .colour_param(o, "specular_reflectance")
            .unwrap_or(Param::Const(Rgb::ONE));
        Bsdf::Conductor {
            alpha,
            eta,
            k,
            specular_reflectance,
        }
    }

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

    pub(super) fn plastic(&mut self, o: &'t Obj) -> Bsdf {
        let alpha = self.alpha(o, "roughplastic");
        let reflectance = self.reflectance(o, "diffuse_reflectance");
        let int_ior = self.ior(o, "int_ior", 1.49);
        let ext_ior = self.ior(o, "ext_ior", 1.000277);
        let ior = int_ior / ext_ior;
        if !(ior > 1.0 && ior < 4.0) {
            self.error(
                o.at,
                format!(
                    "{}: int_ior/ext_ior = {ior} must be in (1, 4)",
                    o.describe()
                ),
            );
        }
        if let Some(s) = self.colour(o, "specular_reflectance")
            && s != Rgb::ONE
        {
            let at = self.prop(o, "specular_reflectance").map_or(o.at, |p| p.at);
            self.warning(
                at,
                format!("{}: specular_reflectance {s:?} is ignored (eyeadapt's plastic coating reflects by Fresnel alone)", o.describe()),
            );
        }
        if self.boolean(o, "nonlinear") == Some(true) {
            let at = self.prop(o, "nonlinear").map_or(o.at, |p| p.at);
            self.warning(
                at,
                format!("{}: nonlinear = true is ignored (eyeadapt's plastic is Mitsuba's linear model)", o.describe()),
            );
        }
        if alpha.constant().is_some_and(|a| a < 0.01) {
            self.warning(
                o.at,
                format!("{}: a smooth coating is approximated by GGX alpha 0.01 (eyeadapt's plastic is always a microfacet coating)", o.describe()),
            );
        }
        Bsdf::Plastic {
            reflectance,
            alpha: match alpha {
                Param::Const(a) => Param::Const(a.max(0.01)),
                t => t,
            },
            ior: ior as f32,
        }
    }
}
