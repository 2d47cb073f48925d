//! `coherence.csv` (one row per estimator, every metric, each metric's ratio to `eye`) and
//! `coherence_frames.csv` (the per-frame values behind the plots).
use super::series::Series;
use eyeadapt_color::{ImageMetrics, SeriesMetrics};
use std::fmt::Write;

/// One metric of one estimator.
#[derive(Clone, Debug, PartialEq)]
pub struct Metric {
    pub name: String,
    pub value: f64,
    pub unit: &'static str,
}

/// Everything measured about one series.
#[derive(Clone, Debug)]
pub struct EstimatorReport {
    pub name: String,
    pub base: String,
    pub filter: Option<String>,
    pub series: SeriesMetrics,
    pub image: Option<ImageMetrics>,
    /// Δu′v′ from the previous frame, per frame (NaN where undefined).
    pub steps: Vec<f64>,
}

/// Metrics that are positions or sizes, not magnitudes: no ratio to `eye`.
const NO_RATIO: &[&str] = &[
    "n_points",
    "n_segments",
    "n_steps",
    "max_jump_frame",
    "max_jump_time",
    "excess_max_frame",
    "dE_cat_max_frame",
    "dE_cat_grey_max_frame",
    "n_image_frames",
];

/// The §7.3 columns; NaN when the image metrics could not be computed, so the CSV always has
/// the same columns.
fn image_metrics(m: Option<&ImageMetrics>) -> Vec<Metric> {
    let v = |f: &dyn Fn(&ImageMetrics) -> f64| m.map_or(f64::NAN, f);
    let frame = |f: Option<u32>| f.map_or(f64::NAN, f64::from);
    let row = |name: &str, value: f64, unit| Metric {
        name: name.to_string(),
        value,
        unit,
    };
    vec![
        row("n_image_frames", v(&|m| m.de_cat.n as f64), "count"),
        row("flicker_ratio", v(&|m| m.flicker_ratio), "1"),
        row("sum_dE_raw", v(&|m| m.sum_de_raw), "dE00"),
        row("sum_dE_adp", v(&|m| m.sum_de_adp), "dE00"),
        row("excess_max", v(&|m| m.excess_max), "dE00"),
        row(
            "excess_max_frame",
            v(&|m| frame(m.excess_max_frame)),
            "frame",
        ),
        row("n_excess", v(&|m| m.n_excess as f64), "count"),
        row("dE_cat_mean", v(&|m| m.de_cat.mean), "dE00"),
        row("dE_cat_max", v(&|m| m.de_cat.max), "dE00"),
        row(
            "dE_cat_max_frame",
            v(&|m| frame(m.de_cat.max_frame)),
            "frame",
        ),
        row("n_dE_cat_gt_1", v(&|m| m.de_cat.n_over as f64), "count"),
        row("dE_cat_grey_mean", v(&|m| m.de_cat_grey.mean), "dE00"),
        row("dE_cat_grey_max", v(&|m| m.de_cat_grey.max), "dE00"),
        row(
            "dE_cat_grey_max_frame",
            v(&|m| frame(m.de_cat_grey.max_frame)),
            "frame",
        ),
        row(
            "n_dE_cat_grey_gt_1",
            v(&|m| m.de_cat_grey.n_over as f64),
            "count",
        ),
    ]
}

impl EstimatorReport {
    /// Every metric, §7.2 first, in a fixed order.
    pub fn metrics(&self) -> Vec<Metric> {
        let mut out: Vec<Metric> = self
            .series
            .rows()
            .into_iter()
            .map(|r| Metric {
                name: r.name,
                value: r.value,
                unit: r.unit,
            })
            .collect();
        out.extend(image_metrics(self.image.as_ref()));
        out
    }
}

/// `value / eye`, NaN when either is undefined or eye's is 0.
pub fn ratio(value: f64, eye: f64) -> f64 {
    if value.is_finite() && eye.is_finite() && eye != 0.0 {
        value / eye
    } else {
        f64::NAN
    }
}

pub fn has_ratio(name: &str) -> bool {
    !NO_RATIO.contains(&name)
}

fn num(out: &mut String, v: f64) {
    if v.is_finite() {
        let _ = write!(out, "{v}");
    } else {
        out.push_str("NaN");
    }
}

/// The text of `coherence.csv`: `estimator,base,filter`, every metric, then
/// `<metric>_vs_eye` for each magnitude metric (NaN when there is no `eye` row).
pub fn coherence_csv(reports: &[EstimatorReport]) -> String {
    let eye = reports
        .iter()
        .find(|r| r.name == "eye")
        .map(|r| r.metrics());
    let Some(first) = reports.first() else {
        return String::new();
    };
    let names: Vec<String> = first.metrics().into_iter().map(|m| m.name).collect();
    let mut s = String::from("estimator,base,filter");
    for n in &names {
        let _ = write!(s, ",{n}");
    }
    for n in names.iter().filter(|n| has_ratio(n)) {
        let _ = write!(s, ",{n}_vs_eye");
    }
    s.push('\n');
    for r in reports {
        let ms = r.metrics();
        let _ = write!(
            s,
            "{},{},{}",
            r.name,
            r.base,
            r.filter.as_deref().unwrap_or("")
        );
        for m in &ms {
            s.push(',');
            num(&mut s, m.value);
        }
        for (k, m) in ms.iter().enumerate().filter(|(_, m)| has_ratio(&m.name)) {
            s.push(',');
            let e = eye.as_ref().map_or(f64::NAN, |e| e[k].value);
            num(&mut s, ratio(m.value, e));
        }
        s.push('\n');
    }
    s
}

/// The text of `coherence_frames.csv`: per frame and estimator, u′v′, the step from the
/// previous frame and the §7.3 differences.
pub fn frames_csv(series: &[Series], reports: &[EstimatorReport]) -> String {
    let mut s = String::from(
        "frame,time_s,estimator,u_prime,v_prime,d_uv,dE_raw,dE_adp,dE_cat,dE_cat_grey\n",
    );
    let n = series.first().map_or(0, |s| s.points.len());
    for k in 0..n {
        for (ser, rep) in series.iter().zip(reports) {
            let p = &ser.points[k];
            let _ = write!(s, "{},", p.frame);
            num(&mut s, p.time);
            let _ = write!(s, ",{}", ser.name);
            let uv = p.uv.unwrap_or([f64::NAN; 2]);
            let img = rep.image.as_ref().map(|m| m.per_frame[k]);
            for v in [
                uv[0],
                uv[1],
                rep.steps[k],
                img.map_or(f64::NAN, |m| m.de_raw),
                img.map_or(f64::NAN, |m| m.de_adp),
                img.map_or(f64::NAN, |m| m.de_cat),
                img.map_or(f64::NAN, |m| m.de_cat_grey),
            ] {
                s.push(',');
                num(&mut s, v);
            }
            s.push('\n');
        }
    }
    s
}
