//! The rough coating's energy terms of Mitsuba's `roughplastic`, precomputed once per
//! (roughness, distribution, IOR): the external transmittance T(cos θ) — the light the rough
//! interface lets into the coating from direction θ, ∫ (1 − F(wi·m)) G1(wt, m) D_wi(m) dm
//! over the visible normals D_wi — tabulated at 64 evenly spaced cosines and interpolated
//! linearly, and the internal diffuse reflectance Fdr, the cosine-weighted mean of the
//! interface's reflectance seen from inside (with total internal reflection), averaged over
//! the same 64 cosines. Both integrals use Gauss–Legendre quadrature over the normal-sampling
//! square (32² nodes entering, 128² leaving), as Mitsuba does.
//!
//! Tables are interned: [`PlasticTable::get`] returns one `'static` table per distinct key, so
//! a [`crate::Bsdf`] carries a pointer, not the 64 values.
use crate::microfacet::{Microfacet, fresnel_refract};
use eyeadapt_scene::Distribution;
use glam::Vec3A;
use std::sync::Mutex;

/// Number of tabulated cosines (Mitsuba's `MI_ROUGH_TRANSMITTANCE_RES`).
pub const RES: usize = 64;

#[derive(Debug)]
pub struct PlasticTable {
    /// T at cos θ = k / (RES − 1) (the first at 1e-6).
    pub t_ext: [f32; RES],
    /// Internal diffuse reflectance of the rough interface.
    pub fdr: f32,
}

type Key = (u32, bool, u32);
static TABLES: Mutex<Vec<(Key, &'static PlasticTable)>> = Mutex::new(Vec::new());

impl PlasticTable {
    /// The table of a coating of roughness `alpha` and relative IOR `eta` (> 1), computed on
    /// first use and kept for the life of the process.
    pub fn get(alpha: f32, distribution: Distribution, eta: f32) -> &'static PlasticTable {
        let key = (
            alpha.to_bits(),
            distribution == Distribution::Beckmann,
            eta.to_bits(),
        );
        let mut tables = TABLES.lock().unwrap_or_else(|e| e.into_inner());
        if let Some((_, t)) = tables.iter().find(|(k, _)| *k == key) {
            return t;
        }
        let t: &'static PlasticTable =
            Box::leak(Box::new(PlasticTable::compute(alpha, distribution, eta)));
        tables.push((key, t));
        t
    }

    fn compute(alpha: f32, distribution: Distribution, eta: f32) -> PlasticTable {
        let md = Microfacet::new(alpha, distribution);
        let enter = gauss_legendre(32);
        let leave = gauss_legendre(128);
        let mut t_ext = [0.0; RES];
        let mut fdr = 0.0f64;
        for (k, t) in t_ext.iter_mut().enumerate() {
            let mu = (k as f32 / (RES - 1) as f32).max(1e-6);
            let wi = Vec3A::new((1.0 - mu * mu).max(0.0).sqrt(), 0.0, mu);
            *t = visible_integral(&md, wi, &enter, |m| transmitted(&md, wi, m, eta)) as f32;
            let r = visible_integral(&md, wi, &leave, |m| reflected(&md, wi, m, 1.0 / eta));
            fdr += r * mu as f64;
        }
        PlasticTable {
            t_ext,
            fdr: (2.0 * fdr / RES as f64) as f32,
        }
    }

    /// T at incidence cosine `cos` (in [0, 1]), interpolated linearly.
    #[inline]
    pub fn transmittance(&self, cos: f32) -> f32 {
        let x = cos.clamp(0.0, 1.0) * (RES - 1) as f32;
        let i = (x as usize).min(RES - 2);
        let f = x - i as f32;
        self.t_ext[i] + (self.t_ext[i + 1] - self.t_ext[i]) * f
    }
}

/// ∫ g(m) D_wi(m) dm over the visible normals of `wi`, by quadrature of the normal-sampling
/// square (nodes and weights on [-1, 1]), each sample weighted by D_wi / its sampling density
/// (1 where `md` samples visible normals).
fn visible_integral(
    md: &Microfacet,
    wi: Vec3A,
    (nodes, weights): &(Vec<f64>, Vec<f64>),
    g: impl Fn(Vec3A) -> f32,
) -> f64 {
    let mut sum = 0.0f64;
    for (x, wx) in nodes.iter().zip(weights) {
        for (y, wy) in nodes.iter().zip(weights) {
            let u = [(0.5 * x + 0.5) as f32, (0.5 * y + 0.5) as f32];
            let m = md.sample(wi, u);
            let pdf = md.pdf(wi, m);
            if pdf <= 0.0 || !pdf.is_finite() {
                continue;
            }
            let d_vis = md.g1(wi, m) * wi.dot(m).max(0.0) * md.d(m) / wi.z;
            let v = g(m) * d_vis / pdf;
            if v.is_finite() {
                sum += v as f64 * wx * wy * 0.25;
            }
        }
    }
    sum
}

/// (1 − F) G1 of the direction refracted at `m` into a medium of relative IOR `eta`.
fn transmitted(md: &Microfacet, wi: Vec3A, m: Vec3A, eta: f32) -> f32 {
    let c = wi.dot(m);
    let (f, cos_t) = fresnel_refract(c, eta);
    if c <= 0.0 || f >= 1.0 {
        return 0.0;
    }
    let wt = m * (c / eta - cos_t) - wi / eta;
    if wt.z >= 0.0 {
        return 0.0;
    }
    md.g1(wt, m) * (1.0 - f)
}

/// F G1 of the direction reflected at `m`, for relative IOR `eta` (total internal reflection
/// included).
fn reflected(md: &Microfacet, wi: Vec3A, m: Vec3A, eta: f32) -> f32 {
    let c = wi.dot(m);
    let wo = 2.0 * c * m - wi;
    if c <= 0.0 || wo.z <= 0.0 {
        return 0.0;
    }
    md.g1(wo, m) * fresnel_refract(c, eta).0
}

/// Gauss–Legendre nodes and weights on [-1, 1] (Newton iteration on Pₙ).
fn gauss_legendre(n: usize) -> (Vec<f64>, Vec<f64>) {
    let mut nodes = vec![0.0; n];
    let mut weights = vec![0.0; n];
    for i in 0..n {
        let mut x = (std::f64::consts::PI * (i as f64 + 0.75) / (n as f64 + 0.5)).cos();
        let mut dp = 1.0;
        for _ in 0..100 {
            let (mut p0, mut p1) = (1.0, x);
            for k in 2..=n {
                let p2 = ((2 * k - 1) as f64 * x * p1 - (k - 1) as f64 * p0) / k as f64;
                p0 = p1;
                p1 = p2;
            }
            dp = n as f64 * (x * p1 - p0) / (x * x - 1.0);
            let dx = p1 / dp;
            x -= dx;
            if dx.abs() < 1e-15 {
                break;
            }
        }
        nodes[i] = x;
        weights[i] = 2.0 / ((1.0 - x * x) * dp * dp);
    }
    (nodes, weights)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::microfacet::{fresnel_dielectric, internal_diffuse_reflectance};

    #[test]
    fn quadrature_integrates_polynomials_exactly() {
        let (x, w) = gauss_legendre(32);
        let i: f64 = x.iter().zip(&w).map(|(x, w)| w * x.powi(10)).sum();
        assert!((i - 2.0 / 11.0).abs() < 1e-12, "{i}");
        let s: f64 = w.iter().sum();
        assert!((s - 2.0).abs() < 1e-12);
    }

    #[test]
    fn nearly_smooth_coating_has_the_fresnel_terms() {
        for d in [Distribution::Ggx, Distribution::Beckmann] {
            let t = PlasticTable::compute(0.001, d, 1.5);
            for cos in [0.2f32, 0.5, 0.9] {
                let smooth = 1.0 - fresnel_dielectric(cos, 1.5);
                assert!((t.transmittance(cos) - smooth).abs() < 5e-3, "{d:?} {cos}");
            }
            // The 64-point mean is coarser than the midpoint rule of the smooth Fdr.
            assert!(
                (t.fdr - internal_diffuse_reflectance(1.5)).abs() < 0.01,
                "{}",
                t.fdr
            );
        }
    }

    #[test]
    fn rougher_coatings_transmit_less_at_normal_incidence_and_more_at_grazing() {
        let smooth = PlasticTable::compute(0.01, Distribution::Ggx, 1.5);
        let rough = PlasticTable::compute(0.5, Distribution::Ggx, 1.5);
        assert!(rough.transmittance(1.0) < smooth.transmittance(1.0));
        assert!(rough.transmittance(0.1) > smooth.transmittance(0.1));
        // Energy: transmittance never exceeds 1.
        assert!(rough.t_ext.iter().all(|&t| (0.0..=1.0).contains(&t)));
    }

    #[test]
    fn tables_are_interned() {
        let a = PlasticTable::get(0.2, Distribution::Ggx, 1.5);
        let b = PlasticTable::get(0.2, Distribution::Ggx, 1.5);
        assert!(std::ptr::eq(a, b));
    }
}
