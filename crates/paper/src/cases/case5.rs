//! Case 5: two rooms, three views (Fig. 10-12).
use super::*;

const CLAIM5: &str = "\"In this case, WCAM computes three different adaptation colors because it considers only the visible objects to compute the adaptation color. Regarding our method, it also computes three adaptation colors which are very close to each other (Figure 11). This can be explained by the fact that our approach is sensitive to where the camera is located rather than the visible surfaces.\" (§5.2)";

const VIEW_NAMES: [&str; 4] = [
    "view 1 (red): room 1 only",
    "view 2 (green): both rooms",
    "view 3 (blue): room 2 only",
    "supplementary: facing away from the doorway",
];

fn spread(points: &[Option<DVec2>]) -> f64 {
    let mut m: f64 = 0.0;
    for (i, a) in points.iter().enumerate() {
        for b in &points[i + 1..] {
            match (a, b) {
                (Some(a), Some(b)) => m = m.max(delta_uv(*a, *b)),
                _ => return f64::NAN,
            }
        }
    }
    m
}

pub(super) fn case5(runs: &[JobRun]) -> (&'static str, Out) {
    let run = &runs[0];
    let mut o = Out::new();
    let _ = writeln!(o.md, "**Setup.** {}", setup_line(run));
    let _ = writeln!(
        o.md,
        "The camera stays at {} in room 1, 4 m from the doorway, and turns: {}. The fourth frame is not in the paper; it faces away from the doorway and shows how the eye estimate depends on the gaze (the cardioid weights light from behind by 0). Spread = the largest pairwise Δu′v′ among the three paper views. Orange light u′v′ = {}, blue light u′v′ = {}.\n",
        fmt3(run.shots[0].view.position.as_dvec3()),
        run.shots
            .iter()
            .zip(VIEW_NAMES)
            .map(|(s, n)| {
                let fwd = s.view.forward;
                format!(
                    "frame {} = {n}, yaw {:.0}° from +x",
                    s.frame,
                    libm::atan2f(fwd.z, fwd.x).to_degrees()
                )
            })
            .collect::<Vec<_>>()
            .join("; "),
        uv_cell(Some(uv_of_rgb(reflectance_emission(
            run.scene(),
            "orange_light"
        )))),
        uv_cell(Some(uv_of_rgb(reflectance_emission(
            run.scene(),
            "blue_light"
        )))),
    );
    let per_shot: Vec<Vec<Est>> = run.shots.iter().map(|s| ests(run, s)).collect();
    let mut head = vec!["estimator".to_string()];
    for (i, _) in run.shots.iter().enumerate().take(3) {
        head.push(format!("view {} u′v′", i + 1));
    }
    head.push("spread (views 1–3)".into());
    if run.shots.len() > 3 {
        head.push("supplementary view u′v′".into());
    }
    let mut t = Table {
        head,
        rows: Vec::new(),
    };
    for (k, e) in per_shot[0].iter().enumerate() {
        let uvs: Vec<Option<DVec2>> = per_shot.iter().map(|es| es[k].uv()).collect();
        let s = spread(&uvs[..3.min(uvs.len())]);
        o.metric(format!("{}.spread", e.name), s);
        for (v, uv) in uvs.iter().enumerate() {
            if let Some(p) = uv {
                o.metric(format!("{}.view{}.u", e.name, v + 1), p.x);
                o.metric(format!("{}.view{}.v", e.name, v + 1), p.y);
            }
        }
        let mut row = vec![format!("`{}`", e.name)];
        row.extend(uvs.iter().take(3).map(|p| uv_cell(*p)));
        row.push(f(s, 5));
        if uvs.len() > 3 {
            row.push(uv_cell(uvs[3]));
        }
        t.row(row);
    }
    o.md.push_str(&t.render());
    let (sw, se) = (o.metrics["wcam.spread"], o.metrics["eye.spread"]);
    o.claim(
        "WCAM computes three different adaptation colours",
        vec![above("WCAM spread (Δu′v′)", sw, THETA_JND)],
    );
    o.claim(
        "eye computes three adaptation colours very close to each other",
        vec![
            below("eye spread (Δu′v′)", se, THETA_JND),
            below("eye spread − WCAM spread", se - sw, 0.0),
        ],
    );
    (CLAIM5, o)
}

fn reflectance_emission(scene: &Scene, material: &str) -> DVec3 {
    scene
        .materials
        .iter()
        .find(|m| m.name == material)
        .map_or(DVec3::NAN, |m| m.emission.as_dvec3())
}
