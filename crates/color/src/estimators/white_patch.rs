//! `white_patch`: the brightest surface is white (Land's retinex / max-RGB, §5).
//!
//! The plain per-channel max (p = ∞ in the Minkowski framework) is dominated by
//! a single Monte-Carlo firefly, so the default is the robust form usual in
//! practice (PROJECT CHOICE): the mean colour of the brightest q % of 𝓜.
//!
//! ```
//! let opts: eyeadapt_color::WhitePatchOptions = toml::from_str(r#"
//! mode = "top_percent"       # or "per_channel_percentile", "max"
//! top_percent = 1.0          # q, for top_percent
//! percentile = 99.0          # for per_channel_percentile
//! "#).unwrap();
//! assert_eq!(opts, eyeadapt_color::WhitePatchOptions::default());
//! ```

use glam::DVec3;
use serde::{Deserialize, Serialize};

use super::estimate::{Estimate, flags};
use super::frame::FrameAovs;
use super::masked_image::{MaskedImage, percentile};
use super::minkowski::minkowski_mean;
use crate::spaces::{luminance, rgb_to_xyz};

/// Which white-patch statistic.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum WhitePatchMode {
    /// Mean RGB of the pixels whose Y is in the top q % (at least one pixel).
    #[default]
    TopPercent,
    /// e_c = the given percentile of channel c, independently per channel.
    PerChannelPercentile,
    /// Per-channel maximum; for ablation only (very noise-sensitive).
    Max,
}

/// White-patch options; `Default` is the §10 default (top 1 %).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct WhitePatchOptions {
    pub mode: WhitePatchMode,
    /// q in percent, for `top_percent`.
    pub top_percent: f64,
    /// Percentile (0..=100), for `per_channel_percentile`.
    pub percentile: f64,
    pub clip_percentile: Option<f64>,
}

impl Default for WhitePatchOptions {
    fn default() -> Self {
        WhitePatchOptions {
            mode: WhitePatchMode::TopPercent,
            top_percent: 1.0,
            percentile: 99.0,
            clip_percentile: None,
        }
    }
}

impl WhitePatchOptions {
    /// Every problem with the options, as readable lines.
    pub fn validate(&self) -> Result<(), Vec<String>> {
        let mut errs = Vec::new();
        if !(self.top_percent > 0.0 && self.top_percent <= 100.0) {
            errs.push(format!(
                "white_patch: top_percent = {} must be in (0, 100]",
                self.top_percent
            ));
        }
        if !(0.0..=100.0).contains(&self.percentile) {
            errs.push(format!(
                "white_patch: percentile = {} must be in [0, 100]",
                self.percentile
            ));
        }
        if let Some(q) = self.clip_percentile
            && !(q > 0.0 && q <= 100.0)
        {
            errs.push(format!(
                "white_patch: clip_percentile = {q} must be in (0, 100]"
            ));
        }
        if errs.is_empty() { Ok(()) } else { Err(errs) }
    }
}

/// Mean colour of the `q` % of masked pixels with the highest luminance.
/// Ties in Y are broken by pixel index, and the chosen pixels are summed in
/// index order, so the result is fully determined by the image.
fn top_percent_mean(img: &MaskedImage, q: f64) -> DVec3 {
    let px = |i: usize| DVec3::new(img.planes[0][i], img.planes[1][i], img.planes[2][i]);
    let mut idx: Vec<usize> = (0..img.mask.len()).filter(|&i| img.mask[i]).collect();
    let k = ((q / 100.0 * idx.len() as f64).ceil() as usize).clamp(1, idx.len());
    let ys: Vec<f64> = (0..img.mask.len()).map(|i| luminance(px(i))).collect();
    // Brightest first; equal Y → lower index first. A total order, so the
    // selected set does not depend on the selection algorithm.
    let brighter = |a: &usize, b: &usize| ys[*b].total_cmp(&ys[*a]).then(a.cmp(b));
    if k < idx.len() {
        idx.select_nth_unstable_by(k - 1, brighter);
    }
    let mut top = idx[..k].to_vec();
    top.sort_unstable();
    top.iter().fold(DVec3::ZERO, |s, &i| s + px(i)) / k as f64
}

/// White-patch estimate. Reads `rgb`, `emitter`.
///
/// # Panics
/// If the options are invalid or a buffer has the wrong length.
pub fn white_patch(aovs: &FrameAovs, opts: &WhitePatchOptions) -> Estimate {
    if let Err(e) = opts.validate() {
        panic!("{}", e.join("; "));
    }
    let img = MaskedImage::new(aovs, opts.clip_percentile);
    let n = img.count();
    let est = if n == 0 {
        Estimate::undefined(flags::EMPTY_MASK)
    } else {
        let e = match opts.mode {
            WhitePatchMode::TopPercent => top_percent_mean(&img, opts.top_percent),
            WhitePatchMode::PerChannelPercentile => DVec3::from_array(std::array::from_fn(|c| {
                percentile(&mut img.masked_values(c), opts.percentile).unwrap_or(f64::NAN)
            })),
            WhitePatchMode::Max => DVec3::from_array(std::array::from_fn(|c| {
                minkowski_mean(&img.planes[c], &img.mask, f64::INFINITY)
            })),
        };
        Estimate::new(rgb_to_xyz(e), n as u64)
    };
    if img.dropped_non_finite {
        est.with_flag(flags::DROPPED_NON_FINITE)
    } else {
        est
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn top_percent_picks_the_brightest_and_breaks_ties_by_index() {
        // 200 pixels: Y rises with index except two equal bright ones at 3 and 150.
        let mut rgb: Vec<[f32; 3]> = (0..200).map(|i| [i as f32 / 1000.0; 3]).collect();
        rgb[3] = [5.0, 4.0, 3.0];
        rgb[150] = [5.0, 4.0, 3.0];
        let em = vec![0.0; 200];
        let img = MaskedImage::new(&FrameAovs::image_only(20, 10, &rgb, &em), None);
        // 1 % of 200 = 2 pixels: both bright ones.
        assert_eq!(top_percent_mean(&img, 1.0), DVec3::new(5.0, 4.0, 3.0));
        // 0.5 % → 1 pixel; the tie is resolved by index (both equal anyway).
        assert_eq!(top_percent_mean(&img, 0.5), DVec3::new(5.0, 4.0, 3.0));
        // 1.5 % → 3 pixels: the two bright ones plus pixel 199.
        let want = (DVec3::new(10.0, 8.0, 6.0) + DVec3::splat(0.199)) / 3.0;
        assert!((top_percent_mean(&img, 1.5) - want).abs().max_element() < 1e-7);
    }

    #[test]
    fn options_are_checked() {
        let bad = WhitePatchOptions {
            top_percent: 0.0,
            percentile: 101.0,
            ..Default::default()
        };
        assert_eq!(bad.validate().unwrap_err().len(), 2);
    }
}
