//! The pieces both principled BSDFs (`principled.rs`, `principled_thin.rs`) are built from,
//! after Mitsuba 3's `principledhelpers.h` and Burley's 2012/2015 course notes: an anisotropic
//! GGX distribution turned to the surface's tangent, the GTR1 clearcoat distribution, Schlick's
//! Fresnel, and the Disney diffuse and sheen lobes. Local frame: the shading normal is +z.
use crate::trig::sincos_turns;
use glam::Vec3A;
use std::f32::consts::{FRAC_1_PI, PI};

/// Anisotropic GGX (Trowbridge–Reitz) with roughness `ax` along the tangent and `ay` across
/// it; the tangent is at angle φ (`cos`, `sin`) from the shading frame's x axis. Sampled by its
/// visible normals (Heitz 2018), as Mitsuba samples it.
#[derive(Clone, Copy, Debug)]
pub struct AnisoGgx {
    pub ax: f32,
    pub ay: f32,
    cos: f32,
    sin: f32,
}

impl AnisoGgx {
    /// Mitsuba's `calc_dist_params`: α = roughness², stretched by √(1 − 0.9·anisotropic)
    /// along the tangent and squeezed across it, at least 0.001 either way.
    pub fn principled(roughness: f32, anisotropic: f32) -> AnisoGgx {
        let r2 = roughness * roughness;
        let aspect = (1.0 - 0.9 * anisotropic).max(0.0).sqrt();
        AnisoGgx {
            ax: (r2 / aspect).max(0.001),
            ay: (r2 * aspect).max(0.001),
            cos: 1.0,
            sin: 0.0,
        }
    }

    /// The same distribution with its tangent along local direction (`cos`, `sin`).
    pub fn turned(self, cos: f32, sin: f32) -> AnisoGgx {
        AnisoGgx { cos, sin, ..self }
    }

    pub fn is_anisotropic(&self) -> bool {
        self.ax != self.ay
    }

    /// Into the distribution's own frame (tangent = x).
    #[inline]
    fn local(&self, v: Vec3A) -> Vec3A {
        Vec3A::new(
            self.cos * v.x + self.sin * v.y,
            -self.sin * v.x + self.cos * v.y,
            v.z,
        )
    }

    #[inline]
    fn shading(&self, v: Vec3A) -> Vec3A {
        Vec3A::new(
            self.cos * v.x - self.sin * v.y,
            self.sin * v.x + self.cos * v.y,
            v.z,
        )
    }

    pub fn d(&self, m: Vec3A) -> f32 {
        if m.z <= 0.0 {
            return 0.0;
        }
        let m = self.local(m);
        let (x, y) = (m.x / self.ax, m.y / self.ay);
        let t = x * x + y * y + m.z * m.z;
        let d = 1.0 / (PI * self.ax * self.ay * t * t);
        if d * m.z > 1e-20 { d } else { 0.0 }
    }

    /// Smith G1 of `v` for microfacet `m` (zero where `v` sees the facet's back).
    pub fn g1(&self, v: Vec3A, m: Vec3A) -> f32 {
        if v.dot(m) * v.z <= 0.0 {
            return 0.0;
        }
        let l = self.local(v);
        let xy = (self.ax * l.x).powi(2) + (self.ay * l.y).powi(2);
        if xy == 0.0 {
            return 1.0;
        }
        2.0 / (1.0 + (1.0 + xy / (l.z * l.z)).sqrt())
    }

    pub fn g(&self, wo: Vec3A, wi: Vec3A, m: Vec3A) -> f32 {
        self.g1(wo, m) * self.g1(wi, m)
    }

    /// Density of [`Self::sample`] over microfacet normals, seen from `wo` (`wo.z > 0`).
    pub fn pdf(&self, wo: Vec3A, m: Vec3A) -> f32 {
        if wo.z <= 0.0 {
            return 0.0;
        }
        self.d(m) * self.g1(wo, m) * wo.dot(m).abs() / wo.z
    }

    /// A visible normal seen from `wo` (`wo.z > 0`).
    pub fn sample(&self, wo: Vec3A, u: [f32; 2]) -> Vec3A {
        let w = self.local(wo);
        let vh = Vec3A::new(self.ax * w.x, self.ay * w.y, w.z).normalize();
        let lensq = vh.x * vh.x + vh.y * vh.y;
        let t1 = if lensq > 0.0 {
            Vec3A::new(-vh.y, vh.x, 0.0) / lensq.sqrt()
        } else {
            Vec3A::X
        };
        let t2 = vh.cross(t1);
        let r = u[0].sqrt();
        let (sin_phi, cos_phi) = sincos_turns(u[1]);
        let p1 = r * cos_phi;
        let s = 0.5 * (1.0 + vh.z);
        let p2 = (1.0 - s) * (1.0 - p1 * p1).max(0.0).sqrt() + s * r * sin_phi;
        let nh = t1 * p1 + t2 * p2 + vh * (1.0 - p1 * p1 - p2 * p2).max(0.0).sqrt();
        let m = Vec3A::new(self.ax * nh.x, self.ay * nh.y, nh.z.max(1e-6)).normalize();
        self.shading(m)
    }
}

/// Burley's GTR1 ("Generalized Trowbridge–Reitz", γ = 1) of the clearcoat, sampled by
/// D(m)·cos θm (its lobe is weak, so Mitsuba does not sample visible normals either).
#[derive(Clone, Copy, Debug)]
pub struct Gtr1 {
    pub alpha: f32,
}

impl Gtr1 {
    /// The clearcoat's roughness: 0.1 at gloss 0 down to 0.001 at gloss 1.
    pub fn clearcoat(gloss: f32) -> Gtr1 {
        Gtr1 {
            alpha: 0.1 + (0.001 - 0.1) * gloss,
        }
    }

    pub fn d(&self, m: Vec3A) -> f32 {
        let a2 = self.alpha * self.alpha;
        let d = (a2 - 1.0) / (PI * libm::logf(a2) * (1.0 + (a2 - 1.0) * m.z * m.z));
        if d * m.z > 1e-20 { d } else { 0.0 }
    }

    pub fn pdf(&self, m: Vec3A) -> f32 {
        if m.z < 0.0 { 0.0 } else { m.z * self.d(m) }
    }

    pub fn sample(&self, u: [f32; 2]) -> Vec3A {
        let phi = 2.0 * PI * u[0];
        let a2 = self.alpha * self.alpha;
        let cos2 = (1.0 - libm::powf(a2, 1.0 - u[1])) / (1.0 - a2);
        let sin = (1.0 - cos2).max(0.0).sqrt();
        let cos = cos2.max(0.0).sqrt();
        Vec3A::new(libm::cosf(phi) * sin, libm::sinf(phi) * sin, cos)
    }
}

/// The clearcoat's fixed Smith masking (isotropic GGX, α = 0.25) of `v` for facet `m`.
pub fn clearcoat_g1(v: Vec3A, m: Vec3A) -> f32 {
    if v.dot(m) * v.z <= 0.0 {
        return 0.0;
    }
    if v.z == 1.0 {
        return 1.0;
    }
    let c2 = v.z * v.z;
    let tan2 = (1.0 - c2) / c2;
    2.0 / (1.0 + (1.0 + 0.0625 * tan2).sqrt())
}

/// (1 − cos)⁵, clamped.
#[inline]
pub fn schlick_weight(cos: f32) -> f32 {
    let m = (1.0 - cos).clamp(0.0, 1.0);
    let m2 = m * m;
    m2 * m2 * m
}

/// The reflectance at normal incidence of an interface of relative IOR `eta`.
#[inline]
pub fn schlick_r0(eta: f32) -> f32 {
    let r = (eta - 1.0) / (eta + 1.0);
    r * r
}

/// Schlick's Fresnel for reflectance `r0` at incidence cosine `cos` (≥ 0) on an interface of
/// relative IOR `eta`; into a less dense medium it uses the refracted angle (1 beyond the
/// critical angle), as Mitsuba's `calc_schlick`.
#[inline]
pub fn schlick(r0: Vec3A, cos: f32, eta: f32) -> Vec3A {
    let w = if eta > 1.0 {
        schlick_weight(cos.abs())
    } else {
        let cos_t2 = 1.0 - (1.0 - cos * cos) / (eta * eta);
        schlick_weight(cos_t2.max(0.0).sqrt())
    };
    r0 + (Vec3A::ONE - r0) * w
}

/// `base` over its luminance `lum` (white when black): the tint of sheen and spec_tint.
#[inline]
pub fn tint(base: Vec3A, lum: f32) -> Vec3A {
    if lum > 0.0 { base / lum } else { Vec3A::ONE }
}

/// The Disney diffuse lobe without its weight: Lambert with Burley's grazing retro-reflection,
/// blended towards the Hanrahan–Krueger-like fake subsurface by `flatness`. `cos_o`, `cos_i`:
/// the two directions' cosines (> 0), `cos_d`: either one's with the half vector.
pub fn diffuse(
    base: Vec3A,
    roughness: f32,
    flatness: f32,
    cos_o: f32,
    cos_i: f32,
    cos_d: f32,
) -> Vec3A {
    let fo = schlick_weight(cos_i);
    let fi = schlick_weight(cos_o);
    let f_diff = (1.0 - 0.5 * fi) * (1.0 - 0.5 * fo);
    let rr = 2.0 * roughness * cos_d * cos_d;
    let f_retro = rr * (fo + fi + fo * fi * (rr - 1.0));
    let mut f = f_diff + f_retro;
    if flatness > 0.0 {
        let fss90 = rr / 2.0;
        let fss = (1.0 + (fss90 - 1.0) * fo) * (1.0 + (fss90 - 1.0) * fi);
        let f_ss = 1.25 * (fss * (1.0 / (cos_o + cos_i) - 0.5) + 0.5);
        f += (f_ss - f) * flatness;
    }
    base * (FRAC_1_PI * f)
}

/// The sheen lobe without its weight: Schlick's grazing term, tinted towards the base colour.
pub fn sheen(base: Vec3A, lum: f32, sheen_tint: f32, cos_d: f32) -> Vec3A {
    let c = Vec3A::ONE + (tint(base, lum) - Vec3A::ONE) * sheen_tint;
    c * schlick_weight(cos_d.abs())
}
