//! `shapegroup` and `instance`: the group's shapes become meshes stored once, and every
//! instance places all of them with its `to_world` (the tracer keeps one acceleration
//! structure per mesh, so memory grows with the group, not with its instances).
use super::Builder;
use crate::mitsuba::xml::{ChildKind, Obj};
use crate::{MaterialId, MeshId, Transform};
use glam::DMat4;

/// A shapegroup's meshes with their materials.
pub(super) type Members = Vec<(MeshId, Option<MaterialId>)>;

impl<'t> Builder<'t> {
    /// `<shape type="instance">` with a `<ref>` to a shapegroup and a `to_world`.
    pub(super) fn instance(&mut self, o: &'t Obj) {
        let to_world = self.transform(o, "to_world").unwrap_or(DMat4::IDENTITY);
        let mut group = None;
        let mut refs = 0;
        for c in &o.children {
            let ChildKind::Ref(id) = &c.kind else {
                continue;
            };
            c.used.set(true);
            refs += 1;
            match self.ids.get(id.as_str()).copied() {
                Some(g) if g.tag == "shape" && g.kind == "shapegroup" => {
                    if group.is_some() {
                        self.error(c.at, format!("{} references more than one shapegroup", o.describe()));
                    }
                    group = Some(self.shapegroup(id, g));
                }
                Some(g) => self.error(
                    c.at,
                    format!("<ref id=\"{id}\"> names a {}, but an instance needs a <shape type=\"shapegroup\">", g.describe()),
                ),
                None => self.error(
                    c.at,
                    format!("<ref id=\"{id}\">: no shapegroup has this id"),
                ),
            }
        }
        self.finish(o);
        match group {
            Some(Some(members)) => {
                let to_world = Transform {
                    matrix: to_world.as_mat4(),
                };
                for (mesh, material) in members {
                    self.scene.add_instance(mesh, material, to_world);
                }
            }
            Some(None) => {}
            None if refs > 0 => {}
            None => self.error(
                o.at,
                format!("{} needs a <ref id=…> to a shapegroup", o.describe()),
            ),
        }
    }

    /// The meshes of shapegroup `g` (built once), not placed anywhere by themselves.
    fn shapegroup(&mut self, id: &str, g: &'t Obj) -> Option<Members> {
        if let Some(done) = self.groups.get(id) {
            return done.clone();
        }
        let mut members = Vec::new();
        let mut ok = true;
        for (index, c) in g.children.iter().enumerate() {
            let ChildKind::Obj(s) = &c.kind else {
                continue;
            };
            if s.tag != "shape" || matches!(s.kind.as_str(), "shapegroup" | "instance") {
                continue;
            }
            c.used.set(true);
            for (mesh, material) in self.shape_meshes(s, index) {
                if self.scene.material(material).is_emissive() {
                    self.error(
                        s.at,
                        format!(
                            "{} inside a shapegroup emits: instanced area lights are not supported",
                            s.describe()
                        ),
                    );
                    ok = false;
                }
                if !mesh.positions.iter().all(|p| p.is_finite()) {
                    ok = false;
                }
                members.push((self.scene.add_mesh(mesh), material));
            }
        }
        self.finish(g);
        let result = ok.then_some(members);
        self.groups.insert(id.to_string(), result.clone());
        result
    }
}
