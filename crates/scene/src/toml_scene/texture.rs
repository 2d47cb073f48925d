//! `[[textures]]`: bitmaps, checkerboards and vertex colours, referenced by name from
//! materials' `*_texture` keys.
use super::Ctx;
use super::format::TextureDef;
use crate::{Bitmap, FilterType, Rgb, Texture, WrapMode};
use glam::{Affine2, Vec2};
use toml::Spanned;

impl Ctx<'_> {
    pub(super) fn texture(&mut self, t: &Spanned<TextureDef>) -> Option<Texture> {
        let d = t.get_ref();
        let kind = d.kind.get_ref().as_str();
        let allowed: &[&str] = match kind {
            "bitmap" => &["file", "raw", "filter", "wrap", "uv_scale", "uv_offset"],
            "checkerboard" => &["color0", "color1", "uv_scale", "uv_offset"],
            "vertex_color" => &[],
            other => {
                self.error(
                    d.kind.span().start,
                    format!("unknown texture type \"{other}\" (expected bitmap, checkerboard or vertex_color)"),
                );
                return None;
            }
        };
        let present = [
            ("file", d.file.as_ref().map(|v| v.span().start)),
            ("raw", d.raw.as_ref().map(|v| v.span().start)),
            ("filter", d.filter.as_ref().map(|v| v.span().start)),
            ("wrap", d.wrap.as_ref().map(|v| v.span().start)),
            ("uv_scale", d.uv_scale.as_ref().map(|v| v.span().start)),
            ("uv_offset", d.uv_offset.as_ref().map(|v| v.span().start)),
            ("color0", d.color0.as_ref().map(|v| v.span().start)),
            ("color1", d.color1.as_ref().map(|v| v.span().start)),
        ];
        let name = d.name.get_ref();
        for (key, at) in present {
            if let Some(at) = at
                && !allowed.contains(&key)
            {
                self.error(
                    at,
                    format!("texture \"{name}\": key `{key}` does not apply to type \"{kind}\""),
                );
            }
        }
        let to_uv = self.uv_transform(d);
        match kind {
            "bitmap" => {
                let Some(file) = &d.file else {
                    self.error(
                        t.span().start,
                        format!("texture \"{name}\" (bitmap) needs a `file`"),
                    );
                    return None;
                };
                let raw = d.raw.as_ref().is_some_and(|r| *r.get_ref());
                let path = self.dir.join(file.get_ref());
                let image = match self.images.get(&path, raw) {
                    Ok(img) => img,
                    Err(e) => {
                        self.error(file.span().start, e);
                        return None;
                    }
                };
                let filter = match d
                    .filter
                    .as_ref()
                    .map(|f| (f.get_ref().as_str(), f.span().start))
                {
                    None | Some(("bilinear", _)) => FilterType::Bilinear,
                    Some(("nearest", _)) => FilterType::Nearest,
                    Some((other, at)) => {
                        self.error(
                            at,
                            format!("filter \"{other}\" must be \"bilinear\" or \"nearest\""),
                        );
                        FilterType::Bilinear
                    }
                };
                let wrap = match d
                    .wrap
                    .as_ref()
                    .map(|w| (w.get_ref().as_str(), w.span().start))
                {
                    None | Some(("repeat", _)) => WrapMode::Repeat,
                    Some(("mirror", _)) => WrapMode::Mirror,
                    Some(("clamp", _)) => WrapMode::Clamp,
                    Some((other, at)) => {
                        self.error(
                            at,
                            format!("wrap \"{other}\" must be \"repeat\", \"mirror\" or \"clamp\""),
                        );
                        WrapMode::Repeat
                    }
                };
                Some(Texture::Bitmap(Bitmap {
                    filename: path,
                    image,
                    raw,
                    filter,
                    wrap,
                    to_uv,
                }))
            }
            "checkerboard" => {
                let color0 = d
                    .color0
                    .as_ref()
                    .map_or(Rgb::splat(0.4), |c| self.colour(c, "color0"));
                let color1 = d
                    .color1
                    .as_ref()
                    .map_or(Rgb::splat(0.2), |c| self.colour(c, "color1"));
                Some(Texture::Checkerboard {
                    color0,
                    color1,
                    to_uv,
                })
            }
            _ => Some(Texture::MeshAttribute {
                name: "vertex_color".into(),
            }),
        }
    }

    /// `uv_scale` then `uv_offset`: uv' = uv · scale + offset.
    fn uv_transform(&mut self, d: &TextureDef) -> Affine2 {
        let mut v2 = |v: &Option<Spanned<[f32; 2]>>, what: &str, default: Vec2| match v {
            Some(s) if s.get_ref().iter().all(|x| x.is_finite()) => Vec2::from_array(*s.get_ref()),
            Some(s) => {
                self.error(s.span().start, format!("{what} must be finite"));
                default
            }
            None => default,
        };
        let scale = v2(&d.uv_scale, "uv_scale", Vec2::ONE);
        let offset = v2(&d.uv_offset, "uv_offset", Vec2::ZERO);
        Affine2::from_scale_angle_translation(scale, 0.0, offset)
    }
}
