//! Pinhole camera.
//!
//! ```toml
//! [camera]
//! position = [278.0, 273.0, -800.0]
//! look_at = [278.0, 273.0, 0.0]
//! up = [0.0, 1.0, 0.0]        # default
//! fov_deg = 39.3              # vertical field of view in degrees
//! width = 256
//! height = 256
//! ```
use glam::Vec3;

/// A pinhole camera looking from `position` towards `look_at`.
#[derive(Clone, Debug, PartialEq)]
pub struct Camera {
    pub position: Vec3,
    pub look_at: Vec3,
    pub up: Vec3,
    /// Vertical field of view in degrees, in (0, 180).
    pub fov_deg: f32,
    pub width: u32,
    pub height: u32,
}

impl Camera {
    /// Unit gaze direction (the eye sensor's pole).
    pub fn forward(&self) -> Vec3 {
        (self.look_at - self.position).normalize()
    }

    /// Orthonormal (right, up, forward) basis; right-handed with +y up by default.
    pub fn basis(&self) -> (Vec3, Vec3, Vec3) {
        let f = self.forward();
        let r = f.cross(self.up).normalize();
        let u = r.cross(f);
        (r, u, f)
    }
}
