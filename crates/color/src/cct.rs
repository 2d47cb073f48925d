//! Correlated colour temperature by McCamy's cubic (1992), §6.8.
//!
//! Used only to make the per-frame CSV readable (`cct_mccamy`). The cubic is a fit
//! to the Planckian locus and means nothing far from it, so results outside
//! [`CCT_RANGE_K`] are reported as absent rather than as a misleading number.

use glam::{DVec2, DVec3};

use crate::spaces::xyz_to_xy;

/// Results outside this range are dropped (PROJECT CHOICE, §6.8).
pub const CCT_RANGE_K: (f64, f64) = (1000.0, 25000.0);

/// McCamy CCT in kelvin from CIE 1931 xy; `None` outside [`CCT_RANGE_K`] or
/// when the formula is singular (y = 0.1858).
pub fn cct_mccamy(xy: DVec2) -> Option<f64> {
    // colour-science's sign convention: n = (x − xₑ)/(y − yₑ) with negated odd terms.
    let n = (xy.x - 0.3320) / (xy.y - 0.1858);
    let cct = -449.0 * n.powi(3) + 3525.0 * n.powi(2) - 6823.3 * n + 5520.33;
    (cct.is_finite() && (CCT_RANGE_K.0..=CCT_RANGE_K.1).contains(&cct)).then_some(cct)
}

/// McCamy CCT from XYZ; `None` when xy is undefined or the CCT is out of range.
pub fn cct_mccamy_xyz(xyz: DVec3) -> Option<f64> {
    xyz_to_xy(xyz).and_then(cct_mccamy)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn far_from_locus_is_none() {
        // A saturated blue-green: the cubic extrapolates to ~37 700 K.
        assert!(cct_mccamy(DVec2::new(0.1, 0.3)).is_none());
        // The cubic cannot tell a point off the locus from one on it; that is
        // what the optional Duv check of §6.8 would add.
        assert!(cct_mccamy(DVec2::new(0.3, 0.6)).is_some());
        assert!(cct_mccamy(DVec2::new(0.3, 0.1858)).is_none());
        assert!(cct_mccamy_xyz(DVec3::ZERO).is_none());
    }
}
