//! `report.html`: one self-contained page (SVGs inline, one small inline script that sorts the
//! table, no external files). It opens with the answer (eye against each field-of-view
//! estimator), then the key figure, then what each estimator measures, then the details: the
//! other plots, the filtered series, the full metrics table and the job's parameters.
use crate::about::what_it_measures;
use crate::coherence::EstimatorReport;
use crate::metrics_table::{SORT_SCRIPT, metrics_table};
use crate::palette::{colour_of, hex};
use crate::plots::Figure;
use crate::summary::{Comparison, Ratio, compare};
use eyeadapt_sequencer::manifest::Manifest;
use std::fmt::Write;

pub fn escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

/// Three significant digits; "–" for undefined.
pub fn fmt(v: f64) -> String {
    if !v.is_finite() {
        return "–".into();
    }
    if v.fract() == 0.0 && v.abs() < 1e9 {
        // Counts and frame numbers.
        return format!("{v:.0}");
    }
    let a = v.abs();
    if (1e-3..1e5).contains(&a) {
        let decimals = (2 - libm::log10(a).floor() as i32).max(0) as usize;
        format!("{v:.decimals$}")
    } else {
        format!("{v:.2e}")
    }
}

pub struct Page<'a> {
    pub manifest: &'a Manifest,
    pub reports: &'a [EstimatorReport],
    /// In display order; the first is the key figure.
    pub plots: &'a [Figure],
    pub notes: &'a [String],
    pub y_n: Option<f64>,
    pub omega: Option<(usize, usize, usize)>,
    pub sigma_s: f64,
}

const STYLE: &str = r#"<style>
body { font-family: sans-serif; margin: 1.5em; color: #222; max-width: 1200px; line-height: 1.4; }
table { border-collapse: collapse; font-size: 13px; }
th, td { border: 1px solid #ccc; padding: 3px 6px; text-align: right; }
th { background: #f3f3f3; } td.name, th.name { text-align: left; }
table.sortable th { cursor: pointer; }
table.sortable th[aria-sort=ascending]::after { content: " ▲"; }
table.sortable th[aria-sort=descending]::after { content: " ▼"; }
.ratio, .ci { color: #777; font-size: 11px; }
.answer { font-size: 16px; border-left: 4px solid #222; padding: 0.2em 1em; background: #fafafa; }
.answer li { margin: 0.3em 0; }
.swatch { display: inline-block; width: 0.8em; height: 0.8em; margin-right: 0.3em; vertical-align: baseline; }
figure { margin: 0.5em 0 1.5em; }
svg { max-width: 100%; height: auto; display: block; }
.note { color: #844; }
details > summary { cursor: pointer; font-weight: bold; margin: 0.8em 0; }
</style>"#;

/// Two significant digits, for ratios: "0.49", "1.1", "12".
fn fmt_ratio(v: f64) -> String {
    if !v.is_finite() {
        return "–".into();
    }
    let decimals = (1 - libm::log10(v.abs().max(1e-9)).floor() as i32).max(0) as usize;
    format!("{v:.decimals$}")
}

/// `0.49× (0.31–0.77)`.
fn with_interval(r: &Ratio) -> String {
    let mut s = format!("{}×", fmt_ratio(r.value));
    if r.lo.is_finite() && r.hi.is_finite() {
        let _ = write!(
            s,
            " <span class=\"ci\">({}–{})</span>",
            fmt_ratio(r.lo),
            fmt_ratio(r.hi)
        );
    }
    s
}

fn swatch(base: &str) -> String {
    format!(
        "<span class=\"swatch\" style=\"background:{}\"></span>",
        hex(colour_of(base))
    )
}

/// eye's verdict against one estimator, from the mean step's interval.
fn verdict(c: &Comparison) -> &'static str {
    let r = c.mean_step;
    if c.never_moves {
        "never moves"
    } else if r.hi < 1.0 {
        "eye steadier"
    } else if r.lo > 1.0 {
        "eye less steady"
    } else {
        "no clear difference"
    }
}

/// One line per estimator: "eye's largest step is 0.49× wcam's (0.31–0.77), …".
fn reading(c: &Comparison) -> String {
    let name = escape(&c.name);
    if c.never_moves {
        return format!(
            "{name}'s white is the same on every frame, so no ratio: {}",
            escape(what_it_measures(&c.base).unwrap_or("it does not change here."))
        );
    }
    let mut s = format!(
        "eye's largest step is {} {name}'s, its mean step {}",
        with_interval(&c.max_step),
        with_interval(&c.mean_step)
    );
    if let Some(d) = &c.de_cat_mean {
        let _ = write!(
            s,
            ", and the colour change its white causes in the picture {}",
            with_interval(d)
        );
    }
    s.push('.');
    s
}

fn answer(h: &mut String, comparisons: &[Comparison], frames: usize) {
    h.push_str("<h2>The answer: eye against each field-of-view estimator</h2>\n");
    if comparisons.is_empty() {
        h.push_str("<p>There is no <code>eye</code> series, or nothing to compare it with.</p>\n");
        return;
    }
    let count = |v: &str| comparisons.iter().filter(|c| verdict(c) == v).count();
    let _ = write!(
        h,
        "<div class=\"answer\"><p>Over {frames} frames, <b>eye's white moves less from frame to frame than {} of the {} field-of-view estimators</b> (its mean step is smaller, with the whole 95 % interval below 1×)",
        count("eye steadier"),
        comparisons.len()
    );
    for (v, what) in [
        ("eye less steady", "it moves more than"),
        ("no clear difference", "there is no clear difference from"),
        ("never moves", ""),
    ] {
        let n = count(v);
        if n > 0 && v == "never moves" {
            let _ = write!(h, "; {n} never move{}", if n == 1 { "s" } else { "" });
        } else if n > 0 {
            let _ = write!(h, "; {what} {n}");
        }
    }
    h.push_str(".</p><ul>\n");
    for c in comparisons {
        let _ = writeln!(
            h,
            "<li>{}<b>{}</b> — {}: {}</li>",
            swatch(&c.base),
            escape(&c.name),
            verdict(c),
            reading(c)
        );
    }
    h.push_str("</ul><p class=\"ci\">Ratios are eye ÷ the estimator (below 1: eye changes less), over the frames where both are defined; in brackets the 95 % moving-block bootstrap interval over frames. Steps are Δu′v′ between consecutive frames (estimators.md §7.2); dE_cat is the mean ΔE00 the change of the white alone causes in the adapted picture (§7.3).</p></div>\n");
}

/// A plot, inline; its title is drawn in it, and named for screen readers.
fn figure(h: &mut String, f: &Figure) {
    let _ = writeln!(h, "<figure aria-label=\"{}\">", escape(&f.title));
    // Inline: drop any XML declaration before the <svg> element.
    h.push_str(&f.svg[f.svg.find("<svg").unwrap_or(0)..]);
    h.push_str("</figure>\n");
}

fn estimators(h: &mut String, reports: &[EstimatorReport]) {
    h.push_str("<h2>What each estimator measures</h2>\n<ul>\n");
    for r in reports.iter().filter(|r| r.filter.is_none()) {
        let _ = writeln!(
            h,
            "<li>{}<b>{}</b>: {}</li>",
            swatch(&r.base),
            escape(&r.name),
            escape(what_it_measures(&r.base).unwrap_or("(not described by this version)"))
        );
    }
    h.push_str("</ul>\n");
}

fn job_parameters(h: &mut String, m: &Manifest) {
    h.push_str("<details><summary>Job parameters</summary>\n<table>\n");
    let mut row = |k: &str, v: &str| {
        let _ = writeln!(
            h,
            "<tr><td class=\"name\">{}</td><td class=\"name\">{}</td></tr>",
            escape(k),
            v
        );
    };
    row("job hash", &format!("<code>{}</code>", escape(&m.job_hash)));
    row("estimators", &escape(&m.estimators.join(", ")));
    for (k, v) in &m.settings.entries() {
        row(k, &escape(v));
    }
    h.push_str("</table></details>\n");
}

pub fn page(p: &Page<'_>) -> String {
    let m = p.manifest;
    let mut h = String::new();
    let _ = write!(
        h,
        r#"<!DOCTYPE html>
<html lang="en"><head><meta charset="utf-8">
<title>eyeadapt coherence report — {name}</title>
{STYLE}</head><body>
<h1>Temporal coherence of the adaptation white — {name}</h1>
<p>Sequence <code>{source}</code>, {n} frame(s) ({frames}) at {fps} frames/s.
Report by eyeadapt {version}; frames rendered by {tool}. Metric definitions: <code>docs/report.md</code>
and <code>shared/design/estimators.md</code> §7–§8.</p>
"#,
        name = escape(&m.job_name),
        source = escape(&m.job_source),
        n = m.frames.len(),
        frames = escape(
            &eyeadapt_sequencer::FrameSet::from_frames(m.frames.keys().copied()).to_string()
        ),
        fps = m.fps,
        version = env!("CARGO_PKG_VERSION"),
        tool = escape(&m.tool),
    );
    answer(&mut h, &compare(p.reports), m.frames.len());
    let (raw, filtered): (Vec<&Figure>, Vec<&Figure>) =
        p.plots.iter().partition(|f| f.filter.is_none());
    if let Some((key, rest)) = raw.split_first() {
        figure(&mut h, key);
        estimators(&mut h, p.reports);
        h.push_str("<h2>Details</h2>\n");
        for n in p.notes {
            let _ = writeln!(h, "<p class=\"note\">{}</p>", escape(n));
        }
        for f in rest {
            figure(&mut h, f);
        }
    }
    let mut filters: Vec<&str> = filtered
        .iter()
        .filter_map(|f| f.filter.as_deref())
        .collect();
    filters.dedup();
    for filter in filters {
        let _ = writeln!(
            h,
            "<details><summary>With the {} temporal filter (estimators.md §8)</summary>",
            escape(filter)
        );
        for f in filtered
            .iter()
            .filter(|f| f.filter.as_deref() == Some(filter))
        {
            figure(&mut h, f);
        }
        h.push_str("</details>\n");
    }

    h.push_str("<h2>All metrics</h2>\n<p>Click a heading to sort. Every metric of every estimator is in <code>coherence.csv</code> (with its ratio to <code>eye</code>); the per-frame values are in <code>coherence_frames.csv</code>. Grey: the estimator's value ÷ eye's. ");
    let _ = write!(h, "hf_rms uses a Gaussian of σ = {} s.", p.sigma_s);
    if let (Some(y), Some((w, hh, n))) = (p.y_n, p.omega) {
        let _ = write!(
            h,
            " Image metrics on {n} pixels (stride 2) of the {w}×{hh} raw frames, Lab white Y_n = {} (99th percentile of raw Y).",
            fmt(y)
        );
    }
    h.push_str("</p>\n");
    metrics_table(&mut h, p.reports);
    job_parameters(&mut h, m);
    h.push_str(SORT_SCRIPT);
    h.push_str("</body></html>\n");
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

    #[test]
    fn readings_say_how_eye_compares() {
        let r = |value, lo, hi| Ratio { value, lo, hi };
        let c = Comparison {
            name: "wcam".into(),
            base: "wcam".into(),
            max_step: r(0.49, 0.31, 0.77),
            mean_step: r(0.2, 0.15, 0.25),
            de_cat_mean: None,
            never_moves: false,
        };
        assert_eq!(verdict(&c), "eye steadier");
        let line = reading(&c);
        assert!(
            line.starts_with(
                "eye's largest step is 0.49× <span class=\"ci\">(0.31–0.77)</span> wcam's"
            ),
            "{line}"
        );
        assert_eq!(fmt_ratio(1.234), "1.2");
        assert_eq!(fmt_ratio(0.0456), "0.046");
        assert_eq!(fmt_ratio(12.3), "12");
        let still = Comparison {
            name: "dominant".into(),
            base: "dominant".into(),
            never_moves: true,
            ..c.clone()
        };
        assert_eq!(verdict(&still), "never moves");
        assert!(reading(&still).contains("constant unless the brightest light changes"));
        let unsure = Comparison {
            mean_step: r(1.1, 0.9, 1.3),
            ..c
        };
        assert_eq!(verdict(&unsure), "no clear difference");
    }
}
