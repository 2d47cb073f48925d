//! Instances: a mesh placed in the world with a material.
//!
//! Many instances may share one [`Mesh`](crate::Mesh); the tracer builds one acceleration
//! structure per mesh and one over the instances, so memory grows with the unique meshes.
use crate::{MaterialId, MeshId, Transform};

/// One placement of a mesh.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Instance {
    pub mesh: MeshId,
    /// `None` renders with the loud [`crate::Material::error`].
    pub material: Option<MaterialId>,
    /// Object to world. A mirroring transform keeps the mesh's winding, so its front side
    /// (and emitting side) mirrors with it, as in Mitsuba.
    pub to_world: Transform,
}
