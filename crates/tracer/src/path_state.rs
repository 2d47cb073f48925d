//! One path's state between the integrator's named steps, and the steps themselves:
//! [`PathState::escape`] (the ray left the scene), [`PathState::shade_hit`] (emission at a
//! hit), [`PathState::light_sample`] and [`PathState::sample_light`] (next-event estimation),
//! [`PathState::sample_bsdf`] and [`PathState::scatter`] (continue along a BSDF sample,
//! reflected or transmitted) and [`PathState::roulette`].
//!
//! **The AOV vertex** is the first vertex that is not a delta event (the first non-specular
//! hit): seen through glass, a mirror or a mask's hole, the AOVs (albedo, normal, depth, the
//! WCAM and irradiance re-renders) read the surface behind, with the specular chain's
//! throughput, and whatever the chain itself shows (an emitter, the environment) counts as seen
//! directly. Without such chains it is the first hit.
//!
//! Everything a step needs from earlier steps lives in [`PathState`]; everything it needs
//! about the current surface lives in [`Vertex`]; its random numbers come in
//! [`VertexSamples`]. A batched or wavefront executor can therefore run one step over many
//! paths at a time and get the same result as [`crate::trace`].
use crate::bsdf::BsdfSample;
use crate::emitter::luminance;
use crate::geometry::RayScratch;
use crate::guiding::{DTree, Recorder, SdTree, guidable, mixture_pdf, sample_guided};
use crate::integrator::{
    AchromaticSpecular, Origin, PathSample, achromatic_ratio, grey_ratio, irradiance_ratio,
    power_heuristic,
};
use crate::interaction::SurfaceInteraction;
use crate::lights::{LightSample, LightSet};
use crate::scene_data::SceneData;
use crate::shadow::{shadow_tmax, shadow_transmittance};
use crate::vertex::{Vertex, VertexSamples};
use glam::Vec3A;

/// The state of a path between steps.
pub struct PathState<'g> {
    /// The ray to trace next.
    pub o: Vec3A,
    pub d: Vec3A,
    /// Throughput: the product of BSDF weights so far.
    pub beta: Vec3A,
    /// Segments traced so far.
    pub depth: u32,
    /// How the current ray was chosen, for MIS at the emitter it reaches.
    prev: Origin,
    /// Where the current ray starts and the normal light choice used there (none at the
    /// camera or the eye, or where the BSDF transmits).
    prev_p: Vec3A,
    prev_n: Option<Vec3A>,
    /// The 2-D light sample of the next vertex (drawn with the direction that leads to it).
    u_light: [f32; 2],
    /// Factors applied to contributions that pass through the AOV vertex.
    ka: Vec3A,
    ke: Vec3A,
    aovs: bool,
    /// The WCAM re-render's specular mode.
    wcam: AchromaticSpecular,
    /// The path's first scattering event was a delta lobe and the mode leaves such samples
    /// out of the WCAM re-render.
    wcam_dropped: bool,
    /// True until the AOV vertex has scattered (every vertex so far was a delta event).
    specular_chain: bool,
    /// The last scattering event went straight through a see-through surface (`shadow.rs`).
    crossed: bool,
    /// Distance along the path to the current hit while `specular_chain` (the depth AOV).
    travelled: f32,
    pub out: PathSample,
    /// The frame's guide, when guiding is on (`guiding/`).
    guide: Option<&'g SdTree>,
    /// The path's training records, in a pass that learns. Boxed: the recorder is a kilobyte,
    /// and inline it made every path's state a kilobyte that building it copied (a `memcpy` per
    /// sample, 1.3 % of a Cornell-box render); only a pass that learns allocates.
    pub recorder: Option<Box<Recorder>>,
}

/// Guiding at one vertex: its leaf of the spatial tree and, once the passes before learned
/// something there, the distribution to sample.
#[derive(Clone, Copy)]
pub struct GuideAt<'g> {
    leaf: u32,
    dist: Option<&'g DTree>,
}

/// A light sample's shadow ray, still to be traced, and what the path gains if it is free.
pub struct ShadowRay {
    pub from: Vec3A,
    pub wi: Vec3A,
    pub tmax: f32,
    pub add: LightAdd,
}

/// What a light sample adds to the path's radiance and its two re-renders.
#[derive(Clone, Copy)]
pub struct LightAdd {
    l: Vec3A,
    achromatic: Vec3A,
    irradiance: Vec3A,
}

impl<'g> PathState<'g> {
    #[inline]
    pub fn new(
        o: Vec3A,
        d: Vec3A,
        from: Origin,
        u_light: [f32; 2],
        aovs: Option<AchromaticSpecular>,
    ) -> PathState<'g> {
        PathState {
            o,
            d,
            beta: Vec3A::ONE,
            depth: 0,
            prev: from,
            prev_p: o,
            prev_n: None,
            u_light,
            ka: Vec3A::ZERO,
            ke: Vec3A::ZERO,
            aovs: aovs.is_some(),
            wcam: aovs.unwrap_or_default(),
            wcam_dropped: false,
            specular_chain: true,
            crossed: false,
            travelled: 0.0,
            out: PathSample::default(),
            guide: None,
            recorder: None,
        }
    }

    /// The path samples from `guide` where guiding applies, and records what it sees when
    /// `learn`. In place: taking and returning the state by value copied all of it (about 40
    /// instructions a path).
    #[inline]
    pub fn use_guide(&mut self, guide: Option<&'g SdTree>, learn: bool) {
        self.guide = guide;
        self.recorder = (guide.is_some() && learn).then(Box::default);
    }

    /// Guiding at `v`: none without a guide, or where it does not apply (`guidable`, and not
    /// on masks or panes, whose straight-through events are no BSDF lobe).
    #[inline]
    pub fn guide_at(&self, v: &Vertex) -> Option<GuideAt<'g>> {
        let tree = self.guide?;
        if !guidable(&v.bsdf) || v.opacity < 1.0 || v.pane {
            return None;
        }
        let leaf = tree.leaf_at(v.p_front);
        let dist = &tree.leaves[leaf as usize].sampling;
        Some(GuideAt {
            leaf,
            dist: dist.has_energy().then_some(dist),
        })
    }

    /// The factor that turns light reaching the camera through the AOV vertex `v` (its BSDF
    /// value `f` towards local direction `wi_l`, `g` its bump shadowing there) into the WCAM
    /// re-render's contribution, in the path's specular mode.
    #[inline]
    fn achromatic_factor(&self, v: &Vertex, f: Vec3A, wi_l: Vec3A, g: f32) -> Vec3A {
        if self.wcam_dropped {
            return Vec3A::ZERO;
        }
        match self.wcam {
            AchromaticSpecular::Include | AchromaticSpecular::ExcludeDelta => achromatic_ratio(f),
            AchromaticSpecular::DiffuseOnly => {
                grey_ratio(luminance(v.bsdf.eval_diffuse(v.wo_l, wi_l) * g), f)
            }
        }
    }

    /// Adds radiance `c` that reached the camera through a vertex after the AOV vertex.
    #[inline]
    fn add_through_later_vertex(&mut self, c: Vec3A) {
        self.add_light(self.through_later_vertex(c));
    }

    /// What radiance `c` reaching the camera through a vertex after the AOV vertex adds.
    #[inline]
    fn through_later_vertex(&self, c: Vec3A) -> LightAdd {
        LightAdd {
            l: c,
            achromatic: c * self.ka,
            irradiance: c * self.ke,
        }
    }

    /// The ray left the scene: the environment, weighted against light sampling.
    #[inline]
    pub fn escape(&mut self, lights: &LightSet) {
        let Some(env) = &lights.env else { return };
        let (li, w) = match self.prev {
            Origin::Camera => (env.radiance(self.d), 1.0),
            Origin::Sampled { pdf } => {
                // One map lookup of the direction for its radiance and its density.
                let (li, env_pdf) = env.radiance_and_pdf(self.d);
                let p = lights.pdf_env_given(self.prev_p, self.prev_n, self.d, || env_pdf);
                (li, power_heuristic(pdf, p))
            }
        };
        let c = self.beta * li * w;
        if self.specular_chain {
            self.out.l += c;
        } else {
            self.add_through_later_vertex(c);
        }
    }

    /// The ray hit `si`: the geometric AOVs (until the AOV vertex) and the emission seen
    /// (front side only), weighted against light sampling.
    #[inline]
    pub fn shade_hit(&mut self, scene: &SceneData, si: &SurfaceInteraction) {
        if self.aovs && self.specular_chain {
            self.travelled += si.t;
            self.out.hit = true;
            self.out.depth = self.travelled;
            self.out.normal = si.ns;
        }
        if si.light == u32::MAX || si.ng.dot(self.d) >= 0.0 {
            return;
        }
        let lights = &scene.lights;
        let w = match self.prev {
            Origin::Camera => 1.0,
            Origin::Sampled { pdf } => power_heuristic(
                pdf,
                lights.pdf_area(si.light, self.prev_p, self.prev_n, si.p),
            ),
        };
        let c = self.beta * scene.materials.emission_at(si) * w;
        if self.specular_chain {
            self.out.l += c;
            self.out.emitter = true;
        } else {
            self.add_through_later_vertex(c);
        }
    }

    /// The light sample of next-event estimation at `v` (none for a delta BSDF), for
    /// [`PathState::sample_light`]. The caller draws it first and the BSDF sample next: the
    /// light choice is a chain of square roots and divisions and the sample's lookups may miss
    /// the cache, and the BSDF sample does not depend on them, so the core works on both.
    #[inline]
    pub fn light_sample(
        &self,
        scene: &SceneData,
        v: &Vertex,
        u: &VertexSamples,
    ) -> Option<LightSample> {
        if v.bsdf.is_delta() {
            return None;
        }
        // A BSDF that only reflects sees light on the viewer's side only, which lets the
        // light choice use the normal.
        let n = (!v.bsdf.has_transmission()).then_some(v.ng);
        scene.lights.sample(v.p_front, n, u.pick, self.u_light)
    }

    /// Next-event estimation at `v` with the light sample `ls` ([`PathState::light_sample`]),
    /// MIS-weighted against BSDF sampling. Where its shadow ray is a plain any-hit test (no
    /// see-through surfaces, no training records that read the radiance so far), the ray is
    /// returned with what it adds once free, for the caller to trace together with the path's
    /// next ray and then [`PathState::add_light`]; otherwise it is traced here.
    #[inline]
    pub fn sample_light(
        &mut self,
        scene: &SceneData,
        scratch: &mut RayScratch,
        v: &Vertex,
        ls: Option<LightSample>,
        g: Option<GuideAt>,
    ) -> Option<ShadowRay> {
        let transmits = v.bsdf.has_transmission();
        let ls = ls?;
        let (from, front) = v.origin_towards(ls.wi);
        if !front && !transmits {
            return None;
        }
        let wi_l = v.frame.to_local(ls.wi);
        // Shadow rays pass thin panes and, unless the scene blocks them there, masks' holes
        // and null surfaces (shadow.rs); light through other glass arrives by BSDF sampling.
        let f_surface = v.bsdf.eval(v.wo_l, wi_l) * v.shadowing(ls.wi);
        let f = f_surface * v.opacity;
        if f.max_element() <= 0.0 {
            return None;
        }
        let deferred = !scene.see_through && self.recorder.is_none();
        let tr = if deferred {
            Vec3A::ONE
        } else {
            shadow_transmittance(scene, scratch, from, ls.wi, ls.dist)
        };
        if tr.max_element() <= 0.0 {
            return None;
        }
        let w = if ls.delta {
            1.0
        } else {
            let pdf = v.bsdf.pdf(v.wo_l, wi_l) * v.opacity;
            match g.and_then(|g| g.dist) {
                None => power_heuristic(ls.pdf, pdf),
                Some(d) => power_heuristic(ls.pdf, mixture_pdf(d, &v.frame, wi_l, pdf)),
            }
        };
        let c = self.beta * f * ls.li * tr * (wi_l.z.abs() * w / ls.pdf);
        let add = if self.specular_chain {
            // The surface's own BSDF, not its mask's share: the irradiance of a half-transparent
            // surface is counted with its opacity as the probability of scattering there.
            LightAdd {
                l: c,
                achromatic: c * self.achromatic_factor(v, f_surface, wi_l, v.shadowing(ls.wi)),
                irradiance: c * irradiance_ratio(f_surface),
            }
        } else {
            self.through_later_vertex(c)
        };
        if !deferred {
            self.add_light(add);
            return None;
        }
        Some(ShadowRay {
            from,
            wi: ls.wi,
            tmax: shadow_tmax(ls.dist),
            add,
        })
    }

    /// Adds a light sample's contribution (once its shadow ray found the way free).
    #[inline]
    pub fn add_light(&mut self, add: LightAdd) {
        self.out.l += add.l;
        self.out.achromatic += add.achromatic;
        self.out.irradiance += add.irradiance;
    }

    /// The BSDF sample at `v` that [`PathState::scatter`] continues along: straight on through
    /// a mask's hole, from the guide where guiding applies (`g`), else from the BSDF. It reads
    /// nothing of the path, so it can be drawn before the light sample is finished.
    #[inline]
    pub fn sample_bsdf(v: &Vertex, u: &VertexSamples, g: Option<GuideAt>) -> Option<BsdfSample> {
        if u.mask >= v.opacity {
            // Through a mask's hole: straight on, unweighted.
            Some(BsdfSample {
                wi: -v.wo_l,
                f: Vec3A::ONE / v.wo_l.z.max(1e-12),
                pdf: 1.0,
                weight: Vec3A::ONE,
                delta: true,
            })
        } else if let Some(dist) = g.and_then(|g| g.dist) {
            // Guided vertices are opaque (`guide_at`).
            sample_guided(&v.bsdf, dist, &v.frame, v.wo_l, v.lobe, u.bsdf)
        } else {
            v.bsdf.sample(v.wo_l, v.lobe, u.bsdf).map(|b| BsdfSample {
                pdf: b.pdf * v.opacity,
                ..b
            })
        }
    }

    /// Continues the path along `bs`, the [`PathState::sample_bsdf`] of `v`, reflected or
    /// transmitted; false when the path ends (no sample, or one on the wrong side of the
    /// geometric surface). At the depth limit (`last`) only a crossing of a see-through
    /// surface continues: it is no segment, and shadow rays counted what lies behind it.
    #[inline]
    pub fn scatter(
        &mut self,
        v: &Vertex,
        u: &VertexSamples,
        last: bool,
        (g, bs): (Option<GuideAt>, Option<BsdfSample>),
    ) -> bool {
        let through = u.mask >= v.opacity;
        let Some(mut bs) = bs else {
            return false;
        };
        let wi = v.frame.to_world(bs.wi);
        if !through && v.terminator.is_some() {
            let g = v.shadowing(wi);
            bs.f *= g;
            bs.weight *= g;
        }
        let (from, front) = v.origin_towards(wi);
        // The sample's side in the shading frame must be its side of the geometric surface:
        // otherwise it is a shading-normal artefact and no light arrives there. (A ray
        // through a hole goes straight on whatever the shading normal says.)
        if (front != (bs.wi.z > 0.0) && !through) || wi.dot(v.ng) == 0.0 {
            return false;
        }
        self.crossed = if through {
            v.holes_pass
        } else {
            v.pane && bs.wi.z < 0.0
        };
        if self.crossed {
            // Straight through a surface shadow rays cross too (a delta event, so the AOV
            // vertex is not here): the path keeps the last scattering vertex's pdf, origin
            // and normal for MIS, and its segment count.
            self.beta *= bs.weight;
            self.u_light = u.light_next;
            self.o = from;
            self.d = wi;
            return true;
        }
        if last {
            return false;
        }
        // Every event of the specular chain is a delta one, so a delta lobe here (not a mask's
        // hole, not a crossing of a see-through surface) means the path's first scattering
        // event was one.
        if self.specular_chain && bs.delta && !through {
            self.wcam_dropped = self.wcam != AchromaticSpecular::Include;
        }
        if self.specular_chain && !bs.delta {
            self.specular_chain = false;
            self.out.albedo = self.beta * bs.weight;
            self.ka = self.achromatic_factor(v, bs.f, bs.wi, v.shadowing(wi));
            self.ke = irradiance_ratio(bs.f);
        }
        self.beta *= bs.weight;
        if let (Some(r), Some(g)) = (&mut self.recorder, g)
            && !bs.delta
        {
            r.push(g.leaf, wi, bs.pdf, self.beta, self.out.l);
        }
        self.u_light = u.light_next;
        self.prev = if bs.delta {
            Origin::Camera
        } else {
            Origin::Sampled { pdf: bs.pdf }
        };
        // The actual ray origin and the normal NEE used, so MIS at the next emitter hit sees
        // the same light-choice probability as NEE computed here.
        self.prev_p = from;
        self.prev_n = (!v.bsdf.has_transmission()).then_some(v.ng);
        self.o = from;
        self.d = wi;
        self.depth += 1;
        true
    }

    /// Russian roulette once `rr_depth` segments are traced (not after a crossing, which is
    /// no segment); false when the path ends.
    #[inline]
    pub fn roulette(&mut self, rr_depth: u32, u_rr: f32) -> bool {
        if self.depth >= rr_depth && !self.crossed {
            let q = self.beta.max_element().min(0.95);
            if u_rr >= q {
                return false;
            }
            self.beta /= q;
        }
        self.beta.max_element() > 0.0
    }
}
