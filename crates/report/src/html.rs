//! `report.html`: one self-contained page (SVGs inline, no scripts, no external files).
use super::coherence::{EstimatorReport, has_ratio, ratio};
use eyeadapt_sequencer::manifest::Manifest;
use std::fmt::Write;

pub fn escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

/// Three significant digits; "–" for undefined.
fn fmt(v: f64) -> String {
    if !v.is_finite() {
        return "–".into();
    }
    if v.fract() == 0.0 && v.abs() < 1e9 {
        // Counts and frame numbers.
        return format!("{v:.0}");
    }
    let a = v.abs();
    if (1e-3..1e5).contains(&a) {
        let decimals = (2 - a.log10().floor() as i32).max(0) as usize;
        format!("{v:.decimals$}")
    } else {
        format!("{v:.2e}")
    }
}

/// The columns of the summary table: (metric name, heading, unit).
const TABLE: &[(&str, &str, &str)] = &[
    ("max_jump", "max jump", "Δu′v′/frame"),
    ("max_jump_frame", "at frame", ""),
    ("mean_step", "mean step", "Δu′v′/frame"),
    ("p95_step", "p95 step", "Δu′v′/frame"),
    ("total_variation", "path length", "Δu′v′"),
    ("n_jumps_0.001", "jumps > 0.001", "count"),
    ("n_jumps_0.004", "jumps > 0.004", "count"),
    ("n_jumps_0.007", "jumps > 0.007", "count"),
    ("hf_rms", "hf_rms", "Δu′v′"),
    ("noise_floor", "noise floor", "Δu′v′"),
    ("dE_cat_mean", "dE_cat mean", "ΔE00"),
    ("dE_cat_max", "dE_cat max", "ΔE00"),
    ("n_dE_cat_gt_1", "dE_cat > 1", "frames"),
    ("dE_cat_grey_mean", "dE_cat_grey mean", "ΔE00"),
    ("flicker_ratio", "flicker ratio", "1"),
    ("n_excess", "excess > 1", "frames"),
];

pub struct Page<'a> {
    pub manifest: &'a Manifest,
    pub reports: &'a [EstimatorReport],
    /// (title, SVG text) in display order.
    pub plots: &'a [(String, String)],
    pub notes: &'a [String],
    pub y_n: Option<f64>,
    pub omega: Option<(usize, usize, usize)>,
    pub sigma_s: f64,
}

pub fn page(p: &Page<'_>) -> String {
    let m = p.manifest;
    let mut h = String::new();
    let _ = write!(
        h,
        r#"<!DOCTYPE html>
<html lang="en"><head><meta charset="utf-8">
<title>eyeadapt coherence report — {name}</title>
<style>
body {{ font-family: sans-serif; margin: 1.5em; color: #222; max-width: 1200px; }}
table {{ border-collapse: collapse; font-size: 13px; }}
th, td {{ border: 1px solid #ccc; padding: 3px 6px; text-align: right; }}
th {{ background: #f3f3f3; }} td.name, th.name {{ text-align: left; }}
.ratio {{ color: #777; font-size: 11px; }}
svg {{ max-width: 100%; height: auto; display: block; margin: 0.5em 0 1.5em; }}
.note {{ color: #844; }}
</style></head><body>
<h1>Temporal coherence of the adaptation white — {name}</h1>
<p>Sequence <code>{source}</code>, {n} frame(s) ({frames}) at {fps} frames/s.
Report by eyeadapt {version}; frames rendered by {tool}. Metric definitions: <code>docs/report.md</code>
and <code>shared/design/estimators.md</code> §7–§8.</p>
"#,
        name = escape(&m.job_name),
        source = escape(&m.job_source),
        n = m.frames.len(),
        frames = escape(&eyeadapt_sequencer::manifest::frames_to_spec(
            &m.frames.keys().copied().collect::<Vec<_>>()
        )),
        fps = m.fps,
        version = env!("CARGO_PKG_VERSION"),
        tool = escape(&m.tool),
    );
    for n in p.notes {
        let _ = writeln!(h, "<p class=\"note\">{}</p>", escape(n));
    }

    // Metrics table.
    let eye = p
        .reports
        .iter()
        .find(|r| r.name == "eye")
        .map(|r| r.metrics());
    h.push_str("<h2>Metrics</h2>\n<p>Every metric of every estimator is in <code>coherence.csv</code> (with its ratio to <code>eye</code>); the per-frame values are in <code>coherence_frames.csv</code>. Grey: ratio to <code>eye</code>. ");
    let _ = write!(h, "hf_rms uses a Gaussian of σ = {} s.", p.sigma_s);
    if let (Some(y), Some((w, hh, n))) = (p.y_n, p.omega) {
        let _ = write!(
            h,
            " Image metrics on {n} pixels (stride 2) of the {w}×{hh} raw frames, Lab white Y_n = {} (99th percentile of raw Y).",
            fmt(y)
        );
    }
    h.push_str("</p>\n<table><tr><th class=\"name\">estimator</th>");
    for (_, head, unit) in TABLE {
        let _ = write!(
            h,
            "<th>{}{}</th>",
            escape(head),
            if unit.is_empty() {
                String::new()
            } else {
                format!("<br><span class=\"ratio\">{}</span>", escape(unit))
            }
        );
    }
    h.push_str("</tr>\n");
    for r in p.reports {
        let ms = r.metrics();
        let _ = write!(h, "<tr><td class=\"name\">{}</td>", escape(&r.name));
        for (name, _, _) in TABLE {
            let Some(k) = ms.iter().position(|m| m.name == *name) else {
                h.push_str("<td>–</td>");
                continue;
            };
            let v = ms[k].value;
            let rat = eye
                .as_ref()
                .filter(|_| has_ratio(name) && r.name != "eye")
                .map(|e| ratio(v, e[k].value))
                .filter(|x| x.is_finite());
            let _ = write!(h, "<td>{}", fmt(v));
            if let Some(x) = rat {
                let _ = write!(h, " <span class=\"ratio\">×{}</span>", fmt(x));
            }
            h.push_str("</td>");
        }
        h.push_str("</tr>\n");
    }
    h.push_str("</table>\n");

    h.push_str("<h2>Plots</h2>\n");
    for (title, svg) in p.plots {
        let _ = writeln!(h, "<h3>{}</h3>", escape(title));
        // Inline: drop any XML declaration before the <svg> element.
        h.push_str(&svg[svg.find("<svg").unwrap_or(0)..]);
        h.push('\n');
    }

    h.push_str("<h2>Job parameters</h2>\n<table>\n");
    let _ = writeln!(
        h,
        "<tr><td class=\"name\">job hash</td><td class=\"name\"><code>{}</code></td></tr>",
        escape(&m.job_hash)
    );
    let _ = writeln!(
        h,
        "<tr><td class=\"name\">estimators</td><td class=\"name\">{}</td></tr>",
        escape(&m.estimators.join(", "))
    );
    for (k, v) in &m.settings {
        let _ = writeln!(
            h,
            "<tr><td class=\"name\">{}</td><td class=\"name\">{}</td></tr>",
            escape(k),
            escape(v)
        );
    }
    h.push_str("</table>\n</body></html>\n");
    h
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_have_three_significant_digits() {
        assert_eq!(fmt(0.0123456), "0.0123");
        assert_eq!(fmt(1.23456), "1.23");
        assert_eq!(fmt(123.456), "123");
        assert_eq!(fmt(0.00001234), "1.23e-5");
        assert_eq!(fmt(f64::NAN), "–");
        assert_eq!(fmt(23.0), "23");
        assert_eq!(fmt(0.0), "0");
        assert_eq!(escape("<a&b>"), "&lt;a&amp;b&gt;");
    }
}
