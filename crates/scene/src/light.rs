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
//! texture = "slide"                  # optional: the beam carries an image ([`Light::TexturedSpot`])
//! up = [0.0, 0.0, 1.0]               # with a texture: where the image's bottom edge goes (default +y)
//!
//! [[lights]]
//! type = "sun"                       # a directional light (Mitsuba `directional`)
//! direction = [-0.3, -1.0, 0.2]      # the way the light travels
//! irradiance = [3.0, 2.9, 2.7]       # on a surface facing the sun (W/m² in linear sRGB)
//! ```
use crate::{Param, Rgb, TextureId};
use glam::{Mat3, Vec3};

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
    /// A spot whose beam carries an image (Mitsuba's `spot` with a `texture`): the profile of
    /// [`Light::Spot`] around the frame's +z, times `texture` at
    /// uv = ½ + ½·(x, y) / (z·tan cone_deg) of the direction (x, y, z) in the light's frame.
    TexturedSpot {
        position: Vec3,
        /// Columns: where the light's x, y and z (beam) axes point in the world
        /// (Mitsuba's `to_world`, linear part).
        frame: Mat3,
        intensity: Rgb,
        cone_deg: f32,
        falloff_deg: f32,
        texture: TextureId,
    },
    /// A slide projector (Mitsuba's `projector`): a point light whose intensity in direction
    /// d = (x, y, z) of its frame (z > 0, along the beam) is π·scale·E(uv)/cos³θ, with E =
    /// `irradiance` at uv = ½·(1 − x/(z·t), 1 − y·aspect/(z·t)), t = `tan_half_fov_x`, zero
    /// where uv leaves [0, 1]²: a plane one unit in front of it, facing it, receives
    /// π·scale·E(uv).
    Projector {
        position: Vec3,
        /// Columns: where the light's x, y and z (beam) axes point in the world.
        frame: Mat3,
        irradiance: Param<Rgb>,
        scale: f32,
        /// tan of half the horizontal field of view (> 0).
        tan_half_fov_x: f32,
        /// Width over height of the projected image (the texture's; 1 for a constant).
        aspect: f32,
    },
}
