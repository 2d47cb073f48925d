//! The tracer's copy of a scene: geometry (two-level BVH), materials with their textures, light
//! set. Built once per scene and shared read-only by every thread and frame.
use crate::envmap::Environment;
use crate::geometry::{Built, Geometry};
use crate::light_visibility::Visibility;
use crate::lights::LightSet;
use crate::material::Materials;
use eyeadapt_scene::{CutoutShadows, MaterialId, Scene};
use glam::Vec3A;

pub struct SceneData {
    pub geometry: Geometry,
    pub materials: Materials,
    pub lights: LightSet,
    /// Some hit's shading reads the surface's UV, ∂p/∂u or colours
    /// ([`Materials::read_parameterisation`]): hits compute them only then.
    pub parameterisation: bool,
    /// Shadow rays pass masks' holes and null surfaces (`CutoutShadows::Transmit`).
    pub cutouts_pass: bool,
    /// Some material may let shadow rays through (a thin pane, or a mask when `cutouts_pass`;
    /// `shadow.rs`). Without one, shadow rays are plain any-hit tests.
    pub see_through: bool,
    /// Centre and radius of the bounding sphere of all geometry.
    pub center: Vec3A,
    pub radius: f32,
}

impl SceneData {
    pub fn new(scene: &Scene) -> SceneData {
        let materials = Materials::new(scene);
        let error = materials.error_index();
        let Built {
            geometry,
            area_lights,
        } = Geometry::build(
            scene,
            |m: Option<MaterialId>| m.map_or(error, |MaterialId(i)| i),
            |m| materials.emission(m),
            |m| materials.emission_texture(m),
        );
        let center = (geometry.bounds_min + geometry.bounds_max) * 0.5;
        let radius = ((geometry.bounds_max - geometry.bounds_min).length() * 0.5).max(1e-3);
        let env = Environment::new(
            scene.environment.map(Vec3A::from),
            scene.environment_map.as_ref(),
        );
        let lights = LightSet::build(area_lights, &scene.lights, env, radius, &scene.textures)
            .with_portals(&scene.portals);
        let parameterisation = materials.read_parameterisation();
        let cutouts_pass = scene.cutout_shadows == CutoutShadows::Transmit;
        // Only materials that something wears: a pane defined but placed nowhere must not
        // send every shadow ray down the see-through walk (the suite's interior without its
        // panes did).
        let see_through = geometry
            .materials_in_use()
            .any(|m| materials.may_pass(m, cutouts_pass));
        let mut data = SceneData {
            parameterisation,
            geometry,
            materials,
            lights,
            cutouts_pass,
            see_through,
            center,
            radius,
        };
        let visibility = Visibility::build(&data);
        data.lights.set_visibility(visibility);
        data
    }
}
