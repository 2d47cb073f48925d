//! The TOML scene format (`docs/scene-format.md`): stage one, `format.rs`, is the raw shape of
//! the file as serde sees it; stage two, here and in the sibling files, validates it into a
//! [`Scene`], collecting every problem.

mod anisotropic;
mod environment;
mod format;
mod light;
mod material;
mod portal;
mod principled;
mod shape;
mod surface;
mod texture;

use crate::diagnostic::{Diagnostic, SceneError, Severity, SourceMap};
use crate::{
    Camera, CameraPath, ImageCache, MaterialId, MeshId, RenderDefaults, Rgb, Scene, TextureId,
};
use format::{CameraDef, SceneFile, V3};
use glam::Vec3;
use std::collections::HashMap;
use std::path::{Path, PathBuf};
use toml::Spanned;

/// Loads and validates a TOML scene file. OBJ paths are relative to the file's directory.
pub fn load_scene(path: &Path) -> Result<Scene, SceneError> {
    let text = crate::read_input_text(path).map_err(|e| SceneError {
        diagnostics: vec![Diagnostic {
            severity: Severity::Error,
            file: path.to_path_buf(),
            line: 0,
            col: 0,
            message: format!("cannot read scene file: {e}"),
        }],
    })?;
    load_scene_str(&text, path)
}

/// Loads a scene from TOML text; `path` names it in messages and anchors relative paths.
pub fn load_scene_str(text: &str, path: &Path) -> Result<Scene, SceneError> {
    load_scene_str_with(text, path, ImageCache::default())
}

/// [`load_scene_str`] with images taken from `images` first (a built-in scene's embedded
/// files, keyed by the paths the scene's relative names resolve to).
pub(crate) fn load_scene_str_with(
    text: &str,
    path: &Path,
    images: ImageCache,
) -> Result<Scene, SceneError> {
    let map = SourceMap { file: path, text };
    let raw: SceneFile = toml::from_str(text).map_err(|e| SceneError {
        diagnostics: vec![toml_error(&map, &e)],
    })?;
    let mut cx = Ctx {
        map,
        diags: Vec::new(),
        dir: scene_dir(path),
        textures: HashMap::new(),
        texture_kinds: Vec::new(),
        images,
        named_shapes: HashMap::new(),
    };
    let scene = cx.scene(raw);
    let (errors, warnings): (Vec<_>, Vec<_>) = cx
        .diags
        .into_iter()
        .partition(|d| d.severity == Severity::Error);
    if errors.is_empty() {
        Ok(Scene { warnings, ..scene })
    } else {
        Err(SceneError {
            diagnostics: errors.into_iter().chain(warnings).collect(),
        })
    }
}

/// The directory a scene's relative file names are resolved in.
pub(crate) fn scene_dir(path: &Path) -> PathBuf {
    path.parent().unwrap_or(Path::new(".")).to_path_buf()
}

pub(crate) fn toml_error(map: &SourceMap, e: &toml::de::Error) -> Diagnostic {
    let offset = e.span().map_or(0, |s| s.start);
    let message = e.message().trim().replace('\n', " ");
    map.error(offset, message)
}

/// The kind of a loaded texture, as far as the keys that reference one care.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum TextureKind {
    /// A bitmap decoded from sRGB (not `raw`).
    SrgbBitmap,
    /// The mesh's vertex colours: defined on surfaces only, not by UV alone.
    VertexColor,
    /// Anything else (a raw bitmap, a checkerboard).
    Other,
}

impl TextureKind {
    fn of(t: &crate::Texture) -> TextureKind {
        match t {
            crate::Texture::Bitmap(b) if !b.raw => TextureKind::SrgbBitmap,
            crate::Texture::MeshAttribute { .. } => TextureKind::VertexColor,
            _ => TextureKind::Other,
        }
    }
}

struct Ctx<'a> {
    map: SourceMap<'a>,
    diags: Vec<Diagnostic>,
    dir: PathBuf,
    textures: HashMap<String, Option<TextureId>>,
    /// What each texture of the scene's table is, by [`TextureId`] (what its users may check).
    texture_kinds: Vec<TextureKind>,
    images: ImageCache,
    /// Shapes with a `name`: their meshes (in object space) and materials.
    named_shapes: HashMap<String, Vec<(MeshId, Option<MaterialId>)>>,
}

impl Ctx<'_> {
    fn error(&mut self, offset: usize, msg: impl Into<String>) {
        let d = self.map.error(offset, msg);
        self.diags.push(d);
    }

    fn warning(&mut self, offset: usize, msg: impl Into<String>) {
        let d = self.map.warning(offset, msg);
        self.diags.push(d);
    }

    /// A finite vector; `what` names the field in messages.
    fn vec3(&mut self, v: &V3, what: &str) -> Vec3 {
        let a = *v.get_ref();
        if a.iter().any(|c| !c.is_finite()) {
            self.error(
                v.span().start,
                format!("{what} {a:?} has a non-finite component"),
            );
            return Vec3::ZERO;
        }
        Vec3::from_array(a)
    }

    /// A finite, non-negative colour no larger than [`crate::MAX_COLOUR`].
    fn colour(&mut self, v: &V3, what: &str) -> Rgb {
        let c = self.vec3(v, what);
        if let Err(problem) = crate::check_colour(c) {
            self.error(
                v.span().start,
                format!("{what} {:?} {problem}", c.to_array()),
            );
            return Rgb::ZERO;
        }
        c
    }

    /// The texture `t` names, for `key` of `owner` (e.g. `material "m"`); `None` after an
    /// error here (an unknown name) or at the texture's definition (it failed to load).
    fn texture_ref(&mut self, owner: &str, key: &str, t: &Spanned<String>) -> Option<TextureId> {
        match self.textures.get(t.get_ref()) {
            Some(id) => *id,
            None => {
                self.error(
                    t.span().start,
                    format!(
                        "{owner}: `{key}` names an unknown texture \"{}\" (textures are defined in [[textures]])",
                        t.get_ref()
                    ),
                );
                None
            }
        }
    }

    /// The kind of a `[[textures]]` texture (the textures an MTL file adds later are `Other`).
    fn texture_kind(&self, id: TextureId) -> TextureKind {
        self.texture_kinds
            .get(id.0 as usize)
            .copied()
            .unwrap_or(TextureKind::Other)
    }

    fn positive(&mut self, v: &Spanned<f32>, what: &str) -> f32 {
        let x = *v.get_ref();
        if !(x.is_finite() && x > 0.0) {
            self.error(
                v.span().start,
                format!("{what} must be a finite number > 0, got {x}"),
            );
            return 1.0;
        }
        x
    }

    fn scene(&mut self, raw: SceneFile) -> Scene {
        let mut scene = Scene {
            source: self.map.file.to_path_buf(),
            ..Scene::default()
        };
        scene.camera = raw.camera.as_ref().map(|c| self.camera(c));
        if let Some(r) = &raw.render {
            scene.render = self.render(r);
        }
        for t in &raw.textures {
            let name = t.get_ref().name.get_ref().clone();
            if self.textures.contains_key(&name) {
                self.error(
                    t.get_ref().name.span().start,
                    format!("texture \"{name}\" is defined twice"),
                );
                continue;
            }
            // A texture that failed to load is remembered as None: its users are not told
            // again that it does not exist.
            let id = self.texture(t).map(|tex| {
                self.texture_kinds.push(TextureKind::of(&tex));
                scene.add_texture(tex)
            });
            self.textures.insert(name, id);
        }
        let mut names: HashMap<String, MaterialId> = HashMap::new();
        for m in &raw.materials {
            let name = m.get_ref().name.get_ref().clone();
            if names.contains_key(&name) {
                self.error(
                    m.get_ref().name.span().start,
                    format!("material \"{name}\" is defined twice"),
                );
                continue;
            }
            let (mat, emission_texture) = self.material(m.get_ref());
            let id = scene.add_material(mat);
            if let Some(t) = emission_texture {
                scene.emission_textures.push((id, t));
            }
            names.insert(name, id);
        }
        for (i, s) in raw.shapes.iter().enumerate() {
            self.shape(i, s, &names, &mut scene);
        }
        for inst in &raw.instances {
            self.instance(inst, &names, &mut scene);
        }
        for l in &raw.lights {
            if let Some(light) = self.light(l) {
                scene.lights.push(light);
            }
        }
        if let Some(env) = &raw.environment {
            self.environment(env, &mut scene);
        }
        for (i, p) in raw.portals.iter().enumerate() {
            if let Some(portal) = self.portal(i, p) {
                scene.portals.push(portal);
            }
        }
        let sun = scene
            .lights
            .iter()
            .any(|l| matches!(l, crate::Light::Directional { .. }));
        if let Some(p) = raw.portals.first()
            && scene.environment.is_none()
            && scene.environment_map.is_none()
            && !sun
        {
            self.warning(
                p.span().start,
                "portals without an [environment] or a sun do nothing (they only steer their sampling)",
            );
        }
        if let Some(p) = raw.camera_path {
            scene.camera_path = self.camera_path(p);
        }
        if scene.meshes.is_empty()
            && scene.lights.is_empty()
            && scene.environment.is_none()
            && scene.environment_map.is_none()
        {
            self.error(
                0,
                "the scene is empty: it has no shapes, lights or environment",
            );
        } else if !scene.has_light_source() {
            self.warning(0, "the scene has no light source (no emissive material, light or environment): it will render black");
        }
        scene
    }

    /// The `[camera_path]` table, deserialised and validated; problems at the table.
    fn camera_path(&mut self, p: Spanned<toml::Value>) -> Option<CameraPath> {
        let at = p.span().start;
        let path: CameraPath = match p.into_inner().try_into() {
            Ok(path) => path,
            Err(e) => {
                let e: toml::de::Error = e;
                let msg = e.message().trim().replace('\n', " ");
                self.error(at, format!("camera_path: {msg}"));
                return None;
            }
        };
        match path.validate() {
            Ok(()) => Some(path),
            Err(problems) => {
                for problem in problems {
                    self.error(at, problem.to_string());
                }
                None
            }
        }
    }

    fn camera(&mut self, c: &Spanned<CameraDef>) -> Camera {
        let d = c.get_ref();
        let position = self.vec3(&d.position, "camera position");
        let look_at = self.vec3(&d.look_at, "camera look_at");
        let up = d.up.as_ref().map_or(Vec3::Y, |u| self.vec3(u, "camera up"));
        let fov = *d.fov_deg.get_ref();
        if !(fov.is_finite() && fov > 0.0 && fov < 180.0) {
            self.error(
                d.fov_deg.span().start,
                format!("fov_deg {fov} is outside (0, 180)"),
            );
        }
        let gaze = look_at - position;
        if gaze.length() <= 1e-6 * (1.0 + position.length()) {
            self.error(
                d.look_at.span().start,
                "camera look_at equals its position: no view direction",
            );
        } else if gaze.normalize().cross(up.normalize_or_zero()).length() < 1e-4 {
            self.error(
                d.up.as_ref()
                    .map_or(d.look_at.span().start, |u| u.span().start),
                "camera up is parallel to the view direction (or zero)",
            );
        }
        let mut size = |v: &Spanned<i64>, what: &str| -> u32 {
            let x = *v.get_ref();
            if !(1..=32768).contains(&x) {
                self.error(
                    v.span().start,
                    format!("camera {what} {x} must be between 1 and 32768"),
                );
                return 1;
            }
            x as u32
        };
        let width = size(&d.width, "width");
        let height = size(&d.height, "height");
        Camera {
            position,
            look_at,
            up,
            fov_deg: fov,
            width,
            height,
            projection: crate::Projection::Pinhole,
        }
    }

    fn render(&mut self, r: &format::RenderDef) -> RenderDefaults {
        let mut out = RenderDefaults::default();
        if let Some(s) = &r.spp {
            if (1..=1 << 24).contains(s.get_ref()) {
                out.spp = Some(*s.get_ref() as u32);
            } else {
                self.error(
                    s.span().start,
                    format!("spp {} must be between 1 and 16777216", s.get_ref()),
                );
            }
        }
        if let Some(s) = &r.max_depth {
            if *s.get_ref() == -1 || (1..=1024).contains(s.get_ref()) {
                out.max_depth = Some(*s.get_ref() as i32);
            } else {
                self.error(
                    s.span().start,
                    format!(
                        "max_depth {} must be -1 (unlimited) or 1..=1024",
                        s.get_ref()
                    ),
                );
            }
        }
        if let Some(s) = &r.rr_depth {
            if (1..=1024).contains(s.get_ref()) {
                out.rr_depth = Some(*s.get_ref() as u32);
            } else {
                self.error(
                    s.span().start,
                    format!("rr_depth {} must be 1..=1024", s.get_ref()),
                );
            }
        }
        if let Some(s) = &r.seed {
            if *s.get_ref() >= 0 {
                out.seed = Some(*s.get_ref() as u64);
            } else {
                self.error(s.span().start, format!("seed {} must be >= 0", s.get_ref()));
            }
        }
        out
    }
}
