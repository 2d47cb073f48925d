//! Tests of every BSDF: sampling against evaluation (a χ² test over a binned sphere, as
//! Mitsuba's test suite does, and the sampled estimate of the albedo against a brute-force
//! integral), the white-furnace energy bound, reciprocity, and R + T = 1 for smooth glass;
//! anisotropic roughness and `pplastic` among them.
use super::*;
use crate::dielectric::RoughDielectric;
use crate::plastic_table::PlasticTable;
use crate::pplastic::PPlastic;
use crate::sampler::{SampleStream, hash_key};
use std::f32::consts::PI;

fn rough_glass(alpha: f32, d: Distribution, eta: f32) -> Bsdf {
    Bsdf::RoughDielectric(RoughDielectric {
        md: Microfacet::new(alpha, d),
        eta,
        r: Vec3A::ONE,
        t: Vec3A::ONE,
    })
}

/// Every non-delta BSDF, with both distributions and both sides of glass.
fn smooth_lobed() -> Vec<Bsdf> {
    let mut v = vec![Bsdf::diffuse(Vec3A::new(0.8, 0.5, 0.2))];
    for d in [Distribution::Ggx, Distribution::Beckmann] {
        v.push(Bsdf::conductor(
            0.3,
            d,
            Vec3A::new(0.2, 0.9, 1.1),
            Vec3A::new(3.9, 2.4, 2.1),
            Vec3A::ONE,
        ));
        v.push(Bsdf::conductor(
            0.05,
            d,
            Vec3A::splat(1.5),
            Vec3A::splat(3.0),
            Vec3A::ONE,
        ));
        v.push(Bsdf::plastic(
            Vec3A::new(0.5, 0.3, 0.1),
            0.2,
            d,
            1.5,
            PlasticTable::get(0.2, d, 1.5),
            0.3,
        ));
        v.push(rough_glass(0.3, d, 1.5));
        v.push(rough_glass(0.3, d, 1.0 / 1.5));
        v.push(rough_glass(0.08, d, 1.33));
        // Anisotropic roughness, both ways round.
        v.push(Bsdf::conductor_uv(
            0.05,
            0.4,
            d,
            Vec3A::new(0.2, 0.9, 1.1),
            Vec3A::new(3.9, 2.4, 2.1),
            Vec3A::ONE,
        ));
        v.push(Bsdf::conductor_uv(
            0.5,
            0.1,
            d,
            Vec3A::splat(1.5),
            Vec3A::splat(3.0),
            Vec3A::ONE,
        ));
        for eta in [1.5, 1.0 / 1.5] {
            v.push(Bsdf::RoughDielectric(RoughDielectric {
                md: Microfacet::anisotropic(0.1, 0.35, d),
                eta,
                r: Vec3A::ONE,
                t: Vec3A::ONE,
            }));
        }
        // pplastic, with the sampling weights of a dark base (mostly specular) and of a
        // bright one, isotropic and not.
        for (md, diffuse) in [
            (Microfacet::new(0.06, d), Vec3A::new(0.05, 0.03, 0.1)),
            (Microfacet::new(0.3, d), Vec3A::new(0.9, 0.8, 0.7)),
            (Microfacet::anisotropic(0.3, 0.08, d), Vec3A::splat(0.5)),
        ] {
            let p = PPlastic::spec_prob((diffuse.x + diffuse.y + diffuse.z) / 3.0, 1.0);
            v.push(Bsdf::PPlastic(PPlastic::new(
                md,
                diffuse,
                Vec3A::ONE,
                1.49,
                p,
            )));
        }
    }
    v
}

/// pplastic without a specular lobe is the Fresnel-attenuated Lambertian alone, sampled by
/// the cosine only (Mitsuba's weight s / (d + s) = 0).
#[test]
fn pplastic_without_specular_is_its_attenuated_base() {
    let d = Vec3A::new(0.05, 0.03, 0.1);
    let md = Microfacet::new(0.06, Distribution::Beckmann);
    let p = Bsdf::PPlastic(PPlastic::new(
        md,
        d,
        Vec3A::ZERO,
        1.49,
        PPlastic::spec_prob(0.06, 0.0),
    ));
    let (wo, wi) = (wo(), Vec3A::new(-0.3, 0.2, 0.93).normalize());
    let f = p.eval(wo, wi);
    let t = (1.0 - fresnel_dielectric(wo.z, 1.49)) * (1.0 - fresnel_dielectric(wi.z, 1.49));
    assert!((f - d * t * FRAC_1_PI).abs().max_element() < 1e-7, "{f}");
    assert!((p.pdf(wo, wi) - wi.z * FRAC_1_PI).abs() < 1e-6);
}

/// Anisotropic roughness is laid out along the frame's axes: turning both directions by 90°
/// about the normal is the same as swapping alpha_u and alpha_v, and equal roughness is
/// the isotropic BSDF.
#[test]
fn anisotropy_follows_the_frame_axes() {
    let rot = |w: Vec3A| Vec3A::new(-w.y, w.x, w.z);
    let key = hash_key(&[5]);
    for d in [Distribution::Ggx, Distribution::Beckmann] {
        let conductor = |au, av| {
            Bsdf::conductor_uv(au, av, d, Vec3A::splat(0.2), Vec3A::splat(3.0), Vec3A::ONE)
        };
        let (a, b) = (conductor(0.05, 0.4), conductor(0.4, 0.05));
        let (iso, iso_uv) = (
            conductor(0.2, 0.2),
            Bsdf::conductor(0.2, d, Vec3A::splat(0.2), Vec3A::splat(3.0), Vec3A::ONE),
        );
        let mut differs = false;
        for i in 0..500 {
            let mut s = SampleStream::new(key, i);
            let wo = cosine_hemisphere(s.next_2d());
            let wi = cosine_hemisphere(s.next_2d());
            let (fa, fb) = (a.eval(wo, wi), b.eval(rot(wo), rot(wi)));
            assert!(
                (fa - fb).abs().max_element() <= 1e-3 * fa.max_element().max(1.0),
                "{d:?}: {fa} vs {fb}"
            );
            let (pa, pb) = (a.pdf(wo, wi), b.pdf(rot(wo), rot(wi)));
            assert!((pa - pb).abs() <= 1e-3 * pa.max(1.0), "{d:?}: {pa} vs {pb}");
            differs |= (a.eval(wo, wi) - b.eval(wo, wi)).abs().max_element() > 1e-2;
            let (f0, f1) = (iso.eval(wo, wi), iso_uv.eval(wo, wi));
            assert!((f0 - f1).abs().max_element() <= 1e-4 * f0.max_element().max(1.0));
        }
        assert!(differs, "{d:?}: alpha_u and alpha_v must matter");
    }
}

fn wo() -> Vec3A {
    Vec3A::new(0.5, 0.1, 0.86).normalize()
}

/// `f` times eta² where it transmits: the importance (not radiance) weight, which no BSDF
/// may make exceed 1 on average.
fn importance(b: &Bsdf, wi: Vec3A, w: Vec3A) -> Vec3A {
    match b {
        Bsdf::RoughDielectric(d) if wi.z < 0.0 => w * d.eta * d.eta,
        Bsdf::Dielectric { eta, .. } if wi.z < 0.0 => w * eta * eta,
        _ => w,
    }
}

/// "Sample matches eval": the importance-sampled albedo equals a brute-force uniform-sphere
/// integral of eval·|cos|, the sampled pdf equals the evaluated one, and no BSDF creates
/// energy (white furnace).
#[test]
fn sampling_is_consistent_with_eval_and_pdf() {
    let wo = wo();
    for b in smooth_lobed() {
        let n = 1 << 16;
        let mut sampled = Vec3A::ZERO;
        let mut uniform = Vec3A::ZERO;
        let mut energy = Vec3A::ZERO;
        let key = hash_key(&[7]);
        for i in 0..n {
            let mut s = SampleStream::new(key, i);
            let ul = s.next_1d();
            let u = s.next_2d();
            if let Some(bs) = b.sample(wo, ul, u) {
                sampled += bs.weight;
                energy += importance(&b, bs.wi, bs.weight);
                let pdf = b.pdf(wo, bs.wi);
                assert!((pdf - bs.pdf).abs() <= 1e-3 * pdf.max(1.0), "{b:?}");
            }
            let uu = s.next_2d();
            let z = 2.0 * uu[0] - 1.0;
            let r = (1.0 - z * z).max(0.0).sqrt();
            let phi = 2.0 * PI * uu[1];
            let wi = Vec3A::new(r * libm::cosf(phi), r * libm::sinf(phi), z);
            uniform += b.eval(wo, wi) * wi.z.abs() * 4.0 * PI;
        }
        let sampled = sampled / n as f32;
        let uniform = uniform / n as f32;
        let energy = energy / n as f32;
        let rel = ((sampled - uniform).abs() / uniform.max(Vec3A::splat(1e-3))).max_element();
        assert!(rel < 0.03, "{b:?}: sampled {sampled} vs uniform {uniform}");
        assert!(
            energy.max_element() <= 1.0 + 2e-3,
            "{b:?} creates energy: {energy}"
        );
    }
}

/// A plastic's sample carries exactly its `pdf` and `eval` (the sampling path shares their
/// intermediate values instead of calling them): smooth and rough coatings, head-on to
/// grazing, both lobes.
#[test]
fn plastic_samples_carry_pdf_and_eval_bit_for_bit() {
    let base = Vec3A::new(0.94, 0.271, 0.361);
    let smooth = PlasticTable::get(0.0, Distribution::Ggx, 1.9);
    let rough = PlasticTable::get(0.2, Distribution::Beckmann, 1.5);
    let plastics = [
        Bsdf::plastic(base, 0.01, Distribution::Ggx, 1.9, smooth, 0.5),
        Bsdf::plastic(base, 0.2, Distribution::Beckmann, 1.5, rough, 0.3),
    ];
    let key = hash_key(&[23]);
    for b in plastics {
        let mut seen = [0u32; 2];
        for (k, z) in [1.0f32, 0.8, 0.3, 0.05].into_iter().enumerate() {
            let wo = Vec3A::new((1.0 - z * z).sqrt(), 0.0, z);
            for i in 0..4096 {
                let mut s = SampleStream::new(key, (k * 4096 + i) as u32);
                let (ul, u) = (s.next_1d(), s.next_2d());
                let Some(bs) = b.sample(wo, ul, u) else {
                    continue;
                };
                let (pdf, f) = (b.pdf(wo, bs.wi), b.eval(wo, bs.wi));
                assert_eq!(
                    bs.pdf.to_bits(),
                    pdf.to_bits(),
                    "{b:?} wo {wo} wi {}",
                    bs.wi
                );
                assert_eq!(
                    bs.f.to_array().map(f32::to_bits),
                    f.to_array().map(f32::to_bits)
                );
                let weight = f * (bs.wi.z.abs() / pdf);
                assert_eq!(
                    bs.weight.to_array().map(f32::to_bits),
                    weight.to_array().map(f32::to_bits)
                );
                // Both lobes were exercised: a glossy direction near the mirror one, or not.
                seen[(bs.wi.dot(Vec3A::new(-wo.x, -wo.y, wo.z)) > 0.999) as usize] += 1;
            }
        }
        assert!(seen[0] > 100 && seen[1] > 100, "{b:?}: lobes {seen:?}");
    }
}

#[test]
fn sampled_directions_follow_the_pdf_chi2() {
    for b in smooth_lobed() {
        assert_sampling_follows_pdf(&b, wo(), 11);
    }
}

/// Pearson's χ² between `n` directions sampled from `b` at `wo` (stream `key`) and the pdf
/// integrated over the bins of a (cos θ, φ) grid of the sphere; bins expecting fewer than 5
/// samples are pooled. The bound is the χ² quantile's normal approximation at about 1e-4
/// significance. Also checks that the samples `b` rejects are the pdf's missing mass.
pub(crate) fn assert_sampling_follows_pdf(b: &Bsdf, wo: Vec3A, key: u64) {
    const NT: usize = 20;
    const NP: usize = 40;
    const SUB: usize = 16;
    let n = 200_000u32;
    let mut observed = vec![0f64; NT * NP];
    let key = hash_key(&[key]);
    let mut total = 0.0;
    for i in 0..n {
        let mut s = SampleStream::new(key, i);
        let ul = s.next_1d();
        if let Some(bs) = b.sample(wo, ul, s.next_2d()) {
            observed[bin(bs.wi, NT, NP)] += 1.0;
            total += 1.0;
        }
    }
    // The pdf over each bin, by a SUB × SUB midpoint rule in (cos θ, φ).
    let mut expected = vec![0f64; NT * NP];
    let (dz, dp) = (2.0 / NT as f64, 2.0 * std::f64::consts::PI / NP as f64);
    for (k, e) in expected.iter_mut().enumerate() {
        let (it, ip) = (k / NP, k % NP);
        for a in 0..SUB {
            for c in 0..SUB {
                let z = -1.0 + dz * (it as f64 + (a as f64 + 0.5) / SUB as f64);
                let p = dp * (ip as f64 + (c as f64 + 0.5) / SUB as f64);
                let r = (1.0 - z * z).max(0.0).sqrt();
                let wi = Vec3A::new(
                    (r * libm::cos(p)) as f32,
                    (r * libm::sin(p)) as f32,
                    z as f32,
                );
                *e += b.pdf(wo, wi) as f64 * dz * dp / (SUB * SUB) as f64;
            }
        }
        *e *= n as f64;
    }
    // Samples the BSDF rejects are the missing mass: compare to the pdf's own mass.
    let mass: f64 = expected.iter().sum();
    assert!(
        (mass - total).abs() < 0.02 * n as f64,
        "{b:?} at {wo}: {mass} vs {total}"
    );
    let (mut chi2, mut dof, mut pool_o, mut pool_e) = (0.0, 0usize, 0.0, 0.0);
    for (o, e) in observed.iter().zip(&expected) {
        if *e < 5.0 {
            pool_o += o;
            pool_e += e;
        } else {
            chi2 += (o - e) * (o - e) / e;
            dof += 1;
        }
    }
    if pool_e >= 5.0 {
        chi2 += (pool_o - pool_e) * (pool_o - pool_e) / pool_e;
        dof += 1;
    }
    let bound = dof as f64 + 3.7 * (2.0 * dof as f64).sqrt() + 10.0;
    assert!(dof > 10, "{b:?}: too few bins ({dof})");
    assert!(
        chi2 < bound,
        "{b:?} at {wo}: χ² {chi2:.1} over {dof} bins (bound {bound:.1})"
    );
}

fn bin(w: Vec3A, nt: usize, np: usize) -> usize {
    let it = (((w.z + 1.0) * 0.5 * nt as f32) as usize).min(nt - 1);
    let phi = libm::atan2f(w.y, w.x).rem_euclid(2.0 * PI);
    let ip = ((phi / (2.0 * PI) * np as f32) as usize).min(np - 1);
    it * np + ip
}

/// Reflection is reciprocal, f(wo, wi) = f(wi, wo); refraction through a rough interface
/// obeys the generalised form f(wo → wi; η) = f(wi → wo; 1/η) / η² for radiance.
#[test]
fn reciprocity() {
    let key = hash_key(&[3]);
    for b in smooth_lobed() {
        for i in 0..2000 {
            let mut s = SampleStream::new(key, i);
            let a = cosine_hemisphere(s.next_2d());
            let c = cosine_hemisphere(s.next_2d());
            let (fa, fb) = (b.eval(a, c), b.eval(c, a));
            assert!((fa - fb).abs().max_element() <= 3e-3 * fa.max_element().max(1.0));
            if let Bsdf::RoughDielectric(d) = b {
                let below = Vec3A::new(c.x, c.y, -c.z);
                let back = RoughDielectric {
                    eta: 1.0 / d.eta,
                    ..d
                };
                let f = d.eval(a, below);
                let g = back.eval(c, Vec3A::new(a.x, a.y, -a.z));
                let expect = f * d.eta * d.eta;
                assert!(
                    (g - expect).abs().max_element() <= 3e-3 * expect.max_element().max(1e-3),
                    "{d:?}: {g} vs {expect} at {a} {c}"
                );
            }
        }
    }
}

/// Smooth glass: reflection and refraction probabilities sum to 1 at every angle, and the
/// refracted weight is the radiance scaling 1/η² (so importance R + T = 1).
#[test]
fn smooth_glass_reflects_plus_transmits_one() {
    for eta in [1.5f32, 1.0 / 1.5, 2.419] {
        let b = Bsdf::Dielectric {
            eta,
            r: Vec3A::ONE,
            t: Vec3A::ONE,
        };
        for k in 0..50 {
            let th = k as f32 / 50.0 * 1.55;
            let wo = Vec3A::new(libm::sinf(th), 0.0, libm::cosf(th));
            let r = b.sample(wo, 0.0, [0.5; 2]).unwrap();
            let t = b.sample(wo, 0.999_999, [0.5; 2]).unwrap();
            assert!(r.delta && r.wi.z > 0.0 && (r.weight - Vec3A::ONE).length() < 1e-6);
            let total = if t.wi.z < 0.0 {
                // Snell: sin θt = sin θi / η, and the weight is 1/η².
                let sin_t = (t.wi.x * t.wi.x + t.wi.y * t.wi.y).sqrt();
                assert!((sin_t * eta - libm::sinf(th)).abs() < 1e-4);
                assert!((t.weight.x * eta * eta - 1.0).abs() < 1e-5);
                r.pdf + t.pdf
            } else {
                // Total internal reflection: both picks reflect.
                assert!(eta < 1.0 && libm::sinf(th) > eta);
                r.pdf
            };
            assert!((total - 1.0).abs() < 1e-6, "eta {eta}, θ {th}: {total}");
        }
    }
    // A thin pane: light passes undeflected, R + T = 1, and R exceeds one interface's.
    let pane = Bsdf::ThinDielectric {
        eta: 1.5,
        r: Vec3A::ONE,
        t: Vec3A::ONE,
    };
    let wo = Vec3A::new(0.6, 0.0, 0.8);
    let r = pane.sample(wo, 0.0, [0.5; 2]).unwrap();
    let t = pane.sample(wo, 0.999_999, [0.5; 2]).unwrap();
    assert_eq!(t.wi, -wo);
    assert!((r.pdf + t.pdf - 1.0).abs() < 1e-6);
    assert!(r.pdf > fresnel_dielectric(0.8, 1.5));
}

#[test]
fn diffuse_albedo_is_exact() {
    let b = Bsdf::Diffuse {
        reflectance: Vec3A::new(0.3, 0.6, 0.9),
    };
    let s = b.sample(Vec3A::Z, 0.5, [0.3, 0.7]).unwrap();
    assert!((s.weight - Vec3A::new(0.3, 0.6, 0.9)).abs().max_element() < 1e-5);
}
