//! Turning `--estimators/--cat/--degree/...` into library settings, and the table printed
//! after a render.
use crate::args::AdaptArgs;
use eyeadapt_color::{Cat, Surround, cct_mccamy, xyz_to_uv, xyz_to_xy};
use eyeadapt_sequencer::adapt::{AdaptationConfig, AdaptationSettings, EstimatorConfig, Reading};
use eyeadapt_sequencer::{Estimator, Failure};

pub fn resolve(
    list: &str,
    a: &AdaptArgs,
) -> Result<(Vec<Estimator>, EstimatorConfig, AdaptationSettings), Failure> {
    let mut cfg = EstimatorConfig {
        list: vec![list.to_string()],
        ..EstimatorConfig::default()
    };
    if let Some(n) = a.eye_samples {
        cfg.eye.fix_samples(n);
    }
    let list = cfg
        .validate()
        .map_err(|e| Failure::Input(format!("--estimators: {}", e.join("; "))))?;
    let adaptation = AdaptationConfig {
        cat: a
            .cat
            .as_deref()
            .map(str::parse::<Cat>)
            .transpose()
            .map_err(|e| Failure::Input(format!("--cat: {e}")))?,
        degree: a.degree,
        adapt_luminance: a.adapt_luminance,
        surround: a
            .surround
            .as_deref()
            .map(|s| match s {
                "average" => Ok(Surround::Average),
                "dim" => Ok(Surround::Dim),
                "dark" => Ok(Surround::Dark),
                other => Err(Failure::Input(format!(
                    "--surround: unknown surround \"{other}\" (average, dim, dark)"
                ))),
            })
            .transpose()?,
        model: None,
    }
    .resolve()
    .map_err(Failure::Input)?;
    Ok((list, cfg, adaptation))
}

pub fn print_table(readings: &[Reading], a: &AdaptationSettings) {
    println!(
        "adaptation white per estimator ({}, D = {:.4}):",
        a.cat, a.degree
    );
    println!(
        "{:<15} {:>8} {:>8} {:>8} {:>8} {:>8} {:>10}  flags",
        "estimator", "x", "y", "u'", "v'", "CCT K", "se(u'v')"
    );
    for r in readings {
        let w = r.estimate.normalized();
        let xy = xyz_to_xy(w);
        let uv = xyz_to_uv(w);
        let f = |v: Option<f64>| v.map_or("-".to_string(), |v| format!("{v:.4}"));
        let se = r.estimate.std_err_uv.map_or("-".to_string(), |[a, b]| {
            format!("{:.2e}", (a * a + b * b).sqrt())
        });
        println!(
            "{:<15} {:>8} {:>8} {:>8} {:>8} {:>8} {:>10}  {}",
            r.estimator.name(),
            f(xy.map(|p| p.x)),
            f(xy.map(|p| p.y)),
            f(uv.map(|p| p.x)),
            f(uv.map(|p| p.y)),
            xy.and_then(cct_mccamy)
                .map_or("-".into(), |c| format!("{c:.0}")),
            se,
            r.estimate.flags.join(";")
        );
    }
}
