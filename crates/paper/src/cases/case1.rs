//! Case 1: white Cornell box, orange light (Fig. 5).
use super::*;

const CLAIM1: &str = "\"The first standard test case consists of a white Cornell box with an orange light source (see Figure 5). In this case Wilkie's method and ours provide the same adaptation color which corresponds to the expected one.\" (§5.1)";

pub(super) fn case1(runs: &[JobRun]) -> (&'static str, Out) {
    let run = &runs[0];
    let shot = &run.shots[0];
    let es = ests(run, shot);
    let light = light_colour(run.scene());
    let light_uv = uv_of_rgb(light);
    let mut o = Out::new();
    let _ = writeln!(o.md, "**Setup.** {}", setup_line(run));
    let _ = writeln!(
        o.md,
        "Every surface has reflectance 0.73 (grey), so the expected adaptation colour is the light's: a 2700 K blackbody, linear sRGB {} (u′v′ = ({:.4}, {:.4})).\n",
        fmt3(light / rgb_to_xyz(light).y),
        light_uv.x,
        light_uv.y
    );
    let mut t = Table::new(&["estimator", "u′v′", "Δu′v′ to the light", "≤ 2e-3"]);
    let mut worst = 0.0f64;
    for e in &es {
        let d = e.uv().map_or(f64::NAN, |p| delta_uv(p, light_uv));
        let ok = d <= CASE1_TOLERANCE;
        worst = if d.is_nan() { d } else { worst.max(d) };
        o.metric(format!("{}.duv_light", e.name), d);
        t.row(vec![
            format!("`{}`", e.name),
            uv_cell(e.uv()),
            f(d, 6),
            yes(ok).into(),
        ]);
    }
    o.md.push_str(&t.render());
    let (eye, wcam) = (find(&es, "eye"), find(&es, "wcam"));
    let de = o.metrics["eye.duv_light"];
    let dw = o.metrics["wcam.duv_light"];
    let dew = match (eye.uv(), wcam.uv()) {
        (Some(a), Some(b)) => delta_uv(a, b),
        _ => f64::NAN,
    };
    o.metric("eye_wcam.duv", dew);
    o.claim(
        "WCAM and eye give the same adaptation colour, the expected one (the light's)",
        vec![
            below("Δu′v′(eye, light)", de, CASE1_TOLERANCE),
            below("Δu′v′(WCAM, light)", dw, CASE1_TOLERANCE),
            below("Δu′v′(eye, WCAM)", dew, CASE1_TOLERANCE),
        ],
    );
    o.claim(
        "(project check) every estimator finds the light's chromaticity in a grey world",
        vec![below(
            "largest Δu′v′(estimator, light) in the table",
            worst,
            CASE1_TOLERANCE,
        )],
    );
    (CLAIM1, o)
}
