//! Property elements: `<float>`, `<integer>`, `<boolean>`, `<string>`, `<rgb>`, `<spectrum>`,
//! `<point>`, `<vector>` (`<transform>` is in `transform.rs`).
use super::{Parser, Prop, Value};
use crate::mitsuba::spectrum;
use glam::DVec3;
use roxmltree::Node;
use std::cell::Cell;

impl Parser {
    pub(super) fn property(&mut self, el: Node) -> Option<Prop> {
        let tag = el.tag_name().name();
        let at = self.pos(el);
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
                self.pos(c),
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
            "spectrum" => self.spectrum(el, &name)?,
            "rgb" => {
                let text = self.required(el, "value")?;
                let nums = self.numbers(el, "value", &text)?;
                match nums.len() {
                    1 => Value::Rgb(DVec3::splat(nums[0])),
                    3 => Value::Rgb(DVec3::new(nums[0], nums[1], nums[2])),
                    n => {
                        self.error(
                            self.attr_at(el, "value"),
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
                            self.attr_at(el, "value"),
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
                            self.attr_at(el, "value"),
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
                            self.attr_at(el, "value"),
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

    pub(super) fn required(&mut self, el: Node, attr: &str) -> Option<String> {
        if el.attribute(attr).is_none() {
            self.error(
                self.pos(el),
                format!("<{}> needs a `{attr}` attribute", el.tag_name().name()),
            );
            return None;
        }
        self.attr(el, attr)
    }

    /// Numbers separated by commas and/or whitespace.
    pub(super) fn numbers(&mut self, el: Node, attr: &str, text: &str) -> Option<Vec<f64>> {
        let mut out = Vec::new();
        for tok in text
            .split(|c: char| c == ',' || c.is_whitespace())
            .filter(|t| !t.is_empty())
        {
            match tok.parse::<f64>() {
                Ok(x) if x.is_finite() => out.push(x),
                _ => {
                    self.error(
                        self.attr_at(el, attr),
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

    pub(super) fn vec3_attr(&mut self, el: Node, attr: &str) -> Option<DVec3> {
        let text = self.required(el, attr)?;
        let n = self.numbers(el, attr, &text)?;
        if n.len() != 3 {
            self.error(
                self.attr_at(el, attr),
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
    pub(super) fn xyz(&mut self, el: Node, default: f64) -> Option<DVec3> {
        let mut v = [default; 3];
        for (i, a) in ["x", "y", "z"].iter().enumerate() {
            if let Some(t) = self.attr(el, a) {
                let n = self.numbers(el, a, &t)?;
                if n.len() != 1 {
                    self.error(
                        self.attr_at(el, a),
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

    /// `<spectrum value="0.5">` (a constant), `value="400:0.1, 500:0.3, …"` or
    /// `filename="x.spd"`.
    fn spectrum(&mut self, el: Node, name: &str) -> Option<Value> {
        let pairs = match (el.attribute("value"), el.attribute("filename")) {
            (Some(_), Some(_)) | (None, None) => {
                self.error(
                    self.pos(el),
                    format!("<spectrum name=\"{name}\"> needs either `value` or `filename`"),
                );
                return None;
            }
            (Some(_), None) => {
                let text = self.required(el, "value")?;
                if !text.contains(':') {
                    let nums = self.numbers(el, "value", &text)?;
                    if nums.len() != 1 {
                        self.error(
                            self.attr_at(el, "value"),
                            format!(
                                "<spectrum name=\"{name}\"> needs one constant or wavelength:value pairs (got {} numbers)",
                                nums.len()
                            ),
                        );
                        return None;
                    }
                    return Some(Value::UniformSpectrum(nums[0]));
                }
                spectrum::parse_pairs(&text)
            }
            (None, Some(_)) => {
                let file = self.required(el, "filename")?;
                let path = self.sources.resolve(&file);
                match crate::read_input_text(&path) {
                    Ok(t)
                        if path
                            .extension()
                            .is_some_and(|e| e.eq_ignore_ascii_case("spd")) =>
                    {
                        spectrum::parse_spd(&t).map_err(|e| format!("{}: {e}", path.display()))
                    }
                    Ok(_) => Err(format!(
                        "{}: spectrum files must be .spd (wavelength value per line)",
                        path.display()
                    )),
                    Err(e) => Err(format!("cannot read spectrum file {}: {e}", path.display())),
                }
            }
        };
        match pairs.and_then(|p| spectrum::check(&p).map(|()| p)) {
            Ok(p) => Some(Value::Spectrum(p)),
            Err(e) => {
                self.error(self.pos(el), format!("<spectrum name=\"{name}\">: {e}"));
                None
            }
        }
    }
}
