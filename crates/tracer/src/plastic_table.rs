//! The rough coating's energy terms of Mitsuba's `roughplastic`, precomputed once per
//! (roughness, distribution, IOR): the external transmittance T(cos θ) — the light the rough
//! interface lets into the coating from direction θ, ∫ (1 − F(wi·m)) G1(wt, m) D_wi(m) dm
//! over the visible normals D_wi — tabulated at 64 evenly spaced cosines and interpolated
//! linearly, and the internal diffuse reflectance Fdr, the cosine-weighted mean of the
//! interface's reflectance seen from inside (with total internal reflection), averaged over
//! the same 64 cosines. Both integrals use Gauss–Legendre quadrature over the normal-sampling
//! square (32² nodes entering, 128² leaving), as Mitsuba does.
//!
//! A smooth coating (Mitsuba's `plastic`, alpha 0) has the smooth interface's terms instead:
//! T = 1 − F(cos θ), evaluated exactly, and Fdr from the fit Mitsuba's `plastic` uses
//! ([`smooth_internal_reflectance`]). The rough tables do not tend to these as alpha → 0: with
//! total internal reflection below the critical angle, the 64-cosine mean of the reflectance
//! undershoots the integral (0.752 against 0.764 at IOR 1.9, which makes the base 5 % darker).
//!
//! Tables are interned: [`PlasticTable::get`] returns one `'static` table per distinct key, so
//! a [`crate::Bsdf`] carries a pointer, not the 64 values.
use crate::microfacet::{Microfacet, fresnel_dielectric, fresnel_refract};
use crate::trig::sincos_turns;
use eyeadapt_scene::Distribution;
use glam::Vec3A;
use rayon::prelude::*;
use std::sync::Mutex;

/// Number of tabulated cosines (Mitsuba's `MI_ROUGH_TRANSMITTANCE_RES`).
pub const RES: usize = 64;

#[derive(Debug)]
pub struct PlasticTable {
    interface: Interface,
    /// Internal diffuse reflectance of the interface.
    pub fdr: f32,
}

// A table is built once per material and leaked, never moved: the smooth variant's unused
// bytes cost nothing, while a boxed array would add an indirection to every evaluation.
#[allow(clippy::large_enum_variant)]
#[derive(Debug)]
enum Interface {
    /// T at cos θ = k / (RES − 1) (the first at 1e-6).
    Rough([f32; RES]),
    /// The smooth interface of relative IOR `eta`: T = 1 − F(cos θ).
    Smooth { eta: f32 },
}

type Key = (u32, bool, u32);
static TABLES: Mutex<Vec<(Key, &'static PlasticTable)>> = Mutex::new(Vec::new());

impl PlasticTable {
    /// The table of a coating of roughness `alpha` (0: smooth) and relative IOR `eta` (> 1),
    /// computed on first use and kept for the life of the process.
    pub fn get(alpha: f32, distribution: Distribution, eta: f32) -> &'static PlasticTable {
        let key = (
            alpha.to_bits(),
            distribution == Distribution::Beckmann,
            eta.to_bits(),
        );
        let find = |tables: &[(Key, &'static PlasticTable)]| {
            tables.iter().find(|(k, _)| *k == key).map(|(_, t)| *t)
        };
        let lock = || TABLES.lock().unwrap_or_else(|e| e.into_inner());
        if let Some(t) = find(&lock()) {
            return t;
        }
        // Computed without the lock (it runs on the thread pool, whose workers may be the ones
        // asking for another table); a thread that lost a race returns the winner's table,
        // which has the same values.
        let computed = PlasticTable::compute(alpha, distribution, eta);
        let mut tables = lock();
        if let Some(t) = find(&tables) {
            return t;
        }
        let t: &'static PlasticTable = Box::leak(Box::new(computed));
        tables.push((key, t));
        t
    }

    fn compute(alpha: f32, distribution: Distribution, eta: f32) -> PlasticTable {
        if alpha == 0.0 {
            return PlasticTable {
                interface: Interface::Smooth { eta },
                fdr: smooth_internal_reflectance(eta),
            };
        }
        let md = Microfacet::new(alpha, distribution);
        let enter = Square::new(32);
        let leave = Square::new(128);
        // The 64 cosines in parallel (a rough plastic's set-up was 200 M instructions on one
        // thread, 7 % of the suite's three-rooms process); Fdr is summed in their order.
        let rows: Vec<(f32, f64)> = (0..RES)
            .into_par_iter()
            .map(|k| {
                let mu = (k as f32 / (RES - 1) as f32).max(1e-6);
                let wi = Vec3A::new((1.0 - mu * mu).max(0.0).sqrt(), 0.0, mu);
                let t = visible_integral(&md, wi, &enter, |m| transmitted(&md, wi, m, eta));
                let r = visible_integral(&md, wi, &leave, |m| reflected(&md, wi, m, 1.0 / eta));
                (t as f32, r * mu as f64)
            })
            .collect();
        let mut t_ext = [0.0; RES];
        let mut fdr = 0.0f64;
        for (t, (tk, rk)) in t_ext.iter_mut().zip(rows) {
            *t = tk;
            fdr += rk;
        }
        PlasticTable {
            interface: Interface::Rough(t_ext),
            fdr: (2.0 * fdr / RES as f64) as f32,
        }
    }

    /// T at incidence cosine `cos` (in [0, 1]): the rough table interpolated linearly, or the
    /// smooth interface's 1 − F.
    #[inline]
    pub fn transmittance(&self, cos: f32) -> f32 {
        match &self.interface {
            Interface::Rough(t) => {
                let x = cos.clamp(0.0, 1.0) * (RES - 1) as f32;
                let i = (x as usize).min(RES - 2);
                let f = x - i as f32;
                t[i] + (t[i + 1] - t[i]) * f
            }
            Interface::Smooth { eta } => 1.0 - fresnel_dielectric(cos, *eta),
        }
    }
}

/// Internal diffuse reflectance of a smooth interface of relative IOR `eta` (> 1) by Egan and
/// Hilgeman's (1973) fit, which Mitsuba's smooth `plastic` uses (its
/// `fresnel_diffuse_reflectance(1 / eta)`): within 0.1 % of the integral up to IOR 1.5 and
/// 0.6 % up to 2, and what Mitsuba renders beyond.
pub fn smooth_internal_reflectance(eta: f32) -> f32 {
    let n = eta as f64;
    (-1.4399 / (n * n) + 0.7099 / n + 0.6681 + 0.0636 * n) as f32
}

/// The normal-sampling square's Gauss–Legendre nodes (per axis, mapped to [0, 1]) and
/// weights (on [-1, 1]), with what sampling computes from one coordinate alone: the disk
/// radius √u₀ and the azimuth's cosine and sine for visible GGX normals.
struct Square {
    u: Vec<f32>,
    weights: Vec<f64>,
    radius: Vec<f32>,
    azimuth: Vec<(f32, f32)>,
}

impl Square {
    fn new(n: usize) -> Square {
        let (nodes, weights) = gauss_legendre(n);
        let u: Vec<f32> = nodes.iter().map(|x| (0.5 * x + 0.5) as f32).collect();
        Square {
            radius: u.iter().map(|u| u.sqrt()).collect(),
            azimuth: u
                .iter()
                .map(|&u| {
                    // The azimuth as `Microfacet::sample_visible` computes it.
                    let (sin_phi, cos_phi) = sincos_turns(u);
                    (cos_phi, sin_phi)
                })
                .collect(),
            u,
            weights,
        }
    }
}

/// ∫ g(m) D_wi(m) dm over the visible normals of `wi`, by quadrature of the normal-sampling
/// square, each sample weighted by D_wi / its sampling density (1 where `md` samples visible
/// normals).
///
/// For GGX the work that depends on `wi` or on one coordinate alone is done once (the
/// sampling frame, G1(wi), the radius and azimuth), and D_wi, which is the sampling density
/// operation for operation, is not evaluated twice: the sum is [`sampled_integral`]'s, bit for
/// bit, at about half the instructions (setting up a scene with a rough plastic cost as much
/// as rendering a 64-pixel-wide preview of it).
fn visible_integral(md: &Microfacet, wi: Vec3A, sq: &Square, g: impl Fn(Vec3A) -> f32) -> f64 {
    if md.beckmann {
        return sampled_integral(md, wi, sq, g);
    }
    let frame = md.visible_frame(wi);
    let g1_wi = md.g1_unmasked(wi);
    let mut sum = 0.0f64;
    for (&r, wx) in sq.radius.iter().zip(&sq.weights) {
        for (&(cos_phi, sin_phi), wy) in sq.azimuth.iter().zip(&sq.weights) {
            let m = md.visible_normal(&frame, r, cos_phi, sin_phi);
            let pdf = md.visible_pdf(wi, g1_wi, m);
            // `pdf <= 0 || !pdf.is_finite()` (NaN included), in two comparisons.
            if !(pdf > 0.0 && pdf < f32::INFINITY) {
                continue;
            }
            // D_wi here is the density's own expression: the same bits.
            let d_vis = pdf;
            let v = g(m) * d_vis / pdf;
            if v.is_finite() {
                sum += v as f64 * wx * wy * 0.25;
            }
        }
    }
    sum
}

/// [`visible_integral`] through [`Microfacet::sample`] and [`Microfacet::pdf`] at each node:
/// any distribution.
fn sampled_integral(md: &Microfacet, wi: Vec3A, sq: &Square, g: impl Fn(Vec3A) -> f32) -> f64 {
    let mut sum = 0.0f64;
    for (&u0, wx) in sq.u.iter().zip(&sq.weights) {
        for (&u1, wy) in sq.u.iter().zip(&sq.weights) {
            let m = md.sample(wi, [u0, u1]);
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
        let mut x = libm::cos(std::f64::consts::PI * (i as f64 + 0.75) / (n as f64 + 0.5));
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

    /// Mitsuba's smooth `plastic`: 1 − F exactly, and Fdr of Egan and Hilgeman's fit (Mitsuba
    /// 3.9.1's `fresnel_diffuse_reflectance(1 / eta)`: 0.596811 at 1.5, 0.763707 at 1.9),
    /// close to the integral. The nearly smooth rough table's 64-cosine Fdr is not (0.752 at
    /// 1.9, which left matpreview's base 5 % darker).
    #[test]
    fn smooth_coating_has_the_smooth_interface_terms() {
        for (eta, mitsuba) in [(1.5f32, 0.596811f32), (1.9, 0.763707)] {
            let t = PlasticTable::get(0.0, Distribution::Ggx, eta);
            for cos in [0.0f32, 0.05, 0.2, 0.5, 0.77, 0.9, 1.0] {
                assert_eq!(t.transmittance(cos), 1.0 - fresnel_dielectric(cos, eta));
            }
            assert!((t.fdr - mitsuba).abs() < 1e-5, "{eta}: {}", t.fdr);
            let exact = internal_diffuse_reflectance(eta);
            assert!(
                (t.fdr / exact - 1.0).abs() < 0.006,
                "{eta}: {} vs {exact}",
                t.fdr
            );
        }
        let nearly = PlasticTable::compute(0.01, Distribution::Ggx, 1.9);
        assert!((nearly.fdr - 0.752).abs() < 1e-3, "{}", nearly.fdr);
    }

    #[test]
    fn rougher_coatings_transmit_less_at_normal_incidence_and_more_at_grazing() {
        let smooth = PlasticTable::compute(0.01, Distribution::Ggx, 1.5);
        let rough = PlasticTable::compute(0.5, Distribution::Ggx, 1.5);
        assert!(rough.transmittance(1.0) < smooth.transmittance(1.0));
        assert!(rough.transmittance(0.1) > smooth.transmittance(0.1));
        // Energy: transmittance never exceeds 1.
        let Interface::Rough(t) = &rough.interface else {
            panic!("alpha 0.5 is rough")
        };
        assert!(t.iter().all(|&t| (0.0..=1.0).contains(&t)));
    }

    /// The GGX shortcut (work per direction and per coordinate hoisted, D_wi taken from the
    /// density) must not move a bit of the tables, which every rough plastic's image depends
    /// on: it is checked against node-by-node sampling for rough and nearly smooth coatings,
    /// grazing to normal incidence, both integrands.
    #[test]
    fn ggx_quadrature_is_the_sampled_one_bit_for_bit() {
        let sq = Square::new(32);
        for alpha in [0.003f32, 0.1, 0.35, 1.0] {
            let md = Microfacet::new(alpha, Distribution::Ggx);
            for mu in [1e-6f32, 0.05, 0.3, 0.77, 1.0] {
                let wi = Vec3A::new((1.0 - mu * mu).max(0.0).sqrt(), 0.0, mu);
                let t = |m| transmitted(&md, wi, m, 1.5);
                let r = |m| reflected(&md, wi, m, 1.0 / 1.9);
                let (a, b) = (
                    visible_integral(&md, wi, &sq, t),
                    sampled_integral(&md, wi, &sq, t),
                );
                assert_eq!(
                    a.to_bits(),
                    b.to_bits(),
                    "T: alpha {alpha}, cos {mu}: {a} vs {b}"
                );
                assert!(a > 0.0);
                let (a, b) = (
                    visible_integral(&md, wi, &sq, r),
                    sampled_integral(&md, wi, &sq, r),
                );
                assert_eq!(
                    a.to_bits(),
                    b.to_bits(),
                    "R: alpha {alpha}, cos {mu}: {a} vs {b}"
                );
            }
        }
    }

    #[test]
    fn tables_are_interned() {
        let a = PlasticTable::get(0.2, Distribution::Ggx, 1.5);
        let b = PlasticTable::get(0.2, Distribution::Ggx, 1.5);
        assert!(std::ptr::eq(a, b));
    }
}
