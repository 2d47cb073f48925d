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
use crate::bsdf::Bsdf;
use crate::geometry::{Hit, RayScratch};
use crate::integrator::visible;
use crate::microfacet::fresnel_refract;
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
    // One walk over every surface on the segment: the first opaque one ends it (the light is
    // blocked, whatever else lies on the way); the see-through ones are kept and their
    // transmittances multiplied afterwards, nearest first.
    let mut crossings = std::mem::take(&mut scratch.crossings);
    crossings.clear();
    let geometry = &scene.geometry;
    let blocked = geometry.each_hit(scratch, from, wi, shadow_tmax(dist), &mut |hit| {
        if !scene
            .materials
            .may_pass(geometry.material_of(&hit), scene.cutouts_pass)
            || crossings.len() == MAX_CROSSINGS
        {
            return true;
        }
        crossings.push(hit);
        false
    });
    let tr = if blocked {
        Vec3A::ZERO
    } else {
        transmittance(scene, from, wi, &mut crossings)
    };
    scratch.crossings = crossings;
    tr
}

/// At most this many see-through surfaces on one segment: beyond, the light counts as
/// blocked.
const MAX_CROSSINGS: usize = 64;

/// The product of the straight-through transmittances at `crossings` (hits along `wi` from
/// `from`, in any order), nearest first. Two hits of one instance at the same distance are one
/// crossing (a ray through the edge two triangles share meets both).
fn transmittance(scene: &SceneData, from: Vec3A, wi: Vec3A, crossings: &mut [Hit]) -> Vec3A {
    crossings.sort_unstable_by(|a, b| {
        a.t.total_cmp(&b.t)
            .then(a.instance.cmp(&b.instance))
            .then(a.prim.cmp(&b.prim))
    });
    let mut tr = Vec3A::ONE;
    let mut last: Option<&Hit> = None;
    for hit in crossings.iter() {
        if last.is_some_and(|l| l.t == hit.t && l.instance == hit.instance) {
            continue;
        }
        last = Some(hit);
        let si = scene
            .geometry
            .interaction(from, wi, hit, scene.parameterisation);
        tr *= surface_transmittance(scene, &si, -wi);
        if tr.max_element() <= 0.0 {
            return Vec3A::ZERO;
        }
    }
    tr
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
    let front = si.ng.dot(wo) > 0.0;
    if let Some(&Bsdf::ThinDielectric { eta, t, .. }) = scene.materials.fixed(si.material, front) {
        // A plain pane (the usual window): what its vertex's `straight_through` gives, bit for
        // bit, without building the vertex (its shading normal on the viewer's side, as
        // `Vertex::with_leaf` turns it, and the pane's share 1 − 2R/(1 + R)).
        let ng = if front { si.ng } else { -si.ng };
        let ns = if si.ns.dot(ng) < 0.0 { -si.ns } else { si.ns };
        let f = fresnel_refract(wo.dot(ns), eta).0;
        return t * (1.0 - 2.0 * f / (1.0 + f));
    }
    leaves_transmittance(scene, si, wo)
}

/// [`surface_transmittance`] of any material: each leaf's vertex built and asked.
fn leaves_transmittance(
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sampler::mix64;
    use eyeadapt_scene::{Material, Rgb, Scene, quad_mesh};
    use glam::Vec3;

    /// A plain pane's shortcut gives what its vertex gives, bit for bit, from either side and
    /// at every angle.
    #[test]
    fn a_plain_panes_shortcut_is_its_vertex_bit_for_bit() {
        let mut s = Scene::default();
        let m = s.add_material(Material {
            name: "pane".into(),
            bsdf: eyeadapt_scene::Bsdf::ThinDielectric {
                eta: 1.5,
                specular_reflectance: Rgb::ONE,
                specular_transmittance: Rgb::new(0.9, 0.8, 0.7),
            },
            emission: Rgb::ZERO,
        });
        let (corner, u, v) = (
            Vec3::new(-1.0, -1.0, 0.3),
            Vec3::new(2.0, 0.2, 0.1),
            Vec3::Y * 2.0,
        );
        s.add_world_mesh(quad_mesh(corner, u, v), Some(m));
        let scene = SceneData::new(&s);
        assert!(scene.see_through);
        let unit = |r: u64| (r >> 40) as f32 / (1u64 << 24) as f32;
        let mut scratch = scene.geometry.scratch();
        for k in 0..2000u64 {
            let r = mix64(k);
            let (a, b) = (0.1 + 0.8 * unit(r), 0.1 + 0.8 * unit(mix64(r)));
            let target = Vec3A::from(corner + u * a + v * b);
            let side = if k % 2 == 0 { 1.0 } else { -1.0 };
            let o = Vec3A::new(unit(r ^ 7) * 4.0 - 2.0, unit(r ^ 9) * 4.0 - 2.0, 2.0 * side);
            let wi = (target - o).normalize();
            let hit = scene
                .geometry
                .intersect_with(&mut scratch, o, wi, f32::INFINITY)
                .expect("the ray crosses the pane");
            let si = scene
                .geometry
                .interaction(o, wi, &hit, scene.parameterisation);
            let (fast, full) = (
                surface_transmittance(&scene, &si, -wi),
                leaves_transmittance(&scene, &si, -wi),
            );
            assert!(fast.max_element() > 0.0 && fast.max_element() < 0.9);
            assert_eq!(
                fast.to_array().map(f32::to_bits),
                full.to_array().map(f32::to_bits)
            );
        }
    }
}
