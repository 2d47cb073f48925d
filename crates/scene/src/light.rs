//! Delta lights. Area lights are emissive materials on shapes; the environment (constant or a
//! map) is `[environment]`.
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
//!
//! [[lights]]
//! type = "sun"                       # a directional light (Mitsuba `directional`)
//! direction = [-0.3, -1.0, 0.2]      # the way the light travels
//! irradiance = [3.0, 2.9, 2.7]       # on a surface facing the sun (W/m² in linear sRGB)
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
    /// Parallel light from infinitely far away, travelling along `direction` (unit).
    Directional {
        direction: Vec3,
        irradiance: Rgb,
    },
}
