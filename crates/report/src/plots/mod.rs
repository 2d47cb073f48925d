//! The report's SVG plots (plotters' SVG backend: text stays `<text>`, so no font is needed).
//!
//! Each plot makes one point: [`over_time`] (the key figure: where each estimator's white goes,
//! one small panel per estimator family, `eye` in each), [`strips`] (the colour adapted to,
//! frame by frame), [`steps`] (frame-to-frame jumps and the colour change they cause, one
//! panel per estimator against `eye`) and [`chromaticity`] (the whites' paths on the u′v′
//! diagram). Colours come from [`crate::palette`]; lines break at undefined frames and at gaps
//! in the frame numbers, and legends sit outside the data.
mod chromaticity;
mod over_time;
mod steps;
mod strips;

pub use chromaticity::chromaticity_plot;
pub use over_time::over_time_plot;
pub use steps::{de_cat_plot, steps_plot};
pub use strips::strips_plot;

use super::series::Series;
use crate::coherence::EstimatorReport;
use crate::palette::{colour_of, dash_of};
use eyeadapt_color::xyz_to_rgb;
use eyeadapt_sequencer::Failure;
use glam::DVec3;
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

type Area<'a> = DrawingArea<SVGBackend<'a>, Shift>;

const FONT: &str = "sans-serif";
const LEGEND_W: u32 = 250;
/// Strip colour of frames without a defined white.
const UNDEFINED: RGBColor = RGBColor(200, 200, 200);
/// Grid lines: light enough that reference lines and data stand out from them.
const GRID: RGBColor = RGBColor(236, 236, 236);
/// Reference lines (thresholds, the locus): dark, dashed and labelled.
const REFERENCE: RGBColor = RGBColor(70, 70, 70);

fn pe<E: std::fmt::Display>(what: &str) -> impl FnOnce(E) -> Failure + '_ {
    move |e| Failure::Other(format!("cannot draw {what}: {e}"))
}

/// One plot of the report.
pub struct Figure {
    /// File name under `plots/`, without `.svg`.
    pub file: String,
    /// Its one message, as the page's heading and the plot's title.
    pub title: String,
    /// The temporal filter of its series; `None` for the per-frame estimates.
    pub filter: Option<String>,
    pub svg: String,
}

/// Every plot: for the per-frame estimates the key figure, the colour strips, the steps, dE_cat
/// (when the image metrics exist) and the chromaticity diagram; for each filter the key figure,
/// the steps and dE_cat of the filtered series.
pub fn figures(
    all: &[Series],
    reports: &[EstimatorReport],
    filters: &[String],
    fps: f64,
    with_image: bool,
) -> Result<Vec<Figure>, Failure> {
    let mut out = Vec::new();
    for filter in std::iter::once(None).chain(filters.iter().map(Some)) {
        let idx: Vec<usize> = (0..all.len())
            .filter(|&k| all[k].filter.as_ref() == filter)
            .collect();
        let group: Vec<&Series> = idx.iter().map(|&k| &all[k]).collect();
        let reps: Vec<&EstimatorReport> = idx.iter().map(|&k| &reports[k]).collect();
        let (suffix, with) = match filter {
            Some(f) => (format!("_{f}"), format!(", with the {f} temporal filter")),
            None => (String::new(), String::new()),
        };
        let mut add = |file: &str, title: String, svg: String| {
            out.push(Figure {
                file: format!("{file}{suffix}"),
                title,
                filter: filter.cloned(),
                svg,
            })
        };
        let t = format!(
            "Where each estimator's white goes over time{with}: eye (black) in every panel"
        );
        add("adaptation", t.clone(), over_time_plot(&group, &t)?);
        if filter.is_none() {
            let t = "The colour each estimator adapts to, frame by frame (Fig. 14 analogue)"
                .to_string();
            add("colour_strips", t.clone(), strips_plot(&group, &t, fps)?);
        }
        let t = format!("How far the white jumps from one frame to the next{with}");
        add("steps", t.clone(), steps_plot(&group, &reps, &t)?);
        if with_image {
            let t = format!("How much the white's change alone changes the picture (dE_cat){with}");
            add("de_cat", t.clone(), de_cat_plot(&group, &reps, &t)?);
        }
        if filter.is_none() {
            let t = "Where the whites travel on the chromaticity diagram (Fig. 11 analogue)"
                .to_string();
            add("chromaticity", t.clone(), chromaticity_plot(&group, &t)?);
        }
    }
    Ok(out)
}

fn stroke(s: &Series) -> ShapeStyle {
    let w = if s.base == "eye" { 3 } else { 2 };
    colour_of(&s.base).stroke_width(w)
}

/// Draws one run of a series in its colour, dashed as its filter says.
fn draw_run<DB, CT>(
    chart: &mut ChartContext<'_, DB, CT>,
    run: Vec<(f64, f64)>,
    s: &Series,
    style: ShapeStyle,
) -> Result<(), Failure>
where
    DB: DrawingBackend,
    CT: CoordTranslate<From = (f64, f64)>,
{
    match dash_of(s.filter.as_deref()) {
        Some((dash, gap)) => chart
            .draw_series(DashedLineSeries::new(run, dash, gap, style))
            .map(|_| ()),
        None => chart.draw_series(LineSeries::new(run, style)).map(|_| ()),
    }
    .map_err(pe(&s.name))
}

/// The adaptation white as a display colour: linear sRGB scaled to a maximum of 1, then
/// sRGB-encoded (hue and saturation of the white; its luminance is not shown).
pub fn display_colour(xyz: DVec3) -> RGBColor {
    let rgb = xyz_to_rgb(xyz).max(DVec3::ZERO);
    let m = rgb.max_element();
    if !(m > 0.0 && m.is_finite()) {
        return RGBColor(128, 128, 128);
    }
    let e = |c: f64| (eyeadapt_color::srgb_encode(c / m) * 255.0).round() as u8;
    RGBColor(e(rgb.x), e(rgb.y), e(rgb.z))
}

/// What a legend entry shows next to its name.
enum Key {
    Line(ShapeStyle),
    Dashed(ShapeStyle),
    Marker(ShapeStyle, bool),
    Cross(ShapeStyle),
    Swatch,
}

struct Entry {
    name: String,
    key: Key,
}

fn legend(area: &Area, title: &str, entries: &[Entry]) -> Result<(), Failure> {
    let font = (FONT, 13).into_font();
    area.draw(&Text::new(
        title.to_string(),
        (10, 14),
        (FONT, 14).into_font().style(FontStyle::Bold),
    ))
    .map_err(pe("legend"))?;
    for (i, e) in entries.iter().enumerate() {
        let y = 40 + 18 * i as i32;
        match &e.key {
            Key::Line(s) => area.draw(&PathElement::new(vec![(10, y), (40, y)], *s)),
            Key::Dashed(s) => area
                .draw(&PathElement::new(vec![(10, y), (20, y)], *s))
                .and_then(|_| area.draw(&PathElement::new(vec![(30, y), (40, y)], *s))),
            Key::Marker(s, filled) => area.draw(&Circle::new(
                (25, y),
                4,
                if *filled { s.filled() } else { *s },
            )),
            Key::Cross(s) => area.draw(&Cross::new((25, y), 5, *s)),
            Key::Swatch => area.draw(&Rectangle::new(
                [(10, y - 6), (40, y + 6)],
                UNDEFINED.filled(),
            )),
        }
        .map_err(pe("legend"))?;
        area.draw(&Text::new(
            e.name.clone(),
            (48, y),
            TextStyle::from(font.clone()).pos(Pos::new(HPos::Left, VPos::Center)),
        ))
        .map_err(pe("legend"))?;
    }
    Ok(())
}

fn series_entries(group: &[&Series]) -> Vec<Entry> {
    group
        .iter()
        .map(|s| Entry {
            name: s.name.clone(),
            key: match dash_of(s.filter.as_deref()) {
                Some(_) => Key::Dashed(stroke(s)),
                None => Key::Line(stroke(s)),
            },
        })
        .collect()
}

/// Renders into an SVG string.
fn svg(
    size: (u32, u32),
    draw: impl FnOnce(&Area) -> Result<(), Failure>,
) -> Result<String, Failure> {
    let mut text = String::new();
    {
        let root = SVGBackend::with_string(&mut text, size).into_drawing_area();
        root.fill(&WHITE).map_err(pe("background"))?;
        draw(&root)?;
        root.present().map_err(pe("plot"))?;
    }
    Ok(text)
}

/// Runs of consecutive frames where `value` is defined, as (x, y) polylines.
fn runs(
    s: &Series,
    x: impl Fn(usize) -> f64,
    value: impl Fn(usize) -> Option<f64>,
) -> Vec<Vec<(f64, f64)>> {
    let mut out: Vec<Vec<(f64, f64)>> = Vec::new();
    let mut current: Vec<(f64, f64)> = Vec::new();
    for (k, p) in s.points.iter().enumerate() {
        let follows = k > 0 && s.points[k - 1].frame + 1 == p.frame;
        if !follows && !current.is_empty() {
            out.push(std::mem::take(&mut current));
        }
        match value(k).filter(|v| v.is_finite()) {
            Some(v) => current.push((x(k), v)),
            None => {
                if !current.is_empty() {
                    out.push(std::mem::take(&mut current));
                }
            }
        }
    }
    if !current.is_empty() {
        out.push(current);
    }
    out
}

/// `lo..hi` padded by 5 % (and widened to at least `min_span`).
fn padded(values: impl Iterator<Item = f64>, min_span: f64) -> (f64, f64) {
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for v in values.filter(|v| v.is_finite()) {
        lo = lo.min(v);
        hi = hi.max(v);
    }
    if !lo.is_finite() {
        return (0.0, 1.0);
    }
    let pad = ((hi - lo) * 0.05).max((min_span - (hi - lo)).max(0.0) / 2.0);
    (lo - pad, hi + pad)
}

fn time_range(group: &[&Series]) -> (f64, f64) {
    let p = &group[0].points;
    let (a, b) = (p[0].time, p[p.len() - 1].time);
    if b > a { (a, b) } else { (a - 0.5, a + 0.5) }
}

/// Fig. 14 analogue: the adaptation colour of every frame as a strip per estimator, and u′(t),
/// v′(t) curves.
#[cfg(test)]
mod tests {
    use super::*;
    use eyeadapt_color::D65_XYZ;

    #[test]
    fn display_colour_of_d65_is_white_and_of_orange_is_orange() {
        assert_eq!(display_colour(D65_XYZ), RGBColor(255, 255, 255));
        let orange = eyeadapt_color::rgb_to_xyz(DVec3::new(1.0, 0.5, 0.1));
        let c = display_colour(orange);
        assert!(c.0 == 255 && c.1 > c.2, "{c:?}");
    }

    #[test]
    fn padded_ranges_are_never_empty() {
        assert_eq!(padded([f64::NAN].into_iter(), 1.0), (0.0, 1.0));
        let (a, b) = padded([0.2, 0.2].into_iter(), 0.01);
        assert!((b - a - 0.01).abs() < 1e-12);
    }
}
