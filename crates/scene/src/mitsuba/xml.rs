//! Stage one: the XML document as a tree of plugin objects ([`Obj`]) with typed, located
//! properties. `$name` parameters are substituted here; nothing is interpreted yet (that is
//! `build.rs`, which also reports the properties no plugin asked for).
use crate::diagnostic::{Diagnostic, SourceMap};
use glam::{DMat3, DMat4, DVec3, DVec4};
use roxmltree::{Document, Node, ParsingOptions};
use std::cell::Cell;
use std::collections::HashMap;

/// Deepest nesting of objects (shape > bsdf > bsdf > texture…) a scene may use; real scenes
/// nest a handful.
const MAX_DEPTH: usize = 64;

/// A typed property value, as the XML tag declared it.
#[derive(Clone, Debug, PartialEq)]
pub(crate) enum Value {
    Float(f64),
    Integer(i64),
    Boolean(bool),
    Str(String),
    /// `<rgb>` or a constant `<spectrum>`.
    Rgb(DVec3),
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

/// The parsed document: top-level objects in document order.
pub(crate) struct Doc {
    pub objects: Vec<Obj>,
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

pub(crate) struct Parser<'a> {
    pub map: &'a SourceMap<'a>,
    /// `$name` → value: caller overrides first, then `<default>`s.
    params: HashMap<String, String>,
    pub diags: Vec<Diagnostic>,
}

impl<'a> Parser<'a> {
    pub(crate) fn new(map: &'a SourceMap<'a>, overrides: &[(&str, &str)]) -> Self {
        Parser {
            map,
            params: overrides
                .iter()
                .map(|(k, v)| (k.to_string(), v.to_string()))
                .collect(),
            diags: Vec::new(),
        }
    }

    fn error(&mut self, at: usize, msg: impl Into<String>) {
        let d = self.map.error(at, msg);
        self.diags.push(d);
    }

    /// Parses the whole document. `None` only when the XML itself is malformed or the root is
    /// not `<scene>`; every other problem is a diagnostic and the element is skipped.
    pub(crate) fn parse(&mut self, text: &str) -> Option<Doc> {
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
                    file: self.map.file.to_path_buf(),
                    line: pos.row as usize,
                    col: pos.col as usize,
                    message: format!("malformed XML: {e}"),
                });
                return None;
            }
        };
        let root = doc.root_element();
        if root.tag_name().name() != "scene" {
            self.error(
                root.range().start,
                format!(
                    "the root element is <{}>, expected <scene version=\"3.0.0\">",
                    root.tag_name().name()
                ),
            );
            return None;
        }
        self.check_attrs(root, &["version"]);
        match root.attribute("version") {
            None => self.error(
                root.range().start,
                "<scene> needs a version attribute (e.g. version=\"3.0.0\")",
            ),
            Some(v) => {
                let major = v
                    .split('.')
                    .next()
                    .and_then(|m| m.trim().parse::<u32>().ok());
                match major {
                    Some(m) if m >= 2 => {}
                    _ => {
                        let at = attr_at(root, "version");
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
                        el.range().start,
                        "<default> needs both `name` and `value` attributes",
                    ),
                }
            }
        }
        let mut objects = Vec::new();
        for el in root.children().filter(|n| n.is_element()) {
            let tag = el.tag_name().name();
            if tag == "default" {
                continue;
            }
            if is_object(el) {
                if let Some(o) = self.object(el, true, 0) {
                    objects.push(o);
                }
            } else if PROPERTY_TAGS.contains(&tag) {
                self.error(
                    el.range().start,
                    format!(
                        "<{tag}> at the top level of <scene>: properties belong inside a plugin"
                    ),
                );
            } else {
                self.other_element(el);
            }
        }
        Some(Doc { objects })
    }

    /// Elements that are neither objects nor properties.
    fn other_element(&mut self, el: Node) {
        let tag = el.tag_name().name();
        let at = el.range().start;
        let msg = match tag {
            "include" => format!(
                "unsupported element <include{}>: eyeadapt reads one self-contained XML file (paste the included file's content instead)",
                el.attribute("filename")
                    .map(|f| format!(" filename=\"{f}\""))
                    .unwrap_or_default()
            ),
            "alias" | "path" | "default" => {
                format!("unsupported element <{tag}> here: eyeadapt does not implement it")
            }
            "ref" => "<ref> at the top level of <scene> references nothing".to_string(),
            _ => format!("unknown element <{tag}>"),
        };
        self.error(at, msg);
    }

    /// Reports attributes outside `allowed`.
    fn check_attrs(&mut self, el: Node, allowed: &[&str]) {
        for a in el.attributes() {
            if !allowed.contains(&a.name()) {
                self.error(
                    a.range().start,
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
                        attr_at(el, name),
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
        let at = el.range().start;
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
                attr_at(el, "name"),
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
            if c.is_text() {
                if c.text().is_some_and(|t| !t.trim().is_empty()) {
                    self.error(
                        c.range().start,
                        format!("unexpected text inside <{}>", obj.tag),
                    );
                }
                continue;
            }
            if !c.is_element() {
                continue;
            }
            let ctag = c.tag_name().name();
            let cat = c.range().start;
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
            } else {
                self.other_element(c);
            }
        }
        Some(obj)
    }

    fn property(&mut self, el: Node) -> Option<Prop> {
        let tag = el.tag_name().name();
        let at = el.range().start;
        let allowed: &[&str] = match tag {
            "point" | "vector" => &["name", "value", "x", "y", "z"],
            "spectrum" => &["name", "value", "filename"],
            "transform" => &["name"],
            _ => &["name", "value"],
        };
        self.check_attrs(el, allowed);
        let Some(name) = self.attr(el, "name") else {
            if el.attribute("name").is_none() {
                self.error(at, format!("<{tag}> needs a `name` attribute"));
            }
            return None;
        };
        if tag != "transform"
            && let Some(c) = el.children().find(|c| c.is_element())
        {
            self.error(
                c.range().start,
                format!("unexpected <{}> inside <{tag}>", c.tag_name().name()),
            );
        }
        let value = match tag {
            "transform" => Value::Transform(self.transform(el)?),
            "point" | "vector" => {
                let v = if el.attribute("value").is_some() {
                    if ["x", "y", "z"].iter().any(|a| el.attribute(*a).is_some()) {
                        self.error(
                            at,
                            format!("<{tag}> takes either `value` or `x`/`y`/`z`, not both"),
                        );
                    }
                    self.vec3_attr(el, "value")?
                } else {
                    self.xyz(el, 0.0)?
                };
                if tag == "point" {
                    Value::Point(v)
                } else {
                    Value::Vector(v)
                }
            }
            "spectrum" => {
                if el.attribute("filename").is_some() {
                    self.error(
                        attr_at(el, "filename"),
                        format!("unsupported <spectrum name=\"{name}\" filename=…>: eyeadapt renders in RGB; give an <rgb> value instead"),
                    );
                    return None;
                }
                let text = self.required(el, "value")?;
                if text.contains(':') {
                    self.error(
                        attr_at(el, "value"),
                        format!("unsupported <spectrum name=\"{name}\"> given as wavelength:value pairs: eyeadapt renders in RGB; give an <rgb> value or a single constant instead"),
                    );
                    return None;
                }
                let nums = self.numbers(el, "value", &text)?;
                if nums.len() != 1 {
                    self.error(
                        attr_at(el, "value"),
                        format!(
                            "<spectrum name=\"{name}\"> must be one constant number (got {})",
                            nums.len()
                        ),
                    );
                    return None;
                }
                Value::Rgb(DVec3::splat(nums[0]))
            }
            "rgb" => {
                let text = self.required(el, "value")?;
                let nums = self.numbers(el, "value", &text)?;
                match nums.len() {
                    1 => Value::Rgb(DVec3::splat(nums[0])),
                    3 => Value::Rgb(DVec3::new(nums[0], nums[1], nums[2])),
                    n => {
                        self.error(
                            attr_at(el, "value"),
                            format!("<rgb name=\"{name}\"> needs 1 or 3 numbers, got {n}"),
                        );
                        return None;
                    }
                }
            }
            "float" => {
                let text = self.required(el, "value")?;
                match text.trim().parse::<f64>() {
                    Ok(x) if x.is_finite() => Value::Float(x),
                    _ => {
                        self.error(
                            attr_at(el, "value"),
                            format!(
                                "<float name=\"{name}\"> value \"{text}\" is not a finite number"
                            ),
                        );
                        return None;
                    }
                }
            }
            "integer" => {
                let text = self.required(el, "value")?;
                match text.trim().parse::<i64>() {
                    Ok(x) => Value::Integer(x),
                    Err(_) => {
                        self.error(
                            attr_at(el, "value"),
                            format!("<integer name=\"{name}\"> value \"{text}\" is not an integer"),
                        );
                        return None;
                    }
                }
            }
            "boolean" => {
                let text = self.required(el, "value")?;
                match text.trim().to_ascii_lowercase().as_str() {
                    "true" => Value::Boolean(true),
                    "false" => Value::Boolean(false),
                    _ => {
                        self.error(
                            attr_at(el, "value"),
                            format!(
                                "<boolean name=\"{name}\"> value \"{text}\" must be true or false"
                            ),
                        );
                        return None;
                    }
                }
            }
            _ => Value::Str(self.required(el, "value")?),
        };
        Some(Prop {
            name,
            value,
            at,
            used: Cell::new(false),
        })
    }

    fn required(&mut self, el: Node, attr: &str) -> Option<String> {
        if el.attribute(attr).is_none() {
            self.error(
                el.range().start,
                format!("<{}> needs a `{attr}` attribute", el.tag_name().name()),
            );
            return None;
        }
        self.attr(el, attr)
    }

    /// Numbers separated by commas and/or whitespace.
    fn numbers(&mut self, el: Node, attr: &str, text: &str) -> Option<Vec<f64>> {
        let mut out = Vec::new();
        for tok in text
            .split(|c: char| c == ',' || c.is_whitespace())
            .filter(|t| !t.is_empty())
        {
            match tok.parse::<f64>() {
                Ok(x) if x.is_finite() => out.push(x),
                _ => {
                    self.error(
                        attr_at(el, attr),
                        format!(
                            "attribute `{attr}` of <{}>: \"{tok}\" is not a finite number",
                            el.tag_name().name()
                        ),
                    );
                    return None;
                }
            }
        }
        Some(out)
    }

    fn vec3_attr(&mut self, el: Node, attr: &str) -> Option<DVec3> {
        let text = self.required(el, attr)?;
        let n = self.numbers(el, attr, &text)?;
        if n.len() != 3 {
            self.error(
                attr_at(el, attr),
                format!(
                    "attribute `{attr}` of <{}> needs 3 numbers, got {}",
                    el.tag_name().name(),
                    n.len()
                ),
            );
            return None;
        }
        Some(DVec3::new(n[0], n[1], n[2]))
    }

    /// `x`, `y`, `z` attributes, each defaulting to `default`.
    fn xyz(&mut self, el: Node, default: f64) -> Option<DVec3> {
        let mut v = [default; 3];
        for (i, a) in ["x", "y", "z"].iter().enumerate() {
            if let Some(t) = self.attr(el, a) {
                let n = self.numbers(el, a, &t)?;
                if n.len() != 1 {
                    self.error(
                        attr_at(el, a),
                        format!(
                            "attribute `{a}` of <{}> must be one number",
                            el.tag_name().name()
                        ),
                    );
                    return None;
                }
                v[i] = n[0];
            } else if el.attribute(*a).is_some() {
                return None;
            }
        }
        Some(DVec3::from_array(v))
    }

    /// `<transform>`: each operation is applied after the previous ones (left-multiplied),
    /// as in Mitsuba.
    fn transform(&mut self, el: Node) -> Option<DMat4> {
        let mut m = DMat4::IDENTITY;
        let mut ok = true;
        for op in el.children() {
            if op.is_text() {
                if op.text().is_some_and(|t| !t.trim().is_empty()) {
                    self.error(op.range().start, "unexpected text inside <transform>");
                    ok = false;
                }
                continue;
            }
            if !op.is_element() {
                continue;
            }
            match self.transform_op(op) {
                Some(t) => m = t * m,
                None => ok = false,
            }
        }
        if !ok {
            return None;
        }
        if !m.is_finite() {
            self.error(el.range().start, "<transform> is not finite");
            return None;
        }
        Some(m)
    }

    fn transform_op(&mut self, op: Node) -> Option<DMat4> {
        let tag = op.tag_name().name();
        let at = op.range().start;
        let value_or_xyz = |p: &mut Self, default: f64| -> Option<DVec3> {
            if op.attribute("value").is_some() {
                p.vec3_attr(op, "value")
            } else {
                p.xyz(op, default)
            }
        };
        match tag {
            "translate" => {
                self.check_attrs(op, &["value", "x", "y", "z"]);
                Some(DMat4::from_translation(value_or_xyz(self, 0.0)?))
            }
            "scale" => {
                self.check_attrs(op, &["value", "x", "y", "z"]);
                let s = if op.attribute("value").is_some() {
                    let t = self.attr(op, "value")?;
                    let n = self.numbers(op, "value", &t)?;
                    match n.len() {
                        1 => DVec3::splat(n[0]),
                        3 => DVec3::new(n[0], n[1], n[2]),
                        k => {
                            self.error(
                                attr_at(op, "value"),
                                format!("<scale> value needs 1 or 3 numbers, got {k}"),
                            );
                            return None;
                        }
                    }
                } else {
                    self.xyz(op, 1.0)?
                };
                if s.abs().min_element() < 1e-12 {
                    self.error(at, format!("<scale> by {s:?} is singular"));
                    return None;
                }
                Some(DMat4::from_scale(s))
            }
            "rotate" => {
                self.check_attrs(op, &["value", "x", "y", "z", "angle"]);
                let axis = value_or_xyz(self, 0.0)?;
                let angle = self.required(op, "angle")?;
                let a = self.numbers(op, "angle", &angle)?;
                if a.len() != 1 {
                    self.error(attr_at(op, "angle"), "<rotate> angle must be one number");
                    return None;
                }
                if axis.length() < 1e-12 {
                    self.error(at, "<rotate> needs a non-zero axis");
                    return None;
                }
                Some(DMat4::from_axis_angle(axis.normalize(), a[0].to_radians()))
            }
            "matrix" => {
                self.check_attrs(op, &["value"]);
                let t = self.required(op, "value")?;
                let n = self.numbers(op, "value", &t)?;
                let m = match n.len() {
                    // Row-major in the file; glam is column-major.
                    16 => DMat4::from_cols_slice(&n).transpose(),
                    9 => DMat4::from_mat3(DMat3::from_cols_slice(&n).transpose()),
                    k => {
                        self.error(
                            attr_at(op, "value"),
                            format!("<matrix> needs 16 (4×4) or 9 (3×3) numbers, got {k}"),
                        );
                        return None;
                    }
                };
                if m.row(3) != DVec4::W {
                    self.error(
                        at,
                        "<matrix> has a projective last row: only affine transforms are supported",
                    );
                    return None;
                }
                if m.determinant().abs() < 1e-12 {
                    self.error(at, "<matrix> is singular");
                    return None;
                }
                Some(m)
            }
            "lookat" => {
                self.check_attrs(op, &["origin", "target", "up"]);
                let origin = self.vec3_attr(op, "origin")?;
                let target = self.vec3_attr(op, "target")?;
                let up = if op.attribute("up").is_some() {
                    Some(self.vec3_attr(op, "up")?)
                } else {
                    None
                };
                let dir = target - origin;
                if dir.length() < 1e-12 {
                    self.error(at, "<lookat> target equals origin: no view direction");
                    return None;
                }
                let dir = dir.normalize();
                let up = up.unwrap_or_else(|| dir.any_orthonormal_vector());
                let left = up.cross(dir);
                if left.length() < 1e-9 {
                    self.error(
                        attr_at(op, "up"),
                        "<lookat> up is parallel to the view direction (or zero)",
                    );
                    return None;
                }
                let left = left.normalize();
                let new_up = dir.cross(left);
                Some(DMat4::from_cols(
                    left.extend(0.0),
                    new_up.extend(0.0),
                    dir.extend(0.0),
                    origin.extend(1.0),
                ))
            }
            other => {
                self.error(
                    at,
                    format!("unknown transform operation <{other}> (expected translate, rotate, scale, matrix or lookat)"),
                );
                None
            }
        }
    }
}

fn is_object(el: Node) -> bool {
    let tag = el.tag_name().name();
    OBJECT_TAGS.contains(&tag) || (tag == "spectrum" && el.attribute("type").is_some())
}

/// Byte offset of an attribute (of its name), or of the element when it is absent.
fn attr_at(el: Node, name: &str) -> usize {
    el.attributes()
        .find(|a| a.name() == name)
        .map_or(el.range().start, |a| a.range().start)
}
