//! Bump mapping, after Mitsuba's `bumpmap`: a height field h(u, v) (a texture read as a
//! number, times `scale`) displaces the surface along its shading normal n, so the tangents
//! become ∂p/∂u + n·(∂h/∂u − n·∂p/∂u) (and likewise for v) and the shading normal their
//! cross product, turned to the geometric normal's side. Where the viewer would be below the
//! new normal, it is mirrored about n (Mitsuba's `flip_invalid_normals`).
//!
//! The light leaving a bumped surface is attenuated by the microfacet-based shadowing term of
//! Estevez et al. 2019 ("A Microfacet-Based Shadowing Function to Solve the Bump Terminator
//! Problem"), as Mitsuba's `use_shadowing_function` does: G = 2 / (1 + √(1 + α² tan²θ)), θ
//! the light direction's angle to the unbumped normal and α² = min(tan²θₙ / 8, 1) from the
//! bumped normal's tilt θₙ. It multiplies the BSDF's value, not its density.
use crate::emitter::luminance;
use crate::interaction::SurfaceInteraction;
use crate::texture::lookup_grad;
use eyeadapt_scene::Texture;
use glam::{Vec2, Vec3A};

/// The gradient (∂h/∂u, ∂h/∂v) of `tex` read as a number at `si`: bilinear bitmaps have one,
/// every other texture is piecewise constant (zero gradient, as in Mitsuba).
pub fn height_gradient(tex: &Texture, si: &SurfaceInteraction) -> Vec2 {
    match tex {
        Texture::Bitmap(b) => {
            let uv = b.to_uv.transform_point2(si.uv);
            let [du, dv] = lookup_grad(&b.image, uv, b.filter, b.wrap);
            // Through `to_uv` by the chain rule: ∂h/∂u = ∇′h · ∂uv′/∂u.
            let g = Vec2::new(luminance(du), luminance(dv));
            let m = b.to_uv.matrix2;
            Vec2::new(g.dot(m.x_axis), g.dot(m.y_axis))
        }
        _ => Vec2::ZERO,
    }
}

/// The bumped shading normal at `si` for the scaled height gradient `g`, seen from `wo`.
pub fn bumped_normal(si: &SurfaceInteraction, g: Vec2, wo: Vec3A) -> Vec3A {
    let n = si.ns;
    let du = si.dpdu + n * (g.x - n.dot(si.dpdu));
    let dv = si.dpdv + n * (g.y - n.dot(si.dpdv));
    let mut m = du.cross(dv).normalize_or_zero();
    if m == Vec3A::ZERO || !m.is_finite() {
        return n;
    }
    if m.dot(si.ng) < 0.0 {
        m = -m;
    }
    if wo.dot(n) * wo.dot(m) <= 0.0 {
        m = 2.0 * m.dot(n) * n - m;
    }
    m
}

/// The shadowing term of a bumped surface and the side check that goes with it.
#[derive(Clone, Copy, Debug)]
pub struct Terminator {
    /// The unbumped shading normal, on the bumped one's side.
    n: Vec3A,
    /// The bumped normal.
    m: Vec3A,
    alpha2: f32,
}

fn tan2(cos: f32) -> f32 {
    let c2 = (cos * cos).max(1e-12);
    ((1.0 - c2) / c2).max(0.0)
}

impl Terminator {
    /// For unbumped normal `n` and bumped normal `m`.
    pub fn new(n: Vec3A, m: Vec3A) -> Terminator {
        let n = if n.dot(m) < 0.0 { -n } else { n };
        Terminator {
            n,
            m,
            alpha2: (0.125 * tan2(n.dot(m))).min(1.0),
        }
    }

    /// The factor for light leaving towards (or arriving from) `wi`: zero where `wi` lies on
    /// different sides of the two normals.
    pub fn factor(&self, wi: Vec3A) -> f32 {
        let c = wi.dot(self.n);
        if c * wi.dot(self.m) <= 0.0 {
            return 0.0;
        }
        2.0 / (1.0 + (1.0 + self.alpha2 * tan2(c)).sqrt())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn flat() -> SurfaceInteraction {
        SurfaceInteraction {
            ng: Vec3A::Z,
            ns: Vec3A::Z,
            dpdu: Vec3A::X,
            dpdv: Vec3A::Y,
            ..Default::default()
        }
    }

    #[test]
    fn a_slope_tilts_the_normal_against_it() {
        // h = 0.5·u over the plane z = 0: the surface rises along x, its normal leans to −x.
        let m = bumped_normal(&flat(), Vec2::new(0.5, 0.0), Vec3A::Z);
        let want = Vec3A::new(-0.5, 0.0, 1.0).normalize();
        assert!((m - want).length() < 1e-6, "{m}");
        // No gradient: the shading normal itself.
        assert_eq!(bumped_normal(&flat(), Vec2::ZERO, Vec3A::Z), Vec3A::Z);
    }

    #[test]
    fn a_normal_facing_away_from_the_viewer_is_mirrored() {
        // A steep descent along x tilts the normal far to +x, (5, 0, 1): a grazing viewer on
        // the +x side sees it, one on the −x side would be below it and gets it mirrored
        // about the unbumped normal, (−5, 0, 1).
        let wo = Vec3A::new(1.0, 0.0, 0.05).normalize();
        let m = bumped_normal(&flat(), Vec2::new(-5.0, 0.0), wo);
        assert!(
            (m - Vec3A::new(5.0, 0.0, 1.0).normalize()).length() < 1e-6,
            "{m}"
        );
        let wo = Vec3A::new(-1.0, 0.0, 0.05).normalize();
        let m = bumped_normal(&flat(), Vec2::new(-5.0, 0.0), wo);
        assert!(
            (m - Vec3A::new(-5.0, 0.0, 1.0).normalize()).length() < 1e-6,
            "{m}"
        );
    }

    #[test]
    fn the_terminator_term_is_one_without_tilt_and_below_one_when_grazing() {
        let t = Terminator::new(Vec3A::Z, Vec3A::Z);
        assert_eq!(t.factor(Vec3A::new(0.9, 0.0, 0.1).normalize()), 1.0);
        let m = Vec3A::new(0.3, 0.0, 1.0).normalize();
        let t = Terminator::new(Vec3A::Z, m);
        assert!((t.factor(Vec3A::Z) - 1.0).abs() < 1e-6);
        let grazing = t.factor(Vec3A::new(1.0, 0.0, 0.05).normalize());
        assert!(grazing > 0.0 && grazing < 0.9, "{grazing}");
        // Below the unbumped normal but above the bumped one: no light.
        assert_eq!(t.factor(Vec3A::new(1.0, 0.0, -0.1).normalize()), 0.0);
    }
}
