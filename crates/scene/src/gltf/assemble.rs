//! The whole glTF file as a [`Scene`]: every node of the default scene placed at time 0.
//!
//! Meshes become object-space meshes (one per primitive, read once however many nodes use
//! them) and each node that uses one an instance with its world transform; materials are read
//! once each; `KHR_lights_punctual` lights are placed by their nodes; the chosen camera at
//! time 0 is the scene camera.
use super::animated::SceneAnimation;
use super::camera::AnimatedCamera;
use super::nodes::NodeTree;
use super::read::{GltfFile, at, fail};
use super::textures::Textures;
use super::{geometry, lights, materials};
use crate::{Camera, Diagnostic, MaterialId, MeshId, Scene, SceneError, Severity, Transform};
use glam::DMat4;
use std::collections::HashMap;

/// Horizontal resolution of the scene camera a glTF file implies (a job or `--width` sets
/// its own); the height follows the camera's aspect ratio, 16:9 when the file gives none.
const DEFAULT_WIDTH: u32 = 640;

/// The scene being put together, and what is read once however many nodes use it.
struct Assembly<'f> {
    file: &'f GltfFile,
    tree: &'f NodeTree,
    s: Scene,
    errors: Vec<Diagnostic>,
    warnings: Vec<Diagnostic>,
    meshes: HashMap<(usize, usize), Option<MeshId>>,
    mats: HashMap<Option<usize>, MaterialId>,
    textures: Textures<'f>,
    moving: SceneAnimation,
}

/// The scene of `file`, seen from `camera` at time 0.
pub fn scene(
    file: &GltfFile,
    tree: &NodeTree,
    camera: Option<&AnimatedCamera>,
) -> Result<Scene, SceneError> {
    let mut a = Assembly {
        file,
        tree,
        s: Scene {
            source: file.path.clone(),
            ..Scene::default()
        },
        errors: Vec::new(),
        warnings: Vec::new(),
        meshes: HashMap::new(),
        mats: HashMap::new(),
        textures: Textures::new(file),
        moving: SceneAnimation {
            tree: tree.clone(),
            instances: Vec::new(),
            lights: Vec::new(),
        },
    };
    let roots: Vec<gltf::Node> = match file
        .document
        .default_scene()
        .or(file.document.scenes().next())
    {
        Some(sc) => sc.nodes().collect(),
        None => file.document.nodes().collect(),
    };
    // Depth-first over the hierarchy with the parent's world transform. The node-tree reader
    // has refused cycles and second parents; `visited` keeps the walk finite regardless.
    let mut stack: Vec<(gltf::Node, DMat4)> =
        roots.into_iter().map(|n| (n, DMat4::IDENTITY)).collect();
    let mut visited = vec![false; file.document.nodes().len()];
    while let Some((node, parent)) = stack.pop() {
        if std::mem::replace(&mut visited[node.index()], true) {
            continue;
        }
        let world = parent
            * DMat4::from_cols_array_2d(&node.transform().matrix().map(|c| c.map(f64::from)));
        for c in node.children() {
            stack.push((c, world));
        }
        a.place_light(&node, world);
        a.place_meshes(&node, world);
    }
    let Assembly {
        mut s,
        mut errors,
        mut warnings,
        moving,
        ..
    } = a;
    if let Some(cam) = camera {
        s.camera = Some(scene_camera(file, cam)?);
    }
    if s.instances.is_empty() && s.lights.is_empty() {
        errors.push(at(
            &file.path,
            "/scenes",
            "the scene has no meshes and no lights",
        ));
    }
    if !errors.is_empty() {
        return Err(SceneError {
            diagnostics: errors,
        });
    }
    if !moving.is_empty() {
        s.animation = Some(std::sync::Arc::new(moving));
    }
    warnings
        .iter_mut()
        .for_each(|w| w.severity = Severity::Warning);
    s.warnings = warnings;
    Ok(s)
}

impl Assembly<'_> {
    /// The node's `KHR_lights_punctual` light, placed by `world` (and listed as moving when
    /// the node is animated, in node space).
    fn place_light(&mut self, node: &gltf::Node, world: DMat4) {
        let Some(light) = node.light() else { return };
        let Some(l) = lights::light(&self.file.path, &light, world, &mut self.warnings) else {
            return;
        };
        if self.tree.is_animated(node.index()) {
            let local = lights::light(&self.file.path, &light, DMat4::IDENTITY, &mut Vec::new());
            let index = self.s.lights.len() as u32;
            self.moving
                .lights
                .extend(local.map(|l| (index, node.index(), l)));
        }
        self.s.lights.push(l);
    }

    /// One instance per primitive of the node's mesh (each mesh and material read once).
    fn place_meshes(&mut self, node: &gltf::Node, world: DMat4) {
        let Some(mesh) = node.mesh() else { return };
        for prim in mesh.primitives() {
            let Some(id) = self.mesh(&mesh, &prim) else {
                continue;
            };
            let mat = self.material(&prim.material());
            if self.tree.is_animated(node.index()) {
                let index = self.s.instances.len() as u32;
                self.moving.instances.push((index, node.index()));
            }
            self.s.add_instance(
                id,
                Some(mat),
                Transform {
                    matrix: world.as_mat4(),
                },
            );
        }
    }

    fn mesh(&mut self, mesh: &gltf::Mesh, prim: &gltf::Primitive) -> Option<MeshId> {
        let key = (mesh.index(), prim.index());
        if let Some(id) = self.meshes.get(&key) {
            return *id;
        }
        let id = match geometry::primitive_mesh(self.file, mesh, prim, &mut self.warnings) {
            Ok(Some(m)) => Some(self.s.add_mesh(m)),
            Ok(None) => None,
            Err(e) => {
                self.errors.push(e);
                None
            }
        };
        self.meshes.insert(key, id);
        id
    }

    fn material(&mut self, gm: &gltf::Material) -> MaterialId {
        if let Some(id) = self.mats.get(&gm.index()) {
            return *id;
        }
        let m = materials::material(
            self.file,
            gm,
            &mut self.textures,
            &mut self.s,
            &mut self.warnings,
        )
        .unwrap_or_else(|e| {
            self.errors.push(e);
            crate::Material::error()
        });
        let id = self.s.add_material(m);
        self.mats.insert(gm.index(), id);
        id
    }
}

fn scene_camera(file: &GltfFile, cam: &AnimatedCamera) -> Result<Camera, SceneError> {
    // Frame 0 is at time 0 on the file's clock, whatever the first keyframe's time.
    let pose = cam.pose(0.0);
    let aspect = file
        .document
        .nodes()
        .nth(cam.node)
        .and_then(|n| n.camera())
        .and_then(|c| match c.projection() {
            gltf::camera::Projection::Perspective(p) => p.aspect_ratio(),
            gltf::camera::Projection::Orthographic(_) => None,
        })
        .filter(|a| a.is_finite() && *a > 0.0)
        .unwrap_or(16.0 / 9.0);
    let height = ((DEFAULT_WIDTH as f32 / aspect).round() as u32).clamp(1, 16384);
    if !pose.position.is_finite() || !pose.forward.is_finite() {
        return Err(fail(at(
            &file.path,
            &format!("/nodes/{}", cam.node),
            "the camera's transform at time 0 is degenerate",
        )));
    }
    Ok(Camera {
        position: pose.position.as_vec3(),
        look_at: (pose.position + pose.forward).as_vec3(),
        up: pose.up.as_vec3(),
        fov_deg: cam.fov_deg as f32,
        width: DEFAULT_WIDTH,
        height,
        projection: crate::Projection::Pinhole,
    })
}
