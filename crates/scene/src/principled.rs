//! The Disney principled BSDFs as Mitsuba 3 defines them (`principled`, `principledthin`):
//! plain parameters, every weight in [0, 1] (`diff_trans` in [0, 2]) and a constant or a
//! texture (read as its luminance, as Mitsuba's `eval_1`).
//!
//! ```toml
//! [[materials]]
//! name = "car paint"
//! type = "principled"
//! base_color = [0.6, 0.05, 0.05]
//! roughness = 0.3
//! metallic = 0.4
//! clearcoat = 1.0
//! clearcoat_gloss = 0.9
//! ```
use crate::{Param, Rgb};

/// Mitsuba's `principled`: a diffuse base with retro-reflection, sheen and fake subsurface
/// (`flatness`), a GGX specular lobe (anisotropic, tinted, metallic), a GGX transmission lobe
/// (`spec_trans`) and a GTR1 clearcoat.
#[derive(Clone, Debug, PartialEq)]
pub struct Principled {
    pub base_color: Param<Rgb>,
    pub roughness: Param<f32>,
    pub metallic: Param<f32>,
    pub spec_tint: Param<f32>,
    pub anisotropic: Param<f32>,
    pub sheen: Param<f32>,
    pub sheen_tint: Param<f32>,
    pub clearcoat: Param<f32>,
    pub clearcoat_gloss: Param<f32>,
    pub spec_trans: Param<f32>,
    pub flatness: Param<f32>,
    /// Interior IOR over exterior (> 0). Mitsuba's `specular` s gives
    /// eta = 2 / (1 − √(0.08 s)) − 1 ([`Principled::eta_of_specular`]).
    pub eta: f32,
}

impl Principled {
    /// Mitsuba's defaults: base colour and roughness 0.5, `specular` 0.5 (eta 1.5), every
    /// other weight 0.
    pub fn new(base_color: Param<Rgb>) -> Principled {
        let zero = Param::Const(0.0);
        Principled {
            base_color,
            roughness: Param::Const(0.5),
            metallic: zero,
            spec_tint: zero,
            anisotropic: zero,
            sheen: zero,
            sheen_tint: zero,
            clearcoat: zero,
            clearcoat_gloss: zero,
            spec_trans: zero,
            flatness: zero,
            eta: 1.5,
        }
    }

    /// The IOR a `specular` weight in [0, 1] stands for (Burley 2015; 0.5 is 1.5).
    pub fn eta_of_specular(specular: f64) -> f64 {
        2.0 / (1.0 - (0.08 * specular).sqrt()) - 1.0
    }

    /// True where the BSDF can transmit (Mitsuba's `spec_trans` given and not 0): it then has a
    /// back side of its own; otherwise it reflects on the front only.
    pub fn transmits(&self) -> bool {
        self.spec_trans != Param::Const(0.0)
    }
}

/// Mitsuba's `principledthin`: a thin sheet with the principled's diffuse, sheen and specular
/// lobes, a GGX transmission lobe whose roughness scales with `eta`, and a Lambertian
/// transmission (`diff_trans`); it looks the same from both sides.
#[derive(Clone, Debug, PartialEq)]
pub struct PrincipledThin {
    pub base_color: Param<Rgb>,
    pub roughness: Param<f32>,
    pub spec_tint: Param<f32>,
    pub anisotropic: Param<f32>,
    pub sheen: Param<f32>,
    pub sheen_tint: Param<f32>,
    pub spec_trans: Param<f32>,
    pub flatness: Param<f32>,
    /// In [0, 2] (Mitsuba's range; the lobes use half of it).
    pub diff_trans: Param<f32>,
    /// The sheet's IOR (> 0), possibly a texture.
    pub eta: Param<f32>,
}

impl PrincipledThin {
    /// Mitsuba's defaults: base colour and roughness 0.5, eta 1.5, every weight 0.
    pub fn new(base_color: Param<Rgb>) -> PrincipledThin {
        let zero = Param::Const(0.0);
        PrincipledThin {
            base_color,
            roughness: Param::Const(0.5),
            spec_tint: zero,
            anisotropic: zero,
            sheen: zero,
            sheen_tint: zero,
            spec_trans: zero,
            flatness: zero,
            diff_trans: zero,
            eta: Param::Const(1.5),
        }
    }
}
