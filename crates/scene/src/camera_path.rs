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

use std::fmt;

use glam::{DMat3, DQuat, DVec3};
use serde::Deserialize;

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
#[serde(try_from = "KeyframeToml")]
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

/// The keyframe as written in TOML. `look_at` and yaw/pitch are alternatives; serde's
/// `flatten` cannot be combined with `deny_unknown_fields` (deps.md §7), so the choice is
/// checked here and turned into [`Orientation`] by `TryFrom`.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct KeyframeToml {
    time: f64,
    position: DVec3,
    look_at: Option<DVec3>,
    up: Option<DVec3>,
    yaw_deg: Option<f64>,
    pitch_deg: Option<f64>,
    fov_deg: Option<f64>,
}

impl TryFrom<KeyframeToml> for Keyframe {
    type Error = String;

    fn try_from(k: KeyframeToml) -> Result<Keyframe, String> {
        let has_angles = k.yaw_deg.is_some() || k.pitch_deg.is_some();
        let orientation = match (k.look_at, k.yaw_deg) {
            (Some(_), _) if has_angles => {
                return Err("give either `look_at` or `yaw_deg`/`pitch_deg`, not both".into());
            }
            (Some(look_at), _) => Orientation::LookAt {
                look_at,
                up: k.up.unwrap_or(DVec3::Y),
            },
            (None, Some(yaw_deg)) => {
                if k.up.is_some() {
                    return Err("`up` only applies with `look_at` (yaw/pitch never roll)".into());
                }
                Orientation::YawPitch {
                    yaw_deg,
                    pitch_deg: k.pitch_deg.unwrap_or(0.0),
                }
            }
            (None, None) if k.pitch_deg.is_some() => {
                return Err("`pitch_deg` needs `yaw_deg`".into());
            }
            (None, None) => {
                return Err(
                    "a keyframe needs `look_at` or `yaw_deg` (and optionally `pitch_deg`)".into(),
                );
            }
        };
        Ok(Keyframe {
            time: k.time,
            position: k.position,
            orientation,
            fov_deg: k.fov_deg,
        })
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
            if !k.position.is_finite() {
                problem(at, format!("position {} is not finite", k.position));
            }
            match k.orientation {
                Orientation::LookAt { look_at, up } => {
                    if !look_at.is_finite() || !up.is_finite() {
                        problem(at, format!("look_at {look_at} / up {up} is not finite"));
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

    /// Keyframe position j, with the reflected phantoms at j = −1 and j = n.
    fn point(&self, j: isize) -> DVec3 {
        let keys = &self.keyframes;
        let n = keys.len() as isize;
        let p = |j: isize| keys[j as usize].position;
        match j {
            -1 if n >= 2 => 2.0 * p(0) - p(1),
            -1 => p(0),
            j if j == n && n >= 2 => 2.0 * p(n - 1) - p(n - 2),
            j if j == n => p(n - 1),
            j => p(j),
        }
    }

    /// Centripetal knot interval between points j and j+1 (phantoms included).
    fn knot_interval(&self, j: isize) -> f64 {
        self.point(j).distance(self.point(j + 1)).sqrt()
    }

    /// Slope of τ(t) at keyframe j: monotone-cubic (PCHIP) slopes of the points (T_j, τ_j).
    fn knot_rate(&self, j: usize) -> f64 {
        let keys = &self.keyframes;
        let n = keys.len();
        let dt = |j: usize| keys[j + 1].time - keys[j].time;
        let secant = |j: usize| self.knot_interval(j as isize) / dt(j);
        if n == 2 {
            return secant(0);
        }
        // Three-point end formula, clipped at zero to stay monotone (SciPy's `_edge_case`; its
        // second clip, to 3× the secant, cannot trigger when all secants are non-negative).
        let end = |h0: f64, h1: f64, m0: f64, m1: f64| {
            (((2.0 * h0 + h1) * m0 - h0 * m1) / (h0 + h1)).max(0.0)
        };
        if j == 0 {
            return end(dt(0), dt(1), secant(0), secant(1));
        }
        if j == n - 1 {
            return end(dt(n - 2), dt(n - 3), secant(n - 2), secant(n - 3));
        }
        let (m0, m1) = (secant(j - 1), secant(j));
        if m0 == 0.0 || m1 == 0.0 {
            // A pause on either side: stop there, so velocity is continuous (zero) across it.
            return 0.0;
        }
        let (h0, h1) = (dt(j - 1), dt(j));
        let (w1, w2) = (2.0 * h1 + h0, h1 + 2.0 * h0);
        (w1 + w2) / (w1 / m0 + w2 / m1)
    }

    /// τ(t) − τ_i inside segment i, in [0, h_i]: the cubic Hermite of the monotone map.
    fn knot_progress(&self, i: usize, t: f64) -> f64 {
        let keys = &self.keyframes;
        let h = self.knot_interval(i as isize);
        let dt = keys[i + 1].time - keys[i].time;
        let s = (t - keys[i].time) / dt;
        let (s2, s3) = (s * s, s * s * s);
        let u = (s3 - 2.0 * s2 + s) * dt * self.knot_rate(i)
            + (3.0 * s2 - 2.0 * s3) * h
            + (s3 - s2) * dt * self.knot_rate(i + 1);
        // Monotone in exact arithmetic; the clamp only absorbs rounding at the ends.
        u.clamp(0.0, h)
    }

    /// Position at time t inside segment i (T_i ≤ t < T_{i+1}).
    fn position(&self, i: usize, t: f64) -> DVec3 {
        if self.knot_interval(i as isize) == 0.0 {
            return self.keyframes[i].position;
        }
        self.curve(i, self.knot_progress(i, t))
    }

    /// The centripetal spline on segment i at local knot parameter u ∈ [0, h_i], h_i > 0.
    fn curve(&self, i: usize, u: f64) -> DVec3 {
        let j = i as isize;
        let points = [-1, 0, 1, 2].map(|k| self.point(j + k));
        let intervals = [-1, 0, 1].map(|k| self.knot_interval(j + k));
        catmull_rom_segment(points, intervals, u)
    }
}

/// The Barry–Goldman pyramid for the segment P1→P2 with knots (−h0, 0, h1, h1 + h2), at local
/// knot parameter `u` ∈ [0, h1], h1 > 0. A zero h0 or h2 (a point repeated at the segment's end)
/// is the limit of its linear term: (P1 − P0)/h0 has length h0 and vanishes, so A1 = P1.
fn catmull_rom_segment(p: [DVec3; 4], h: [f64; 3], u: f64) -> DVec3 {
    let [p0, p1, p2, p3] = p;
    let [h0, h1, h2] = h;
    if u <= 0.0 {
        return p1;
    }
    if u >= h1 {
        return p2;
    }
    let a1 = if h0 == 0.0 {
        p1
    } else {
        p1 + (p1 - p0) * (u / h0)
    };
    let a2 = p1 + (p2 - p1) * (u / h1);
    let a3 = if h2 == 0.0 {
        p2
    } else {
        p2 + (p3 - p2) * ((u - h1) / h2)
    };
    let b1 = (a1 * (h1 - u) + a2 * (u + h0)) / (h0 + h1);
    let b2 = (a2 * (h1 + h2 - u) + a3 * u) / (h1 + h2);
    (b1 * (h1 - u) + b2 * u) / h1
}

fn pose(position: DVec3, q: DQuat, fov_deg: Option<f64>) -> CameraPose {
    // Renormalising keeps |forward| = |up| = 1 to the last bit after slerp's rounding.
    let q = q.normalize();
    CameraPose {
        position,
        forward: (q * DVec3::NEG_Z).normalize(),
        up: (q * DVec3::Y).normalize(),
        fov_deg,
    }
}

/// Rotation taking the camera's local frame (−z forward, +y up) to the keyframe's.
fn orientation_quat(k: &Keyframe) -> DQuat {
    match k.orientation {
        Orientation::LookAt { look_at, up } => {
            let basis = look_at_basis(k.position, look_at, up).unwrap_or(DMat3::IDENTITY);
            DQuat::from_mat3(&basis).normalize()
        }
        // Pitch about the camera's own x axis first, then yaw about world +y: no roll.
        Orientation::YawPitch { yaw_deg, pitch_deg } => {
            DQuat::from_rotation_y(yaw_deg.to_radians())
                * DQuat::from_rotation_x(pitch_deg.to_radians())
        }
    }
}

/// Columns (right, up, −forward), or `None` when the direction is degenerate or `up` is
/// (nearly) parallel to it.
fn look_at_basis(position: DVec3, look_at: DVec3, up: DVec3) -> Option<DMat3> {
    let forward = (look_at - position).try_normalize()?;
    let right = forward.cross(up.try_normalize()?);
    // sin of the angle between up and forward; below 1e-6 the roll is numerically meaningless.
    if right.length() < 1e-6 {
        return None;
    }
    let right = right.normalize();
    Some(DMat3::from_cols(right, right.cross(forward), -forward))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn key(time: f64, position: [f64; 3], orientation: Orientation) -> Keyframe {
        Keyframe {
            time,
            position: DVec3::from(position),
            orientation,
            fov_deg: None,
        }
    }

    fn look(at: [f64; 3]) -> Orientation {
        Orientation::LookAt {
            look_at: DVec3::from(at),
            up: DVec3::Y,
        }
    }

    fn yaw_pitch(yaw_deg: f64, pitch_deg: f64) -> Orientation {
        Orientation::YawPitch { yaw_deg, pitch_deg }
    }

    /// Uneven spacing *and* uneven timing, with turns: the case where a naive time mapping
    /// breaks C1.
    fn wiggly_path() -> CameraPath {
        let pts = [
            (0.0, [0.0, 1.6, 4.0]),
            (0.7, [1.0, 1.7, 3.5]),
            (3.0, [4.0, 1.5, 0.0]),
            (3.4, [4.2, 1.5, -0.5]),
            (6.0, [0.0, 2.0, -3.0]),
            (9.5, [-3.0, 1.6, 1.0]),
        ];
        let keyframes = pts
            .iter()
            .map(|&(t, p)| key(t, p, look([0.0, 1.0, 0.0])))
            .collect();
        CameraPath {
            fps: 24.0,
            keyframes,
        }
    }

    fn assert_close(a: DVec3, b: DVec3, tol: f64, what: &str) {
        assert!(
            (a - b).length() <= tol,
            "{what}: {a} vs {b} (|Δ| = {:e})",
            (a - b).length()
        );
    }

    /// One-sided second-order derivative estimates at t, from the left and from the right.
    fn one_sided_velocities(path: &CameraPath, t: f64, h: f64) -> (DVec3, DVec3) {
        let p = |t: f64| path.sample(t).position;
        let left = (3.0 * p(t) - 4.0 * p(t - h) + p(t - 2.0 * h)) / (2.0 * h);
        let right = (-3.0 * p(t) + 4.0 * p(t + h) - p(t + 2.0 * h)) / (2.0 * h);
        (left, right)
    }

    #[test]
    fn passes_through_every_keyframe_exactly() {
        let mut path = wiggly_path();
        path.keyframes[3].orientation = yaw_pitch(200.0, -20.0);
        path.validate().unwrap();
        for (i, k) in path.keyframes.iter().enumerate() {
            let pose = path.sample(k.time);
            assert_eq!(pose.position, k.position, "keyframe {i}");
            let expected = match k.orientation {
                Orientation::LookAt { look_at, up } => {
                    look_at_basis(k.position, look_at, up).unwrap()
                }
                Orientation::YawPitch { yaw_deg, pitch_deg } => {
                    let (y, p) = (yaw_deg.to_radians(), pitch_deg.to_radians());
                    let forward = DVec3::new(-y.sin() * p.cos(), p.sin(), -y.cos() * p.cos());
                    let right = DVec3::new(y.cos(), 0.0, -y.sin());
                    DMat3::from_cols(right, right.cross(forward), -forward)
                }
            };
            assert_close(pose.forward, -expected.z_axis, 1e-12, "forward");
            assert_close(pose.up, expected.y_axis, 1e-12, "up");
        }
    }

    #[test]
    fn pose_basis_is_orthonormal_everywhere() {
        let path = wiggly_path();
        for n in 0..=1000 {
            let pose = path.sample(-1.0 + 12.0 * n as f64 / 1000.0);
            assert!((pose.forward.length() - 1.0).abs() < 1e-12);
            assert!((pose.up.length() - 1.0).abs() < 1e-12);
            assert!(pose.forward.dot(pose.up).abs() < 1e-12);
            assert!(pose.position.is_finite());
        }
    }

    #[test]
    fn position_is_c1_in_time_at_every_interior_keyframe() {
        let path = wiggly_path();
        let keys = &path.keyframes;
        for (i, k) in keys.iter().enumerate().take(keys.len() - 1).skip(1) {
            let (left, right) = one_sided_velocities(&path, k.time, 1e-4);
            let scale = left.length().max(right.length());
            assert!(
                scale > 0.1,
                "keyframe {i} should be passed at speed, got {scale}"
            );
            assert_close(
                left,
                right,
                1e-4 * scale,
                &format!("velocity at keyframe {i}"),
            );
        }
    }

    /// Why the module does not map each segment's knot interval linearly onto its time
    /// interval: on the same path that shortcut changes velocity abruptly at keyframes.
    #[test]
    fn naive_time_mapping_would_not_be_c1() {
        let path = wiggly_path();
        let keys = &path.keyframes;
        let naive = |i: usize, t: f64| {
            let h = path.knot_interval(i as isize);
            path.curve(
                i,
                (t - keys[i].time) / (keys[i + 1].time - keys[i].time) * h,
            )
        };
        let (i, e) = (2, 1e-6);
        let t = keys[i].time;
        let left = (naive(i - 1, t) - naive(i - 1, t - e)) / e;
        let right = (naive(i, t + e) - naive(i, t)) / e;
        let jump = (left - right).length() / left.length().max(right.length());
        // Here the speed changes by about half (0.49) at the keyframe.
        assert!(jump > 0.3, "relative velocity jump {jump}");
    }

    /// With keyframe times proportional to the centripetal knots, τ(t) is linear and the path
    /// is the textbook centripetal Catmull-Rom spline, segment by segment.
    #[test]
    fn knot_proportional_timing_reproduces_the_classic_spline() {
        let mut path = wiggly_path();
        let mut t = 0.0;
        for i in 0..path.keyframes.len() {
            path.keyframes[i].time = t;
            if i + 1 < path.keyframes.len() {
                t += 0.8 * path.knot_interval(i as isize);
            }
        }
        let keys = &path.keyframes;
        for i in 0..keys.len() - 1 {
            for n in 0..=20 {
                let s = n as f64 / 20.0;
                let classic = path.curve(i, s * path.knot_interval(i as isize));
                let t = keys[i].time + s * (keys[i + 1].time - keys[i].time);
                assert_close(
                    path.sample(t).position,
                    classic,
                    1e-12,
                    &format!("segment {i} s {s}"),
                );
            }
        }
    }

    /// Random paths: finite everywhere, C1 at every keyframe, and progress along the curve never
    /// reverses (τ(t) is non-decreasing on every segment and ends on its knot).
    #[test]
    fn property_random_paths_are_c1_and_finite() {
        let mut state = 7u64;
        let mut rand = move || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 11) as f64 / (1u64 << 53) as f64
        };
        for _ in 0..200 {
            let n = 2 + (rand() * 7.0) as usize;
            let mut t = rand();
            let mut keyframes = Vec::new();
            for _ in 0..n {
                let p = [rand() * 10.0 - 5.0, rand() * 3.0, rand() * 10.0 - 5.0];
                keyframes.push(key(
                    t,
                    p,
                    yaw_pitch(rand() * 720.0 - 360.0, rand() * 180.0 - 90.0),
                ));
                t += 0.05 + rand() * 3.0;
            }
            let path = CameraPath {
                fps: 24.0,
                keyframes,
            };
            path.validate().unwrap();
            let keys = &path.keyframes;
            for k in keys.iter().take(n - 1).skip(1) {
                let (left, right) = one_sided_velocities(&path, k.time, 1e-5);
                let scale = left.length().max(right.length()).max(1e-3);
                assert_close(
                    left,
                    right,
                    1e-3 * scale,
                    &format!("velocity at t = {}", k.time),
                );
            }
            for i in 0..n - 1 {
                let (ta, tb) = (keys[i].time, keys[i + 1].time);
                let h = path.knot_interval(i as isize);
                let mut before = 0.0;
                for m in 0..=200 {
                    let u = path.knot_progress(i, ta + (tb - ta) * m as f64 / 200.0);
                    assert!(
                        u >= before - 1e-12 * h,
                        "segment {i}: τ went back from {before} to {u}"
                    );
                    before = u;
                }
                assert!(
                    (before - h).abs() <= 1e-12 * h.max(1.0),
                    "segment {i} ends at its knot"
                );
            }
            let (t0, t1) = (keys[0].time, keys[n - 1].time);
            for m in 0..=500 {
                let pose = path.sample(t0 + (t1 - t0) * m as f64 / 500.0);
                assert!(
                    pose.position.is_finite() && pose.forward.is_finite() && pose.up.is_finite()
                );
            }
        }
    }

    #[test]
    fn straight_line_with_uniform_timing_has_uniform_speed() {
        let keyframes = (0..5)
            .map(|i| {
                key(
                    i as f64 * 2.0,
                    [i as f64 * 3.0, 1.0, -(i as f64) * 4.0],
                    yaw_pitch(0.0, 0.0),
                )
            })
            .collect();
        let path = CameraPath {
            fps: 30.0,
            keyframes,
        };
        let speed = 5.0 / 2.0; // |(3, 0, −4)| per 2 s
        for n in 0..=800 {
            let t = 8.0 * n as f64 / 800.0;
            let expected = DVec3::new(1.5 * t, 1.0, -2.0 * t);
            assert_close(
                path.sample(t).position,
                expected,
                1e-12,
                &format!("t = {t}"),
            );
        }
        let (left, right) = one_sided_velocities(&path, 3.1, 1e-3);
        assert!((left.length() - speed).abs() < 1e-9 && (right.length() - speed).abs() < 1e-9);
    }

    #[test]
    fn duplicate_positions_pause_without_nan() {
        let o = look([0.0, 0.0, -10.0]);
        let keyframes = vec![
            key(0.0, [0.0, 0.0, 0.0], o),
            key(1.0, [0.0, 0.0, 0.0], o), // repeated start: zero knot interval at the phantom side
            key(2.0, [2.0, 0.0, 0.0], o),
            key(3.0, [2.0, 0.0, 0.0], o), // the camera waits here…
            key(4.0, [2.0, 0.0, 0.0], o),
            key(5.0, [3.0, 1.0, 0.0], o),
        ];
        let path = CameraPath {
            fps: 24.0,
            keyframes,
        };
        path.validate().unwrap();
        for n in 0..=5000 {
            let t = 5.0 * n as f64 / 5000.0;
            let pose = path.sample(t);
            assert!(
                pose.position.is_finite() && pose.forward.is_finite(),
                "t = {t}"
            );
            if (3.0..=4.0).contains(&t) {
                assert_eq!(pose.position, DVec3::new(2.0, 0.0, 0.0), "t = {t}");
            }
            if t <= 1.0 {
                assert_eq!(pose.position, DVec3::ZERO, "t = {t}");
            }
        }
        // …and arrives and leaves at zero velocity, so velocity is continuous there too. It must
        // already be at rest at t = 2, where it reaches the position it then holds.
        for t in [1.0, 2.0, 3.0, 4.0] {
            let (left, right) = one_sided_velocities(&path, t, 1e-5);
            assert!(
                left.length() < 1e-6 && right.length() < 1e-6,
                "t = {t}: {left} {right}"
            );
        }
        let (left, right) = one_sided_velocities(&path, 1.5, 1e-4);
        assert!(left.length() > 0.5, "it does move between the pauses");
        assert_close(left, right, 1e-6, "velocity inside a segment");
    }

    #[test]
    fn yaw_pitch_conventions() {
        let forward = |yaw, pitch| {
            let path = CameraPath {
                fps: 1.0,
                keyframes: vec![key(0.0, [0.0; 3], yaw_pitch(yaw, pitch))],
            };
            path.sample(0.0)
        };
        assert_close(forward(0.0, 0.0).forward, DVec3::NEG_Z, 1e-15, "yaw 0");
        assert_close(forward(90.0, 0.0).forward, DVec3::NEG_X, 1e-15, "yaw 90");
        assert_close(forward(180.0, 0.0).forward, DVec3::Z, 1e-15, "yaw 180");
        assert_close(forward(-90.0, 0.0).forward, DVec3::X, 1e-15, "yaw -90");
        let up30 = forward(0.0, 30.0);
        assert_close(
            up30.forward,
            DVec3::new(0.0, 0.5, -(0.75f64).sqrt()),
            1e-15,
            "pitch 30",
        );
        assert!(
            up30.up.y > 0.0 && up30.up.z > 0.0,
            "tilting up tips `up` backwards (+z, behind a camera facing −z): {}",
            up30.up
        );
        // No roll: the right axis stays horizontal, and is +x for yaw 0 (right-handed).
        let p = forward(37.0, -62.0);
        assert!(p.right().y.abs() < 1e-15);
        assert_close(forward(0.0, 0.0).right(), DVec3::X, 1e-15, "right");
        assert_close(forward(0.0, 90.0).forward, DVec3::Y, 1e-15, "straight up");
        // A yaw/pitch keyframe and the equivalent look_at agree.
        let path = CameraPath {
            fps: 1.0,
            keyframes: vec![key(0.0, [1.0, 2.0, 3.0], look([-4.0, 2.0, 3.0]))],
        };
        assert_close(
            path.sample(0.0).forward,
            forward(90.0, 0.0).forward,
            1e-15,
            "look_at −x",
        );
        assert_close(path.sample(0.0).up, DVec3::Y, 1e-15, "look_at up");
    }

    #[test]
    fn slerp_takes_the_short_way() {
        // Yaw 0 and yaw 360 are the same rotation but opposite quaternions (q and −q).
        let path = CameraPath {
            fps: 10.0,
            keyframes: vec![
                key(0.0, [0.0; 3], yaw_pitch(0.0, 0.0)),
                key(1.0, [0.0; 3], yaw_pitch(360.0, 0.0)),
            ],
        };
        assert!(
            orientation_quat(&path.keyframes[0]).dot(orientation_quat(&path.keyframes[1])) < -0.999
        );
        for n in 0..=100 {
            let pose = path.sample(n as f64 / 100.0);
            assert_close(pose.forward, DVec3::NEG_Z, 1e-12, "no spin");
        }
        // 0° → 350° turns 10° clockwise, not 350° counter-clockwise.
        let path = CameraPath {
            fps: 10.0,
            keyframes: vec![
                key(0.0, [0.0; 3], yaw_pitch(0.0, 0.0)),
                key(1.0, [0.0; 3], yaw_pitch(350.0, 0.0)),
            ],
        };
        let half = (-5.0f64).to_radians();
        assert_close(
            path.sample(0.5).forward,
            DVec3::new(-half.sin(), 0.0, -half.cos()),
            1e-12,
            "mid",
        );
    }

    #[test]
    fn orientation_is_slerp_in_time() {
        let path = CameraPath {
            fps: 10.0,
            keyframes: vec![
                key(1.0, [0.0; 3], yaw_pitch(0.0, 0.0)),
                key(3.0, [5.0, 0.0, 0.0], yaw_pitch(90.0, 0.0)),
            ],
        };
        for n in 0..=10 {
            let s = n as f64 / 10.0;
            let a = (90.0 * s).to_radians();
            let pose = path.sample(1.0 + 2.0 * s);
            assert_close(
                pose.forward,
                DVec3::new(-a.sin(), 0.0, -a.cos()),
                1e-12,
                "constant angular speed",
            );
        }
    }

    #[test]
    fn fov_is_linear_and_optional() {
        let mut path = wiggly_path();
        assert_eq!(path.sample(1.0).fov_deg, None);
        for (i, k) in path.keyframes.iter_mut().enumerate() {
            k.fov_deg = Some(30.0 + 10.0 * i as f64);
        }
        assert!((path.sample(0.35).fov_deg.unwrap() - 35.0).abs() < 1e-12);
        assert_eq!(path.sample(3.0).fov_deg, Some(50.0));
        assert_eq!(path.sample(100.0).fov_deg, Some(80.0));
    }

    #[test]
    fn clamps_outside_the_keyframe_range_and_single_keyframe_is_static() {
        let path = wiggly_path();
        assert_eq!(path.sample(-5.0), path.sample(0.0));
        assert_eq!(path.sample(f64::NAN), path.sample(0.0));
        assert_eq!(path.sample(1e9), path.sample(9.5));
        let still = CameraPath {
            fps: 24.0,
            keyframes: vec![key(2.0, [1.0, 2.0, 3.0], look([0.0; 3]))],
        };
        assert_eq!(still.frame_count(), 1);
        assert_eq!(still.sample(0.0), still.sample(7.0));
        assert_eq!(still.sample(7.0).position, DVec3::new(1.0, 2.0, 3.0));
    }

    #[test]
    fn frame_count_and_times() {
        let path = |t0: f64, t1: f64, fps: f64| CameraPath {
            fps,
            keyframes: vec![
                key(t0, [0.0; 3], yaw_pitch(0.0, 0.0)),
                key(t1, [1.0, 0.0, 0.0], yaw_pitch(0.0, 0.0)),
            ],
        };
        assert_eq!(path(0.0, 10.0, 24.0).frame_count(), 241);
        assert_eq!(path(0.0, 1.01, 24.0).frame_count(), 25);
        assert_eq!(
            path(0.0, 2.3, 10.0).frame_count(),
            24,
            "2.3 s × 10 fps rounds to 22.999…"
        );
        assert_eq!(path(1.5, 2.5, 25.0).frame_count(), 26);
        let p = path(1.5, 2.5, 25.0);
        assert_eq!(p.frame_time(0), 1.5);
        assert!((p.frame_time(25) - 2.5).abs() < 1e-15);
        assert_eq!(
            CameraPath {
                fps: 24.0,
                keyframes: vec![]
            }
            .frame_count(),
            0
        );
        let ntsc = path(0.0, 10.0, 24000.0 / 1001.0);
        assert_eq!(ntsc.frame_count(), 240); // 239.76 frames fit, plus frame 0
    }

    #[test]
    fn validation_reports_every_problem() {
        let keyframes = vec![
            Keyframe {
                fov_deg: Some(180.0),
                ..key(0.0, [0.0; 3], look([0.0; 3]))
            },
            key(
                0.0,
                [0.0; 3],
                Orientation::LookAt {
                    look_at: DVec3::new(0.0, 5.0, 0.0),
                    up: DVec3::Y,
                },
            ),
            key(f64::NAN, [0.0, f64::INFINITY, 0.0], yaw_pitch(0.0, 95.0)),
            Keyframe {
                fov_deg: Some(0.0),
                ..key(-1.0, [0.0; 3], look([1.0, 0.0, 0.0]))
            },
        ];
        let path = CameraPath {
            fps: 0.0,
            keyframes,
        };
        let problems: Vec<String> = path
            .validate()
            .unwrap_err()
            .iter()
            .map(|p| p.to_string())
            .collect();
        let expected = [
            "camera_path: fps must be a positive number, got 0",
            "camera_path: fov_deg is given on 2 of 4 keyframes; give it on all or none (a missing one would have to blend with the scene camera's)",
            "camera_path.keyframes[0]: look_at [0, 0, 0] equals the position",
            "camera_path.keyframes[0]: fov_deg 180 is outside (0, 180)",
            "camera_path.keyframes[1]: time 0 s must be after the previous keyframe's 0 s",
            "camera_path.keyframes[1]: up [0, 1, 0] is parallel to the view direction",
            "camera_path.keyframes[2]: time must be finite, got NaN",
            "camera_path.keyframes[2]: position [0, inf, 0] is not finite",
            "camera_path.keyframes[2]: pitch_deg 95 is outside [-90, 90]",
            "camera_path.keyframes[3]: fov_deg 0 is outside (0, 180)",
        ];
        assert_eq!(problems, expected);
        let empty = CameraPath {
            fps: f64::NAN,
            keyframes: vec![],
        };
        let problems: Vec<String> = empty
            .validate()
            .unwrap_err()
            .iter()
            .map(|p| p.to_string())
            .collect();
        assert_eq!(
            problems,
            [
                "camera_path: fps must be a positive number, got NaN",
                "camera_path: needs at least 1 keyframe"
            ]
        );
        assert!(wiggly_path().validate().is_ok());
    }

    #[derive(Debug, Deserialize)]
    struct Doc {
        camera_path: CameraPath,
    }

    fn parse(toml_src: &str) -> Result<CameraPath, String> {
        toml::from_str::<Doc>(toml_src)
            .map(|d| d.camera_path)
            .map_err(|e| e.to_string())
    }

    #[test]
    fn toml_forms() {
        let path = parse(
            "[camera_path]\nfps = 24\n\
             [[camera_path.keyframes]]\ntime = 0\nposition = [0, 1.6, 4]\nlook_at = [0, 1.2, 0]\nup = [0, 0, -1]\n\
             [[camera_path.keyframes]]\ntime = 1\nposition = [0, 1.6, 4]\nyaw_deg = 180\n",
        )
        .unwrap();
        assert_eq!(path.fps, 24.0);
        assert_eq!(
            path.keyframes[0].orientation,
            Orientation::LookAt {
                look_at: DVec3::new(0.0, 1.2, 0.0),
                up: DVec3::NEG_Z
            }
        );
        assert_eq!(path.keyframes[1].orientation, yaw_pitch(180.0, 0.0));
        assert_eq!(path.keyframes[1].fov_deg, None);
    }

    #[test]
    fn toml_errors_are_specific() {
        let head =
            "[camera_path]\nfps = 24\n[[camera_path.keyframes]]\ntime = 0\nposition = [0, 0, 0]\n";
        let cases = [
            (
                "look_at = [0, 0, -1]\nyaw_deg = 3\n",
                "give either `look_at` or `yaw_deg`/`pitch_deg`, not both",
            ),
            ("look_at = [0, 0, -1]\npitch_deg = 3\n", "not both"),
            (
                "yaw_deg = 3\nup = [0, 1, 0]\n",
                "`up` only applies with `look_at`",
            ),
            ("pitch_deg = 3\n", "`pitch_deg` needs `yaw_deg`"),
            ("fov_deg = 3\n", "a keyframe needs `look_at` or `yaw_deg`"),
            (
                "look_at = [0, 0, -1]\nlookat = 1\n",
                "unknown field `lookat`",
            ),
        ];
        for (rest, needle) in cases {
            let err = parse(&format!("{head}{rest}")).unwrap_err();
            assert!(err.contains(needle), "{rest:?} gave:\n{err}");
        }
        let err = parse("[camera_path]\nfps = 24\nkeyframes = []\nspeed = 2\n").unwrap_err();
        assert!(err.contains("unknown field `speed`"), "{err}");
    }
}
