//! Scene description for eyeadapt: plain data, loading and validation, no rendering behaviour.
//!
//! A [`Scene`] is loaded from a TOML file by [`load_scene`] (format: `docs/scene-format.md`).
//! It owns triangle [`Mesh`]es in object space placed by [`Instance`]s, [`Material`]s
//! referenced by [`MaterialId`] whose parameters are constants or [`Texture`]s ([`Param`]),
//! delta [`Light`]s (point, spot and directional), an optional constant environment and
//! [`EnvironmentMap`] with the [`Portal`]s it is sampled through, the [`Camera`] and an
//! optional [`CameraPath`] (keyframes that [`CameraPath::sample`] turns into a [`CameraPose`]).
//! Quads, boxes and spheres are tessellated at load time; OBJ files come in through `tobj`.
//! Every problem found while loading is a [`Diagnostic`] carrying `file:line:col`; loading
//! reports all of them at once ([`SceneError`]). Warnings (a missing MTL, an unknown material)
//! do not stop loading: the affected triangles get the loud [`Material::error`] material.
//! Every file a scene names is opened through [`open_input`], which reads regular files only
//! (a FIFO or device is an error naming it, never a read that blocks or does not end).
//!
//! Units: lengths are arbitrary scene units; colours are linear sRGB (Rec. 709 primaries, D65
//! white); `emission` and environment values are radiance, light `intensity` is radiant
//! intensity (radiance × area / distance² behaves as in Mitsuba 3's `rgb` emitters).
// Public items' docs point at the private code that does their work: the crate's docs are
// read with `cargo doc --document-private-items`, where those links resolve.
#![allow(rustdoc::private_intra_doc_links)]

mod any;
mod builtin;
mod camera;
mod camera_motion;
mod camera_path;
mod camera_track;
mod diagnostic;
mod environment;
mod fingerprint;
pub mod gltf;
mod image_file;
mod input_file;
mod instance;
mod light;
mod material;
mod mesh;
mod mitsuba;
mod obj;
mod pixel_filter;
mod portal;
mod principled;
mod scene;
mod shapes;
mod texture;
mod toml_scene;
mod track;
mod transform;

pub use crate::any::{is_mitsuba_path, load_scene_file};
pub use crate::builtin::{builtin_scenes, load_builtin, resolve_scene};
pub use crate::camera::{Camera, Projection};
pub use crate::camera_motion::{CameraMotion, DEFAULT_FPS, MAX_FPS, MAX_FRAMES};
pub use crate::camera_path::{CameraPath, CameraPose, Keyframe, Orientation, PathProblem};
pub use crate::camera_track::{CameraTrack, MAX_TRACK_ROWS};
pub use crate::diagnostic::{Diagnostic, SceneError, Severity, SourceMap};
pub use crate::environment::{EnvironmentMap, check_lat_long, rotation_part};
pub use crate::image_file::{ImageCache, load_image, srgb_to_linear};
pub use crate::input_file::{check_input, is_bad_input, open_input, read_input, read_input_text};
pub use crate::instance::Instance;
pub use crate::light::Light;
pub use crate::material::{Bsdf, Distribution, Material, MaterialId, Param};
pub use crate::mesh::{Mesh, MeshId};
pub use crate::mitsuba::{load_mitsuba, load_mitsuba_str, mitsuba_vertical_fov};
pub use crate::obj::{LoadedObj, load_obj_bytes};
pub use crate::pixel_filter::{FilterWeights, PixelFilter};
pub use crate::portal::Portal;
pub use crate::principled::{Principled, PrincipledThin};
pub use crate::scene::{CutoutShadows, RenderDefaults, Scene};
pub use crate::shapes::{box_mesh, quad_mesh, sphere_mesh};
pub use crate::texture::{Bitmap, FilterType, Image, Texture, TextureId, WrapMode};
pub use crate::toml_scene::{load_scene, load_scene_str};
pub(crate) use crate::toml_scene::{load_scene_str_with, scene_dir};
pub use crate::track::{Interpolation, Track, TrackValue};
pub use crate::transform::Transform;

/// Linear sRGB triple (radiance, reflectance or intensity, depending on the field).
pub type Rgb = glam::Vec3;

/// Largest colour component any loader accepts (emission, environment radiance, intensity,
/// reflectance, IOR). Far beyond any radiance in scene units; above it the tracer's light
/// powers (π · area · luminance, in single precision) overflow, and an area light whose power
/// is infinite silently drops out of light sampling.
pub const MAX_COLOUR: f32 = 1e15;

/// Why a colour is unusable, if it is: NaN or infinite, negative, or above [`MAX_COLOUR`].
pub fn check_colour(c: Rgb) -> Result<(), String> {
    if !c.is_finite() {
        Err("has a non-finite component".into())
    } else if c.min_element() < 0.0 {
        Err("has a negative component".into())
    } else if c.max_element() > MAX_COLOUR {
        Err(format!(
            "has a component above {MAX_COLOUR:e}: beyond any radiance, and light powers would overflow"
        ))
    } else {
        Ok(())
    }
}
