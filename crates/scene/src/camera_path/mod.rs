//! Camera paths: keyframes in time, evaluated into a camera pose at any frame time.
//!
//! A scene's `[camera_path]` table (all times in seconds, positions in scene units):
//!
//! ```
//! # use eyeadapt_scene::CameraPath;
//! # #[derive(serde::Deserialize)] struct Doc { camera_path: CameraPath }
//! # let doc: Doc = toml::from_str(r#"
//! [camera_path]
//! fps = 24
//!
//! [[camera_path.keyframes]]
//! time = 0.0
//! position = [0.0, 1.6, 4.0]
//! look_at = [0.0, 1.2, 0.0]     # `up` is optional, default [0, 1, 0]
//! fov_deg = 50                  # optional; without it the scene camera's fov is used
//!
//! [[camera_path.keyframes]]
//! time = 2.5
//! position = [1.0, 1.6, 2.0]
//! yaw_deg = 180                 # instead of look_at; pitch_deg defaults to 0
//! pitch_deg = -5
//! fov_deg = 40
//! # "#).unwrap();
//! # let path = doc.camera_path;
//! # assert!(path.validate().is_ok());
//! # assert_eq!(path.frame_count(), 61);
//! ```
//!
//! **Conventions.** Right-handed, +y up. A camera looks along its local −z with +y up and +x to
//! the right (glam's and OpenGL's convention). `yaw_deg = 0` looks along −z, and yaw grows
//! counter-clockwise seen from above (+y), so yaw 90° looks along −x and yaw 180° along +z.
//! `pitch_deg` > 0 looks up; |pitch| ≤ 90°. Yaw/pitch keyframes never roll: their right axis
//! stays horizontal.
//!
//! **Evaluation** ([`CameraPath::sample`]). Before the first keyframe and after the last, the
//! camera holds the end pose; one keyframe is a static camera.
//! - *Position* follows a centripetal Catmull-Rom spline (α = ½, Barry–Goldman pyramid) through
//!   the keyframe positions, with phantom end points by reflection (P₋₁ = 2P₀ − P₁,
//!   Pₙ = 2Pₙ₋₁ − Pₙ₋₂). Centripetal knots (τᵢ₊₁ − τᵢ = |Pᵢ₊₁ − Pᵢ|^½) are what keep the curve
//!   free of cusps and self-intersections inside a segment.
//! - *Timing.* Mapping each segment's knot interval linearly onto its time interval, the usual
//!   shortcut, is only C0 in time: the spline is C1 in its knot parameter τ, so the velocity
//!   `dP/dt = dP/dτ · Δτᵢ/ΔTᵢ` jumps at a keyframe wherever that ratio differs between the two
//!   neighbouring segments — a visible kick in camera speed (a test below measures it). Instead,
//!   τ is a C1 function of time: the monotone cubic interpolant (Fritsch–Carlson, with Brodlie's
//!   weighted-harmonic-mean slopes, as in SciPy's `PchipInterpolator`) of the points (Tᵢ, τᵢ).
//!   The camera thus travels exactly along the centripetal curve, never backs up along it (τ is
//!   monotone), reaches every keyframe at its time, and its velocity is continuous. When the
//!   keyframe times are proportional to the knot spacing, τ(t) is linear and this is exactly the
//!   centripetal spline with time-uniform segments; evenly spaced keyframes on a straight line
//!   at even times give constant speed.
//! - *Duplicate positions* (a zero knot interval: the camera waits while it turns, say) hold the
//!   camera still; the monotone map gives zero velocity on both sides of such a pause, so
//!   velocity stays continuous and no division by zero occurs.
//! - *Orientation* is a quaternion per keyframe, each flipped into the same hemisphere as the
//!   previous one, then slerped linearly in time: the shorter arc, so a turn of more than 180°
//!   between two keyframes needs an intermediate keyframe.
//! - *Field of view* is linear in time. It must be given on every keyframe or on none (then
//!   [`CameraPose::fov_deg`] is `None` and the scene camera's fov applies).
//!
//! **Frames.** Frame i is at `t₀ + i/fps`, from the first keyframe up to and including the last
//! keyframe's time when it falls on a frame ([`CameraPath::frame_count`]).

mod keyframe_toml;
pub(crate) mod orientation;
mod spline;
#[cfg(test)]
mod tests;

use crate::camera_path::orientation::{look_at_basis, orientation_quat, pose};
use glam::DVec3;
use serde::Deserialize;
use std::fmt;

/// Keyframed camera motion, as read from a scene's `[camera_path]` table.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CameraPath {
    /// Frames per second of the rendered sequence.
    pub fps: f64,
    /// In increasing time order (checked by [`CameraPath::validate`]).
    pub keyframes: Vec<Keyframe>,
}

/// One keyframe of a [`CameraPath`].
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(try_from = "keyframe_toml::KeyframeToml")]
pub struct Keyframe {
    /// Seconds.
    pub time: f64,
    pub position: DVec3,
    pub orientation: Orientation,
    /// Vertical field of view in degrees; `None`: the scene camera's.
    pub fov_deg: Option<f64>,
}

/// How a keyframe says where the camera looks.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Orientation {
    /// Look from the keyframe position towards `look_at`, with `up` as the approximate up.
    LookAt { look_at: DVec3, up: DVec3 },
    /// Angles in degrees; see the module docs for the convention.
    YawPitch { yaw_deg: f64, pitch_deg: f64 },
}

/// The camera at one instant. `forward` and `up` are unit length and orthogonal.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CameraPose {
    pub position: DVec3,
    pub forward: DVec3,
    pub up: DVec3,
    /// `None` when the path gives no fov: use the scene camera's.
    pub fov_deg: Option<f64>,
}

impl CameraPose {
    /// `forward × up`: the image's +x direction.
    pub fn right(&self) -> DVec3 {
        self.forward.cross(self.up)
    }
}

/// One thing wrong with a camera path; `keyframe` is the index in `keyframes` when the problem
/// belongs to one (so a loader holding spans can point at the right table).
#[derive(Debug, Clone, PartialEq)]
pub struct PathProblem {
    pub keyframe: Option<usize>,
    pub message: String,
}

impl fmt::Display for PathProblem {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.keyframe {
            Some(i) => write!(f, "camera_path.keyframes[{i}]: {}", self.message),
            None => write!(f, "camera_path: {}", self.message),
        }
    }
}

impl CameraPath {
    /// Every problem at once, so a user fixes a path in one edit. [`CameraPath::sample`] and
    /// the frame functions assume a path that passed.
    pub fn validate(&self) -> Result<(), Vec<PathProblem>> {
        let mut problems = Vec::new();
        let mut problem =
            |keyframe, message: String| problems.push(PathProblem { keyframe, message });
        if !(self.fps.is_finite() && self.fps > 0.0) {
            problem(
                None,
                format!("fps must be a positive number, got {}", self.fps),
            );
        }
        if self.keyframes.is_empty() {
            problem(None, "needs at least 1 keyframe".into());
        }
        let with_fov = self
            .keyframes
            .iter()
            .filter(|k| k.fov_deg.is_some())
            .count();
        if with_fov != 0 && with_fov != self.keyframes.len() {
            problem(
                None,
                format!(
                    "fov_deg is given on {with_fov} of {} keyframes; give it on all or none \
                     (a missing one would have to blend with the scene camera's)",
                    self.keyframes.len()
                ),
            );
        }
        for (i, k) in self.keyframes.iter().enumerate() {
            let at = Some(i);
            let prev = i.checked_sub(1).map(|p| self.keyframes[p].time);
            if !k.time.is_finite() {
                problem(at, format!("time must be finite, got {}", k.time));
            } else if let Some(prev) = prev.filter(|&prev| prev.is_finite() && k.time <= prev) {
                problem(
                    at,
                    format!(
                        "time {} s must be after the previous keyframe's {prev} s",
                        k.time
                    ),
                );
            }
            // Keyframes are f64 but the renderer's rays are f32: beyond ±3.4e38 a coordinate
            // turns infinite (and its square overflows long before in the direction's length).
            let single = |v: DVec3| v.as_vec3().is_finite();
            if !single(k.position) {
                problem(
                    at,
                    format!(
                        "position {:?} is not finite in single precision (coordinates must stay within ±3.4e38)",
                        k.position.to_array()
                    ),
                );
            }
            match k.orientation {
                Orientation::LookAt { look_at, up } => {
                    if !single(look_at) || !single(up) {
                        problem(
                            at,
                            format!(
                                "look_at {:?} / up {:?} is not finite in single precision (coordinates must stay within ±3.4e38)",
                                look_at.to_array(),
                                up.to_array()
                            ),
                        );
                    } else if !single(k.position) {
                        // Reported above; the view direction cannot be judged from it.
                    } else if (look_at - k.position).try_normalize().is_none() {
                        problem(at, format!("look_at {look_at} equals the position"));
                    } else if up.try_normalize().is_none() {
                        problem(at, "up is the zero vector".into());
                    } else if look_at_basis(k.position, look_at, up).is_none() {
                        problem(at, format!("up {up} is parallel to the view direction"));
                    }
                }
                Orientation::YawPitch { yaw_deg, pitch_deg } => {
                    if !yaw_deg.is_finite() || !pitch_deg.is_finite() {
                        problem(
                            at,
                            format!("yaw_deg {yaw_deg} / pitch_deg {pitch_deg} is not finite"),
                        );
                    } else if pitch_deg.abs() > 90.0 {
                        problem(at, format!("pitch_deg {pitch_deg} is outside [-90, 90]"));
                    }
                }
            }
            if let Some(fov) = k.fov_deg.filter(|fov| !(*fov > 0.0 && *fov < 180.0)) {
                problem(at, format!("fov_deg {fov} is outside (0, 180)"));
            }
        }
        if problems.is_empty() {
            Ok(())
        } else {
            Err(problems)
        }
    }

    /// The camera at time `t` (seconds), clamped to the keyframe range. A NaN `t` gives the
    /// first keyframe.
    ///
    /// # Panics
    /// If there are no keyframes ([`CameraPath::validate`] reports that).
    pub fn sample(&self, t: f64) -> CameraPose {
        let keys = &self.keyframes;
        assert!(!keys.is_empty(), "camera path has no keyframes");
        let last = keys.len() - 1;
        // NaN compares as unordered and lands here too.
        if last == 0 || t.partial_cmp(&keys[0].time) != Some(std::cmp::Ordering::Greater) {
            return self.keyframe_pose(0);
        }
        if t >= keys[last].time {
            return self.keyframe_pose(last);
        }
        // Segment i with T_i <= t < T_{i+1}.
        let i = keys.partition_point(|k| k.time <= t) - 1;
        let (k0, k1) = (&keys[i], &keys[i + 1]);
        let s = (t - k0.time) / (k1.time - k0.time);
        let q0 = orientation_quat(k0);
        let mut q1 = orientation_quat(k1);
        // q and −q are the same rotation; slerp between opposite signs would spin the long way.
        if q0.dot(q1) < 0.0 {
            q1 = -q1;
        }
        let fov_deg = k0.fov_deg.zip(k1.fov_deg).map(|(a, b)| a + (b - a) * s);
        pose(self.position(i, t), q0.slerp(q1, s), fov_deg)
    }

    /// Number of frames from the first keyframe to the last, both inclusive when on a frame.
    pub fn frame_count(&self) -> usize {
        let (Some(first), Some(last)) = (self.keyframes.first(), self.keyframes.last()) else {
            return 0;
        };
        let frames = (last.time - first.time) * self.fps;
        // A duration such as 2.3 s at 10 fps computes as 22.999999999999996 frames; a tolerance
        // far below one frame keeps the frame that lies on the last keyframe.
        (frames + 1e-9).floor() as usize + 1
    }

    /// Time of frame `index`: `t₀ + index/fps` (past the end, [`CameraPath::sample`] clamps).
    pub fn frame_time(&self, index: usize) -> f64 {
        let t0 = self.keyframes.first().map_or(0.0, |k| k.time);
        t0 + index as f64 / self.fps
    }

    fn keyframe_pose(&self, i: usize) -> CameraPose {
        let k = &self.keyframes[i];
        pose(k.position, orientation_quat(k), k.fov_deg)
    }
}
