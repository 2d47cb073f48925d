//! The key figure: the adaptation white over time, one small panel per estimator family with
//! `eye` drawn in every panel, u′ on the top row and v′ below. The rows share their axes, so
//! a panel that wanders more than another really does.
use super::{Area, FONT, GRID, draw_run, padded, pe, runs, stroke, svg, time_range};
use crate::palette::dash_of;
use crate::series::Series;
use eyeadapt_sequencer::Failure;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

/// Estimator families, each one panel; an estimator in none of them goes to "other".
const FAMILIES: &[(&str, &[&str])] = &[
    ("eye, field of view only", &["eye_fov"]),
    ("scene-aware (renderer AOVs)", &["wcam", "ncns"]),
    ("dominant light", &["dominant"]),
    (
        "image statistics: mean and brightest",
        &["grey_world", "white_patch"],
    ),
    (
        "image statistics: p-norms",
        &["shades_of_grey", "grey_edge"],
    ),
];

/// The panels: (title, members), in the order of [`FAMILIES`], empty families left out.
fn families<'a>(group: &[&'a Series]) -> Vec<(&'static str, Vec<&'a Series>)> {
    let mut out: Vec<(&'static str, Vec<&'a Series>)> = FAMILIES
        .iter()
        .map(|(title, names)| {
            let members = group
                .iter()
                .filter(|s| names.contains(&s.base.as_str()))
                .copied()
                .collect();
            (*title, members)
        })
        .collect();
    let known = |b: &str| b == "eye" || FAMILIES.iter().any(|(_, ns)| ns.contains(&b));
    out.push((
        "other",
        group.iter().filter(|s| !known(&s.base)).copied().collect(),
    ));
    out.retain(|(_, m)| !m.is_empty());
    if out.is_empty() {
        out.push(("eye", Vec::new()));
    }
    out
}

/// Where each key item of a column header goes: (x, y) per series, wrapping at `width`.
fn key_layout(width: i32, items: &[&Series]) -> Vec<(i32, i32)> {
    let (mut x, mut y) = (60, 30);
    let mut out = Vec::with_capacity(items.len());
    for s in items {
        let item_w = 35 + 7 * s.name.chars().count() as i32;
        if x > 60 && x + item_w > width {
            (x, y) = (60, y + 16);
        }
        out.push((x, y));
        x += item_w;
    }
    out
}

/// A column's key: eye first, then the family.
fn with_eye<'a>(eye: Option<&'a Series>, members: &[&'a Series]) -> Vec<&'a Series> {
    eye.into_iter().chain(members.iter().copied()).collect()
}

/// Family title and the members' names in their colours, above a column.
fn header(area: &Area, title: &str, items: &[&Series]) -> Result<(), Failure> {
    area.draw(&Text::new(
        title.to_string(),
        (60, 12),
        (FONT, 13).into_font().style(FontStyle::Bold),
    ))
    .map_err(pe("panel title"))?;
    let places = key_layout(area.dim_in_pixel().0 as i32, items);
    for (s, (x, y)) in items.iter().zip(places) {
        let style = stroke(s);
        match dash_of(s.filter.as_deref()) {
            Some(_) => area
                .draw(&PathElement::new(vec![(x, y), (x + 7, y)], style))
                .and_then(|_| area.draw(&PathElement::new(vec![(x + 11, y), (x + 18, y)], style))),
            None => area.draw(&PathElement::new(vec![(x, y), (x + 18, y)], style)),
        }
        .map_err(pe("panel key"))?;
        area.draw(&Text::new(
            s.name.clone(),
            (x + 23, y),
            TextStyle::from((FONT, 12).into_font()).pos(Pos::new(HPos::Left, VPos::Center)),
        ))
        .map_err(pe("panel key"))?;
    }
    Ok(())
}

/// u′(t) and v′(t) of each family (coloured) against `eye` (black, on top).
pub fn over_time_plot<'a>(group: &[&'a Series], title: &str) -> Result<String, Failure> {
    let eye = group.iter().copied().find(|s| s.base == "eye");
    let fams = families(group);
    let n = fams.len();
    let w = 1150u32;
    let items = |members: &[&'a Series]| with_eye(eye, members);
    // The header is as tall as the column whose key wraps the most.
    let col_w = (w / n as u32) as i32;
    let key_bottom = fams
        .iter()
        .flat_map(|(_, m)| key_layout(col_w, &items(m)))
        .map(|(_, y)| y)
        .max()
        .unwrap_or(30);
    let (title_h, header_h, panel_h) = (34u32, key_bottom as u32 + 16, 215u32);
    let h = title_h + header_h + 2 * panel_h;
    let ranges = [0usize, 1].map(|c| {
        padded(
            group
                .iter()
                .flat_map(|s| s.points.iter().filter_map(move |p| p.uv.map(|uv| uv[c]))),
            0.004,
        )
    });
    let (t0, t1) = time_range(group);
    svg((w, h), |root| {
        let (top, body) = root.split_vertically(title_h);
        top.draw(&Text::new(
            title.to_string(),
            (w as i32 / 2, 18),
            TextStyle::from((FONT, 17).into_font()).pos(Pos::new(HPos::Center, VPos::Center)),
        ))
        .map_err(pe("title"))?;
        let columns = body.split_evenly((1, n));
        for (col, (area, (fam_title, members))) in columns.iter().zip(&fams).enumerate() {
            let (head, panels) = area.split_vertically(header_h);
            header(&head, fam_title, &items(members))?;
            let (u_area, v_area) = panels.split_vertically(panel_h);
            for (row, (panel, name)) in [(&u_area, "u′"), (&v_area, "v′")].into_iter().enumerate()
            {
                let (lo, hi) = ranges[row];
                let mut chart = ChartBuilder::on(panel)
                    .margin_left(6)
                    .margin_right(10)
                    .margin_bottom(4)
                    .x_label_area_size(if row == 1 { 34 } else { 18 })
                    .y_label_area_size(54)
                    .build_cartesian_2d(t0..t1, lo..hi)
                    .map_err(pe("white over time"))?;
                let mut mesh = chart.configure_mesh();
                mesh.light_line_style(WHITE)
                    .bold_line_style(GRID)
                    .x_labels(5)
                    .y_labels(6)
                    .axis_desc_style((FONT, 12))
                    .y_label_formatter(&|v| format!("{v:.3}"));
                if col == 0 {
                    mesh.y_desc(format!("{name} of the white"));
                }
                if row == 1 {
                    mesh.x_desc("time (s)");
                }
                mesh.draw().map_err(pe("white over time axes"))?;
                for s in members.iter().chain(eye.iter()) {
                    for run in runs(
                        s,
                        |k| s.points[k].time,
                        |k| s.points[k].uv.map(|uv| uv[row]),
                    ) {
                        draw_run(&mut chart, run, s, stroke(s))?;
                    }
                }
            }
        }
        Ok(())
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn series(name: &str) -> Series {
        Series {
            name: name.into(),
            base: name.into(),
            filter: None,
            points: Vec::new(),
        }
    }

    #[test]
    fn every_estimator_lands_in_exactly_one_panel_and_eye_in_none() {
        let all: Vec<Series> = ["eye", "wcam", "dominant", "grey_edge", "mystery"]
            .into_iter()
            .map(series)
            .collect();
        let group: Vec<&Series> = all.iter().collect();
        let fams = families(&group);
        let titles: Vec<&str> = fams.iter().map(|(t, _)| *t).collect();
        assert_eq!(
            titles,
            [
                "scene-aware (renderer AOVs)",
                "dominant light",
                "image statistics: p-norms",
                "other"
            ]
        );
        let placed: Vec<&str> = fams
            .iter()
            .flat_map(|(_, m)| m.iter().map(|s| s.name.as_str()))
            .collect();
        assert_eq!(placed, ["wcam", "dominant", "grey_edge", "mystery"]);
        assert_eq!(
            families(&group[..1]).len(),
            1,
            "eye alone still gets a panel"
        );
    }
}
