//! Triangle meshes in object space; [`crate::Instance`]s place them in the world.
use crate::Rgb;
use glam::{Vec2, Vec3};

/// Index into [`crate::Scene::meshes`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct MeshId(pub u32);

/// A triangle mesh in its own (object) space. It has no material: each [`crate::Instance`] that
/// places it names one, so one mesh can appear many times in different materials.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Mesh {
    /// Where it came from (`shapes[3] (box)`, `meshes/bunny.obj#Body`), for messages.
    pub name: String,
    pub positions: Vec<Vec3>,
    /// Triangles as vertex indices; the front side is the one `(b − a) × (c − a)` points to.
    pub indices: Vec<[u32; 3]>,
    /// Per-vertex shading normals, or empty (then the geometric normal is used).
    pub normals: Vec<Vec3>,
    /// Per-vertex texture coordinates, or empty. Mitsuba's convention: (0, 0) is the top-left
    /// corner of a bitmap and v grows down the image (OBJ's v, which grows upwards, is flipped
    /// when read, as Mitsuba's `flip_tex_coords` does by default).
    pub uvs: Vec<Vec2>,
    /// Per-vertex colours (linear sRGB, read by `mesh_attribute` textures), or empty.
    pub colors: Vec<Rgb>,
    /// Per-triangle colours (linear sRGB, read by `face_color` textures), or empty.
    pub face_colors: Vec<Rgb>,
}

impl Mesh {
    pub fn triangle_count(&self) -> usize {
        self.indices.len()
    }

    /// Total surface area in object space (zero-area triangles contribute nothing).
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
