//! What moves in a glTF scene besides the camera: instances and lights placed by animated
//! nodes (the node or one of its ancestors has tracks), re-placed at any time of the file's
//! clock by [`SceneAnimation::apply`].
//!
//! Rigid animation only (translation, rotation, scale of nodes); meshes keep their object-space
//! triangles, so a frame's scene differs from frame 0's only in instance transforms and light
//! positions. Every frame is computed from the time alone, never from the frame before it, so
//! chunks and resumed runs get the same bits.
use super::nodes::NodeTree;
use crate::{Light, Scene, Transform};
use glam::{DMat4, DVec3};

/// The animated instances and lights of a glTF scene, with the node tree that moves them.
#[derive(Clone, Debug, PartialEq)]
pub struct SceneAnimation {
    /// Every node of the file with the tracks of the animation that plays.
    pub tree: NodeTree,
    /// (index into [`Scene::instances`], the node that places it).
    pub instances: Vec<(u32, usize)>,
    /// (index into [`Scene::lights`], the node that places it, the light in node space:
    /// at the origin, pointing down −z).
    pub lights: Vec<(u32, usize, Light)>,
}

impl SceneAnimation {
    /// True when nothing moves.
    pub fn is_empty(&self) -> bool {
        self.instances.is_empty() && self.lights.is_empty()
    }

    /// Places every animated instance and light of `scene` as it is at time `t` (seconds on
    /// the file's animation clock).
    pub fn apply(&self, scene: &mut Scene, t: f64) {
        for &(i, node) in &self.instances {
            scene.instances[i as usize].to_world = Transform {
                matrix: self.tree.world(node, t).as_mat4(),
            };
        }
        for (i, node, local) in &self.lights {
            scene.lights[*i as usize] = placed(local, self.tree.world(*node, t));
        }
    }
}

/// `local` (a light in its node's space) carried to world space by `to_world`.
pub fn placed(local: &Light, to_world: DMat4) -> Light {
    let point = |p: glam::Vec3| to_world.transform_point3(p.as_dvec3()).as_vec3();
    let dir = |d: glam::Vec3| {
        to_world
            .transform_vector3(d.as_dvec3())
            .normalize_or(DVec3::NEG_Z)
            .as_vec3()
    };
    match local {
        Light::Point {
            position,
            intensity,
        } => Light::Point {
            position: point(*position),
            intensity: *intensity,
        },
        Light::Spot {
            position,
            direction,
            intensity,
            cone_deg,
            falloff_deg,
        } => Light::Spot {
            position: point(*position),
            direction: dir(*direction),
            intensity: *intensity,
            cone_deg: *cone_deg,
            falloff_deg: *falloff_deg,
        },
        Light::Directional {
            direction,
            irradiance,
        } => Light::Directional {
            direction: dir(*direction),
            irradiance: *irradiance,
        },
        // Mitsuba's lights, which glTF files never hold; carried all the same.
        Light::TexturedSpot {
            position, frame, ..
        }
        | Light::Projector {
            position, frame, ..
        } => {
            let mut l = local.clone();
            let (p, f) = (
                point(*position),
                glam::DMat3::from_mat4(to_world) * frame.as_dmat3(),
            );
            match &mut l {
                Light::TexturedSpot {
                    position, frame, ..
                }
                | Light::Projector {
                    position, frame, ..
                } => {
                    *position = p;
                    *frame = f.as_mat3();
                }
                _ => unreachable!(),
            }
            l
        }
    }
}
