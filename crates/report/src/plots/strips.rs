//! The paper's Fig. 14 analogue: the colour each estimator adapts to, frame by frame, as one
//! strip per estimator (hue and saturation of the white, not its brightness).
use super::{Area, Entry, FONT, Key, LEGEND_W, UNDEFINED, display_colour, legend, pe, svg};
use crate::series::Series;
use eyeadapt_sequencer::Failure;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

/// One strip per estimator; grey where its white is undefined.
pub fn strips_plot(group: &[&Series], title: &str, fps: f64) -> Result<String, Failure> {
    let n = group.len();
    let h = 90 + 20 * n as u32;
    let w = 1150;
    let longest = group
        .iter()
        .map(|s| s.name.chars().count())
        .max()
        .unwrap_or(4) as u32;
    svg((w, h), |root: &Area| {
        let (left, right) = root.split_horizontally(w - LEGEND_W);
        let p = &group[0].points;
        let (f0, f1) = (p[0].frame as f64, p[p.len() - 1].frame as f64 + 1.0);
        let mut chart = ChartBuilder::on(&left)
            .caption(title, (FONT, 17))
            .margin(10)
            .x_label_area_size(36)
            .y_label_area_size(30 + 7 * longest)
            .build_cartesian_2d(f0..f1, 0f64..n as f64)
            .map_err(pe("strip"))?;
        chart
            .configure_mesh()
            .disable_mesh()
            .y_labels(0)
            .x_desc(format!("frame ({fps} frames/s)"))
            .x_label_formatter(&|v| format!("{v:.0}"))
            .axis_desc_style((FONT, 13))
            .draw()
            .map_err(pe("strip axes"))?;
        for (i, s) in group.iter().enumerate() {
            let y0 = (n - 1 - i) as f64;
            // Grey under the row: frames without a defined white. (A defined white is never
            // grey: its display colour has a channel at 1.)
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
                TextStyle::from((FONT, 12).into_font()).pos(Pos::new(HPos::Right, VPos::Center)),
            ))
            .map_err(pe("strip labels"))?;
        }
        legend(
            &right,
            "strip",
            &[Entry {
                name: "no defined white".into(),
                key: Key::Swatch,
            }],
        )
    })
}
