//! The emitters that shine a beam from a point: `spot` (optionally carrying a `texture`
//! across its cone) and `projector` (an image, or a constant, thrown through a frustum).
use super::Builder;
use crate::mitsuba::xml::Obj;
use crate::{Light, Param, Rgb, Texture};
use glam::{DMat3, DMat4, DVec3};

impl<'t> Builder<'t> {
    /// `<emitter type="spot">`: `to_world` (the beam along its +z), `intensity` (1),
    /// `cutoff_angle` (20), `beam_width` (¾ of the cutoff) and an optional `texture`.
    pub(super) fn spot(&mut self, o: &'t Obj) {
        let m = self.transform(o, "to_world").unwrap_or(DMat4::IDENTITY);
        let intensity = self.colour(o, "intensity").unwrap_or(Rgb::ONE);
        let cone = self.float_in(o, "cutoff_angle", 0.0..=90.0).unwrap_or(20.0);
        let falloff = self.float(o, "beam_width").unwrap_or(cone * 0.75);
        if !(falloff > 0.0 && falloff <= cone) {
            let at = self.prop(o, "beam_width").map_or(o.at, |p| p.at);
            self.error(
                at,
                format!(
                    "{}: beam_width {falloff} must be in (0, cutoff_angle {cone}]",
                    o.describe()
                ),
            );
        }
        if cone <= 0.0 {
            self.error(o.at, format!("{}: cutoff_angle must be > 0", o.describe()));
        }
        // As in Mitsuba, the texture must vary across the beam: a constant is refused.
        let texture = match self.colour_param(o, "texture") {
            None => None,
            Some(Param::Texture(t)) => Some(t),
            Some(Param::Const(_)) => {
                let at = self.prop(o, "texture").map_or(o.at, |p| p.at);
                self.error(
                    at,
                    format!(
                        "{}: `texture` must be a texture that varies across the beam (e.g. a bitmap), not a constant",
                        o.describe()
                    ),
                );
                None
            }
        };
        self.float(o, "sampling_weight");
        self.finish(o);
        let Some(frame) = self.beam_frame(o, m) else {
            return;
        };
        let position = m.transform_point3(DVec3::ZERO).as_vec3();
        let (cone_deg, falloff_deg) = (cone as f32, falloff as f32);
        self.scene.lights.push(match texture {
            None => Light::Spot {
                position,
                direction: frame.z_axis.normalize().as_vec3(),
                intensity,
                cone_deg,
                falloff_deg,
            },
            Some(texture) => Light::TexturedSpot {
                position,
                frame: frame.as_mat3(),
                intensity,
                cone_deg,
                falloff_deg,
                texture,
            },
        });
    }

    /// `<emitter type="projector">`: `irradiance` (1, or a texture), `scale` (1), `fov` /
    /// `fov_axis` or `focal_length` (as a perspective sensor's, on a film of the texture's
    /// aspect ratio) and `to_world` (the beam along its +z).
    pub(super) fn projector(&mut self, o: &'t Obj) {
        let m = self.transform(o, "to_world").unwrap_or(DMat4::IDENTITY);
        let irradiance = self
            .colour_param(o, "irradiance")
            .unwrap_or(Param::Const(Rgb::ONE));
        let scale = self.float(o, "scale").unwrap_or(1.0);
        if !(scale.is_finite() && scale >= 0.0 && scale as f32 <= crate::MAX_COLOUR) {
            let at = self.prop(o, "scale").map_or(o.at, |p| p.at);
            self.error(
                at,
                format!(
                    "{}: scale {scale} must be in [0, {:e}]",
                    o.describe(),
                    crate::MAX_COLOUR
                ),
            );
        }
        // Mitsuba's image plane has the texture's resolution (1 × 1 for a constant).
        let aspect = match irradiance {
            Param::Texture(t) => match self.scene.texture(t) {
                Texture::Bitmap(b) => b.image.width as f64 / b.image.height.max(1) as f64,
                _ => 1.0,
            },
            Param::Const(_) => 1.0,
        };
        let vertical = self.field_of_view(o, aspect);
        self.float(o, "sampling_weight");
        self.finish(o);
        let (Some(frame), Some(vertical)) = (self.beam_frame(o, m), vertical) else {
            return;
        };
        let tan_half_fov_x = libm::tan(vertical.to_radians() / 2.0) * aspect;
        self.scene.lights.push(Light::Projector {
            position: m.transform_point3(DVec3::ZERO).as_vec3(),
            frame: frame.as_mat3(),
            irradiance,
            scale: scale as f32,
            tan_half_fov_x: tan_half_fov_x as f32,
            aspect: aspect as f32,
        });
    }

    /// The linear part of a beam's `to_world`; an error when it collapses a direction.
    fn beam_frame(&mut self, o: &Obj, m: DMat4) -> Option<DMat3> {
        let frame = DMat3::from_mat4(m);
        if frame.determinant().abs() < 1e-18 || !frame.is_finite() {
            let at = self.prop(o, "to_world").map_or(o.at, |p| p.at);
            self.error(
                at,
                format!(
                    "{}: to_world collapses the light's frame (its linear part is singular)",
                    o.describe()
                ),
            );
            return None;
        }
        Some(frame)
    }
}
