//! Mitsuba 3's `principledthin` at one hit, in the local shading frame on the viewer's side
//! (`wo.z > 0`; the sheet is the same from both sides): the principled's diffuse and sheen
//! weighted (1 − spec_trans)(1 − diff_trans), a Lambertian transmission weighted
//! (1 − spec_trans)·diff_trans, and, weighted spec_trans, a GGX reflection and a GGX
//! transmission that leaves undeflected (the reflection mirrored through the sheet) with its
//! roughness scaled by (0.65 η − 0.35) (Burley 2015, Fig. 15). `diff_trans` here is half the
//! scene's (Mitsuba's range is [0, 2]).
//!
//! Lobes are picked as Mitsuba picks them: the two specular ones with spec_trans/2 each, the
//! two diffuse ones with their weights.
use crate::bsdf::{BsdfSample, cosine_hemisphere};
use crate::emitter::luminance;
use crate::microfacet::fresnel_refract;
use crate::principled_lobes::{AnisoGgx, diffuse, schlick, schlick_r0, sheen, tint};
use eyeadapt_scene::{Param, Rgb};
use glam::Vec3A;
use std::f32::consts::FRAC_1_PI;

#[derive(Clone, Copy, Debug)]
pub struct PrincipledThin {
    pub base: Vec3A,
    /// The reflection's distribution and the transmission's (rougher or smoother by η).
    pub spec: AnisoGgx,
    pub trans: AnisoGgx,
    pub roughness: f32,
    pub spec_tint: f32,
    pub sheen: f32,
    pub sheen_tint: f32,
    pub spec_trans: f32,
    pub flatness: f32,
    /// Half the scene's `diff_trans`, in [0, 1].
    pub diff_trans: f32,
    pub eta: f32,
}

/// `wi` mirrored to the viewer's side (a transmission is a reflection through the sheet).
#[inline]
fn mirrored(wi: Vec3A) -> Vec3A {
    Vec3A::new(wi.x, wi.y, wi.z.abs())
}

impl PrincipledThin {
    /// The scene's thin principled at a hit whose parameters `rgb` and `number` evaluate.
    pub fn at(
        p: &eyeadapt_scene::PrincipledThin,
        rgb: impl Fn(Param<Rgb>) -> Vec3A,
        number: impl Fn(Param<f32>) -> f32,
    ) -> PrincipledThin {
        let w = |x| number(x).clamp(0.0, 1.0);
        let roughness = w(p.roughness);
        let anisotropic = w(p.anisotropic);
        // A texture's IOR is kept away from 0 (the scene's constants are positive).
        let eta = number(p.eta).max(1e-3);
        PrincipledThin {
            base: rgb(p.base_color).max(Vec3A::ZERO),
            spec: AnisoGgx::principled(roughness, anisotropic),
            trans: AnisoGgx::principled(Self::trans_roughness(roughness, eta), anisotropic),
            roughness,
            spec_tint: w(p.spec_tint),
            sheen: w(p.sheen),
            sheen_tint: w(p.sheen_tint),
            spec_trans: w(p.spec_trans),
            flatness: w(p.flatness),
            diff_trans: (0.5 * number(p.diff_trans)).clamp(0.0, 1.0),
            eta,
        }
    }

    /// The transmission distribution's roughness for a sheet of IOR `eta`.
    pub fn trans_roughness(roughness: f32, eta: f32) -> f32 {
        (0.65 * eta - 0.35) * roughness
    }

    pub fn transmits(&self) -> bool {
        self.spec_trans > 0.0 || self.diff_trans > 0.0
    }

    /// The probabilities of the specular reflection, specular transmission and diffuse
    /// reflection (the rest is the diffuse transmission); they sum to 1.
    #[inline]
    fn lobe_probs(&self) -> (f32, f32, f32) {
        let st = self.spec_trans;
        (0.5 * st, 0.5 * st, (1.0 - st) * (1.0 - self.diff_trans))
    }

    /// BSDF value (without cosine).
    pub fn eval(&self, wo: Vec3A, wi: Vec3A) -> Vec3A {
        if wo.z <= 0.0 || wi.z == 0.0 {
            return Vec3A::ZERO;
        }
        let st = self.spec_trans;
        let dt = self.diff_trans;
        let wh = (wo + mirrored(wi)).normalize_or_zero();
        let (dot_o, dot_i) = (wo.dot(wh), wi.dot(wh));
        let f = fresnel_refract(dot_o, self.eta).0;
        let cos_i = wi.z.abs();
        let mut v = Vec3A::ZERO;
        if wi.z < 0.0 {
            if st > 0.0 && dot_o > 0.0 && dot_i < 0.0 {
                let dg = self.trans.d(wh) * self.trans.g(wo, wi, wh);
                v += self.base * (st * (1.0 - f) * dg / (4.0 * wo.z * cos_i));
            }
            if st < 1.0 && dt > 0.0 {
                v += self.base * ((1.0 - st) * dt * FRAC_1_PI);
            }
            return v;
        }
        if st > 0.0 && dot_o > 0.0 && dot_i > 0.0 {
            let mut fr = Vec3A::splat(f);
            if self.spec_tint > 0.0 {
                let r0 = tint(self.base, luminance(self.base)) * schlick_r0(self.eta);
                fr += (schlick(r0, dot_o, self.eta) - fr) * self.spec_tint;
            }
            let dg = self.spec.d(wh) * self.spec.g(wo, wi, wh);
            v += fr * (st * dg / (4.0 * wo.z * wi.z));
        }
        if st < 1.0 && dt < 1.0 {
            let w = (1.0 - st) * (1.0 - dt);
            v += w * diffuse(self.base, self.roughness, self.flatness, wo.z, wi.z, dot_i);
            if self.sheen > 0.0 {
                v += (w * self.sheen)
                    * sheen(self.base, luminance(self.base), self.sheen_tint, dot_i);
            }
        }
        v
    }

    /// The diffuse reflection lobe alone, without sheen.
    pub fn eval_diffuse(&self, wo: Vec3A, wi: Vec3A) -> Vec3A {
        let (st, dt) = (self.spec_trans, self.diff_trans);
        if wo.z <= 0.0 || wi.z <= 0.0 || st >= 1.0 || dt >= 1.0 {
            return Vec3A::ZERO;
        }
        let wh = (wo + mirrored(wi)).normalize_or_zero();
        let w = (1.0 - st) * (1.0 - dt);
        w * diffuse(
            self.base,
            self.roughness,
            self.flatness,
            wo.z,
            wi.z,
            wi.dot(wh),
        )
    }

    /// Density of [`Self::sample`] over solid angle.
    pub fn pdf(&self, wo: Vec3A, wi: Vec3A) -> f32 {
        if wo.z <= 0.0 || wi.z == 0.0 {
            return 0.0;
        }
        let (pr, pt, pd) = self.lobe_probs();
        let wr = mirrored(wi);
        let wh = (wo + wr).normalize_or_zero();
        let (dot_o, dot_i) = (wo.dot(wh), wi.dot(wh));
        let jacobian = 1.0 / (4.0 * wr.dot(wh).abs());
        if wi.z > 0.0 {
            let mut p = pd * wi.z * FRAC_1_PI;
            if pr > 0.0 && dot_o > 0.0 && dot_i > 0.0 {
                p += pr * self.spec.pdf(wo, wh) * jacobian;
            }
            p
        } else {
            let mut p = (1.0 - pr - pt - pd).max(0.0) * -wi.z * FRAC_1_PI;
            if pt > 0.0 && dot_o > 0.0 && dot_i < 0.0 {
                p += pt * self.trans.pdf(wo, wh) * jacobian;
            }
            p
        }
    }

    /// Picks a lobe with `u_lobe` (specular reflection, specular transmission, diffuse
    /// reflection, diffuse transmission, in Mitsuba's order) and places it with `u`.
    pub fn sample(&self, wo: Vec3A, u_lobe: f32, u: [f32; 2]) -> Option<BsdfSample> {
        if wo.z <= 0.0 {
            return None;
        }
        let (pr, pt, pd) = self.lobe_probs();
        let wi = if u_lobe < pr + pt {
            let reflect = u_lobe < pr;
            let md = if reflect { self.spec } else { self.trans };
            let m = md.sample(wo, u);
            let c = wo.dot(m);
            let r = 2.0 * c * m - wo;
            if c <= 0.0 || r.z <= 0.0 {
                return None;
            }
            if reflect {
                r
            } else {
                // Mitsuba's compatibility: the facet must face away from the sheet's far side.
                let t = Vec3A::new(r.x, r.y, -r.z);
                if t.dot(m) >= 0.0 {
                    return None;
                }
                t
            }
        } else if u_lobe < pr + pt + pd {
            cosine_hemisphere(u)
        } else {
            -cosine_hemisphere(u)
        };
        if wi.z == 0.0 {
            return None;
        }
        BsdfSample::of_lobe(wi, self.pdf(wo, wi), || self.eval(wo, wi))
    }
}
