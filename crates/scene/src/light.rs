//! Delta lights. Area lights are emissive materials on shapes; the constant environment is
//! `[environment] radiance = [r, g, b]`.
//!
//! ```toml
//! [[lights]]
//! type = "point"
//! position = [0.0, 2.0, 0.0]
//! intensity = [10.0, 10.0, 10.0]     # radiant intensity (W/sr in linear sRGB)
//!
//! [[lights]]
//! type = "spot"
//! position = [0.0, 2.0, 0.0]
//! look_at = [0.0, 0.0, 0.0]
//! intensity = [50.0, 5.0, 5.0]
//! cone_deg = 25.0                    # half-angle where the light reaches zero (Mitsuba `cutoff_angle`)
//! falloff_deg = 18.0                 # half-angle of full intensity (Mitsuba `beam_width`); default 3/4 of cone_deg
//! ```
use crate::Rgb;
use glam::Vec3;

#[derive(Clone, Debug, PartialEq)]
pub enum Light {
    Point {
        position: Vec3,
        intensity: Rgb,
    },
    /// Intensity is full inside `falloff_deg`, falls linearly in angle to zero at `cone_deg`
    /// (the profile of Mitsuba 3's `spot`).
    Spot {
        position: Vec3,
        direction: Vec3,
        intensity: Rgb,
        cone_deg: f32,
        falloff_deg: f32,
    },
}
