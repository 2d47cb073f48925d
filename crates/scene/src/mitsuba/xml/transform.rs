//! `<transform>` and its operations (translate, rotate, scale, matrix, lookat).
use super::Parser;
use glam::{DMat3, DMat4, DVec3, DVec4};
use roxmltree::Node;

impl Parser {
    /// `<transform>`: each operation is applied after the previous ones (left-multiplied),
    /// as in Mitsuba.
    pub(super) fn transform(&mut self, el: Node) -> Option<DMat4> {
        let mut m = DMat4::IDENTITY;
        let mut ok = true;
        for op in el.children() {
            if op.is_text() {
                if op.text().is_some_and(|t| !t.trim().is_empty()) {
                    self.error(self.pos(op), "unexpected text inside <transform>");
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
            self.error(self.pos(el), "<transform> is not finite");
            return None;
        }
        Some(m)
    }

    fn transform_op(&mut self, op: Node) -> Option<DMat4> {
        let tag = op.tag_name().name();
        let at = self.pos(op);
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
            "scale" => self.scale_op(op, at),
            "rotate" => {
                self.check_attrs(op, &["value", "x", "y", "z", "angle"]);
                let axis = value_or_xyz(self, 0.0)?;
                let angle = self.required(op, "angle")?;
                let a = self.numbers(op, "angle", &angle)?;
                if a.len() != 1 {
                    self.error(
                        self.attr_at(op, "angle"),
                        "<rotate> angle must be one number",
                    );
                    return None;
                }
                if axis.length() < 1e-12 {
                    self.error(at, "<rotate> needs a non-zero axis");
                    return None;
                }
                Some(DMat4::from_axis_angle(axis.normalize(), a[0].to_radians()))
            }
            "matrix" => self.matrix_op(op, at),
            "lookat" => self.lookat_op(op, at),
            other => {
                self.error(
                    at,
                    format!("unknown transform operation <{other}> (expected translate, rotate, scale, matrix or lookat)"),
                );
                None
            }
        }
    }

    /// `<scale value="s">`, `value="x, y, z"` or `x=… y=… z=…`; singular scales are errors.
    fn scale_op(&mut self, op: Node, at: usize) -> Option<DMat4> {
        self.check_attrs(op, &["value", "x", "y", "z"]);
        let s = if op.attribute("value").is_some() {
            let t = self.attr(op, "value")?;
            let n = self.numbers(op, "value", &t)?;
            match n.len() {
                1 => DVec3::splat(n[0]),
                3 => DVec3::new(n[0], n[1], n[2]),
                k => {
                    self.error(
                        self.attr_at(op, "value"),
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

    /// `<matrix value="…">`: 16 (4×4) or 9 (3×3) numbers, row-major, affine and invertible.
    fn matrix_op(&mut self, op: Node, at: usize) -> Option<DMat4> {
        self.check_attrs(op, &["value"]);
        let t = self.required(op, "value")?;
        let n = self.numbers(op, "value", &t)?;
        let m = match n.len() {
            // Row-major in the file; glam is column-major.
            16 => DMat4::from_cols_slice(&n).transpose(),
            9 => DMat4::from_mat3(DMat3::from_cols_slice(&n).transpose()),
            k => {
                self.error(
                    self.attr_at(op, "value"),
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

    /// `<lookat origin target up>`: the camera frame Mitsuba builds (x = up × dir, z = dir).
    fn lookat_op(&mut self, op: Node, at: usize) -> Option<DMat4> {
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
                self.attr_at(op, "up"),
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
}
