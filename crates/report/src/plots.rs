//! The report's SVG plots (plotters' SVG backend: text stays `<text>`, so no font is needed).
//!
//! Every plot has a legend column on its right naming every series drawn; lines break at
//! undefined frames and at gaps in the frame numbers.
use super::coherence::EstimatorReport;
use super::locus;
use super::series::Series;
use eyeadapt_color::{D65_XYZ, DEFAULT_DE_THRESHOLD, DEFAULT_THRESHOLDS, xyz_to_rgb, xyz_to_uv};
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

fn pe<E: std::fmt::Display>(what: &str) -> impl FnOnce(E) -> Failure + '_ {
    move |e| Failure::Other(format!("cannot draw {what}: {e}"))
}

/// Colour and stroke of an estimator (filtered copies share their base's colour).
pub fn colour_of(base: &str) -> RGBColor {
    match base {
        "eye" => RGBColor(0, 0, 0),
        "eye_fov" => RGBColor(127, 127, 127),
        "wcam" => RGBColor(225, 87, 89),
        "ncns" => RGBColor(78, 121, 167),
        "dominant" => RGBColor(176, 122, 161),
        "grey_world" => RGBColor(89, 161, 79),
        "white_patch" => RGBColor(242, 142, 43),
        "shades_of_grey" => RGBColor(118, 183, 178),
        "grey_edge" => RGBColor(156, 117, 95),
        other => {
            // Anything else: a stable colour from the name.
            let h = other
                .bytes()
                .fold(7u32, |h, b| h.wrapping_mul(31).wrapping_add(b as u32));
            RGBColor(
                (h % 200) as u8,
                ((h / 200) % 200) as u8,
                ((h / 40_000) % 200) as u8,
            )
        }
    }
}

fn stroke(s: &Series) -> ShapeStyle {
    let w = if s.base == "eye" { 3 } else { 2 };
    colour_of(&s.base).stroke_width(w)
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
            key: Key::Line(stroke(s)),
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
pub fn adaptation_plot(group: &[&Series], title: &str, fps: f64) -> Result<String, Failure> {
    let n = group.len();
    let strip_h = 80 + 18 * n as u32;
    let panel_h = 260;
    let w = 1150;
    let longest = group
        .iter()
        .map(|s| s.name.chars().count())
        .max()
        .unwrap_or(4) as u32;
    svg((w, strip_h + 2 * panel_h), |root| {
        let (left, right) = root.split_horizontally(w - LEGEND_W);
        let (strip, curves) = left.split_vertically(strip_h);
        let (u_area, v_area) = curves.split_vertically(panel_h);
        let p = &group[0].points;
        let (f0, f1) = (p[0].frame as f64, p[p.len() - 1].frame as f64 + 1.0);
        let label_w = 30 + 7 * longest;
        {
            let mut chart = ChartBuilder::on(&strip)
                .caption(title, (FONT, 17))
                .margin(10)
                .x_label_area_size(36)
                .y_label_area_size(label_w)
                .build_cartesian_2d(f0..f1, 0f64..n as f64)
                .map_err(pe("strip"))?;
            chart
                .configure_mesh()
                .disable_mesh()
                .y_labels(0)
                .x_desc(format!("frame ({fps} frames/s)"))
                .x_label_formatter(&|v| format!("{v:.0}"))
                .y_desc("estimator")
                .axis_desc_style((FONT, 13))
                .draw()
                .map_err(pe("strip axes"))?;
            for (i, s) in group.iter().enumerate() {
                let y0 = (n - 1 - i) as f64;
                // Grey under the row: frames without a defined white. (A defined white is
                // never grey: its display colour has a channel at 1.)
                chart
                    .draw_series([Rectangle::new(
                        [(f0, y0 + 0.1), (f1, y0 + 0.9)],
                        UNDEFINED.filled(),
                    )])
                    .map_err(pe("strip"))?;
                chart
                    .draw_series(s.points.iter().filter_map(|pt| {
                        pt.white.map(|wh| {
                            Rectangle::new(
                                [
                                    (pt.frame as f64, y0 + 0.1),
                                    (pt.frame as f64 + 1.0, y0 + 0.9),
                                ],
                                display_colour(wh).filled(),
                            )
                        })
                    }))
                    .map_err(pe("strip"))?;
                chart
                    .draw_series([Rectangle::new(
                        [(f0, y0 + 0.1), (f1, y0 + 0.9)],
                        RGBColor(150, 150, 150).stroke_width(1),
                    )])
                    .map_err(pe("strip"))?;
                let (px, py) = chart.backend_coord(&(f0, y0 + 0.5));
                root.draw(&Text::new(
                    s.name.clone(),
                    (px - 6, py),
                    TextStyle::from((FONT, 12).into_font())
                        .pos(Pos::new(HPos::Right, VPos::Center)),
                ))
                .map_err(pe("strip labels"))?;
            }
        }
        for (area, c, name) in [(&u_area, 0usize, "u′"), (&v_area, 1usize, "v′")] {
            let (t0, t1) = time_range(group);
            let (lo, hi) = padded(
                group
                    .iter()
                    .flat_map(|s| s.points.iter().filter_map(|p| p.uv.map(|uv| uv[c]))),
                0.004,
            );
            let mut chart = ChartBuilder::on(area)
                .margin(10)
                .x_label_area_size(36)
                .y_label_area_size(70)
                .build_cartesian_2d(t0..t1, lo..hi)
                .map_err(pe("u′v′ curves"))?;
            chart
                .configure_mesh()
                .light_line_style(RGBColor(235, 235, 235))
                .x_desc("time (s)")
                .y_desc(format!("{name} of the white (CIE 1976, unitless)"))
                .axis_desc_style((FONT, 13))
                .y_label_formatter(&|v| format!("{v:.3}"))
                .draw()
                .map_err(pe("u′v′ axes"))?;
            for s in group {
                for run in runs(s, |k| s.points[k].time, |k| s.points[k].uv.map(|uv| uv[c])) {
                    chart
                        .draw_series(LineSeries::new(run, stroke(s)))
                        .map_err(pe("u′v′ curves"))?;
                }
            }
        }
        let mut entries = series_entries(group);
        entries.push(Entry {
            name: "no defined white (strip)".into(),
            key: Key::Swatch,
        });
        legend(&right, "estimator", &entries)
    })
}

/// Fig. 11 analogue: the u′v′ trajectories on a chromaticity diagram with the Planckian locus.
pub fn chromaticity_plot(group: &[&Series], title: &str) -> Result<String, Failure> {
    let (w, h) = (1000u32, 760u32);
    let d65 = xyz_to_uv(D65_XYZ).expect("D65 has a chromaticity");
    svg((w, h), |root| {
        let (left, right) = root.split_horizontally(w - LEGEND_W);
        let (label_x, label_y, margin) = (44u32, 70u32, 10u32);
        let plot_w = (w - LEGEND_W - label_y - 2 * margin) as f64;
        let plot_h = (h - label_x - 2 * margin - 30) as f64;
        let us = group
            .iter()
            .flat_map(|s| s.points.iter().filter_map(|p| p.uv.map(|uv| uv[0])))
            .chain([d65.x]);
        let vs = group
            .iter()
            .flat_map(|s| s.points.iter().filter_map(|p| p.uv.map(|uv| uv[1])))
            .chain([d65.y]);
        let (mut u0, mut u1) = padded(us, 0.02);
        let (mut v0, mut v1) = padded(vs, 0.02);
        // Equal scales on both axes, so distances read as Δu′v′ in every direction.
        let scale = ((u1 - u0) / plot_w).max((v1 - v0) / plot_h);
        let (cu, cv) = ((u0 + u1) / 2.0, (v0 + v1) / 2.0);
        (u0, u1) = (cu - scale * plot_w / 2.0, cu + scale * plot_w / 2.0);
        (v0, v1) = (cv - scale * plot_h / 2.0, cv + scale * plot_h / 2.0);
        let inside = |p: [f64; 2]| p[0] >= u0 && p[0] <= u1 && p[1] >= v0 && p[1] <= v1;

        let mut chart = ChartBuilder::on(&left)
            .caption(title, (FONT, 17))
            .margin(margin)
            .x_label_area_size(label_x)
            .y_label_area_size(label_y)
            .build_cartesian_2d(u0..u1, v0..v1)
            .map_err(pe("chromaticity"))?;
        chart
            .configure_mesh()
            .light_line_style(RGBColor(235, 235, 235))
            .x_desc("u′ (CIE 1976 UCS, unitless)")
            .y_desc("v′ (CIE 1976 UCS, unitless)")
            .axis_desc_style((FONT, 13))
            .x_label_formatter(&|v| format!("{v:.3}"))
            .y_label_formatter(&|v| format!("{v:.3}"))
            .draw()
            .map_err(pe("chromaticity axes"))?;

        // The locus, clipped to the window by hand (plotters does not clip paths).
        let locus_style = RGBColor(120, 120, 120).stroke_width(2);
        let mut run: Vec<(f64, f64)> = Vec::new();
        for (_, p) in locus::locus_uv(600) {
            if inside(p) {
                run.push((p[0], p[1]));
            } else if !run.is_empty() {
                chart
                    .draw_series(DashedLineSeries::new(
                        std::mem::take(&mut run),
                        6,
                        4,
                        locus_style,
                    ))
                    .map_err(pe("locus"))?;
            }
        }
        if !run.is_empty() {
            chart
                .draw_series(DashedLineSeries::new(run, 6, 4, locus_style))
                .map_err(pe("locus"))?;
        }
        for t in [
            1700.0, 2000.0, 2500.0, 3000.0, 3500.0, 4000.0, 5000.0, 6500.0, 8000.0, 10000.0,
            15000.0, 25000.0,
        ] {
            let p = locus::planck_uv(t);
            if inside(p) {
                chart
                    .draw_series([Circle::new(
                        (p[0], p[1]),
                        3,
                        RGBColor(120, 120, 120).filled(),
                    )])
                    .map_err(pe("locus"))?;
                let (px, py) = chart.backend_coord(&(p[0], p[1]));
                root.draw(&Text::new(
                    format!("{t} K"),
                    (px - 7, py),
                    (FONT, 11)
                        .into_font()
                        .color(&RGBColor(90, 90, 90))
                        .pos(Pos::new(HPos::Right, VPos::Center)),
                ))
                .map_err(pe("locus"))?;
            }
        }
        chart
            .draw_series([Cross::new((d65.x, d65.y), 6, BLACK.stroke_width(2))])
            .map_err(pe("D65"))?;
        for s in group {
            let st = stroke(s);
            for run in runs(
                s,
                |k| s.points[k].uv.map_or(f64::NAN, |u| u[0]),
                |k| s.points[k].uv.map(|u| u[1]),
            ) {
                chart
                    .draw_series(LineSeries::new(run, st))
                    .map_err(pe("trajectories"))?;
            }
            let defined: Vec<[f64; 2]> = s.points.iter().filter_map(|p| p.uv).collect();
            if let (Some(a), Some(b)) = (defined.first(), defined.last()) {
                chart
                    .draw_series([
                        Circle::new((a[0], a[1]), 5, st),
                        Circle::new((b[0], b[1]), 5, st.filled()),
                    ])
                    .map_err(pe("trajectories"))?;
            }
        }
        let mut entries = series_entries(group);
        let grey = RGBColor(120, 120, 120).stroke_width(2);
        entries.extend([
            Entry {
                name: "first frame".into(),
                key: Key::Marker(BLACK.stroke_width(2), false),
            },
            Entry {
                name: "last frame".into(),
                key: Key::Marker(BLACK.stroke_width(2), true),
            },
            Entry {
                name: "Planckian locus (Kim et al. 2002)".into(),
                key: Key::Dashed(grey),
            },
            Entry {
                name: "D65 (display white)".into(),
                key: Key::Cross(BLACK.stroke_width(2)),
            },
        ]);
        legend(&right, "estimator", &entries)
    })
}

const THRESHOLD_NAMES: [&str; 3] = ["1 MacAdam step", "display JND", "7-step (large)"];

fn threshold_style(i: usize) -> ShapeStyle {
    [
        RGBColor(150, 150, 150),
        RGBColor(90, 90, 90),
        RGBColor(30, 30, 30),
    ][i.min(2)]
    .stroke_width(1)
}

/// Frame-to-frame Δu′v′ per estimator on a log axis, with the §7.1 thresholds.
pub fn steps_plot(
    group: &[&Series],
    reports: &[&EstimatorReport],
    title: &str,
) -> Result<String, Failure> {
    let (w, h) = (1150u32, 560u32);
    svg((w, h), |root| {
        let (left, right) = root.split_horizontally(w - LEGEND_W);
        let values = || {
            reports
                .iter()
                .flat_map(|r| r.steps.iter().copied())
                .filter(|v| v.is_finite() && *v > 0.0)
        };
        let max = values().fold(DEFAULT_THRESHOLDS[2], f64::max);
        let min = values().fold(DEFAULT_THRESHOLDS[0], f64::min);
        let floor = (min / 2.0).max(1e-7);
        let (t0, t1) = time_range(group);
        let mut chart = ChartBuilder::on(&left)
            .caption(title, (FONT, 17))
            .margin(10)
            .x_label_area_size(40)
            .y_label_area_size(80)
            .build_cartesian_2d(t0..t1, (floor..max * 1.5).log_scale())
            .map_err(pe("steps"))?;
        chart
            .configure_mesh()
            .light_line_style(RGBColor(235, 235, 235))
            .x_desc("time (s)")
            .y_desc("Δu′v′ from the previous frame (log scale; 0 drawn at the floor)")
            .axis_desc_style((FONT, 13))
            .y_label_formatter(&|v| format!("{v:.0e}"))
            .draw()
            .map_err(pe("steps axes"))?;
        for (i, th) in DEFAULT_THRESHOLDS.iter().enumerate() {
            chart
                .draw_series(DashedLineSeries::new(
                    [(t0, *th), (t1, *th)],
                    8,
                    5,
                    threshold_style(i),
                ))
                .map_err(pe("thresholds"))?;
        }
        for (s, r) in group.iter().zip(reports) {
            for run in runs(
                s,
                |k| s.points[k].time,
                |k| {
                    let d = r.steps[k];
                    (!d.is_nan()).then(|| d.max(floor))
                },
            ) {
                chart
                    .draw_series(LineSeries::new(run, stroke(s)))
                    .map_err(pe("steps"))?;
            }
        }
        let mut entries = series_entries(group);
        for (i, th) in DEFAULT_THRESHOLDS.iter().enumerate() {
            entries.push(Entry {
                name: format!("θ = {th} ({})", THRESHOLD_NAMES[i]),
                key: Key::Dashed(threshold_style(i)),
            });
        }
        legend(&right, "estimator", &entries)
    })
}

/// dE_cat per frame per estimator (§7.3), with the ΔE00 = 1 threshold.
pub fn de_cat_plot(
    group: &[&Series],
    reports: &[&EstimatorReport],
    title: &str,
) -> Result<String, Failure> {
    let (w, h) = (1150u32, 560u32);
    svg((w, h), |root| {
        let (left, right) = root.split_horizontally(w - LEGEND_W);
        let values = || {
            reports
                .iter()
                .filter_map(|r| r.image.as_ref())
                .flat_map(|m| m.per_frame.iter().map(|f| f.de_cat))
                .filter(|v| v.is_finite() && *v > 0.0)
        };
        let max = values().fold(2.0 * DEFAULT_DE_THRESHOLD, f64::max);
        let floor = (values().fold(0.1, f64::min) / 2.0).max(1e-5);
        let (t0, t1) = time_range(group);
        let mut chart = ChartBuilder::on(&left)
            .caption(title, (FONT, 17))
            .margin(10)
            .x_label_area_size(40)
            .y_label_area_size(80)
            .build_cartesian_2d(t0..t1, (floor..max * 1.5).log_scale())
            .map_err(pe("dE_cat"))?;
        chart
            .configure_mesh()
            .light_line_style(RGBColor(235, 235, 235))
            .x_desc("time (s)")
            .y_desc("dE_cat: mean ΔE00 due to the white's change (log; 0 at the floor)")
            .axis_desc_style((FONT, 13))
            .y_label_formatter(&|v| format!("{v:.0e}"))
            .draw()
            .map_err(pe("dE_cat axes"))?;
        let th = threshold_style(1);
        chart
            .draw_series(DashedLineSeries::new(
                [(t0, DEFAULT_DE_THRESHOLD), (t1, DEFAULT_DE_THRESHOLD)],
                8,
                5,
                th,
            ))
            .map_err(pe("dE_cat"))?;
        for (s, r) in group.iter().zip(reports) {
            let Some(m) = &r.image else { continue };
            for run in runs(
                s,
                |k| s.points[k].time,
                |k| {
                    let d = m.per_frame[k].de_cat;
                    (!d.is_nan()).then(|| d.max(floor))
                },
            ) {
                chart
                    .draw_series(LineSeries::new(run, stroke(s)))
                    .map_err(pe("dE_cat"))?;
            }
        }
        let mut entries = series_entries(group);
        entries.push(Entry {
            name: "ΔE00 = 1 (≈ 1 JND)".into(),
            key: Key::Dashed(th),
        });
        legend(&right, "estimator", &entries)
    })
}

#[cfg(test)]
mod tests {
    use super::*;

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
