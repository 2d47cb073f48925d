//! Microfacet distributions (GGX and Beckmann, isotropic), Smith masking, normal sampling
//! (GGX: visible normals; Beckmann: the full distribution D(m)·cos θm) and Fresnel terms.
//! Local frame: the shading normal is +z.
use eyeadapt_scene::Distribution;
use glam::Vec3A;
use std::f32::consts::PI;

#[derive(Clone, Copy, Debug)]
pub struct Microfacet {
    pub alpha: f32,
    pub beckmann: bool,
}

impl Microfacet {
    pub fn new(alpha: f32, distribution: Distribution) -> Microfacet {
        Microfacet {
            alpha,
            beckmann: distribution == Distribution::Beckmann,
        }
    }

    pub fn d(&self, m: Vec3A) -> f32 {
        if m.z <= 0.0 {
            return 0.0;
        }
        let a2 = self.alpha * self.alpha;
        let c2 = m.z * m.z;
        if self.beckmann {
            let tan2 = (1.0 - c2).max(0.0) / c2;
            (-tan2 / a2).exp() / (PI * a2 * c2 * c2)
        } else {
            let t = c2 * (a2 - 1.0) + 1.0;
            a2 / (PI * t * t)
        }
    }

    /// Smith G1 of direction `w` for microfacet normal `m` (Beckmann: the rational fit of
    /// Walter et al. 2007, as Mitsuba uses).
    pub fn g1(&self, w: Vec3A, m: Vec3A) -> f32 {
        if w.dot(m) * w.z <= 0.0 {
            return 0.0;
        }
        let c2 = w.z * w.z;
        if c2 >= 1.0 {
            return 1.0;
        }
        let tan2 = (1.0 - c2).max(0.0) / c2.max(1e-12);
        if self.beckmann {
            let a = 1.0 / (self.alpha * tan2.sqrt());
            if a >= 1.6 {
                return 1.0;
            }
            let a2 = a * a;
            (3.535 * a + 2.181 * a2) / (1.0 + 2.276 * a + 2.577 * a2)
        } else {
            1.0 / (1.0 + 0.5 * (-1.0 + (1.0 + self.alpha * self.alpha * tan2).sqrt()))
        }
    }

    /// Separable Smith shadowing-masking, as Mitsuba 3 uses.
    pub fn g(&self, wi: Vec3A, wo: Vec3A, m: Vec3A) -> f32 {
        self.g1(wi, m) * self.g1(wo, m)
    }

    /// Samples a microfacet normal for viewing direction `wi` (`wi.z > 0`); its density is
    /// [`Self::pdf`].
    pub fn sample(&self, wi: Vec3A, u: [f32; 2]) -> Vec3A {
        if self.beckmann {
            let tan2 = -self.alpha * self.alpha * (1.0 - u[0]).max(1e-12).ln();
            let cos = 1.0 / (1.0 + tan2).sqrt();
            let sin = (1.0 - cos * cos).max(0.0).sqrt();
            let phi = 2.0 * PI * u[1];
            Vec3A::new(sin * phi.cos(), sin * phi.sin(), cos)
        } else {
            self.sample_visible(wi, u)
        }
    }

    /// Density of [`Self::sample`] over microfacet normals.
    pub fn pdf(&self, wi: Vec3A, m: Vec3A) -> f32 {
        if self.beckmann {
            self.d(m) * m.z.max(0.0)
        } else {
            if wi.z <= 0.0 {
                return 0.0;
            }
            self.g1(wi, m) * wi.dot(m).max(0.0) * self.d(m) / wi.z
        }
    }

    /// Samples a visible GGX normal seen from `wi` (Heitz 2018, "Sampling the GGX
    /// Distribution of Visible Normals"). `wi.z > 0`.
    fn sample_visible(&self, wi: Vec3A, u: [f32; 2]) -> Vec3A {
        let a = self.alpha;
        let vh = Vec3A::new(a * wi.x, a * wi.y, wi.z).normalize();
        let lensq = vh.x * vh.x + vh.y * vh.y;
        let t1 = if lensq > 0.0 {
            Vec3A::new(-vh.y, vh.x, 0.0) / lensq.sqrt()
        } else {
            Vec3A::X
        };
        let t2 = vh.cross(t1);
        let r = u[0].sqrt();
        let phi = 2.0 * PI * u[1];
        let p1 = r * phi.cos();
        let mut p2 = r * phi.sin();
        let s = 0.5 * (1.0 + vh.z);
        p2 = (1.0 - s) * (1.0 - p1 * p1).max(0.0).sqrt() + s * p2;
        let nh = t1 * p1 + t2 * p2 + vh * (1.0 - p1 * p1 - p2 * p2).max(0.0).sqrt();
        Vec3A::new(a * nh.x, a * nh.y, nh.z.max(1e-6)).normalize()
    }
}

/// Unpolarised Fresnel reflectance of a conductor with complex IOR `eta + i k`.
pub fn fresnel_conductor(cos_i: f32, eta: f32, k: f32) -> f32 {
    let c2 = (cos_i * cos_i).min(1.0);
    let s2 = 1.0 - c2;
    let s4 = s2 * s2;
    let t1 = eta * eta - k * k - s2;
    let a2pb2 = (t1 * t1 + 4.0 * k * k * eta * eta).max(0.0).sqrt();
    let a = (0.5 * (a2pb2 + t1)).max(0.0).sqrt();
    let term1 = a2pb2 + c2;
    let term2 = 2.0 * cos_i * a;
    let rs = (term1 - term2) / (term1 + term2);
    let term3 = a2pb2 * c2 + s4;
    let term4 = term2 * s2;
    let rp = rs * (term3 - term4) / (term3 + term4);
    (0.5 * (rs + rp)).clamp(0.0, 1.0)
}

/// Unpolarised Fresnel reflectance at an interface of relative IOR `eta` (transmitted side
/// over incident side; below 1 when leaving a denser medium), for incidence cosine `cos_i`.
pub fn fresnel_dielectric(cos_i: f32, eta: f32) -> f32 {
    fresnel_refract(cos_i, eta).0
}

/// [`fresnel_dielectric`] and the cosine of the refracted direction (0 under total internal
/// reflection, where the reflectance is 1).
pub fn fresnel_refract(cos_i: f32, eta: f32) -> (f32, f32) {
    let cos_i = cos_i.clamp(0.0, 1.0);
    let sin_t2 = (1.0 - cos_i * cos_i) / (eta * eta);
    if sin_t2 >= 1.0 {
        return (1.0, 0.0);
    }
    let cos_t = (1.0 - sin_t2).sqrt();
    let rs = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
    let rp = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
    (0.5 * (rs * rs + rp * rp), cos_t)
}

/// Hemispherical average of the dielectric Fresnel reflectance seen from inside a medium of
/// relative IOR `eta` (Fdr for 1/eta), by numerical integration: it is computed once per
/// material, so accuracy beats a polynomial fit.
pub fn internal_diffuse_reflectance(eta: f32) -> f32 {
    // Light inside (IOR eta) hitting the interface towards IOR 1: relative IOR 1/eta.
    let inv = 1.0 / eta;
    let n = 2048;
    let mut sum = 0.0f64;
    for i in 0..n {
        // ∫ F(μ) 2μ dμ over μ in [0,1] with the midpoint rule.
        let mu = (i as f64 + 0.5) / n as f64;
        let sin_t2 = (1.0 - mu * mu) / (inv as f64 * inv as f64);
        let f = if sin_t2 >= 1.0 {
            1.0
        } else {
            let ct = (1.0 - sin_t2).sqrt();
            let e = inv as f64;
            let rs = (mu - e * ct) / (mu + e * ct);
            let rp = (e * mu - ct) / (e * mu + ct);
            0.5 * (rs * rs + rp * rp)
        };
        sum += f * 2.0 * mu / n as f64;
    }
    sum as f32
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn d_integrates_projected_area_to_one() {
        // ∫ D(m) cos θm dm = 1 over the hemisphere.
        for (alpha, d) in [0.05f32, 0.3, 0.8]
            .into_iter()
            .flat_map(|a| [(a, Distribution::Ggx), (a, Distribution::Beckmann)])
        {
            let g = Microfacet::new(alpha, d);
            let n = 400_000; // fine enough to resolve the alpha = 0.05 peak
            let mut s = 0.0f64;
            for i in 0..n {
                let ct = (i as f64 + 0.5) / n as f64;
                let st = (1.0 - ct * ct).sqrt();
                let m = Vec3A::new(st as f32, 0.0, ct as f32);
                s += g.d(m) as f64 * ct * 2.0 * std::f64::consts::PI / n as f64;
            }
            assert!((s - 1.0).abs() < 0.02, "alpha {alpha} {d:?}: {s}");
        }
    }

    #[test]
    fn fresnel_limits() {
        assert!((fresnel_dielectric(1.0, 1.5) - 0.04).abs() < 1e-4);
        assert!((fresnel_dielectric(0.0, 1.5) - 1.0).abs() < 1e-4);
        // A conductor with k = 0 is a dielectric.
        assert!((fresnel_conductor(0.7, 1.5, 0.0) - fresnel_dielectric(0.7, 1.5)).abs() < 1e-4);
        // Fdr(1/1.5) from inside glass is about 0.596 (known value).
        assert!((internal_diffuse_reflectance(1.5) - 0.596).abs() < 0.005);
    }
}
