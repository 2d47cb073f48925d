//! `[[portals]]`: rectangles the environment is sampled through (`crate::Portal`).
use super::Ctx;
use super::format::PortalDef;
use crate::Portal;
use toml::Spanned;

impl Ctx<'_> {
    /// Portal `index`: `corner`, `u` and `v`, all required, with `u ⟂ v`.
    pub(super) fn portal(&mut self, index: usize, p: &Spanned<PortalDef>) -> Option<Portal> {
        let d = p.get_ref();
        let at = p.span().start;
        let before = self.diags.len();
        let mut key = |v: &Option<super::format::V3>, name: &str| match v {
            Some(v) => Some(self.vec3(v, &format!("portals[{index}] {name}"))),
            None => {
                let msg =
                    format!("portals[{index}] needs `{name}` (a portal is `corner`, `u`, `v`)");
                self.error(at, msg);
                None
            }
        };
        let (corner, u, v) = (key(&d.corner, "corner"), key(&d.u, "u"), key(&d.v, "v"));
        let (corner, u, v) = (corner?, u?, v?);
        if self.diags.len() > before {
            return None; // a non-finite component, already reported
        }
        let v_at = d.v.as_ref().map_or(at, |v| v.span().start);
        if let Err(problem) = Portal::check(u, v) {
            self.error(v_at, format!("portals[{index}] {problem}"));
            return None;
        }
        Some(Portal { corner, u, v })
    }
}
