//! Typed parameter access: every accessor marks what it reads as used, and
//! [`Builder::finish`] reports what no plugin read.
use super::Builder;
use crate::Rgb;
use crate::mitsuba::spectrum;
use crate::mitsuba::xml::{ChildKind, Obj, Prop, Value};
use glam::{DMat4, DVec3};

impl<'t> Builder<'t> {
    pub(super) fn prop<'o>(&self, o: &'o Obj, name: &str) -> Option<&'o Prop> {
        let p = o.props.iter().find(|p| p.name == name)?;
        p.used.set(true);
        Some(p)
    }

    pub(super) fn wrong_type(&mut self, o: &Obj, p: &Prop, want: &str) {
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

    pub(super) fn float(&mut self, o: &Obj, name: &str) -> Option<f64> {
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
    pub(super) fn float_in(
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

    pub(super) fn int(&mut self, o: &Obj, name: &str) -> Option<(i64, usize)> {
        let p = self.prop(o, name)?;
        match &p.value {
            Value::Integer(i) => Some((*i, p.at)),
            _ => {
                self.wrong_type(o, p, "an <integer>");
                None
            }
        }
    }

    pub(super) fn boolean(&mut self, o: &Obj, name: &str) -> Option<bool> {
        let p = self.prop(o, name)?;
        match &p.value {
            Value::Boolean(b) => Some(*b),
            _ => {
                self.wrong_type(o, p, "a <boolean>");
                None
            }
        }
    }

    pub(super) fn string<'o>(&mut self, o: &'o Obj, name: &str) -> Option<(&'o str, usize)> {
        let p = self.prop(o, name)?;
        match &p.value {
            Value::Str(s) => Some((s.as_str(), p.at)),
            _ => {
                self.wrong_type(o, p, "a <string>");
                None
            }
        }
    }

    pub(super) fn point(&mut self, o: &Obj, name: &str) -> Option<DVec3> {
        let p = self.prop(o, name)?;
        match &p.value {
            Value::Point(v) | Value::Vector(v) => Some(*v),
            _ => {
                self.wrong_type(o, p, "a <point>");
                None
            }
        }
    }

    pub(super) fn transform(&mut self, o: &Obj, name: &str) -> Option<DMat4> {
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
    pub(super) fn single_precision(&mut self, ok: bool, o: &Obj) {
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
    pub(super) fn colour(&mut self, o: &'t Obj, name: &str) -> Option<Rgb> {
        if let Some(p) = self.prop(o, name) {
            let c = match &p.value {
                Value::Rgb(c) => *c,
                // As Mitsuba's RGB variants: the colour of a spectrum depends on whether it
                // is emitted (`spectrum.rs`).
                Value::UniformSpectrum(v) if o.tag == "emitter" => spectrum::uniform_emitter(*v),
                Value::UniformSpectrum(v) => DVec3::splat(*v),
                // A conductor's complex IOR is unbounded (Mitsuba clamps it at 0 only).
                Value::Spectrum(pairs) if o.tag == "bsdf" && matches!(name, "eta" | "k") => {
                    spectrum::to_srgb_unbounded(pairs)
                }
                Value::Spectrum(pairs) => spectrum::to_srgb(pairs, o.tag == "emitter"),
                Value::Float(x) => DVec3::splat(*x),
                Value::Integer(i) => DVec3::splat(*i as f64),
                _ => {
                    self.wrong_type(o, p, "an <rgb>, <spectrum> or <float>");
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
    /// A texture where eyeadapt takes constants only (or with nothing to fill).
    pub(super) fn texture(&mut self, t: &Obj) {
        self.error(
            t.at,
            format!(
                "unsupported {} here: eyeadapt takes textures for reflectances and roughness only (use a constant <rgb> or <float>)",
                t.describe()
            ),
        );
    }

    pub(super) fn resolve(&mut self, id: &str, at: usize) -> Option<&'t Obj> {
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
    pub(super) fn finish(&mut self, o: &Obj) {
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
}
