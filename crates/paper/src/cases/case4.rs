//! Case 4: statue, red spot (Fig. 9).
use super::spot::{self, Spot};
use super::*;
use crate::RegionMean;

const CLAIM4: &str = "\"The first complex test case consists of a room containing a white Buddha statue lit by a red lightspot and a main white light source located on the ceiling (see figure 9). WCAM computes a red adaptation color because the white statue is partially lit by a red spotlight. Consequently, after chromatic adaptation, the part of the statue lit by the spotlight gets a white color while the part takes a blue color, which looks unnatural. Instead, our method provides a result that looks more natural.\" (§5.2)";

pub(super) fn case4(runs: &[JobRun]) -> (&'static str, Out) {
    let run = &runs[0];
    let shot = &run.shots[0];
    let img = shot.image.as_ref().expect("stills keep their image");
    let scene = run.scene();
    let es = ests(run, shot);
    let mut o = Out::new();
    let spot = Spot::of(scene).expect("the statue scene has a spot light");
    let data = eyeadapt_tracer::SceneData::new(scene);
    let statue = Region::from_material(scene, "statue", "statue", 0.0);
    let statue_px = crate::measure::region_pixels(scene, img, &shot.view, &statue);
    // The lit side: statue pixels the spot reaches directly (inside its cone, not shadowed).
    let lit_px = spot::lit(&data, &spot, img, &shot.view, &statue_px);
    // "The part" the spot does not light: every other statue pixel.
    let unlit_px: Vec<usize> = statue_px
        .iter()
        .copied()
        .filter(|i| !lit_px.contains(i))
        .collect();
    let statue_id = scene
        .materials
        .iter()
        .position(|m| m.name == "statue")
        .expect("the statue scene has a statue material") as u32;
    let on_statue = spot::power_share(&data, &spot, statue_id);
    let lit_share = lit_px.len() as f64 / statue_px.len().max(1) as f64;
    o.metric("spot.power_on_statue", on_statue);
    o.metric("lit.share", lit_share);
    let mean_of = |px: &[usize], v: &[[f32; 3]]| {
        px.iter()
            .map(|&i| glam::Vec3::from(v[i]).as_dvec3())
            .sum::<DVec3>()
            / px.len() as f64
    };
    let lit_rgb = mean_of(&lit_px, &img.rgb);
    let rho = reflectance(scene, "statue").unwrap_or(DVec3::NAN);
    let unlit_mean = RegionMean {
        rgb: mean_of(&unlit_px, &img.rgb),
        irradiance: mean_of(&unlit_px, &img.irradiance),
        pixels: unlit_px.len(),
        reflectance: rho,
    };
    let _ = writeln!(o.md, "**Setup.** {}", setup_line(run));
    let _ = writeln!(
        o.md,
        "Statue reflectance {}; white ceiling light {}; red spot at {} with intensity {}, cone {}° (core {}°). Read-outs: the statue's lit side = statue pixels the spot lights directly, inside its cone and not shadowed ({} pixels); its unlit part = every other statue pixel ({} pixels). The expected adaptation colour is not known (§5.2); the main light is D65 white.\n",
        fmt3(rho),
        fmt3(light_colour(scene)),
        fmt3(spot.position.as_dvec3()),
        fmt3(spot.intensity.as_dvec3()),
        spot.cone_deg,
        spot.falloff_deg,
        lit_px.len(),
        unlit_mean.pixels
    );
    let _ = writeln!(
        o.md,
        "Where the spot's light goes, from the scene's geometry (its power over a 128 × 128 grid of directions in its cone, weighted by its falloff): {:.1} % of it lands first on the statue, {:.1} % on the pedestal, floor and walls. The lit side is {:.1} % of the statue's visible pixels at this size (the design check measures it at the study's).\n",
        100.0 * on_statue,
        100.0 * (1.0 - on_statue),
        100.0 * lit_share
    );
    o.metric("unlit.pixels", unlit_mean.pixels as f64);
    let unlit_e = uv_of_rgb(unlit_mean.irradiance);
    let ue = hsv_of_linear(unlit_mean.irradiance / unlit_mean.irradiance.max_element());
    o.metric("unlit.irradiance.hue", ue.h);
    o.metric("unlit.irradiance.duv_d65", delta_uv(unlit_e, d65_uv()));
    let _ = writeln!(
        o.md,
        "The unlit side's own irradiance (irradiance AOV) has u′v′ = {} (Δu′v′ = {} from D65, hue {:.0}°): the light it receives from the room, including the spot's light reflected by the wall, floor and pedestal.\n",
        uv_cell(Some(unlit_e)),
        f(delta_uv(unlit_e, d65_uv()), 5),
        ue.h
    );
    o.metric("lit.pixels", lit_px.len() as f64);
    estimator_table(&es, &unlit_mean, lit_rgb, &mut o);
    verdicts(&mut o);
    (CLAIM4, o)
}

/// Hue of an estimate's white as linear sRGB normalised to max 1 (0 when undefined).
fn white_hue(e: &Estimate) -> f64 {
    if !e.is_valid() {
        return f64::NAN;
    }
    let rgb = xyz_to_rgb(e.normalized());
    eyeadapt_color::hsv(rgb.max(DVec3::ZERO) / rgb.max_element().max(1e-12)).h
}

/// One row per estimator (its white's hue, the unlit and lit sides after adaptation).
fn estimator_table(es: &[Est], unlit_mean: &RegionMean, lit_rgb: DVec3, o: &mut Out) {
    let rho = unlit_mean.reflectance;
    let d65 = d65_uv();
    let mut t = Table::new(&[
        "estimator",
        "u′v′",
        "Δu′v′ to D65",
        "white's hue (linear sRGB)",
        "unlit side hue",
        "unlit side S",
        "lit side hue",
        "lit side S",
    ]);
    let ru = equal_luminance_hsv(unlit_mean.rgb, rho);
    let rl = equal_luminance_hsv(lit_rgb, rho);
    t.row(vec![
        "raw (no adaptation)".into(),
        "–".into(),
        "–".into(),
        "–".into(),
        hue_cell(ru.h, ru.s),
        pct(ru.s),
        hue_cell(rl.h, rl.s),
        pct(rl.s),
    ]);
    for e in es {
        let u = equal_luminance_hsv(e.m * unlit_mean.rgb, rho);
        let l = equal_luminance_hsv(e.m * lit_rgb, rho);
        let d = e.uv().map_or(f64::NAN, |p| delta_uv(p, d65));
        let wh = white_hue(e.estimate);
        o.metric(format!("{}.duv_d65", e.name), d);
        o.metric(format!("{}.white_hue", e.name), wh);
        o.metric(format!("{}.unlit.hue", e.name), u.h);
        o.metric(format!("{}.unlit.sat", e.name), u.s);
        o.metric(format!("{}.lit.hue", e.name), l.h);
        o.metric(format!("{}.lit.sat", e.name), l.s);
        t.row(vec![
            format!("`{}`", e.name),
            uv_cell(e.uv()),
            f(d, 5),
            format!("{:.0}°", wh.round().rem_euclid(360.0)),
            hue_cell(u.h, u.s),
            pct(u.s),
            hue_cell(l.h, l.s),
            pct(l.s),
        ]);
    }
    o.md.push_str(&t.render());
}

fn verdicts(o: &mut Out) {
    let m = o.metrics.clone();
    let (dw, de) = (m["wcam.duv_d65"], m["eye.duv_d65"]);
    let wwh = m["wcam.white_hue"];
    let (wuh, wus) = (m["wcam.unlit.hue"], m["wcam.unlit.sat"]);
    let wls = m["wcam.lit.sat"];
    let eus = m["eye.unlit.sat"];
    o.claim(
        "WCAM computes a red adaptation colour",
        vec![
            above("WCAM white's Δu′v′ to D65", dw, THETA_JND),
            below(
                "WCAM white's |hue − 0°| (linear sRGB, °)",
                hue_diff(wwh, 0.0).abs(),
                40.0,
            ),
        ],
    );
    o.claim(
        "after WCAM, the part of the statue lit by the spot gets a white colour",
        vec![below("lit side S after WCAM", wls, 0.05)],
    );
    o.claim(
        "after WCAM, the statue's unlit side turns blue",
        vec![
            below(
                "unlit side after WCAM: |hue − 220°| (°)",
                hue_diff(wuh, 220.0).abs(),
                40.0,
            ),
            above("unlit side S after WCAM", wus, 0.02),
        ],
    );
    o.claim(
        "eye gives a more natural result",
        vec![
            below("Δu′v′ to D65, eye − WCAM", de - dw, 0.0),
            below("unlit (white) side S, eye − WCAM", eus - wus, 0.0),
        ],
    );
    o.claim(
        "(design check) the spot lights only the statue, and only part of it",
        vec![
            above(
                "share of the spot's power landing on the statue",
                m["spot.power_on_statue"],
                0.95,
            ),
            below(
                "lit share of the statue's visible pixels",
                m["lit.share"],
                0.75,
            ),
            above(
                "lit share of the statue's visible pixels",
                m["lit.share"],
                0.05,
            ),
        ],
    );
}
