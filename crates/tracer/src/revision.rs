//! The render revision: a number that changes whenever the renderer's output bits change.
//!
//! A sequence's output directory is keyed by a hash of the job (`eyeadapt-sequencer`'s
//! `job_hash`), and a resumed or merged run refuses a directory whose hash differs, so that
//! frames of two renderers never end up in one video. The job's inputs alone cannot say
//! whether the *code* that renders them changed its bits; this number does. It is part of the
//! job hash, and `tests/render_revision.rs` pins the bits of a set of small renders that cover
//! the renderer's paths (built-in scenes, a Mitsuba XML scene, more lights than the direct
//! light choice handles, a splatting filter, the eye sensor) to it: a change that moves any of
//! those bits fails the test until this number is raised and the pins are retaken.
//!
//! Raising it makes every older output directory refuse to resume with this binary (the user
//! is told to use another `--out` or `--force`), which is exactly what should happen when the
//! frames would differ.

/// The current render revision (see the module documentation).
///
/// 1: the renderer up to the smooth-plastic and light-tree changes of issue 23.
/// 2: smooth `plastic` in Mitsuba XML is a smooth coating (α 0), scenes with more than 16
///    lights choose them through the light tree.
/// 3: the light tree is four children wide (scenes with more than 16 lights).
/// 4: triangles are tested four at a time with a watertight test (every scene, in the last
///    bits).
/// 5: behind light portals the light choice weighs the environment by the share of the sky
///    the portals show (scenes with `[[portals]]`).
/// 6: behind light portals a directional light's importance drops where its direction
///    crosses no portal.
/// 7: every transcendental function is the `libm` crate's or the tracer's own (`trig.rs`)
///    instead of the C library's, so that nodes with different glibc versions give the same
///    bits (every scene, in the last bits).
/// 8: an environment map draws points inside a cell in proportion to the bilinear luminance
///    (scenes with a map).
/// 9: with 2 to 16 lights, the light choice weighs each light by how much of it the shading
///    point's cell of the scene sees (`light_visibility.rs`; scenes with 2 to 16 lights).
/// 10: so does the light tree, for 17 to 64 lights.
/// 11: the visibility grid shoots from 8 points a cell instead of 16 (the same error, half the
///    build).
/// 12: the Gaussian pixel filter's weights come from a table (within 2e-6 of the exact ones;
///    scenes with that filter, in the last bits).
/// 13: an environment map's longitude and colatitude come from the tracer's own f64 atan2
///    (within an f32 ulp of libm's `atan2f` / `acosf`), and its density from the same bilinear
///    blend as its radiance (scenes with a map, in the last bits).
/// 14: a shadow ray in a scene with see-through surfaces is one walk over every surface on its
///    segment instead of a closest hit after each crossing, so an opaque surface nearer than
///    the old offset past a crossing now blocks it (scenes with panes, masks or null
///    surfaces; the built-in interior's mean −0.008 %).
/// 15: a mesh's eight-wide nodes are collapsed from obvhs's binary BVH by the tracer itself,
///    each leaf one block of four triangles (`collapse.rs`), instead of obvhs's CWBVH: the same
///    hits, but of two triangles hit at the same distance (a ray through their shared edge) the
///    other may now be reported (every scene with such edges, in a few pixels; the built-in
///    interior's mean +0.010 %).
/// 16: the light tree is eight children wide (scenes with more than 16 lights).
/// 17: an environment map's sample carries the radiance and density of the drawn map point
///    instead of those of the point its direction maps back to (within 10⁻⁴; scenes with a
///    map).
/// 18: a cosine-weighted direction's height comes from the disk point's radius instead of
///    its two coordinates (every scene with diffuse surfaces, in the last bits).
/// 19: a mesh whose vertex normals are its faces' own (within 10⁻⁶ in cosine) shades with the
///    geometric normals instead of interpolating them (such meshes, in the last bits; none of
///    the pinned scenes has one, so the pins stay; `tests/face_normals.rs` covers it).
/// 20: a pixel's camera rays are walked eight at a time (`packet.rs`; groups of five or more
///    samples of a pass): of two triangles at
///    exactly one distance, or one at a box's rounding edge, the packet's order of visits may
///    report the other (a ray through a shared edge; the built-in interior at 128 × 96, 16 spp:
///    one pixel of 12 288, by 9·10⁻⁸; none of the pinned scenes, so the pins stay).
pub const RENDER_REVISION: u32 = 20;
