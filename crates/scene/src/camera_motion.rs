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

/// Highest frame rate of a sequence. Far above any film or high-speed capture a path tracer
/// renders; it bounds what is computed from the rate (frame counts, the report's smoothing
/// window of σ·fps frames), so that `fps = 1e9` is an error, not a 16 GB allocation.
pub const MAX_FPS: f64 = 10_000.0;

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
    /// a positive number up to [`MAX_FPS`], more than [`MAX_FRAMES`] frames, or a frame whose
    /// camera is not finite in single precision (the renderer's) after the path's arithmetic.
    pub fn check(&self) -> Result<(), String> {
        let fps = self.fps();
        if !(fps.is_finite() && fps > 0.0) {
            return Err(format!("fps = {} is not a positive number", short(fps)));
        }
        if fps > MAX_FPS {
            return Err(format!(
                "fps = {} is above the {MAX_FPS} a sequence may have",
                short(fps)
            ));
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
                "{} s at {} fps is {} frames, more than the {MAX_FRAMES} a sequence may have",
                short(end),
                short(fps),
                short(frames.floor())
            ));
        }
        for f in 0..self.frame_count() {
            let t = self.frame_time(f);
            let pose = self.sample(t);
            let single = |v: glam::DVec3| v.as_vec3().is_finite();
            if !(single(pose.position) && single(pose.forward) && single(pose.up)) {
                return Err(format!(
                    "the camera of frame {f} (t = {} s) is not finite in single precision: \
                     position {:?}, forward {:?}, up {:?} (coordinates must stay within ±3.4e38)",
                    short(t),
                    pose.position.to_array(),
                    pose.forward.to_array(),
                    pose.up.to_array()
                ));
            }
        }
        Ok(())
    }
}

/// A number for a message: as it is when short, in scientific notation when huge or tiny.
fn short(x: f64) -> String {
    if x == 0.0 || !x.is_finite() || (1e-4..1e9).contains(&x.abs()) {
        format!("{x}")
    } else {
        format!("{x:e}")
    }
}

/// Frames at `fps` from time 0 to `end`. Exporters write times in single precision (Blender:
/// 47/24 s is 1.9583333 s, times 24 = 46.999999): a tolerance far below a frame keeps the last.
fn frames_to(end: f64, fps: f64) -> usize {
    let frames = end.max(0.0) * fps;
    (frames + 1e-4).floor().min(MAX_FRAMES as f64) as usize + 1
}
