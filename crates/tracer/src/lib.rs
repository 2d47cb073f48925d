//! The renderer: two levels of eight-wide BVHs over obvhs's builds ([`Geometry`] over per-mesh
//! [`Accel`]s, whose nodes have float boxes and are walked nearest child first), materials
//! evaluated per hit with their textures ([`Materials`]), stateless Owen-scrambled Sobol sampling
//! ([`SampleStream`]), BSDFs, the light set (with environment maps, [`Environment`], sampled
//! through a [`Distribution2D`] or through light portals in the openings of an interior), a
//! path tracer with next-event estimation and MIS ([`trace`]) whose shadow rays pass thin
//! window panes and cut-outs (`shadow.rs`), the film with its AOVs ([`render`] → [`Frame`]) and
//! the eye-centred hemispherical sensor ([`eye_sensor`]).
//!
//! Build a [`SceneData`] once from an `eyeadapt_scene::Scene`, then render any number of
//! [`View`]s from it. Results depend only on the scene, the view and the settings, never on
//! the number of threads.
// Public items' docs point at the private code that does their work: the crate's docs are
// read with `cargo doc --document-private-items`, where those links resolve.
#![allow(rustdoc::private_intra_doc_links)]

mod accel;
mod accel_wide;
mod beam;
mod bilinear;
mod bsdf;
mod bump;
mod bvh_bench;
mod collapse;
mod dielectric;
mod distribution2d;
mod emitter;
mod envmap;
mod eye;
mod film;
mod fmath;
mod geometry;
mod guiding;
mod integrator;
mod interaction;
mod isa;
mod lanes8;
mod light_bounds4;
mod light_pick;
mod light_pick4;
mod light_tree;
mod light_visibility;
mod lights;
mod material;
mod microfacet;
mod packet;
mod path_state;
mod plastic_table;
mod portal;
mod pplastic;
mod prefetch;
mod principled;
mod principled_lobes;
mod principled_thin;
mod revision;
mod sampler;
mod scene_data;
mod scramble4;
mod shadow;
mod texture;
mod traverse_pair;
mod tri4;
mod triangle;
mod trig;
mod vertex;
mod wide_bvh;
mod wide_test;
mod wide_walk;

pub use crate::accel::{Accel, InputTri, SlotHit, TriInfo, build_params};
pub use crate::bsdf::{Bsdf, BsdfSample};
pub use crate::bvh_bench::ObvhsBuildInput;
pub use crate::distribution2d::Distribution2D;
pub use crate::emitter::luminance;
pub use crate::envmap::{EnvSample, Environment};
pub use crate::eye::{
    EYE_REPLICATES, EYE_ROUND, EyeEstimate, EyeSettings, eye_direct_per_light, eye_sensor,
    eye_sensor_until, sample_cardioid,
};
pub use crate::film::{
    Basis, Frame, RenderSettings, RenderStats, View, render, render_with_progress,
};
pub use crate::geometry::{Geometry, Hit, RayScratch};
pub use crate::guiding::{DTree, Guiding, SdTree, from_square, to_square};
pub use crate::integrator::{AchromaticSpecular, Origin, PathSample, PathSettings, trace};
pub use crate::interaction::SurfaceInteraction;
pub use crate::isa::simd_setting;
pub use crate::lights::LightSet;
pub use crate::material::Materials;
pub use crate::packet::PacketStack;
pub use crate::revision::RENDER_REVISION;
pub use crate::sampler::{SampleStream, StreamSeeds, hash_key, mix64};
pub use crate::scene_data::SceneData;
pub use crate::wide_bvh::Node8;
pub use crate::wide_walk::WalkStack;
pub use obvhs::BvhBuildParams;
