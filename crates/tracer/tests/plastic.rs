//! The plastic coating through the integrator, in a uniform environment (radiance 1) where a
//! pixel shows the BSDF's directional albedo: a smooth `plastic` (alpha 0) has the albedo of
//! Mitsuba's smooth plastic, computed here from its formulas.
use eyeadapt_scene::{Bsdf, Camera, Distribution, Material, Param, Rgb, Scene, quad_mesh};
use eyeadapt_tracer::{Frame, PathSettings, RenderSettings, SceneData, View, render};
use glam::Vec3;

/// Unpolarised Fresnel reflectance for incidence cosine `c` and relative IOR `eta`.
fn fresnel(c: f64, eta: f64) -> f64 {
    let s2 = (1.0 - c * c) / (eta * eta);
    if s2 >= 1.0 {
        return 1.0;
    }
    let t = (1.0 - s2).sqrt();
    let rs = (c - eta * t) / (c + eta * t);
    let rp = (eta * c - t) / (eta * c + t);
    0.5 * (rs * rs + rp * rp)
}

/// Mitsuba's smooth `plastic` (`nonlinear = false`) seen head-on under radiance 1: the
/// specular reflection F(1) plus the base ρ / (1 − Fdr) attenuated by (1 − F) on the way in
/// and out and by 1/η² (the cosine-weighted integral of 1 − F(cos θo) is 1 − Fdr_ext), with
/// Mitsuba's Fdr, `fresnel_diffuse_reflectance(1/η)` (Egan and Hilgeman's fit).
fn mitsuba_albedo_at_normal_incidence(rho: f64, eta: f64) -> f64 {
    let fdr_int = -1.4399 / (eta * eta) + 0.7099 / eta + 0.6681 + 0.0636 * eta;
    let n = 100_000;
    let fdr_ext: f64 = (0..n)
        .map(|i| {
            let mu = (i as f64 + 0.5) / n as f64;
            2.0 * mu * fresnel(mu, eta) / n as f64
        })
        .sum();
    let f0 = fresnel(1.0, eta);
    f0 + rho / (1.0 - fdr_int) * (1.0 - f0) * (1.0 - fdr_ext) / (eta * eta)
}

/// A quad of `bsdf` filling a narrow view from far away (every pixel sees it at normal
/// incidence), lit by the uniform environment only, one bounce: the mean pixel.
fn head_on(bsdf: Bsdf) -> Vec3 {
    let mut s = Scene::default();
    let m = s.add_material(Material {
        name: "m".into(),
        bsdf,
        emission: Rgb::ZERO,
    });
    let q = quad_mesh(
        Vec3::new(-2.0, -2.0, 0.0),
        Vec3::new(4.0, 0.0, 0.0),
        Vec3::new(0.0, 4.0, 0.0),
    );
    s.add_world_mesh(q, Some(m));
    s.environment = Some(Rgb::ONE);
    let view = View::from_camera(&Camera {
        position: Vec3::new(0.0, 0.0, 100.0),
        look_at: Vec3::ZERO,
        up: Vec3::Y,
        fov_deg: 1.0,
        width: 16,
        height: 16,
        projection: Default::default(),
    });
    let settings = RenderSettings {
        spp: 1024,
        path: PathSettings {
            max_depth: 2,
            rr_depth: 50,
        },
        seed: 3,
        frame: 0,
        filter: Default::default(),
        wcam_specular: Default::default(),
        guiding: Default::default(),
    };
    let f: Frame = render(&SceneData::new(&s), &view, &settings);
    f.rgb.iter().map(|&x| Vec3::from(x)).sum::<Vec3>() / f.rgb.len() as f32
}

/// matpreview's material (mitsuba-data): a smooth `plastic`, IOR 1.9. With the rough
/// interface's tables at alpha 0.01 instead, the base was 5 % darker (the tables' Fdr is 0.752
/// at this IOR, the smooth interface's 0.764).
#[test]
fn smooth_plastic_has_the_albedo_of_mitsubas_smooth_plastic() {
    let rho = [0.94, 0.271, 0.361];
    let eta = 1.9;
    let got = head_on(Bsdf::Plastic {
        reflectance: Param::Const(Rgb::new(rho[0], rho[1], rho[2])),
        alpha: Param::Const(0.0),
        distribution: Distribution::Ggx,
        ior: eta,
    });
    for (c, r) in rho.into_iter().enumerate() {
        let want = mitsuba_albedo_at_normal_incidence(r as f64, eta as f64) as f32;
        let rel = got[c] / want - 1.0;
        assert!(
            rel.abs() < 0.005,
            "channel {c}: {} vs {want} ({rel:+.4})",
            got[c]
        );
    }
}
