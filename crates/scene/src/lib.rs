//! Scene description: plain data loaded from TOML (and OBJ), with validation that reports every
//! problem at once. A [`CameraPath`] is a list of [`Keyframe`]s that [`CameraPath::sample`]
//! turns into a [`CameraPose`] at any frame time.

mod camera_path;

pub use camera_path::{CameraPath, CameraPose, Keyframe, Orientation, PathProblem};
