//! Microfacet distributions (GGX and Beckmann, isotropic or anisotropic), Smith masking,
//! normal sampling (GGX: visible normals; Beckmann: the full distribution D(m)·cos θm) and
//! Fresnel terms. Local frame: the shading normal is +z, ∂p/∂u along +x (where `alpha_u`
//! applies; `alpha_v` along +y).
//!
//! Isotropic surfaces keep their own, shorter formulas (and bits): the anisotropic ones are
//! used only where `alpha_u ≠ alpha_v`.
use crate::trig::sincos_turns;
use eyeadapt_scene::Distribution;
use glam::Vec3A;
use std::f32::consts::PI;

/// The stretched view direction of visible-normal sampling and the frame around it
/// ([`Microfacet::visible_frame`]).
#[derive(Clone, Copy, Debug)]
pub struct VisibleFrame {
    vh: Vec3A,
    t1: Vec3A,
    t2: Vec3A,
    /// Weight of the half-disk warp, (1 + vh.z) / 2.
    s: f32,
}

#[derive(Clone, Copy, Debug)]
pub struct Microfacet {
    pub alpha: f32,
    /// The roughness along +y; equal to `alpha` for isotropic surfaces.
    pub alpha_v: f32,
    pub beckmann: bool,
}

impl Microfacet {
    pub fn new(alpha: f32, distribution: Distribution) -> Microfacet {
        Microfacet::anisotropic(alpha, alpha, distribution)
    }

    /// Roughness `alpha_u` along +x and `alpha_v` along +y.
    pub fn anisotropic(alpha_u: f32, alpha_v: f32, distribution: Distribution) -> Microfacet {
        Microfacet {
            alpha: alpha_u,
            alpha_v,
            beckmann: distribution == Distribution::Beckmann,
        }
    }

    #[inline]
    fn isotropic(&self) -> bool {
        self.alpha == self.alpha_v
    }

    pub fn d(&self, m: Vec3A) -> f32 {
        if m.z <= 0.0 {
            return 0.0;
        }
        if !self.isotropic() {
            return self.d_anisotropic(m);
        }
        let a2 = self.alpha * self.alpha;
        let c2 = m.z * m.z;
        if self.beckmann {
            let tan2 = (1.0 - c2).max(0.0) / c2;
            libm::expf(-tan2 / a2) / (PI * a2 * c2 * c2)
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
        self.g1_unmasked(w)
    }

    /// [`Self::g1`] for a microfacet normal on `w`'s side (`w·m` and `w.z` of one sign): past
    /// that test G1 depends on `w` alone, so a caller with many normals for one `w` (the
    /// plastic tables' quadrature) computes it once.
    #[inline]
    pub fn g1_unmasked(&self, w: Vec3A) -> f32 {
        if !self.isotropic() {
            return self.g1_anisotropic(w);
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
        if self.beckmann && !self.isotropic() {
            return self.sample_beckmann_anisotropic(u);
        }
        if self.beckmann {
            let tan2 = -self.alpha * self.alpha * libm::logf((1.0 - u[0]).max(1e-12));
            let cos = 1.0 / (1.0 + tan2).sqrt();
            let sin = (1.0 - cos * cos).max(0.0).sqrt();
            let (sin_phi, cos_phi) = sincos_turns(u[1]);
            Vec3A::new(sin * cos_phi, sin * sin_phi, cos)
        } else {
            self.sample_visible(wi, u)
        }
    }

    /// Density of [`Self::sample`] over microfacet normals.
    pub fn pdf(&self, wi: Vec3A, m: Vec3A) -> f32 {
        if self.beckmann {
            self.d(m) * m.z.max(0.0)
        } else {
            self.visible_pdf(wi, self.g1_unmasked(wi), m)
        }
    }

    /// [`Self::pdf`] of a GGX surface (visible normals), given `wi`'s
    /// [`Self::g1_unmasked`]: G1(wi, m) (wi·m)⁺ D(m) / wi.z, operation for operation.
    #[inline]
    pub fn visible_pdf(&self, wi: Vec3A, g1_wi: f32, m: Vec3A) -> f32 {
        if wi.z <= 0.0 {
            return 0.0;
        }
        let g1 = if wi.dot(m) * wi.z <= 0.0 { 0.0 } else { g1_wi };
        g1 * wi.dot(m).max(0.0) * self.d(m) / wi.z
    }

    /// Samples a visible GGX normal seen from `wi` (Heitz 2018, "Sampling the GGX
    /// Distribution of Visible Normals"). `wi.z > 0`.
    fn sample_visible(&self, wi: Vec3A, u: [f32; 2]) -> Vec3A {
        let (sin_phi, cos_phi) = sincos_turns(u[1]);
        self.visible_normal(&self.visible_frame(wi), u[0].sqrt(), cos_phi, sin_phi)
    }

    /// The part of [`Self::sample`] for GGX that depends on `wi` alone (`wi.z > 0`).
    #[inline]
    pub fn visible_frame(&self, wi: Vec3A) -> VisibleFrame {
        let vh = Vec3A::new(self.alpha * wi.x, self.alpha_v * wi.y, wi.z).normalize();
        let lensq = vh.x * vh.x + vh.y * vh.y;
        let t1 = if lensq > 0.0 {
            Vec3A::new(-vh.y, vh.x, 0.0) / lensq.sqrt()
        } else {
            Vec3A::X
        };
        VisibleFrame {
            vh,
            t1,
            t2: vh.cross(t1),
            s: 0.5 * (1.0 + vh.z),
        }
    }

    /// The visible GGX normal of `frame`'s direction at disk radius `r` (√u₀) and azimuth
    /// φ = 2π u₁ given by its cosine and sine: [`Self::sample`] for GGX, bit for bit.
    #[inline]
    pub fn visible_normal(
        &self,
        frame: &VisibleFrame,
        r: f32,
        cos_phi: f32,
        sin_phi: f32,
    ) -> Vec3A {
        let VisibleFrame { vh, t1, t2, s } = *frame;
        let p1 = r * cos_phi;
        let mut p2 = r * sin_phi;
        p2 = (1.0 - s) * (1.0 - p1 * p1).max(0.0).sqrt() + s * p2;
        let nh = t1 * p1 + t2 * p2 + vh * (1.0 - p1 * p1 - p2 * p2).max(0.0).sqrt();
        Vec3A::new(self.alpha * nh.x, self.alpha_v * nh.y, nh.z.max(1e-6)).normalize()
    }

    /// D(m) of an anisotropic surface (`m.z > 0`).
    fn d_anisotropic(&self, m: Vec3A) -> f32 {
        let (au, av) = (self.alpha, self.alpha_v);
        let (x, y) = (m.x / au, m.y / av);
        let z2 = m.z * m.z;
        if self.beckmann {
            libm::expf(-(x * x + y * y) / z2) / (PI * au * av * z2 * z2)
        } else {
            let t = x * x + y * y + z2;
            1.0 / (PI * au * av * t * t)
        }
    }

    /// Smith G1 of an anisotropic surface: the isotropic one with the roughness projected
    /// on `w`'s azimuth, α² tan²θ = (αu² x² + αv² y²) / z².
    fn g1_anisotropic(&self, w: Vec3A) -> f32 {
        let (x, y) = (self.alpha * w.x, self.alpha_v * w.y);
        let xy2 = x * x + y * y;
        if xy2 <= 0.0 {
            return 1.0;
        }
        let a2tan2 = xy2 / (w.z * w.z).max(1e-12);
        if self.beckmann {
            let a = 1.0 / a2tan2.sqrt();
            if a >= 1.6 {
                return 1.0;
            }
            let a2 = a * a;
            (3.535 * a + 2.181 * a2) / (1.0 + 2.276 * a + 2.577 * a2)
        } else {
            2.0 / (1.0 + (1.0 + a2tan2).sqrt())
        }
    }

    /// Samples D(m)·cos θm of an anisotropic Beckmann surface: the azimuth with density
    /// 1/(2π αu αv A(φ)), A(φ) = cos²φ/αu² + sin²φ/αv² (tan φ = αv/αu · tan 2πu₁), then
    /// tan²θ = −ln(1 − u₀)/A(φ).
    fn sample_beckmann_anisotropic(&self, u: [f32; 2]) -> Vec3A {
        let (au, av) = (self.alpha, self.alpha_v);
        let (sin_psi, cos_psi) = sincos_turns(u[1]);
        let (sp, cp) = (av * sin_psi, au * cos_psi);
        let r = (sp * sp + cp * cp).sqrt();
        let (sin_phi, cos_phi) = (sp / r, cp / r);
        let a = cos_phi * cos_phi / (au * au) + sin_phi * sin_phi / (av * av);
        let tan2 = -libm::logf((1.0 - u[0]).max(1e-12)) / a;
        let cos = 1.0 / (1.0 + tan2).sqrt();
        let sin = (1.0 - cos * cos).max(0.0).sqrt();
        Vec3A::new(sin * cos_phi, sin * sin_phi, cos)
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
#[cfg(test)]
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
    fn anisotropic_d_integrates_projected_area_to_one() {
        // ∫ D(m) cos θm dm = 1, on a (cos θ, φ) grid: the peak of the smaller roughness needs
        // the fine steps near the pole.
        for d in [Distribution::Ggx, Distribution::Beckmann] {
            for (au, av) in [(0.1f32, 0.4f32), (0.6, 0.2)] {
                let g = Microfacet::anisotropic(au, av, d);
                let (nt, np) = (4000, 256);
                let mut s = 0.0f64;
                for i in 0..nt {
                    // cos θ = 1 − t², t uniform: dense steps at the pole.
                    let t = (i as f64 + 0.5) / nt as f64;
                    let ct = 1.0 - t * t;
                    let st = (1.0 - ct * ct).max(0.0).sqrt();
                    for j in 0..np {
                        let phi = (j as f64 + 0.5) / np as f64 * 2.0 * std::f64::consts::PI;
                        let m = Vec3A::new(
                            (st * libm::cos(phi)) as f32,
                            (st * libm::sin(phi)) as f32,
                            ct as f32,
                        );
                        let dw = 2.0 * t / nt as f64 * 2.0 * std::f64::consts::PI / np as f64;
                        s += g.d(m) as f64 * ct * dw;
                    }
                }
                assert!((s - 1.0).abs() < 0.02, "{au} {av} {d:?}: {s}");
            }
        }
    }

    #[test]
    fn anisotropic_formulas_meet_the_isotropic_ones_at_equal_roughness() {
        for d in [Distribution::Ggx, Distribution::Beckmann] {
            let iso = Microfacet::new(0.3, d);
            for k in 0..20 {
                let th = k as f32 / 20.0 * 1.5;
                let w = Vec3A::new(libm::sinf(th) * 0.6, libm::sinf(th) * 0.8, libm::cosf(th));
                let (a, b) = (iso.d(w), iso.d_anisotropic(w));
                assert!(
                    (a - b).abs() <= 1e-4 * a.max(1.0),
                    "{d:?} D at {th}: {a} vs {b}"
                );
                let (a, b) = (iso.g1(w, Vec3A::Z), iso.g1_anisotropic(w));
                assert!((a - b).abs() <= 1e-4, "{d:?} G1 at {th}: {a} vs {b}");
            }
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
