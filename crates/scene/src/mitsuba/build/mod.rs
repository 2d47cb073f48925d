//! Stage two: interpret the object tree (`xml.rs`) as eyeadapt's [`Scene`].
//!
//! Every plugin reads its parameters through the typed accessors of `params.rs`, which mark them as
//! used; [`Builder::finish`] then reports whatever was left, the way Mitsuba reports
//! "unreferenced properties". Unsupported plugin types are reported once, at their element.
use super::source::Sources;
use super::xml::{ChildKind, Doc, Obj};
use crate::diagnostic::{Diagnostic, Severity};
use crate::{CutoutShadows, Light, MaterialId, Scene};
use std::collections::{HashMap, HashSet};

mod beam;
mod blend;
mod bsdf;
mod dielectric;
mod emitter;
mod integrator;
mod params;
mod principled;
mod rough;
mod sensor;
mod shape;
mod shapegroup;
mod texture;

use bsdf::BuiltBsdf;
pub use sensor::vertical_fov;

pub(crate) struct Builder<'t> {
    sources: &'t Sources,
    pub diags: Vec<Diagnostic>,
    /// Every object with an id, nested ones included, and the aliases.
    ids: HashMap<&'t str, &'t Obj>,
    /// BSDFs by id (`None`: failed).
    bsdfs: HashMap<String, Option<BuiltBsdf>>,
    /// Ids of the objects being built, innermost last: a `<ref>` to one of them is a cycle.
    building: Vec<String>,
    /// Built shapegroups by id: their meshes with materials (`None`: failed).
    groups: HashMap<String, Option<shapegroup::Members>>,
    /// Built textures by id (`None`: failed).
    textures: HashMap<String, Option<crate::TextureId>>,
    /// Decoded image files by (path, raw), shared by the textures that name them.
    images: HashMap<(std::path::PathBuf, bool), std::sync::Arc<crate::Image>>,
    /// Ids of area emitters that some shape references.
    referenced_emitters: HashSet<&'t str>,
    /// Non-emissive material of each BSDF id, shared by every shape that references it.
    shared: HashMap<String, MaterialId>,
    default_material: Option<MaterialId>,
    /// Whether the document has a `<medium>` anywhere (`volpath` renders as `path` only
    /// without one).
    has_media: bool,
    pub scene: Scene,
}

/// True when `o` is or contains a `<medium>`.
fn has_medium(o: &Obj) -> bool {
    o.tag == "medium"
        || o.children.iter().any(|c| match &c.kind {
            ChildKind::Obj(t) => has_medium(t),
            ChildKind::Ref(_) => false,
        })
}

impl<'t> Builder<'t> {
    pub(crate) fn new(sources: &'t Sources) -> Self {
        Builder {
            sources,
            diags: Vec::new(),
            ids: HashMap::new(),
            bsdfs: HashMap::new(),
            building: Vec::new(),
            referenced_emitters: HashSet::new(),
            textures: HashMap::new(),
            groups: HashMap::new(),
            images: HashMap::new(),
            shared: HashMap::new(),
            default_material: None,
            has_media: false,
            scene: Scene {
                source: sources.main().to_path_buf(),
                // Mitsuba's `path` and `direct` shadow rays stop at every surface; `volpath`
                // (integrator.rs) lets them through masks' holes and null surfaces.
                cutout_shadows: CutoutShadows::Block,
                ..Scene::default()
            },
        }
    }

    pub(super) fn error(&mut self, at: usize, msg: impl Into<String>) {
        let d = self.sources.error(at, msg);
        self.diags.push(d);
    }

    pub(super) fn warning(&mut self, at: usize, msg: impl Into<String>) {
        let d = self.sources.warning(at, msg);
        self.diags.push(d);
    }

    pub(super) fn unsupported(&mut self, o: &Obj, supported: &str) {
        self.error(
            o.at,
            format!(
                "unsupported {}: eyeadapt supports {} plugins {supported}",
                o.describe(),
                o.tag
            ),
        );
    }

    // ----- the scene ----------------------------------------------------------------------

    pub(crate) fn build(&mut self, doc: &'t Doc) {
        let objects = &doc.objects;
        for o in objects {
            self.register(o);
        }
        self.has_media = objects.iter().any(has_medium);
        self.aliases(doc);
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
                // Built where a parameter references it.
                "texture" if o.id.is_some() => {}
                "texture" => self.texture(o),
                // Built where an instance references it.
                "shape" if o.kind == "shapegroup" && o.id.is_some() => {}
                "shape" => {
                    let before = self.scene.meshes.len();
                    if o.kind == "instance" {
                        self.instance(o);
                    } else {
                        self.shape(o, index);
                    }
                    let ok = self.scene.meshes[before..]
                        .iter()
                        .all(|m| m.positions.iter().all(|p| p.is_finite()));
                    self.single_precision(ok, o);
                }
                // Built where a shape references it.
                "emitter" if o.kind == "area" && o.id.is_some() => {}
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
                        Light::Directional { direction, .. } => direction.is_finite(),
                        Light::TexturedSpot {
                            position, frame, ..
                        }
                        | Light::Projector {
                            position, frame, ..
                        } => position.is_finite() && frame.is_finite(),
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
                // A <film>, <sampler> or <rfilter> that a sensor references.
                _ if o.id.is_some() => {}
                _ => self.error(
                    o.at,
                    format!(
                        "{} at the top level: it belongs inside a <sensor>",
                        o.describe()
                    ),
                ),
            }
        }
        for o in objects {
            if o.tag == "emitter"
                && o.kind == "area"
                && let Some(id) = &o.id
                && !self.referenced_emitters.contains(id.as_str())
            {
                self.warning(
                    o.at,
                    format!(
                        "{} is not referenced by any shape: it emits nothing",
                        o.describe()
                    ),
                );
            }
        }
        self.check_lights();
    }

    /// `<alias id="from" as="to">`: `to` names `from`'s object.
    fn aliases(&mut self, doc: &'t Doc) {
        for a in &doc.aliases {
            if self.ids.contains_key(a.to.as_str()) {
                self.error(
                    a.at,
                    format!("<alias as=\"{}\">: the id is already used", a.to),
                );
            } else if let Some(o) = self.ids.get(a.from.as_str()) {
                self.ids.insert(a.to.as_str(), *o);
            } else {
                self.error(
                    a.at,
                    format!("<alias id=\"{}\">: no object has this id", a.from),
                );
            }
        }
    }

    /// Records the ids of `o` and of the objects nested in it.
    fn register(&mut self, o: &'t Obj) {
        if let Some(id) = &o.id
            && self.ids.insert(id.as_str(), o).is_some()
        {
            self.error(o.at, format!("id \"{id}\" is used twice"));
        }
        for c in &o.children {
            if let ChildKind::Obj(n) = &c.kind {
                self.register(n);
            }
        }
    }

    pub(super) fn check_lights(&mut self) {
        let s = &self.scene;
        if s.meshes.is_empty()
            && s.lights.is_empty()
            && s.environment.is_none()
            && s.environment_map.is_none()
        {
            let d = self.sources.whole(
                Severity::Error,
                "the scene is empty: it has no shapes, lights or environment",
            );
            self.diags.push(d);
        } else if !s.has_light_source() {
            let d = self.sources.whole(Severity::Warning, "the scene has no light source (no area, point, spot, directional, constant or envmap emitter): it will render black");
            self.diags.push(d);
        }
    }
}
