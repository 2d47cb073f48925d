//! Emitter plugins outside shapes: point, spot and constant.
use super::Builder;
use crate::mitsuba::xml::Obj;
use crate::{Light, Rgb};
use glam::{DMat4, DVec3};

const EMITTERS: &str = "area (inside a shape), point, spot and constant";

impl<'t> Builder<'t> {
    pub(super) fn emitter(&mut self, o: &'t Obj) {
        match o.kind.as_str() {
            "point" => {
                let to_world = self.transform(o, "to_world");
                let position = self.point(o, "position");
                let position = match (position, to_world) {
                    (Some(_), Some(_)) => {
                        self.error(
                            o.at,
                            format!(
                                "{}: give either `position` or `to_world`, not both",
                                o.describe()
                            ),
                        );
                        DVec3::ZERO
                    }
                    (Some(p), None) => p,
                    (None, Some(m)) => m.transform_point3(DVec3::ZERO),
                    (None, None) => DVec3::ZERO,
                };
                let intensity = self.colour(o, "intensity").unwrap_or(Rgb::ONE);
                self.float(o, "sampling_weight");
                self.finish(o);
                self.scene.lights.push(Light::Point {
                    position: position.as_vec3(),
                    intensity,
                });
            }
            "spot" => {
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
                self.float(o, "sampling_weight");
                self.finish(o);
                let direction = m.transform_vector3(DVec3::Z);
                if direction.length() < 1e-12 {
                    self.error(o.at, format!("{}: to_world maps +z to zero", o.describe()));
                    return;
                }
                self.scene.lights.push(Light::Spot {
                    position: m.transform_point3(DVec3::ZERO).as_vec3(),
                    direction: direction.normalize().as_vec3(),
                    intensity,
                    cone_deg: cone as f32,
                    falloff_deg: falloff as f32,
                });
            }
            "constant" => {
                let radiance = self.colour(o, "radiance").unwrap_or(Rgb::ONE);
                self.float(o, "sampling_weight");
                self.finish(o);
                if self.scene.environment.is_some() {
                    self.error(
                        o.at,
                        format!("{}: the scene already has a constant emitter", o.describe()),
                    );
                }
                self.scene.environment = Some(radiance);
            }
            "area" => self.error(
                o.at,
                format!(
                    "{} at the top level: area emitters must be nested in a <shape>",
                    o.describe()
                ),
            ),
            _ => self.unsupported(o, EMITTERS),
        }
    }
}
