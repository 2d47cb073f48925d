//! Per-frame changes as small multiples: one panel per estimator, with `eye` (black) in every
//! panel as the yardstick, on one shared log axis, and the thresholds as dark dashed lines
//! labelled beside each panel. Eight overlapping log-scale lines cannot be read; a pair can.
use super::{FONT, GRID, REFERENCE, pe, runs, svg, time_range};
use crate::coherence::EstimatorReport;
use crate::palette::colour_of;
use crate::series::Series;
use eyeadapt_color::{DEFAULT_DE_THRESHOLD, DEFAULT_THRESHOLDS};
use eyeadapt_sequencer::Failure;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

const COLUMNS: usize = 4;

/// What one small-multiples figure shows.
struct Multiples<'a> {
    title: &'a str,
    /// Under the title: what black, colour and the dashed lines are.
    key: String,
    y_desc: &'a str,
    /// (value, label) of each reference line.
    thresholds: Vec<(f64, String)>,
    /// Smallest value the axis must show (the floor is half the smallest positive value).
    min: f64,
}

/// The per-frame value of series `k` of `reports`, or None where undefined.
type Value<'a> = &'a dyn Fn(&EstimatorReport, usize) -> f64;

fn multiples(
    group: &[&Series],
    reports: &[&EstimatorReport],
    m: &Multiples,
    value: Value,
) -> Result<String, Failure> {
    let eye = group.iter().position(|s| s.base == "eye");
    let panels: Vec<usize> = (0..group.len()).filter(|&k| Some(k) != eye).collect();
    let panels = if panels.is_empty() { vec![0] } else { panels };
    let rows = panels.len().div_ceil(COLUMNS);
    let (w, head_h, panel_h) = (1150u32, 52u32, 220u32);
    let h = head_h + rows as u32 * panel_h;
    let positive = || {
        reports.iter().flat_map(|r| {
            (0..r.steps.len())
                .map(move |k| value(r, k))
                .filter(|v| v.is_finite() && *v > 0.0)
        })
    };
    let top = positive().fold(m.thresholds.last().map_or(m.min, |t| t.0) * 1.5, f64::max) * 1.5;
    let floor = (positive().fold(m.min, f64::min) / 2.0).max(1e-7);
    let (t0, t1) = time_range(group);
    svg((w, h), |root| {
        let (head, body) = root.split_vertically(head_h);
        head.draw(&Text::new(
            m.title.to_string(),
            (w as i32 / 2, 16),
            TextStyle::from((FONT, 17).into_font()).pos(Pos::new(HPos::Center, VPos::Center)),
        ))
        .map_err(pe("title"))?;
        head.draw(&Text::new(
            m.key.clone(),
            (w as i32 / 2, 38),
            TextStyle::from((FONT, 12).into_font()).pos(Pos::new(HPos::Center, VPos::Center)),
        ))
        .map_err(pe("title"))?;
        let areas = body.split_evenly((rows, COLUMNS));
        for (slot, &k) in panels.iter().enumerate() {
            let s = group[k];
            let area = &areas[slot];
            let col = slot % COLUMNS;
            let mut chart = ChartBuilder::on(area)
                .caption(
                    &s.name,
                    (FONT, 14)
                        .into_font()
                        .style(FontStyle::Bold)
                        .color(&colour_of(&s.base)),
                )
                .margin_top(4)
                .margin_left(4)
                .margin_right(40)
                .x_label_area_size(32)
                .y_label_area_size(48)
                .build_cartesian_2d(t0..t1, (floor..top).log_scale())
                .map_err(pe(m.title))?;
            let mut mesh = chart.configure_mesh();
            mesh.light_line_style(WHITE)
                .bold_line_style(GRID)
                .x_labels(5)
                .y_labels(5)
                .x_desc("time (s)")
                .axis_desc_style((FONT, 12))
                .y_label_formatter(&|v| format!("{v:.0e}"));
            if col == 0 {
                mesh.y_desc(m.y_desc);
            }
            mesh.draw().map_err(pe(m.title))?;
            for (th, label) in &m.thresholds {
                chart
                    .draw_series(DashedLineSeries::new(
                        [(t0, *th), (t1, *th)],
                        6,
                        4,
                        REFERENCE.stroke_width(1),
                    ))
                    .map_err(pe("thresholds"))?;
                let (px, py) = chart.backend_coord(&(t1, *th));
                root.draw(&Text::new(
                    label.clone(),
                    (px + 4, py),
                    TextStyle::from((FONT, 10).into_font())
                        .color(&REFERENCE)
                        .pos(Pos::new(HPos::Left, VPos::Center)),
                ))
                .map_err(pe("thresholds"))?;
            }
            // eye first, underneath: the panel's estimator stays visible where they meet.
            for (j, width) in eye.map(|e| (e, 2)).into_iter().chain([(k, 2)]) {
                let (sj, rj) = (group[j], reports[j]);
                let style = colour_of(&sj.base).stroke_width(width);
                for run in runs(
                    sj,
                    |i| sj.points[i].time,
                    |i| {
                        let d = value(rj, i);
                        (!d.is_nan()).then(|| d.max(floor))
                    },
                ) {
                    chart
                        .draw_series(LineSeries::new(run, style))
                        .map_err(pe(m.title))?;
                }
            }
        }
        Ok(())
    })
}

/// Frame-to-frame Δu′v′ of each estimator against eye's, with the §7.1 thresholds.
pub fn steps_plot(
    group: &[&Series],
    reports: &[&EstimatorReport],
    title: &str,
) -> Result<String, Failure> {
    let names = ["1 MacAdam step", "display JND", "large"];
    let m = Multiples {
        title,
        key: format!(
            "black: eye in every panel · dashed: θ = {} ({}), {} ({}), {} ({}) · a zero step is drawn at the bottom",
            DEFAULT_THRESHOLDS[0],
            names[0],
            DEFAULT_THRESHOLDS[1],
            names[1],
            DEFAULT_THRESHOLDS[2],
            names[2]
        ),
        y_desc: "Δu′v′ from the previous frame",
        thresholds: DEFAULT_THRESHOLDS
            .iter()
            .map(|t| (*t, format!("{t}")))
            .collect(),
        min: DEFAULT_THRESHOLDS[0],
    };
    multiples(group, reports, &m, &|r, k| r.steps[k])
}

/// dE_cat per frame (§7.3) of each estimator against eye's, with ΔE00 = 1.
pub fn de_cat_plot(
    group: &[&Series],
    reports: &[&EstimatorReport],
    title: &str,
) -> Result<String, Failure> {
    let m = Multiples {
        title,
        key: "black: eye in every panel · dashed: ΔE00 = 1 (≈ 1 just-noticeable difference) · zero drawn at the bottom".into(),
        y_desc: "dE_cat (ΔE00)",
        thresholds: vec![(DEFAULT_DE_THRESHOLD, "ΔE 1".into())],
        min: 0.1,
    };
    multiples(group, reports, &m, &|r, k| {
        r.image.as_ref().map_or(f64::NAN, |i| i.per_frame[k].de_cat)
    })
}
