//! The job's `[camera_path]` table and the camera motion it selects.
//!
//! ```toml
//! [camera_path]                 # keyframes, as in a scene's [camera_path]
//! fps = 24
//! keyframes = [ { time = 0.0, position = [0, 1.6, 4], look_at = [0, 1.2, 0] }, … ]
//!
//! [camera_path]                 # or a CSV track (eyeadapt_scene::CameraTrack's format)
//! file = "camera.csv"           # relative to the job file
//! fps = 30                      # default 24
//!
//! [camera_path]                 # or, for a .gltf/.glb scene, one of its cameras
//! camera = "Eye"                # node or camera name; default the first animated camera
//! animation = "CameraAction"    # default: every animation of the file plays at once
//! fps = 24                      # default 24
//! ```
//!
//! Without a `[camera_path]` the scene's own path is used, and a glTF scene is followed
//! through its first animated camera at 24 fps from time 0 to the end of its animation.
use eyeadapt_scene::gltf::{is_gltf_path, load_camera};
use eyeadapt_scene::{CameraMotion, CameraPath, CameraTrack, DEFAULT_FPS, Keyframe, Scene};
use serde::Deserialize;
use std::path::Path;
use toml::Spanned;

/// The `[camera_path]` table of a job file.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CameraPathTable {
    fps: Option<f64>,
    keyframes: Option<Vec<Keyframe>>,
    file: Option<String>,
    camera: Option<String>,
    animation: Option<String>,
}

/// A problem at a byte offset of the job file.
pub type Problem = (usize, String);

/// The camera motion of a job whose scene is `scene` (loaded from `scene_path`), with the job
/// file's `[camera_path]` table if it has one; relative files are found from `dir`.
pub fn camera_motion(
    table: Option<&Spanned<CameraPathTable>>,
    scene: &Scene,
    scene_path: &Path,
    dir: &Path,
) -> Result<CameraMotion, Vec<Problem>> {
    let at = table.map_or(0, |t| t.span().start);
    let one = |msg: String| vec![(at, msg)];
    let gltf = is_gltf_path(scene_path);
    let motion = match table.map(Spanned::get_ref) {
        None if gltf => follow(scene_path, None, None, DEFAULT_FPS).map_err(one)?,
        None => match &scene.camera_path {
            Some(path) => CameraMotion::Keyframes(path.clone()),
            None => {
                return Err(one(
                    "the job has no [camera_path] and its scene defines none".into(),
                ));
            }
        },
        Some(t) => from_table(t, scene, scene_path, dir, gltf).map_err(one)?,
    };
    motion
        .check()
        .map_err(|m| one(format!("camera_path: {m}")))?;
    Ok(motion)
}

fn from_table(
    t: &CameraPathTable,
    scene: &Scene,
    scene_path: &Path,
    dir: &Path,
    gltf: bool,
) -> Result<CameraMotion, String> {
    let gltf_keys = t.camera.is_some() || t.animation.is_some();
    if gltf_keys && !gltf {
        return Err(
            "camera_path: `camera` and `animation` choose a glTF camera; this scene is not glTF"
                .into(),
        );
    }
    match (&t.keyframes, &t.file) {
        (Some(_), Some(_)) => Err("camera_path: give `keyframes` or `file`, not both".into()),
        (Some(_), None) | (None, Some(_)) if gltf_keys => Err(
            "camera_path: `camera`/`animation` follow the glTF file's camera; they do not go \
             with `keyframes` or `file`"
                .into(),
        ),
        (Some(keyframes), None) => {
            let fps = t.fps.ok_or("camera_path: keyframes need `fps`")?;
            let path = CameraPath {
                fps,
                keyframes: keyframes.clone(),
            };
            path.validate().map_err(|problems| {
                // Some problems name their field (`camera_path.keyframes[1]: …`), some do not.
                let all: Vec<String> = problems.iter().map(|e| e.to_string()).collect();
                let all = all.join("; ");
                match all.strip_prefix("camera_path: ") {
                    Some(rest) => format!("camera_path: {rest}"),
                    None => format!("camera_path: {all}"),
                }
            })?;
            Ok(CameraMotion::Keyframes(path))
        }
        (None, Some(file)) => {
            let fps = t.fps.unwrap_or(DEFAULT_FPS);
            // A `frame` column is divided by fps: check it before the rows are read.
            if !(fps.is_finite() && fps > 0.0) {
                return Err(format!("camera_path: fps = {fps} is not a positive number"));
            }
            let track = CameraTrack::read_csv(&dir.join(file), fps).map_err(|e| e.to_string())?;
            Ok(CameraMotion::Track { track, fps })
        }
        (None, None) if gltf => follow(
            scene_path,
            t.camera.as_deref(),
            t.animation.as_deref(),
            t.fps.unwrap_or(DEFAULT_FPS),
        ),
        (None, None) => match (&scene.camera_path, t.fps) {
            (Some(path), None) => Ok(CameraMotion::Keyframes(path.clone())),
            _ => Err("camera_path: give `keyframes` or a CSV `file`".into()),
        },
    }
}

fn follow(
    scene_path: &Path,
    camera: Option<&str>,
    animation: Option<&str>,
    fps: f64,
) -> Result<CameraMotion, String> {
    let camera = load_camera(scene_path, camera, animation).map_err(|e| e.to_string())?;
    Ok(CameraMotion::Gltf {
        camera: Box::new(camera),
        fps,
    })
}

/// A glTF scene's moving objects follow the animation its camera follows: the job's
/// `[camera_path] animation` picks one for both (by default every animation plays).
pub fn play_with_camera(scene: &mut Scene, motion: &CameraMotion) {
    if let (CameraMotion::Gltf { camera, .. }, Some(a)) = (motion, scene.animation.as_mut()) {
        std::sync::Arc::make_mut(a).tree = camera.tree.clone();
    }
}
