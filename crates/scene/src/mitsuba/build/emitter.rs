//! Emitter plugins outside shapes: point, spot and projector (`beam.rs`), directional,
//! constant and envmap.
use super::Builder;
use crate::mitsuba::xml::Obj;
use crate::{EnvironmentMap, Light, Rgb};
use glam::{DMat4, DVec3, Mat3};

const EMITTERS: &str =
    "area (inside a shape), point, spot, projector, directional, constant and envmap";

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
            "spot" => self.spot(o),
            "projector" => self.projector(o),
            "constant" => {
                let radiance = self.colour(o, "radiance").unwrap_or(Rgb::ONE);
                self.float(o, "sampling_weight");
                self.finish(o);
                self.environment_slot(o);
                self.scene.environment = Some(radiance);
            }
            "envmap" => self.envmap(o),
            "directional" => self.directional(o),
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

    /// `<emitter type="envmap">`: `filename`, `scale` (1), `to_world` (a rotation).
    fn envmap(&mut self, o: &'t Obj) {
        let scale = self.float(o, "scale").unwrap_or(1.0);
        if !(scale.is_finite() && scale >= 0.0) {
            let at = self.prop(o, "scale").map_or(o.at, |p| p.at);
            self.error(
                at,
                format!("{}: scale {scale} must be finite and >= 0", o.describe()),
            );
        }
        let to_world = match self.transform(o, "to_world") {
            None => Mat3::IDENTITY,
            Some(m) => match crate::rotation_part(Mat3::from_mat4(m.as_mat4())) {
                Ok(r) => r,
                Err(e) => {
                    let at = self.prop(o, "to_world").map_or(o.at, |p| p.at);
                    self.error(at, format!("{}: to_world {e}", o.describe()));
                    Mat3::IDENTITY
                }
            },
        };
        // Accepted: how Mitsuba compensates its own sampling changes nothing in the image.
        self.boolean(o, "mis_compensation");
        self.float(o, "sampling_weight");
        let file = self.string(o, "filename");
        self.finish(o);
        let Some((file, at)) = file else {
            self.error(
                o.at,
                format!("{} needs a <string name=\"filename\">", o.describe()),
            );
            return;
        };
        let path = self.sources.resolve(file);
        let Some(image) = self.image(&path, false, at) else {
            return;
        };
        if let Err(e) = crate::check_lat_long(&image) {
            self.error(
                at,
                format!("{}: environment map {} {e}", o.describe(), path.display()),
            );
            return;
        }
        self.environment_slot(o);
        self.scene.environment_map = Some(EnvironmentMap {
            filename: path,
            image,
            scale: scale as f32,
            to_world,
        });
    }

    /// Mitsuba allows one environment emitter (`constant` or `envmap`) per scene.
    fn environment_slot(&mut self, o: &Obj) {
        if self.scene.environment.is_some() || self.scene.environment_map.is_some() {
            self.error(
                o.at,
                format!(
                    "{}: the scene already has an environment emitter (constant or envmap)",
                    o.describe()
                ),
            );
        }
    }

    /// `<emitter type="directional">`: `irradiance` (1), `direction` or `to_world` (+z).
    fn directional(&mut self, o: &'t Obj) {
        let irradiance = self.colour(o, "irradiance").unwrap_or(Rgb::ONE);
        let to_world = self.transform(o, "to_world");
        let direction = match (self.point(o, "direction"), to_world) {
            (Some(_), Some(_)) => {
                self.error(
                    o.at,
                    format!(
                        "{}: give either `direction` or `to_world`, not both",
                        o.describe()
                    ),
                );
                return;
            }
            (Some(d), None) => d,
            (None, m) => m.unwrap_or(DMat4::IDENTITY).transform_vector3(DVec3::Z),
        };
        self.float(o, "sampling_weight");
        self.finish(o);
        if direction.length() <= 1e-12 || !direction.is_finite() {
            self.error(o.at, format!("{}: the direction is zero", o.describe()));
            return;
        }
        self.scene.lights.push(Light::Directional {
            direction: direction.normalize().as_vec3(),
            irradiance,
        });
    }
}
