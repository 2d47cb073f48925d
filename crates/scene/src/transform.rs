//! Affine transforms of shapes.
//!
//! ```toml
//! transform = { translate = [0.0, 1.0, 0.0], rotate = [0.0, 1.0, 0.0, 90.0], scale = 2.0 }
//! # applied as scale, then rotate (axis x,y,z and angle in degrees), then translate; or
//! transform = { matrix = [[1.0, 0.0, 0.0, 0.0], [0.0, 1.0, 0.0, 0.0], [0.0, 0.0, 1.0, 0.0], [0.0, 0.0, 0.0, 1.0]] }
//! ```
use glam::{Mat3, Mat4, Vec3};

/// An affine map from object to world space.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Transform {
    pub matrix: Mat4,
}

impl Default for Transform {
    fn default() -> Self {
        Transform {
            matrix: Mat4::IDENTITY,
        }
    }
}

impl Transform {
    pub fn point(&self, p: Vec3) -> Vec3 {
        self.matrix.transform_point3(p)
    }

    pub fn vector(&self, v: Vec3) -> Vec3 {
        self.matrix.transform_vector3(v)
    }

    /// Normals transform with the inverse transpose.
    pub fn normal(&self, n: Vec3) -> Vec3 {
        let m = Mat3::from_mat4(self.matrix).inverse().transpose();
        (m * n).normalize_or_zero()
    }

    /// True when the map mirrors space (then triangle winding must be flipped to keep normals).
    pub fn flips_handedness(&self) -> bool {
        Mat3::from_mat4(self.matrix).determinant() < 0.0
    }

    pub fn then(self, outer: Transform) -> Transform {
        Transform {
            matrix: outer.matrix * self.matrix,
        }
    }
}
