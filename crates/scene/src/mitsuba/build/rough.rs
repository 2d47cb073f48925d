//! Anisotropic roughness (`alpha_u`/`alpha_v`, each a number or a texture) for the plugins
//! where Mitsuba allows it (`roughconductor`, `roughdielectric`, `pplastic`), and the
//! `pplastic` plugin as Mitsuba's RGB variants render it.
use super::Builder;
use crate::mitsuba::xml::Obj;
use crate::{Bsdf, Distribution, Param, Rgb};

/// A rough plugin's roughness: `alpha_u` (or the isotropic `alpha`), `alpha_v` when it
/// differs, and the distribution.
pub(super) struct Roughness {
    pub alpha: Param<f32>,
    pub alpha_v: Option<Param<f32>>,
    pub distribution: Distribution,
}

impl<'t> Builder<'t> {
    /// True when `o` gives parameter `name`, as a value or a texture (nothing is marked used).
    fn gives(&self, o: &Obj, name: &str) -> bool {
        o.props.iter().any(|p| p.name == name)
            || o.children.iter().any(|c| c.name.as_deref() == Some(name))
    }

    /// One roughness parameter: a number in [0, 1] or a texture (default 0.1).
    fn alpha_param(&mut self, o: &'t Obj, name: &str) -> Param<f32> {
        match self.float_texture(o, name) {
            Some(Some(t)) => Param::Texture(t),
            Some(None) => Param::Const(0.1),
            None => Param::Const(self.float_in(o, name, 0.0..=1.0).unwrap_or(0.1) as f32),
        }
    }

    /// The roughness of `o` when it is the `rough` plugin (smooth otherwise: alpha 0). Mitsuba's
    /// rule: `alpha`, or both `alpha_u` and `alpha_v`, never both kinds.
    pub(super) fn roughness_uv(&mut self, o: &'t Obj, rough: &str) -> Roughness {
        let (u, v) = (self.gives(o, "alpha_u"), self.gives(o, "alpha_v"));
        if o.kind != rough || !(u || v) {
            let (alpha, distribution) = self.alpha(o, rough);
            return Roughness {
                alpha,
                alpha_v: None,
                distribution,
            };
        }
        if self.gives(o, "alpha") {
            let at = self.prop(o, "alpha").map_or(o.at, |p| p.at);
            self.error(
                at,
                format!(
                    "{}: give either `alpha` or `alpha_u` and `alpha_v`, not both",
                    o.describe()
                ),
            );
        }
        if u != v {
            self.error(
                o.at,
                format!(
                    "{}: `alpha_u` and `alpha_v` must be given together",
                    o.describe()
                ),
            );
        }
        let alpha = self.alpha_param(o, "alpha_u");
        let alpha_v = self.alpha_param(o, "alpha_v");
        let distribution = self.distribution(o);
        Roughness {
            alpha_v: (alpha_v != alpha).then_some(alpha_v),
            alpha,
            distribution,
        }
    }

    /// `pplastic` without polarisation: `diffuse_reflectance` (0.5, or a texture),
    /// `specular_reflectance` (1, or a texture), `int_ior` ("polypropylene")/`ext_ior`
    /// ("air") or `eta`, `alpha` (0.1) or `alpha_u`/`alpha_v`, `distribution` (Beckmann).
    pub(super) fn pplastic(&mut self, o: &'t Obj) -> Bsdf {
        let Roughness {
            alpha,
            alpha_v,
            distribution,
        } = self.roughness_uv(o, "pplastic");
        let diffuse_reflectance = self.reflectance(o, "diffuse_reflectance");
        let specular_reflectance = self
            .colour_param(o, "specular_reflectance")
            .unwrap_or(Param::Const(Rgb::ONE));
        let eta = if let Some(p) = self.prop(o, "eta") {
            let at = p.at;
            if self.gives(o, "int_ior") || self.gives(o, "ext_ior") {
                self.error(
                    at,
                    format!(
                        "{}: give either `eta` or `int_ior`/`ext_ior`, not both",
                        o.describe()
                    ),
                );
            }
            self.float(o, "eta").unwrap_or(1.49)
        } else {
            self.ior(o, "int_ior", 1.49) / self.ior(o, "ext_ior", 1.000277)
        };
        if !(eta.is_finite() && eta > 0.0) || eta == 1.0 {
            self.error(
                o.at,
                format!(
                    "{}: the relative IOR {eta} must be positive and not 1",
                    o.describe()
                ),
            );
        }
        Bsdf::PPlastic {
            diffuse_reflectance,
            specular_reflectance,
            alpha,
            alpha_v,
            distribution,
            eta: eta as f32,
        }
    }
}
