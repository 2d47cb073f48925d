//! Unidirectional path tracing with next-event estimation and multiple importance sampling
//! (power heuristic), Russian roulette, and the first-vertex AOVs the estimators need.
//!
//! **Depth convention (same as Mitsuba 3's `path` integrator):** `max_depth` is the largest
//! number of path segments. 1 renders only directly visible emitters, 2 adds direct
//! lighting, −1 is unlimited. Russian roulette starts once `rr_depth` segments have been
//! traced, with survival probability min(max(throughput), 0.95).
use crate::emitter::luminance;
use crate::geometry::{Hit, RayScratch};
use crate::guiding::{Record, SdTree};
use crate::path_state::{PathState, ShadowRay};
use crate::sampler::SampleStream;
use crate::scene_data::SceneData;
use crate::vertex::{Vertex, VertexSamples};
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

/// How the WCAM achromatic re-render (the `achromatic` AOV) takes specular first bounces
/// (estimators.md §2.3, the job file's `estimators.wcam.specular`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum AchromaticSpecular {
    /// Every lobe of the first surface, in grey (the default).
    #[default]
    Include,
    /// Samples whose first scattering event is a delta lobe (a mirror, glass, a pane; not a
    /// mask's hole) add nothing to the re-render.
    ExcludeDelta,
    /// As `ExcludeDelta`, and at the first non-delta surface only its diffuse lobe, in grey:
    /// A = Y(f_d)·L·cos/pdf, which is Y(ρ_d)·E/π for a Lambertian base. On a Lambertian
    /// surface this is `Include`, bit for bit.
    DiffuseOnly,
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
    /// The frame around unit normal `n` whose +x is `tangent` made perpendicular to `n`
    /// (Mitsuba's shading frame, which anisotropic BSDFs need); [`Frame::new`]'s where the
    /// tangent is parallel to `n` or zero.
    #[inline]
    pub fn with_tangent(n: Vec3A, tangent: Vec3A) -> Frame {
        let s = (tangent - n * n.dot(tangent)).normalize_or_zero();
        if s == Vec3A::ZERO || !s.is_finite() {
            return Frame::new(n);
        }
        Frame {
            s,
            t: n.cross(s),
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
pub fn achromatic_ratio(f: Vec3A) -> Vec3A {
    grey_ratio(luminance(f), f)
}

/// Per-channel factor that turns a BSDF value `f` into the grey of luminance `y`, guarded
/// where a channel is nearly black.
#[inline]
pub fn grey_ratio(y: f32, f: Vec3A) -> Vec3A {
    let r = |c: f32| (y / c.max(1e-8)).min(1e3);
    Vec3A::new(r(f.x), r(f.y), r(f.z))
}

#[inline]
pub fn irradiance_ratio(f: Vec3A) -> Vec3A {
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
    scene
        .geometry
        .unoccluded_with(scratch, from, wi, crate::shadow::shadow_tmax(dist))
}

/// Traces one path from `origin` along `dir` and returns its radiance plus first-vertex AOVs
/// (the AOVs are only filled when `aovs` is given, with the WCAM re-render's specular mode).
///
/// The first thing drawn from `s` is the first vertex's 2-D light sample: callers draw their
/// direction from dimensions 0-1 of a chunk and leave `s` there, so that the two share it.
///
/// The loop only sequences the named steps of [`PathState`]; each step reads and advances
/// the path's state, so a batched executor can run the same steps over many paths.
pub fn trace(
    scene: &SceneData,
    o: Vec3A,
    d: Vec3A,
    from: Origin,
    s: &mut SampleStream,
    settings: PathSettings,
    aovs: Option<AchromaticSpecular>,
) -> PathSample {
    let mut scratch = scene.geometry.scratch();
    trace_guided(
        &mut scratch,
        scene,
        (o, d),
        from,
        s,
        settings,
        aovs,
        None,
        None,
        None,
    )
}

/// [`trace`], sampling from `guide` where guiding applies (`guiding/`) and, given `records`,
/// appending the path's training records to it. Without a guide it is [`trace`], bit for bit.
/// `scratch` is the traversal state, reused: a caller tracing many paths (a pixel's samples)
/// zeroes its two 256-byte stacks once instead of once a path (80 instructions a sample).
/// `first`, when given, is the closest hit of the path's first ray, found already (a pixel's
/// camera rays are walked together, `packet.rs`).
#[allow(clippy::too_many_arguments)]
pub(crate) fn trace_guided(
    scratch: &mut RayScratch,
    scene: &SceneData,
    (o, d): (Vec3A, Vec3A),
    from: Origin,
    s: &mut SampleStream,
    settings: PathSettings,
    aovs: Option<AchromaticSpecular>,
    guide: Option<&SdTree>,
    records: Option<&mut Vec<Record>>,
    mut first: Option<Option<Hit>>,
) -> PathSample {
    // The first vertex's light sample comes from the dimensions right after the caller's
    // direction (the pixel position, the eye's cardioid direction), in the same 4-D Sobol chunk:
    // direct light at the first hit is then one jointly stratified 4-D integral over
    // (direction, light point) instead of two 2-D ones paired at random. Every later vertex
    // likewise draws its light sample together with the direction that leads to it.
    let mut path = PathState::new(o, d, from, s.next_2d(), aovs);
    path.use_guide(guide, records.is_some());
    let max_depth = if settings.max_depth < 0 {
        u32::MAX
    } else {
        settings.max_depth as u32
    };
    // A vertex's shadow ray, walked together with the ray that continues the path
    // (`traverse_pair.rs`). Its light is added right after that walk, before anything the next
    // hit adds, so the path's sums are made in the same order as when it was traced at once.
    let mut shadow: Option<ShadowRay> = None;
    loop {
        s.start_group();
        let hit = match shadow.take() {
            None => match first.take() {
                Some(hit) => hit,
                None => scene
                    .geometry
                    .intersect_with(scratch, path.o, path.d, f32::INFINITY),
            },
            Some(sh) => {
                let (hit, free) = scene.geometry.intersect_and_unoccluded(
                    scratch,
                    (path.o, path.d, f32::INFINITY),
                    (sh.from, sh.wi, sh.tmax),
                );
                if free {
                    path.add_light(sh.add);
                }
                hit
            }
        };
        let Some(hit) = hit else {
            path.escape(&scene.lights);
            break;
        };
        let si = scene
            .geometry
            .interaction(path.o, path.d, &hit, scene.parameterisation);
        path.shade_hit(scene, &si);
        // At the depth limit the path ends, unless it may cross a see-through surface here
        // (`shadow.rs`: a crossing is no segment).
        let last = path.depth + 1 >= max_depth;
        if last && !scene.see_through {
            break;
        }
        let u = VertexSamples::draw(s);
        let v = Vertex::new(scene, &si, -path.d, &u);
        let g = if last { None } else { path.guide_at(&v) };
        // The light sample first, the BSDF sample (independent of it) next, then the rest of
        // next-event estimation: the core overlaps the two (`PathState::light_sample`).
        let ls = if last {
            None
        } else {
            path.light_sample(scene, &v, &u)
        };
        let bs = PathState::sample_bsdf(&v, &u, g);
        if !last {
            shadow = path.sample_light(scene, scratch, &v, ls, g);
        }
        if !path.scatter(&v, &u, last, (g, bs)) || !path.roulette(settings.rr_depth, u.rr) {
            break;
        }
    }
    // The path ended with a shadow ray left: alone, then.
    if let Some(sh) = shadow
        && scene
            .geometry
            .unoccluded_with(scratch, sh.from, sh.wi, sh.tmax)
    {
        path.add_light(sh.add);
    }
    if let (Some(r), Some(tree), Some(out)) = (&path.recorder, guide, records) {
        r.finish(path.out.l, tree, out);
    }
    path.out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sampler::hash_key;

    #[test]
    fn a_scratch_shared_by_many_paths_traces_what_fresh_ones_do() {
        // The Cornell box flat, and with its last mesh placed twice (two levels, whose
        // traversal uses both states of the scratch).
        let mut two_levels = false;
        for twice in [false, true] {
            let mut box_scene = eyeadapt_scene::load_builtin("cornell-box").unwrap();
            if twice {
                let last = *box_scene.instances.last().unwrap();
                let mut t = last.to_world;
                t.matrix = glam::Mat4::from_translation(glam::Vec3::new(0.1, 0.05, 0.1)) * t.matrix;
                box_scene.add_instance(last.mesh, last.material, t);
            }
            let name = if twice { "two levels" } else { "flat" };
            let scene = SceneData::new(&box_scene);
            let (lo, hi) = (scene.geometry.bounds_min, scene.geometry.bounds_max);
            two_levels |= scene.geometry.is_two_level();
            let mut shared = scene.geometry.scratch();
            let mut hits = 0;
            for k in 0..400u64 {
                let key = hash_key(&[k]);
                let mut s = SampleStream::new(key, 0);
                let [a, b, c, e] = s.next_4d();
                let o = lo + (hi - lo) * Vec3A::new(0.2 + 0.6 * a, 0.2 + 0.6 * b, 0.5);
                let (z, phi) = (1.0 - 2.0 * c, std::f32::consts::TAU * e);
                let r = (1.0 - z * z).max(0.0).sqrt();
                let d = Vec3A::new(r * libm::cosf(phi), r * libm::sinf(phi), z);
                let (mut s1, mut s2) = (s, s);
                let settings = PathSettings::default();
                let fresh = trace(&scene, o, d, Origin::Camera, &mut s1, settings, None);
                let reused = trace_guided(
                    &mut shared,
                    &scene,
                    (o, d),
                    Origin::Camera,
                    &mut s2,
                    settings,
                    None,
                    None,
                    None,
                    None,
                );
                // The first hit found beforehand (as a packet of camera rays finds it).
                let first = scene
                    .geometry
                    .intersect_with(&mut shared, o, d, f32::INFINITY);
                let mut s3 = s;
                let given = trace_guided(
                    &mut shared,
                    &scene,
                    (o, d),
                    Origin::Camera,
                    &mut s3,
                    settings,
                    None,
                    None,
                    None,
                    Some(first),
                );
                assert_eq!(
                    fresh.l.to_array().map(f32::to_bits),
                    reused.l.to_array().map(f32::to_bits)
                );
                assert_eq!(
                    fresh.l.to_array().map(f32::to_bits),
                    given.l.to_array().map(f32::to_bits)
                );
                hits += (fresh.l != Vec3A::ZERO) as u32;
            }
            assert!(hits > 100, "{name}: the paths must find light ({hits})");
        }
        assert!(two_levels);
    }
}
