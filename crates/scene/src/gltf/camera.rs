//! A glTF camera node followed through time: the camera pose of a walkthrough.
//!
//! glTF cameras look down their node's local −z with +y up (§3.10.1). The pose at time `t` is
//! that frame carried to world space by the node's world transform at `t` (its own and its
//! parents' animation). Positions and directions stay in the file's coordinates (+y up), so
//! the CSV's `cam_x/y/z` are exactly the authored positions.
use super::nodes::NodeTree;
use crate::CameraPose;
use glam::DVec3;

/// The chosen camera and the animation that moves it.
#[derive(Clone, Debug, PartialEq)]
pub struct AnimatedCamera {
    /// The camera node's index in the file's `nodes`.
    pub node: usize,
    /// The node's name, or the camera's, or `nodes/N`.
    pub name: String,
    /// Vertical field of view in degrees (`yfov`).
    pub fov_deg: f64,
    /// The chosen animation's name (or `animations/N`), `None` for a still camera.
    pub animation: Option<String>,
    /// Seconds covered by the animation that plays, over every node it moves (`(0, 0)` when
    /// nothing moves).
    pub range: (f64, f64),
    /// Every node of the file with the chosen animation's tracks.
    pub tree: NodeTree,
}

impl AnimatedCamera {
    /// The camera at time `t` (seconds, on the file's animation clock).
    pub fn pose(&self, t: f64) -> CameraPose {
        let m = self.tree.world(self.node, t);
        let position = m.transform_point3(DVec3::ZERO);
        let forward = m.transform_vector3(DVec3::NEG_Z).normalize();
        // Re-orthogonalise: a non-uniform scale on a parent may shear the frame slightly.
        let up_raw = m.transform_vector3(DVec3::Y);
        let up = (up_raw - forward * up_raw.dot(forward)).normalize();
        CameraPose {
            position,
            forward,
            up,
            fov_deg: Some(self.fov_deg),
        }
    }
}
