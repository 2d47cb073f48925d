//! The tracer's flattened copy of a scene: acceleration structure, BSDF and emission tables,
//! light set. Built once per scene and shared read-only by every thread and frame.
use crate::accel::{Accel, scene_triangles};
use crate::bsdf::Bsdf;
use crate::lights::LightSet;
use eyeadapt_scene::{MaterialId, Scene};
use glam::Vec3A;

pub struct SceneData {
    pub accel: Accel,
    pub bsdfs: Vec<Bsdf>,
    pub emission: Vec<Vec3A>,
    pub lights: LightSet,
    /// Centre and radius of the bounding sphere of all geometry.
    pub center: Vec3A,
    pub radius: f32,
}

impl SceneData {
    pub fn new(scene: &Scene) -> SceneData {
        // Table = the scene's materials, then the error material at the end.
        let mut bsdfs: Vec<Bsdf> = scene
            .materials
            .iter()
            .map(|m| Bsdf::from_scene(&m.bsdf))
            .collect();
        let mut emission: Vec<Vec3A> = scene.materials.iter().map(|m| m.emission.into()).collect();
        let error = eyeadapt_scene::Material::error();
        bsdfs.push(Bsdf::from_scene(&error.bsdf));
        emission.push(Vec3A::ZERO);
        let error_index = (bsdfs.len() - 1) as u32;
        let index = |m: Option<MaterialId>| m.map_or(error_index, |MaterialId(i)| i);
        let tris = scene_triangles(scene, index, |m| emission[m as usize].max_element() > 0.0);
        let accel = Accel::build(&tris);
        let center = (accel.bounds_min + accel.bounds_max) * 0.5;
        let radius = ((accel.bounds_max - accel.bounds_min).length() * 0.5).max(1e-3);
        let lights = LightSet::build(
            &tris,
            &emission,
            &scene.lights,
            scene.environment.map(Vec3A::from),
            radius,
        );
        SceneData {
            accel,
            bsdfs,
            emission,
            lights,
            center,
            radius,
        }
    }
}
