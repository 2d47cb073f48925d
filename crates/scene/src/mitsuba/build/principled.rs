//! BSDF plugins `principled` and `principledthin`, with Mitsuba's parameters, defaults and
//! ranges: the weights in [0, 1] (`diff_trans` in [0, 2]), each a `<float>` or a texture; the
//! base colour a reflectance or a texture; `eta` positive (or, for `principled`, `specular`
//! in its place).
//!
//! A `principled` that cannot transmit is one-sided like Mitsuba's other reflecting BSDFs
//! (Mitsuba's is black seen from inside), so `twosided` applies to it; one that transmits
//! has a back side of its own. `principledthin` looks the same from both sides.
use super::Builder;
use crate::mitsuba::xml::Obj;
use crate::{Bsdf, Param, Principled, PrincipledThin};

/// Mitsuba's lobe sampling rates: they change only the noise, so they are accepted and
/// eyeadapt samples with the default rates (those of Mitsuba's own scenes).
const SAMPLING_RATES: &[&str] = &[
    "main_specular_sampling_rate",
    "clearcoat_sampling_rate",
    "diffuse_reflectance_sampling_rate",
    "specular_reflectance_sampling_rate",
    "specular_transmittance_sampling_rate",
    "diffuse_transmittance_sampling_rate",
];

impl<'t> Builder<'t> {
    /// A weight in `[0, max]` (default `default`): a `<float>` or a texture.
    fn weight(&mut self, o: &'t Obj, name: &str, default: f32, max: f64) -> Param<f32> {
        match self.float_texture(o, name) {
            Some(Some(t)) => Param::Texture(t),
            // A failed texture (reported): go on with the default.
            Some(None) => Param::Const(default),
            None => Param::Const(
                self.float_in(o, name, 0.0..=max)
                    .map_or(default, |x| x as f32),
            ),
        }
    }

    /// A positive, finite IOR (default 1.5); `None` after reporting a bad one.
    fn principled_eta(&mut self, o: &'t Obj) -> Option<f64> {
        let eta = self.float(o, "eta")?;
        if !(eta.is_finite() && eta > 0.0 && eta as f32 > 0.0) {
            let at = self.prop(o, "eta").map_or(o.at, |p| p.at);
            self.error(
                at,
                format!(
                    "parameter `eta` of {} is {eta}: it must be positive and finite",
                    o.describe()
                ),
            );
            return None;
        }
        Some(eta)
    }

    fn sampling_rates(&mut self, o: &'t Obj) {
        for name in SAMPLING_RATES {
            if let Some(x) = self.float(o, name)
                && x != 1.0
            {
                let at = self.prop(o, name).map_or(o.at, |p| p.at);
                self.warning(
                    at,
                    format!(
                        "{}: `{name}` {x} is ignored (eyeadapt samples the lobes at Mitsuba's default rates; only the noise differs)",
                        o.describe()
                    ),
                );
            }
        }
    }

    /// `principled` (`o.kind`), one-sided unless it transmits.
    pub(super) fn principled(&mut self, o: &'t Obj) -> Bsdf {
        let mut p = Principled::new(self.reflectance(o, "base_color"));
        p.roughness = self.weight(o, "roughness", 0.5, 1.0);
        p.metallic = self.weight(o, "metallic", 0.0, 1.0);
        p.spec_tint = self.weight(o, "spec_tint", 0.0, 1.0);
        p.anisotropic = self.weight(o, "anisotropic", 0.0, 1.0);
        p.sheen = self.weight(o, "sheen", 0.0, 1.0);
        p.sheen_tint = self.weight(o, "sheen_tint", 0.0, 1.0);
        p.clearcoat = self.weight(o, "clearcoat", 0.0, 1.0);
        p.clearcoat_gloss = self.weight(o, "clearcoat_gloss", 0.0, 1.0);
        p.spec_trans = self.weight(o, "spec_trans", 0.0, 1.0);
        p.flatness = self.weight(o, "flatness", 0.0, 1.0);
        self.sampling_rates(o);
        let transmits = p.transmits();
        let has_eta = self.prop(o, "eta").is_some();
        let has_specular = self.prop(o, "specular").is_some();
        let eta = if has_eta && has_specular {
            let at = self.prop(o, "specular").map_or(o.at, |p| p.at);
            self.error(
                at,
                format!(
                    "{}: give either `eta` or `specular`, not both (one determines the other)",
                    o.describe()
                ),
            );
            1.5
        } else if has_eta {
            // As Mitsuba: an interface without refraction cannot transmit through microfacets.
            match self.principled_eta(o) {
                Some(e) if transmits && e == 1.0 => 1.001,
                Some(e) => e,
                None => 1.5,
            }
        } else {
            let s = self.float_in(o, "specular", 0.0..=1.0).unwrap_or(0.5);
            // As Mitsuba: specular 0 (eta 1) is implausible for transmission.
            let s = if transmits && s == 0.0 { 1e-3 } else { s };
            Principled::eta_of_specular(s)
        };
        p.eta = eta as f32;
        let b = Bsdf::Principled(Box::new(p));
        if transmits {
            b
        } else {
            Bsdf::OneSided(Box::new(b))
        }
    }

    /// `principledthin`, the same from both sides.
    pub(super) fn principled_thin(&mut self, o: &'t Obj) -> Bsdf {
        let mut p = PrincipledThin::new(self.reflectance(o, "base_color"));
        p.roughness = self.weight(o, "roughness", 0.5, 1.0);
        p.spec_tint = self.weight(o, "spec_tint", 0.0, 1.0);
        p.anisotropic = self.weight(o, "anisotropic", 0.0, 1.0);
        p.sheen = self.weight(o, "sheen", 0.0, 1.0);
        p.sheen_tint = self.weight(o, "sheen_tint", 0.0, 1.0);
        p.spec_trans = self.weight(o, "spec_trans", 0.0, 1.0);
        p.flatness = self.weight(o, "flatness", 0.0, 1.0);
        p.diff_trans = self.weight(o, "diff_trans", 0.0, 2.0);
        self.sampling_rates(o);
        p.eta = match self.float_texture(o, "eta") {
            Some(Some(t)) => Param::Texture(t),
            Some(None) => Param::Const(1.5),
            None => Param::Const(self.principled_eta(o).map_or(1.5, |e| e as f32)),
        };
        Bsdf::PrincipledThin(Box::new(p))
    }
}
