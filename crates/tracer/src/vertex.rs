//! The current surface of a path as its steps see it ([`Vertex`]: the BSDF built there, its
//! frame and ray origins) and the random numbers of that vertex ([`VertexSamples`]), for the
//! steps of [`crate::path_state`].
use crate::bsdf::Bsdf;
use crate::bump::Terminator;
use crate::integrator::{Frame, offset};
use crate::interaction::SurfaceInteraction;
use crate::material::Leaf;
use crate::microfacet::fresnel_refract;
use crate::sampler::SampleStream;
use crate::scene_data::SceneData;
use glam::Vec3A;

/// The current surface, as the steps after [`crate::path_state::PathState::shade_hit`] see it.
pub struct Vertex {
    /// Geometric normal on the viewer's side.
    pub(crate) ng: Vec3A,
    pub(crate) frame: Frame,
    pub(crate) wo_l: Vec3A,
    pub(crate) bsdf: Bsdf,
    /// The probability that the surface scatters (masks); otherwise light passes straight
    /// through, a delta event.
    pub(crate) opacity: f32,
    /// The lobe-choice number left for `bsdf` (a blend's choice of child rescales it).
    pub(crate) lobe: f32,
    /// A bump map's shadowing term (`bump.rs`).
    pub(crate) terminator: Option<Terminator>,
    /// Ray origins just off the surface on the viewer's side and behind it.
    pub(crate) p_front: Vec3A,
    pub(crate) p_back: Vec3A,
    /// A thin pane that shadow rays pass (`shadow.rs`).
    pub(crate) pane: bool,
    /// The mask's holes pass shadow rays (`CutoutShadows::Transmit`), so a path through one
    /// is a crossing, not a segment (`shadow.rs`).
    pub(crate) holes_pass: bool,
}

/// The random numbers of one vertex, in the sample stream's fixed order.
pub struct VertexSamples {
    pub(crate) pick: f32,
    pub(crate) lobe: f32,
    pub rr: f32,
    pub(crate) mask: f32,
    pub(crate) bsdf: [f32; 2],
    pub(crate) light_next: [f32; 2],
}

impl VertexSamples {
    #[inline]
    pub fn draw(s: &mut SampleStream) -> VertexSamples {
        // Two whole chunks (the caller starts a group): what eight `next_1d` calls draw.
        let [pick, lobe, rr, mask] = s.next_4d();
        let [b0, b1, l0, l1] = s.next_4d();
        let (bsdf, light_next) = ([b0, b1], [l0, l1]);
        VertexSamples {
            pick,
            lobe,
            rr,
            mask,
            bsdf,
            light_next,
        }
    }
}

impl Vertex {
    /// The surface `si` seen along `wo` (towards the viewer), with its BSDF built there (a
    /// blend's child chosen with `u.lobe`).
    #[inline]
    pub fn new(scene: &SceneData, si: &SurfaceInteraction, wo: Vec3A, u: &VertexSamples) -> Vertex {
        let front = si.ng.dot(wo) > 0.0;
        if let Some(&bsdf) = scene.materials.fixed(si.material, front) {
            // What `with_leaf` gives for such a material, without building it.
            let ng = if front { si.ng } else { -si.ng };
            let ns = if si.ns.dot(ng) < 0.0 { -si.ns } else { si.ns };
            let frame = Frame::new(ns);
            return Vertex {
                ng,
                frame,
                wo_l: frame.to_local(wo),
                pane: scene.see_through && matches!(bsdf, Bsdf::ThinDielectric { .. }),
                holes_pass: false,
                bsdf,
                opacity: 1.0,
                lobe: u.lobe,
                terminator: None,
                p_front: offset(si.p, ng),
                p_back: offset(si.p, -ng),
            };
        }
        let (leaf, lobe) = scene.materials.select(si, u.lobe);
        Vertex::with_leaf(scene, si, wo, leaf, lobe)
    }

    /// The surface `si` seen along `wo` scattering with `leaf` (one of its blend's children),
    /// `lobe` the lobe-choice number left for it.
    #[inline]
    pub(crate) fn with_leaf(
        scene: &SceneData,
        si: &SurfaceInteraction,
        wo: Vec3A,
        leaf: Leaf<'_>,
        lobe: f32,
    ) -> Vertex {
        // Shading frame on the viewer's side; the BSDF knows which side that is.
        let front = si.ng.dot(wo) > 0.0;
        let ng = if front { si.ng } else { -si.ng };
        let (ns, terminator) = scene.materials.shading_normal(leaf, si, wo);
        let ns = if ns.dot(ng) < 0.0 { -ns } else { ns };
        let bsdf = scene.materials.bsdf(leaf, si, front);
        // Anisotropic roughness is laid out along ∂p/∂u (in the plane of the mesh's shading
        // normal first, as Mitsuba's frame, then of the mapped one).
        let frame = if bsdf.is_anisotropic() {
            Frame::with_tangent(ns, si.dpdu - si.ns * si.ns.dot(si.dpdu))
        } else {
            Frame::new(ns)
        };
        let opacity = scene.materials.opacity(leaf, si);
        let holes_pass = scene.cutouts_pass && opacity < 1.0;
        // A masked pane passes shadow rays only where its holes do.
        let pane = scene.see_through
            && matches!(bsdf, Bsdf::ThinDielectric { .. })
            && (opacity >= 1.0 || holes_pass);
        Vertex {
            ng,
            frame,
            wo_l: frame.to_local(wo),
            pane,
            holes_pass,
            // Principled lobes turn their own anisotropy to ∂p/∂u (`Bsdf::oriented`).
            bsdf: bsdf.oriented(&frame, si.dpdu),
            opacity,
            lobe,
            terminator,
            p_front: offset(si.p, ng),
            p_back: offset(si.p, -ng),
        }
    }

    /// The bump map's shadowing of light along `wi` (1 without one).
    #[inline]
    pub(crate) fn shadowing(&self, wi: Vec3A) -> f32 {
        self.terminator.map_or(1.0, |t| t.factor(wi))
    }

    /// The expected share of light this surface passes straight on towards the viewer, the
    /// probability of a crossing times its weight (`shadow.rs`): 1 − opacity through holes
    /// that pass shadow rays, plus opacity times a pane's transmittance (times
    /// 1 − 2R/(1 + R), as `sample_thin` transmits). 0 for anything else.
    #[inline]
    pub(crate) fn straight_through(&self) -> Vec3A {
        let holes = if self.holes_pass {
            1.0 - self.opacity
        } else {
            0.0
        };
        match self.bsdf {
            Bsdf::ThinDielectric { eta, t, .. } if self.pane => {
                let f = fresnel_refract(self.wo_l.z, eta).0;
                let pane = t * (1.0 - 2.0 * f / (1.0 + f));
                if self.opacity >= 1.0 {
                    pane
                } else {
                    pane * self.opacity + Vec3A::splat(holes)
                }
            }
            _ => Vec3A::splat(holes),
        }
    }

    /// The ray origin for leaving along `wi`, and whether that side is the viewer's.
    #[inline]
    pub(crate) fn origin_towards(&self, wi: Vec3A) -> (Vec3A, bool) {
        if wi.dot(self.ng) > 0.0 {
            (self.p_front, true)
        } else {
            (self.p_back, false)
        }
    }
}
