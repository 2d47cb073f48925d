//! Per-estimator adaptation-white series over the committed frames, the temporal filters
//! applied to them (estimators.md §8), and their metrics (§7.2 on the series, §7.3 on the
//! adapted images).
use super::table::{Row, Table, derived_row};
use eyeadapt_color::{
    D65_XYZ, FilterInit, ImageMetrics, ImageMetricsAccumulator, LabConverter, LuminancePercentile,
    PixelSubset, SeriesMetrics, SeriesParams, SeriesPoint, TemporalFilter, filter_series,
    mean_delta_e, series_metrics, xyz_to_uv,
};
use eyeadapt_sequencer::Failure;
use eyeadapt_sequencer::adapt::{AdaptationSettings, cat_matrix};
use eyeadapt_sequencer::manifest::Manifest;
use eyeadapt_sequencer::output::read_exr;
use eyeadapt_sequencer::pipeline::frame_name;
use glam::{DMat3, DVec3};
use rayon::prelude::*;
use std::collections::HashMap;
use std::path::Path;

/// One frame of a series.
#[derive(Clone, Debug, PartialEq)]
pub struct Point {
    pub frame: u32,
    pub time: f64,
    /// The adaptation white (XYZ, Y = 1); `None` when undefined.
    pub white: Option<DVec3>,
    pub uv: Option<[f64; 2]>,
    pub std_err: Option<[f64; 2]>,
}

impl Point {
    /// The white the CAT uses: undefined whites adapt with D65, as the sequencer does.
    pub fn cat_white(&self) -> DVec3 {
        self.white.unwrap_or(D65_XYZ)
    }
}

/// One estimator's series, or a filtered copy of one (`eye+fairchild`).
#[derive(Clone, Debug, PartialEq)]
pub struct Series {
    pub name: String,
    pub base: String,
    pub filter: Option<String>,
    /// One point per committed frame, in frame order.
    pub points: Vec<Point>,
}

/// The series of every estimator in the manifest (then any other estimator found in the CSV,
/// in order of appearance), over every committed frame.
pub fn base_series(m: &Manifest, table: &Table) -> Vec<Series> {
    let mut names: Vec<String> = m.estimators.clone();
    for r in &table.rows {
        if !names.contains(&r.estimator) {
            names.push(r.estimator.clone());
        }
    }
    let by_key: HashMap<(u32, &str), &Row> = table
        .rows
        .iter()
        .map(|r| ((r.frame, r.estimator.as_str()), r))
        .collect();
    names
        .into_iter()
        .map(|name| {
            let points = m
                .frames
                .iter()
                .map(|(&frame, e)| {
                    let row = by_key.get(&(frame, name.as_str()));
                    let white = row
                        .filter(|r| r.valid && r.xyz[1] > 0.0)
                        .map(|r| DVec3::from_array(r.xyz) / r.xyz[1]);
                    Point {
                        frame,
                        time: e.time_s,
                        white,
                        uv: white.and(row.and_then(|r| r.uv)),
                        std_err: row.and_then(|r| r.std_err),
                    }
                })
                .collect();
            Series {
                base: name.clone(),
                name,
                filter: None,
                points,
            }
        })
        .collect()
}

/// The job's temporal filter presets, `none` and repeats left out.
pub fn presets(m: &Manifest) -> Vec<TemporalFilter> {
    let mut out = Vec::new();
    for f in &m.settings.temporal_filters {
        if *f != TemporalFilter::None && !out.contains(f) {
            out.push(*f);
        }
    }
    out
}

/// Filters `s` with `filter` (observer adapted to the first frame); returns the series and
/// its CSV rows (one per frame, in frame order).
pub fn filtered(
    s: &Series,
    filter: TemporalFilter,
    table: &Table,
) -> Result<(Series, Vec<(u32, String)>), Failure> {
    let name = format!("{}+{filter}", s.name);
    let input: Vec<(f64, Option<[f64; 3]>)> = s
        .points
        .iter()
        .map(|p| (p.time, p.white.map(|w| w.to_array())))
        .collect();
    let out = filter_series(filter, FilterInit::FirstFrame, &input)
        .map_err(|e| Failure::Input(format!("temporal filter {filter} on {}: {e}", s.name)))?;
    let rows_of: HashMap<u32, &Row> = table
        .rows
        .iter()
        .filter(|r| r.estimator == s.name)
        .map(|r| (r.frame, r))
        .collect();
    let mut points = Vec::with_capacity(out.len());
    let mut rows = Vec::with_capacity(out.len());
    for (p, o) in s.points.iter().zip(out) {
        let xyz = DVec3::from_array(o.xyz);
        // Before any defined input the observer has no state: that frame adapts with D65 and
        // is undefined, like an undefined raw estimate.
        let valid = !o.flags.fallback_d65;
        let mut flags = Vec::new();
        if o.flags.undefined_input {
            flags.push("undefined_input");
        }
        if o.flags.fallback_d65 {
            flags.push("fallback_d65");
        }
        if o.flags.clamped {
            flags.push("clamped");
        }
        rows.push((
            p.frame,
            derived_row(
                p.frame,
                p.time,
                &name,
                xyz,
                valid,
                &flags,
                rows_of.get(&p.frame).copied(),
            ),
        ));
        let white = valid.then_some(xyz);
        points.push(Point {
            frame: p.frame,
            time: p.time,
            white,
            uv: white.and_then(xyz_to_uv).map(|v| v.to_array()),
            std_err: None,
        });
    }
    Ok((
        Series {
            name,
            base: s.base.clone(),
            filter: Some(filter.to_string()),
            points,
        },
        rows,
    ))
}

/// §7.2 metrics of a series.
pub fn metrics_of(s: &Series, fps: f64, sigma_s: f64) -> Result<SeriesMetrics, Failure> {
    let points: Vec<SeriesPoint> = s
        .points
        .iter()
        .map(|p| SeriesPoint {
            frame: p.frame,
            time: p.time,
            uv: p.uv,
            std_err: p.std_err,
        })
        .collect();
    let params = SeriesParams {
        sigma_s,
        ..SeriesParams::new(fps)
    };
    series_metrics(&points, &params)
        .map_err(|e| Failure::Input(format!("series metrics of {}: {e}", s.name)))
}

/// Frame-to-frame Δu′v′ per point (NaN on a run's first frame or next to an undefined one).
pub fn steps(s: &Series) -> Vec<f64> {
    let mut out = Vec::with_capacity(s.points.len());
    for (k, p) in s.points.iter().enumerate() {
        let prev = k.checked_sub(1).map(|j| &s.points[j]);
        let d = match (prev, p.uv) {
            (Some(q), Some(b)) if q.frame + 1 == p.frame => {
                q.uv.map_or(f64::NAN, |a| libm::hypot(b[0] - a[0], b[1] - a[1]))
            }
            _ => f64::NAN,
        };
        out.push(d);
    }
    out
}

/// Result of the image pass.
pub struct ImagePass {
    /// One per series, in order.
    pub metrics: Vec<ImageMetrics>,
    pub y_n: f64,
    pub omega_pixels: usize,
    pub width: usize,
    pub height: usize,
}

/// Frames kept in memory between the two passes up to this many bytes of RGB + mask (of
/// their Ω pixels only: 32 frames of 1080p at stride 2, against 8 whole ones).
const CACHE_BYTES: usize = 256 << 20;

type Pixels = (Vec<[f32; 3]>, Vec<f32>);

/// A frame's RGB and emitter mask at the pixels of `omega`, in its order: everything the
/// metrics read of a frame (a quarter of it at stride 2). The metrics over these with
/// [`compact_subset`] are the metrics over the frame with `omega`, value for value.
fn omega_pixels(omega: &PixelSubset, (rgb, emitter): Pixels) -> Pixels {
    let idx = omega.indices();
    (
        idx.iter().map(|&i| rgb[i]).collect(),
        idx.iter().map(|&i| emitter[i]).collect(),
    )
}

/// Every pixel of the image [`omega_pixels`] makes: Ω's every `stride`-th column and row of a
/// `width` × `height` frame are ⌈width / stride⌉ × ⌈height / stride⌉ pixels, in row order.
fn compact_subset(omega: &PixelSubset) -> PixelSubset {
    let c = PixelSubset::new(
        omega.width.div_ceil(omega.stride),
        omega.height.div_ceil(omega.stride),
        1,
    );
    debug_assert_eq!(c.len(), omega.len());
    c
}

/// §7.3 metrics of every series, reading the raw EXRs twice (once for Y_n, once for the
/// differences) unless they fit in memory. `None` (with the reason) when a committed frame has
/// no raw EXR.
pub fn image_pass(
    dir: &Path,
    m: &Manifest,
    series: &[Series],
    adaptation: &AdaptationSettings,
    stride: usize,
    on_frame: &dyn Fn(usize, usize),
) -> Result<Result<ImagePass, String>, Failure> {
    let paths = match raw_exrs(dir, m)? {
        Ok(p) => p,
        Err(why) => return Ok(Err(why)),
    };
    let read = |rel: &str| -> Result<(usize, usize, Pixels), Failure> {
        let fr = read_exr(&dir.join(rel))?;
        Ok((fr.width, fr.height, (fr.rgb, fr.emitter)))
    };

    // First pass: Y_n, the size, and a cache while it fits.
    let mut cache: Vec<Option<Pixels>> = Vec::with_capacity(paths.len());
    let mut cached_bytes = 0usize;
    let mut pct = LuminancePercentile::new();
    let mut size: Option<(usize, usize)> = None;
    let mut omega: Option<(PixelSubset, PixelSubset)> = None;
    let steps = 2 * paths.len();
    // Decoded a thread's worth of frames at a time (PIZ decoding is most of this pass's
    // serial time: 263 M instructions for a 320×180 demo frame), used in frame order.
    let batch = rayon::current_num_threads().max(1);
    let mut decoded = Vec::new().into_iter();
    for (k, (f, rel)) in paths.iter().enumerate() {
        if k % batch == 0 {
            let next: Vec<_> = paths[k..(k + batch).min(paths.len())]
                .par_iter()
                .map(|(_, rel)| read(rel))
                .collect();
            decoded = next.into_iter();
        }
        on_frame(k + 1, steps);
        let (w, h, px) = decoded.next().expect("one per frame")?;
        match size {
            None => {
                size = Some((w, h));
                let full = PixelSubset::new(w, h, stride);
                omega = Some((compact_subset(&full), full));
            }
            Some(s) if s != (w, h) => {
                return Err(Failure::Input(format!(
                    "{rel}: frame {f} is {w}x{h} but earlier frames are {}x{}",
                    s.0, s.1
                )));
            }
            _ => {}
        }
        let (compact, full) = omega.as_ref().expect("set above");
        let px = omega_pixels(full, px);
        pct.add_frame(compact, &px.0, Some(&px.1));
        let bytes = px.0.len() * 16;
        if cached_bytes + bytes <= CACHE_BYTES {
            cached_bytes += bytes;
            cache.push(Some(px));
        } else {
            cache.push(None);
        }
    }
    let (width, height) = size.expect("at least one frame");
    let (compact, full) = omega.expect("at least one frame");
    let omega_len = full.len();
    let y_n = pct
        .value(eyeadapt_color::DEFAULT_Y_PERCENTILE)
        .filter(|y| *y > 0.0)
        .unwrap_or(1.0);
    let conv = LabConverter::new(compact, y_n);

    // Second pass: per frame, the raw Lab once, then every series in parallel (each series'
    // own reduction stays sequential, so the result does not depend on the thread count).
    let mut accs = vec![ImageMetricsAccumulator::new(); series.len()];
    let mut prev_raw: Option<(u32, eyeadapt_color::LabImage)> = None;
    for (k, (f, rel)) in paths.iter().enumerate() {
        on_frame(paths.len() + k + 1, steps);
        let px = match cache[k].take() {
            Some(px) => px,
            None => omega_pixels(&full, read(rel)?.2),
        };
        let raw = conv.convert(&px.0, Some(&px.1), None);
        let de_raw = match &prev_raw {
            Some((p, lab)) if p + 1 == *f => mean_delta_e(&raw, lab),
            _ => f64::NAN,
        };
        let mats: Vec<DMat3> = series
            .iter()
            .map(|s| cat_matrix(s.points[k].cat_white(), adaptation))
            .collect();
        accs.par_iter_mut().zip(&mats).for_each(|(acc, mat)| {
            acc.push(&conv, *f, &px.0, Some(&px.1), mat, de_raw);
        });
        prev_raw = Some((*f, raw));
    }
    Ok(Ok(ImagePass {
        metrics: accs
            .into_iter()
            .map(|a| a.finish(eyeadapt_color::DEFAULT_DE_THRESHOLD))
            .collect(),
        y_n,
        omega_pixels: omega_len,
        width,
        height,
    }))
}

/// The committed frames' raw EXRs (frame, path relative to `dir`), each checked against its
/// manifest record (present, same size) before any is decoded. `Ok(Err(why))` when a frame
/// has none (the job did not write raw EXRs).
fn raw_exrs(dir: &Path, m: &Manifest) -> Result<Result<Vec<(u32, String)>, String>, Failure> {
    let paths: Vec<(u32, String)> = m
        .frames
        .iter()
        .map(|(&f, _)| (f, format!("frames/raw/{}", frame_name(f, "exr"))))
        .collect();
    let missing: Vec<u32> = paths
        .iter()
        .filter(|(f, rel)| !m.frames[f].files.iter().any(|e| &e.path == rel))
        .map(|(f, _)| *f)
        .collect();
    if !missing.is_empty() {
        return Ok(Err(format!(
            "no raw EXR for {} frame(s) (first: {}); the job's outputs.raw_exr is off",
            missing.len(),
            missing[0]
        )));
    }
    // Every frame is checked against its record before any is decoded.
    for (f, rel) in &paths {
        let entry = m.frames[f].files.iter().find(|e| &e.path == rel);
        let p = dir.join(rel);
        let len = eyeadapt_scene::check_input(&p)
            .map_err(|e| Failure::input_io("cannot read raw EXR", &p, &e))?;
        if let Some(e) = entry.filter(|e| e.bytes != len) {
            return Err(Failure::Input(format!(
                "{}: frame {f}'s raw EXR is {len} bytes but manifest.json records {} (damaged)",
                p.display(),
                e.bytes
            )));
        }
    }
    Ok(Ok(paths))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn omega_pixels_give_the_full_frames_metrics_value_for_value() {
        // Odd sizes, so that Ω's last column and row are partial; an emitter pixel, a NaN and
        // a negative channel among them.
        for (w, h, stride) in [(7, 5, 2), (6, 4, 2), (9, 7, 3), (4, 3, 1)] {
            let rgb: Vec<[f32; 3]> = (0..w * h)
                .map(|i| {
                    let k = i as f32;
                    match i % 11 {
                        3 => [f32::NAN, 0.2, 0.3],
                        5 => [-0.1, 0.4 + 0.01 * k, 0.2],
                        _ => [0.05 * k, 0.5 + 0.02 * k, 1.0 - 0.01 * k],
                    }
                })
                .collect();
            let emitter: Vec<f32> = (0..w * h).map(|i| (i % 7 == 2) as u8 as f32).collect();
            let full = PixelSubset::new(w, h, stride);
            let compact = compact_subset(&full);
            assert_eq!(compact.len(), full.len(), "{w}×{h}/{stride}");
            let px = omega_pixels(&full, (rgb.clone(), emitter.clone()));

            let (mut p_full, mut p_compact) =
                (LuminancePercentile::new(), LuminancePercentile::new());
            p_full.add_frame(&full, &rgb, Some(&emitter));
            p_compact.add_frame(&compact, &px.0, Some(&px.1));
            assert_eq!(p_full.count(), p_compact.count());
            let q = |p: &LuminancePercentile| p.value(0.9).map(f64::to_bits);
            assert_eq!(q(&p_full), q(&p_compact));

            let m = DMat3::from_diagonal(DVec3::new(1.1, 0.9, 1.3));
            let bits = |lab: eyeadapt_color::LabImage| {
                lab.0
                    .iter()
                    .flatten()
                    .map(|c| c.to_bits())
                    .collect::<Vec<_>>()
            };
            let (c_full, c_compact) = (
                LabConverter::new(full.clone(), 0.8),
                LabConverter::new(compact.clone(), 0.8),
            );
            for mat in [None, Some(&m)] {
                assert_eq!(
                    bits(c_full.convert(&rgb, Some(&emitter), mat)),
                    bits(c_compact.convert(&px.0, Some(&px.1), mat)),
                    "{w}×{h}/{stride}"
                );
            }
        }
    }
}
