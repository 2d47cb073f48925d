//! The masked linear frame shared by the colour-constancy methods (§5).
//!
//! Van de Weijer's reference code masks 8-bit saturated pixels. An HDR render
//! has no saturation, so the mask 𝓜 is instead: the pixel does not directly see
//! an emitter (`emitter == 0`) and its luminance is finite. Optionally each
//! channel is first clipped at a percentile (over 𝓜) to tame Monte-Carlo fireflies.
//!
//! For filtered methods two more exclusions apply:
//! * the frame border, σ+1 pixels wide (rounded up), as `set_border` does;
//! * every pixel within the kernel radius R of an excluded pixel. The reference
//!   code dilates its mask by 3×3 only; dilating by R (PROJECT CHOICE) makes
//!   the result provably independent of what excluded pixels contain — an
//!   emitter's radiance would otherwise leak into its neighbours' gradients.

use super::frame::FrameAovs;
use crate::spaces::luminance_f32;

/// Channel planes (f64) plus the per-pixel mask.
pub(crate) struct MaskedImage {
    pub width: usize,
    pub height: usize,
    pub planes: [Vec<f64>; 3],
    pub mask: Vec<bool>,
    /// Some pixels were non-finite and were excluded.
    pub dropped_non_finite: bool,
}

impl MaskedImage {
    /// Builds 𝓜 from `rgb` and `emitter`, then clips at `clip_percentile` if given.
    /// Non-finite pixels are zeroed in the planes so they cannot poison filters.
    ///
    /// # Panics
    /// If `rgb` or `emitter` is not width × height long.
    pub fn new(aovs: &FrameAovs, clip_percentile: Option<f64>) -> Self {
        aovs.expect_len("rgb", aovs.rgb.len());
        aovs.expect_len("emitter", aovs.emitter.len());
        let n = aovs.pixel_count();
        let mut planes = [vec![0.0; n], vec![0.0; n], vec![0.0; n]];
        let mut mask = vec![false; n];
        let mut dropped_non_finite = false;
        for (i, px) in aovs.rgb.iter().enumerate() {
            if !luminance_f32(*px).is_finite() || px.iter().any(|c| !c.is_finite()) {
                dropped_non_finite = true;
                continue;
            }
            for c in 0..3 {
                planes[c][i] = px[c] as f64;
            }
            mask[i] = aovs.emitter[i] == 0.0;
        }
        let mut img = MaskedImage {
            width: aovs.width,
            height: aovs.height,
            planes,
            mask,
            dropped_non_finite,
        };
        if let Some(q) = clip_percentile {
            img.clip_channels(q);
        }
        img
    }

    /// Number of pixels in the mask.
    pub fn count(&self) -> usize {
        self.mask.iter().filter(|m| **m).count()
    }

    /// The values of channel `c` under the mask, in pixel order.
    pub fn masked_values(&self, c: usize) -> Vec<f64> {
        self.planes[c]
            .iter()
            .zip(&self.mask)
            .filter(|(_, m)| **m)
            .map(|(v, _)| *v)
            .collect()
    }

    /// Clips every channel at its `q`-th percentile over the mask.
    fn clip_channels(&mut self, q: f64) {
        for c in 0..3 {
            let mut vals = self.masked_values(c);
            if let Some(limit) = percentile(&mut vals, q) {
                self.planes[c].iter_mut().for_each(|v| *v = v.min(limit));
            }
        }
    }

    /// Removes from the mask every pixel within Chebyshev distance `radius` of an
    /// excluded pixel (a square dilation of the exclusion set, done separably).
    pub fn dilate_exclusion(&mut self, radius: usize) {
        if radius == 0 {
            return;
        }
        let (w, h) = (self.width, self.height);
        let excluded: Vec<bool> = self.mask.iter().map(|m| !m).collect();
        let rows = dilate_lines(&excluded, w, h, radius, true);
        let both = dilate_lines(&rows, w, h, radius, false);
        for (m, e) in self.mask.iter_mut().zip(both) {
            *m &= !e;
        }
    }

    /// Removes a border `width_px` pixels wide from the mask.
    pub fn exclude_border(&mut self, width_px: usize) {
        let (w, h) = (self.width, self.height);
        for y in 0..h {
            for x in 0..w {
                if x < width_px || y < width_px || x + width_px >= w || y + width_px >= h {
                    self.mask[y * w + x] = false;
                }
            }
        }
    }
}

/// 1-D dilation of a boolean image along rows or columns, with prefix counts.
fn dilate_lines(src: &[bool], w: usize, h: usize, r: usize, horizontal: bool) -> Vec<bool> {
    let (len, lines) = if horizontal { (w, h) } else { (h, w) };
    let at = |line: usize, pos: usize| {
        if horizontal {
            line * w + pos
        } else {
            pos * w + line
        }
    };
    let mut out = vec![false; src.len()];
    let mut prefix = vec![0usize; len + 1];
    for line in 0..lines {
        for pos in 0..len {
            prefix[pos + 1] = prefix[pos] + src[at(line, pos)] as usize;
        }
        for pos in 0..len {
            let lo = pos.saturating_sub(r);
            let hi = (pos + r + 1).min(len);
            out[at(line, pos)] = prefix[hi] > prefix[lo];
        }
    }
    out
}

/// The `q`-th percentile (0..=100) with linear interpolation between order
/// statistics (numpy's default). Reorders `values`. `None` when empty.
pub(crate) fn percentile(values: &mut [f64], q: f64) -> Option<f64> {
    if values.is_empty() {
        return None;
    }
    let rank = (q / 100.0).clamp(0.0, 1.0) * (values.len() - 1) as f64;
    let lo = rank.floor() as usize;
    let (_, lo_val, upper) = values.select_nth_unstable_by(lo, f64::total_cmp);
    let lo_val = *lo_val;
    let frac = rank - lo as f64;
    if frac == 0.0 || upper.is_empty() {
        return Some(lo_val);
    }
    let hi_val = upper.iter().copied().fold(f64::INFINITY, f64::min);
    Some(lo_val + frac * (hi_val - lo_val))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn percentile_matches_numpy_linear() {
        let mut v = vec![5.0, 1.0, 4.0, 2.0, 3.0];
        assert_eq!(percentile(&mut v, 50.0), Some(3.0));
        assert_eq!(percentile(&mut v, 100.0), Some(5.0));
        assert_eq!(percentile(&mut v, 0.0), Some(1.0));
        // rank = 0.9 · 4 = 3.6 → 4 + 0.6·(5 − 4)
        assert!((percentile(&mut v, 90.0).unwrap() - 4.6).abs() < 1e-12);
        assert_eq!(percentile(&mut [], 50.0), None);
    }

    #[test]
    fn dilation_is_a_square() {
        let (w, h) = (7, 5);
        let rgb = vec![[1.0f32; 3]; w * h];
        let mut em = vec![0.0f32; w * h];
        em[2 * w + 3] = 1.0;
        let aovs = FrameAovs::image_only(w, h, &rgb, &em);
        let mut img = MaskedImage::new(&aovs, None);
        assert_eq!(img.count(), w * h - 1);
        img.dilate_exclusion(1);
        assert_eq!(img.count(), w * h - 9);
        assert!(!img.mask[w + 2] && !img.mask[3 * w + 4] && img.mask[w + 1]);
        img.exclude_border(1);
        // Interior is 5×3 = 15 pixels, minus the 9 dilated ones.
        assert_eq!(img.count(), 6);
    }

    #[test]
    fn non_finite_pixels_are_zeroed_and_flagged() {
        let rgb = [[1.0, f32::NAN, 1.0], [1.0, 2.0, 3.0]];
        let em = [0.0, 0.0];
        let img = MaskedImage::new(&FrameAovs::image_only(2, 1, &rgb, &em), None);
        assert!(img.dropped_non_finite && !img.mask[0] && img.mask[1]);
        assert_eq!(img.planes[1][0], 0.0);
    }

    #[test]
    fn clipping_limits_fireflies() {
        let mut rgb = vec![[1.0f32; 3]; 100];
        rgb[7] = [1e6, 1.0, 1.0];
        let em = vec![0.0; 100];
        let img = MaskedImage::new(&FrameAovs::image_only(10, 10, &rgb, &em), Some(90.0));
        assert_eq!(img.planes[0][7], 1.0);
    }
}
