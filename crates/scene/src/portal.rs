//! Light portals: rectangles in the openings of an interior (windows, doors) through which the
//! environment's light enters. They are not geometry — rays pass them, nothing renders them —
//! and they do not change what a scene looks like, only how the renderer samples the
//! environment: from a point on the room's side of a portal, it draws directions through the
//! portals instead of over the whole sky (Cycles' portals).
//!
//! ```toml
//! [[portals]]
//! corner = [-3.0, 0.7, -5.0]   # one corner of the opening
//! u = [0.0, 1.8, 0.0]          # its two edges from the corner, at right angles;
//! v = [0.0, 0.0, 1.6]          # the room is on the side of u × v (as a quad light's front)
//! ```
use glam::Vec3;

/// A rectangle `corner + s·u + t·v`, s, t ∈ [0, 1], with `u ⟂ v`; it serves the points on the
/// side of `u × v`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Portal {
    pub corner: Vec3,
    pub u: Vec3,
    pub v: Vec3,
}

impl Portal {
    /// Largest |cos| between `u` and `v` a portal may have (it must be a rectangle).
    pub const MAX_EDGE_COS: f32 = 1e-4;

    /// Why edges `u`, `v` make no portal, if they do not: a zero edge or edges that are not
    /// at right angles.
    pub fn check(u: Vec3, v: Vec3) -> Result<(), String> {
        let (lu, lv) = (u.length(), v.length());
        if !(lu > 0.0 && lv > 0.0) {
            return Err("has a zero edge (u or v is zero)".into());
        }
        let cos = u.dot(v) / (lu * lv);
        if cos.abs() > Self::MAX_EDGE_COS {
            return Err(format!(
                "is not a rectangle: u and v must be at right angles (their cosine is {cos})"
            ));
        }
        Ok(())
    }
}
