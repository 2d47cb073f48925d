//! EXPERIMENT (issue 23, goal 4; reverted right after its commit, kept in history): the eye sensor's paths with their contributions split by segment
//! and strategy, and variants (all-lights NEE, splitting at the first hit).
use crate::eye::{EYE_REPLICATES, EyeSettings, sample_cardioid};
use crate::film::View;
use crate::integrator::{Frame, Origin, PathSettings, offset, power_heuristic};
use crate::path_state::{PathState, Vertex, VertexSamples};
use crate::sampler::{SampleStream, StreamSeeds, hash_key};
use crate::scene_data::SceneData;
use crate::shadow::shadow_transmittance;
use glam::{DVec3, Vec3A};
use std::f32::consts::PI;

/// Components: 0 eye NEE; 2s−1 emission reached by segment s (BSDF/cardioid sampled); 2k NEE at
/// vertex k.
pub const PROBE_COMPONENTS: usize = 16;

#[derive(Clone, Copy, Debug, Default)]
pub struct ProbeVariant {
    /// All-lights NEE at the eye.
    pub eye_all: bool,
    /// All-lights NEE at vertices 1..=k.
    pub nee_all_upto: u32,
    /// Continuations per first direction.
    pub split: u32,
    /// Independent (hashed) first direction instead of QMC.
    pub random_dir: bool,
    /// Everything after the first direction from an independent stream.
    pub random_rest: bool,
    /// Only directions outside the camera frustum (the frustum's share assumed exact).
    pub out_fov: bool,
    /// All-lights NEE at vertex 1 uses the path's QMC light sample (joint with the direction).
    pub qmc_light: bool,
    /// Lights whose pick probability is below `tau` are traced with probability P/tau.
    pub tau: f32,
    /// All-lights only where no unit's pick probability reaches this (0: always).
    pub dominant: f32,
}

/// The largest one-pick probability of a unit at `x`.
fn max_pick(
    scene: &SceneData,
    units: &[(usize, Option<usize>)],
    x: Vec3A,
    n: Option<Vec3A>,
) -> f32 {
    let mut m = 0.0f32;
    for &unit in units {
        let (t, y) = sample_unit(scene, unit, [0.5, 0.5]);
        let a = &scene.lights.area[t];
        let d = y - x;
        let d2 = d.length_squared();
        let cos_l = a.n.dot(d).abs() / d2.sqrt();
        if cos_l > 0.0 {
            m = m.max(
                scene.lights.pdf_area(t as u32, x, n, y) * cos_l / d2 * unit_area(scene, unit),
            );
        }
    }
    m
}

fn comp_emission(seg: u32) -> usize {
    ((2 * seg.max(1)) as usize - 1).min(PROBE_COMPONENTS - 1)
}

/// An area-light unit: one triangle or a pair (a quad).
fn units(scene: &SceneData) -> Vec<(usize, Option<usize>)> {
    let a = &scene.lights.area;
    let mut out = Vec::new();
    let mut t = 0;
    while t < a.len() {
        if t + 1 < a.len()
            && a[t].emission == a[t + 1].emission
            && a[t].n == a[t + 1].n
            && a[t].texture == u32::MAX
            && a[t + 1].texture == u32::MAX
        {
            out.push((t, Some(t + 1)));
            t += 2;
        } else {
            out.push((t, None));
            t += 1;
        }
    }
    out
}

/// A point on unit `(t, t2)` with density 1/area: (triangle, point).
fn sample_unit(scene: &SceneData, unit: (usize, Option<usize>), u: [f32; 2]) -> (usize, Vec3A) {
    let a = &scene.lights.area;
    let (t, u0) = match unit.1 {
        None => (unit.0, u[0]),
        Some(t2) => {
            let p = a[unit.0].area / (a[unit.0].area + a[t2].area);
            if u[0] < p {
                (unit.0, u[0] / p)
            } else {
                (t2, ((u[0] - p) / (1.0 - p)).min(0.999_999_9))
            }
        }
    };
    let tri = &a[t];
    let su = u0.sqrt();
    let (b1, b2) = (su * (1.0 - u[1]), su * u[1]);
    (t, tri.v0 + tri.e1 * b1 + tri.e2 * b2)
}

fn unit_area(scene: &SceneData, unit: (usize, Option<usize>)) -> f32 {
    let a = &scene.lights.area;
    a[unit.0].area + unit.1.map_or(0.0, |t| a[t].area)
}

/// All-lights NEE from `x` (normal `n` for the pick), `f(wi)` the BSDF·cos (or kernel) and
/// `pdf_other(wi)` the competing strategy's density; MIS weights of the one-pick strategy.
#[allow(clippy::too_many_arguments)]
fn nee_all(
    scene: &SceneData,
    units: &[(usize, Option<usize>)],
    x: Vec3A,
    n: Option<Vec3A>,
    key: u64,
    u_fixed: Option<[f32; 2]>,
    tau: f32,
    f: impl Fn(Vec3A) -> Vec3A,
    pdf_other: impl Fn(Vec3A) -> f32,
) -> Vec3A {
    let mut scratch = scene.geometry.scratch();
    let mut sum = Vec3A::ZERO;
    for (j, &unit) in units.iter().enumerate() {
        let u =
            u_fixed.unwrap_or_else(|| SampleStream::new(hash_key(&[key, j as u64]), 0).next_2d());
        let (t, y) = sample_unit(scene, unit, u);
        let a = &scene.lights.area[t];
        let d = y - x;
        let d2 = d.length_squared();
        let dist = d2.sqrt();
        let wi = d / dist;
        let cos_l = -a.n.dot(wi);
        if cos_l <= 0.0 {
            continue;
        }
        let fv = f(wi);
        if fv.max_element() <= 0.0 {
            continue;
        }
        let pick_pdf = scene.lights.pdf_area(t as u32, x, n, y);
        let mut keep = 1.0;
        if tau > 0.0 {
            let p = pick_pdf * cos_l / d2 * unit_area(scene, unit);
            keep = (p / tau).min(1.0);
            let ur = SampleStream::new(hash_key(&[key, 0x5EE, j as u64]), 0).next_1d();
            if ur >= keep {
                continue;
            }
        }
        let tr = shadow_transmittance(scene, &mut scratch, x, wi, dist);
        if tr.max_element() <= 0.0 {
            continue;
        }
        let w = power_heuristic(pick_pdf, pdf_other(wi));
        let pdf_unit = d2 / (cos_l * unit_area(scene, unit));
        sum += fv * a.emission * tr * (w / (pdf_unit * keep));
    }
    sum
}

/// One path from the eye along `dir`, its contributions added to `comps` times `scale`.
#[allow(clippy::too_many_arguments)]
fn eye_path(
    scene: &SceneData,
    units: &[(usize, Option<usize>)],
    eye: Vec3A,
    dir: Vec3A,
    pdf: f32,
    s: &mut SampleStream,
    settings: PathSettings,
    variant: &ProbeVariant,
    key: u64,
    scale: f32,
    comps: &mut [Vec3A; PROBE_COMPONENTS],
) {
    let mut scratch = scene.geometry.scratch();
    let u1 = s.next_2d();
    let mut path = PathState::new(eye, dir, Origin::Sampled { pdf }, u1, None);
    let max_depth = settings.max_depth as u32;
    loop {
        s.start_group();
        let seg = path.depth + 1;
        let l0 = path.out.l;
        let Some(hit) = scene
            .geometry
            .intersect_with(&mut scratch, path.o, path.d, f32::INFINITY)
        else {
            path.escape(&scene.lights);
            comps[comp_emission(seg)] += (path.out.l - l0) * scale;
            break;
        };
        let si = scene
            .geometry
            .interaction(path.o, path.d, &hit, scene.parameterisation);
        path.shade_hit(scene, &si);
        comps[comp_emission(seg)] += (path.out.l - l0) * scale;
        let last = path.depth + 1 >= max_depth;
        if last {
            break;
        }
        let u = VertexSamples::draw(s);
        let v = Vertex::new(scene, &si, -path.d, &u);
        let k = path.depth + 1;
        let ci = (2 * k as usize).min(PROBE_COMPONENTS - 1);
        let dominated = variant.dominant > 0.0 && {
            let wo = -path.d;
            let ng = if si.ng.dot(wo) > 0.0 { si.ng } else { -si.ng };
            max_pick(scene, units, offset(si.p, ng), Some(ng)) >= variant.dominant
        };
        if k <= variant.nee_all_upto && !dominated {
            let wo = -path.d;
            let front = si.ng.dot(wo) > 0.0;
            let bsdf = *scene
                .materials
                .fixed(si.material, front)
                .expect("probe: fixed materials only");
            let ng = if front { si.ng } else { -si.ng };
            let ns = if si.ns.dot(ng) < 0.0 { -si.ns } else { si.ns };
            let fr = Frame::new(ns);
            let wo_l = fr.to_local(wo);
            if !bsdf.is_delta() && !bsdf.has_transmission() {
                let c = nee_all(
                    scene,
                    units,
                    offset(si.p, ng),
                    Some(ng),
                    hash_key(&[key, k as u64]),
                    (k == 1 && variant.qmc_light).then_some(u1),
                    variant.tau,
                    |wi| {
                        let wl = fr.to_local(wi);
                        bsdf.eval(wo_l, wl) * wl.z.abs()
                    },
                    |wi| bsdf.pdf(wo_l, fr.to_local(wi)),
                );
                comps[ci] += path.beta * c * scale;
            }
        } else {
            let l1 = path.out.l;
            path.sample_light(scene, &mut scratch, &v, &u, None);
            comps[ci] += (path.out.l - l1) * scale;
        }
        if !path.scatter(&v, &u, last, None) || !path.roulette(settings.rr_depth, u.rr) {
            break;
        }
    }
}

/// Mean of each component over `settings.samples` paths of frame `frame` (CRN off).
pub fn eye_probe(
    scene: &SceneData,
    view: &View,
    settings: &EyeSettings,
    frame: u32,
    path: PathSettings,
    variant: &ProbeVariant,
) -> [DVec3; PROBE_COMPONENTS] {
    let key = hash_key(&[settings.seed, 0xE7E_5E45, 1, frame as u64]);
    let replicate_seeds: [StreamSeeds; EYE_REPLICATES] =
        std::array::from_fn(|b| StreamSeeds::new(hash_key(&[key, 0x4E9_11CA, b as u64])));
    let units = units(scene);
    let eye = Vec3A::from(view.position);
    let (r, up, axis) = view.basis();
    let mut total = [DVec3::ZERO; PROBE_COMPONENTS];
    for i in 0..settings.samples {
        let mut comps = [Vec3A::ZERO; PROBE_COMPONENTS];
        let b = i as usize % EYE_REPLICATES;
        let mut s = SampleStream::seeded(&replicate_seeds[b], i / EYE_REPLICATES as u32);
        let u_pick = s.next_1d();
        let _ = s.next_1d();
        let u_light = s.next_2d();
        s.start_group();
        let mut u_dir = s.next_2d();
        let pkey = hash_key(&[key, 0x9B0B, i as u64]);
        if variant.random_dir {
            u_dir = SampleStream::new(hash_key(&[pkey, 77]), 0).next_2d();
        }
        if variant.eye_all {
            comps[0] += nee_all(
                scene,
                &units,
                eye,
                None,
                hash_key(&[pkey, 0]),
                None,
                variant.tau,
                |wi| Vec3A::splat((1.0 + wi.dot(axis)) * 0.25),
                |wi| (1.0 + wi.dot(axis)) * 0.25 / PI,
            );
        } else if let Some(ls) = scene.lights.sample(eye, None, u_pick, u_light) {
            let k = (1.0 + ls.wi.dot(axis)) * 0.25;
            if k > 0.0 && !(variant.out_fov && view.in_frustum((r, up, axis), ls.wi)) {
                let tr =
                    shadow_transmittance(scene, &mut scene.geometry.scratch(), eye, ls.wi, ls.dist);
                let w = if ls.delta {
                    1.0
                } else {
                    power_heuristic(ls.pdf, k / PI)
                };
                comps[0] += ls.li * tr * (k * w / ls.pdf);
            }
        }
        let (mu, phi) = sample_cardioid(u_dir);
        let st = (1.0 - mu * mu).max(0.0).sqrt();
        let dir = (r * (st * phi.cos()) + up * (st * phi.sin()) + axis * mu).normalize();
        if mu > -1.0 && !(variant.out_fov && view.in_frustum((r, up, axis), dir)) {
            let pdf = (1.0 + mu) / (4.0 * PI);
            let k = variant.split.max(1);
            for j in 0..k {
                let seeds = StreamSeeds::new(hash_key(&[pkey, 1000 + j as u64]));
                let mut sj = SampleStream::seeded(&seeds, 0);
                let pk = hash_key(&[pkey, 2000 + j as u64]);
                let sc = PI / k as f32;
                if j == 0 && !variant.random_rest {
                    eye_path(
                        scene, &units, eye, dir, pdf, &mut s, path, variant, pk, sc, &mut comps,
                    );
                } else {
                    eye_path(
                        scene, &units, eye, dir, pdf, &mut sj, path, variant, pk, sc, &mut comps,
                    );
                }
            }
        }
        let sum: Vec3A = comps.iter().copied().sum();
        if sum.is_finite() {
            for c in 0..PROBE_COMPONENTS {
                total[c] += comps[c].as_dvec3();
            }
        }
    }
    total.map(|t| t / settings.samples as f64)
}
