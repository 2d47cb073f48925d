//! BSDF plugins that combine or modify other BSDFs, or are no surface at all: `blendbsdf`
//! (two BSDFs mixed by a weight), `bumpmap` (a height field's gradient tilts the shading
//! normal) and `null` (invisible).
use super::Builder;
use super::bsdf::BuiltBsdf;
use crate::mitsuba::xml::{ChildKind, Obj};
use crate::{Bsdf, Param};

impl<'t> Builder<'t> {
    /// The nested `<bsdf>` children of `o` (objects or references that name a BSDF), in
    /// document order, each marked as used.
    fn nested_bsdfs(&mut self, o: &'t Obj) -> Vec<Option<BuiltBsdf>> {
        let inner: Vec<_> = o
            .children
            .iter()
            .filter(|c| match &c.kind {
                ChildKind::Obj(b) => b.tag == "bsdf",
                ChildKind::Ref(id) => {
                    c.name.is_none() || self.ids.get(id.as_str()).is_some_and(|r| r.tag == "bsdf")
                }
            })
            .collect();
        inner
            .into_iter()
            .map(|c| {
                c.used.set(true);
                match &c.kind {
                    ChildKind::Obj(b) => self.bsdf(b),
                    ChildKind::Ref(id) => self.bsdf_by_id(id, c.at),
                }
            })
            .collect()
    }

    /// `blendbsdf`: `weight` (0.5, a number in [0, 1] or a texture) mixes its first BSDF
    /// (weight 0) with its second (weight 1).
    pub(super) fn blendbsdf(&mut self, o: &'t Obj, name: String) -> Option<BuiltBsdf> {
        let weight = match self.float_texture(o, "weight") {
            Some(Some(t)) => Some(Param::Texture(t)),
            Some(None) => None,
            None => self
                .float_in(o, "weight", 0.0..=1.0)
                .map(|w| Param::Const(w as f32))
                .or_else(|| {
                    self.prop(o, "weight")
                        .is_none()
                        .then_some(Param::Const(0.5))
                }),
        };
        let inner = self.nested_bsdfs(o);
        self.finish(o);
        if inner.len() != 2 {
            self.error(
                o.at,
                format!(
                    "{} needs exactly two nested <bsdf>s, found {}",
                    o.describe(),
                    inner.len()
                ),
            );
            return None;
        }
        let mut inner = inner.into_iter();
        let (a, b) = (inner.next()??, inner.next()??);
        Some(BuiltBsdf {
            bsdf: Bsdf::Blend {
                weight: weight?,
                bsdfs: Box::new([a.bsdf, b.bsdf]),
            },
            name,
        })
    }

    /// `bumpmap`: its one nested texture (any name) is the height field, `scale` (1) its
    /// gradient's multiplier. Mitsuba's `flip_invalid_normals` and `use_shadowing_function`
    /// are accepted when true (their default and eyeadapt's behaviour).
    pub(super) fn bumpmap(&mut self, o: &'t Obj, name: String) -> Option<BuiltBsdf> {
        let scale = self.float(o, "scale").unwrap_or(1.0);
        if !scale.is_finite() {
            let at = self.prop(o, "scale").map_or(o.at, |p| p.at);
            self.error(at, format!("{}: scale must be finite", o.describe()));
        }
        for flag in ["flip_invalid_normals", "use_shadowing_function"] {
            if self.boolean(o, flag) == Some(false) {
                let at = self.prop(o, flag).map_or(o.at, |p| p.at);
                self.error(
                    at,
                    format!("{}: {flag} = false is not supported", o.describe()),
                );
            }
        }
        let textures: Vec<(String, usize)> = o
            .children
            .iter()
            .filter_map(|c| {
                let is_texture = match &c.kind {
                    ChildKind::Obj(t) => t.tag == "texture",
                    ChildKind::Ref(id) => self
                        .ids
                        .get(id.as_str())
                        .is_some_and(|r| r.tag == "texture"),
                };
                (is_texture && c.name.is_some()).then(|| (c.name.clone().unwrap_or_default(), c.at))
            })
            .collect();
        let height = match textures.as_slice() {
            [(t, _)] => self.float_texture(o, t).flatten(),
            [] => {
                self.error(o.at, format!("{} needs a nested <texture>", o.describe()));
                None
            }
            [_, (_, at), ..] => {
                self.error(*at, format!("{} takes one nested <texture>", o.describe()));
                None
            }
        };
        let inner = self.nested_bsdfs(o);
        self.finish(o);
        if inner.len() != 1 {
            self.error(
                o.at,
                format!(
                    "{} needs exactly one nested <bsdf>, found {}",
                    o.describe(),
                    inner.len()
                ),
            );
            return None;
        }
        let inner = inner.into_iter().next()??;
        Some(BuiltBsdf {
            bsdf: Bsdf::BumpMap {
                height: height?,
                scale: scale as f32,
                bsdf: Box::new(inner.bsdf),
            },
            name,
        })
    }

    /// `null`: no surface (it takes no parameters).
    pub(super) fn null(&mut self, o: &'t Obj, name: String) -> Option<BuiltBsdf> {
        self.finish(o);
        Some(BuiltBsdf {
            bsdf: Bsdf::Null,
            name,
        })
    }
}
