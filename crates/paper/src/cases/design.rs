//! The designs of cases 4 and 6, computed from the scenes' geometry (no rendering): the
//! premises their design checks test at run time hold in every configuration of their grids.
//! `cargo test --release -p eyeadapt-paper design -- --nocapture` prints the design figures
//! docs/paper.md quotes ("Case 4", "Case 6").
use super::spot::{self, Spot};
use crate::Region;
use crate::grids::case_grid;
use crate::study::Config;
use eyeadapt_scene::{Bsdf, Scene};
use eyeadapt_tracer::{SceneData, View};
use glam::{DVec3, Vec3, Vec3A};

/// Case `number`'s scene template filled with `config`, loaded beside `paper/scenes/`.
fn scene(number: u32, config: &Config) -> Scene {
    let case = crate::CASES.iter().find(|c| c.number == number).unwrap();
    let (name, _, template) = case.jobs[0];
    let text = crate::shot::fill_template(template.unwrap(), config, name).unwrap();
    let beside = concat!(env!("CARGO_MANIFEST_DIR"), "/../../paper/scenes/s.toml");
    eyeadapt_scene::load_scene_str(&text, std::path::Path::new(beside)).unwrap()
}

fn material_id(scene: &Scene, name: &str) -> u32 {
    scene.materials.iter().position(|m| m.name == name).unwrap() as u32
}

/// Case 4: the spot's whole power lands on the statue, and the statue pixels it lights (centre
/// rays at the study's 96 × 72) are 5–75 % of the statue's, for every cone of the grid.
#[test]
fn case4_design_the_spot_lights_only_the_statue_and_part_of_it() {
    let (_, configs) = case_grid(4, false);
    let (w, h, _) = crate::CASES[3].study[0];
    let mut seen = Vec::new();
    for config in &configs {
        let cone = config.get("spot_cone_deg").unwrap().to_string();
        if seen.contains(&cone) {
            continue;
        }
        seen.push(cone.clone());
        let scene = scene(4, config);
        let data = SceneData::new(&scene);
        let spot = Spot::of(&scene).unwrap();
        let statue = material_id(&scene, "statue");
        let power = spot::power_share(&data, &spot, statue);
        let mut view = View::from_camera(scene.camera.as_ref().unwrap());
        (view.width, view.height) = (w, h);
        let basis = view.basis();
        let mut scratch = data.geometry.scratch();
        let (mut on_statue, mut lit) = (0usize, 0usize);
        for y in 0..h {
            for x in 0..w {
                let d = view.ray_dir(basis, x as f32 + 0.5, y as f32 + 0.5);
                let o = Vec3A::from(view.position);
                let Some(hit) = data
                    .geometry
                    .intersect_with(&mut scratch, o, d, f32::INFINITY)
                else {
                    continue;
                };
                let i = data.geometry.interaction(o, d, &hit, data.parameterisation);
                if i.material == statue {
                    on_statue += 1;
                    let p = view.position + Vec3::from(d) * hit.t;
                    lit += usize::from(spot::lights(&data, &mut scratch, &spot, p));
                }
            }
        }
        let share = lit as f64 / on_statue as f64;
        println!(
            "case 4, cone {cone}°: {:.1} % of the spot's power on the statue; lit {lit} of \
             {on_statue} statue pixels at {w} × {h} ({:.1} %)",
            100.0 * power,
            100.0 * share
        );
        assert!(power > 0.999, "cone {cone}: {power}");
        assert!((0.05..=0.75).contains(&share), "cone {cone}: {share}");
    }
}

/// Case 4: wider cones from the same place spill off the statue (the built-in scene's 18° cone
/// puts most of the spot's power on the pedestal and the room), which is why the grid stops at
/// the widest cone that fits.
#[test]
fn case4_design_wider_cones_spill_onto_the_room() {
    let (_, configs) = case_grid(4, false);
    let mut config = configs[0].clone();
    let mut shares = Vec::new();
    for cone in [5.0f64, 8.0, 12.0, 18.0] {
        for (k, v) in config.fill.iter_mut() {
            match *k {
                "spot_cone_deg" => *v = format!("{cone:?}"),
                "spot_falloff_deg" => *v = format!("{:?}", 0.75 * cone),
                _ => {}
            }
        }
        let scene = scene(4, &config);
        let data = SceneData::new(&scene);
        let spot = Spot::of(&scene).unwrap();
        let share = spot::power_share(&data, &spot, material_id(&scene, "statue"));
        println!(
            "case 4, cone {cone}°: {:.1} % of the spot's power on the statue",
            100.0 * share
        );
        shares.push(share);
    }
    assert!(shares[0] > 0.999, "{shares:?}");
    assert!(shares.windows(2).all(|w| w[1] < w[0]), "{shares:?}");
    assert!(shares[3] < 0.5, "{shares:?}");
}

/// A flat emitter: its rectangle in the plane y = `y` and its luminance.
struct Emitter {
    name: String,
    min: DVec3,
    max: DVec3,
    luminance: f64,
}

fn emitters(scene: &Scene) -> Vec<Emitter> {
    scene
        .materials
        .iter()
        .filter(|m| m.is_emissive())
        .map(|m| {
            let r = Region::from_material(scene, &m.name, &m.name, 0.0);
            let e = m.emission.as_dvec3();
            Emitter {
                name: m.name.clone(),
                min: r.min.as_dvec3(),
                max: r.max.as_dvec3(),
                luminance: e.dot(DVec3::new(0.2126, 0.7152, 0.0722)),
            }
        })
        .collect()
}

/// The rectangle of the bench plane y = `b` where the eye at `e` sees emitter `l` mirrored:
/// each corner interpolates between the eye and the corner's image below the plane.
fn mirror_footprint(e: DVec3, l: &Emitter, b: f64) -> (DVec3, DVec3) {
    let ly = 0.5 * (l.min.y + l.max.y);
    let t = (e.y - b) / ((e.y - b) + (ly - b));
    let lo = e + (DVec3::new(l.min.x, b, l.min.z) - e) * t;
    let hi = e + (DVec3::new(l.max.x, b, l.max.z) - e) * t;
    (lo.min(hi).with_y(b), lo.max(hi).with_y(b))
}

fn fresnel_dielectric(cos_i: f64, eta: f64) -> f64 {
    let sin_t2 = (1.0 - cos_i * cos_i).max(0.0) / (eta * eta);
    let cos_t = (1.0 - sin_t2).max(0.0).sqrt();
    let rs = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
    let rp = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
    0.5 * (rs * rs + rp * rp)
}

/// GGX normal distribution at cos θ_h, roughness `a`.
fn ggx_d(cos_h: f64, a: f64) -> f64 {
    if cos_h <= 0.0 {
        return 0.0;
    }
    let t2 = (1.0 - cos_h * cos_h) / (cos_h * cos_h);
    a * a / (std::f64::consts::PI * cos_h.powi(4) * (a * a + t2).powi(2))
}

/// Smith's Λ for GGX.
fn ggx_lambda(cos: f64, a: f64) -> f64 {
    let t2 = (1.0 - cos * cos) / (cos * cos);
    0.5 * (-1.0 + (1.0 + a * a * t2).sqrt())
}

/// Luminance the eye at `e` sees reflected by the bench's coating (GGX roughness `a`, IOR
/// `ior`, normal +y) at `p` from every emitter (downward-facing rectangles, 16 × 16 cells,
/// each with a shadow ray through the scene): the highlight, without the diffuse base.
fn highlight(data: &SceneData, emitters: &[Emitter], e: DVec3, p: DVec3, a: f64, ior: f64) -> f64 {
    const N: usize = 16;
    let mut scratch = data.geometry.scratch();
    let wo = (e - p).normalize();
    let mut sum = 0.0;
    for l in emitters {
        let (dx, dz) = (
            (l.max.x - l.min.x) / N as f64,
            (l.max.z - l.min.z) / N as f64,
        );
        let ly = 0.5 * (l.min.y + l.max.y);
        for i in 0..N {
            for j in 0..N {
                let q = DVec3::new(
                    l.min.x + (i as f64 + 0.5) * dx,
                    ly,
                    l.min.z + (j as f64 + 0.5) * dz,
                );
                let r = (q - p).length();
                let wi = (q - p) / r;
                if wi.y <= 0.0 {
                    continue;
                }
                let o = Vec3A::from((p + DVec3::Y * 1e-4).as_vec3());
                let hit = data.geometry.intersect_with(
                    &mut scratch,
                    o,
                    Vec3A::from(wi.as_vec3()),
                    f32::INFINITY,
                );
                if hit.is_none_or(|h| (h.t as f64) < r - 2e-3) {
                    continue;
                }
                let hv = (wi + wo).normalize();
                let g = 1.0 / (1.0 + ggx_lambda(wi.y, a) + ggx_lambda(wo.y, a));
                let f =
                    fresnel_dielectric(wi.dot(hv), ior) * ggx_d(hv.y, a) * g / (4.0 * wo.y * wi.y);
                // Radiance × BRDF × cos θ_i × dω, dω = cos θ_light dA / r² (θ_light = θ_i).
                sum += l.luminance * f * wi.y * wi.y / (r * r) * dx * dz;
            }
        }
    }
    sum
}

/// The brightest highlight over the bench top (a 3 cm grid) seen from `e`.
fn brightest_on_bench(
    data: &SceneData,
    emitters: &[Emitter],
    bench: &Region,
    e: DVec3,
    a: f64,
    ior: f64,
) -> (f64, DVec3) {
    let (lo, hi) = (bench.min.as_dvec3(), bench.max.as_dvec3());
    let steps = |a: f64, b: f64| ((b - a) / 0.03).ceil() as usize;
    let mut best = (0.0, DVec3::NAN);
    for i in 0..=steps(lo.x, hi.x) {
        for k in 0..=steps(lo.z, hi.z) {
            let x = (lo.x + 0.03 * i as f64).min(hi.x);
            let z = (lo.z + 0.03 * k as f64).min(hi.z);
            let p = DVec3::new(x, hi.y, z);
            let v = highlight(data, emitters, e, p, a, ior);
            if v > best.0 {
                best = (v, p);
            }
        }
    }
    best
}

/// The gap between two rectangles of the plane (0 when they overlap).
fn gap(a: (DVec3, DVec3), b: (DVec3, DVec3)) -> f64 {
    let dx = (a.0.x - b.1.x).max(b.0.x - a.1.x).max(0.0);
    let dz = (a.0.z - b.1.z).max(b.0.z - a.1.z).max(0.0);
    libm::hypot(dx, dz)
}

/// Case 6: along the spline path's frames 5 and 10, the orange light's mirror image lies off
/// the bench at frame 5 (its far edge ≥ 0.1 m short of the bench's near end) and a strip of it
/// on the bench at frame 10 (≥ 0.1 m deep, its x extent inside the bench's); the other lights'
/// images stay ≥ 0.2 m off the bench in both frames. Every roughness α of the grid is at most a
/// third of the sweep of the mirror direction from frame 5 to 10 (the lobe, ≈ 2α wide, at most
/// two thirds of it), and the highlight model (the coating's GGX lobe integrated over every
/// light, shadowed by the scene) puts the bench's brightest highlight at frame 10 at least 3 ×
/// its brightest at frame 5.
#[test]
fn case6_design_the_orange_highlight_reaches_the_bench_between_frames_5_and_10() {
    let (_, configs) = case_grid(6, false);
    let base = scene(6, &configs[0]);
    let path = base.camera_path.clone().unwrap();
    let eye = |f: usize| path.sample(path.frame_time(f)).position;
    let bench = Region::from_material(&base, "bench", "bench", 0.0);
    let (blo, bhi) = (bench.min.as_dvec3(), bench.max.as_dvec3());
    let top = bhi.y;
    let lights = emitters(&base);
    for f in [0, 5, 10, 15, 20, 24] {
        let e = eye(f);
        print!("frame {f:2}: eye ({:.3}, {:.3}, {:.3})", e.x, e.y, e.z);
        for l in &lights {
            let (lo, hi) = mirror_footprint(e, l, top);
            print!(
                "; {} image x [{:.3}, {:.3}] z [{:.3}, {:.3}]",
                l.name, lo.x, hi.x, lo.z, hi.z
            );
        }
        println!();
    }
    println!(
        "bench top y {top:.2}: x [{:.3}, {:.3}], z [{:.3}, {:.3}]",
        blo.x, bhi.x, blo.z, bhi.z
    );
    let orange = lights.iter().find(|l| l.name == "orange_light").unwrap();
    let (f5, f10) = (
        mirror_footprint(eye(5), orange, top),
        mirror_footprint(eye(10), orange, top),
    );
    let near = bhi.z;
    assert!(
        f5.0.z - near >= 0.1,
        "frame 5: far edge {} near end {near}",
        f5.0.z
    );
    assert!(
        near - f10.0.z >= 0.1,
        "frame 10: far edge {} near end {near}",
        f10.0.z
    );
    for fp in [f5, f10] {
        assert!(fp.0.x >= blo.x && fp.1.x <= bhi.x, "{fp:?}");
    }
    for l in lights.iter().filter(|l| l.name != "orange_light") {
        for f in [5, 10] {
            let g = gap(mirror_footprint(eye(f), l, top), (blo, bhi));
            assert!(g >= 0.2, "{} frame {f}: {g}", l.name);
        }
    }
    // The sweep: how far the direction from the bench's near end (the footprints' middle in x)
    // to the eye turns from frame 5 to frame 10, and with it the mirror direction.
    let p = DVec3::new(0.25 * (f5.0.x + f5.1.x + f10.0.x + f10.1.x), top, near);
    let sweep = (eye(5) - p).angle_between(eye(10) - p);
    println!(
        "the mirror direction at the bench's near end sweeps {sweep:.4} rad from frame 5 to 10"
    );
    let mut seen = Vec::new();
    for config in &configs {
        let r = config.get("bench_roughness").unwrap().to_string();
        if seen.contains(&r) {
            continue;
        }
        seen.push(r.clone());
        let s = scene(6, config);
        let Some(Bsdf::Plastic { alpha, ior, .. }) = s
            .materials
            .iter()
            .find(|m| m.name == "bench")
            .map(|m| m.bsdf.clone())
        else {
            panic!("the bench is plastic");
        };
        let a = f64::from(alpha.constant().unwrap().max(0.01));
        let data = SceneData::new(&s);
        let (h5, p5) = brightest_on_bench(&data, &lights, &bench, eye(5), a, f64::from(ior));
        let (h10, p10) = brightest_on_bench(&data, &lights, &bench, eye(10), a, f64::from(ior));
        println!(
            "roughness {r}: brightest highlight on the bench {h5:.3} at frame 5 (x {:.2}, z {:.2}), \
             {h10:.3} at frame 10 (x {:.2}, z {:.2}); ratio {:.1}",
            p5.x,
            p5.z,
            p10.x,
            p10.z,
            h10 / h5
        );
        assert!(
            a <= sweep / 3.0,
            "roughness {r}: lobe too wide for the sweep {sweep}"
        );
        assert!(h10 >= 3.0 * h5, "roughness {r}: {h5} {h10}");
    }
}
