//! Dielectric interfaces in the local shading frame on the viewer's side (`wo.z > 0`): smooth
//! ([`sample_smooth`]), thin ([`sample_thin`]) and rough ([`RoughDielectric`], Walter et al.
//! 2007, "Microfacet Models for Refraction through Rough Surfaces").
//!
//! `eta` is the relative IOR of the side light refracts into over the viewer's side, so it is
//! the material's int/ext seen from outside and its inverse seen from inside. Values are for
//! radiance (camera paths): refracted radiance is scaled by 1/eta² for the compression of
//! solid angle, as in Mitsuba's `TransportMode::Radiance`.
use crate::bsdf::BsdfSample;
use crate::microfacet::{Microfacet, fresnel_refract};
use glam::Vec3A;

/// The delta lobe `wi` with the sample weight `weight` (`f` is chosen so that
/// f·|cos|/pdf = weight with pdf = `prob`).
fn delta(wi: Vec3A, weight: Vec3A, prob: f32) -> BsdfSample {
    BsdfSample {
        wi,
        f: weight * (prob / wi.z.abs().max(1e-12)),
        pdf: prob,
        weight,
        delta: true,
    }
}

/// A smooth interface: Fresnel reflection with probability F, refraction otherwise (F = 1
/// beyond the critical angle). `r`, `t`: Mitsuba's `specular_reflectance`/`_transmittance`.
pub fn sample_smooth(wo: Vec3A, eta: f32, r: Vec3A, t: Vec3A, u_lobe: f32) -> BsdfSample {
    let (f, cos_t) = fresnel_refract(wo.z, eta);
    if u_lobe < f {
        delta(Vec3A::new(-wo.x, -wo.y, wo.z), r, f)
    } else {
        let wi = Vec3A::new(-wo.x / eta, -wo.y / eta, -cos_t);
        delta(wi, t / (eta * eta), 1.0 - f)
    }
}

/// A thin sheet: the reflectance with every inter-reflection of the two interfaces summed,
/// R' = 2R/(1 + R); the rest passes straight through (no deflection, no 1/eta²: the light
/// leaves into the medium it came from).
pub fn sample_thin(wo: Vec3A, eta: f32, r: Vec3A, t: Vec3A, u_lobe: f32) -> BsdfSample {
    let f = fresnel_refract(wo.z, eta).0;
    let f = 2.0 * f / (1.0 + f);
    if u_lobe < f {
        delta(Vec3A::new(-wo.x, -wo.y, wo.z), r, f)
    } else {
        delta(-wo, t, 1.0 - f)
    }
}

/// A rough interface between two dielectrics.
#[derive(Clone, Copy, Debug)]
pub struct RoughDielectric {
    pub md: Microfacet,
    pub eta: f32,
    pub r: Vec3A,
    pub t: Vec3A,
}

/// The microfacet normal and Fresnel reflectance that connect `wo` and `wi`, with whether the
/// pair is a reflection; `None` where no microfacet facing both can.
struct Facet {
    m: Vec3A,
    f: f32,
    reflect: bool,
}

impl RoughDielectric {
    fn facet(&self, wo: Vec3A, wi: Vec3A) -> Option<Facet> {
        let reflect = wi.z > 0.0;
        let h = if reflect { wo + wi } else { wo + self.eta * wi };
        let m = h.normalize_or_zero() * h.z.signum();
        // Both directions must see the facet from their own side of the macro-surface.
        if m.z <= 0.0 || wo.dot(m) <= 0.0 || (wi.dot(m) > 0.0) != reflect {
            return None;
        }
        let f = fresnel_refract(wo.dot(m), self.eta).0;
        Some(Facet { m, f, reflect })
    }

    /// BSDF value (without cosine), for radiance.
    pub fn eval(&self, wo: Vec3A, wi: Vec3A) -> Vec3A {
        let Some(Facet { m, f, reflect }) = self.facet(wo, wi) else {
            return Vec3A::ZERO;
        };
        let dg = self.md.d(m) * self.md.g(wi, wo, m);
        if reflect {
            self.r * (f * dg / (4.0 * wo.z * wi.z))
        } else {
            // The eta² of the half-vector Jacobian cancels the 1/eta² of radiance.
            let denom = wo.dot(m) + self.eta * wi.dot(m);
            let v = (1.0 - f) * dg * (wi.dot(m) * wo.dot(m)).abs()
                / ((wo.z * wi.z).abs() * denom * denom);
            self.t * v
        }
    }

    /// Density of [`Self::sample`] over solid angle.
    pub fn pdf(&self, wo: Vec3A, wi: Vec3A) -> f32 {
        let Some(Facet { m, f, reflect }) = self.facet(wo, wi) else {
            return 0.0;
        };
        let pm = self.md.pdf(wo, m);
        if reflect {
            pm * f / (4.0 * wo.dot(m))
        } else {
            let denom = wo.dot(m) + self.eta * wi.dot(m);
            pm * (1.0 - f) * self.eta * self.eta * wi.dot(m).abs() / (denom * denom)
        }
    }

    /// Samples a microfacet normal, then reflection with probability F at it, else refraction.
    pub fn sample(&self, wo: Vec3A, u_lobe: f32, u: [f32; 2]) -> Option<BsdfSample> {
        let m = self.md.sample(wo, u);
        let c = wo.dot(m);
        if c <= 0.0 {
            return None;
        }
        let (f, cos_t) = fresnel_refract(c, self.eta);
        let reflect = u_lobe < f;
        let wi = if reflect {
            2.0 * c * m - wo
        } else {
            (c / self.eta - cos_t) * m - wo / self.eta
        };
        // A direction on the other side of the macro-surface than its lobe says is shadowed.
        if (wi.z > 0.0) != reflect {
            return None;
        }
        BsdfSample::of_lobe(wi, self.pdf(wo, wi), || self.eval(wo, wi))
    }
}
