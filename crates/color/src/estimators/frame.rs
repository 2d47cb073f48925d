//! The per-frame buffers the renderer hands to the estimators.
//!
//! Plain borrowed slices keep this crate independent of the tracer (data flows
//! scene → tracer → color). Every buffer is row-major, `width × height`, with y
//! pointing down, and holds the pixel-filtered average over the pixel's samples,
//! exactly like the beauty image (§2.2 e: "same pixel filter and sample count").

use glam::DVec3;

use crate::spaces::to_dvec3;

/// Borrowed AOVs of one frame. A buffer an estimator does not read may be
/// empty: each estimator checks the lengths of the buffers it uses, and panics
/// with the buffer's name when one is wrong (a renderer bug, not a data condition).
#[derive(Clone, Copy, Debug)]
pub struct FrameAovs<'a> {
    pub width: usize,
    pub height: usize,
    /// Beauty image, scene-linear sRGB (read by the §5 colour-constancy methods).
    pub rgb: &'a [[f32; 3]],
    /// First-hit directional-hemispherical reflectance ρ (§2.2 a); 0 where the
    /// camera ray missed. Read by `wcam` and `ncns`.
    pub albedo: &'a [[f32; 3]],
    /// WCAM achromatic re-render A_i (§2.2 b), computed by the renderer,
    /// including its `specular` and `include_emitters` choices.
    pub achromatic: &'a [[f32; 3]],
    /// First-hit irradiance E_i, linear sRGB (read by `ncns`).
    pub irradiance: &'a [[f32; 3]],
    /// Fraction (0..1) of the pixel's samples whose first hit is an emitter.
    pub emitter: &'a [f32],
    /// Fraction (0..1) of the pixel's samples whose camera ray hit a surface.
    pub hit: &'a [f32],
    /// Vertical field of view of the pinhole camera, in degrees.
    pub fov_y_deg: f64,
}

impl<'a> FrameAovs<'a> {
    /// The buffers the image-only methods (§5) need; the others stay empty.
    pub fn image_only(
        width: usize,
        height: usize,
        rgb: &'a [[f32; 3]],
        emitter: &'a [f32],
    ) -> Self {
        FrameAovs {
            width,
            height,
            rgb,
            albedo: &[],
            achromatic: &[],
            irradiance: &[],
            emitter,
            hit: &[],
            fov_y_deg: 0.0,
        }
    }

    /// width × height.
    pub fn pixel_count(&self) -> usize {
        self.width * self.height
    }

    /// Panics with the buffer's name if it is not width × height long.
    pub(crate) fn expect_len(&self, name: &str, len: usize) {
        assert_eq!(
            len,
            self.pixel_count(),
            "AOV `{name}` has {len} entries, expected {}×{} = {}",
            self.width,
            self.height,
            self.pixel_count()
        );
    }

    /// Fraction of pixel `i` that shows a surface: samples that hit, minus those
    /// that hit an emitter unless emitters are wanted. 0 for background pixels.
    pub(crate) fn surface_coverage(&self, i: usize, include_emitters: bool) -> f64 {
        let hit = self.hit[i] as f64;
        let cov = if include_emitters {
            hit
        } else {
            hit - self.emitter[i] as f64
        };
        if cov.is_finite() {
            cov.clamp(0.0, 1.0)
        } else {
            0.0
        }
    }

    /// cos θ_i between pixel i's centre ray and the optical axis, for a pinhole
    /// with square pixels and vertical field of view `fov_y_deg`.
    pub(crate) fn cos_axis_angle(&self, i: usize) -> f64 {
        let (x, y) = (i % self.width, i / self.width);
        let tan_half = libm::tan(self.fov_y_deg.to_radians() / 2.0);
        let aspect = self.width as f64 / self.height as f64;
        let px = (2.0 * (x as f64 + 0.5) / self.width as f64 - 1.0) * aspect * tan_half;
        let py = (1.0 - 2.0 * (y as f64 + 0.5) / self.height as f64) * tan_half;
        1.0 / (1.0 + px * px + py * py).sqrt()
    }

    /// `albedo[i]` in f64.
    pub(crate) fn albedo_at(&self, i: usize) -> DVec3 {
        to_dvec3(self.albedo[i])
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn frame<'a>(w: usize, h: usize, hit: &'a [f32], em: &'a [f32], fov: f64) -> FrameAovs<'a> {
        FrameAovs {
            hit,
            emitter: em,
            fov_y_deg: fov,
            ..FrameAovs::image_only(w, h, &[], &[])
        }
    }

    #[test]
    fn axis_angle_of_pinhole() {
        // 3×3 at 90°: the centre pixel looks down the axis; the middle of the
        // top row sits at tan θ = 2/3 · tan 45°.
        let f = frame(3, 3, &[], &[], 90.0);
        assert!((f.cos_axis_angle(4) - 1.0).abs() < 1e-15);
        let t: f64 = 2.0 / 3.0;
        assert!((f.cos_axis_angle(1) - 1.0 / (1.0 + t * t).sqrt()).abs() < 1e-15);
        // Symmetric corners.
        assert_eq!(f.cos_axis_angle(0), f.cos_axis_angle(8));
    }

    #[test]
    fn coverage_excludes_misses_and_emitters() {
        let hit = [1.0, 1.0, 0.0, 0.5];
        let em = [0.0, 1.0, 0.0, 0.25];
        let f = frame(4, 1, &hit, &em, 60.0);
        let c: Vec<f64> = (0..4).map(|i| f.surface_coverage(i, false)).collect();
        assert_eq!(c, [1.0, 0.0, 0.0, 0.25]);
        assert_eq!(f.surface_coverage(1, true), 1.0);
    }

    #[test]
    #[should_panic(expected = "AOV `hit` has 2 entries")]
    fn wrong_length_names_the_buffer() {
        frame(3, 1, &[1.0, 1.0], &[], 60.0).expect_len("hit", 2);
    }
}
