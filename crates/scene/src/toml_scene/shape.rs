//! `[[shapes]]` and their transforms.
use super::Ctx;
use super::format::{InstanceDef, ShapeDef, TransformDef};
use crate::{MaterialId, Mesh, Scene, Transform, box_mesh, obj, quad_mesh, shapes, sphere_mesh};
use glam::{Mat4, Quat, Vec3};
use std::collections::HashMap;
use toml::Spanned;

impl Ctx<'_> {
    pub(super) fn transform(&mut self, t: &Spanned<TransformDef>) -> Transform {
        let d = t.get_ref();
        let at = t.span().start;
        if let Some(m) = d.matrix {
            if d.translate.is_some() || d.rotate.is_some() || d.scale.is_some() {
                self.error(
                    at,
                    "transform: `matrix` cannot be combined with translate/rotate/scale",
                );
            }
            if m.iter().flatten().any(|x| !x.is_finite()) {
                self.error(at, "transform matrix has a non-finite entry");
                return Transform::default();
            }
            let mat = Mat4::from_cols_array_2d(&m).transpose();
            if mat.determinant().abs() < 1e-12 {
                self.error(at, "transform matrix is singular");
                return Transform::default();
            }
            return Transform { matrix: mat };
        }
        let scale = match &d.scale {
            None => Vec3::ONE,
            Some(toml::Value::Float(s)) => Vec3::splat(*s as f32),
            Some(toml::Value::Integer(s)) => Vec3::splat(*s as f32),
            Some(toml::Value::Array(a)) if a.len() == 3 => {
                let v: Vec<f32> = a
                    .iter()
                    .filter_map(|x| x.as_float().or_else(|| x.as_integer().map(|i| i as f64)))
                    .map(|x| x as f32)
                    .collect();
                if v.len() == 3 {
                    Vec3::new(v[0], v[1], v[2])
                } else {
                    self.error(
                        at,
                        "transform scale must be a number or an array of 3 numbers",
                    );
                    Vec3::ONE
                }
            }
            Some(_) => {
                self.error(
                    at,
                    "transform scale must be a number or an array of 3 numbers",
                );
                Vec3::ONE
            }
        };
        if !scale.is_finite() || scale.abs().min_element() < 1e-12 {
            self.error(
                at,
                format!("transform scale {scale:?} must be finite and non-zero"),
            );
            return Transform::default();
        }
        let rot = match d.rotate {
            None => Quat::IDENTITY,
            Some([x, y, z, deg]) => {
                let axis = Vec3::new(x, y, z);
                if !axis.is_finite() || axis.length() < 1e-12 || !deg.is_finite() {
                    self.error(
                        at,
                        "transform rotate needs a non-zero finite axis and a finite angle",
                    );
                    Quat::IDENTITY
                } else {
                    Quat::from_axis_angle(axis.normalize(), deg.to_radians())
                }
            }
        };
        let tr = Vec3::from_array(d.translate.unwrap_or([0.0; 3]));
        if !tr.is_finite() {
            self.error(at, "transform translate is not finite");
        }
        Transform {
            matrix: Mat4::from_scale_rotation_translation(scale, rot, tr),
        }
    }

    pub(super) fn shape(
        &mut self,
        index: usize,
        s: &Spanned<ShapeDef>,
        names: &HashMap<String, MaterialId>,
        scene: &mut Scene,
    ) {
        let d = s.get_ref();
        let kind = d.kind.get_ref().as_str();
        let material = self.shape_material(index, d, names);
        if !self.check_shape_keys(index, d) {
            return;
        }
        if kind != "obj" && d.material.is_none() {
            self.error(
                s.span().start,
                format!("shapes[{index}] ({kind}) needs a `material`"),
            );
        }
        let transform = d
            .transform
            .as_ref()
            .map(|t| self.transform(t))
            .unwrap_or_default();
        let mut meshes: Vec<(Mesh, Option<MaterialId>)> = if kind == "obj" {
            let Some(meshes) = self.obj_shape(index, s, material, scene) else {
                return;
            };
            meshes
        } else {
            vec![(self.primitive(index, s), material)]
        };
        if let Some(name) = &d.name {
            self.named_shape(name, d, meshes, transform, scene);
            return;
        }
        if d.template == Some(true) {
            self.error(
                s.span().start,
                format!("shapes[{index}]: `template` needs a `name` for instances to use"),
            );
        }
        for (m, _) in &mut meshes {
            if m.name.is_empty() {
                m.name = format!("shapes[{index}] ({kind})");
            }
            place(m, &transform, d.flip_normals == Some(true));
        }
        for (m, material) in meshes {
            scene.add_world_mesh(m, material);
        }
    }

    /// The shape's `material` by name; an unknown name is a warning and the error material.
    fn shape_material(
        &mut self,
        index: usize,
        d: &ShapeDef,
        names: &HashMap<String, MaterialId>,
    ) -> Option<MaterialId> {
        let n = d.material.as_ref()?;
        let id = names.get(n.get_ref()).copied();
        if id.is_none() {
            self.warning(
                n.span().start,
                format!(
                    "unknown material \"{}\": rendering shapes[{index}] with the error material (magenta)",
                    n.get_ref()
                ),
            );
        }
        id
    }

    /// False (with an error) for an unknown shape type; every key the type does not take is
    /// an error at the key.
    fn check_shape_keys(&mut self, index: usize, d: &ShapeDef) -> bool {
        let kind = d.kind.get_ref().as_str();
        let allowed: &[&str] = match kind {
            "quad" => &["corner", "u", "v"],
            "box" => &["min", "max"],
            "sphere" => &["center", "radius", "subdivisions"],
            "obj" => &["file"],
            other => {
                self.error(
                    d.kind.span().start,
                    format!("unknown shape type \"{other}\" (expected obj, quad, box or sphere)"),
                );
                return false;
            }
        };
        let present = [
            ("corner", d.corner.as_ref().map(|v| v.span().start)),
            ("u", d.u.as_ref().map(|v| v.span().start)),
            ("v", d.v.as_ref().map(|v| v.span().start)),
            ("min", d.min.as_ref().map(|v| v.span().start)),
            ("max", d.max.as_ref().map(|v| v.span().start)),
            ("center", d.center.as_ref().map(|v| v.span().start)),
            ("radius", d.radius.as_ref().map(|v| v.span().start)),
            (
                "subdivisions",
                d.subdivisions.as_ref().map(|v| v.span().start),
            ),
            ("file", d.file.as_ref().map(|v| v.span().start)),
        ];
        for (key, at) in present {
            if let Some(at) = at
                && !allowed.contains(&key)
            {
                self.error(
                    at,
                    format!("shapes[{index}]: key `{key}` does not apply to type \"{kind}\""),
                );
            }
        }
        true
    }

    /// The mesh of a quad, box or sphere shape, in object space.
    fn primitive(&mut self, index: usize, s: &Spanned<ShapeDef>) -> Mesh {
        let d = s.get_ref();
        match d.kind.get_ref().as_str() {
            "quad" => {
                let corner = d
                    .corner
                    .as_ref()
                    .map_or(Vec3::new(-1.0, -1.0, 0.0), |v| self.vec3(v, "corner"));
                let u =
                    d.u.as_ref()
                        .map_or(Vec3::new(2.0, 0.0, 0.0), |v| self.vec3(v, "u"));
                let v =
                    d.v.as_ref()
                        .map_or(Vec3::new(0.0, 2.0, 0.0), |x| self.vec3(x, "v"));
                if u.cross(v).length() < 1e-12 {
                    self.error(
                        s.span().start,
                        format!(
                            "shapes[{index}] quad has zero area (u and v are parallel or zero)"
                        ),
                    );
                }
                quad_mesh(corner, u, v)
            }
            "box" => {
                let min = d
                    .min
                    .as_ref()
                    .map_or(Vec3::splat(-1.0), |v| self.vec3(v, "min"));
                let max = d
                    .max
                    .as_ref()
                    .map_or(Vec3::splat(1.0), |v| self.vec3(v, "max"));
                if (max - min).min_element() <= 0.0 {
                    self.error(
                        s.span().start,
                        format!("shapes[{index}] box needs max > min on every axis"),
                    );
                }
                box_mesh(min, max)
            }
            _ => {
                let center = d
                    .center
                    .as_ref()
                    .map_or(Vec3::ZERO, |v| self.vec3(v, "center"));
                let radius = d
                    .radius
                    .as_ref()
                    .map_or(1.0, |r| self.positive(r, "radius"));
                let level = match &d.subdivisions {
                    Some(n) if (0..=7).contains(n.get_ref()) => *n.get_ref() as u32,
                    Some(n) => {
                        self.error(
                            n.span().start,
                            format!("subdivisions {} must be 0..=7", n.get_ref()),
                        );
                        0
                    }
                    None => 4,
                };
                sphere_mesh(center, radius, level)
            }
        }
    }
}

/// Moves `m` from object to world space by `transform` (keeping its winding when the
/// transform mirrors), turning its front side round when `flip_normals`.
fn place(m: &mut Mesh, transform: &Transform, flip_normals: bool) {
    for p in &mut m.positions {
        *p = transform.point(*p);
    }
    for n in &mut m.normals {
        *n = transform.normal(*n);
    }
    if transform.flips_handedness() {
        // Mirroring reverses winding; restore it so the front side stays where it was.
        for t in &mut m.indices {
            t.swap(1, 2);
        }
    }
    if flip_normals {
        shapes::flip(m);
    }
}

impl Ctx<'_> {
    /// A shape with a `name`: its meshes stay in object space, placed by its own transform
    /// (unless it is a `template`) and by `[[instances]]`.
    fn named_shape(
        &mut self,
        name: &Spanned<String>,
        d: &ShapeDef,
        meshes: Vec<(Mesh, Option<MaterialId>)>,
        transform: Transform,
        scene: &mut Scene,
    ) {
        if self.named_shapes.contains_key(name.get_ref()) {
            self.error(
                name.span().start,
                format!("shape \"{}\" is defined twice", name.get_ref()),
            );
            return;
        }
        let mut placed = Vec::new();
        for (mut m, material) in meshes {
            if m.name.is_empty() {
                m.name = format!("shape \"{}\"", name.get_ref());
            }
            if d.flip_normals == Some(true) {
                shapes::flip(&mut m);
            }
            let id = scene.add_mesh(m);
            if d.template != Some(true) {
                scene.add_instance(id, material, transform);
            }
            placed.push((id, material));
        }
        self.named_shapes.insert(name.get_ref().clone(), placed);
    }

    /// `[[instances]]`: another placement of a named shape, optionally in another material.
    pub(super) fn instance(
        &mut self,
        i: &Spanned<InstanceDef>,
        names: &HashMap<String, MaterialId>,
        scene: &mut Scene,
    ) {
        let d = i.get_ref();
        let Some(meshes) = self.named_shapes.get(d.shape.get_ref()).cloned() else {
            self.error(
                d.shape.span().start,
                format!(
                    "instance of unknown shape \"{}\" (instances name a shape with `name`, defined above them)",
                    d.shape.get_ref()
                ),
            );
            return;
        };
        let material = match &d.material {
            Some(n) => match names.get(n.get_ref()) {
                Some(id) => Some(Some(*id)),
                None => {
                    self.error(
                        n.span().start,
                        format!("unknown material \"{}\"", n.get_ref()),
                    );
                    return;
                }
            },
            None => None,
        };
        let transform = d
            .transform
            .as_ref()
            .map(|t| self.transform(t))
            .unwrap_or_default();
        for (mesh, own) in meshes {
            scene.add_instance(mesh, material.unwrap_or(own), transform);
        }
    }
}

impl Ctx<'_> {
    /// An MTL material whose `map_Kd` names a file: its reflectance becomes that bitmap
    /// (resolved next to the OBJ, decoded from sRGB). A file that cannot be read is an error.
    fn diffuse_map(
        &mut self,
        mut m: crate::Material,
        map: Option<String>,
        obj: &std::path::Path,
        at: usize,
        scene: &mut Scene,
    ) -> crate::Material {
        let Some(file) = map else { return m };
        let path = obj
            .parent()
            .unwrap_or(std::path::Path::new("."))
            .join(&file);
        match self.images.get(&path, false) {
            Ok(image) => {
                let id = scene.add_texture(crate::Texture::Bitmap(crate::Bitmap {
                    filename: path,
                    image,
                    raw: false,
                    filter: crate::FilterType::Bilinear,
                    wrap: crate::WrapMode::Repeat,
                    to_uv: glam::Affine2::IDENTITY,
                }));
                m.bsdf = crate::Bsdf::Diffuse {
                    reflectance: crate::Param::Texture(id),
                };
            }
            Err(e) => self.error(
                at,
                format!(
                    "OBJ {}: material \"{}\": map_Kd: {e}",
                    obj.display(),
                    m.name
                ),
            ),
        }
        m
    }
}

impl Ctx<'_> {
    /// The meshes of an `obj` shape with their materials: `material` if given, else each
    /// model's MTL material (with its `map_Kd`); `None` after an error.
    fn obj_shape(
        &mut self,
        index: usize,
        s: &Spanned<ShapeDef>,
        material: Option<MaterialId>,
        scene: &mut Scene,
    ) -> Option<Vec<(Mesh, Option<MaterialId>)>> {
        let d = s.get_ref();
        let Some(file) = &d.file else {
            self.error(
                s.span().start,
                format!("shapes[{index}] (obj) needs a `file`"),
            );
            return None;
        };
        let path = self.dir.join(file.get_ref());
        let loaded = match obj::load_obj(&path, material) {
            Ok(loaded) => loaded,
            Err(e) => {
                self.error(file.span().start, e);
                return None;
            }
        };
        for w in loaded.warnings {
            self.warning(file.span().start, w);
        }
        let mut out = Vec::new();
        let parts = loaded.meshes.into_iter().zip(loaded.materials);
        for ((m, mat), map) in parts.zip(loaded.diffuse_maps) {
            let mat = match (material, mat) {
                (Some(_), _) => material,
                (None, Some(mm)) => {
                    let mm = self.diffuse_map(mm, map, &path, file.span().start, scene);
                    Some(scene.add_material(mm))
                }
                (None, None) => None,
            };
            out.push((m, mat));
        }
        Some(out)
    }
}
