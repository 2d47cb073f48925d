//! Shape plugins: obj, ply, serialized and the built-in rectangle, cube, sphere, disk and
//! cylinder (tessellated in `shapes.rs` with Mitsuba's UVs), with their BSDF and area emitter.
use super::Builder;
use super::BuiltBsdf;
use crate::mitsuba::xml::{ChildKind, Obj};
use crate::shapes::{self, ROUND_SEGMENTS};
use crate::{Bsdf, Material, MaterialId, Mesh, Param, Rgb, obj, quad_mesh};
use glam::{DMat3, DMat4, DVec3, Vec3};

const SHAPES: &str =
    "obj, ply, serialized, rectangle, cube, sphere, disk, cylinder, shapegroup and instance";

/// A shape's meshes in its object space and the transform that comes before `to_world`
/// (a sphere's centre and radius, a cylinder's end points and radius).
struct Geometry {
    meshes: Vec<Mesh>,
    local: DMat4,
    /// Flat shading asked for by the file itself (serialized meshes).
    face_normals: bool,
}

impl<'t> Builder<'t> {
    /// A top-level shape: its meshes, each placed once.
    pub(super) fn shape(&mut self, o: &'t Obj, index: usize) {
        for (mesh, material) in self.shape_meshes(o, index) {
            self.scene.add_world_mesh(mesh, material);
        }
    }

    /// Shape `o`'s meshes in the space `to_world` maps it to, with their material.
    pub(super) fn shape_meshes(
        &mut self,
        o: &'t Obj,
        index: usize,
    ) -> Vec<(Mesh, Option<MaterialId>)> {
        let kind = o.kind.as_str();
        if !matches!(
            kind,
            "obj" | "ply" | "serialized" | "rectangle" | "cube" | "sphere" | "disk" | "cylinder"
        ) {
            self.unsupported(o, SHAPES);
            return Vec::new();
        }
        let to_world = self.transform(o, "to_world").unwrap_or(DMat4::IDENTITY);
        let flip_normals = self.boolean(o, "flip_normals").unwrap_or(false);
        let analytic = matches!(kind, "sphere" | "disk" | "cylinder" | "rectangle");
        let face_normals = !analytic && self.boolean(o, "face_normals").unwrap_or(false);
        let label = format!("shape[{index}] ({kind}, line {})", self.sources.line(o.at));
        // After an error, the BSDF and emitter are still checked.
        let geometry = self.geometry(o, kind).unwrap_or(Geometry {
            meshes: Vec::new(),
            local: DMat4::IDENTITY,
            face_normals: false,
        });
        let face_normals = face_normals || geometry.face_normals;
        let to_world = to_world * geometry.local;
        let mut meshes = geometry.meshes;
        let bsdf = self.shape_bsdf(o);
        let emission = self.shape_emission(o);
        self.finish(o);

        let material = match (bsdf, emission) {
            (Err(()), _) => None,
            (Ok(b), Some(radiance)) => {
                let (bsdf, name) = match b {
                    Some(b) => (b.bsdf, b.name),
                    None => (default_bsdf(), "default diffuse".to_string()),
                };
                // A textured radiance: the texture times 1.
                let emission = radiance.constant().unwrap_or(Rgb::ONE);
                let id = self.scene.add_material(Material {
                    name: format!("{name} + area emitter of {label}"),
                    bsdf,
                    emission,
                });
                if let Param::Texture(t) = radiance {
                    self.scene.emission_textures.push((id, t));
                }
                Some(id)
            }
            (Ok(Some(b)), None) => match self.shared.get(&b.name) {
                Some(id) => Some(*id),
                None => {
                    let id = self.scene.add_material(Material {
                        name: b.name.clone(),
                        bsdf: b.bsdf,
                        emission: Rgb::ZERO,
                    });
                    self.shared.insert(b.name, id);
                    Some(id)
                }
            },
            (Ok(None), None) => Some(*self.default_material.get_or_insert_with(|| {
                self.scene.add_material(Material {
                    name: "default (Mitsuba's diffuse 0.5)".into(),
                    bsdf: default_bsdf(),
                    emission: Rgb::ZERO,
                })
            })),
        };

        let m = to_world.as_mat4();
        let normal_matrix = DMat3::from_mat4(to_world).inverse().transpose().as_mat3();
        let mirrored = DMat3::from_mat4(to_world).determinant() < 0.0;
        for mesh in &mut meshes {
            mesh.name = if mesh.name.is_empty() {
                label.clone()
            } else {
                format!("{label} {}", mesh.name)
            };
            for p in &mut mesh.positions {
                *p = m.transform_point3(*p);
            }
            // Mitsuba keeps the winding under a mirroring transform, so the geometric normal
            // (and with it the emitting side) flips; so do its analytic sphere's and cylinder's.
            let flip_shading = mirrored && matches!(kind, "sphere" | "cylinder");
            for n in &mut mesh.normals {
                *n = (normal_matrix * *n).normalize_or_zero();
                if flip_shading {
                    *n = -*n;
                }
            }
            if face_normals {
                mesh.normals.clear();
            } else if mesh.normals.is_empty() && matches!(kind, "obj" | "ply" | "serialized") {
                mesh.normals = smooth_normals(mesh);
            }
            if flip_normals {
                shapes::flip(mesh);
            }
        }
        meshes.into_iter().map(|m| (m, material)).collect()
    }

    /// The meshes of shape `o` (a `kind` known to [`Builder::shape`]); `None` after an error.
    fn geometry(&mut self, o: &'t Obj, kind: &str) -> Option<Geometry> {
        let plain = |meshes| Geometry {
            meshes,
            local: DMat4::IDENTITY,
            face_normals: false,
        };
        Some(match kind {
            "obj" | "ply" | "serialized" => self.mesh_file(o, kind)?,
            "rectangle" => plain(vec![quad_mesh(
                Vec3::new(-1.0, -1.0, 0.0),
                Vec3::new(2.0, 0.0, 0.0),
                Vec3::new(0.0, 2.0, 0.0),
            )]),
            "cube" => plain(vec![shapes::mitsuba_cube()]),
            "disk" => plain(vec![shapes::disk(ROUND_SEGMENTS)]),
            "sphere" => {
                let center = self.point(o, "center").unwrap_or(DVec3::ZERO);
                let radius = self.radius(o);
                Geometry {
                    local: DMat4::from_translation(center)
                        * DMat4::from_scale(DVec3::splat(radius)),
                    ..plain(vec![shapes::uv_sphere(ROUND_SEGMENTS)])
                }
            }
            _ => {
                let radius = self.radius(o);
                let p0 = self.point(o, "p0").unwrap_or(DVec3::ZERO);
                let p1 = self.point(o, "p1").unwrap_or(DVec3::Z);
                let d = p1 - p0;
                if d.length() < 1e-12 {
                    self.error(o.at, format!("{}: p0 and p1 coincide", o.describe()));
                    return None;
                }
                let (s, t) = mitsuba_frame(d.normalize());
                let frame = DMat4::from_cols(
                    s.extend(0.0),
                    t.extend(0.0),
                    d.normalize().extend(0.0),
                    p0.extend(1.0),
                );
                Geometry {
                    local: frame * DMat4::from_scale(DVec3::new(radius, radius, d.length())),
                    ..plain(vec![shapes::cylinder(ROUND_SEGMENTS)])
                }
            }
        })
    }

    /// `radius` (default 1), which must be positive.
    fn radius(&mut self, o: &'t Obj) -> f64 {
        match self.float(o, "radius") {
            Some(r) if r > 0.0 => r,
            Some(r) => {
                let at = self.prop(o, "radius").map_or(o.at, |p| p.at);
                self.error(at, format!("{}: radius {r} must be > 0", o.describe()));
                1.0
            }
            None => 1.0,
        }
    }

    /// An `obj`, `ply` or `serialized` file's meshes.
    fn mesh_file(&mut self, o: &'t Obj, kind: &str) -> Option<Geometry> {
        // Mitsuba flips OBJ texture coordinates by default, never PLY or serialized ones.
        let flip_v = self.boolean(o, "flip_tex_coords").unwrap_or(kind == "obj");
        let Some((file, at)) = self.string(o, "filename") else {
            self.error(
                o.at,
                format!("{} needs a <string name=\"filename\">", o.describe()),
            );
            return None;
        };
        let path = self.sources.resolve(file);
        let mut face_normals = false;
        let loaded = match kind {
            "obj" => obj::load_obj(&path, Some(MaterialId(0))).map(|l| l.meshes),
            "ply" => crate::mitsuba::ply::load_ply(&path).map(|p| {
                vec![Mesh {
                    name: path.display().to_string(),
                    positions: p.positions,
                    normals: p.normals,
                    uvs: p.uvs,
                    colors: p.colors,
                    face_colors: p.face_colors,
                    indices: p.indices,
                }]
            }),
            _ => {
                let index = match self.int(o, "shape_index") {
                    Some((i, _)) if i >= 0 => i as usize,
                    Some((i, at)) => {
                        self.error(
                            at,
                            format!("{}: shape_index {i} must be >= 0", o.describe()),
                        );
                        return None;
                    }
                    None => 0,
                };
                crate::mitsuba::serialized::load_serialized(&path, index).map(|s| {
                    face_normals = s.face_normals;
                    vec![s.mesh]
                })
            }
        };
        let mut meshes = match loaded {
            Ok(m) => m,
            Err(e) => {
                self.error(at, e);
                return None;
            }
        };
        // `flip_tex_coords` turns the file's v into 1 − v, as in Mitsuba. The OBJ reader has
        // already done so (its meshes follow Mitsuba's default), so an OBJ is flipped back
        // only when the scene turns the flip off.
        if flip_v != (kind == "obj") {
            for uv in meshes.iter_mut().flat_map(|m| &mut m.uvs) {
                uv.y = 1.0 - uv.y;
            }
        }
        Some(Geometry {
            meshes,
            local: DMat4::IDENTITY,
            face_normals,
        })
    }

    /// The shape's BSDF: `Ok(None)` for none (Mitsuba's default diffuse), `Err` on errors.
    pub(super) fn shape_bsdf(&mut self, o: &'t Obj) -> Result<Option<BuiltBsdf>, ()> {
        let mut found: Option<Result<BuiltBsdf, ()>> = None;
        for c in &o.children {
            let b = match &c.kind {
                ChildKind::Obj(b) if b.tag == "bsdf" => self.bsdf(b),
                ChildKind::Ref(id) => match self.ids.get(id.as_str()) {
                    Some(t) if t.tag == "bsdf" => self.bsdf_by_id(id, c.at),
                    Some(_) => continue, // reported by `finish` as unexpected
                    None => {
                        c.used.set(true);
                        self.resolve(id, c.at);
                        None
                    }
                },
                ChildKind::Obj(_) => continue,
            };
            c.used.set(true);
            if found.is_some() {
                self.error(c.at, format!("{} has more than one BSDF", o.describe()));
                return Err(());
            }
            found = Some(b.ok_or(()));
        }
        found.transpose()
    }

    /// The radiance of a nested `area` emitter: a colour or a texture.
    pub(super) fn shape_emission(&mut self, o: &'t Obj) -> Option<Param<Rgb>> {
        let mut out = None;
        for c in &o.children {
            let e = match &c.kind {
                ChildKind::Obj(e) => e,
                // A top-level `<emitter type="area" id=…>`.
                ChildKind::Ref(id) => match self.ids.get(id.as_str()) {
                    Some(e) if e.tag == "emitter" => {
                        self.referenced_emitters.insert(id.as_str());
                        *e
                    }
                    _ => continue,
                },
            };
            if e.tag != "emitter" {
                continue;
            }
            c.used.set(true);
            if e.kind != "area" {
                self.error(
                    e.at,
                    format!(
                        "unsupported {} inside a shape: only area emitters attach to shapes",
                        e.describe()
                    ),
                );
                continue;
            }
            let radiance = self
                .colour_param(e, "radiance")
                .unwrap_or(Param::Const(Rgb::ONE));
            // Light sampling reads a texture by UV alone.
            if let Param::Texture(t) = radiance
                && let crate::Texture::MeshAttribute { .. } = self.scene.texture(t)
            {
                self.error(
                    e.at,
                    format!(
                        "{}: a mesh_attribute radiance is not supported (use a bitmap or checkerboard)",
                        e.describe()
                    ),
                );
            }
            self.float(e, "sampling_weight");
            self.finish(e);
            if out.is_some() {
                self.error(
                    e.at,
                    format!("{} has more than one area emitter", o.describe()),
                );
            }
            out = Some(radiance);
        }
        out
    }
}

/// Angle-weighted vertex normals, what Mitsuba computes for meshes without normals (unless
/// `face_normals` is set).
fn smooth_normals(mesh: &Mesh) -> Vec<Vec3> {
    let mut acc = vec![DVec3::ZERO; mesh.positions.len()];
    for t in &mesh.indices {
        let p = t.map(|i| mesh.positions[i as usize].as_dvec3());
        let n = (p[1] - p[0]).cross(p[2] - p[0]);
        if n.length() == 0.0 {
            continue;
        }
        let n = n.normalize();
        for k in 0..3 {
            let a = (p[(k + 1) % 3] - p[k]).normalize_or_zero();
            let b = (p[(k + 2) % 3] - p[k]).normalize_or_zero();
            let angle = libm::acos(a.dot(b).clamp(-1.0, 1.0));
            acc[t[k] as usize] += n * angle;
        }
    }
    acc.iter()
        .map(|n| n.normalize_or_zero().as_vec3())
        .collect()
}

/// The tangents Mitsuba's `Frame3f(n)` gives a unit normal `n` (the branchless orthonormal
/// basis of Duff et al. 2017), so that a cylinder's azimuth starts where Mitsuba's does.
fn mitsuba_frame(n: DVec3) -> (DVec3, DVec3) {
    let sign = 1f64.copysign(n.z);
    let a = -1.0 / (sign + n.z);
    let b = n.x * n.y * a;
    (
        DVec3::new(1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x),
        DVec3::new(b, sign + n.y * n.y * a, -n.y),
    )
}

/// Mitsuba's BSDF for a shape without one: a one-sided diffuse reflector of 0.5.
fn default_bsdf() -> Bsdf {
    Bsdf::OneSided(Box::new(Bsdf::Diffuse {
        reflectance: Rgb::splat(0.5).into(),
    }))
}
