//! Environment maps: radiance arriving from infinitely far away, looked up by direction in a
//! latitude–longitude image (Mitsuba 3's `envmap`). A constant environment is
//! [`crate::Scene::environment`]; a map is [`crate::Scene::environment_map`].
//!
//! ```toml
//! [environment]
//! map = "sky.exr"                                  # lat-long image, twice as wide as tall
//! scale = 1.0                                      # radiance multiplier (default 1)
//! transform = { rotate = [0.0, 1.0, 0.0, 90.0] }   # rotations only
//! ```
//!
//! The mapping is Mitsuba's: in the map's own frame (world = `to_world` · map), a direction
//! `d` reads the image at u = atan2(d.x, −d.z) / 2π (wrapped into [0, 1)), v = acos(d.y) / π,
//! so the top row is +y, the image's left edge (u = 0) looks along −z and its centre along +z;
//! the lookup is bilinear between texel centres along u (wrapping around) and between rows
//! along v, row 0 lying on the +y pole and the last row on the −y pole.
use crate::Image;
use glam::Mat3;
use std::path::PathBuf;
use std::sync::Arc;

/// A lat-long environment map.
#[derive(Clone, Debug, PartialEq)]
pub struct EnvironmentMap {
    /// The file it was decoded from (messages, fingerprints).
    pub filename: PathBuf,
    /// Linear RGB radiance texels, row 0 the top (+y) row.
    pub image: Arc<Image>,
    /// Multiplies every texel.
    pub scale: f32,
    /// Rotation from the map's frame to the world.
    pub to_world: Mat3,
}

/// Why `image` cannot be a lat-long map, if it cannot: it must be twice as wide as tall.
pub fn check_lat_long(image: &Image) -> Result<(), String> {
    if image.width == 2 * image.height && image.height >= 1 {
        Ok(())
    } else {
        Err(format!(
            "is {}×{}: a latitude–longitude environment map is twice as wide as it is tall",
            image.width, image.height
        ))
    }
}

/// Why the linear part `m` cannot be an environment map's `to_world`, if it cannot: it must
/// be a rotation (a uniform scale is divided out and allowed; a mirror or shear is not).
pub fn rotation_part(m: Mat3) -> Result<Mat3, String> {
    let s = libm::cbrtf(m.determinant().abs());
    if !(s.is_finite() && s > 0.0) {
        return Err("collapses directions (its determinant is 0)".into());
    }
    let r = m * (1.0 / s);
    let err = (r.transpose() * r - Mat3::IDENTITY).abs().to_cols_array();
    if err.iter().any(|e| *e > 1e-3) || r.determinant() < 0.0 {
        return Err("is not a rotation (environment maps can only be rotated)".into());
    }
    Ok(r)
}
