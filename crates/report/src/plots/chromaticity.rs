//! The paper's Fig. 11 analogue: where each estimator's white travels on the CIE 1976 UCS
//! diagram, with the Planckian locus and D65.
//!
//! Nothing hides anything else: `eye` is drawn after the other series, the markers after all
//! lines, and D65 last, as a ring with a cross and a label, so an estimator that sits on D65
//! (a white light's `dominant`) shows inside its ring. Temperature labels sit on the side of
//! the locus away from the data, on a white ground, and a label that would overlap the one
//! before it is left out.
use super::{
    Area, Entry, FONT, GRID, Key, LEGEND_W, REFERENCE, draw_run, legend, padded, pe, runs,
    series_entries, stroke, svg,
};
use crate::locus;
use crate::series::Series;
use eyeadapt_color::{D65_XYZ, xyz_to_uv};
use eyeadapt_sequencer::Failure;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

const TEMPERATURES: [f64; 12] = [
    1700.0, 2000.0, 2500.0, 3000.0, 3500.0, 4000.0, 5000.0, 6500.0, 8000.0, 10000.0, 15000.0,
    25000.0,
];
const D65_COLOUR: RGBColor = RGBColor(0, 0, 0);

/// "6500 K", "25 000 K".
fn kelvin(t: f64) -> String {
    let t = t.round() as u64;
    if t >= 10_000 {
        format!("{} {:03} K", t / 1000, t % 1000)
    } else {
        format!("{t} K")
    }
}

/// A label's box in pixels: left, top, right, bottom.
type Rect = (i32, i32, i32, i32);
/// Where a label is drawn: its anchor point, which end of the text is at it, and its box.
type Place = ((i32, i32), HPos, Rect);

fn overlaps(a: Rect, b: Rect) -> bool {
    a.0 < b.2 && b.0 < a.2 && a.1 < b.3 && b.1 < a.3
}

/// Where a temperature label of `size` pixels goes next to the locus point `p`: of the eight
/// places around it, the one that covers the fewest data points (`data`, pixels), staying
/// inside `area` and off the labels already `taken`; ties go to the side away from the data's
/// centre. `None` when every place is outside or taken.
fn label_place(
    p: (i32, i32),
    size: (i32, i32),
    data: &[(i32, i32)],
    taken: &[Rect],
    area: Rect,
) -> Option<Place> {
    let (w, h) = size;
    let n = data.len().max(1) as f64;
    let centre = (
        data.iter().map(|d| d.0 as f64).sum::<f64>() / n,
        data.iter().map(|d| d.1 as f64).sum::<f64>() / n,
    );
    let mut best: Option<(usize, f64, Place)> = None;
    for (dx, dy) in [
        (-1, 0),
        (1, 0),
        (-1, -1),
        (1, 1),
        (-1, 1),
        (1, -1),
        (0, -1),
        (0, 1),
    ] {
        let at = (p.0 + 8 * dx, p.1 + 12 * dy);
        let (hpos, left) = match dx {
            -1 => (HPos::Right, at.0 - w),
            1 => (HPos::Left, at.0),
            _ => (HPos::Center, at.0 - w / 2),
        };
        let rect = (left - 2, at.1 - h / 2 - 1, left + w + 2, at.1 + h / 2 + 1);
        let outside = rect.0 < area.0 || rect.1 < area.1 || rect.2 > area.2 || rect.3 > area.3;
        if outside || taken.iter().any(|t| overlaps(*t, rect)) {
            continue;
        }
        let covered = data
            .iter()
            .filter(|d| {
                d.0 >= rect.0 - 3 && d.0 <= rect.2 + 3 && d.1 >= rect.1 - 3 && d.1 <= rect.3 + 3
            })
            .count();
        // Closer to the data's centre is worse.
        let near = -((at.0 as f64 - centre.0).powi(2) + (at.1 as f64 - centre.1).powi(2));
        if best
            .as_ref()
            .is_none_or(|(c, d, _)| covered < *c || (covered == *c && near < *d))
        {
            best = Some((covered, near, (at, hpos, rect)));
        }
    }
    best.map(|(_, _, place)| place)
}

/// u′v′ trajectories of every series of `group`.
pub fn chromaticity_plot(group: &[&Series], title: &str) -> Result<String, Failure> {
    let (w, h) = (1000u32, 760u32);
    let d65 = xyz_to_uv(D65_XYZ).expect("D65 has a chromaticity");
    svg((w, h), |root| {
        let (left, right) = root.split_horizontally(w - LEGEND_W);
        let (label_x, label_y, margin) = (44u32, 70u32, 10u32);
        let plot_w = (w - LEGEND_W - label_y - 2 * margin) as f64;
        let plot_h = (h - label_x - 2 * margin - 30) as f64;
        let defined = || {
            group
                .iter()
                .flat_map(|s| s.points.iter().filter_map(|p| p.uv))
        };
        let (mut u0, mut u1) = padded(defined().map(|uv| uv[0]).chain([d65.x]), 0.02);
        let (mut v0, mut v1) = padded(defined().map(|uv| uv[1]).chain([d65.y]), 0.02);
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
            .light_line_style(WHITE)
            .bold_line_style(GRID)
            .x_desc("u′ (CIE 1976 UCS, unitless)")
            .y_desc("v′ (CIE 1976 UCS, unitless)")
            .axis_desc_style((FONT, 13))
            .x_label_formatter(&|v| format!("{v:.3}"))
            .y_label_formatter(&|v| format!("{v:.3}"))
            .draw()
            .map_err(pe("chromaticity axes"))?;
        draw_locus(root, &mut chart, group, &inside)?;

        // Lines: everything but eye, then eye on top; then the markers, eye's last.
        let mut order: Vec<&Series> = group.iter().copied().filter(|s| s.base != "eye").collect();
        order.extend(group.iter().copied().filter(|s| s.base == "eye"));
        for s in &order {
            for run in runs(
                s,
                |k| s.points[k].uv.map_or(f64::NAN, |u| u[0]),
                |k| s.points[k].uv.map(|u| u[1]),
            ) {
                draw_run(&mut chart, run, s, stroke(s))?;
            }
        }
        for s in &order {
            let st = stroke(s);
            let ends: Vec<[f64; 2]> = s.points.iter().filter_map(|p| p.uv).collect();
            if let (Some(a), Some(b)) = (ends.first(), ends.last()) {
                chart
                    .draw_series([
                        Circle::new((a[0], a[1]), 5, WHITE.filled()),
                        Circle::new((a[0], a[1]), 5, st),
                        Circle::new((b[0], b[1]), 4, st.filled()),
                    ])
                    .map_err(pe("trajectories"))?;
            }
        }
        // D65 last: a ring that leaves what is under it visible, a cross, and its name.
        let ring = D65_COLOUR.stroke_width(2);
        chart
            .draw_series([EmptyElement::at((d65.x, d65.y))
                + Circle::new((0, 0), 10, ring)
                + Cross::new((0, 0), 4, ring)])
            .map_err(pe("D65"))?;
        let (px, py) = chart.backend_coord(&(d65.x, d65.y));
        halo_text(
            root,
            "D65",
            (px + 13, py - 13),
            HPos::Left,
            (13.0, D65_COLOUR, true),
        )?;

        let mut entries = series_entries(group);
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
                key: Key::Dashed(REFERENCE.stroke_width(2)),
            },
            Entry {
                name: "D65 (display white)".into(),
                key: Key::Cross(ring),
            },
        ]);
        legend(&right, "estimator", &entries)
    })
}

/// Text on a white ground, so lines under it do not cross it.
fn halo_text(
    root: &Area,
    text: &str,
    at: (i32, i32),
    h: HPos,
    font: (f64, RGBColor, bool),
) -> Result<(), Failure> {
    let (size, colour, bold) = font;
    let width = (text.chars().count() as f64 * size * 0.58).ceil() as i32;
    let x0 = match h {
        HPos::Left => at.0 - 2,
        HPos::Right => at.0 - width - 2,
        HPos::Center => at.0 - width / 2 - 2,
    };
    let half = (size * 0.6).ceil() as i32;
    root.draw(&Rectangle::new(
        [(x0, at.1 - half), (x0 + width + 4, at.1 + half)],
        WHITE.mix(0.85).filled(),
    ))
    .map_err(pe("label"))?;
    let style = if bold {
        FontStyle::Bold
    } else {
        FontStyle::Normal
    };
    root.draw(&Text::new(
        text.to_string(),
        at,
        TextStyle::from((FONT, size).into_font().style(style))
            .color(&colour)
            .pos(Pos::new(h, VPos::Center)),
    ))
    .map_err(pe("label"))
}

/// The locus (clipped to the window by hand: plotters does not clip paths), its temperature
/// marks and their labels.
fn draw_locus<DB: DrawingBackend>(
    root: &Area,
    chart: &mut ChartContext<
        '_,
        DB,
        Cartesian2d<plotters::coord::types::RangedCoordf64, plotters::coord::types::RangedCoordf64>,
    >,
    group: &[&Series],
    inside: &dyn Fn([f64; 2]) -> bool,
) -> Result<(), Failure> {
    let style = REFERENCE.stroke_width(2);
    let mut run: Vec<(f64, f64)> = Vec::new();
    let mut flush = |run: &mut Vec<(f64, f64)>| -> Result<(), Failure> {
        if !run.is_empty() {
            chart
                .draw_series(DashedLineSeries::new(std::mem::take(run), 6, 4, style))
                .map_err(pe("locus"))?;
        }
        Ok(())
    };
    for (_, p) in locus::locus_uv(600) {
        if inside(p) {
            run.push((p[0], p[1]));
        } else {
            flush(&mut run)?;
        }
    }
    flush(&mut run)?;
    // Labels avoid the data (every defined white, in pixels) and each other.
    let data: Vec<(i32, i32)> = group
        .iter()
        .flat_map(|s| s.points.iter().filter_map(|p| p.uv))
        .map(|uv| chart.backend_coord(&(uv[0], uv[1])))
        .collect();
    let (xr, yr) = (
        chart.plotting_area().get_x_range(),
        chart.plotting_area().get_y_range(),
    );
    let corner = |u: f64, v: f64| chart.backend_coord(&(u, v));
    let (lt, rb) = (corner(xr.start, yr.end), corner(xr.end, yr.start));
    let area = (lt.0, lt.1, rb.0, rb.1);
    let mut taken: Vec<Rect> = Vec::new();
    for t in TEMPERATURES {
        let p = locus::planck_uv(t);
        if !inside(p) {
            continue;
        }
        chart
            .draw_series([Circle::new((p[0], p[1]), 3, REFERENCE.filled())])
            .map_err(pe("locus"))?;
        let px = chart.backend_coord(&(p[0], p[1]));
        let text = kelvin(t);
        let size = (
            (text.chars().count() as f64 * 11.0 * 0.58).ceil() as i32,
            13,
        );
        let Some((at, h, rect)) = label_place(px, size, &data, &taken, area) else {
            continue;
        };
        halo_text(root, &text, at, h, (11.0, REFERENCE, false))?;
        taken.push(rect);
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn labels_go_where_there_is_no_data() {
        let area = (0, 0, 400, 400);
        // Data to the right of the point: the label goes left.
        let data: Vec<(i32, i32)> = (0..20).map(|k| (110 + 5 * k, 100)).collect();
        let (at, h, _) = label_place((100, 100), (40, 12), &data, &[], area).unwrap();
        assert!(at.0 < 100 && matches!(h, HPos::Right), "{at:?}");
        // Data to the left too, on the same row: above or below instead.
        let both: Vec<(i32, i32)> = (0..40).map(|k| (20 + 8 * k, 100)).collect();
        let (at, _, _) = label_place((100, 100), (40, 12), &both, &[], area).unwrap();
        assert_ne!(at.1, 100, "{at:?}");
        // A place already taken is not used again, and nothing outside the area.
        assert!(label_place((100, 100), (40, 12), &[], &[(0, 0, 400, 400)], area).is_none());
        assert!(label_place((2, 2), (40, 12), &[], &[], (0, 0, 30, 30)).is_none());
        assert_eq!(kelvin(25000.0), "25 000 K");
        assert_eq!(kelvin(6500.0), "6500 K");
    }
}
