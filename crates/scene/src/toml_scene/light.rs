//! `[[lights]]`: point, spot (optionally carrying a `texture` across its beam, oriented by
//! `up`) and sun (directional) lights.
use super::Ctx;
use super::TextureKind;
use super::format::LightDef;
use crate::{Light, Rgb, TextureId};
use glam::{DMat3, Mat3, Vec3};
use toml::Spanned;

impl Ctx<'_> {
    pub(super) fn light(&mut self, l: &Spanned<LightDef>) -> Option<Light> {
        let d = l.get_ref();
        let at = l.span().start;
        let kind = d.kind.get_ref().as_str();
        if kind != "spot" {
            if let Some(t) = &d.texture {
                self.error(
                    t.span().start,
                    format!("{kind} light: key `texture` applies to a spot only"),
                );
            }
            if let Some(v) = &d.up {
                self.error(
                    v.span().start,
                    format!("{kind} light: key `up` applies to a spot with a `texture` only"),
                );
            }
        }
        if kind == "sun" {
            return self.sun(d, at);
        }
        if let Some(v) = &d.irradiance {
            self.error(
                v.span().start,
                format!("{kind} light: key `irradiance` applies to a sun only (use `intensity`)"),
            );
        }
        let Some(pos) = &d.position else {
            self.error(at, format!("{kind} light needs a `position`"));
            return None;
        };
        let position = self.vec3(pos, "light position");
        let Some(i) = &d.intensity else {
            self.error(at, format!("{kind} light needs an `intensity`"));
            return None;
        };
        let intensity = self.colour(i, "light intensity");
        match kind {
            "point" => {
                for (key, v) in [("look_at", &d.look_at), ("direction", &d.direction)] {
                    if let Some(v) = v {
                        self.error(
                            v.span().start,
                            format!("point light: key `{key}` does not apply"),
                        );
                    }
                }
                Some(Light::Point {
                    position,
                    intensity,
                })
            }
            "spot" => self.spot(d, at, position, intensity),
            other => {
                self.error(d.kind.span().start, format!("unknown light type \"{other}\" (expected point, spot or sun; area lights are emissive materials, the environment is [environment])"));
                None
            }
        }
    }

    /// A spot: `look_at` or `direction`, `cone_deg`, `falloff_deg`, and optionally a
    /// `texture` oriented by `up`.
    fn spot(&mut self, d: &LightDef, at: usize, position: Vec3, intensity: Rgb) -> Option<Light> {
        let direction = match (&d.look_at, &d.direction) {
            (Some(t), None) => self.vec3(t, "look_at") - position,
            (None, Some(v)) => self.vec3(v, "direction"),
            _ => {
                self.error(
                    at,
                    "spot light needs exactly one of `look_at` or `direction`",
                );
                return None;
            }
        };
        if direction.length() < 1e-9 {
            self.error(at, "spot light direction is zero");
            return None;
        }
        let cone = d
            .cone_deg
            .as_ref()
            .map_or(20.0, |c| self.positive(c, "cone_deg"));
        let falloff = d
            .falloff_deg
            .as_ref()
            .map_or(cone * 0.75, |c| self.positive(c, "falloff_deg"));
        if cone > 90.0 {
            self.error(at, format!("spot cone_deg {cone} must be at most 90"));
        }
        if falloff > cone {
            self.error(
                at,
                format!("spot falloff_deg {falloff} exceeds cone_deg {cone}"),
            );
        }
        let beam = direction;
        let direction = direction.normalize();
        let Some(t) = &d.texture else {
            if let Some(v) = &d.up {
                self.error(
                    v.span().start,
                    "spot light: key `up` orients a `texture` and does nothing without one",
                );
            }
            return Some(Light::Spot {
                position,
                direction,
                intensity,
                cone_deg: cone,
                falloff_deg: falloff,
            });
        };
        let texture = self.beam_texture(t)?;
        let frame = self.beam_frame(d, beam, at)?;
        Some(Light::TexturedSpot {
            position,
            frame,
            intensity,
            cone_deg: cone,
            falloff_deg: falloff,
            texture,
        })
    }

    /// A spot's `texture`: any but vertex colours (a beam has no surface to read them on).
    fn beam_texture(&mut self, t: &Spanned<String>) -> Option<TextureId> {
        let id = self.texture_ref("spot light", "texture", t)?;
        if self.texture_kind(id) == TextureKind::VertexColor {
            self.error(
                t.span().start,
                format!("spot light: `texture` \"{}\" is a vertex_color texture, which a light cannot use (use a bitmap or checkerboard)", t.get_ref()),
            );
            return None;
        }
        Some(id)
    }

    /// The frame of a textured spot, as Mitsuba's `<lookat>` builds it: z along the beam
    /// (`direction`, normalised here), x = `up` × z normalised (`up` default +y), y = z × x.
    fn beam_frame(&mut self, d: &LightDef, direction: Vec3, at: usize) -> Option<Mat3> {
        let up = d.up.as_ref().map_or(Vec3::Y, |u| self.vec3(u, "spot up"));
        let z = direction.as_dvec3().normalize();
        let x = up.as_dvec3().cross(z);
        if x.length() < 1e-9 {
            let at = d.up.as_ref().map_or(at, |u| u.span().start);
            self.error(
                at,
                "spot light: `up` is parallel to the beam (or zero); give an `up` across it to orient the texture",
            );
            return None;
        }
        let x = x.normalize();
        Some(DMat3::from_cols(x, z.cross(x), z).as_mat3())
    }

    /// A directional light: `direction` (the way the light travels) and `irradiance`.
    fn sun(&mut self, d: &LightDef, at: usize) -> Option<Light> {
        for (key, v) in [
            ("position", &d.position),
            ("look_at", &d.look_at),
            ("intensity", &d.intensity),
        ] {
            if let Some(v) = v {
                self.error(
                    v.span().start,
                    format!("sun light: key `{key}` does not apply (a sun has `direction` and `irradiance`)"),
                );
            }
        }
        for (key, v) in [("cone_deg", &d.cone_deg), ("falloff_deg", &d.falloff_deg)] {
            if let Some(v) = v {
                self.error(
                    v.span().start,
                    format!("sun light: key `{key}` does not apply"),
                );
            }
        }
        let (Some(dir), Some(e)) = (&d.direction, &d.irradiance) else {
            self.error(at, "sun light needs a `direction` and an `irradiance`");
            return None;
        };
        let direction = self.vec3(dir, "sun direction");
        let irradiance = self.colour(e, "sun irradiance");
        if direction.length() < 1e-9 {
            self.error(dir.span().start, "sun direction is zero");
            return None;
        }
        Some(Light::Directional {
            direction: direction.normalize(),
            irradiance,
        })
    }
}
