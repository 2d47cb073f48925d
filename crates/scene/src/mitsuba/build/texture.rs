//! Texture plugins where Mitsuba accepts a texture: `bitmap` (with `raw`, `filter_type`,
//! `wrap_mode`, `to_uv`), `checkerboard`, `mesh_attribute` (vertex and face colours) and
//! `rawconstant`. Each texture
//! goes into the scene's table once (a referenced one is shared, as are decoded images).
use super::Builder;
use crate::mitsuba::xml::{ChildKind, Obj, Value};
use crate::{Bitmap, FilterType, Param, Rgb, Texture, TextureId, WrapMode};
use glam::{Affine2, DMat4, DVec3, Mat2, Vec2};

impl<'t> Builder<'t> {
    /// The texture filling parameter `name` of `o`, nested or referenced: `None` when there is
    /// none, `Some(None)` when there is one but it failed (reported).
    fn texture_child(&mut self, o: &'t Obj, name: &str) -> Option<Option<TextureId>> {
        let c = o
            .children
            .iter()
            .find(|c| c.name.as_deref() == Some(name))?;
        let t = match &c.kind {
            ChildKind::Obj(t) => t,
            ChildKind::Ref(id) => match self.ids.get(id.as_str()) {
                Some(t) if t.tag == "texture" => *t,
                // Not a texture: `colour` reports it.
                _ => return None,
            },
        };
        if t.tag != "texture" {
            return None;
        }
        c.used.set(true);
        Some(self.texture_id(t))
    }

    /// A colour parameter that may also be a texture.
    pub(super) fn colour_param(&mut self, o: &'t Obj, name: &str) -> Option<Param<Rgb>> {
        match self.texture_child(o, name) {
            Some(t) => t.map(Param::Texture),
            None => self.colour(o, name).map(Param::Const),
        }
    }

    /// A texture used as a number (its luminance, as Mitsuba's `eval_1`), if one fills `name`.
    pub(super) fn float_texture(&mut self, o: &'t Obj, name: &str) -> Option<Option<TextureId>> {
        self.texture_child(o, name)
    }

    /// Builds texture `t` (once per id).
    fn texture_id(&mut self, t: &'t Obj) -> Option<TextureId> {
        if let Some(id) = &t.id
            && let Some(done) = self.textures.get(id)
        {
            return *done;
        }
        let built = self.texture_plugin(t);
        self.finish(t);
        let id = built.map(|tex| self.scene.add_texture(tex));
        if let Some(name) = &t.id {
            self.textures.insert(name.clone(), id);
        }
        id
    }

    fn texture_plugin(&mut self, t: &'t Obj) -> Option<Texture> {
        match t.kind.as_str() {
            "bitmap" => self.bitmap(t).map(Texture::Bitmap),
            "checkerboard" => {
                let color0 = self.colour(t, "color0").unwrap_or(Rgb::splat(0.4));
                let color1 = self.colour(t, "color1").unwrap_or(Rgb::splat(0.2));
                Some(Texture::Checkerboard {
                    color0,
                    color1,
                    to_uv: self.uv_transform(t),
                })
            }
            "mesh_attribute" => match self.string(t, "name") {
                Some((name @ ("vertex_color" | "face_color"), _)) => {
                    Some(Texture::MeshAttribute { name: name.into() })
                }
                Some((other, at)) => {
                    self.error(
                        at,
                        format!("{}: attribute \"{other}\" is not supported (eyeadapt meshes carry vertex_color and face_color only)", t.describe()),
                    );
                    None
                }
                None => {
                    self.error(
                        t.at,
                        format!("{} needs a <string name=\"name\">", t.describe()),
                    );
                    None
                }
            },
            "rawconstant" => self.raw_constant(t),
            _ => {
                self.error(
                    t.at,
                    format!(
                        "unsupported {}: eyeadapt supports texture plugins bitmap, checkerboard, mesh_attribute and rawconstant",
                        t.describe()
                    ),
                );
                None
            }
        }
    }

    /// `rawconstant`: `value`, a number or a 3-vector, used as it is (no colour conversion).
    fn raw_constant(&mut self, t: &'t Obj) -> Option<Texture> {
        let Some(p) = self.prop(t, "value") else {
            self.error(
                t.at,
                format!(
                    "{} needs a <float> or <vector name=\"value\">",
                    t.describe()
                ),
            );
            return None;
        };
        let value = match &p.value {
            Value::Float(x) => DVec3::splat(*x),
            Value::Integer(i) => DVec3::splat(*i as f64),
            Value::Vector(v) | Value::Point(v) | Value::Rgb(v) => *v,
            _ => {
                self.wrong_type(t, p, "a <float> or <vector>");
                return None;
            }
        };
        // Mitsuba checks nothing; eyeadapt's textures are colours and numbers >= 0.
        if let Err(problem) = crate::check_colour(value.as_vec3()) {
            self.error(
                p.at,
                format!(
                    "parameter `value` of {} is {:?}: it {problem}",
                    t.describe(),
                    value.to_array()
                ),
            );
            return None;
        }
        Some(Texture::Constant {
            value: value.as_vec3(),
        })
    }

    fn bitmap(&mut self, t: &'t Obj) -> Option<Bitmap> {
        let raw = self.boolean(t, "raw").unwrap_or(false);
        // Accepted: how Mitsuba stores the texture in memory.
        self.boolean(t, "accel");
        self.string(t, "format");
        let filter = match self.string(t, "filter_type") {
            None | Some(("bilinear", _)) => FilterType::Bilinear,
            Some(("nearest", _)) => FilterType::Nearest,
            Some((other, at)) => {
                self.error(
                    at,
                    format!(
                        "{}: unknown filter_type \"{other}\" (expected bilinear or nearest)",
                        t.describe()
                    ),
                );
                FilterType::Bilinear
            }
        };
        let wrap = match self.string(t, "wrap_mode") {
            None | Some(("repeat", _)) => WrapMode::Repeat,
            Some(("mirror", _)) => WrapMode::Mirror,
            Some(("clamp", _)) => WrapMode::Clamp,
            Some((other, at)) => {
                self.error(
                    at,
                    format!(
                        "{}: unknown wrap_mode \"{other}\" (expected repeat, mirror or clamp)",
                        t.describe()
                    ),
                );
                WrapMode::Repeat
            }
        };
        let to_uv = self.uv_transform(t);
        let Some((file, at)) = self.string(t, "filename") else {
            self.error(
                t.at,
                format!("{} needs a <string name=\"filename\">", t.describe()),
            );
            return None;
        };
        let path = self.sources.resolve(file);
        let image = self.image(&path, raw, at)?;
        Some(Bitmap {
            filename: path,
            image,
            raw,
            filter,
            wrap,
            to_uv,
        })
    }

    /// The decoded image file `path`, shared by every user of the same (file, raw); a file
    /// that cannot be decoded is an error at `at`.
    pub(super) fn image(
        &mut self,
        path: &std::path::Path,
        raw: bool,
        at: usize,
    ) -> Option<std::sync::Arc<crate::Image>> {
        let key = (path.to_path_buf(), raw);
        if let Some(i) = self.images.get(&key) {
            return Some(i.clone());
        }
        match crate::load_image(path, raw) {
            Ok(i) => {
                let i = std::sync::Arc::new(i);
                self.images.insert(key, i.clone());
                Some(i)
            }
            Err(e) => {
                self.error(at, e);
                None
            }
        }
    }

    /// `to_uv`: the 2D part of a 4×4 transform (x and y rows, the translation column).
    fn uv_transform(&mut self, t: &'t Obj) -> Affine2 {
        let m = self
            .transform(t, "to_uv")
            .unwrap_or(DMat4::IDENTITY)
            .as_mat4();
        Affine2::from_mat2_translation(
            Mat2::from_cols(
                m.x_axis.truncate().truncate(),
                m.y_axis.truncate().truncate(),
            ),
            Vec2::new(m.w_axis.x, m.w_axis.y),
        )
    }
}
