//! BSDFs in the local shading frame (+z = shading normal, turned towards the viewer, so every
//! surface is two-sided for reflection; a transmitting BSDF samples `wi.z < 0`). `f` values
//! exclude the cosine. The dielectrics are in `dielectric.rs`, the principled BSDFs in
//! `principled.rs` and `principled_thin.rs`.
use crate::dielectric::{RoughDielectric, sample_smooth, sample_thin};
use crate::integrator::Frame;
use crate::microfacet::{Microfacet, fresnel_conductor, fresnel_dielectric};
use crate::plastic_table::PlasticTable;
use crate::pplastic::PPlastic;
use crate::principled::Principled;
use crate::principled_thin::PrincipledThin;
use crate::trig::sincos_quarter_pi;
use eyeadapt_scene::Distribution;
use glam::Vec3A;
use std::f32::consts::FRAC_1_PI;

#[derive(Clone, Copy, Debug)]
pub enum Bsdf {
    Diffuse {
        reflectance: Vec3A,
    },
    RoughConductor {
        ggx: Microfacet,
        eta: Vec3A,
        k: Vec3A,
        specular: Vec3A,
    },
    /// Perfect mirror (conductor with roughness 0).
    Mirror {
        eta: Vec3A,
        k: Vec3A,
        specular: Vec3A,
    },
    /// Microfacet coating over Lambert, Mitsuba's `roughplastic` (`nonlinear = false`): the
    /// diffuse base is divided by (1 − Fdr) and attenuated by the rough interface's
    /// transmittance T on the way in and out, both from the coating's [`PlasticTable`].
    Plastic {
        diffuse: Vec3A,
        ggx: Microfacet,
        eta: f32,
        inv_eta2: f32,
        spec_weight: f32,
        table: &'static PlasticTable,
    },
    /// Smooth glass; `eta` relative to the viewer's side (see `dielectric.rs`).
    Dielectric {
        eta: f32,
        r: Vec3A,
        t: Vec3A,
    },
    /// A thin pane; `eta` is the material's own (a pane looks the same from both sides).
    ThinDielectric {
        eta: f32,
        r: Vec3A,
        t: Vec3A,
    },
    RoughDielectric(RoughDielectric),
    /// Mitsuba's `principled`; it handles both sides itself.
    Principled(Principled),
    /// Mitsuba's `principledthin`.
    PrincipledThin(PrincipledThin),
    /// Mitsuba's `pplastic` without polarisation (`pplastic.rs`).
    PPlastic(PPlastic),
}

#[derive(Clone, Copy, Debug)]
pub struct BsdfSample {
    pub wi: Vec3A,
    /// BSDF value (without cosine); for delta lobes the value that makes `weight` right.
    pub f: Vec3A,
    pub pdf: f32,
    /// f · cos / pdf.
    pub weight: Vec3A,
    pub delta: bool,
}

impl BsdfSample {
    /// The sample `wi` of a non-delta lobe with density `pdf` and value `f()`; none where the
    /// density is zero or not finite (`f` is then not evaluated).
    #[inline]
    pub fn of_lobe(wi: Vec3A, pdf: f32, f: impl FnOnce() -> Vec3A) -> Option<BsdfSample> {
        if pdf <= 0.0 || !pdf.is_finite() {
            return None;
        }
        let f = f();
        Some(BsdfSample {
            wi,
            f,
            pdf,
            weight: f * (wi.z.abs() / pdf),
            delta: false,
        })
    }
}

fn fresnel_conductor3(c: f32, eta: Vec3A, k: Vec3A) -> Vec3A {
    Vec3A::new(
        fresnel_conductor(c, eta.x, k.x),
        fresnel_conductor(c, eta.y, k.y),
        fresnel_conductor(c, eta.z, k.z),
    )
}

/// Cosine-weighted hemisphere sample (concentric mapping).
pub fn cosine_hemisphere(u: [f32; 2]) -> Vec3A {
    let a = 2.0 * u[0] - 1.0;
    let b = 2.0 * u[1] - 1.0;
    // φ = π/4·(b/a), or π/2 − π/4·(a/b), whose cosine and sine are the sine and cosine of
    // π/4·(a/b).
    let (x, y) = if a == 0.0 && b == 0.0 {
        (0.0, 0.0)
    } else if a.abs() > b.abs() {
        let (s, c) = sincos_quarter_pi(b / a);
        (a * c, a * s)
    } else {
        let (s, c) = sincos_quarter_pi(a / b);
        (b * s, b * c)
    };
    // The disk point's radius is the larger of |a| and |b|: z from it needs no wait for the
    // division and the sine and cosine (the next ray's direction waits on this chain).
    let r = a.abs().max(b.abs());
    Vec3A::new(x, y, (1.0 - r * r).max(0.0).sqrt())
}

fn reflect(wo: Vec3A, m: Vec3A) -> Vec3A {
    2.0 * wo.dot(m) * m - wo
}

impl Bsdf {
    pub fn diffuse(reflectance: Vec3A) -> Bsdf {
        Bsdf::Diffuse { reflectance }
    }

    /// A microfacet conductor; `alpha` ≤ 1e-4 is a perfect mirror.
    pub fn conductor(
        alpha: f32,
        distribution: Distribution,
        eta: Vec3A,
        k: Vec3A,
        specular: Vec3A,
    ) -> Bsdf {
        if alpha <= 1e-4 {
            Bsdf::Mirror { eta, k, specular }
        } else {
            Bsdf::RoughConductor {
                ggx: Microfacet::new(alpha, distribution),
                eta,
                k,
                specular,
            }
        }
    }

    /// An anisotropic microfacet conductor (roughness `alpha_u` along the shading frame's +x,
    /// `alpha_v` along +y, each at least 1e-4); both ≤ 1e-4 is a perfect mirror.
    pub fn conductor_uv(
        alpha_u: f32,
        alpha_v: f32,
        distribution: Distribution,
        eta: Vec3A,
        k: Vec3A,
        specular: Vec3A,
    ) -> Bsdf {
        if alpha_u.max(alpha_v) <= 1e-4 {
            Bsdf::Mirror { eta, k, specular }
        } else {
            Bsdf::RoughConductor {
                ggx: Microfacet::anisotropic(alpha_u.max(1e-4), alpha_v.max(1e-4), distribution),
                eta,
                k,
                specular,
            }
        }
    }

    /// True when the BSDF depends on the azimuth around the normal (anisotropic roughness):
    /// its shading frame's +x must then follow ∂p/∂u.
    pub fn is_anisotropic(&self) -> bool {
        match self {
            Bsdf::RoughConductor { ggx, .. } => ggx.alpha != ggx.alpha_v,
            Bsdf::RoughDielectric(d) => d.md.alpha != d.md.alpha_v,
            Bsdf::PPlastic(p) => p.md.alpha != p.md.alpha_v,
            _ => false,
        }
    }

    /// The plastic over base `reflectance`; `table` holds the coating's transmittance and
    /// internal reflectance ([`PlasticTable::get`], computed once per material). `d_mean` is
    /// the base's mean reflectance over the surface, which steers lobe sampling.
    pub fn plastic(
        reflectance: Vec3A,
        alpha: f32,
        distribution: Distribution,
        ior: f32,
        table: &'static PlasticTable,
        d_mean: f32,
    ) -> Bsdf {
        Bsdf::Plastic {
            diffuse: reflectance / (1.0 - table.fdr),
            ggx: Microfacet::new(alpha, distribution),
            eta: ior,
            inv_eta2: 1.0 / (ior * ior),
            spec_weight: 1.0 / (1.0 + d_mean),
            table,
        }
    }

    /// True when the BSDF can send light through the surface: its samples may then have
    /// `wi.z < 0` (the far side of the shading frame), and light arrives from both sides. The
    /// match is exhaustive so that a new BSDF has to say.
    pub fn has_transmission(&self) -> bool {
        match self {
            Bsdf::Diffuse { .. }
            | Bsdf::RoughConductor { .. }
            | Bsdf::Mirror { .. }
            | Bsdf::Plastic { .. }
            | Bsdf::PPlastic(_) => false,
            Bsdf::Dielectric { .. } | Bsdf::ThinDielectric { .. } | Bsdf::RoughDielectric(_) => {
                true
            }
            Bsdf::Principled(p) => p.transmits(),
            Bsdf::PrincipledThin(p) => p.transmits(),
        }
    }

    /// The BSDF with its anisotropy turned to the surface's tangent ∂p/∂u (world space),
    /// projected into `frame` (the shading frame), as Mitsuba orients it; isotropic BSDFs are
    /// returned unchanged.
    #[inline]
    pub fn oriented(self, frame: &Frame, dpdu: Vec3A) -> Bsdf {
        let turn = |g: crate::principled_lobes::AnisoGgx| {
            let t = dpdu - frame.n * frame.n.dot(dpdu);
            let (c, s) = (t.dot(frame.s), t.dot(frame.t));
            let l = (c * c + s * s).sqrt();
            if l > 0.0 && l.is_finite() {
                g.turned(c / l, s / l)
            } else {
                g
            }
        };
        match self {
            Bsdf::Principled(mut p) if p.spec.is_anisotropic() => {
                p.spec = turn(p.spec);
                Bsdf::Principled(p)
            }
            Bsdf::PrincipledThin(mut p) if p.spec.is_anisotropic() => {
                p.spec = turn(p.spec);
                p.trans = turn(p.trans);
                Bsdf::PrincipledThin(p)
            }
            b => b,
        }
    }

    /// True when the BSDF is a pure delta lobe (no light sampling possible).
    pub fn is_delta(&self) -> bool {
        matches!(
            self,
            Bsdf::Mirror { .. } | Bsdf::Dielectric { .. } | Bsdf::ThinDielectric { .. }
        )
    }

    pub fn eval(&self, wo: Vec3A, wi: Vec3A) -> Vec3A {
        match self {
            Bsdf::RoughDielectric(d) => {
                return if wo.z > 0.0 {
                    d.eval(wo, wi)
                } else {
                    Vec3A::ZERO
                };
            }
            Bsdf::Principled(p) => return p.eval(wo, wi),
            Bsdf::PrincipledThin(p) => return p.eval(wo, wi),
            _ => {}
        }
        if let Bsdf::PPlastic(p) = self {
            return p.eval(wo, wi);
        }
        if wo.z <= 0.0 || wi.z <= 0.0 {
            return Vec3A::ZERO;
        }
        match *self {
            Bsdf::Diffuse { reflectance } => reflectance * FRAC_1_PI,
            Bsdf::Mirror { .. }
            | Bsdf::Dielectric { .. }
            | Bsdf::ThinDielectric { .. }
            | Bsdf::RoughDielectric(_)
            | Bsdf::Principled(_)
            | Bsdf::PrincipledThin(_)
            | Bsdf::PPlastic(_) => Vec3A::ZERO,
            Bsdf::RoughConductor {
                ggx,
                eta,
                k,
                specular,
            } => {
                let m = (wo + wi).normalize();
                let d = ggx.d(m);
                if d == 0.0 {
                    return Vec3A::ZERO;
                }
                let f = fresnel_conductor3(wi.dot(m), eta, k) * specular;
                f * (d * ggx.g(wi, wo, m) / (4.0 * wi.z * wo.z))
            }
            Bsdf::Plastic { table, .. } => {
                let m = (wo + wi).normalize();
                self.plastic_value(wo, wi, m, table.transmittance(wo.z))
            }
        }
    }

    /// The value of the diffuse lobe alone (reflection only; zero for BSDFs without one), for
    /// the WCAM re-render's `diffuse_only` mode (estimators.md §2.3). A Lambertian BSDF's is
    /// its [`Bsdf::eval`], bit for bit.
    pub fn eval_diffuse(&self, wo: Vec3A, wi: Vec3A) -> Vec3A {
        if wo.z <= 0.0 || wi.z <= 0.0 {
            return Vec3A::ZERO;
        }
        match *self {
            Bsdf::Diffuse { reflectance } => reflectance * FRAC_1_PI,
            Bsdf::Plastic {
                diffuse,
                inv_eta2,
                table,
                ..
            } => {
                let ti = table.transmittance(wi.z);
                let to = table.transmittance(wo.z);
                diffuse * (FRAC_1_PI * inv_eta2 * ti * to)
            }
            Bsdf::PPlastic(p) => p.eval_diffuse(wo, wi),
            Bsdf::Principled(p) => p.eval_diffuse(wo, wi),
            Bsdf::PrincipledThin(p) => p.eval_diffuse(wo, wi),
            Bsdf::RoughConductor { .. }
            | Bsdf::Mirror { .. }
            | Bsdf::Dielectric { .. }
            | Bsdf::ThinDielectric { .. }
            | Bsdf::RoughDielectric(_) => Vec3A::ZERO,
        }
    }

    /// A plastic's probability of sampling its specular lobe, from the coating's
    /// transmittance `to` towards wo.
    fn plastic_spec_prob(to: f32, spec_weight: f32) -> f32 {
        let ps = (1.0 - to) * spec_weight;
        let pd = to * (1.0 - spec_weight);
        ps / (ps + pd)
    }

    /// A plastic's density of `wi` (half vector `m`), given its specular probability `ps`.
    fn plastic_pdf(ggx: &Microfacet, wo: Vec3A, wi: Vec3A, m: Vec3A, ps: f32) -> f32 {
        let spec = ggx.pdf(wo, m) / (4.0 * wo.dot(m).abs().max(1e-12));
        ps * spec + (1.0 - ps) * wi.z * FRAC_1_PI
    }

    /// A `Plastic`'s value at `wi` (half vector `m`), given the coating's transmittance `to`
    /// towards wo.
    fn plastic_value(&self, wo: Vec3A, wi: Vec3A, m: Vec3A, to: f32) -> Vec3A {
        let Bsdf::Plastic {
            diffuse,
            ggx,
            eta,
            inv_eta2,
            table,
            ..
        } = *self
        else {
            unreachable!("plastic_value of a {self:?}")
        };
        let spec =
            fresnel_dielectric(wi.dot(m), eta) * ggx.d(m) * ggx.g(wi, wo, m) / (4.0 * wi.z * wo.z);
        let ti = table.transmittance(wi.z);
        Vec3A::splat(spec) + diffuse * (FRAC_1_PI * inv_eta2 * ti * to)
    }

    pub fn pdf(&self, wo: Vec3A, wi: Vec3A) -> f32 {
        match self {
            Bsdf::RoughDielectric(d) => return if wo.z > 0.0 { d.pdf(wo, wi) } else { 0.0 },
            Bsdf::Principled(p) => return p.pdf(wo, wi),
            Bsdf::PrincipledThin(p) => return p.pdf(wo, wi),
            _ => {}
        }
        if let Bsdf::PPlastic(p) = self {
            return p.pdf(wo, wi);
        }
        if wo.z <= 0.0 || wi.z <= 0.0 {
            return 0.0;
        }
        match *self {
            Bsdf::Diffuse { .. } => wi.z * FRAC_1_PI,
            Bsdf::Mirror { .. }
            | Bsdf::Dielectric { .. }
            | Bsdf::ThinDielectric { .. }
            | Bsdf::RoughDielectric(_)
            | Bsdf::Principled(_)
            | Bsdf::PrincipledThin(_)
            | Bsdf::PPlastic(_) => 0.0,
            Bsdf::RoughConductor { ggx, .. } => {
                let m = (wo + wi).normalize();
                ggx.pdf(wo, m) / (4.0 * wo.dot(m).abs().max(1e-12))
            }
            Bsdf::Plastic {
                ggx,
                table,
                spec_weight,
                ..
            } => {
                let ps = Self::plastic_spec_prob(table.transmittance(wo.z), spec_weight);
                let m = (wo + wi).normalize();
                Self::plastic_pdf(&ggx, wo, wi, m, ps)
            }
        }
    }

    /// Samples an incident direction. `u_lobe` picks a lobe, `u` places the direction.
    pub fn sample(&self, wo: Vec3A, u_lobe: f32, u: [f32; 2]) -> Option<BsdfSample> {
        if wo.z <= 0.0 {
            return None;
        }
        let wi = match *self {
            Bsdf::Diffuse { reflectance } => {
                // `eval` and `pdf` of the sample, without their dispatch.
                let wi = cosine_hemisphere(u);
                if wi.z <= 0.0 {
                    return None;
                }
                return BsdfSample::of_lobe(wi, wi.z * FRAC_1_PI, || reflectance * FRAC_1_PI);
            }
            Bsdf::Mirror { eta, k, specular } => {
                let wi = Vec3A::new(-wo.x, -wo.y, wo.z);
                let weight = fresnel_conductor3(wo.z, eta, k) * specular;
                return Some(BsdfSample {
                    wi,
                    f: weight / wi.z.max(1e-12),
                    pdf: 1.0,
                    weight,
                    delta: true,
                });
            }
            Bsdf::Dielectric { eta, r, t } => return Some(sample_smooth(wo, eta, r, t, u_lobe)),
            Bsdf::ThinDielectric { eta, r, t } => return Some(sample_thin(wo, eta, r, t, u_lobe)),
            Bsdf::RoughDielectric(d) => return d.sample(wo, u_lobe, u),
            Bsdf::Principled(p) => return p.sample(wo, u_lobe, u),
            Bsdf::PrincipledThin(p) => return p.sample(wo, u_lobe, u),
            Bsdf::PPlastic(p) => return p.sample(wo, u_lobe, u),
            Bsdf::RoughConductor { ggx, .. } => reflect(wo, ggx.sample(wo, u)),
            Bsdf::Plastic { .. } => return self.sample_plastic(wo, u_lobe, u),
        };
        if wi.z <= 0.0 {
            return None;
        }
        BsdfSample::of_lobe(wi, self.pdf(wo, wi), || self.eval(wo, wi))
    }

    /// [`Bsdf::sample`] of a `Plastic` (wo above the surface): its `pdf` and `eval`, bit for
    /// bit, with what they share computed once (the coating's transmittance towards `wo`,
    /// which the lobe choice, `pdf` and `eval` each evaluated, and the half vector).
    #[inline]
    fn sample_plastic(&self, wo: Vec3A, u_lobe: f32, u: [f32; 2]) -> Option<BsdfSample> {
        let Bsdf::Plastic {
            ggx,
            spec_weight,
            table,
            ..
        } = *self
        else {
            unreachable!("sample_plastic of a {self:?}")
        };
        let to = table.transmittance(wo.z);
        let ps = Self::plastic_spec_prob(to, spec_weight);
        let wi = if u_lobe < ps {
            reflect(wo, ggx.sample(wo, u))
        } else {
            cosine_hemisphere(u)
        };
        if wi.z <= 0.0 {
            return None;
        }
        let m = (wo + wi).normalize();
        let pdf = Self::plastic_pdf(&ggx, wo, wi, m, ps);
        BsdfSample::of_lobe(wi, pdf, || self.plastic_value(wo, wi, m, to))
    }
}

#[cfg(test)]
#[path = "bsdf_tests.rs"]
pub(crate) mod tests;
