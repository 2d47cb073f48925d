//! BSDF plugins: diffuse, conductor, roughconductor, plastic, roughplastic, twosided, mask
//! (the dielectrics are in `dielectric.rs`, the principled BSDFs in `principled.rs`;
//! blendbsdf, bumpmap and null in `blend.rs`; pplastic and anisotropic roughness in
//! `rough.rs`).
//!
//! Mitsuba's reflecting BSDFs are one-sided: their back sides are black unless a `twosided`
//! wraps them. They are built as [`Bsdf::OneSided`], and `twosided` unwraps them again.
use super::Builder;
use super::rough::Roughness;
use crate::mitsuba::presets::CONDUCTOR_PRESETS;
use crate::mitsuba::xml::{ChildKind, Obj};
use crate::{Bsdf, Distribution, Param, Rgb};

const BSDFS: &str = "diffuse, conductor, roughconductor, plastic, roughplastic, pplastic, dielectric, thindielectric, roughdielectric, principled, principledthin, mask, normalmap, bumpmap, blendbsdf, null and twosided";
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
        let one_sided = |b: Bsdf| Bsdf::OneSided(Box::new(b));
        let bsdf = match o.kind.as_str() {
            "twosided" => return self.twosided(o),
            "mask" => return self.mask(o, name),
            "normalmap" => return self.normalmap(o, name),
            "bumpmap" => return self.bumpmap(o, name),
            "blendbsdf" => return self.blendbsdf(o, name),
            "null" => return self.null(o, name),
            "pplastic" => one_sided(self.pplastic(o)),
            "diffuse" => {
                let reflectance = self.reflectance(o, "reflectance");
                one_sided(Bsdf::Diffuse { reflectance })
            }
            "conductor" | "roughconductor" => one_sided(self.conductor(o)),
            "plastic" | "roughplastic" => one_sided(self.plastic(o)),
            "dielectric" | "thindielectric" | "roughdielectric" => self.dielectric(o),
            "principled" => self.principled(o),
            "principledthin" => self.principled_thin(o),
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

    /// The one nested `<bsdf>` (or reference) of `o`, which `what` needs.
    fn nested_bsdf(&mut self, o: &'t Obj, what: &str) -> Option<BuiltBsdf> {
        let inner: Vec<_> = o
            .children
            .iter()
            .filter(|c| match &c.kind {
                ChildKind::Obj(b) => b.tag == "bsdf",
                // A reference is a nested BSDF when it names one (Mitsuba's scenes write both
                // `<ref id=…>` and `<ref name="bsdf" id=…>`); a named reference to anything
                // else is a parameter (a texture).
                ChildKind::Ref(id) => {
                    c.name.is_none() || self.ids.get(id.as_str()).is_some_and(|r| r.tag == "bsdf")
                }
            })
            .collect();
        for c in &inner {
            c.used.set(true);
        }
        match inner.as_slice() {
            [c] => match &c.kind {
                ChildKind::Obj(b) => self.bsdf(b),
                ChildKind::Ref(id) => self.bsdf_by_id(id, c.at),
            },
            [] => {
                self.error(o.at, format!("{} needs one nested <bsdf>", o.describe()));
                None
            }
            _ => {
                self.error(o.at, format!("unsupported {} with {what}", o.describe()));
                None
            }
        }
    }

    /// `twosided` makes its one BSDF reflect alike on both sides.
    pub(super) fn twosided(&mut self, o: &'t Obj) -> Option<BuiltBsdf> {
        let result = self.nested_bsdf(
            o,
            "different front and back BSDFs: eyeadapt surfaces scatter the same on both sides",
        );
        self.finish(o);
        result.map(|b| BuiltBsdf {
            name: o.id.clone().unwrap_or(b.name),
            bsdf: two_sided(b.bsdf),
        })
    }

    /// `normalmap`: its BSDF shaded with the normals of the `normalmap` texture (read as it
    /// is stored: Mitsuba's scenes give it `raw = true`).
    fn normalmap(&mut self, o: &'t Obj, name: String) -> Option<BuiltBsdf> {
        let normals = match self.float_texture(o, "normalmap") {
            Some(t) => t,
            None => {
                self.error(
                    o.at,
                    format!("{} needs a <texture name=\"normalmap\">", o.describe()),
                );
                None
            }
        };
        let inner = self.nested_bsdf(o, "more than one nested <bsdf>");
        self.finish(o);
        Some(BuiltBsdf {
            bsdf: Bsdf::NormalMap {
                normals: normals?,
                bsdf: Box::new(inner?.bsdf),
            },
            name,
        })
    }

    /// `mask`: its BSDF where `opacity` (0.5, or a texture) is 1, a hole where it is 0.
    fn mask(&mut self, o: &'t Obj, name: String) -> Option<BuiltBsdf> {
        let opacity = match self.float_texture(o, "opacity") {
            Some(Some(t)) => Param::Texture(t),
            Some(None) => Param::Const(0.5),
            None => Param::Const(self.float_in(o, "opacity", 0.0..=1.0).unwrap_or(0.5) as f32),
        };
        let inner = self.nested_bsdf(o, "more than one nested <bsdf>");
        self.finish(o);
        Some(BuiltBsdf {
            bsdf: Bsdf::Mask {
                opacity,
                bsdf: Box::new(inner?.bsdf),
            },
            name,
        })
    }

    /// The roughness and distribution of a `rough` plugin (alpha a constant or a texture);
    /// alpha 0 for the smooth one.
    pub(super) fn alpha(&mut self, o: &'t Obj, rough: &str) -> (Param<f32>, Distribution) {
        if o.kind != rough {
            return (Param::Const(0.0), Distribution::Ggx);
        }
        match self.float_texture(o, "alpha") {
            Some(Some(t)) => {
                // Still reads `distribution` and `sample_visible`.
                let (_, d) = self.roughness(o, 0.1);
                (Param::Texture(t), d)
            }
            Some(None) => (Param::Const(0.1), Distribution::Ggx),
            None => {
                let (a, d) = self.roughness(o, 0.1);
                (Param::Const(a), d)
            }
        }
    }

    /// `alpha` (or equal `alpha_u`/`alpha_v`) and `distribution` (Mitsuba's default:
    /// Beckmann) of rough plugins.
    pub(super) fn roughness(&mut self, o: &'t Obj, default: f64) -> (f32, Distribution) {
        // Mitsuba's roughplastic is isotropic: there `alpha_u` is an unknown parameter.
        let anisotropic = o.kind != "roughplastic" && self.prop(o, "alpha_u").is_some();
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
        (alpha as f32, self.distribution(o))
    }

    /// `distribution` (Mitsuba's default: Beckmann) and `sample_visible` of rough plugins.
    pub(super) fn distribution(&mut self, o: &'t Obj) -> Distribution {
        let distribution = match self.string(o, "distribution") {
            Some(("ggx", _)) => Distribution::Ggx,
            Some(("beckmann", _)) | None => Distribution::Beckmann,
            Some((other, at)) => {
                self.error(
                    at,
                    format!(
                        "{}: unknown distribution \"{other}\" (expected ggx or beckmann)",
                        o.describe()
                    ),
                );
                Distribution::Ggx
            }
        };
        // Accepted: eyeadapt samples GGX by its visible normals and Beckmann by D(m)·cos θm
        // (both unbiased; only the noise differs).
        self.boolean(o, "sample_visible");
        distribution
    }

    pub(super) fn conductor(&mut self, o: &'t Obj) -> Bsdf {
        let Roughness {
            alpha,
            alpha_v,
            distribution,
        } = self.roughness_uv(o, "roughconductor");
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
            alpha_v,
            distribution,
            eta,
            k,
            specular_reflectance,
        }
    }

    pub(super) fn plastic(&mut self, o: &'t Obj) -> Bsdf {
        let (alpha, distribution) = self.alpha(o, "roughplastic");
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
        let smooth = o.kind == "plastic";
        if smooth {
            self.warning(
                o.at,
                format!("{}: the smooth coating's reflection is approximated by GGX alpha 0.01 (its transmittance and internal reflectance are the smooth interface's)", o.describe()),
            );
        } else if alpha.constant().is_some_and(|a| a < 0.01) {
            self.warning(
                o.at,
                format!(
                    "{}: alpha below 0.01 is approximated by GGX alpha 0.01",
                    o.describe()
                ),
            );
        }
        Bsdf::Plastic {
            reflectance,
            // A constant 0 marks the smooth `plastic` (see `Bsdf::Plastic`).
            alpha: match alpha {
                Param::Const(_) if smooth => Param::Const(0.0),
                Param::Const(a) => Param::Const(a.max(0.01)),
                t => t,
            },
            distribution,
            ior: ior as f32,
        }
    }
}

/// `b` reflecting alike on both sides: the one-sided wrappers removed, also inside masks,
/// normal and bump maps and blends.
fn two_sided(b: Bsdf) -> Bsdf {
    match b {
        Bsdf::OneSided(inner) => two_sided(*inner),
        Bsdf::Mask { opacity, bsdf } => Bsdf::Mask {
            opacity,
            bsdf: Box::new(two_sided(*bsdf)),
        },
        Bsdf::NormalMap { normals, bsdf } => Bsdf::NormalMap {
            normals,
            bsdf: Box::new(two_sided(*bsdf)),
        },
        Bsdf::BumpMap {
            height,
            scale,
            bsdf,
        } => Bsdf::BumpMap {
            height,
            scale,
            bsdf: Box::new(two_sided(*bsdf)),
        },
        Bsdf::Blend { weight, bsdfs } => {
            let [a, b] = *bsdfs;
            Bsdf::Blend {
                weight,
                bsdfs: Box::new([two_sided(a), two_sided(b)]),
            }
        }
        other => other,
    }
}
