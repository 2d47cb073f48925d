//! Triangle meshes in world space.
use crate::MaterialId;
use glam::Vec3;

/// A triangle mesh, already transformed to world space, with one material.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Mesh {
    /// Where it came from (`shapes[3] (box)`, `meshes/bunny.obj#Body`), for messages.
    pub name: String,
    pub positions: Vec<Vec3>,
    pub indices: Vec<[u32; 3]>,
    /// Per-vertex shading normals, or empty (then the geometric normal is used).
    pub normals: Vec<Vec3>,
    pub material: Option<MaterialId>,
}

impl Mesh {
    pub fn triangle_count(&self) -> usize {
        self.indices.len()
    }

    /// Total surface area (zero-area triangles contribute nothing).
    pub fn area(&self) -> f64 {
        self.indices
            .iter()
            .map(|t| {
                let [a, b, c] = t.map(|i| self.positions[i as usize].as_dvec3());
                0.5 * (b - a).cross(c - a).length()
            })
            .sum()
    }
}
