//! Mitsuba 3's `principled` BSDF (Burley 2012, 2015) at one hit, in the local shading frame
//! on the viewer's side (`wo.z > 0`): a diffuse base (with retro-reflection, fake subsurface
//! and sheen) weighted (1 − metallic)(1 − spec_trans), an anisotropic GGX reflection whose
//! Fresnel blends the dielectric's with tinted and metallic Schlick terms, a GGX transmission
//! weighted (1 − metallic)·spec_trans, and a GTR1 clearcoat.
//!
//! Seen from inside (`front` false, only for a BSDF that transmits) it is a rough dielectric
//! interface scaled by the transmission weight, as in Mitsuba. Values are for radiance (the
//! refracted part carries the 1/η² of solid-angle compression, which cancels against the
//! half-vector Jacobian). Lobes are picked with Mitsuba's probabilities: diffuse ∝ its weight,
//! clearcoat ∝ clearcoat/4, and the specular pair ∝ 1, split at the sampled microfacet by its
//! Fresnel, so the noise is comparable.
use crate::bsdf::{BsdfSample, cosine_hemisphere};
use crate::emitter::luminance;
use crate::microfacet::fresnel_refract;
use crate::principled_lobes::{
    AnisoGgx, Gtr1, clearcoat_g1, diffuse, schlick, schlick_r0, sheen, tint,
};
use eyeadapt_scene::{Param, Rgb};
use glam::Vec3A;
use std::f32::consts::FRAC_1_PI;

#[derive(Clone, Copy, Debug)]
pub struct Principled {
    pub base: Vec3A,
    pub spec: AnisoGgx,
    pub roughness: f32,
    pub metallic: f32,
    pub spec_tint: f32,
    pub sheen: f32,
    pub sheen_tint: f32,
    pub clearcoat: f32,
    pub clearcoat_gloss: f32,
    pub spec_trans: f32,
    pub flatness: f32,
    /// The material's interior IOR over its exterior.
    pub eta: f32,
    /// The viewer is outside (always, for a BSDF that cannot transmit).
    pub front: bool,
}

/// The half vector of a pair of directions and the Fresnel reflectance at it.
struct Half {
    wh: Vec3A,
    /// wo·wh and wi·wh.
    dot_o: f32,
    dot_i: f32,
    f: f32,
}

impl Principled {
    /// The scene's principled at a hit whose parameters `rgb` and `number` evaluate, seen
    /// from outside when `front` (or when it cannot transmit: its back side is then black or,
    /// in a `twosided`, like its front).
    pub fn at(
        p: &eyeadapt_scene::Principled,
        front: bool,
        rgb: impl Fn(Param<Rgb>) -> Vec3A,
        number: impl Fn(Param<f32>) -> f32,
    ) -> Principled {
        let w = |x| number(x).clamp(0.0, 1.0);
        let roughness = w(p.roughness);
        Principled {
            base: rgb(p.base_color).max(Vec3A::ZERO),
            spec: AnisoGgx::principled(roughness, w(p.anisotropic)),
            roughness,
            metallic: w(p.metallic),
            spec_tint: w(p.spec_tint),
            sheen: w(p.sheen),
            sheen_tint: w(p.sheen_tint),
            clearcoat: w(p.clearcoat),
            clearcoat_gloss: w(p.clearcoat_gloss),
            spec_trans: w(p.spec_trans),
            flatness: w(p.flatness),
            eta: p.eta,
            front: front || !p.transmits(),
        }
    }

    /// The relative IOR of the far side over the viewer's.
    #[inline]
    fn eta_path(&self) -> f32 {
        if self.front { self.eta } else { 1.0 / self.eta }
    }

    /// The weights of the diffuse base and of the transmission.
    #[inline]
    fn weights(&self) -> (f32, f32) {
        let m = 1.0 - self.metallic;
        (m * (1.0 - self.spec_trans), m * self.spec_trans)
    }

    /// True when some light passes through at this hit.
    pub fn transmits(&self) -> bool {
        self.weights().1 > 0.0
    }

    #[inline]
    fn half(&self, wo: Vec3A, wi: Vec3A) -> Half {
        let eta = self.eta_path();
        let h = if wi.z > 0.0 { wo + wi } else { wo + eta * wi };
        let wh = h.normalize_or_zero() * h.z.signum();
        let dot_o = wo.dot(wh);
        Half {
            wh,
            dot_o,
            dot_i: wi.dot(wh),
            f: fresnel_refract(dot_o, eta).0,
        }
    }

    /// The probabilities of picking the diffuse, clearcoat and transmission lobes (the rest
    /// is the specular reflection), for dielectric Fresnel reflectance `f` at the microfacet.
    #[inline]
    fn lobe_probs(&self, f: f32) -> (f32, f32, f32) {
        let (brdf, bsdf) = self.weights();
        if self.front {
            let tot = 1.0 + brdf + 0.25 * self.clearcoat;
            (
                brdf / tot,
                0.25 * self.clearcoat / tot,
                bsdf * (1.0 - f) / tot,
            )
        } else {
            (0.0, 0.0, 1.0 - f)
        }
    }

    /// The specular reflection's Fresnel: outside, the dielectric's blended with the tinted
    /// and the metallic Schlick terms; inside, the dielectric's scaled by the transmission
    /// weight.
    fn fresnel(&self, f_dielectric: f32, cos: f32) -> Vec3A {
        let (_, bsdf) = self.weights();
        if !self.front {
            return Vec3A::splat(bsdf * f_dielectric);
        }
        let mut f = Vec3A::splat((1.0 - self.metallic) * (1.0 - self.spec_tint) * f_dielectric);
        if self.metallic > 0.0 {
            f += self.metallic * schlick(self.base, cos, self.eta);
        }
        if self.spec_tint > 0.0 {
            let r0 = tint(self.base, luminance(self.base)) * schlick_r0(self.eta);
            f += (1.0 - self.metallic) * self.spec_tint * schlick(r0, cos, self.eta);
        }
        f
    }

    /// BSDF value (without cosine), for radiance.
    pub fn eval(&self, wo: Vec3A, wi: Vec3A) -> Vec3A {
        if wo.z <= 0.0 || wi.z == 0.0 {
            return Vec3A::ZERO;
        }
        let (brdf, bsdf) = self.weights();
        let Half {
            wh,
            dot_o,
            dot_i,
            f,
        } = self.half(wo, wi);
        let mut v = Vec3A::ZERO;
        if wi.z < 0.0 {
            if bsdf > 0.0 && dot_o > 0.0 && dot_i < 0.0 && f < 1.0 {
                let eta = self.eta_path();
                let denom = dot_o + eta * dot_i;
                let t =
                    (1.0 - f) * self.spec.d(wh) * self.spec.g(wo, wi, wh) * (dot_o * dot_i).abs()
                        / (wo.z * -wi.z * denom * denom);
                let sqrt_base =
                    Vec3A::new(self.base.x.sqrt(), self.base.y.sqrt(), self.base.z.sqrt());
                v += sqrt_base * (bsdf * t);
            }
            return v;
        }
        let compatible = dot_o > 0.0 && dot_i > 0.0;
        if compatible && f > 0.0 {
            let dg = self.spec.d(wh) * self.spec.g(wo, wi, wh);
            v += self.fresnel(f, dot_o) * (dg / (4.0 * wo.z * wi.z));
        }
        if !self.front {
            return v;
        }
        if compatible && self.clearcoat > 0.0 {
            // Mitsuba's clearcoat has no 1/(4 cos cos) (Burley's folds it into his G).
            let fc = schlick(Vec3A::splat(0.04), dot_o, self.eta).x;
            let d = Gtr1::clearcoat(self.clearcoat_gloss).d(wh);
            let g = clearcoat_g1(wo, wh) * clearcoat_g1(wi, wh);
            v += Vec3A::splat(0.25 * self.clearcoat * fc * d * g);
        }
        if brdf > 0.0 {
            let d = diffuse(self.base, self.roughness, self.flatness, wo.z, wi.z, dot_i);
            v += brdf * d;
        }
        if self.sheen > 0.0 && self.metallic < 1.0 {
            let s = sheen(self.base, luminance(self.base), self.sheen_tint, dot_i);
            v += (self.sheen * (1.0 - self.metallic)) * s;
        }
        v
    }

    /// The diffuse reflection lobe alone (front side), without sheen.
    pub fn eval_diffuse(&self, wo: Vec3A, wi: Vec3A) -> Vec3A {
        let (brdf, _) = self.weights();
        if wo.z <= 0.0 || wi.z <= 0.0 || !self.front || brdf <= 0.0 {
            return Vec3A::ZERO;
        }
        let dot_i = self.half(wo, wi).dot_i;
        brdf * diffuse(self.base, self.roughness, self.flatness, wo.z, wi.z, dot_i)
    }

    /// Density of [`Self::sample`] over solid angle.
    pub fn pdf(&self, wo: Vec3A, wi: Vec3A) -> f32 {
        if wo.z <= 0.0 || wi.z == 0.0 || (!self.front && !self.transmits()) {
            return 0.0;
        }
        let Half {
            wh,
            dot_o,
            dot_i,
            f,
        } = self.half(wo, wi);
        let (pd, pc, pt) = self.lobe_probs(f);
        if wi.z < 0.0 {
            if pt <= 0.0 || dot_o <= 0.0 || dot_i >= 0.0 {
                return 0.0;
            }
            let eta = self.eta_path();
            let denom = dot_o + eta * dot_i;
            return pt * self.spec.pdf(wo, wh) * eta * eta * -dot_i / (denom * denom);
        }
        let mut p = pd * wi.z * FRAC_1_PI;
        if dot_o > 0.0 && dot_i > 0.0 {
            let pr = 1.0 - pd - pc - pt;
            let mut pm = pr * self.spec.pdf(wo, wh);
            if pc > 0.0 {
                pm += pc * Gtr1::clearcoat(self.clearcoat_gloss).pdf(wh);
            }
            p += pm / (4.0 * dot_i);
        }
        p
    }

    /// Picks a lobe with `u_lobe` (diffuse, clearcoat, transmission, reflection in Mitsuba's
    /// order) and places the direction with `u`.
    pub fn sample(&self, wo: Vec3A, u_lobe: f32, u: [f32; 2]) -> Option<BsdfSample> {
        if wo.z <= 0.0 || (!self.front && !self.transmits()) {
            return None;
        }
        // The diffuse and clearcoat probabilities do not depend on the microfacet.
        let (pd, pc, _) = self.lobe_probs(0.0);
        let (wi, transmitted) = if u_lobe < pd {
            (cosine_hemisphere(u), false)
        } else if u_lobe < pd + pc {
            let m = Gtr1::clearcoat(self.clearcoat_gloss).sample(u);
            let c = wo.dot(m);
            if c <= 0.0 {
                return None;
            }
            (2.0 * c * m - wo, false)
        } else {
            let m = self.spec.sample(wo, u);
            let c = wo.dot(m);
            if c <= 0.0 {
                return None;
            }
            let eta = self.eta_path();
            let (f, cos_t) = fresnel_refract(c, eta);
            let (_, _, pt) = self.lobe_probs(f);
            if u_lobe < pd + pc + pt {
                ((c / eta - cos_t) * m - wo / eta, true)
            } else {
                (2.0 * c * m - wo, false)
            }
        };
        // A direction on the other side than its lobe says is shadowed (Mitsuba's
        // macro/micro-surface compatibility).
        if (wi.z < 0.0) != transmitted || wi.z == 0.0 {
            return None;
        }
        BsdfSample::of_lobe(wi, self.pdf(wo, wi), || self.eval(wo, wi))
    }
}

#[cfg(test)]
#[path = "principled_tests.rs"]
mod tests;
