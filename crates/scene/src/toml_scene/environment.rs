//! `[environment]`: a constant radiance or a lat-long environment map.
use super::Ctx;
use super::format::EnvironmentDef;
use crate::{EnvironmentMap, Scene};
use glam::Mat3;
use toml::Spanned;

impl Ctx<'_> {
    pub(super) fn environment(&mut self, env: &Spanned<EnvironmentDef>, scene: &mut Scene) {
        let d = env.get_ref();
        let at = env.span().start;
        match (&d.radiance, &d.map) {
            (Some(r), None) => {
                for (key, v) in [
                    ("scale", d.scale.as_ref().map(|s| s.span().start)),
                    ("transform", d.transform.as_ref().map(|t| t.span().start)),
                ] {
                    if let Some(v) = v {
                        self.error(v, format!("environment: `{key}` applies to a `map` only"));
                    }
                }
                scene.environment = Some(self.colour(r, "environment radiance"));
            }
            (None, Some(file)) => scene.environment_map = self.environment_map(d, file),
            (Some(_), Some(_)) => self.error(
                at,
                "environment: give either `radiance` (constant) or `map` (an image), not both",
            ),
            (None, None) => self.error(
                at,
                "environment needs `radiance` (constant) or `map` (an image file)",
            ),
        }
    }

    fn environment_map(
        &mut self,
        d: &EnvironmentDef,
        file: &Spanned<String>,
    ) -> Option<EnvironmentMap> {
        let scale = match &d.scale {
            Some(s) if !(s.get_ref().is_finite() && *s.get_ref() >= 0.0) => {
                self.error(
                    s.span().start,
                    format!(
                        "environment scale must be finite and >= 0, got {}",
                        s.get_ref()
                    ),
                );
                1.0
            }
            Some(s) => *s.get_ref(),
            None => 1.0,
        };
        let to_world = match &d.transform {
            None => Mat3::IDENTITY,
            Some(t) => {
                let m = self.transform(t);
                match crate::rotation_part(Mat3::from_mat4(m.matrix)) {
                    Ok(r) => r,
                    Err(e) => {
                        self.error(t.span().start, format!("environment transform {e}"));
                        Mat3::IDENTITY
                    }
                }
            }
        };
        let path = self.dir.join(file.get_ref());
        let image = match self.images.get(&path, false) {
            Ok(img) => img,
            Err(e) => {
                self.error(file.span().start, format!("environment `map`: {e}"));
                return None;
            }
        };
        if let Err(e) = crate::check_lat_long(&image) {
            self.error(
                file.span().start,
                format!("environment map {} {e}", path.display()),
            );
            return None;
        }
        Some(EnvironmentMap {
            filename: path,
            image,
            scale,
            to_world,
        })
    }
}
