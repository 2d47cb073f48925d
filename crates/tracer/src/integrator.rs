//! Unidirectional path tracing with next-event estimation and multiple importance sampling
//! (power heuristic), Russian roulette, and the first-vertex AOVs the estimators need.
//!
//! **Depth convention (same as Mitsuba 3's `path` integrator):** `max_depth` is the largest
//! number of path segments. 1 renders only directly visible emitters, 2 adds direct
//! lighting, −1 is unlimited. Russian roulette starts once `rr_depth` segments have been
//! traced, with survival probability min(max(throughput), 0.95).
use crate::emitter::luminance;
use crate::geometry::RayScratch;
use crate::lights::LightSet;
use crate::sampler::SampleStream;
use crate::scene_data::SceneData;
use glam::Vec3A;

/// Path-length settings.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct PathSettings {
    /// Mitsuba `max_depth` (−1 = unlimited).
    pub max_depth: i32,
    /// Mitsuba `rr_depth`.
    pub rr_depth: u32,
}

impl Default for PathSettings {
    fn default() -> Self {
        PathSettings {
            max_depth: 8,
            rr_depth: 5,
        }
    }
}

/// What one camera sample returns.
#[derive(Clone, Copy, Debug, Default)]
pub struct PathSample {
    pub l: Vec3A,
    /// WCAM achromatic re-render: the first vertex's BSDF replaced by its luminance (grey).
    pub achromatic: Vec3A,
    /// Irradiance at the first vertex (first-vertex BSDF replaced by a white Lambertian, ×π).
    pub irradiance: Vec3A,
    /// One-sample estimate of the first vertex's directional-hemispherical reflectance.
    pub albedo: Vec3A,
    pub normal: Vec3A,
    pub depth: f32,
    pub hit: bool,
    pub emitter: bool,
}

/// Where the path came from, for MIS at the next emitter hit.
#[derive(Clone, Copy, Debug)]
pub enum Origin {
    /// A camera ray: emitters seen directly get full weight.
    Camera,
    /// A sampled direction with this solid-angle density, competing with light sampling.
    Sampled { pdf: f32 },
}

#[inline]
pub fn power_heuristic(a: f32, b: f32) -> f32 {
    let a2 = a * a;
    let b2 = b * b;
    if a2 + b2 == 0.0 { 0.0 } else { a2 / (a2 + b2) }
}

/// Local frame around a unit normal (Duff et al. 2017, branchless ONB).
#[derive(Clone, Copy, Debug)]
pub struct Frame {
    pub s: Vec3A,
    pub t: Vec3A,
    pub n: Vec3A,
}

impl Frame {
    #[inline]
    pub fn new(n: Vec3A) -> Frame {
        let sign = 1f32.copysign(n.z);
        let a = -1.0 / (sign + n.z);
        let b = n.x * n.y * a;
        Frame {
            s: Vec3A::new(1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x),
            t: Vec3A::new(b, sign + n.y * n.y * a, -n.y),
            n,
        }
    }
    #[inline]
    pub fn to_local(self, v: Vec3A) -> Vec3A {
        Vec3A::new(v.dot(self.s), v.dot(self.t), v.dot(self.n))
    }
    #[inline]
    pub fn to_world(self, v: Vec3A) -> Vec3A {
        self.s * v.x + self.t * v.y + self.n * v.z
    }
}

/// Offset of ray origins off a surface, relative to the coordinates' magnitude.
#[inline]
pub fn offset(p: Vec3A, n: Vec3A) -> Vec3A {
    p + n * (1e-4 * (1.0 + p.abs().max_element()))
}

/// Per-channel factor that turns a BSDF value into its grey, luminance-preserving version
/// (estimators.md §2.2 b), guarded where a channel is nearly black.
#[inline]
fn achromatic_ratio(f: Vec3A) -> Vec3A {
    let y = luminance(f);
    let r = |c: f32| (y / c.max(1e-8)).min(1e3);
    Vec3A::new(r(f.x), r(f.y), r(f.z))
}

#[inline]
fn irradiance_ratio(f: Vec3A) -> Vec3A {
    let r = |c: f32| if c > 1e-8 { 1.0 / c } else { 0.0 };
    Vec3A::new(r(f.x), r(f.y), r(f.z))
}

/// Unoccluded-visibility test from a shading point towards a light sample.
#[inline]
pub fn visible(
    scene: &SceneData,
    scratch: &mut RayScratch,
    from: Vec3A,
    wi: Vec3A,
    dist: f32,
) -> bool {
    let tmax = if dist.is_finite() {
        dist * (1.0 - 2e-4)
    } else {
        f32::INFINITY
    };
    scene.geometry.unoccluded_with(scratch, from, wi, tmax)
}

/// Traces one path from `origin` along `dir` and returns its radiance plus first-vertex AOVs
/// (the AOVs are only filled when `aovs` is set).
///
/// The first thing drawn from `s` is the first vertex's 2-D light sample: callers draw their
/// direction from dimensions 0-1 of a chunk and leave `s` there, so that the two share it.
pub fn trace(
    scene: &SceneData,
    mut o: Vec3A,
    mut d: Vec3A,
    from: Origin,
    s: &mut SampleStream,
    settings: PathSettings,
    aovs: bool,
) -> PathSample {
    let lights: &LightSet = &scene.lights;
    let mut scratch = scene.geometry.scratch();
    let mut out = PathSample::default();
    let mut beta = Vec3A::ONE;
    // Factors applied to contributions that pass through the first vertex (AOVs).
    let mut ka = Vec3A::ZERO;
    let mut ke = Vec3A::ZERO;
    let mut prev = from;
    let mut prev_p = o;
    // Normal of the vertex `prev_p` is on (none at the start: a camera or the eye).
    let mut prev_n: Option<Vec3A> = None;
    let mut depth: u32 = 0;
    // The first vertex's light sample comes from the dimensions right after the caller's
    // direction (the pixel position, the eye's cardioid direction), in the same 4-D Sobol chunk:
    // direct light at the first hit is then one jointly stratified 4-D integral over
    // (direction, light point) instead of two 2-D ones paired at random. Every later vertex
    // likewise draws its light sample together with the direction that leads to it.
    let mut u_light = s.next_2d();
    let max_depth = if settings.max_depth < 0 {
        u32::MAX
    } else {
        settings.max_depth as u32
    };
    loop {
        s.start_group();
        let Some(hit) = scene
            .geometry
            .intersect_with(&mut scratch, o, d, f32::INFINITY)
        else {
            if let Some(env) = lights.env {
                let w = match prev {
                    Origin::Camera => 1.0,
                    Origin::Sampled { pdf } => power_heuristic(pdf, lights.pdf_env(prev_p, prev_n)),
                };
                let c = beta * env * w;
                out.l += c;
                if depth > 0 {
                    out.achromatic += c * ka;
                    out.irradiance += c * ke;
                }
            }
            break;
        };
        let si = scene.geometry.interaction(o, d, &hit);
        let wo = -d;
        let front = si.ng.dot(wo) > 0.0;
        if aovs && depth == 0 {
            out.hit = true;
            out.depth = si.t;
            out.normal = si.ns;
        }
        // Emission (one-sided: front face only).
        if front && si.light != u32::MAX {
            let emission = scene.materials.emission(si.material);
            let w = match prev {
                Origin::Camera => 1.0,
                Origin::Sampled { pdf } => {
                    power_heuristic(pdf, lights.pdf_area(si.light, prev_p, prev_n, si.p))
                }
            };
            let c = beta * emission * w;
            out.l += c;
            if depth == 0 {
                out.emitter = true;
            } else {
                out.achromatic += c * ka;
                out.irradiance += c * ke;
            }
        }
        if depth + 1 >= max_depth {
            break;
        }
        // Shading frame on the viewer's side; every surface reflects on both sides.
        let ng = if front { si.ng } else { -si.ng };
        let ns = if si.ns.dot(ng) < 0.0 { -si.ns } else { si.ns };
        let frame = Frame::new(ns);
        let wo_l = frame.to_local(wo);
        let bsdf = scene.materials.bsdf(&si);
        let u_pick = s.next_1d();
        let u_lobe = s.next_1d();
        let u_rr = s.next_1d();
        let _ = s.next_1d();
        let u_bsdf = s.next_2d();
        let u_light_next = s.next_2d();
        let p = offset(si.p, ng);

        // Next-event estimation.
        if !bsdf.is_delta()
            && let Some(ls) = lights.sample(p, Some(ng), u_pick, u_light)
            && ls.wi.dot(ng) > 0.0
        {
            let wi_l = frame.to_local(ls.wi);
            let f = bsdf.eval(wo_l, wi_l);
            if f.max_element() > 0.0 && visible(scene, &mut scratch, p, ls.wi, ls.dist) {
                let w = if ls.delta {
                    1.0
                } else {
                    power_heuristic(ls.pdf, bsdf.pdf(wo_l, wi_l))
                };
                let c = beta * f * ls.li * (wi_l.z * w / ls.pdf);
                out.l += c;
                if depth == 0 {
                    out.achromatic += c * achromatic_ratio(f);
                    out.irradiance += c * irradiance_ratio(f);
                } else {
                    out.achromatic += c * ka;
                    out.irradiance += c * ke;
                }
            }
        }

        // Continue by sampling the BSDF.
        let Some(bs) = bsdf.sample(wo_l, u_lobe, u_bsdf) else {
            break;
        };
        let wi = frame.to_world(bs.wi);
        if wi.dot(ng) <= 0.0 {
            break; // below the geometric surface: shading-normal artefact, no light there
        }
        if depth == 0 {
            out.albedo = bs.weight;
            if bs.delta {
                ka = achromatic_ratio(bs.weight);
                ke = Vec3A::ZERO; // irradiance cannot be estimated through a delta lobe
            } else {
                ka = achromatic_ratio(bs.f);
                ke = irradiance_ratio(bs.f);
            }
        }
        beta *= bs.weight;
        u_light = u_light_next;
        prev = if bs.delta {
            Origin::Camera
        } else {
            Origin::Sampled { pdf: bs.pdf }
        };
        // The actual ray origin and the normal NEE used, so MIS at the next emitter hit sees
        // the same light-choice probability as NEE computed here.
        prev_p = p;
        prev_n = Some(ng);
        o = p;
        d = wi;
        depth += 1;
        if depth >= settings.rr_depth {
            let q = beta.max_element().min(0.95);
            if u_rr >= q {
                break;
            }
            beta /= q;
        }
        if beta.max_element() <= 0.0 {
            break;
        }
    }
    out
}
