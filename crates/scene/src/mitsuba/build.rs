//! Stage two: interpret the object tree (`xml.rs`) as eyeadapt's [`Scene`].
//!
//! Every plugin reads its parameters through the typed accessors below, which mark them as
//! used; [`Builder::finish`] then reports whatever was left, the way Mitsuba reports
//! "unreferenced properties". Unsupported plugin types are reported once, at their element.
use super::presets::CONDUCTOR_PRESETS;
use super::xml::{ChildKind, Obj, Prop, Value};
use crate::diagnostic::{Diagnostic, SourceMap};
use crate::{
    Bsdf, Camera, Light, Material, MaterialId, Mesh, Rgb, Scene, box_mesh, obj, quad_mesh, shapes,
    sphere_mesh,
};
use glam::{DMat3, DMat4, DVec3, Vec3};
use std::collections::HashMap;
use std::path::PathBuf;

/// Icosphere level used for `sphere` shapes (5120 triangles, area 0.3 % under 4πr²).
pub(crate) const SPHERE_SUBDIVISIONS: u32 = 4;

const BSDFS: &str = "diffuse, conductor, roughconductor, plastic, roughplastic and twosided";
const SHAPES: &str = "obj, ply, rectangle, cube and sphere";
const EMITTERS: &str = "area (inside a shape), point, spot and constant";
const SAMPLERS: &[&str] = &[
    "independent",
    "stratified",
    "multijitter",
    "orthogonal",
    "ldsampler",
];
/// Named IORs accepted by Mitsuba's `int_ior`/`ext_ior` (Mitsuba's `ior.h` table).
const IORS: &[(&str, f64)] = &[
    ("vacuum", 1.0),
    ("helium", 1.000036),
    ("hydrogen", 1.000132),
    ("air", 1.000277),
    ("carbon dioxide", 1.00045),
    ("water", 1.3330),
    ("acetone", 1.36),
    ("ethanol", 1.361),
    ("carbon tetrachloride", 1.461),
    ("glycerol", 1.4729),
    ("benzene", 1.501),
    ("silicone oil", 1.52045),
    ("bromine", 1.661),
    ("water ice", 1.31),
    ("fused quartz", 1.458),
    ("pyrex", 1.470),
    ("acrylic glass", 1.49),
    ("polypropylene", 1.49),
    ("bk7", 1.5046),
    ("sodium chloride", 1.544),
    ("amber", 1.55),
    ("pet", 1.5750),
    ("diamond", 2.419),
];

/// A BSDF as built from XML, before it becomes a material.
#[derive(Clone, Debug)]
struct BuiltBsdf {
    bsdf: Bsdf,
    /// The id, or a description of the inline element.
    name: String,
}

pub(crate) struct Builder<'t> {
    map: &'t SourceMap<'t>,
    pub diags: Vec<Diagnostic>,
    dir: PathBuf,
    ids: HashMap<&'t str, &'t Obj>,
    /// Top-level BSDFs by id (`None`: failed, or being built).
    bsdfs: HashMap<String, Option<BuiltBsdf>>,
    /// Non-emissive material of each BSDF id, shared by every shape that references it.
    shared: HashMap<String, MaterialId>,
    default_material: Option<MaterialId>,
    pub scene: Scene,
}

impl<'t> Builder<'t> {
    pub(crate) fn new(map: &'t SourceMap<'t>) -> Self {
        Builder {
            map,
            diags: Vec::new(),
            dir: map
                .file
                .parent()
                .unwrap_or(std::path::Path::new("."))
                .to_path_buf(),
            ids: HashMap::new(),
            bsdfs: HashMap::new(),
            shared: HashMap::new(),
            default_material: None,
            scene: Scene {
                source: map.file.to_path_buf(),
                ..Scene::default()
            },
        }
    }

    fn error(&mut self, at: usize, msg: impl Into<String>) {
        let d = self.map.error(at, msg);
        self.diags.push(d);
    }

    fn warning(&mut self, at: usize, msg: impl Into<String>) {
        let d = self.map.warning(at, msg);
        self.diags.push(d);
    }

    fn unsupported(&mut self, o: &Obj, supported: &str) {
        self.error(
            o.at,
            format!(
                "unsupported {}: eyeadapt supports {} plugins {supported}",
                o.describe(),
                o.tag
            ),
        );
    }

    // ----- typed parameter access ---------------------------------------------------------

    fn prop<'o>(&self, o: &'o Obj, name: &str) -> Option<&'o Prop> {
        let p = o.props.iter().find(|p| p.name == name)?;
        p.used.set(true);
        Some(p)
    }

    fn wrong_type(&mut self, o: &Obj, p: &Prop, want: &str) {
        self.error(
            p.at,
            format!(
                "parameter `{}` of {} must be {want}, not <{}>",
                p.name,
                o.describe(),
                p.value.tag()
            ),
        );
    }

    fn float(&mut self, o: &Obj, name: &str) -> Option<f64> {
        let p = self.prop(o, name)?;
        match &p.value {
            Value::Float(x) => Some(*x),
            Value::Integer(i) => Some(*i as f64),
            _ => {
                self.wrong_type(o, p, "a <float>");
                None
            }
        }
    }

    /// A float in `range`, with the element's location on failure.
    fn float_in(
        &mut self,
        o: &Obj,
        name: &str,
        range: std::ops::RangeInclusive<f64>,
    ) -> Option<f64> {
        let x = self.float(o, name)?;
        if !range.contains(&x) {
            let at = self.prop(o, name).map_or(o.at, |p| p.at);
            self.error(
                at,
                format!(
                    "parameter `{name}` of {} is {x}, outside [{}, {}]",
                    o.describe(),
                    range.start(),
                    range.end()
                ),
            );
            return None;
        }
        Some(x)
    }

    fn int(&mut self, o: &Obj, name: &str) -> Option<(i64, usize)> {
        let p = self.prop(o, name)?;
        match &p.value {
            Value::Integer(i) => Some((*i, p.at)),
            _ => {
                self.wrong_type(o, p, "an <integer>");
                None
            }
        }
    }

    fn boolean(&mut self, o: &Obj, name: &str) -> Option<bool> {
        let p = self.prop(o, name)?;
        match &p.value {
            Value::Boolean(b) => Some(*b),
            _ => {
                self.wrong_type(o, p, "a <boolean>");
                None
            }
        }
    }

    fn string<'o>(&mut self, o: &'o Obj, name: &str) -> Option<(&'o str, usize)> {
        let p = self.prop(o, name)?;
        match &p.value {
            Value::Str(s) => Some((s.as_str(), p.at)),
            _ => {
                self.wrong_type(o, p, "a <string>");
                None
            }
        }
    }

    fn point(&mut self, o: &Obj, name: &str) -> Option<DVec3> {
        let p = self.prop(o, name)?;
        match &p.value {
            Value::Point(v) | Value::Vector(v) => Some(*v),
            _ => {
                self.wrong_type(o, p, "a <point>");
                None
            }
        }
    }

    fn transform(&mut self, o: &Obj, name: &str) -> Option<DMat4> {
        let p = self.prop(o, name)?;
        match &p.value {
            Value::Transform(m) => Some(*m),
            _ => {
                self.wrong_type(o, p, "a <transform>");
                None
            }
        }
    }

    /// Numbers are read as f64 but rendered in f32: a finite value beyond ±3.4e38 (a
    /// `translate` of 1e300, a sphere radius of 1e300) became infinite and the object
    /// silently vanished from the render. `ok` says whether `o`'s result stayed finite.
    fn single_precision(&mut self, ok: bool, o: &Obj) {
        if !ok {
            self.error(
                o.at,
                format!(
                    "{}: its positions are not finite in single precision (a coordinate, \
                     transform or radius beyond ±3.4e38)",
                    o.describe()
                ),
            );
        }
    }

    /// A colour: `<rgb>`, a constant `<spectrum>`, `<float>` or `<integer>` (grey). A texture
    /// in its place is unsupported (reported where the texture is defined or nested).
    fn colour(&mut self, o: &'t Obj, name: &str) -> Option<Rgb> {
        if let Some(p) = self.prop(o, name) {
            let c = match &p.value {
                Value::Rgb(c) => *c,
                Value::Float(x) => DVec3::splat(*x),
                Value::Integer(i) => DVec3::splat(*i as f64),
                _ => {
                    self.wrong_type(o, p, "an <rgb>, constant <spectrum> or <float>");
                    return None;
                }
            };
            if c.min_element() < 0.0 {
                self.error(
                    p.at,
                    format!(
                        "parameter `{name}` of {} is {c:?}: colours cannot be negative",
                        o.describe()
                    ),
                );
                return None;
            }
            // As in TOML scenes: at most MAX_COLOUR (so also finite in single precision).
            if let Err(problem) = crate::check_colour(c.as_vec3()) {
                let problem = if c.as_vec3().is_finite() {
                    problem
                } else {
                    // Beyond f32: say what check_colour says of the largest f32.
                    crate::check_colour(Rgb::splat(f32::MAX)).unwrap_err()
                };
                self.error(
                    p.at,
                    format!(
                        "parameter `{name}` of {} is {:?}: it {problem}",
                        o.describe(),
                        c.to_array()
                    ),
                );
                return None;
            }
            return Some(c.as_vec3());
        }
        // A nested or referenced texture filling this parameter.
        if let Some(c) = o.children.iter().find(|c| c.name.as_deref() == Some(name)) {
            c.used.set(true);
            match &c.kind {
                ChildKind::Obj(t) if t.tag == "texture" => self.texture(t),
                ChildKind::Obj(t) => self.error(
                    c.at,
                    format!(
                        "{} cannot give parameter `{name}` of {}",
                        t.describe(),
                        o.describe()
                    ),
                ),
                ChildKind::Ref(id) => {
                    // Unsupported textures are reported where they are defined.
                    if let Some(t) = self.resolve(id, c.at)
                        && t.tag != "texture"
                    {
                        self.error(
                            c.at,
                            format!(
                                "<ref id=\"{id}\"> names a <{}>, which cannot give parameter `{name}` of {}",
                                t.tag,
                                o.describe()
                            ),
                        );
                    }
                }
            }
            // Any error above fails the load; the caller goes on with its default.
        }
        None
    }

    /// Every texture plugin is unsupported: eyeadapt materials are constant.
    fn texture(&mut self, t: &Obj) {
        let hint = match t.kind.as_str() {
            "bitmap" => " (image textures are not implemented: use a constant <rgb>)",
            _ => " (eyeadapt materials are constant: use an <rgb>)",
        };
        self.error(t.at, format!("unsupported {}{hint}", t.describe()));
    }

    fn resolve(&mut self, id: &str, at: usize) -> Option<&'t Obj> {
        match self.ids.get(id) {
            Some(o) => Some(*o),
            None => {
                self.error(
                    at,
                    format!("<ref id=\"{id}\">: no top-level object has this id"),
                );
                None
            }
        }
    }

    /// Reports parameters and nested objects no plugin used.
    fn finish(&mut self, o: &Obj) {
        for p in &o.props {
            if !p.used.get() {
                self.error(
                    p.at,
                    format!(
                        "unknown parameter <{} name=\"{}\"> of {} (eyeadapt does not support it)",
                        p.value.tag(),
                        p.name,
                        o.describe()
                    ),
                );
            }
        }
        for c in &o.children {
            if c.used.get() {
                continue;
            }
            match &c.kind {
                ChildKind::Obj(t) if t.tag == "texture" => self.texture(t),
                ChildKind::Obj(t) => self.error(
                    c.at,
                    format!("unexpected {} inside {}", t.describe(), o.describe()),
                ),
                ChildKind::Ref(id) => self.error(
                    c.at,
                    format!("unexpected <ref id=\"{id}\"> inside {}", o.describe()),
                ),
            }
        }
    }

    // ----- the scene ----------------------------------------------------------------------

    pub(crate) fn build(&mut self, objects: &'t [Obj]) {
        for o in objects {
            if let Some(id) = &o.id
                && self.ids.insert(id.as_str(), o).is_some()
            {
                self.error(o.at, format!("id \"{id}\" is used twice"));
            }
        }
        let mut sensor_seen = false;
        let mut integrator_seen = false;
        for (index, o) in objects.iter().enumerate() {
            match o.tag.as_str() {
                "bsdf" => match &o.id {
                    Some(id) => {
                        self.bsdf_by_id(id, o.at);
                    }
                    None => {
                        self.bsdf(o);
                    }
                },
                "texture" => self.texture(o),
                "shape" => {
                    let before = self.scene.meshes.len();
                    self.shape(o, index);
                    let ok = self.scene.meshes[before..]
                        .iter()
                        .all(|m| m.positions.iter().all(|p| p.is_finite()));
                    self.single_precision(ok, o);
                }
                "emitter" => {
                    let before = self.scene.lights.len();
                    self.emitter(o);
                    let ok = self.scene.lights[before..].iter().all(|l| match l {
                        Light::Point { position, .. } => position.is_finite(),
                        Light::Spot {
                            position,
                            direction,
                            ..
                        } => position.is_finite() && direction.is_finite(),
                    });
                    self.single_precision(ok, o);
                }
                "sensor" => {
                    if sensor_seen {
                        self.warning(
                            o.at,
                            format!("{} ignored: eyeadapt renders the first sensor only (as Mitsuba does by default)", o.describe()),
                        );
                    } else {
                        sensor_seen = true;
                        self.sensor(o);
                        let ok = self.scene.camera.as_ref().is_none_or(|c| {
                            c.position.is_finite() && c.look_at.is_finite() && c.up.is_finite()
                        });
                        self.single_precision(ok, o);
                    }
                }
                "integrator" => {
                    if integrator_seen {
                        self.error(o.at, "a scene can have only one <integrator>");
                    } else {
                        integrator_seen = true;
                        self.integrator(o);
                    }
                }
                "medium" | "phase" | "volume" | "spectrum" => self.error(
                    o.at,
                    format!(
                        "unsupported {}: eyeadapt has no participating media or spectral plugins",
                        o.describe()
                    ),
                ),
                _ => self.error(
                    o.at,
                    format!(
                        "{} at the top level: it belongs inside a <sensor>",
                        o.describe()
                    ),
                ),
            }
        }
        self.check_lights();
    }

    fn check_lights(&mut self) {
        let s = &self.scene;
        let emitters = s.has_emissive_instance();
        if s.meshes.is_empty() && s.lights.is_empty() && s.environment.is_none() {
            self.error(
                0,
                "the scene is empty: it has no shapes, lights or environment",
            );
        } else if !emitters
            && s.lights.is_empty()
            && s.environment.is_none_or(|e| e.max_element() <= 0.0)
        {
            self.warning(0, "the scene has no light source (no area, point, spot or constant emitter): it will render black");
        }
    }

    // ----- BSDFs --------------------------------------------------------------------------

    fn bsdf_by_id(&mut self, id: &str, at: usize) -> Option<BuiltBsdf> {
        if let Some(b) = self.bsdfs.get(id) {
            return b.clone();
        }
        let o = self.resolve(id, at)?;
        if o.tag != "bsdf" {
            if o.tag != "texture" {
                self.error(
                    at,
                    format!("<ref id=\"{id}\"> names a <{}>, expected a <bsdf>", o.tag),
                );
            }
            return None;
        }
        self.bsdfs.insert(id.to_string(), None);
        let b = self.bsdf(o);
        self.bsdfs.insert(id.to_string(), b.clone());
        b
    }

    fn bsdf(&mut self, o: &'t Obj) -> Option<BuiltBsdf> {
        let name = o
            .id
            .clone()
            .unwrap_or_else(|| format!("{} at line {}", o.describe(), self.map.line_col(o.at).0));
        let bsdf = match o.kind.as_str() {
            "twosided" => return self.twosided(o),
            "diffuse" => {
                let reflectance = self.reflectance(o, "reflectance");
                Bsdf::Diffuse {
                    reflectance: reflectance.into(),
                }
            }
            "conductor" | "roughconductor" => self.conductor(o),
            "plastic" | "roughplastic" => self.plastic(o),
            _ => {
                self.unsupported(o, BSDFS);
                return None;
            }
        };
        self.finish(o);
        Some(BuiltBsdf { bsdf, name })
    }

    /// A reflectance in [0, 1] (default 0.5).
    fn reflectance(&mut self, o: &'t Obj, name: &str) -> Rgb {
        let c = self.colour(o, name).unwrap_or(Rgb::splat(0.5));
        if c.max_element() > 1.0 {
            let at = self.prop(o, name).map_or(o.at, |p| p.at);
            self.error(
                at,
                format!(
                    "parameter `{name}` of {} is {c:?}: a reflectance above 1 creates energy",
                    o.describe()
                ),
            );
        }
        c
    }

    /// eyeadapt is always two-sided, so `twosided` just unwraps its one BSDF.
    fn twosided(&mut self, o: &'t Obj) -> Option<BuiltBsdf> {
        let inner: Vec<_> = o
            .children
            .iter()
            .filter(|c| match &c.kind {
                ChildKind::Obj(b) => b.tag == "bsdf",
                ChildKind::Ref(_) => true,
            })
            .collect();
        for c in &inner {
            c.used.set(true);
        }
        let result = match inner.as_slice() {
            [c] => match &c.kind {
                ChildKind::Obj(b) => self.bsdf(b),
                ChildKind::Ref(id) => self.bsdf_by_id(id, c.at),
            },
            [] => {
                self.error(o.at, format!("{} needs one nested <bsdf>", o.describe()));
                None
            }
            _ => {
                self.error(
                    o.at,
                    format!("unsupported {} with different front and back BSDFs: eyeadapt surfaces scatter the same on both sides", o.describe()),
                );
                None
            }
        };
        self.finish(o);
        result.map(|b| BuiltBsdf {
            name: o.id.clone().unwrap_or(b.name),
            bsdf: b.bsdf,
        })
    }

    /// `alpha` (or equal `alpha_u`/`alpha_v`) and `distribution` of rough plugins.
    fn roughness(&mut self, o: &'t Obj, default: f64) -> f32 {
        // Mitsuba's roughplastic is isotropic: there `alpha_u` is an unknown parameter.
        let anisotropic = o.kind == "roughconductor" && self.prop(o, "alpha_u").is_some();
        let alpha = match (self.prop(o, "alpha").is_some(), anisotropic) {
            (true, _) => self.float_in(o, "alpha", 0.0..=1.0).unwrap_or(default),
            (false, true) => {
                let u = self.float_in(o, "alpha_u", 0.0..=1.0).unwrap_or(default);
                let v = self.float_in(o, "alpha_v", 0.0..=1.0).unwrap_or(u);
                if (u - v).abs() > 1e-6 {
                    self.warning(
                        o.at,
                        format!("{}: anisotropic roughness (alpha_u {u}, alpha_v {v}) approximated by the isotropic alpha {}", o.describe(), (u * v).sqrt()),
                    );
                }
                (u * v).sqrt()
            }
            (false, false) => default,
        };
        match self.string(o, "distribution") {
            Some(("ggx", _)) => {}
            Some(("beckmann", at)) => self.warning(
                at,
                format!("{}: the Beckmann distribution is approximated by GGX with the same alpha", o.describe()),
            ),
            Some((other, at)) => self.error(
                at,
                format!("{}: unknown distribution \"{other}\" (expected ggx or beckmann)", o.describe()),
            ),
            None => self.warning(
                o.at,
                format!("{}: Mitsuba's default Beckmann distribution is approximated by GGX with the same alpha (say <string name=\"distribution\" value=\"ggx\"/> to match exactly)", o.describe()),
            ),
        }
        // Accepted: eyeadapt always samples visible normals.
        self.boolean(o, "sample_visible");
        alpha as f32
    }

    fn conductor(&mut self, o: &'t Obj) -> Bsdf {
        let alpha = if o.kind == "roughconductor" {
            self.roughness(o, 0.1)
        } else {
            0.0
        };
        let material = self.string(o, "material");
        let has_eta = self.prop(o, "eta").is_some() || self.prop(o, "k").is_some();
        let (eta, k) = match material {
            Some((name, at)) if has_eta => {
                self.error(
                    at,
                    format!(
                        "{}: give either `material` (\"{name}\") or `eta`/`k`, not both",
                        o.describe()
                    ),
                );
                (Rgb::ZERO, Rgb::ONE)
            }
            Some((name, at)) => match CONDUCTOR_PRESETS.iter().find(|(n, _, _)| *n == name) {
                Some((_, eta, k)) => (Rgb::from_array(*eta), Rgb::from_array(*k)),
                None => {
                    self.error(
                        at,
                        format!(
                            "{}: unknown conductor material \"{name}\" (known: {})",
                            o.describe(),
                            CONDUCTOR_PRESETS
                                .iter()
                                .map(|p| p.0)
                                .collect::<Vec<_>>()
                                .join(", ")
                        ),
                    );
                    (Rgb::ZERO, Rgb::ONE)
                }
            },
            // Mitsuba's default material "none": a perfect mirror (eta 0, k 1).
            None => (
                self.colour(o, "eta").unwrap_or(Rgb::ZERO),
                self.colour(o, "k").unwrap_or(Rgb::ONE),
            ),
        };
        let specular_reflectance = self.colour(o, "specular_reflectance").unwrap_or(Rgb::ONE);
        Bsdf::Conductor {
            alpha: alpha.into(),
            eta,
            k,
            specular_reflectance: specular_reflectance.into(),
        }
    }

    fn ior(&mut self, o: &'t Obj, name: &str, default: f64) -> f64 {
        let Some(p) = self.prop(o, name) else {
            return default;
        };
        match &p.value {
            Value::Float(x) => *x,
            Value::Integer(i) => *i as f64,
            Value::Str(s) => match IORS.iter().find(|(n, _)| n.eq_ignore_ascii_case(s)) {
                Some((_, v)) => *v,
                None => {
                    self.error(
                        p.at,
                        format!(
                            "{}: unknown IOR name \"{s}\" (known: {})",
                            o.describe(),
                            IORS.iter().map(|i| i.0).collect::<Vec<_>>().join(", ")
                        ),
                    );
                    default
                }
            },
            _ => {
                self.wrong_type(o, p, "a <float> or <string>");
                default
            }
        }
    }

    fn plastic(&mut self, o: &'t Obj) -> Bsdf {
        let alpha = if o.kind == "roughplastic" {
            self.roughness(o, 0.1)
        } else {
            0.0
        };
        let reflectance = self.reflectance(o, "diffuse_reflectance");
        let int_ior = self.ior(o, "int_ior", 1.49);
        let ext_ior = self.ior(o, "ext_ior", 1.000277);
        let ior = int_ior / ext_ior;
        if !(ior > 1.0 && ior < 4.0) {
            self.error(
                o.at,
                format!(
                    "{}: int_ior/ext_ior = {ior} must be in (1, 4)",
                    o.describe()
                ),
            );
        }
        if let Some(s) = self.colour(o, "specular_reflectance")
            && s != Rgb::ONE
        {
            let at = self.prop(o, "specular_reflectance").map_or(o.at, |p| p.at);
            self.warning(
                at,
                format!("{}: specular_reflectance {s:?} is ignored (eyeadapt's plastic coating reflects by Fresnel alone)", o.describe()),
            );
        }
        if self.boolean(o, "nonlinear") == Some(true) {
            let at = self.prop(o, "nonlinear").map_or(o.at, |p| p.at);
            self.warning(
                at,
                format!("{}: nonlinear = true is ignored (eyeadapt's plastic is Mitsuba's linear model)", o.describe()),
            );
        }
        if alpha < 0.01 {
            self.warning(
                o.at,
                format!("{}: a smooth coating is approximated by GGX alpha 0.01 (eyeadapt's plastic is always a microfacet coating)", o.describe()),
            );
        }
        Bsdf::Plastic {
            reflectance: reflectance.into(),
            alpha: alpha.max(0.01).into(),
            ior: ior as f32,
        }
    }

    // ----- shapes -------------------------------------------------------------------------

    fn shape(&mut self, o: &'t Obj, index: usize) {
        let kind = o.kind.as_str();
        if !matches!(kind, "obj" | "ply" | "rectangle" | "cube" | "sphere") {
            self.unsupported(o, SHAPES);
            return;
        }
        let to_world = self.transform(o, "to_world").unwrap_or(DMat4::IDENTITY);
        let flip_normals = self.boolean(o, "flip_normals").unwrap_or(false);
        let face_normals = if kind == "sphere" {
            false
        } else {
            self.boolean(o, "face_normals").unwrap_or(false)
        };
        let label = format!(
            "shape[{index}] ({kind}, line {})",
            self.map.line_col(o.at).0
        );
        let mut meshes: Vec<Mesh> = match kind {
            "obj" | "ply" => {
                self.boolean(o, "flip_tex_coords");
                let Some((file, at)) = self.string(o, "filename") else {
                    self.error(
                        o.at,
                        format!("{} needs a <string name=\"filename\">", o.describe()),
                    );
                    self.finish(o);
                    return;
                };
                let path = self.dir.join(file);
                let loaded = if kind == "obj" {
                    obj::load_obj(&path, Some(MaterialId(0))).map(|l| l.meshes)
                } else {
                    super::ply::load_ply(&path).map(|p| {
                        vec![Mesh {
                            name: path.display().to_string(),
                            positions: p.positions,
                            normals: p.normals,
                            indices: p.indices,
                            ..Mesh::default()
                        }]
                    })
                };
                match loaded {
                    Ok(m) => m,
                    Err(e) => {
                        self.error(at, e);
                        Vec::new()
                    }
                }
            }
            "rectangle" => vec![quad_mesh(
                Vec3::new(-1.0, -1.0, 0.0),
                Vec3::new(2.0, 0.0, 0.0),
                Vec3::new(0.0, 2.0, 0.0),
            )],
            "cube" => vec![box_mesh(Vec3::splat(-1.0), Vec3::splat(1.0))],
            _ => {
                let center = self.point(o, "center").unwrap_or(DVec3::ZERO);
                let radius = match self.float(o, "radius") {
                    Some(r) if r > 0.0 => r,
                    Some(r) => {
                        let at = self.prop(o, "radius").map_or(o.at, |p| p.at);
                        self.error(at, format!("{}: radius {r} must be > 0", o.describe()));
                        1.0
                    }
                    None => 1.0,
                };
                vec![sphere_mesh(
                    center.as_vec3(),
                    radius as f32,
                    SPHERE_SUBDIVISIONS,
                )]
            }
        };
        let bsdf = self.shape_bsdf(o);
        let emission = self.shape_emission(o);
        self.finish(o);

        let material = match (bsdf, emission) {
            (Err(()), _) => None,
            (Ok(b), Some(emission)) => {
                let (bsdf, name) = match b {
                    Some(b) => (b.bsdf, b.name),
                    None => (
                        Bsdf::Diffuse {
                            reflectance: Rgb::splat(0.5).into(),
                        },
                        "default diffuse".to_string(),
                    ),
                };
                Some(self.scene.add_material(Material {
                    name: format!("{name} + area emitter of {label}"),
                    bsdf,
                    emission,
                }))
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
                self.scene.add_material(Material::diffuse(
                    "default (Mitsuba's diffuse 0.5)",
                    Rgb::splat(0.5),
                ))
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
            // (and with it the emitting side) flips; so does its analytic sphere's normal.
            let flip_shading = mirrored && kind == "sphere";
            for n in &mut mesh.normals {
                *n = (normal_matrix * *n).normalize_or_zero();
                if flip_shading {
                    *n = -*n;
                }
            }
            if face_normals {
                mesh.normals.clear();
            } else if mesh.normals.is_empty() && matches!(kind, "obj" | "ply") {
                mesh.normals = smooth_normals(mesh);
            }
            if flip_normals {
                shapes::flip(mesh);
            }
        }
        for mesh in meshes {
            self.scene.add_world_mesh(mesh, material);
        }
    }

    /// The shape's BSDF: `Ok(None)` for none (Mitsuba's default diffuse), `Err` on errors.
    fn shape_bsdf(&mut self, o: &'t Obj) -> Result<Option<BuiltBsdf>, ()> {
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

    /// The radiance of a nested `area` emitter.
    fn shape_emission(&mut self, o: &'t Obj) -> Option<Rgb> {
        let mut out = None;
        for c in &o.children {
            let ChildKind::Obj(e) = &c.kind else { continue };
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
            let radiance = self.colour(e, "radiance").unwrap_or(Rgb::ONE);
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

    // ----- emitters -----------------------------------------------------------------------

    fn emitter(&mut self, o: &'t Obj) {
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

    // ----- sensor, film, sampler, integrator ----------------------------------------------

    /// The one nested object with this tag (`<film>`, `<sampler>`, `<rfilter>`).
    fn nested(&mut self, o: &'t Obj, tag: &str) -> Option<&'t Obj> {
        let mut found = None;
        for c in &o.children {
            let t = match &c.kind {
                ChildKind::Obj(t) => t,
                ChildKind::Ref(id) => match self.ids.get(id.as_str()) {
                    Some(t) => *t,
                    None => continue,
                },
            };
            if t.tag != tag {
                continue;
            }
            c.used.set(true);
            if found.is_some() {
                self.error(c.at, format!("{} has more than one <{tag}>", o.describe()));
            } else {
                found = Some(t);
            }
        }
        found
    }

    fn sensor(&mut self, o: &'t Obj) {
        if o.kind != "perspective" {
            self.error(
                o.at,
                format!(
                    "unsupported {}: eyeadapt supports the perspective (pinhole) sensor only",
                    o.describe()
                ),
            );
            return;
        }
        let to_world = self.transform(o, "to_world").unwrap_or(DMat4::IDENTITY);
        // Accepted and ignored: eyeadapt does not clip (documented in docs/mitsuba.md).
        self.float(o, "near_clip");
        self.float(o, "far_clip");
        let (width, height) = match self.nested(o, "film") {
            Some(f) => self.film(f),
            None => (768, 576),
        };
        if let Some(s) = self.nested(o, "sampler") {
            self.sampler(s);
        }
        let aspect = width as f64 / height as f64;
        let fov = self.float(o, "fov");
        let focal = self
            .prop(o, "focal_length")
            .map(|p| (p.at, p.value.clone()));
        let vertical = match (fov, focal) {
            (Some(_), Some((at, _))) => {
                self.error(
                    at,
                    format!(
                        "{}: give either `fov` or `focal_length`, not both",
                        o.describe()
                    ),
                );
                None
            }
            (Some(fov), None) => {
                let at = self.prop(o, "fov").map_or(o.at, |p| p.at);
                if !(fov > 0.0 && fov < 180.0) {
                    self.error(
                        at,
                        format!("{}: fov {fov} must be in (0, 180)", o.describe()),
                    );
                    None
                } else {
                    let axis = self.string(o, "fov_axis").unwrap_or(("x", o.at));
                    match vertical_fov(fov, axis.0, aspect) {
                        Some(v) => Some(v),
                        None => {
                            self.error(
                                axis.1,
                                format!("{}: unknown fov_axis \"{}\" (expected x, y, diagonal, smaller or larger)", o.describe(), axis.0),
                            );
                            None
                        }
                    }
                }
            }
            (None, focal) => {
                // Mitsuba: a 35 mm film (36 mm wide) with a 50 mm lens unless told otherwise.
                let mm = match focal {
                    None => Some(50.0),
                    Some((at, Value::Str(s))) => {
                        let t = s.trim().trim_end_matches("mm").trim();
                        match t.parse::<f64>() {
                            Ok(f) if f > 0.0 => Some(f),
                            _ => {
                                self.error(at, format!("{}: focal_length \"{s}\" is not a positive length like \"50mm\"", o.describe()));
                                None
                            }
                        }
                    }
                    Some((_, Value::Float(f))) if f > 0.0 => Some(f),
                    Some((at, _)) => {
                        self.error(
                            at,
                            format!(
                                "{}: focal_length must be a <string> like \"50mm\"",
                                o.describe()
                            ),
                        );
                        None
                    }
                };
                mm.and_then(|f| vertical_fov(2.0 * (18.0 / f).atan().to_degrees(), "x", aspect))
            }
        };
        self.finish(o);
        let position = to_world.transform_point3(DVec3::ZERO);
        let forward = to_world.transform_vector3(DVec3::Z);
        let up = to_world.transform_vector3(DVec3::Y);
        let left = to_world.transform_vector3(DVec3::X);
        if left.cross(up).dot(forward) <= 0.0
            || forward.cross(up).length() < 1e-9 * forward.length() * up.length()
        {
            let at = self.prop(o, "to_world").map_or(o.at, |p| p.at);
            self.error(
                at,
                format!("{}: to_world mirrors or collapses the view (eyeadapt's camera cannot mirror the image)", o.describe()),
            );
            return;
        }
        self.scene.camera = Some(Camera {
            position: position.as_vec3(),
            look_at: (position + forward.normalize()).as_vec3(),
            up: up.normalize().as_vec3(),
            fov_deg: vertical.unwrap_or(40.0) as f32,
            width,
            height,
        });
    }

    fn film(&mut self, f: &'t Obj) -> (u32, u32) {
        if f.kind != "hdrfilm" {
            self.error(
                f.at,
                format!(
                    "unsupported {}: eyeadapt supports hdrfilm only",
                    f.describe()
                ),
            );
            return (768, 576);
        }
        let size = |b: &mut Self, name: &str, default: u32| -> u32 {
            match b.int(f, name) {
                Some((x, _)) if (1..=32768).contains(&x) => x as u32,
                Some((x, at)) => {
                    b.error(
                        at,
                        format!("{}: {name} {x} must be between 1 and 32768", f.describe()),
                    );
                    default
                }
                None => default,
            }
        };
        let width = size(self, "width", 768);
        let height = size(self, "height", 576);
        // Accepted and ignored: eyeadapt writes its own EXR layout.
        for s in ["file_format", "pixel_format", "component_format"] {
            self.string(f, s);
        }
        self.boolean(f, "banner");
        self.boolean(f, "compensate");
        // The box filter never reaches past its pixel, so the border changes nothing.
        self.boolean(f, "sample_border");
        match self.nested(f, "rfilter") {
            Some(r) if r.kind == "box" => self.finish(r),
            Some(r) => self.error(
                r.at,
                format!("unsupported {}: eyeadapt reconstructs with a box filter only (use <rfilter type=\"box\"/>)", r.describe()),
            ),
            None => self.warning(
                f.at,
                format!("{} has no <rfilter>: Mitsuba would use a Gaussian, eyeadapt uses a box filter (say <rfilter type=\"box\"/> to match)", f.describe()),
            ),
        }
        self.finish(f);
        (width, height)
    }

    fn sampler(&mut self, s: &'t Obj) {
        if !SAMPLERS.contains(&s.kind.as_str()) {
            self.error(
                s.at,
                format!(
                    "unsupported {}: known samplers are {}",
                    s.describe(),
                    SAMPLERS.join(", ")
                ),
            );
            return;
        }
        match self.int(s, "sample_count") {
            Some((n, _)) if (1..=1 << 24).contains(&n) => self.scene.render.spp = Some(n as u32),
            Some((n, at)) => self.error(
                at,
                format!(
                    "{}: sample_count {n} must be between 1 and 16777216",
                    s.describe()
                ),
            ),
            None => self.scene.render.spp = Some(4),
        }
        match self.int(s, "seed") {
            Some((n, _)) if n >= 0 => self.scene.render.seed = Some(n as u64),
            Some((n, at)) => self.error(at, format!("{}: seed {n} must be >= 0", s.describe())),
            None => {}
        }
        // Accepted: eyeadapt has its own sampler; the pattern parameters do not apply.
        if matches!(s.kind.as_str(), "stratified" | "multijitter" | "orthogonal") {
            self.boolean(s, "jitter");
        }
        if s.kind == "orthogonal" {
            self.int(s, "strength");
        }
        self.finish(s);
    }

    fn integrator(&mut self, o: &'t Obj) {
        if o.kind != "path" {
            self.error(
                o.at,
                format!("unsupported {}: eyeadapt is a unidirectional path tracer (use <integrator type=\"path\">)", o.describe()),
            );
            return;
        }
        match self.int(o, "max_depth") {
            Some((d, _)) if d == -1 || (1..=1024).contains(&d) => {
                self.scene.render.max_depth = Some(d as i32)
            }
            Some((d, at)) => self.error(
                at,
                format!(
                    "{}: max_depth {d} must be -1 (unlimited) or 1..=1024",
                    o.describe()
                ),
            ),
            None => self.scene.render.max_depth = Some(-1),
        }
        match self.int(o, "rr_depth") {
            Some((d, _)) if (1..=1024).contains(&d) => self.scene.render.rr_depth = Some(d as u32),
            Some((d, at)) => self.error(
                at,
                format!("{}: rr_depth {d} must be 1..=1024", o.describe()),
            ),
            None => self.scene.render.rr_depth = Some(5),
        }
        // Accepted: how many samples Mitsuba takes per pass changes nothing in the result.
        self.int(o, "samples_per_pass");
        if let Some(true) = self.boolean(o, "hide_emitters") {
            let at = self.prop(o, "hide_emitters").map_or(o.at, |p| p.at);
            self.error(
                at,
                format!("{}: hide_emitters = true is not supported", o.describe()),
            );
        }
        self.finish(o);
    }
}

/// eyeadapt's vertical field of view (degrees) for Mitsuba's `fov` along `axis` on a film of
/// `aspect` = width / height; `None` for an unknown axis.
pub fn vertical_fov(fov_deg: f64, axis: &str, aspect: f64) -> Option<f64> {
    let t = (fov_deg.to_radians() / 2.0).tan();
    let tv = match axis {
        "x" => t / aspect,
        "y" => t,
        "diagonal" => t / (1.0 + aspect * aspect).sqrt(),
        "smaller" if aspect >= 1.0 => t,
        "smaller" => t / aspect,
        "larger" if aspect >= 1.0 => t / aspect,
        "larger" => t,
        _ => return None,
    };
    Some(2.0 * tv.atan().to_degrees())
}

/// Angle-weighted vertex normals, what Mitsuba computes for meshes without normals (unless
/// `face_normals` is set).
pub(crate) fn smooth_normals(mesh: &Mesh) -> Vec<Vec3> {
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
            let angle = a.dot(b).clamp(-1.0, 1.0).acos();
            acc[t[k] as usize] += n * angle;
        }
    }
    acc.iter()
        .map(|n| n.normalize_or_zero().as_vec3())
        .collect()
}
