//! Contact sheets: one row per view, three tiles per row — raw, adapted with `wcam`, adapted
//! with `eye` — like the paper's figures. Tiles are box-downscaled in linear light to at most
//! [`TILE_MAX_WIDTH`](crate::sheet::TILE_MAX_WIDTH) pixels, exposed so that the raw frame's 99th-percentile luminance
//! (emitters excluded) maps to 0.9, the same exposure for the three tiles of a row, and encoded
//! with the preview curve (`output::preview_bytes`). Rows and tiles are separated by 4 px of
//! black.
use crate::Named;
use eyeadapt_color::luminance_f32;
use eyeadapt_sequencer::Failure;
use eyeadapt_sequencer::adapt::{AdaptationSettings, apply, cat_matrix, white_for_cat};
use eyeadapt_sequencer::output::{atomic_write_bytes, preview_bytes};
use eyeadapt_tracer::Frame;

pub const TILE_MAX_WIDTH: usize = 192;
const GAP: usize = 4;

/// The three tiles of one view, 8-bit sRGB, row-major.
#[derive(Clone, Debug, Default)]
pub struct Tiles {
    pub width: usize,
    pub height: usize,
    /// raw, wcam, eye
    pub rgb8: [Vec<u8>; 3],
}

fn downscale(rgb: &[[f32; 3]], w: usize, h: usize, k: usize) -> (Vec<[f32; 3]>, usize, usize) {
    let (tw, th) = (w / k, h / k);
    let mut out = Vec::with_capacity(tw * th);
    for ty in 0..th {
        for tx in 0..tw {
            let mut acc = [0f64; 3];
            for y in ty * k..ty * k + k {
                for x in tx * k..tx * k + k {
                    let p = rgb[y * w + x];
                    for c in 0..3 {
                        acc[c] += if p[c].is_finite() { p[c] as f64 } else { 0.0 };
                    }
                }
            }
            let n = (k * k) as f64;
            out.push(acc.map(|v| (v / n) as f32));
        }
    }
    (out, tw, th)
}

/// Exposure (stops) that maps the 99th-percentile luminance of non-emitter pixels to 0.9.
pub fn auto_exposure(frame: &Frame) -> f32 {
    let mut ys: Vec<f64> = frame
        .rgb
        .iter()
        .zip(&frame.emitter)
        .filter(|(_, e)| **e == 0.0)
        .map(|(p, _)| luminance_f32(*p))
        .filter(|y| y.is_finite())
        .collect();
    if ys.is_empty() {
        return 0.0;
    }
    ys.sort_by(f64::total_cmp);
    let p99 = ys[((ys.len() - 1) as f64 * 0.99).round() as usize];
    if p99 > 0.0 {
        libm::log2(0.9 / p99) as f32
    } else {
        0.0
    }
}

/// Builds the raw | wcam | eye tiles of a frame (estimators missing from `readings` adapt
/// with D65, i.e. show the raw frame).
pub(crate) fn tiles(frame: &Frame, readings: &[Named], adaptation: &AdaptationSettings) -> Tiles {
    let ev = auto_exposure(frame);
    let k = frame.width.div_ceil(TILE_MAX_WIDTH).max(1);
    let adapted = |name: &str| {
        let white = readings
            .iter()
            .find(|r| r.name == name)
            .map_or(eyeadapt_color::D65_XYZ, |r| {
                white_for_cat(&r.estimate, eyeadapt_color::D65_XYZ).0
            });
        apply(cat_matrix(white, adaptation), &frame.rgb)
    };
    let images = [frame.rgb.clone(), adapted("wcam"), adapted("eye")];
    let mut t = Tiles::default();
    for (i, img) in images.iter().enumerate() {
        let (small, tw, th) = downscale(img, frame.width, frame.height, k);
        t.width = tw;
        t.height = th;
        t.rgb8[i] = preview_bytes(&small, ev);
    }
    t
}

/// Writes rows of tiles as one PNG (atomically).
pub fn write_sheet(path: &std::path::Path, rows: &[&Tiles]) -> Result<(), Failure> {
    let w = rows
        .iter()
        .map(|t| 3 * t.width + 2 * GAP)
        .max()
        .unwrap_or(1)
        .max(1);
    let h = rows
        .iter()
        .map(|t| t.height + GAP)
        .sum::<usize>()
        .max(1 + GAP)
        - GAP;
    let mut px = vec![0u8; w * h * 3];
    let mut y0 = 0;
    for t in rows {
        for (i, tile) in t.rgb8.iter().enumerate() {
            let x0 = i * (t.width + GAP);
            for y in 0..t.height {
                let src = &tile[y * t.width * 3..(y + 1) * t.width * 3];
                let dst = ((y0 + y) * w + x0) * 3;
                px[dst..dst + src.len()].copy_from_slice(src);
            }
        }
        y0 += t.height + GAP;
    }
    let mut encoded = Vec::new();
    use image::ImageEncoder;
    image::codecs::png::PngEncoder::new_with_quality(
        &mut encoded,
        image::codecs::png::CompressionType::Best,
        image::codecs::png::FilterType::Adaptive,
    )
    .write_image(&px, w as u32, h as u32, image::ExtendedColorType::Rgb8)
    .map_err(|e| Failure::Other(format!("cannot encode PNG {}: {e}", path.display())))?;
    atomic_write_bytes(path, &encoded)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn downscale_averages_blocks() {
        let img = vec![
            [1.0, 0.0, 0.0],
            [3.0, 0.0, 0.0],
            [5.0, 0.0, 0.0],
            [7.0, 2.0, 0.0],
        ];
        let (s, w, h) = downscale(&img, 2, 2, 2);
        assert_eq!((w, h), (1, 1));
        assert_eq!(s[0], [4.0, 0.5, 0.0]);
    }
}
