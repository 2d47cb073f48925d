//! Stage two: validate the raw TOML (`format.rs`) into a [`Scene`], collecting every problem.
use crate::diagnostic::{Diagnostic, SceneError, Severity, SourceMap};
use crate::format::{CameraDef, LightDef, MaterialDef, SceneFile, ShapeDef, TransformDef, V3};
use crate::{
    Bsdf, Camera, CameraPath, Light, Material, MaterialId, Mesh, Param, RenderDefaults, Rgb, Scene,
    Transform, box_mesh, obj, quad_mesh, shapes, sphere_mesh,
};
use glam::{Mat4, Quat, Vec3};
use std::collections::HashMap;
use std::path::{Path, PathBuf};
use toml::Spanned;

/// Loads and validates a TOML scene file. OBJ paths are relative to the file's directory.
pub fn load_scene(path: &Path) -> Result<Scene, SceneError> {
    let text = std::fs::read_to_string(path).map_err(|e| SceneError {
        diagnostics: vec![Diagnostic {
            severity: Severity::Error,
            file: path.to_path_buf(),
            line: 0,
            col: 0,
            message: format!("cannot read scene file: {e}"),
        }],
    })?;
    load_scene_str(&text, path)
}

/// Loads a scene from TOML text; `path` names it in messages and anchors relative paths.
pub fn load_scene_str(text: &str, path: &Path) -> Result<Scene, SceneError> {
    let map = SourceMap { file: path, text };
    let raw: SceneFile = toml::from_str(text).map_err(|e| SceneError {
        diagnostics: vec![toml_error(&map, &e)],
    })?;
    let mut cx = Ctx {
        map,
        diags: Vec::new(),
        dir: path.parent().unwrap_or(Path::new(".")).to_path_buf(),
    };
    let scene = cx.scene(raw);
    let (errors, warnings): (Vec<_>, Vec<_>) = cx
        .diags
        .into_iter()
        .partition(|d| d.severity == Severity::Error);
    if errors.is_empty() {
        Ok(Scene { warnings, ..scene })
    } else {
        Err(SceneError {
            diagnostics: errors.into_iter().chain(warnings).collect(),
        })
    }
}

pub(crate) fn toml_error(map: &SourceMap, e: &toml::de::Error) -> Diagnostic {
    let offset = e.span().map_or(0, |s| s.start);
    let message = e.message().trim().replace('\n', " ");
    map.error(offset, message)
}

struct Ctx<'a> {
    map: SourceMap<'a>,
    diags: Vec<Diagnostic>,
    dir: PathBuf,
}

impl Ctx<'_> {
    fn error(&mut self, offset: usize, msg: impl Into<String>) {
        let d = self.map.error(offset, msg);
        self.diags.push(d);
    }

    fn warning(&mut self, offset: usize, msg: impl Into<String>) {
        let d = self.map.warning(offset, msg);
        self.diags.push(d);
    }

    /// A finite vector; `what` names the field in messages.
    fn vec3(&mut self, v: &V3, what: &str) -> Vec3 {
        let a = *v.get_ref();
        if a.iter().any(|c| !c.is_finite()) {
            self.error(
                v.span().start,
                format!("{what} {a:?} has a non-finite component"),
            );
            return Vec3::ZERO;
        }
        Vec3::from_array(a)
    }

    /// A finite, non-negative colour no larger than [`crate::MAX_COLOUR`].
    fn colour(&mut self, v: &V3, what: &str) -> Rgb {
        let c = self.vec3(v, what);
        if let Err(problem) = crate::check_colour(c) {
            self.error(
                v.span().start,
                format!("{what} {:?} {problem}", c.to_array()),
            );
            return Rgb::ZERO;
        }
        c
    }

    fn positive(&mut self, v: &Spanned<f32>, what: &str) -> f32 {
        let x = *v.get_ref();
        if !(x.is_finite() && x > 0.0) {
            self.error(
                v.span().start,
                format!("{what} must be a finite number > 0, got {x}"),
            );
            return 1.0;
        }
        x
    }

    fn scene(&mut self, raw: SceneFile) -> Scene {
        let mut scene = Scene {
            source: self.map.file.to_path_buf(),
            ..Scene::default()
        };
        scene.camera = raw.camera.as_ref().map(|c| self.camera(c));
        if let Some(r) = &raw.render {
            scene.render = self.render(r);
        }
        let mut names: HashMap<String, MaterialId> = HashMap::new();
        for m in &raw.materials {
            let name = m.get_ref().name.get_ref().clone();
            if names.contains_key(&name) {
                self.error(
                    m.get_ref().name.span().start,
                    format!("material \"{name}\" is defined twice"),
                );
                continue;
            }
            let mat = self.material(m.get_ref());
            names.insert(name, scene.add_material(mat));
        }
        for (i, s) in raw.shapes.iter().enumerate() {
            self.shape(i, s, &names, &mut scene);
        }
        for l in &raw.lights {
            if let Some(light) = self.light(l) {
                scene.lights.push(light);
            }
        }
        if let Some(env) = &raw.environment {
            scene.environment = Some(self.colour(&env.get_ref().radiance, "environment radiance"));
        }
        if let Some(p) = raw.camera_path {
            scene.camera_path = self.camera_path(p);
        }
        let emitters = scene.has_emissive_instance();
        if scene.meshes.is_empty() && scene.lights.is_empty() && scene.environment.is_none() {
            self.error(
                0,
                "the scene is empty: it has no shapes, lights or environment",
            );
        } else if !emitters
            && scene.lights.is_empty()
            && scene.environment.is_none_or(|e| e.max_element() <= 0.0)
        {
            self.warning(0, "the scene has no light source (no emissive material, light or environment): it will render black");
        }
        scene
    }

    /// The `[camera_path]` table, deserialised and validated; problems at the table.
    fn camera_path(&mut self, p: Spanned<toml::Value>) -> Option<CameraPath> {
        let at = p.span().start;
        let path: CameraPath = match p.into_inner().try_into() {
            Ok(path) => path,
            Err(e) => {
                let e: toml::de::Error = e;
                let msg = e.message().trim().replace('\n', " ");
                self.error(at, format!("camera_path: {msg}"));
                return None;
            }
        };
        match path.validate() {
            Ok(()) => Some(path),
            Err(problems) => {
                for problem in problems {
                    self.error(at, problem.to_string());
                }
                None
            }
        }
    }

    fn camera(&mut self, c: &Spanned<CameraDef>) -> Camera {
        let d = c.get_ref();
        let position = self.vec3(&d.position, "camera position");
        let look_at = self.vec3(&d.look_at, "camera look_at");
        let up = d.up.as_ref().map_or(Vec3::Y, |u| self.vec3(u, "camera up"));
        let fov = *d.fov_deg.get_ref();
        if !(fov.is_finite() && fov > 0.0 && fov < 180.0) {
            self.error(
                d.fov_deg.span().start,
                format!("fov_deg {fov} is outside (0, 180)"),
            );
        }
        let gaze = look_at - position;
        if gaze.length() <= 1e-6 * (1.0 + position.length()) {
            self.error(
                d.look_at.span().start,
                "camera look_at equals its position: no view direction",
            );
        } else if gaze.normalize().cross(up.normalize_or_zero()).length() < 1e-4 {
            self.error(
                d.up.as_ref()
                    .map_or(d.look_at.span().start, |u| u.span().start),
                "camera up is parallel to the view direction (or zero)",
            );
        }
        let mut size = |v: &Spanned<i64>, what: &str| -> u32 {
            let x = *v.get_ref();
            if !(1..=32768).contains(&x) {
                self.error(
                    v.span().start,
                    format!("camera {what} {x} must be between 1 and 32768"),
                );
                return 1;
            }
            x as u32
        };
        let width = size(&d.width, "width");
        let height = size(&d.height, "height");
        Camera {
            position,
            look_at,
            up,
            fov_deg: fov,
            width,
            height,
        }
    }

    fn render(&mut self, r: &crate::format::RenderDef) -> RenderDefaults {
        let mut out = RenderDefaults::default();
        if let Some(s) = &r.spp {
            if (1..=1 << 24).contains(s.get_ref()) {
                out.spp = Some(*s.get_ref() as u32);
            } else {
                self.error(
                    s.span().start,
                    format!("spp {} must be between 1 and 16777216", s.get_ref()),
                );
            }
        }
        if let Some(s) = &r.max_depth {
            if *s.get_ref() == -1 || (1..=1024).contains(s.get_ref()) {
                out.max_depth = Some(*s.get_ref() as i32);
            } else {
                self.error(
                    s.span().start,
                    format!(
                        "max_depth {} must be -1 (unlimited) or 1..=1024",
                        s.get_ref()
                    ),
                );
            }
        }
        if let Some(s) = &r.rr_depth {
            if (1..=1024).contains(s.get_ref()) {
                out.rr_depth = Some(*s.get_ref() as u32);
            } else {
                self.error(
                    s.span().start,
                    format!("rr_depth {} must be 1..=1024", s.get_ref()),
                );
            }
        }
        if let Some(s) = &r.seed {
            if *s.get_ref() >= 0 {
                out.seed = Some(*s.get_ref() as u64);
            } else {
                self.error(s.span().start, format!("seed {} must be >= 0", s.get_ref()));
            }
        }
        out
    }

    fn material(&mut self, m: &MaterialDef) -> Material {
        let name = m.name.get_ref().clone();
        let kind = m.kind.get_ref().as_str();
        let emission = m
            .emission
            .as_ref()
            .map_or(Rgb::ZERO, |e| self.colour(e, "emission"));
        let allowed: &[&str] = match kind {
            "diffuse" => &["reflectance"],
            "conductor" => &["roughness", "eta", "k", "specular_reflectance"],
            "plastic" => &["reflectance", "roughness", "ior"],
            other => {
                self.error(
                    m.kind.span().start,
                    format!(
                        "unknown material type \"{other}\" (expected diffuse, conductor or plastic)"
                    ),
                );
                return Material::error();
            }
        };
        let present: [(&str, Option<usize>); 6] = [
            (
                "reflectance",
                m.reflectance.as_ref().map(|v| v.span().start),
            ),
            ("roughness", m.roughness.as_ref().map(|v| v.span().start)),
            ("eta", m.eta.as_ref().map(|v| v.span().start)),
            ("k", m.k.as_ref().map(|v| v.span().start)),
            (
                "specular_reflectance",
                m.specular_reflectance.as_ref().map(|v| v.span().start),
            ),
            ("ior", m.ior.as_ref().map(|v| v.span().start)),
        ];
        for (key, at) in present {
            if let Some(at) = at
                && !allowed.contains(&key)
            {
                self.error(
                    at,
                    format!("material \"{name}\": key `{key}` does not apply to type \"{kind}\""),
                );
            }
        }
        let reflectance = |cx: &mut Self| -> Rgb {
            match &m.reflectance {
                Some(r) => {
                    let c = cx.colour(r, "reflectance");
                    if c.max_element() > 1.0 {
                        cx.error(
                            r.span().start,
                            format!("reflectance {c:?} exceeds 1: the surface would create energy"),
                        );
                    }
                    c
                }
                None => Rgb::splat(0.5),
            }
        };
        let roughness = |cx: &mut Self| -> f32 {
            match &m.roughness {
                Some(r) => {
                    let a = *r.get_ref();
                    if !(a.is_finite() && (0.0..=1.0).contains(&a)) {
                        cx.error(r.span().start, format!("roughness {a} must be in [0, 1]"));
                        return 0.1;
                    }
                    a
                }
                None => 0.1,
            }
        };
        let bsdf = match kind {
            "diffuse" => Bsdf::Diffuse {
                reflectance: Param::Const(reflectance(self)),
            },
            "conductor" => {
                let alpha = roughness(self);
                // Default: gold, Mitsuba's `Au` at the Rec.709 primaries.
                let eta = m
                    .eta
                    .as_ref()
                    .map_or(Rgb::new(0.143, 0.374, 1.442), |v| self.colour(v, "eta"));
                let k =
                    m.k.as_ref()
                        .map_or(Rgb::new(3.983, 2.386, 1.603), |v| self.colour(v, "k"));
                let specular_reflectance = m
                    .specular_reflectance
                    .as_ref()
                    .map_or(Rgb::ONE, |v| self.colour(v, "specular_reflectance"));
                Bsdf::Conductor {
                    alpha: Param::Const(alpha),
                    eta,
                    k,
                    specular_reflectance: Param::Const(specular_reflectance),
                }
            }
            _ => {
                let ior = m.ior.as_ref().map_or(1.5, |v| {
                    let x = *v.get_ref();
                    if !(x.is_finite() && x > 1.0 && x < 4.0) {
                        self.error(v.span().start, format!("ior {x} must be in (1, 4)"));
                        return 1.5;
                    }
                    x
                });
                Bsdf::Plastic {
                    reflectance: Param::Const(reflectance(self)),
                    alpha: Param::Const(roughness(self).max(0.01)),
                    ior,
                }
            }
        };
        Material {
            name,
            bsdf,
            emission,
        }
    }

    fn transform(&mut self, t: &Spanned<TransformDef>) -> Transform {
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

    fn shape(
        &mut self,
        index: usize,
        s: &Spanned<ShapeDef>,
        names: &HashMap<String, MaterialId>,
        scene: &mut Scene,
    ) {
        let d = s.get_ref();
        let kind = d.kind.get_ref().as_str();
        let material = match &d.material {
            Some(n) => match names.get(n.get_ref()) {
                Some(id) => Some(*id),
                None => {
                    self.warning(
                        n.span().start,
                        format!("unknown material \"{}\": rendering shapes[{index}] with the error material (magenta)", n.get_ref()),
                    );
                    None
                }
            },
            None => None,
        };
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
                return;
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
        let mut meshes: Vec<(Mesh, Option<MaterialId>)> = match kind {
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
                vec![(quad_mesh(corner, u, v), material)]
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
                vec![(box_mesh(min, max), material)]
            }
            "sphere" => {
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
                vec![(sphere_mesh(center, radius, level), material)]
            }
            _ => {
                let Some(file) = &d.file else {
                    self.error(
                        s.span().start,
                        format!("shapes[{index}] (obj) needs a `file`"),
                    );
                    return;
                };
                let path = self.dir.join(file.get_ref());
                match obj::load_obj(&path, material) {
                    Ok(loaded) => {
                        for w in loaded.warnings {
                            self.warning(file.span().start, w);
                        }
                        loaded
                            .meshes
                            .into_iter()
                            .zip(loaded.materials)
                            .map(|(m, mat)| match material {
                                Some(_) => (m, material),
                                None => (m, mat.map(|mm| scene.add_material(mm))),
                            })
                            .collect()
                    }
                    Err(e) => {
                        self.error(file.span().start, e);
                        return;
                    }
                }
            }
        };
        for (m, _) in &mut meshes {
            if m.name.is_empty() {
                m.name = format!("shapes[{index}] ({kind})");
            }
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
            if d.flip_normals == Some(true) {
                shapes::flip(m);
            }
        }
        for (m, material) in meshes {
            scene.add_world_mesh(m, material);
        }
    }

    fn light(&mut self, l: &Spanned<LightDef>) -> Option<Light> {
        let d = l.get_ref();
        let at = l.span().start;
        let kind = d.kind.get_ref().as_str();
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
                self.error(d.kind.span().start, format!("unknown light type \"{other}\" (expected point or spot; area lights are emissive materials, the environment is [environment])"));
                None
            }
        }
    }
}
