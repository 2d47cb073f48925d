//! obvhs's own CWBVH build (its PLOC build, reinsertion and collapse to its compressed wide
//! nodes), timed next to [`Accel::build_with`](crate::Accel::build_with) by `eyeadapt bench
//! --bvh-triangles`: a peer for the renderer's build, which shares obvhs's PLOC build and
//! reinsertion and collapses the binary BVH itself ([`crate::collapse`]).
use crate::accel::InputTri;
use obvhs::BvhBuildParams;
use obvhs::cwbvh::builder::build_cwbvh_from_tris;
use obvhs::triangle::Triangle;
use std::time::Duration;

/// A mesh in obvhs's build input form, made once so that converting it is not timed.
pub struct ObvhsBuildInput {
    tris: Vec<Triangle>,
}

impl ObvhsBuildInput {
    pub fn new(mesh: &[InputTri]) -> ObvhsBuildInput {
        ObvhsBuildInput {
            tris: mesh.iter().map(InputTri::triangle).collect(),
        }
    }

    /// Builds (and drops) obvhs's CWBVH of the mesh with `params`.
    pub fn build(&self, params: BvhBuildParams) {
        drop(build_cwbvh_from_tris(
            &self.tris,
            params,
            &mut Duration::default(),
        ));
    }
}
