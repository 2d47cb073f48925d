//! glTF 2.0 (`.gltf` + `.bin` or data URIs, `.glb`), read with the `gltf` crate.
//!
//! - [`read`]: the document and its buffers, errors as JSON pointers;
//! - [`nodes`]: the node hierarchy and world transforms at any time;
//! - [`load_nodes`]: the hierarchy and the chosen animation's channels from the file;
//! - [`camera`]: the camera a walkthrough is rendered from, as a pose per time;
//! - [`geometry`], [`materials`], [`lights`]: meshes, metallic-roughness materials and
//!   `KHR_lights_punctual` lights in eyeadapt's terms; [`assemble`]: the whole [`Scene`].
mod animated;
mod assemble;
mod camera;
mod geometry;
mod lights;
mod load_nodes;
mod materials;
mod nodes;
mod read;
mod textures;

pub use animated::SceneAnimation;
pub use camera::AnimatedCamera;
pub use lights::LUMENS_PER_WATT;
pub use load_nodes::MAX_ANIMATION_SECONDS;
pub use nodes::{Node, NodeTracks, NodeTree, Rest};
pub use read::{GltfFile, json_pointer, open};

use crate::{Scene, SceneError};
use std::path::Path;

/// True for the extensions this reader takes (`.gltf`, `.glb`, any case).
pub fn is_gltf_path(path: &Path) -> bool {
    path.extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("gltf") || e.eq_ignore_ascii_case("glb"))
}

/// The scene of a glTF file seen from its first animated camera (or first camera) at time 0:
/// what `eyeadapt render` shows. Sequences follow the camera with [`load_camera`]; instances
/// and lights on animated nodes are listed in [`Scene::animation`] (every animation playing).
pub fn load_gltf(path: &Path) -> Result<Scene, SceneError> {
    let file = open(path)?;
    // The hierarchy and every animation are checked whether or not a camera uses them: a
    // cycle or a broken track is an error in the file, not only in a walkthrough of it.
    let tree =
        load_nodes::node_tree(&file, None).map_err(|diagnostics| SceneError { diagnostics })?;
    let has_camera = file.document.nodes().any(|n| n.camera().is_some());
    let camera = if has_camera {
        Some(camera_of(&file, None, None)?)
    } else {
        None
    };
    assemble::scene(&file, &tree, camera.as_ref())
}

/// The camera of a glTF file and the animation that moves it.
///
/// `camera` names a node or a camera; without a name the first camera node (in the file's
/// node order) that is animated, or failing that the first camera node. `animation` names
/// one animation; without a name every animation plays at once.
pub fn load_camera(
    path: &Path,
    camera: Option<&str>,
    animation: Option<&str>,
) -> Result<AnimatedCamera, SceneError> {
    let file = open(path)?;
    camera_of(&file, camera, animation)
}

/// [`load_camera`] on an opened file.
pub fn camera_of(
    file: &GltfFile,
    camera: Option<&str>,
    animation: Option<&str>,
) -> Result<AnimatedCamera, SceneError> {
    let tree =
        load_nodes::node_tree(file, animation).map_err(|diagnostics| SceneError { diagnostics })?;
    let cameras: Vec<gltf::Node> = file
        .document
        .nodes()
        .filter(|n| n.camera().is_some())
        .collect();
    let node = match camera {
        Some(name) => cameras
            .iter()
            .find(|n| n.name() == Some(name) || n.camera().and_then(|c| c.name()) == Some(name)),
        None => cameras
            .iter()
            .find(|n| tree.is_animated(n.index()))
            .or(cameras.first()),
    };
    let Some(node) = node else {
        let msg = match camera {
            Some(name) => {
                let names: Vec<String> = cameras.iter().map(node_label).collect();
                format!(
                    "no camera named \"{name}\" (the file's camera nodes: {})",
                    if names.is_empty() {
                        "none".into()
                    } else {
                        names.join(", ")
                    }
                )
            }
            None => "the file has no camera node; give the job a camera path".into(),
        };
        return Err(read::fail(read::at(&file.path, "/nodes", msg)));
    };
    let cam = node.camera().expect("filtered on camera nodes");
    let here = format!("/cameras/{}", cam.index());
    let fov_deg = match cam.projection() {
        gltf::camera::Projection::Perspective(p) => f64::from(p.yfov()).to_degrees(),
        gltf::camera::Projection::Orthographic(_) => {
            return Err(read::fail(read::at(
                &file.path,
                &format!("{here}/type"),
                "orthographic cameras are not supported (perspective only)",
            )));
        }
    };
    if !(fov_deg > 0.0 && fov_deg < 180.0) {
        return Err(read::fail(read::at(
            &file.path,
            &format!("{here}/perspective/yfov"),
            format!("yfov of {fov_deg}° is not in (0°, 180°)"),
        )));
    }
    // The walkthrough lasts as long as anything in the animation moves (a camera that stops
    // while a door still opens holds its last pose), as Blender's frame range does.
    let range = tree.range();
    let animation = match (range, animation) {
        (None, _) => None,
        (Some(_), Some(name)) => Some(name.to_string()),
        (Some(_), None) => Some(
            file.document
                .animations()
                .map(|a| load_nodes::label(&a))
                .collect::<Vec<_>>()
                .join("+"),
        ),
    };
    Ok(AnimatedCamera {
        node: node.index(),
        name: node_label(node),
        fov_deg,
        animation,
        range: range.unwrap_or((0.0, 0.0)),
        tree,
    })
}

fn node_label(n: &gltf::Node) -> String {
    n.name()
        .or_else(|| n.camera().and_then(|c| c.name()))
        .map_or_else(|| format!("nodes/{}", n.index()), str::to_string)
}
