//! The tracer's copy of a scene: geometry (two-level BVH), materials with their textures, light
//! set. Built once per scene and shared read-only by every thread and frame.
use crate::envmap::Environment;
use crate::geometry::{Built, Geometry};
use crate::lights::LightSet;
use crate::material::Materials;
use eyeadapt_scene::{MaterialId, Scene};
use glam::Vec3A;

pub struct SceneData {
    pub geometry: Geometry,
    pub materials: Materials,
    pub lights: LightSet,
    /// Some material is a thin pane, which shadow rays pass (`panes.rs`).
    pub thin_panes: bool,
    /// Some hit's shading reads the surface's UV, ∂p/∂u or colours
    /// ([`Materials::read_parameterisation`]): hits compute them only then.
    pub parameterisation: bool,
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
        let lights = LightSet::build(area_lights, &scene.lights, env, radius, &scene.textures);
        let thin_panes = materials.has_thin_panes();
        let parameterisation = materials.read_parameterisation();
        SceneData {
            parameterisation,
            geometry,
            materials,
            lights,
            thin_panes,
            center,
            radius,
        }
    }
}
