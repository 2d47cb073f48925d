//! Anisotropic roughness for `conductor` and `dielectric`: `roughness_u` (along ∂p/∂u) and
//! `roughness_v` (along ∂p/∂v), each a GGX alpha in [0, 1] or a texture
//! (`roughness_u_texture`, `roughness_v_texture`), given together and instead of
//! `roughness` (Mitsuba's `alpha_u`/`alpha_v` rule). Equal values are the isotropic surface.
use super::Ctx;
use super::format::MaterialDef;
use crate::Param;
use toml::Spanned;

/// The anisotropic keys given (name, offset), for the check that other types do not take them.
pub(super) fn present(m: &MaterialDef) -> Vec<(&'static str, usize)> {
    let num = |v: &Option<Spanned<f32>>| v.as_ref().map(|v| v.span().start);
    let tex = |v: &Option<Spanned<String>>| v.as_ref().map(|v| v.span().start);
    [
        ("roughness_u", num(&m.roughness_u)),
        ("roughness_v", num(&m.roughness_v)),
        ("roughness_u_texture", tex(&m.roughness_u_texture)),
        ("roughness_v_texture", tex(&m.roughness_v_texture)),
    ]
    .into_iter()
    .filter_map(|(k, at)| at.map(|a| (k, a)))
    .collect()
}

/// A roughness: the alpha along ∂p/∂u (or the isotropic one) and, when it differs, along ∂p/∂v.
pub(super) struct Alphas {
    pub alpha: Param<f32>,
    pub alpha_v: Option<Param<f32>>,
    /// True when any roughness key was given at all.
    pub given: bool,
}

impl Ctx<'_> {
    /// A roughness value in [0, 1] under `key` (`default` when absent or bad).
    pub(super) fn alpha_value(&mut self, v: &Option<Spanned<f32>>, key: &str, default: f32) -> f32 {
        let Some(v) = v else { return default };
        let a = *v.get_ref();
        if !(a.is_finite() && (0.0..=1.0).contains(&a)) {
            self.error(v.span().start, format!("{key} {a} must be in [0, 1]"));
            return default;
        }
        a
    }

    /// `roughness` (or `roughness_texture`), or `roughness_u` and `roughness_v` (each a
    /// number or a texture); `default` where nothing is given.
    pub(super) fn alphas(&mut self, m: &MaterialDef, name: &str, default: f32) -> Alphas {
        let u_given = m.roughness_u.is_some() || m.roughness_u_texture.is_some();
        let v_given = m.roughness_v.is_some() || m.roughness_v_texture.is_some();
        let iso_given = m.roughness.is_some() || m.roughness_texture.is_some();
        if !(u_given || v_given) {
            let alpha = self.param(
                name,
                "roughness_texture",
                &m.roughness_texture,
                m.roughness.is_some(),
                |cx| cx.alpha_value(&m.roughness, "roughness", default),
            );
            return Alphas {
                alpha,
                alpha_v: None,
                given: iso_given,
            };
        }
        if iso_given {
            let at = m
                .roughness
                .as_ref()
                .map(|v| v.span().start)
                .or(m.roughness_texture.as_ref().map(|v| v.span().start))
                .unwrap_or(m.name.span().start);
            self.error(
                at,
                format!("material \"{name}\": give either `roughness` or `roughness_u` and `roughness_v`, not both"),
            );
        }
        if u_given != v_given {
            let (given, missing) = if u_given {
                ("roughness_u", "roughness_v")
            } else {
                ("roughness_v", "roughness_u")
            };
            let at = present(m).first().map_or(m.name.span().start, |p| p.1);
            self.error(
                at,
                format!(
                    "material \"{name}\": `{given}` needs `{missing}` too (they are given together)"
                ),
            );
        }
        let alpha = self.param(
            name,
            "roughness_u_texture",
            &m.roughness_u_texture,
            m.roughness_u.is_some(),
            |cx| cx.alpha_value(&m.roughness_u, "roughness_u", default),
        );
        let alpha_v = self.param(
            name,
            "roughness_v_texture",
            &m.roughness_v_texture,
            m.roughness_v.is_some(),
            |cx| cx.alpha_value(&m.roughness_v, "roughness_v", default),
        );
        Alphas {
            alpha_v: (alpha_v != alpha).then_some(alpha_v),
            alpha,
            given: true,
        }
    }
}
