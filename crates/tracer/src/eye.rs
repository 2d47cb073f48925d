//! The eye-centred hemispherical sensor of Gruson, Ribardière and Cozot (estimators.md §1).
//!
//! With the sensor's radius → 0, the average irradiance over a hemisphere whose pole is the
//! gaze axis `a` is a cardioid-weighted integral of all incident radiance:
//!
//! ```text
//! x_eye = ∫_{S²} L(eye, ω) K(ω) dω,   K(ω) = (1 + cos θ) / 4,   θ = ∠(ω, a)
//! ```
//!
//! It is estimated with two strategies combined by MIS (power heuristic): directions drawn
//! from the cardioid itself (pdf K/π, so each sample weighs π) followed by an ordinary path,
//! and light sampling from the eye (the only way to see point and spot lights). The sensor is
//! not geometry: it never appears in the image and does not occlude anything.
//!
//! By default every frame uses the same random numbers (common random numbers), so Monte-Carlo
//! noise does not turn into frame-to-frame jitter of the adaptation colour.
//!
//! **Standard error.** The paths are split into [`EYE_REPLICATES`] independently scrambled
//! low-discrepancy sequences (randomised QMC): path `i` is path `i / R` of replicate `i % R`.
//! Each replicate is an unbiased estimate on its own, so the spread of the replicate means is
//! an honest estimate of the error of their average. The i.i.d. formula (sample covariance / N)
//! ignores the stratification and overstated the error 1.7–2.3× on the paper's scenes (issue 22).
use crate::film::View;
use crate::integrator::{Origin, PathSettings, power_heuristic, trace};
use crate::sampler::{SampleStream, StreamSeeds, hash_key};
use crate::scene_data::SceneData;
use crate::shadow::shadow_transmittance;
use crate::trig::sincos_turns;
use glam::{DMat3, DVec3, Vec3, Vec3A};
use rayon::prelude::*;
use std::f32::consts::PI;

/// Sensor parameters.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct EyeSettings {
    /// Most sensor paths per frame (estimators.md §10: 16 384).
    pub samples: u32,
    /// Paths traced before the caller's stopping rule is first asked (see [`eye_sensor_until`]);
    /// `min_samples >= samples` gives a fixed budget.
    pub min_samples: u32,
    /// Common random numbers across frames (default true).
    pub common_random_numbers: bool,
    /// The `eye_fov` ablation: only directions inside the camera frustum count.
    pub fov_only: bool,
    pub seed: u64,
}

impl Default for EyeSettings {
    fn default() -> Self {
        EyeSettings {
            samples: 16_384,
            min_samples: 16_384,
            common_random_numbers: true,
            fov_only: false,
            seed: 0,
        }
    }
}

/// The sensor reading: mean irradiance (linear sRGB) and the covariance of that mean.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct EyeEstimate {
    pub mean_rgb: DVec3,
    /// Covariance matrix of `mean_rgb`, from the spread of the [`EYE_REPLICATES`] replicate
    /// means (zero when fewer than two replicates have a path).
    pub cov_rgb: DMat3,
    pub samples: u64,
    pub invalid_samples: u64,
}

/// Independently scrambled replicates the paths are dealt into (randomised QMC batches). 16
/// gives the error estimate 15 degrees of freedom (its own relative error is about 18 %).
pub const EYE_REPLICATES: usize = 16;

#[derive(Clone, Copy, Default)]
struct Partial {
    /// Per replicate: sum of the path values and number of valid paths.
    sum: [DVec3; EYE_REPLICATES],
    n: [u64; EYE_REPLICATES],
    invalid: u64,
}

impl Partial {
    fn add(&mut self, p: &Partial) {
        for b in 0..EYE_REPLICATES {
            self.sum[b] += p.sum[b];
            self.n[b] += p.n[b];
        }
        self.invalid += p.invalid;
    }
}

/// Samples per parallel task (a multiple of [`EYE_REPLICATES`]); fixed so that the reduction
/// order never depends on threads.
const CHUNK: u32 = 256;

/// Paths added between two consultations of the stopping rule (a multiple of [`CHUNK`]).
pub const EYE_ROUND: u32 = 2048;

/// Direction with cos θ = μ around `axis` drawn from the cardioid pdf (1 + cos θ)/(4π).
#[inline]
pub fn sample_cardioid(u: [f32; 2]) -> (f32, f32) {
    let mu = 2.0 * u[0].sqrt() - 1.0;
    (mu, 2.0 * PI * u[1])
}

/// Estimates the eye sensor at `view.position`, pole on `view.forward`, with a fixed budget of
/// `settings.samples` paths.
pub fn eye_sensor(
    scene: &SceneData,
    view: &View,
    settings: &EyeSettings,
    frame: u32,
    path: PathSettings,
) -> EyeEstimate {
    let fixed = EyeSettings {
        min_samples: settings.samples,
        ..*settings
    };
    eye_sensor_until(scene, view, &fixed, frame, path, |_| false)
}

/// Estimates the eye sensor, stopping early once `done` accepts the running estimate.
///
/// Paths are traced in rounds of [`EYE_ROUND`]: after `min_samples` paths and after every round
/// beyond them, `done` sees the estimate so far (e.g. "standard error of u′v′ below a target")
/// and ends the reading when it returns true; `samples` caps the total. Every path is a pure
/// function of its index and partial sums are folded in index order, so where the reading stops,
/// and its bits, never depend on the thread count. (Stopping on the reading's own error estimate
/// correlates the two slightly; with thousands of paths before the first check this bias is far
/// below the noise.)
pub fn eye_sensor_until(
    scene: &SceneData,
    view: &View,
    settings: &EyeSettings,
    frame: u32,
    path: PathSettings,
    done: impl Fn(&EyeEstimate) -> bool,
) -> EyeEstimate {
    let key = if settings.common_random_numbers {
        hash_key(&[settings.seed, 0xE7E_5E45, 0])
    } else {
        hash_key(&[settings.seed, 0xE7E_5E45, 1, frame as u64])
    };
    let replicate_seeds: [StreamSeeds; EYE_REPLICATES] =
        std::array::from_fn(|b| StreamSeeds::new(hash_key(&[key, 0x4E9_11CA, b as u64])));
    let eye = Vec3A::from(view.position);
    let basis = view.basis();
    let (r, u, axis) = basis.axes();
    let one = |i: u32| -> Option<Vec3A> {
        let b = i as usize % EYE_REPLICATES;
        let mut s = SampleStream::seeded(&replicate_seeds[b], i / EYE_REPLICATES as u32);
        let u_pick = s.next_1d();
        let _ = s.next_1d();
        let u_light = s.next_2d();
        // Dimensions 0-1 of the next chunk; `trace` draws the first hit's light sample from
        // dimensions 2-3, so that direct light there is stratified jointly with the direction.
        s.start_group();
        let u_dir = s.next_2d();
        let mut x = Vec3A::ZERO;
        // Light sampling from the eye (includes the direct term of point and spot lights).
        if let Some(ls) = scene.lights.sample(eye, None, u_pick, u_light) {
            let cos = ls.wi.dot(axis);
            let k = (1.0 + cos) * 0.25;
            let seen = k > 0.0 && (!settings.fov_only || view.in_frustum(basis, ls.wi));
            // Through thin panes (a sun behind a window) and cut-outs with their transmittance.
            let tr = if seen {
                shadow_transmittance(scene, &mut scene.geometry.scratch(), eye, ls.wi, ls.dist)
            } else {
                Vec3A::ZERO
            };
            if tr.max_element() > 0.0 {
                let w = if ls.delta {
                    1.0
                } else {
                    power_heuristic(ls.pdf, k / PI)
                };
                x += ls.li * tr * (k * w / ls.pdf);
            }
        }
        // A cardioid-distributed path.
        let (mu, _) = sample_cardioid(u_dir);
        let (sin_phi, cos_phi) = sincos_turns(u_dir[1]);
        let st = (1.0 - mu * mu).max(0.0).sqrt();
        let dir = (r * (st * cos_phi) + u * (st * sin_phi) + axis * mu).normalize();
        if (!settings.fov_only || view.in_frustum(basis, dir)) && mu > -1.0 {
            let pdf = (1.0 + mu) / (4.0 * PI);
            let p = trace(scene, eye, dir, Origin::Sampled { pdf }, &mut s, path, None);
            x += p.l * PI;
        }
        x.is_finite().then_some(x)
    };
    let chunk_partial = |c: u32| {
        let mut p = Partial::default();
        for i in c * CHUNK..((c + 1) * CHUNK).min(settings.samples) {
            let b = i as usize % EYE_REPLICATES;
            match one(i) {
                Some(x) => {
                    p.sum[b] += Vec3::from(x).as_dvec3();
                    p.n[b] += 1;
                }
                None => p.invalid += 1,
            }
        }
        p
    };
    let all_chunks = settings.samples.div_ceil(CHUNK);
    let mut total = Partial::default();
    let mut next = 0u32;
    // The first round reaches `min_samples`, later ones add EYE_ROUND paths each.
    let mut end = settings
        .min_samples
        .max(1)
        .min(settings.samples)
        .div_ceil(CHUNK);
    loop {
        let partials: Vec<Partial> = (next..end).into_par_iter().map(chunk_partial).collect();
        for p in &partials {
            total.add(p);
        }
        next = end;
        if next >= all_chunks || done(&summarize(&total)) {
            break;
        }
        end = (next + EYE_ROUND / CHUNK).min(all_chunks);
    }
    summarize(&total)
}

fn summarize(total: &Partial) -> EyeEstimate {
    let n: u64 = total.n.iter().sum();
    let nf = n.max(1) as f64;
    let mean = total.sum.iter().sum::<DVec3>() / nf;
    // Var(Σ n_b m_b / N) = Σ (n_b/N)² Var(m_b), each Var(m_b) read off the replicates' spread
    // (with equal n_b this is the textbook Σ (m_b − m̄)² / (R (R − 1))).
    let used = total.n.iter().filter(|&&k| k > 0).count();
    let mut cov = DMat3::ZERO;
    if used > 1 {
        for b in (0..EYE_REPLICATES).filter(|&b| total.n[b] > 0) {
            let d = total.sum[b] / total.n[b] as f64 - mean;
            let w = (total.n[b] as f64 / nf).powi(2);
            cov += DMat3::from_cols(d * d.x, d * d.y, d * d.z) * w;
        }
        cov *= used as f64 / (used as f64 - 1.0);
    }
    EyeEstimate {
        mean_rgb: mean,
        cov_rgb: cov,
        samples: n + total.invalid,
        invalid_samples: total.invalid,
    }
}

/// Each light's share of the sensor's direct term Φ_direct (estimators.md §4, `dominant_by =
/// eye`): (emission, intensity, irradiance or mean environment colour, luminance of its direct
/// contribution). Area lights are grouped by emission colour, like [`crate::LightSet::fluxes`];
/// point, spot and directional lights are exact, area lights and the environment use
/// `samples` stratified points or directions each.
pub fn eye_direct_per_light(
    scene: &SceneData,
    view: &View,
    samples: u32,
    seed: u64,
) -> Vec<(Vec3A, f64)> {
    use crate::emitter::luminance;
    let eye = Vec3A::from(view.position);
    let axis = view.basis().f;
    let mut out: Vec<(Vec3A, f64)> = Vec::new();
    let lights = &scene.lights;
    let mut scratch = scene.geometry.scratch();
    let mut groups: Vec<(Vec3A, Vec<usize>, f32)> = Vec::new();
    for (i, a) in lights.area.iter().enumerate() {
        match groups.iter_mut().find(|g| g.0 == a.emission) {
            Some(g) => {
                g.1.push(i);
                g.2 += a.area;
            }
            None => groups.push((a.emission, vec![i], a.area)),
        }
    }
    for (gi, (emission, tris, total_area)) in groups.iter().enumerate() {
        let key = hash_key(&[seed, 0xD0_0041, gi as u64]);
        let mut sum = 0.0f64;
        // Pick triangles by area with a running CDF, then a uniform point on the triangle.
        let cdf: Vec<f32> = tris
            .iter()
            .scan(0.0, |acc, &t| {
                *acc += lights.area[t].area / total_area;
                Some(*acc)
            })
            .collect();
        let seeds = StreamSeeds::new(key);
        for i in 0..samples {
            let mut s = SampleStream::seeded(&seeds, i);
            let u0 = s.next_1d();
            let _ = s.next_1d();
            let u = s.next_2d();
            let k = cdf.partition_point(|&c| c <= u0).min(tris.len() - 1);
            let a = &lights.area[tris[k]];
            let su = u[0].sqrt();
            let (b1, b2) = (su * (1.0 - u[1]), su * u[1]);
            let y = a.v0 + a.e1 * b1 + a.e2 * b2;
            let d = y - eye;
            let d2 = d.length_squared();
            let wi = d / d2.sqrt();
            let cos_l = -a.n.dot(wi);
            let kern = (1.0 + wi.dot(axis)) * 0.25;
            if cos_l > 0.0 && kern > 0.0 {
                let tr = shadow_transmittance(scene, &mut scratch, eye, wi, d2.sqrt());
                let radiance = a.radiance(b1, b2, &lights.textures);
                sum += (luminance(radiance * tr) * kern * cos_l / d2) as f64;
            }
        }
        out.push((*emission, sum * *total_area as f64 / samples.max(1) as f64));
    }
    for l in &lights.deltas {
        let v = match l.arrival(eye, crate::beam::Lookup::Texture(&lights.textures)) {
            Some(a) => {
                let kern = (1.0 + a.wi.dot(axis)) * 0.25;
                if kern > 0.0 {
                    let tr = shadow_transmittance(scene, &mut scratch, eye, a.wi, a.dist);
                    (luminance(a.li * tr) * kern) as f64
                } else {
                    0.0
                }
            }
            None => 0.0,
        };
        out.push((l.colour(), v));
    }
    if let Some(env) = &lights.env {
        // The environment's directions drawn from its own density, each seen unless occluded.
        let seeds = StreamSeeds::new(hash_key(&[seed, 0xD0_0042]));
        let mut sum = 0.0f64;
        for i in 0..samples {
            let Some(s) = env.sample(SampleStream::seeded(&seeds, i).next_2d()) else {
                continue;
            };
            let kern = (1.0 + s.wi.dot(axis)) * 0.25;
            if kern > 0.0 {
                let tr = shadow_transmittance(scene, &mut scratch, eye, s.wi, f32::INFINITY);
                sum += (luminance(s.li * tr) * kern / s.pdf) as f64;
            }
        }
        out.push((env.mean(), sum / samples.max(1) as f64));
    }
    out
}
