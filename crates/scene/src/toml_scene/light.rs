//! `[[lights]]`: point, spot and sun (directional) lights.
use super::Ctx;
use super::format::LightDef;
use crate::Light;
use toml::Spanned;

impl Ctx<'_> {
    pub(super) fn light(&mut self, l: &Spanned<LightDef>) -> Option<Light> {
        let d = l.get_ref();
        let at = l.span().start;
        let kind = d.kind.get_ref().as_str();
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
            "spot" => {
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
                Some(Light::Spot {
                    position,
                    direction: direction.normalize(),
                    intensity,
                    cone_deg: cone,
                    falloff_deg: falloff,
                })
            }
            other => {
                self.error(d.kind.span().start, format!("unknown light type \"{other}\" (expected point, spot or sun; area lights are emissive materials, the environment is [environment])"));
                None
            }
        }
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
