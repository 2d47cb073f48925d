//! Thin panes ([`Bsdf::ThinDielectric`]) seen by shadow rays.
//!
//! A thin pane does not deflect what it transmits, so the straight segment from a shading point
//! to a light sample is a real light path through any panes on it, attenuated by each pane's
//! transmittance. Shadow rays therefore pass through fully opaque thin panes (not masked ones,
//! not solid or rough glass) and carry that transmittance: a sun, a point or a spot light behind
//! a window pane lights the room and reaches the eye sensor, which no BSDF-sampled path can
//! do for a delta light. For MIS to stay consistent, a BSDF-sampled path that crosses a pane
//! keeps the pdf, origin and normal of the vertex before the pane and does not count the
//! crossing as a segment (as volumetric path tracers treat null interfaces), so both
//! strategies sample the same set of paths. (Mitsuba 3's `path` integrator blocks shadow rays
//! at every surface instead: its panes pass area lights and the environment by BSDF sampling
//! only, and a delta light behind a pane is black there; docs/mitsuba.md.)
//!
//! Scenes without thin panes take none of this code: their shadow rays are the any-hit test
//! they always were, and their images are bit-identical.
use crate::bsdf::Bsdf;
use crate::geometry::RayScratch;
use crate::integrator::visible;
use crate::path_state::{Vertex, VertexSamples};
use crate::scene_data::SceneData;
use glam::Vec3A;

/// What arrives at `from` along `wi` (unit) from a light sample at distance `dist` (∞ for
/// the environment and the sun), per channel: 0 behind anything but a thin pane, otherwise
/// the product of the panes' transmittances.
#[inline]
pub fn shadow_transmittance(
    scene: &SceneData,
    scratch: &mut RayScratch,
    from: Vec3A,
    wi: Vec3A,
    dist: f32,
) -> Vec3A {
    if !scene.thin_panes {
        return if visible(scene, scratch, from, wi, dist) {
            Vec3A::ONE
        } else {
            Vec3A::ZERO
        };
    }
    // The same end of the segment as `visible` (just short of the light sample).
    let tmax = if dist.is_finite() {
        dist * (1.0 - 2e-4)
    } else {
        f32::INFINITY
    };
    let mut tr = Vec3A::ONE;
    let mut o = from;
    // At most this many panes on one segment: beyond it, the light counts as blocked.
    for _ in 0..64 {
        let left = tmax - (o - from).dot(wi);
        if left <= 0.0 {
            return tr;
        }
        let Some(hit) = scene.geometry.intersect_with(scratch, o, wi, left) else {
            return tr;
        };
        let si = scene
            .geometry
            .interaction(o, wi, &hit, scene.parameterisation);
        let v = Vertex::new(scene, &si, -wi, &VertexSamples::middle());
        let Some(t) = v.pane_transmittance() else {
            return Vec3A::ZERO;
        };
        tr *= t;
        if tr.max_element() <= 0.0 {
            return Vec3A::ZERO;
        }
        o = v.behind();
    }
    Vec3A::ZERO
}

/// True when `bsdf` with `opacity` is a pane shadow rays pass (see the module docs).
#[inline]
pub fn is_pane(bsdf: &Bsdf, opacity: f32) -> bool {
    matches!(bsdf, Bsdf::ThinDielectric { .. }) && opacity >= 1.0
}
