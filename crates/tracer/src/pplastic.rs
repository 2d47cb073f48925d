//! Mitsuba's `pplastic` as its RGB variants render it: a microfacet Fresnel reflection over a
//! Lambertian base that is attenuated by the smooth-interface Fresnel transmittance on the
//! way in and on the way out,
//!
//! f = s·F(wi·m)·D(m)·G / (4 cos θi cos θo) + ρ·(1 − F(cos θi))(1 − F(cos θo)) / π,
//!
//! with no normalisation of the base for the light the interface reflects back into it (that
//! is `roughplastic`'s (1 − Fdr) term, and why the two differ). The specular lobe is sampled
//! with the fixed probability mean(s) / (mean(ρ) + mean(s)), as in Mitsuba.
use crate::bsdf::{BsdfSample, cosine_hemisphere};
use crate::microfacet::{Microfacet, fresnel_dielectric};
use glam::Vec3A;
use std::f32::consts::FRAC_1_PI;

#[derive(Clone, Copy, Debug)]
pub struct PPlastic {
    pub md: Microfacet,
    pub diffuse: Vec3A,
    pub specular: Vec3A,
    /// Interior over exterior IOR.
    pub eta: f32,
    /// Probability of sampling the specular lobe.
    pub spec_prob: f32,
}

impl PPlastic {
    /// `spec_prob` from the means of the two reflectances (Mitsuba uses the textures' means
    /// over the whole surface; a constant's mean is its channel mean).
    pub fn new(md: Microfacet, diffuse: Vec3A, specular: Vec3A, eta: f32, spec_prob: f32) -> Self {
        PPlastic {
            md,
            diffuse,
            specular,
            eta,
            spec_prob,
        }
    }

    /// The sampling probability of the specular lobe for mean reflectances `d` and `s`.
    pub fn spec_prob(d: f32, s: f32) -> f32 {
        if d + s > 0.0 { s / (d + s) } else { 0.5 }
    }

    /// Value without the cosine; both directions above the surface.
    pub fn eval(&self, wo: Vec3A, wi: Vec3A) -> Vec3A {
        if wo.z <= 0.0 || wi.z <= 0.0 {
            return Vec3A::ZERO;
        }
        let m = (wo + wi).normalize();
        let spec = fresnel_dielectric(wi.dot(m), self.eta) * self.md.d(m) * self.md.g(wi, wo, m)
            / (4.0 * wi.z * wo.z);
        let ti = 1.0 - fresnel_dielectric(wi.z, self.eta);
        let to = 1.0 - fresnel_dielectric(wo.z, self.eta);
        self.specular * spec + self.diffuse * (FRAC_1_PI * ti * to)
    }

    /// The attenuated Lambertian base alone (both directions above the surface).
    pub fn eval_diffuse(&self, wo: Vec3A, wi: Vec3A) -> Vec3A {
        let ti = 1.0 - fresnel_dielectric(wi.z, self.eta);
        let to = 1.0 - fresnel_dielectric(wo.z, self.eta);
        self.diffuse * (FRAC_1_PI * ti * to)
    }

    pub fn pdf(&self, wo: Vec3A, wi: Vec3A) -> f32 {
        if wo.z <= 0.0 || wi.z <= 0.0 {
            return 0.0;
        }
        let m = (wo + wi).normalize();
        let spec = if wo.dot(m) > 0.0 && wi.dot(m) > 0.0 {
            self.md.pdf(wo, m) / (4.0 * wo.dot(m))
        } else {
            0.0
        };
        self.spec_prob * spec + (1.0 - self.spec_prob) * wi.z * FRAC_1_PI
    }

    pub fn sample(&self, wo: Vec3A, u_lobe: f32, u: [f32; 2]) -> Option<BsdfSample> {
        let wi = if u_lobe < self.spec_prob {
            let m = self.md.sample(wo, u);
            2.0 * wo.dot(m) * m - wo
        } else {
            cosine_hemisphere(u)
        };
        if wi.z <= 0.0 {
            return None;
        }
        BsdfSample::of_lobe(wi, self.pdf(wo, wi), || self.eval(wo, wi))
    }
}
