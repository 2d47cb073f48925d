//! What shadow rays pass: surfaces that let light straight through, undeflected.
//!
//! Two kinds of surface do: thin panes ([`Bsdf::ThinDielectric`]), and — when the scene's
//! [`CutoutShadows`] is `Transmit` (TOML, glTF and built-in scenes, Mitsuba's `volpath`) — the
//! holes of masks and null surfaces. The straight segment from a shading point to a light
//! sample is then a real light path through every such surface on it, attenuated by each
//! one's expected straight-through transmittance ([`Vertex::straight_through`]): a mask of
//! opacity o passes 1 − o, a pane its Fresnel transmittance, a masked pane
//! 1 − o + o·T_pane, a blend the mix of its children's with the blend's weight (what the
//! BSDF-sampled path crossing it passes on average, so no random number is needed; these are
//! Mitsuba 3's `eval_null_transmission`). A sun, a point or a spot light behind a window or
//! behind leaves cut out of a texture lights what is behind, and reaches the eye sensor,
//! which no BSDF-sampled path can do for a delta light.
//!
//! For MIS to stay consistent, a BSDF-sampled path that crosses such a surface keeps the pdf,
//! origin and normal of the vertex before it and does not count the crossing as a segment
//! (as volumetric path tracers treat null interfaces, and Mitsuba's `volpath` does), so both
//! strategies sample the same set of paths. With `CutoutShadows::Block` (Mitsuba's `path` and
//! `direct` in XML scenes) shadow rays stop at masks and null surfaces, and crossing one is an
//! ordinary delta event that counts as a segment, as there. (Mitsuba's `path` blocks shadow
//! rays at panes too; eyeadapt lets them through in every scene: docs/mitsuba.md.)
//!
//! Scenes without any such surface take none of this code: their shadow rays are the any-hit
//! test they always were, and their images are bit-identical.
#[cfg(doc)]
use crate::bsdf::Bsdf;
use crate::geometry::RayScratch;
use crate::integrator::{offset, visible};
use crate::scene_data::SceneData;
use crate::vertex::Vertex;
#[cfg(doc)]
use eyeadapt_scene::CutoutShadows;
use glam::Vec3A;

/// What arrives at `from` along `wi` (unit) from a light sample at distance `dist` (∞ for
/// the environment and the sun), per channel: 0 behind anything opaque, otherwise the product
/// of the straight-through transmittances of the surfaces on the way.
#[inline]
pub fn shadow_transmittance(
    scene: &SceneData,
    scratch: &mut RayScratch,
    from: Vec3A,
    wi: Vec3A,
    dist: f32,
) -> Vec3A {
    if !scene.see_through {
        return if visible(scene, scratch, from, wi, dist) {
            Vec3A::ONE
        } else {
            Vec3A::ZERO
        };
    }
    let tmax = shadow_tmax(dist);
    let mut tr = Vec3A::ONE;
    let mut o = from;
    // At most this many see-through surfaces on one segment: beyond, the light counts as
    // blocked.
    for _ in 0..64 {
        let left = tmax - (o - from).dot(wi);
        if left <= 0.0 {
            return tr;
        }
        let Some(hit) = scene.geometry.intersect_with(scratch, o, wi, left) else {
            return tr;
        };
        // Most hits are opaque (a wall between the point and the light), and an opaque
        // material passes nothing, which needs no interaction to know.
        let interaction = || {
            scene
                .geometry
                .interaction(o, wi, &hit, scene.parameterisation)
        };
        let material = scene.geometry.material_of(&hit);
        let mut seen = None;
        tr *= if scene.materials.may_pass(material, scene.cutouts_pass) {
            let si = interaction();
            let t = surface_transmittance(scene, &si, -wi);
            seen = Some(si);
            t
        } else {
            Vec3A::ZERO
        };
        if tr.max_element() <= 0.0 {
            return Vec3A::ZERO;
        }
        let si = seen.unwrap_or_else(interaction);
        // On past the surface, just behind it as seen from the shading point.
        let ng = if si.ng.dot(wi) < 0.0 { si.ng } else { -si.ng };
        o = offset(si.p, -ng);
    }
    Vec3A::ZERO
}

/// Where a shadow ray to a light sample at distance `dist` (∞ for the environment and the
/// sun) ends: just short of the sample, so that the light's own surface does not block it.
#[inline]
pub fn shadow_tmax(dist: f32) -> f32 {
    if dist.is_finite() {
        dist * (1.0 - 2e-4)
    } else {
        f32::INFINITY
    }
}

/// The expected share of light that `si`, seen along `wo`, passes straight on: the
/// straight-through transmittance of each material it may scatter with, weighted by the
/// probability of that choice (a blend's weight).
#[inline]
fn surface_transmittance(
    scene: &SceneData,
    si: &crate::interaction::SurfaceInteraction,
    wo: Vec3A,
) -> Vec3A {
    let mut t = Vec3A::ZERO;
    scene.materials.leaves(si, |leaf, p| {
        // Opaque leaves pass nothing; only the others need their BSDF built.
        if leaf.may_pass(scene.cutouts_pass) {
            t += Vertex::with_leaf(scene, si, wo, leaf, 0.0).straight_through() * p;
        }
    });
    t
}
