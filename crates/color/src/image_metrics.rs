//! Temporal-coherence metrics on the adapted image sequence (estimators.md §7.3).
//!
//! Let `R_t` be the raw linear frame and `A_t = T_t · R_t` the frame adapted with that frame's
//! linear-sRGB CAT `T_t`. Per frame t (from the second frame of each run of consecutive frames):
//!
//! - `dE_raw_t` = mean over Ω of ΔE00(Lab R_t, Lab R_{t−1}); `dE_adp_t` the same on A_t;
//! - `dE_cat_t` = mean over Ω of ΔE00(Lab T_t R_t, Lab T_{t−1} R_t): the change caused only by
//!   the change of adaptation colour, on one image, so scene motion does not enter it;
//! - `dE_cat_grey_t` = ΔE00(Lab T_t g, Lab T_{t−1} g) for a neutral patch g of reflectance
//!   0.18 under the display white (linear sRGB 0.18·(1,1,1)), measured against `W_r` itself.
//!
//! and over the sequence `flicker_ratio = Σ dE_adp / Σ dE_raw`, `e_t = dE_adp_t − dE_raw_t`
//! with its max and `n_excess = #{t : e_t > 1}`, and the mean, max and `#{> 1}` of dE_cat and
//! dE_cat_grey.
//!
//! Conventions (§7.3, PROJECT CHOICE):
//! - **Lab white** `Y_n · W_r`, with one `Y_n` for the whole sequence and every estimator: by
//!   default the 99th percentile of raw Y over all frames ([`LuminancePercentile`], a first
//!   pass over the same pixels Ω that the metrics use).
//! - **Clamps**: RGB (raw, or after the CAT) to ≥ 0, then `Y/Y_n` to ≤ 1 by scaling the whole
//!   XYZ triple (the chromaticity is kept), then Lab.
//! - **Ω**: every `stride`-th pixel in x and in y, starting at (0, 0) ([`PixelSubset`]);
//!   a pixel is left out of frame t when it sees an emitter (`mask.emitter ≠ 0`) or is not
//!   finite, and a pair of frames uses the pixels valid in both.
//! - A frame that does not follow the previous one (a gap in the frame numbers) starts a new
//!   run: its differences are NaN, like the first frame's, and are left out of every sum,
//!   mean, max and count. A mean over no pixel is NaN as well.
//! - Every reduction is a plain sequential loop in pixel order, so results do not depend on
//!   threading.

use glam::{DMat3, DVec3};

use crate::lab::{delta_e_2000, xyz_to_lab};
use crate::spaces::{D65_XYZ, M_RGB_TO_XYZ};

/// Stride of the pixel subset Ω (§10).
pub const DEFAULT_STRIDE: usize = 2;
/// ΔE00 above which a frame counts in `n_excess` and the `> 1` counts (≈ one JND).
pub const DEFAULT_DE_THRESHOLD: f64 = 1.0;
/// Percentile of raw Y that sets the Lab white luminance Y_n.
pub const DEFAULT_Y_PERCENTILE: f64 = 0.99;
/// Reflectance of the synthetic neutral patch of `dE_cat_grey`.
pub const GREY_REFLECTANCE: f64 = 0.18;

/// The fixed pixel subset Ω of a `width × height` image: indices `y·width + x` for every
/// `stride`-th x and y.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct PixelSubset {
    pub width: usize,
    pub height: usize,
    pub stride: usize,
    indices: Vec<usize>,
}

impl PixelSubset {
    /// # Panics
    /// If `stride` is 0.
    pub fn new(width: usize, height: usize, stride: usize) -> PixelSubset {
        assert!(stride > 0, "pixel subset stride must be at least 1");
        let indices = (0..height)
            .step_by(stride)
            .flat_map(|y| (0..width).step_by(stride).map(move |x| y * width + x))
            .collect();
        PixelSubset {
            width,
            height,
            stride,
            indices,
        }
    }

    /// Pixel indices, in row-major order.
    pub fn indices(&self) -> &[usize] {
        &self.indices
    }

    pub fn len(&self) -> usize {
        self.indices.len()
    }

    pub fn is_empty(&self) -> bool {
        self.indices.is_empty()
    }

    fn check(&self, rgb: &[[f32; 3]], emitter: Option<&[f32]>) {
        let n = self.width * self.height;
        assert_eq!(rgb.len(), n, "frame has {} pixels, expected {n}", rgb.len());
        if let Some(e) = emitter {
            assert_eq!(
                e.len(),
                n,
                "emitter mask has {} pixels, expected {n}",
                e.len()
            );
        }
    }
}

/// The pixel as a clamped (≥ 0) f64 triple, or `None` when it is excluded from Ω for this
/// frame (sees an emitter, or is not finite).
fn usable(rgb: &[[f32; 3]], emitter: Option<&[f32]>, i: usize) -> Option<DVec3> {
    if emitter.is_some_and(|e| e[i] != 0.0) {
        return None;
    }
    let p = rgb[i];
    if !p.iter().all(|c| c.is_finite()) {
        return None;
    }
    Some(DVec3::new(p[0] as f64, p[1] as f64, p[2] as f64).max(DVec3::ZERO))
}

/// Bits of an f32 histogram key: sign (always 0 here) + 8 exponent + 11 mantissa bits, so a bin
/// spans a relative width of 2⁻¹¹ ≈ 0.05 %.
const HIST_SHIFT: u32 = 12;
const HIST_BINS: usize = 1 << (31 - HIST_SHIFT);

/// First pass: a percentile of raw luminance Y over Ω of every frame (the Lab `Y_n`).
///
/// Memory is fixed whatever the sequence length: a histogram over the f32 bit pattern of Y
/// (monotone for non-negative floats) with bins of relative width 2⁻¹¹, each holding a count
/// and the sum of its values. [`value`](Self::value) takes the nearest-rank order statistic
/// (rank ⌈q·n⌉) and returns the mean of the values in its bin: exact when that bin holds one
/// distinct value, otherwise within 0.05 %.
#[derive(Clone, Debug)]
pub struct LuminancePercentile {
    counts: Vec<u64>,
    sums: Vec<f64>,
    n: u64,
}

impl Default for LuminancePercentile {
    fn default() -> Self {
        Self::new()
    }
}

impl LuminancePercentile {
    pub fn new() -> LuminancePercentile {
        LuminancePercentile {
            counts: vec![0; HIST_BINS],
            sums: vec![0.0; HIST_BINS],
            n: 0,
        }
    }

    /// Adds the Y (≥ 0) of every usable pixel of Ω.
    ///
    /// # Panics
    /// If the frame or mask size does not match `omega`.
    pub fn add_frame(&mut self, omega: &PixelSubset, rgb: &[[f32; 3]], emitter: Option<&[f32]>) {
        omega.check(rgb, emitter);
        for &i in omega.indices() {
            if let Some(p) = usable(rgb, emitter, i) {
                let y = (M_RGB_TO_XYZ.row(1).dot(p)).max(0.0) as f32;
                let bin = (y.to_bits() >> HIST_SHIFT) as usize;
                self.counts[bin] += 1;
                self.sums[bin] += y as f64;
                self.n += 1;
            }
        }
    }

    /// Pixels counted so far.
    pub fn count(&self) -> u64 {
        self.n
    }

    /// The `q`-quantile (q in [0, 1]); `None` without pixels.
    pub fn value(&self, q: f64) -> Option<f64> {
        if self.n == 0 {
            return None;
        }
        let rank = ((q.clamp(0.0, 1.0) * self.n as f64).ceil() as u64).max(1);
        let mut seen = 0;
        for (bin, &c) in self.counts.iter().enumerate() {
            seen += c;
            if seen >= rank {
                return Some(self.sums[bin] / c as f64);
            }
        }
        unreachable!("rank {rank} <= n {}", self.n)
    }
}

/// Converts Ω of a frame to CIELAB under the sequence's fixed white `Y_n · W_r`.
#[derive(Clone, Debug)]
pub struct LabConverter {
    omega: PixelSubset,
    y_n: f64,
    white: DVec3,
}

/// CIELAB of the pixels of Ω, in Ω's order; excluded pixels are NaN. Stored as f32 to keep
/// one frame per estimator in memory cheaply (ΔE00 is then computed in f64).
#[derive(Clone, Debug, PartialEq)]
pub struct LabImage(pub Vec<[f32; 3]>);

impl LabConverter {
    /// # Panics
    /// If `y_n` is not a positive finite number.
    pub fn new(omega: PixelSubset, y_n: f64) -> LabConverter {
        assert!(
            y_n.is_finite() && y_n > 0.0,
            "Lab white luminance Y_n must be positive, got {y_n}"
        );
        LabConverter {
            omega,
            y_n,
            white: D65_XYZ * y_n,
        }
    }

    pub fn omega(&self) -> &PixelSubset {
        &self.omega
    }

    pub fn y_n(&self) -> f64 {
        self.y_n
    }

    /// Lab of one linear-sRGB pixel (already ≥ 0): clamp Y/Y_n to 1 keeping chromaticity.
    fn lab(&self, rgb: DVec3) -> DVec3 {
        let mut xyz = M_RGB_TO_XYZ * rgb;
        if xyz.y > self.y_n {
            xyz *= self.y_n / xyz.y;
        }
        xyz_to_lab(xyz, self.white)
    }

    /// Lab of `m · R` over Ω (`m = None`: the raw frame). RGB is clamped to ≥ 0 before and
    /// after the matrix.
    ///
    /// # Panics
    /// If the frame or mask size does not match Ω's image.
    pub fn convert(
        &self,
        rgb: &[[f32; 3]],
        emitter: Option<&[f32]>,
        m: Option<&DMat3>,
    ) -> LabImage {
        self.omega.check(rgb, emitter);
        LabImage(
            self.omega
                .indices()
                .iter()
                .map(|&i| match usable(rgb, emitter, i) {
                    Some(p) => {
                        let p = m.map_or(p, |m| (*m * p).max(DVec3::ZERO));
                        self.lab(p).as_vec3().to_array()
                    }
                    None => [f32::NAN; 3],
                })
                .collect(),
        )
    }
}

/// Mean ΔE00 over the pixels defined in both images (NaN when there is none).
///
/// # Panics
/// If the images have different sizes.
pub fn mean_delta_e(a: &LabImage, b: &LabImage) -> f64 {
    assert_eq!(a.0.len(), b.0.len(), "Lab images differ in size");
    let (mut sum, mut n) = (0.0, 0usize);
    for (p, q) in a.0.iter().zip(&b.0) {
        if p[0].is_nan() || q[0].is_nan() {
            continue;
        }
        let lab = |v: &[f32; 3]| DVec3::new(v[0] as f64, v[1] as f64, v[2] as f64);
        sum += delta_e_2000(lab(p), lab(q));
        n += 1;
    }
    if n == 0 { f64::NAN } else { sum / n as f64 }
}

/// `dE_cat_grey`: ΔE00 between the neutral patch (linear sRGB 0.18·(1,1,1)) adapted by `prev`
/// and by `cur`, in Lab relative to `W_r` (Y = 1). RGB is clamped to ≥ 0 after each matrix.
pub fn delta_e_cat_grey(prev: &DMat3, cur: &DMat3) -> f64 {
    let g = DVec3::splat(GREY_REFLECTANCE);
    let lab = |m: &DMat3| xyz_to_lab(M_RGB_TO_XYZ * (*m * g).max(DVec3::ZERO), D65_XYZ);
    delta_e_2000(lab(prev), lab(cur))
}

/// The §7.3 differences of one frame (NaN on the first frame of a run).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FrameImageMetrics {
    pub frame: u32,
    pub de_raw: f64,
    pub de_adp: f64,
    pub de_cat: f64,
    pub de_cat_grey: f64,
}

/// Mean, max (and where) and count over a threshold of one per-frame series.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SeriesSummary {
    /// Frames with a defined value.
    pub n: usize,
    pub mean: f64,
    pub max: f64,
    /// The first frame reaching `max`.
    pub max_frame: Option<u32>,
    /// `#{t : value_t > threshold}`.
    pub n_over: usize,
}

fn summarize(values: impl Iterator<Item = (u32, f64)>, threshold: f64) -> SeriesSummary {
    let (mut n, mut sum, mut n_over) = (0, 0.0, 0);
    let mut max: Option<(f64, u32)> = None;
    for (frame, v) in values.filter(|(_, v)| v.is_finite()) {
        n += 1;
        sum += v;
        if v > threshold {
            n_over += 1;
        }
        if max.is_none_or(|(m, _)| v > m) {
            max = Some((v, frame));
        }
    }
    SeriesSummary {
        n,
        mean: if n == 0 { f64::NAN } else { sum / n as f64 },
        max: max.map_or(f64::NAN, |m| m.0),
        max_frame: max.map(|m| m.1),
        n_over,
    }
}

/// Every §7.3 metric of one estimator's adapted sequence.
#[derive(Clone, Debug, PartialEq)]
pub struct ImageMetrics {
    pub per_frame: Vec<FrameImageMetrics>,
    /// Σ dE_raw and Σ dE_adp over the frames where both are defined.
    pub sum_de_raw: f64,
    pub sum_de_adp: f64,
    /// `sum_de_adp / sum_de_raw` (NaN when the raw sequence does not change at all).
    pub flicker_ratio: f64,
    /// Max of `e_t = dE_adp_t − dE_raw_t`, and where.
    pub excess_max: f64,
    pub excess_max_frame: Option<u32>,
    /// `#{t : e_t > threshold}`.
    pub n_excess: usize,
    pub de_cat: SeriesSummary,
    pub de_cat_grey: SeriesSummary,
}

/// Sums up per-frame values (in frame order) with the ΔE `threshold` (default 1).
pub fn image_metrics_summary(per_frame: Vec<FrameImageMetrics>, threshold: f64) -> ImageMetrics {
    let both = || {
        per_frame
            .iter()
            .filter(|m| m.de_raw.is_finite() && m.de_adp.is_finite())
    };
    let sum_de_raw: f64 = both().map(|m| m.de_raw).sum();
    let sum_de_adp: f64 = both().map(|m| m.de_adp).sum();
    let excess = summarize(both().map(|m| (m.frame, m.de_adp - m.de_raw)), threshold);
    let flicker_ratio = if sum_de_raw > 0.0 {
        sum_de_adp / sum_de_raw
    } else {
        f64::NAN
    };
    ImageMetrics {
        sum_de_raw,
        sum_de_adp,
        flicker_ratio,
        excess_max: excess.max,
        excess_max_frame: excess.max_frame,
        n_excess: excess.n_over,
        de_cat: summarize(per_frame.iter().map(|m| (m.frame, m.de_cat)), threshold),
        de_cat_grey: summarize(
            per_frame.iter().map(|m| (m.frame, m.de_cat_grey)),
            threshold,
        ),
        per_frame,
    }
}

/// Streaming computation for one estimator: feed frames in increasing order with
/// [`push`](Self::push), sharing the raw frame's Lab (and `dE_raw_t`) between estimators.
#[derive(Clone, Debug, Default)]
pub struct ImageMetricsAccumulator {
    prev: Option<(u32, DMat3, LabImage)>,
    per_frame: Vec<FrameImageMetrics>,
}

impl ImageMetricsAccumulator {
    pub fn new() -> ImageMetricsAccumulator {
        ImageMetricsAccumulator::default()
    }

    /// Adds frame `frame` with raw pixels `rgb`, its emitter mask, its CAT `m` and `de_raw`
    /// (the raw frame's [`mean_delta_e`] against the previous frame; ignored — NaN — when the
    /// frame does not follow the previous one).
    pub fn push(
        &mut self,
        conv: &LabConverter,
        frame: u32,
        rgb: &[[f32; 3]],
        emitter: Option<&[f32]>,
        m: &DMat3,
        de_raw: f64,
    ) {
        let adapted = conv.convert(rgb, emitter, Some(m));
        let metrics = match self.prev.take() {
            Some((f, m_prev, lab_prev)) if frame > 0 && f == frame - 1 => {
                let cat_prev = conv.convert(rgb, emitter, Some(&m_prev));
                FrameImageMetrics {
                    frame,
                    de_raw,
                    de_adp: mean_delta_e(&adapted, &lab_prev),
                    de_cat: mean_delta_e(&adapted, &cat_prev),
                    de_cat_grey: delta_e_cat_grey(&m_prev, m),
                }
            }
            _ => FrameImageMetrics {
                frame,
                de_raw: f64::NAN,
                de_adp: f64::NAN,
                de_cat: f64::NAN,
                de_cat_grey: f64::NAN,
            },
        };
        self.per_frame.push(metrics);
        self.prev = Some((frame, *m, adapted));
    }

    pub fn finish(self, threshold: f64) -> ImageMetrics {
        image_metrics_summary(self.per_frame, threshold)
    }
}

/// One raw frame of a sequence held in memory.
#[derive(Clone, Copy, Debug)]
pub struct SequenceFrame<'a> {
    pub frame: u32,
    pub rgb: &'a [[f32; 3]],
    /// `mask.emitter` (fraction of samples that saw an emitter); `None`: no emitters.
    pub emitter: Option<&'a [f32]>,
}

/// Parameters of [`image_metrics`]; `Default` is §10.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ImageMetricsParams {
    pub stride: usize,
    pub de_threshold: f64,
    pub y_percentile: f64,
    /// A fixed Y_n instead of the percentile.
    pub y_n: Option<f64>,
}

impl Default for ImageMetricsParams {
    fn default() -> Self {
        ImageMetricsParams {
            stride: DEFAULT_STRIDE,
            de_threshold: DEFAULT_DE_THRESHOLD,
            y_percentile: DEFAULT_Y_PERCENTILE,
            y_n: None,
        }
    }
}

/// The sequence's Lab white luminance: `params.y_n`, else the percentile of raw Y over Ω of
/// every frame; 1 when no pixel is usable or all are black.
pub fn sequence_y_n(
    frames: &[SequenceFrame<'_>],
    omega: &PixelSubset,
    params: &ImageMetricsParams,
) -> f64 {
    if let Some(y) = params.y_n {
        return y;
    }
    let mut pct = LuminancePercentile::new();
    for f in frames {
        pct.add_frame(omega, f.rgb, f.emitter);
    }
    pct.value(params.y_percentile)
        .filter(|y| *y > 0.0)
        .unwrap_or(1.0)
}

/// Every §7.3 metric of a `width × height` sequence held in memory, for each estimator:
/// `matrices[e][k]` is estimator e's linear-sRGB CAT for `frames[k]` (frames in increasing
/// order). Returns the metrics per estimator and the Y_n used.
///
/// # Panics
/// If sizes disagree.
pub fn image_metrics(
    width: usize,
    height: usize,
    frames: &[SequenceFrame<'_>],
    matrices: &[Vec<DMat3>],
    params: &ImageMetricsParams,
) -> (Vec<ImageMetrics>, f64) {
    let omega = PixelSubset::new(width, height, params.stride);
    let y_n = sequence_y_n(frames, &omega, params);
    let conv = LabConverter::new(omega, y_n);
    let mut acc = vec![ImageMetricsAccumulator::new(); matrices.len()];
    let mut prev_raw: Option<(u32, LabImage)> = None;
    for (k, f) in frames.iter().enumerate() {
        let raw = conv.convert(f.rgb, f.emitter, None);
        let de_raw = match &prev_raw {
            Some((p, lab)) if f.frame > 0 && *p == f.frame - 1 => mean_delta_e(&raw, lab),
            _ => f64::NAN,
        };
        for (a, ms) in acc.iter_mut().zip(matrices) {
            a.push(&conv, f.frame, f.rgb, f.emitter, &ms[k], de_raw);
        }
        prev_raw = Some((f.frame, raw));
    }
    let metrics = acc
        .into_iter()
        .map(|a| a.finish(params.de_threshold))
        .collect();
    (metrics, y_n)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{Cat, adaptation_matrix_rgb, rgb_to_xyz};

    fn image(w: usize, h: usize, f: impl Fn(usize, usize) -> [f32; 3]) -> Vec<[f32; 3]> {
        (0..h)
            .flat_map(|y| (0..w).map(move |x| (x, y)))
            .map(|(x, y)| f(x, y))
            .collect()
    }

    fn textured(w: usize, h: usize, k: f32) -> Vec<[f32; 3]> {
        image(w, h, |x, y| {
            [
                0.1 + 0.05 * x as f32 * k,
                0.2 + 0.03 * y as f32,
                0.05 + 0.01 * (x * y) as f32,
            ]
        })
    }

    fn cat(white_rgb: [f64; 3]) -> DMat3 {
        adaptation_matrix_rgb(
            Cat::Cat02,
            rgb_to_xyz(DVec3::from_array(white_rgb)),
            D65_XYZ,
            1.0,
        )
    }

    #[test]
    fn subset_takes_every_second_pixel_of_every_second_row() {
        let s = PixelSubset::new(5, 3, 2);
        assert_eq!(s.indices(), &[0, 2, 4, 10, 12, 14]);
        assert_eq!(PixelSubset::new(4, 4, 1).len(), 16);
    }

    #[test]
    fn percentile_is_nearest_rank_and_exact_for_repeated_values() {
        let omega = PixelSubset::new(10, 10, 1);
        // 100 pixels, grey levels 0.01..=1.00 (Y = level exactly for a grey).
        let rgb = image(10, 10, |x, y| [((y * 10 + x + 1) as f32) / 100.0; 3]);
        let mut p = LuminancePercentile::new();
        p.add_frame(&omega, &rgb, None);
        let y99 = p.value(0.99).unwrap();
        assert!((y99 - 0.99).abs() < 0.99 * 5e-4, "{y99}");
        let mut c = LuminancePercentile::new();
        c.add_frame(&omega, &vec![[0.3; 3]; 100], None);
        let grey_y = M_RGB_TO_XYZ.row(1).dot(DVec3::splat(0.3)) as f32 as f64;
        assert_eq!(c.value(0.99), Some(grey_y));
        assert_eq!(LuminancePercentile::new().value(0.99), None);
    }

    #[test]
    fn emitter_pixels_are_left_out_of_the_percentile_and_the_lab_image() {
        let omega = PixelSubset::new(4, 1, 1);
        let rgb = vec![[0.2; 3], [50.0; 3], [0.2; 3], [0.2; 3]];
        let mask = [0.0, 1.0, 0.0, 0.0];
        let mut p = LuminancePercentile::new();
        p.add_frame(&omega, &rgb, Some(&mask));
        assert_eq!(p.count(), 3);
        assert!(p.value(1.0).unwrap() < 1.0);
        let lab = LabConverter::new(omega, 1.0).convert(&rgb, Some(&mask), None);
        assert!(lab.0[1][0].is_nan() && !lab.0[0][0].is_nan());
    }

    #[test]
    fn lab_clamps_luminance_to_the_white_and_rgb_to_zero() {
        let conv = LabConverter::new(PixelSubset::new(2, 1, 1), 0.5);
        let lab = conv.convert(&[[4.0, 4.0, 4.0], [-1.0, -1.0, -1.0]], None, None);
        // Brighter than Y_n: clamped to the white itself, L* = 100, neutral.
        assert!((lab.0[0][0] - 100.0).abs() < 1e-4 && lab.0[0][1].abs() < 1e-3);
        assert_eq!(lab.0[1], [0.0, 0.0, 0.0]);
    }

    #[test]
    fn identical_frames_give_zero_everywhere() {
        let (w, h) = (8, 6);
        let rgb = textured(w, h, 1.0);
        let frames: Vec<SequenceFrame> = (0..4)
            .map(|f| SequenceFrame {
                frame: f,
                rgb: &rgb,
                emitter: None,
            })
            .collect();
        let m = cat([1.0, 0.7, 0.4]);
        let (out, y_n) = image_metrics(
            w,
            h,
            &frames,
            &[vec![m; 4], vec![DMat3::IDENTITY; 4]],
            &Default::default(),
        );
        assert!(y_n > 0.0);
        for est in &out {
            assert!(est.per_frame[0].de_raw.is_nan());
            for f in &est.per_frame[1..] {
                assert_eq!(
                    (f.de_raw, f.de_adp, f.de_cat, f.de_cat_grey),
                    (0.0, 0.0, 0.0, 0.0)
                );
            }
            assert!(est.flicker_ratio.is_nan(), "0/0 is undefined");
            assert_eq!((est.excess_max, est.n_excess), (0.0, 0));
            assert_eq!(
                (est.de_cat.mean, est.de_cat.n_over, est.de_cat.n),
                (0.0, 0, 3)
            );
        }
    }

    #[test]
    fn identity_cat_gives_zero_de_cat_and_flicker_ratio_one() {
        let (w, h) = (8, 6);
        let a = textured(w, h, 1.0);
        let b = textured(w, h, 1.6);
        let frames = [
            SequenceFrame {
                frame: 3,
                rgb: &a,
                emitter: None,
            },
            SequenceFrame {
                frame: 4,
                rgb: &b,
                emitter: None,
            },
            SequenceFrame {
                frame: 5,
                rgb: &a,
                emitter: None,
            },
        ];
        let (out, _) = image_metrics(
            w,
            h,
            &frames,
            &[vec![DMat3::IDENTITY; 3]],
            &Default::default(),
        );
        let m = &out[0];
        assert_eq!(m.de_cat.mean, 0.0);
        assert_eq!(m.de_cat_grey.max, 0.0);
        assert!(m.per_frame[1].de_raw > 0.5, "{:?}", m.per_frame[1]);
        assert_eq!(m.per_frame[1].de_raw, m.per_frame[1].de_adp);
        assert_eq!(m.flicker_ratio, 1.0);
        assert_eq!(m.excess_max, 0.0);
    }

    #[test]
    fn white_change_on_constant_grey_matches_direct_delta_e() {
        // A uniform 0.18 grey frame and a CAT that changes from D65 (identity) to an orange
        // white: dE_cat and dE_cat_grey both equal ΔE00 of the two adapted greys.
        let (w, h) = (4, 4);
        let grey = vec![[0.18f32; 3]; w * h];
        let frames = [
            SequenceFrame {
                frame: 0,
                rgb: &grey,
                emitter: None,
            },
            SequenceFrame {
                frame: 1,
                rgb: &grey,
                emitter: None,
            },
        ];
        let m1 = cat([1.0, 0.6, 0.3]);
        let params = ImageMetricsParams {
            y_n: Some(1.0),
            ..Default::default()
        };
        let (out, _) = image_metrics(w, h, &frames, &[vec![DMat3::IDENTITY, m1]], &params);
        let g = DVec3::splat(0.18);
        let direct = delta_e_2000(
            xyz_to_lab(M_RGB_TO_XYZ * g, D65_XYZ),
            xyz_to_lab(M_RGB_TO_XYZ * (m1 * g).max(DVec3::ZERO), D65_XYZ),
        );
        let f = out[0].per_frame[1];
        assert!(direct > 5.0, "{direct}");
        assert!(
            (f.de_cat_grey - direct).abs() < 1e-12,
            "{} vs {direct}",
            f.de_cat_grey
        );
        // The image path stores Lab as f32.
        assert!(
            (f.de_cat - direct).abs() < 1e-4 * direct,
            "{} vs {direct}",
            f.de_cat
        );
        assert_eq!(f.de_raw, 0.0);
        assert!((f.de_adp - f.de_cat).abs() < 1e-12);
        assert_eq!(out[0].n_excess, 1);
        assert_eq!(out[0].de_cat.max_frame, Some(1));
        assert!(out[0].flicker_ratio.is_nan());
    }

    #[test]
    fn a_gap_in_frame_numbers_starts_a_new_run() {
        let (w, h) = (4, 4);
        let a = textured(w, h, 1.0);
        let b = textured(w, h, 2.0);
        let frames = [
            SequenceFrame {
                frame: 0,
                rgb: &a,
                emitter: None,
            },
            SequenceFrame {
                frame: 1,
                rgb: &b,
                emitter: None,
            },
            SequenceFrame {
                frame: 5,
                rgb: &a,
                emitter: None,
            },
            SequenceFrame {
                frame: 6,
                rgb: &a,
                emitter: None,
            },
        ];
        let (out, _) = image_metrics(
            w,
            h,
            &frames,
            &[vec![DMat3::IDENTITY; 4]],
            &Default::default(),
        );
        let pf = &out[0].per_frame;
        assert!(pf[1].de_raw > 0.0);
        assert!(pf[2].de_raw.is_nan() && pf[2].de_cat.is_nan());
        assert_eq!(pf[3].de_raw, 0.0);
        assert_eq!(out[0].de_cat.n, 2);
    }
}
