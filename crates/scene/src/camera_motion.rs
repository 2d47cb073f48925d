//! How the camera of a sequence moves: keyframes, a glTF animation, or a CSV track.
//!
//! All three answer the same questions — how many frames, the time of frame i, the pose at a
//! time — so the sequencer need not know where the motion came from.
//! - [`CameraPath`] keyframes carry their own fps; frame i is at `t₀ + i/fps` from the first
//!   keyframe's time.
//! - A glTF camera ([`AnimatedCamera`]) and a CSV track ([`CameraTrack`]) run on the file's
//!   clock: frame i is at `i/fps` (frame 0 at time 0) up to the end of the animation or
//!   track, both ends included when the end falls on a frame.
use crate::gltf::AnimatedCamera;
use crate::{CameraPath, CameraPose, CameraTrack};

/// Frames per second of a glTF walkthrough whose job gives none (glTF's own animations are
/// in seconds; 24 is Blender's default and the film rate).
pub const DEFAULT_FPS: f64 = 24.0;

/// Most frames a camera motion may have: a day at 120 fps. Bounding the count before any
/// per-frame allocation keeps a typo such as `fps = 1e9` a clear error, not an abort.
pub const MAX_FRAMES: usize = 10_368_000;

#[derive(Clone, Debug, PartialEq)]
pub enum CameraMotion {
    Keyframes(CameraPath),
    Gltf {
        camera: Box<AnimatedCamera>,
        fps: f64,
    },
    Track {
        track: CameraTrack,
        fps: f64,
    },
}

impl CameraMotion {
    pub fn fps(&self) -> f64 {
        match self {
            CameraMotion::Keyframes(p) => p.fps,
            CameraMotion::Gltf { fps, .. } | CameraMotion::Track { fps, .. } => *fps,
        }
    }

    /// Frames from the start to the end, both inclusive when the end falls on a frame.
    pub fn frame_count(&self) -> usize {
        match self {
            CameraMotion::Keyframes(p) => p.frame_count(),
            CameraMotion::Gltf { camera, fps } => frames_to(camera.range.1, *fps),
            CameraMotion::Track { track, fps } => frames_to(track.range().1, *fps),
        }
    }

    /// The time of frame `index` (seconds).
    pub fn frame_time(&self, index: usize) -> f64 {
        match self {
            CameraMotion::Keyframes(p) => p.frame_time(index),
            CameraMotion::Gltf { fps, .. } | CameraMotion::Track { fps, .. } => index as f64 / fps,
        }
    }

    /// The camera at time `t` (seconds).
    pub fn sample(&self, t: f64) -> CameraPose {
        match self {
            CameraMotion::Keyframes(p) => p.sample(t),
            CameraMotion::Gltf { camera, .. } => camera.pose(t),
            CameraMotion::Track { track, .. } => track.pose(t),
        }
    }

    /// Why the motion cannot be rendered as a sequence, if it cannot: a frame rate that is not
    /// a positive finite number, or more than [`MAX_FRAMES`] frames.
    pub fn check(&self) -> Result<(), String> {
        let fps = self.fps();
        if !(fps.is_finite() && fps > 0.0) {
            return Err(format!("fps = {fps} is not a positive number"));
        }
        let end = match self {
            CameraMotion::Keyframes(p) => {
                p.keyframes.last().map_or(0.0, |k| k.time)
                    - p.keyframes.first().map_or(0.0, |k| k.time)
            }
            CameraMotion::Gltf { camera, .. } => camera.range.1,
            CameraMotion::Track { track, .. } => track.range().1,
        };
        let frames = end.max(0.0) * fps;
        if !frames.is_finite() || frames >= MAX_FRAMES as f64 {
            return Err(format!(
                "{end} s at {fps} fps is {frames:.0} frames, more than the {MAX_FRAMES} a sequence may have"
            ));
        }
        Ok(())
    }
}

/// Frames at `fps` from time 0 to `end`. Exporters write times in single precision (Blender:
/// 47/24 s is 1.9583333 s, times 24 = 46.999999): a tolerance far below a frame keeps the last.
fn frames_to(end: f64, fps: f64) -> usize {
    let frames = end.max(0.0) * fps;
    (frames + 1e-4).floor().min(MAX_FRAMES as f64) as usize + 1
}
