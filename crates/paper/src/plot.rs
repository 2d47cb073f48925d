//! The sensitivity plot of a case: for each parameter of its study, the fraction of
//! configurations in which each claim holds, per level of that parameter (SVG, no scripts).
use crate::case_info::CaseInfo;
use crate::study::Study;
use std::fmt::Write;

const PANEL_W: f64 = 230.0;
const PANEL_H: f64 = 170.0;
const PAD: f64 = 40.0;
const COLOURS: [&str; 6] = [
    "#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e", "#8c564b",
];

fn esc(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

/// The SVG text. Claims are numbered as in RESULTS.md; a dashed line marks the 80 % that
/// "robust" needs.
pub fn sensitivity_svg(case: &CaseInfo, st: &Study) -> String {
    let claims: Vec<String> = st.baseline().iter().map(|v| v.claim.clone()).collect();
    let np = st.params.len().max(1);
    // Wide enough for the panels, the title and the legend's longest line (≈ 6 px a character).
    let legend_w = claims
        .iter()
        .enumerate()
        .map(|(i, c)| 6.0 * (c.chars().count() + st.robustness(i).chars().count() + 8) as f64)
        .fold(0.0, f64::max);
    let width = (PAD + np as f64 * (PANEL_W + PAD))
        .max(PAD + 18.0 + legend_w)
        .max(760.0);
    // Tick labels wider than their slot alternate between two rows.
    let crowded = |p: &crate::study::Param| {
        let widest = p.levels.iter().map(|l| l.label.chars().count()).max();
        6.0 * widest.unwrap_or(0) as f64 > PANEL_W / p.levels.len().max(1) as f64 - 4.0
    };
    let any_crowded = st.params.iter().any(crowded);
    let legend_y = PAD + PANEL_H + 50.0 + if any_crowded { 12.0 } else { 0.0 };
    let height = legend_y + 18.0 * claims.len() as f64 + 20.0;
    let mut s = String::new();
    let _ = writeln!(
        s,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{width:.0}" height="{height:.0}" viewBox="0 0 {width:.0} {height:.0}" font-family="sans-serif" font-size="11">"#
    );
    let _ = writeln!(
        s,
        r#"<rect width="100%" height="100%" fill="white"/><text x="{PAD}" y="18" font-size="13">Case {}: fraction of configurations in which each claim holds, per parameter level ({} configurations × {} seeds)</text>"#,
        case.number,
        st.configs.len(),
        st.seeds.len()
    );
    for (pi, p) in st.params.iter().enumerate() {
        let x0 = PAD + pi as f64 * (PANEL_W + PAD);
        let y0 = PAD;
        let rows = if crowded(p) { 12.0 } else { 0.0 };
        let _ = writeln!(
            s,
            r##"<rect x="{x0}" y="{y0}" width="{PANEL_W}" height="{PANEL_H}" fill="none" stroke="#999"/><text x="{:.1}" y="{:.1}" text-anchor="middle">{}</text>"##,
            x0 + PANEL_W / 2.0,
            y0 + PANEL_H + 32.0 + rows,
            esc(p.name)
        );
        let y_of = |f: f64| y0 + PANEL_H * (1.0 - f);
        for (f, label) in [(0.0, "0"), (0.5, "0.5"), (1.0, "1")] {
            let _ = writeln!(
                s,
                r##"<text x="{:.1}" y="{:.1}" text-anchor="end">{label}</text>"##,
                x0 - 4.0,
                y_of(f) + 4.0
            );
        }
        let _ = writeln!(
            s,
            r##"<line x1="{x0}" x2="{:.1}" y1="{:.1}" y2="{:.1}" stroke="#666" stroke-dasharray="4 3"/>"##,
            x0 + PANEL_W,
            y_of(0.8),
            y_of(0.8)
        );
        let n = p.levels.len();
        let x_of = |l: usize| x0 + PANEL_W * (l as f64 + 0.5) / n as f64;
        for (l, lev) in p.levels.iter().enumerate() {
            let _ = writeln!(
                s,
                r##"<text x="{:.1}" y="{:.1}" text-anchor="middle">{}</text>"##,
                x_of(l),
                y0 + PANEL_H + 14.0 + rows * (l % 2) as f64,
                esc(&lev.label)
            );
        }
        for (ci, _) in claims.iter().enumerate() {
            let colour = COLOURS[ci % COLOURS.len()];
            // Claims drawn with a small vertical offset each, so equal fractions stay visible.
            let dy = (ci as f64 - claims.len() as f64 / 2.0) * 2.0;
            let pts: Vec<(f64, f64)> = (0..n)
                .map(|l| (x_of(l), y_of(st.level_fraction(ci, pi, l)) + dy))
                .filter(|(_, y)| y.is_finite())
                .collect();
            let path: Vec<String> = pts.iter().map(|(x, y)| format!("{x:.1},{y:.1}")).collect();
            let _ = writeln!(
                s,
                r#"<polyline points="{}" fill="none" stroke="{colour}" stroke-width="1.5"/>"#,
                path.join(" ")
            );
            for (x, y) in pts {
                let _ = writeln!(
                    s,
                    r#"<circle cx="{x:.1}" cy="{y:.1}" r="3" fill="{colour}"/>"#
                );
            }
        }
    }
    for (ci, c) in claims.iter().enumerate() {
        let y = legend_y + 18.0 * ci as f64;
        let _ = writeln!(
            s,
            r#"<rect x="{PAD}" y="{:.1}" width="12" height="12" fill="{}"/><text x="{:.1}" y="{:.1}">{}. {} — {}</text>"#,
            y - 10.0,
            COLOURS[ci % COLOURS.len()],
            PAD + 18.0,
            y,
            ci + 1,
            esc(c),
            esc(&st.robustness(ci))
        );
    }
    s.push_str("</svg>\n");
    s
}
