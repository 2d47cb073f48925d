//! Sampling a guided vertex: one-sample MIS between the learned distribution and the BSDF.
//!
//! With probability [`GUIDE_FRACTION`] the direction comes from the vertex's quadtree, else
//! from the BSDF; either way its density is the mixture α·p_guide + (1 − α)·p_bsdf, which the
//! path weight, the light sample's MIS weight and the next emitter's MIS weight all use, so
//! every pass is unbiased whatever the guide has learned. The choice rescales the BSDF's first
//! sample number, so a guided vertex draws no more numbers than an unguided one.
use super::dtree::{DTree, from_square};
use crate::bsdf::{Bsdf, BsdfSample};
use crate::integrator::Frame;
use glam::Vec3A;

/// α: the share of guided vertices' directions drawn from the guide. Müller et al. use 0.5;
/// 0.3 measured better on both scenes of `docs/benchmarks/guiding.md`, whose guides, learned
/// from a few thousand records per leaf, are noisier than theirs.
pub const GUIDE_FRACTION: f32 = 0.3;

/// Roughest GGX/Beckmann α below which a conductor is left to its own sampling (a narrow
/// lobe is sampled better by the BSDF than by any quadtree).
const MIN_CONDUCTOR_ALPHA: f32 = 0.3;

/// Whether guiding applies to `bsdf`: lobes without a delta part that are wide enough for a
/// quadtree to help. Glass, mirrors, panes, near-specular metals and the principled BSDFs
/// (which may carry delta lobes) keep plain BSDF sampling.
pub fn guidable(bsdf: &Bsdf) -> bool {
    match bsdf {
        Bsdf::Diffuse { .. } | Bsdf::Plastic { .. } | Bsdf::PPlastic(_) => true,
        Bsdf::RoughConductor { ggx, .. } => ggx.alpha.min(ggx.alpha_v) >= MIN_CONDUCTOR_ALPHA,
        Bsdf::Mirror { .. }
        | Bsdf::Dielectric { .. }
        | Bsdf::ThinDielectric { .. }
        | Bsdf::RoughDielectric(_)
        | Bsdf::Principled(_)
        | Bsdf::PrincipledThin(_) => false,
    }
}

/// The guided density of local direction `wi_l` at a vertex whose BSDF density there is
/// `pdf_bsdf`.
#[inline]
pub fn mixture_pdf(guide: &DTree, frame: &Frame, wi_l: Vec3A, pdf_bsdf: f32) -> f32 {
    let a = GUIDE_FRACTION;
    a * guide.pdf_dir(frame.to_world(wi_l)) + (1.0 - a) * pdf_bsdf
}

/// A direction at a guided vertex (local frame), as [`Bsdf::sample`] gives one but with the
/// mixture's density and weight; `u_lobe` and `u` are the vertex's BSDF numbers.
pub fn sample_guided(
    bsdf: &Bsdf,
    guide: &DTree,
    frame: &Frame,
    wo_l: Vec3A,
    u_lobe: f32,
    u: [f32; 2],
) -> Option<BsdfSample> {
    let a = GUIDE_FRACTION;
    let (wi_l, f, pdf) = if u[0] < a {
        // The guide's density from its own sampling (what `mixture_pdf` finds again).
        let (p, pdf_square) = guide.sample([u[0] / a, u[1]]);
        let wi_l = frame.to_local(from_square(p));
        let pdf_guide = pdf_square * (0.25 / std::f32::consts::PI);
        let pdf = a * pdf_guide + (1.0 - a) * bsdf.pdf(wo_l, wi_l);
        (wi_l, bsdf.eval(wo_l, wi_l), pdf)
    } else {
        let v = ((u[0] - a) / (1.0 - a)).min(1.0 - f32::EPSILON * 0.5);
        let b = bsdf.sample(wo_l, u_lobe, [v, u[1]])?;
        if b.delta {
            // Not for guidable BSDFs; kept correct anyway: a discrete lobe picked with the
            // BSDF's share of the choice.
            return Some(BsdfSample {
                weight: b.weight / (1.0 - a),
                ..b
            });
        }
        (b.wi, b.f, mixture_pdf(guide, frame, b.wi, b.pdf))
    };
    BsdfSample::of_lobe(wi_l, pdf, || f)
}
