//! The sensor and what it nests (film, rfilter, sampler).
use super::Builder;
use crate::mitsuba::xml::{ChildKind, Obj, Value};
use crate::{Camera, PixelFilter, Projection};
use glam::{DMat4, DVec3};

const SAMPLERS: &[&str] = &[
    "independent",
    "stratified",
    "multijitter",
    "orthogonal",
    "ldsampler",
];

impl<'t> Builder<'t> {
    /// The one nested object with this tag (`<film>`, `<sampler>`, `<rfilter>`).
    pub(super) fn nested(&mut self, o: &'t Obj, tag: &str) -> Option<&'t Obj> {
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

    pub(super) fn sensor(&mut self, o: &'t Obj) {
        if !matches!(o.kind.as_str(), "perspective" | "thinlens" | "orthographic") {
            self.error(
                o.at,
                format!(
                    "unsupported {}: eyeadapt supports the perspective, thinlens and orthographic sensors",
                    o.describe()
                ),
            );
            return;
        }
        let to_world = self.transform(o, "to_world").unwrap_or(DMat4::IDENTITY);
        // Accepted and ignored: eyeadapt does not clip (documented in docs/mitsuba.md).
        self.float(o, "near_clip");
        self.float(o, "far_clip");
        let lens = self.lens(o);
        let shift = self.principal_point(o);
        let (width, height) = match self.nested(o, "film") {
            Some(f) => self.film(f),
            None => (768, 576),
        };
        if let Some(s) = self.nested(o, "sampler") {
            self.sampler(s);
        }
        let aspect = width as f64 / height as f64;
        let vertical = if o.kind == "orthographic" {
            None
        } else {
            self.field_of_view(o, aspect)
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
        // Mitsuba's orthographic view spans camera x in [−1, 1] and y in [−1, 1] / aspect,
        // scaled by `to_world`.
        let projection = match lens {
            _ if o.kind == "orthographic" => Projection::Orthographic {
                half_width: left.length() as f32,
                half_height: (up.length() / aspect) as f32,
            },
            _ if shift != (0.0, 0.0) => Projection::Shifted {
                shift_x: shift.0,
                shift_y: shift.1,
                aperture_radius: lens.map_or(0.0, |l| l.0),
                focus_distance: lens.map_or(1.0, |l| l.1),
            },
            Some((aperture_radius, focus_distance)) => Projection::ThinLens {
                aperture_radius,
                focus_distance,
            },
            None => Projection::Pinhole,
        };
        self.scene.camera = Some(Camera {
            position: position.as_vec3(),
            look_at: (position + forward.normalize()).as_vec3(),
            up: up.normalize().as_vec3(),
            fov_deg: vertical.unwrap_or(40.0) as f32,
            width,
            height,
            projection,
        });
    }

    /// `principal_point_offset_x`/`_y` of a perspective sensor (0): the image's shift in its
    /// plane, in fractions of its width and height (Mitsuba's thinlens and orthographic
    /// sensors have none).
    fn principal_point(&mut self, o: &'t Obj) -> (f32, f32) {
        if o.kind != "perspective" {
            return (0.0, 0.0);
        }
        let mut get = |name: &str| match self.float(o, name) {
            Some(x) if x.is_finite() && x.abs() <= 1e3 => x as f32,
            Some(x) => {
                let at = self.prop(o, name).map_or(o.at, |p| p.at);
                self.error(
                    at,
                    format!("{}: {name} {x} must be finite, within ±1000", o.describe()),
                );
                0.0
            }
            None => 0.0,
        };
        (
            get("principal_point_offset_x"),
            get("principal_point_offset_y"),
        )
    }

    /// `thinlens`: `aperture_radius` and `focus_distance`, both needed (as in Mitsuba). A
    /// perspective sensor's `focus_distance` is accepted and ignored: a pinhole is in focus
    /// everywhere (Mitsuba ignores it too).
    fn lens(&mut self, o: &'t Obj) -> Option<(f32, f32)> {
        if o.kind != "thinlens" {
            if o.kind == "perspective" {
                self.float(o, "focus_distance");
            }
            return None;
        }
        let get = |b: &mut Self, name: &str| match b.float(o, name) {
            Some(x) if x.is_finite() && x > 0.0 => Some(x as f32),
            Some(x) => {
                let at = b.prop(o, name).map_or(o.at, |p| p.at);
                b.error(at, format!("{}: {name} {x} must be > 0", o.describe()));
                None
            }
            None => {
                b.error(
                    o.at,
                    format!("{} needs a <float name=\"{name}\">", o.describe()),
                );
                None
            }
        };
        let r = get(self, "aperture_radius");
        let f = get(self, "focus_distance");
        r.zip(f)
    }

    /// The vertical field of view (degrees) from `fov`/`fov_axis` or `focal_length`.
    pub(super) fn field_of_view(&mut self, o: &'t Obj, aspect: f64) -> Option<f64> {
        let fov = self.float(o, "fov");
        let focal = self
            .prop(o, "focal_length")
            .map(|p| (p.at, p.value.clone()));
        match (fov, focal) {
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
                // Mitsuba: a 50 mm lens unless told otherwise, on 35 mm film (36 × 24 mm),
                // measured along the film's diagonal (`parse_fov` in Mitsuba's sensor.h).
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
                let diagonal = (36.0f64 * 36.0 + 24.0 * 24.0).sqrt();
                mm.and_then(|f| {
                    let fov = 2.0 * libm::atan(diagonal / (2.0 * f)).to_degrees();
                    vertical_fov(fov, "diagonal", aspect)
                })
            }
        }
    }

    pub(super) fn film(&mut self, f: &'t Obj) -> (u32, u32) {
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
        self.full_crop(f, width, height);
        // Accepted and ignored: eyeadapt writes its own EXR layout.
        for s in ["file_format", "pixel_format", "component_format"] {
            self.string(f, s);
        }
        self.boolean(f, "banner");
        self.boolean(f, "compensate");
        let border = self.boolean(f, "sample_border").unwrap_or(false);
        let filter = match self.nested(f, "rfilter") {
            Some(r) => self.rfilter(r),
            // Mitsuba's default.
            None => Some(PixelFilter::GAUSSIAN),
        };
        if border && filter.is_some_and(|p| p != PixelFilter::Box) {
            let at = self.prop(f, "sample_border").map_or(f.at, |p| p.at);
            self.warning(
                at,
                format!("{}: sample_border is ignored (the pixels at the image's edge get only the samples inside it)", f.describe()),
            );
        }
        self.scene.render.filter = filter;
        self.finish(f);
        (width, height)
    }

    /// `crop_offset_*`/`crop_width`/`crop_height` are accepted when they keep the whole film;
    /// a real crop is an error (eyeadapt renders whole frames).
    fn full_crop(&mut self, f: &Obj, width: u32, height: u32) {
        let full = [
            ("crop_offset_x", 0),
            ("crop_offset_y", 0),
            ("crop_width", i64::from(width)),
            ("crop_height", i64::from(height)),
        ];
        for (name, whole) in full {
            if let Some((v, at)) = self.int(f, name)
                && v != whole
            {
                self.error(
                    at,
                    format!(
                        "{}: {name} {v} crops the film: eyeadapt renders the whole {width}×{height} frame ({name} must be {whole} or absent)",
                        f.describe()
                    ),
                );
            }
        }
    }

    /// `<rfilter>`: box, tent (`radius`, default 1) or gaussian (`stddev`, default 0.5, reaching
    /// 4 · stddev), as in Mitsuba.
    fn rfilter(&mut self, r: &'t Obj) -> Option<PixelFilter> {
        let filter = match r.kind.as_str() {
            "box" => Some(PixelFilter::Box),
            "tent" => Some(PixelFilter::Tent {
                radius: self.float_in(r, "radius", 0.5..=16.0).unwrap_or(1.0) as f32,
            }),
            "gaussian" => {
                let stddev = self.float_in(r, "stddev", 0.05..=4.0).unwrap_or(0.5) as f32;
                Some(PixelFilter::Gaussian {
                    stddev,
                    radius: 4.0 * stddev,
                })
            }
            _ => {
                self.error(
                    r.at,
                    format!(
                        "unsupported {}: eyeadapt reconstructs with box, tent or gaussian filters",
                        r.describe()
                    ),
                );
                return None;
            }
        };
        self.finish(r);
        filter
    }

    pub(super) fn sampler(&mut self, s: &'t Obj) {
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
}

/// eyeadapt's vertical field of view (degrees) for Mitsuba's `fov` along `axis` on a film of
/// `aspect` = width / height; `None` for an unknown axis.
pub fn vertical_fov(fov_deg: f64, axis: &str, aspect: f64) -> Option<f64> {
    let t = libm::tan(fov_deg.to_radians() / 2.0);
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
    Some(2.0 * libm::atan(tv).to_degrees())
}
