//! The loaded scene: plain data for the tracer, whatever front-end (TOML, Mitsuba XML) read it.
use crate::gltf::SceneAnimation;
use crate::{
    Camera, CameraPath, Diagnostic, EnvironmentMap, Instance, Light, Material, MaterialId, Mesh,
    MeshId, Portal, Rgb, Texture, TextureId, Transform,
};
use std::path::PathBuf;
use std::sync::Arc;

/// Render settings a scene file may suggest; command-line flags and job files override them.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct RenderDefaults {
    pub spp: Option<u32>,
    /// Mitsuba's convention: the longest path has `max_depth` segments; −1 = unlimited.
    pub max_depth: Option<i32>,
    pub rr_depth: Option<u32>,
    pub seed: Option<u64>,
    /// The film's reconstruction filter (Mitsuba's `rfilter`); `None`: the renderer's box.
    pub filter: Option<crate::PixelFilter>,
}

/// What shadow rays (light samples, the eye sensor's direct terms) make of the surfaces light
/// passes straight through: masks' holes and null surfaces. Thin panes pass shadow rays in
/// both cases.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum CutoutShadows {
    /// Shadow rays pass them with their expected transmittance (1 − opacity), so a cut-out
    /// leaf casts a leaf-shaped shadow in the sun; a path that crosses one does not count the
    /// crossing as a segment (Mitsuba 3's `volpath`; glTF renderers' alpha cut-outs).
    #[default]
    Transmit,
    /// Shadow rays stop at them and a crossing counts as a segment, as in Mitsuba 3's `path`
    /// and `direct` integrators: light through a hole arrives by BSDF sampling only (the same
    /// image for area lights and environments), and a point, spot or sun behind one is black.
    Block,
}

/// A loaded scene: object-space meshes placed by instances, materials whose parameters may
/// point into the texture table, delta lights, the environment, the camera and its path.
#[derive(Clone, Debug, Default)]
pub struct Scene {
    /// The file it came from (for messages and relative paths).
    pub source: PathBuf,
    pub camera: Option<Camera>,
    pub materials: Vec<Material>,
    pub textures: Vec<Texture>,
    /// Unique geometry, in object space; only instances make it visible.
    pub meshes: Vec<Mesh>,
    pub instances: Vec<Instance>,
    pub lights: Vec<Light>,
    /// Constant environment radiance seen by rays that leave the scene.
    pub environment: Option<Rgb>,
    /// An environment map seen by rays that leave the scene (added to `environment`).
    pub environment_map: Option<EnvironmentMap>,
    /// Openings the environment's light enters through (sampling only: not geometry).
    pub portals: Vec<Portal>,
    /// Emission that varies over a surface: each listed material's `emission` is multiplied
    /// by its texture at every point (Mitsuba's `area` emitter with a textured `radiance`;
    /// the material's `emission` is then the texture's scale). A material appears at most once.
    pub emission_textures: Vec<(MaterialId, TextureId)>,
    pub render: RenderDefaults,
    /// Whether shadow rays pass masks' holes and null surfaces.
    pub cutout_shadows: CutoutShadows,
    /// The scene's own camera path, already validated.
    pub camera_path: Option<CameraPath>,
    /// Warnings met while loading (missing MTL, unknown material, …), already formatted.
    pub warnings: Vec<Diagnostic>,
    /// Instances and lights that move over time (glTF node animation); `None`: all still.
    pub animation: Option<Arc<SceneAnimation>>,
}

impl Scene {
    pub fn material(&self, id: Option<MaterialId>) -> &Material {
        static ERROR: std::sync::OnceLock<Material> = std::sync::OnceLock::new();
        match id {
            Some(MaterialId(i)) => &self.materials[i as usize],
            None => ERROR.get_or_init(Material::error),
        }
    }

    pub fn mesh(&self, id: MeshId) -> &Mesh {
        &self.meshes[id.0 as usize]
    }

    pub fn texture(&self, id: TextureId) -> &Texture {
        &self.textures[id.0 as usize]
    }

    /// The texture that multiplies material `id`'s emission, if any.
    pub fn emission_texture(&self, id: MaterialId) -> Option<TextureId> {
        self.emission_textures
            .iter()
            .find(|(m, _)| *m == id)
            .map(|&(_, t)| t)
    }

    /// True when the scene has objects or lights that move over time.
    pub fn is_animated(&self) -> bool {
        self.animation.as_ref().is_some_and(|a| !a.is_empty())
    }

    /// The scene as it is at time `t` (seconds on its animation's clock): a copy with every
    /// animated instance and light placed for `t`.
    pub fn at_time(&self, t: f64) -> Scene {
        let mut s = self.clone();
        if let Some(a) = &self.animation {
            a.apply(&mut s, t);
        }
        s
    }

    /// Triangles as rendered: every instance counts its mesh's triangles.
    pub fn triangle_count(&self) -> usize {
        self.instances
            .iter()
            .map(|i| self.mesh(i.mesh).triangle_count())
            .sum()
    }

    /// Triangles stored: each unique mesh once.
    pub fn unique_triangle_count(&self) -> usize {
        self.meshes.iter().map(Mesh::triangle_count).sum()
    }

    /// True when some light, emissive material or environment can light the scene.
    pub fn has_light_source(&self) -> bool {
        self.has_emissive_instance()
            || !self.lights.is_empty()
            || self.environment.is_some_and(|e| e.max_element() > 0.0)
            || self.environment_map.as_ref().is_some_and(|m| {
                m.scale > 0.0 && m.image.texels.iter().any(|t| t.max_element() > 0.0)
            })
    }

    /// True when some instance's material emits.
    pub fn has_emissive_instance(&self) -> bool {
        self.instances
            .iter()
            .any(|i| self.material(i.material).is_emissive())
    }

    /// Adds a material and returns its id.
    pub fn add_material(&mut self, m: Material) -> MaterialId {
        self.materials.push(m);
        MaterialId(self.materials.len() as u32 - 1)
    }

    /// Adds a texture and returns its id.
    pub fn add_texture(&mut self, t: Texture) -> TextureId {
        self.textures.push(t);
        TextureId(self.textures.len() as u32 - 1)
    }

    /// Adds a mesh (not yet visible) and returns its id.
    pub fn add_mesh(&mut self, m: Mesh) -> MeshId {
        self.meshes.push(m);
        MeshId(self.meshes.len() as u32 - 1)
    }

    /// Places mesh `mesh` with `material`.
    pub fn add_instance(
        &mut self,
        mesh: MeshId,
        material: Option<MaterialId>,
        to_world: Transform,
    ) {
        self.instances.push(Instance {
            mesh,
            material,
            to_world,
        });
    }

    /// Adds a mesh already in world space and its one identity instance.
    pub fn add_world_mesh(&mut self, m: Mesh, material: Option<MaterialId>) {
        let id = self.add_mesh(m);
        self.add_instance(id, material, Transform::default());
    }
}
