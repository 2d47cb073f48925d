//! Case 2: worlds of one reflectance (Fig. 6, 7).
use super::*;

const CLAIM2: &str = "\"The second test case is the worlds of one reflectance: White World-Orange Light and Orange World-White Light. Wilkie's method and ours give the expected adaptation colors. The actual object reflectances are recovered in both cases (Figure 6 and 7).\" (§5.1)";

/// The back-wall patch both worlds are read at.
fn case2_region() -> Region {
    Region::new(
        "back wall",
        "surface",
        [-0.5, 1.6, -2.52],
        [0.5, 2.2, -2.48],
    )
}

pub(super) fn case2(runs: &[JobRun]) -> (&'static str, Out) {
    let mut o = Out::new();
    let mut judged: Vec<(String, Vec<Check>)> = Vec::new();
    for (run, key, title) in [
        (&runs[0], "white", "White world, orange light (Fig. 6)"),
        (&runs[1], "orange", "Orange world, white light (Fig. 7)"),
    ] {
        let shot = &run.shots[0];
        let img = shot.image.as_ref().expect("stills keep their image");
        let es = ests(run, shot);
        let r = region_mean(run.scene(), img, &shot.view, &case2_region());
        let rho = r.reflectance;
        let ref_hsv = hsv_of_linear(rho);
        let light = light_colour(run.scene());
        let _ = writeln!(o.md, "**{title}.** {}", setup_line(run));
        let _ = writeln!(
            o.md,
            "Every surface has reflectance {}; light {}. Read-out: the back wall, {} pixels (x ∈ [−0.5, 0.5] m, y ∈ [1.6, 2.2] m). True reflectance: hue {}, S {}.\n",
            fmt3(rho),
            fmt3(light),
            r.pixels,
            hue_cell(ref_hsv.h, ref_hsv.s),
            pct(ref_hsv.s)
        );
        o.metric(format!("{key}.reflectance.hue"), ref_hsv.h);
        o.metric(format!("{key}.reflectance.sat"), ref_hsv.s);
        o.metric(format!("{key}.pixels"), r.pixels as f64);
        let light_uv = uv_of_rgb(light);
        let mut t = Table::new(&[
            "estimator",
            "u′v′",
            "Δu′v′ to the light",
            "wall hue",
            "wall S",
            "Δhue vs reflectance",
            "S / S(reflectance)",
        ]);
        let raw_hsv = equal_luminance_hsv(r.rgb, rho);
        t.row(vec![
            "raw (no adaptation)".into(),
            "–".into(),
            "–".into(),
            hue_cell(raw_hsv.h, raw_hsv.s),
            pct(raw_hsv.s),
            dh_cell(raw_hsv.h, raw_hsv.s, ref_hsv.h, ref_hsv.s),
            s_ratio_cell(raw_hsv.s, ref_hsv.s),
        ]);
        for e in &es {
            let hsv = equal_luminance_hsv(e.m * r.rgb, rho);
            o.metric(format!("{key}.{}.hue", e.name), hsv.h);
            o.metric(format!("{key}.{}.sat", e.name), hsv.s);
            let d = e.uv().map_or(f64::NAN, |p| delta_uv(p, light_uv));
            o.metric(format!("{key}.{}.duv_light", e.name), d);
            t.row(vec![
                format!("`{}`", e.name),
                uv_cell(e.uv()),
                f(d, 5),
                hue_cell(hsv.h, hsv.s),
                pct(hsv.s),
                dh_cell(hsv.h, hsv.s, ref_hsv.h, ref_hsv.s),
                s_ratio_cell(hsv.s, ref_hsv.s),
            ]);
            if e.name == "eye" || e.name == "wcam" {
                let checks = if key == "white" {
                    vec![below("grey wall S", hsv.s, 0.01)]
                } else {
                    vec![
                        below(
                            "orange wall |hue − reflectance's| (°)",
                            hue_diff(hsv.h, ref_hsv.h).abs(),
                            10.0,
                        ),
                        above("orange wall S / reflectance's S", hsv.s / ref_hsv.s, 0.5),
                    ]
                };
                judged.push((e.name.to_string(), checks));
            }
        }
        o.md.push_str(&t.render());
        o.md.push('\n');
    }
    for name in ["eye", "wcam"] {
        let checks: Vec<Check> = judged
            .iter()
            .filter(|(n, _)| n == name)
            .flat_map(|(_, c)| c.iter().cloned())
            .collect();
        o.claim(
            &format!(
                "{}: the reflectances are recovered in both worlds",
                if name == "eye" { "eye" } else { "WCAM" }
            ),
            checks,
        );
    }
    (CLAIM2, o)
}

fn dh_cell(h: f64, s: f64, h_ref: f64, s_ref: f64) -> String {
    if s < 0.0005 || s_ref < 0.0005 {
        "–".into()
    } else {
        format!("{:+.1}°", hue_diff(h, h_ref))
    }
}

fn s_ratio_cell(s: f64, s_ref: f64) -> String {
    if s_ref < 0.0005 {
        "–".into()
    } else {
        format!("{:.2}", s / s_ref)
    }
}
