//! Stage one: the XML document as a tree of plugin objects ([`Obj`]) with typed, located
//! properties. `$name` parameters are substituted here; nothing is interpreted yet (that is
//! `build.rs`, which also reports the properties no plugin asked for).
mod property;
mod transform;

use super::source::Sources;
use crate::diagnostic::Diagnostic;
use glam::{DMat4, DVec3};
use roxmltree::{Document, Node, ParsingOptions};
use std::cell::Cell;
use std::collections::HashMap;
use std::path::{Path, PathBuf};

/// Deepest nesting of objects (shape > bsdf > bsdf > texture…) a scene may use; real scenes
/// nest a handful.
const MAX_DEPTH: usize = 64;

/// Longest chain of `<include>`s (Mitsuba stops at 15).
pub(crate) const MAX_INCLUDE_DEPTH: usize = 16;

/// Where the elements of a document (or of an included one) go.
enum Target<'o> {
    /// The scene's top level.
    Top(&'o mut Vec<Obj>),
    /// Inside an object nested `depth` objects deep.
    Obj(&'o mut Obj, usize),
}

/// A typed property value, as the XML tag declared it.
#[derive(Clone, Debug, PartialEq)]
pub(crate) enum Value {
    Float(f64),
    Integer(i64),
    Boolean(bool),
    Str(String),
    Rgb(DVec3),
    /// `<spectrum value="v">`: one constant (its RGB depends on where it is used).
    UniformSpectrum(f64),
    /// `<spectrum>` as (wavelength in nm, value) pairs, from the attribute or a file.
    Spectrum(Vec<(f64, f64)>),
    Point(DVec3),
    Vector(DVec3),
    Transform(DMat4),
}

impl Value {
    pub(crate) fn tag(&self) -> &'static str {
        match self {
            Value::Float(_) => "float",
            Value::Integer(_) => "integer",
            Value::Boolean(_) => "boolean",
            Value::Str(_) => "string",
            Value::Rgb(_) => "rgb",
            Value::UniformSpectrum(_) | Value::Spectrum(_) => "spectrum",
            Value::Point(_) => "point",
            Value::Vector(_) => "vector",
            Value::Transform(_) => "transform",
        }
    }
}

/// One `<float name=… value=…/>`-like property.
#[derive(Debug)]
pub(crate) struct Prop {
    pub name: String,
    pub value: Value,
    /// Byte offset of the property element.
    pub at: usize,
    pub used: Cell<bool>,
}

/// A plugin instance: `<bsdf type="diffuse" id="white"> … </bsdf>`.
#[derive(Debug)]
pub(crate) struct Obj {
    /// Element name: `bsdf`, `shape`, `emitter`, `sensor`, `film`, …
    pub tag: String,
    /// The `type` attribute (after substitution).
    pub kind: String,
    pub id: Option<String>,
    /// The `name` attribute of a nested object (the parameter it fills), if any.
    pub name: Option<String>,
    /// Byte offset of the element's `<`.
    pub at: usize,
    pub props: Vec<Prop>,
    pub children: Vec<Child>,
}

impl Obj {
    /// `<bsdf type="diffuse">` (with the id when there is one), for messages.
    pub(crate) fn describe(&self) -> String {
        match &self.id {
            Some(id) => format!("<{} type=\"{}\" id=\"{id}\">", self.tag, self.kind),
            None => format!("<{} type=\"{}\">", self.tag, self.kind),
        }
    }
}

#[derive(Debug)]
pub(crate) enum ChildKind {
    Obj(Obj),
    /// `<ref id=…/>`.
    Ref(String),
}

/// A nested object or a reference to a top-level one.
#[derive(Debug)]
pub(crate) struct Child {
    pub kind: ChildKind,
    /// The `name` attribute (which parameter it fills), if any.
    pub name: Option<String>,
    pub at: usize,
    pub used: Cell<bool>,
}

/// `<alias id="from" as="to"/>`: `to` names the same object as `from`.
pub(crate) struct Alias {
    pub from: String,
    pub to: String,
    pub at: usize,
}

/// The parsed scene: top-level objects in document order (included files' in place of their
/// `<include>`), and the aliases.
pub(crate) struct Doc {
    pub objects: Vec<Obj>,
    pub aliases: Vec<Alias>,
}

const OBJECT_TAGS: &[&str] = &[
    "bsdf",
    "shape",
    "emitter",
    "sensor",
    "film",
    "sampler",
    "integrator",
    "rfilter",
    "texture",
    "medium",
    "phase",
    "volume",
];
const PROPERTY_TAGS: &[&str] = &[
    "float",
    "integer",
    "boolean",
    "string",
    "rgb",
    "spectrum",
    "point",
    "vector",
    "transform",
];

pub(crate) struct Parser {
    pub sources: Sources,
    /// `$name` → value: caller overrides first, then `<default>`s.
    params: HashMap<String, String>,
    pub diags: Vec<Diagnostic>,
    /// Offset of the document being read in `sources`.
    base: usize,
    /// The files being read, the main one first: the chain of `<include>`s.
    stack: Vec<PathBuf>,
    aliases: Vec<Alias>,
}

impl Parser {
    pub(crate) fn new(sources: Sources, overrides: &[(&str, &str)]) -> Self {
        Parser {
            sources,
            params: overrides
                .iter()
                .map(|(k, v)| (k.to_string(), v.to_string()))
                .collect(),
            diags: Vec::new(),
            base: 0,
            stack: Vec::new(),
            aliases: Vec::new(),
        }
    }

    fn error(&mut self, at: usize, msg: impl Into<String>) {
        let d = self.sources.error(at, msg);
        self.diags.push(d);
    }

    /// The offset of a node of the document being read.
    fn pos(&self, n: Node) -> usize {
        self.base + n.range().start
    }

    /// Offset of an attribute (of its name), or of the element when it is absent.
    fn attr_at(&self, el: Node, name: &str) -> usize {
        el.attributes()
            .find(|a| a.name() == name)
            .map_or(self.pos(el), |a| self.base + a.range().start)
    }

    /// Parses the main file (`text`) and everything it includes. `None` only when the main
    /// file's XML itself is malformed or its root is not `<scene>`; every other problem is a
    /// diagnostic and the element is skipped.
    pub(crate) fn parse(&mut self, text: &str) -> Option<Doc> {
        let mut objects = Vec::new();
        self.stack.push(canonical(self.sources.main()));
        let ok = self.document(text, &mut Target::Top(&mut objects));
        self.stack.pop();
        ok.then(|| Doc {
            objects,
            aliases: std::mem::take(&mut self.aliases),
        })
    }

    /// One file's elements into `target`; `false` when it is not a scene file at all.
    fn document(&mut self, text: &str, target: &mut Target) -> bool {
        let opts = ParsingOptions {
            allow_dtd: false,
            ..ParsingOptions::default()
        };
        let doc = match Document::parse_with_options(text, opts) {
            Ok(d) => d,
            Err(e) => {
                let pos = e.pos();
                self.diags.push(Diagnostic {
                    severity: crate::Severity::Error,
                    file: self.sources.path_at(self.base).to_path_buf(),
                    line: pos.row as usize,
                    col: pos.col as usize,
                    message: format!("malformed XML: {e}"),
                });
                return false;
            }
        };
        let root = doc.root_element();
        if root.tag_name().name() != "scene" {
            self.error(
                self.pos(root),
                format!(
                    "the root element is <{}>, expected <scene version=\"3.0.0\">",
                    root.tag_name().name()
                ),
            );
            return false;
        }
        self.check_attrs(root, &["version"]);
        self.check_version(root);
        // `<default>`s first, so that `$name` works anywhere in the file.
        for el in root.children().filter(|n| n.is_element()) {
            if el.tag_name().name() == "default" {
                self.check_attrs(el, &["name", "value"]);
                match (el.attribute("name"), el.attribute("value")) {
                    (Some(n), Some(v)) => {
                        self.params
                            .entry(n.to_string())
                            .or_insert_with(|| v.to_string());
                    }
                    _ => self.error(
                        self.pos(el),
                        "<default> needs both `name` and `value` attributes",
                    ),
                }
            }
        }
        for el in root.children() {
            match target {
                Target::Top(objects) => {
                    if el.is_element() {
                        self.top_level(el, objects);
                    }
                }
                Target::Obj(obj, depth) => self.object_child(el, obj, *depth),
            }
        }
        true
    }

    fn check_version(&mut self, root: Node) {
        match root.attribute("version") {
            None => self.error(
                self.pos(root),
                "<scene> needs a version attribute (e.g. version=\"3.0.0\")",
            ),
            Some(v) => {
                let major = v
                    .split('.')
                    .next()
                    .and_then(|m| m.trim().parse::<u32>().ok());
                if major.is_none_or(|m| m < 2) {
                    let at = self.attr_at(root, "version");
                    self.error(
                        at,
                        format!(
                            "scene version=\"{v}\" is not supported: eyeadapt reads the Mitsuba 2/3 format (version 2.0.0 or later), whose parameter names differ from Mitsuba 0.x"
                        ),
                    );
                }
            }
        }
    }

    /// A child element of `<scene>`.
    fn top_level(&mut self, el: Node, objects: &mut Vec<Obj>) {
        let tag = el.tag_name().name();
        match tag {
            "default" => {}
            "include" => self.include(el, &mut Target::Top(objects)),
            "path" => self.path(el),
            "alias" => self.alias(el),
            _ if is_object(el) => objects.extend(self.object(el, true, 0)),
            _ if PROPERTY_TAGS.contains(&tag) => self.error(
                self.pos(el),
                format!("<{tag}> at the top level of <scene>: properties belong inside a plugin"),
            ),
            "ref" => self.error(
                self.pos(el),
                "<ref> at the top level of <scene> references nothing",
            ),
            _ => self.error(self.pos(el), format!("unknown element <{tag}>")),
        }
    }

    /// `<include filename=…/>`: the included file's elements take its place. The name is
    /// looked up from the including file's folder first, then as any other file name.
    fn include(&mut self, el: Node, target: &mut Target) {
        self.check_attrs(el, &["filename", "name"]);
        let at = self.pos(el);
        let Some(name) = self.required(el, "filename") else {
            return;
        };
        let path = self.sources.resolve_from(at, &name);
        let key = canonical(&path);
        if let Some(i) = self.stack.iter().position(|p| *p == key) {
            let chain: Vec<String> = self.stack[i..]
                .iter()
                .chain([&key])
                .map(|p| p.display().to_string())
                .collect();
            self.error(
                at,
                format!("cyclic <include>: {}", chain.join(" includes ")),
            );
            return;
        }
        if self.stack.len() > MAX_INCLUDE_DEPTH {
            self.error(
                at,
                format!(
                    "<include filename=\"{name}\"> is nested more than {MAX_INCLUDE_DEPTH} includes deep"
                ),
            );
            return;
        }
        let text = match crate::read_input(&path) {
            Ok(bytes) => match String::from_utf8(bytes) {
                Ok(t) => t,
                Err(_) => {
                    self.error(
                        at,
                        format!("included file {} is not UTF-8 text", path.display()),
                    );
                    return;
                }
            },
            Err(e) => {
                self.error(
                    at,
                    format!("cannot read included file {}: {e}", path.display()),
                );
                return;
            }
        };
        let outer = self.base;
        self.base = self.sources.add(&path, &text);
        self.stack.push(key);
        self.document(&text, target);
        self.stack.pop();
        self.base = outer;
    }

    /// `<path value=…/>`: one more folder where file names are looked up, relative to the
    /// file that names it.
    fn path(&mut self, el: Node) {
        self.check_attrs(el, &["value"]);
        let Some(value) = self.required(el, "value") else {
            return;
        };
        let at = self.pos(el);
        // The declaring file's folder first, then those of the files including it (Mitsuba's
        // resolver holds them while an include is read), then the main file's search path.
        let here = self.sources.path_at(at).to_path_buf();
        let dir = std::iter::once(here.as_path())
            .chain(self.stack.iter().rev().map(PathBuf::as_path))
            .map(|f| f.parent().unwrap_or(Path::new(".")).join(&value))
            .find(|d| d.is_dir())
            .unwrap_or_else(|| self.sources.resolve(&value));
        if dir.is_dir() {
            self.sources.add_search_folder(dir);
        } else {
            self.error(
                at,
                format!(
                    "<path value=\"{value}\">: folder {} not found",
                    dir.display()
                ),
            );
        }
    }

    fn alias(&mut self, el: Node) {
        self.check_attrs(el, &["id", "as"]);
        let (Some(from), Some(to)) = (self.required(el, "id"), self.required(el, "as")) else {
            return;
        };
        self.aliases.push(Alias {
            from,
            to,
            at: self.pos(el),
        });
    }

    /// Reports attributes outside `allowed`.
    fn check_attrs(&mut self, el: Node, allowed: &[&str]) {
        for a in el.attributes() {
            if !allowed.contains(&a.name()) {
                self.error(
                    self.base + a.range().start,
                    format!(
                        "unknown attribute `{}` on <{}>",
                        a.name(),
                        el.tag_name().name()
                    ),
                );
            }
        }
    }

    /// An attribute's value with `$name` parameters substituted.
    fn attr(&mut self, el: Node, name: &str) -> Option<String> {
        let raw = el.attribute(name)?;
        if !raw.contains('$') {
            return Some(raw.to_string());
        }
        let mut out = String::with_capacity(raw.len());
        let mut rest = raw;
        while let Some(i) = rest.find('$') {
            out.push_str(&rest[..i]);
            let after = &rest[i + 1..];
            let len = after
                .char_indices()
                .find(|(_, c)| !(c.is_ascii_alphanumeric() || *c == '_'))
                .map_or(after.len(), |(j, _)| j);
            let key = &after[..len];
            match self.params.get(key) {
                Some(v) if !key.is_empty() => out.push_str(v),
                _ => {
                    self.error(
                        self.attr_at(el, name),
                        format!(
                            "attribute `{name}` of <{}> uses the parameter `${key}`, which has no <default name=\"{key}\" …> and was not given by the caller",
                            el.tag_name().name()
                        ),
                    );
                    return None;
                }
            }
            rest = &after[len..];
        }
        out.push_str(rest);
        Some(out)
    }

    /// `depth` counts the objects around `el`; past [`MAX_DEPTH`] the subtree is an error
    /// (the recursion overflowed the stack on about 10 000 nested elements).
    fn object(&mut self, el: Node, top_level: bool, depth: usize) -> Option<Obj> {
        let tag = el.tag_name().name().to_string();
        let at = self.pos(el);
        if depth >= MAX_DEPTH {
            self.error(
                at,
                format!("<{tag}> is nested more than {MAX_DEPTH} objects deep"),
            );
            return None;
        }
        self.check_attrs(el, &["type", "id", "name"]);
        let Some(kind) = self.attr(el, "type") else {
            if el.attribute("type").is_none() {
                self.error(at, format!("<{tag}> needs a `type` attribute"));
            }
            return None;
        };
        let id = self.attr(el, "id");
        let name = self.attr(el, "name");
        if top_level && name.is_some() {
            self.error(
                self.attr_at(el, "name"),
                format!("top-level <{tag}> cannot have a `name` (give it an `id` instead)"),
            );
        }
        let mut obj = Obj {
            tag,
            kind,
            id,
            name,
            at,
            props: Vec::new(),
            children: Vec::new(),
        };
        for c in el.children() {
            self.object_child(c, &mut obj, depth);
        }
        Some(obj)
    }

    /// A node inside `obj`, which is nested `depth` objects deep.
    fn object_child(&mut self, c: Node, obj: &mut Obj, depth: usize) {
        if c.is_text() {
            if c.text().is_some_and(|t| !t.trim().is_empty()) {
                self.error(self.pos(c), format!("unexpected text inside <{}>", obj.tag));
            }
            return;
        }
        if !c.is_element() {
            return;
        }
        let ctag = c.tag_name().name();
        let cat = self.pos(c);
        if is_object(c) {
            if let Some(child) = self.object(c, false, depth + 1) {
                let name = child.name.clone();
                obj.children.push(Child {
                    kind: ChildKind::Obj(child),
                    name,
                    at: cat,
                    used: Cell::new(false),
                });
            }
        } else if PROPERTY_TAGS.contains(&ctag) {
            if let Some(p) = self.property(c) {
                if obj.props.iter().any(|q| q.name == p.name) {
                    self.error(
                        cat,
                        format!(
                            "parameter `{}` of <{} type=\"{}\"> is given twice",
                            p.name, obj.tag, obj.kind
                        ),
                    );
                } else {
                    obj.props.push(p);
                }
            }
        } else if ctag == "ref" {
            self.check_attrs(c, &["id", "name"]);
            match self.attr(c, "id") {
                Some(id) => {
                    let name = self.attr(c, "name");
                    obj.children.push(Child {
                        kind: ChildKind::Ref(id),
                        name,
                        at: cat,
                        used: Cell::new(false),
                    });
                }
                None => {
                    if c.attribute("id").is_none() {
                        self.error(cat, "<ref> needs an `id` attribute");
                    }
                }
            }
        } else if ctag == "include" {
            self.include(c, &mut Target::Obj(obj, depth));
        } else {
            let msg = match ctag {
                "path" | "alias" | "default" => {
                    format!("<{ctag}> belongs at the top level of <scene>, not inside a plugin")
                }
                _ => format!("unknown element <{ctag}>"),
            };
            self.error(cat, msg);
        }
    }
}

fn is_object(el: Node) -> bool {
    let tag = el.tag_name().name();
    OBJECT_TAGS.contains(&tag) || (tag == "spectrum" && el.attribute("type").is_some())
}

/// A path's canonical form where it exists (so that `a/../b.xml` and `b.xml` are one file).
fn canonical(p: &Path) -> PathBuf {
    p.canonicalize().unwrap_or_else(|_| p.to_path_buf())
}
