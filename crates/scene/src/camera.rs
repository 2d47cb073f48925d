//! The camera: a pinhole in TOML scenes; Mitsuba scenes may also give a thin lens or an
//! orthographic view ([`Projection`]).
//!
//! ```toml
//! [camera]
//! position = [278.0, 273.0, -800.0]
//! look_at = [278.0, 273.0, 0.0]
//! up = [0.0, 1.0, 0.0]        # default
//! fov_deg = 39.3              # vertical field of view in degrees
//! width = 256
//! height = 256
//! ```
use glam::Vec3;

/// How camera rays leave the camera.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub enum Projection {
    /// Every ray starts at the camera's position (field of view `fov_deg`).
    #[default]
    Pinhole,
    /// Rays start on a disc of `aperture_radius` around the position, across the view, and
    /// meet the pinhole's ray of their pixel at `focus_distance` along the view (Mitsuba's
    /// `thinlens`); the field of view is the pinhole's.
    ThinLens {
        aperture_radius: f32,
        focus_distance: f32,
    },
    /// Parallel rays along the view, from a rectangle of these half-extents (scene units)
    /// centred on the position (Mitsuba's `orthographic`); `fov_deg` is not used for them.
    Orthographic { half_width: f32, half_height: f32 },
    /// A pinhole (`aperture_radius` 0) or thin lens whose image is shifted in its plane
    /// (Mitsuba's `principal_point_offset_x`/`_y`, in fractions of the image's width and
    /// height): pixel (x, y) looks where pixel (x + shift_x·width, y + shift_y·height) of the
    /// centred view would.
    Shifted {
        shift_x: f32,
        shift_y: f32,
        aperture_radius: f32,
        focus_distance: f32,
    },
}

/// A camera looking from `position` towards `look_at`.
#[derive(Clone, Debug, PartialEq)]
pub struct Camera {
    pub position: Vec3,
    pub look_at: Vec3,
    pub up: Vec3,
    /// Vertical field of view in degrees, in (0, 180).
    pub fov_deg: f32,
    pub width: u32,
    pub height: u32,
    pub projection: Projection,
}

impl Camera {
    /// Unit gaze direction (the eye sensor's pole).
    pub fn forward(&self) -> Vec3 {
        (self.look_at - self.position).normalize()
    }

    /// Orthonormal (right, up, forward) basis; right-handed with +y up by default.
    pub fn basis(&self) -> (Vec3, Vec3, Vec3) {
        let f = self.forward();
        let r = f.cross(self.up).normalize();
        let u = r.cross(f);
        (r, u, f)
    }
}
