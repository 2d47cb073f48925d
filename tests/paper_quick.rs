//! The quick variant of `eyeadapt paper`, cases 1 and 2 (the paper's single-illuminant
//! benchmarks, whose expected answers are known): every estimator finds the light's colour in
//! the grey Cornell box, and the eye-centred sensor recovers the reflectance in both worlds of
//! one reflectance. Also: the same seed gives byte-identical RESULTS.md and contact sheets.
use eyeadapt_paper::{CaseReport, PaperOptions, run};
use std::time::Instant;

fn hue_diff(a: f64, b: f64) -> f64 {
    let d = (a - b).rem_euclid(360.0);
    if d > 180.0 { d - 360.0 } else { d }
}

fn quick(dir: &std::path::Path) -> Vec<CaseReport> {
    let o = PaperOptions {
        quick: true,
        cases: vec![1, 2],
        ..PaperOptions::new(dir.to_path_buf())
    };
    run(&o).expect("paper --quick cases 1, 2").cases
}

#[test]
fn quick_cases_1_and_2_reproduce_the_single_illuminant_claims() {
    let tmp = tempfile::tempdir().unwrap();
    let t = Instant::now();
    let reports = quick(&tmp.path().join("a"));
    eprintln!(
        "paper --quick --cases 1,2: {:.1} s",
        t.elapsed().as_secs_f64()
    );
    let (c1, c2) = (&reports[0], &reports[1]);
    assert_eq!((c1.info.number, c2.info.number), (1, 2));

    // Case 1: every estimator within 2e-3 of the light's chromaticity.
    let duvs: Vec<(&String, &f64)> = c1
        .metrics
        .iter()
        .filter(|(k, _)| k.ends_with(".duv_light"))
        .collect();
    assert!(duvs.len() >= 8, "every estimator reports: {duvs:?}");
    for (k, v) in &duvs {
        assert!(**v <= 2e-3, "case 1 {k} = {v}");
    }
    assert!(c1.all_hold(), "{:#?}", c1.verdicts);

    // Case 2, after eye adaptation: the grey world reads neutral, the orange world stays orange.
    let s_white = c2.metric("white.eye.sat");
    assert!(s_white < 0.01, "grey world after eye: S = {s_white}");
    let (h, s) = (c2.metric("orange.eye.hue"), c2.metric("orange.eye.sat"));
    let (h_ref, s_ref) = (
        c2.metric("orange.reflectance.hue"),
        c2.metric("orange.reflectance.sat"),
    );
    assert!(
        hue_diff(h, h_ref).abs() <= 10.0,
        "orange world after eye: hue {h} vs reflectance {h_ref}"
    );
    assert!(
        s >= 0.5 * s_ref,
        "orange world after eye: S {s} vs reflectance {s_ref}"
    );
    assert!(c2.metric("white.pixels") > 50.0 && c2.metric("orange.pixels") > 50.0);

    // Outputs exist, and a second run with the same seed is byte-identical.
    let a = tmp.path().join("a");
    let md = std::fs::read(a.join("RESULTS.md")).unwrap();
    let text = String::from_utf8(md.clone()).unwrap();
    assert!(
        text.contains("## Case 1") && text.contains("## Case 2"),
        "{text}"
    );
    quick(&tmp.path().join("b"));
    let b = tmp.path().join("b");
    assert_eq!(md, std::fs::read(b.join("RESULTS.md")).unwrap());
    for sheet in ["case1-cornell-orange.png", "case2-one-reflectance.png"] {
        assert_eq!(
            std::fs::read(a.join(sheet)).unwrap(),
            std::fs::read(b.join(sheet)).unwrap(),
            "{sheet}"
        );
    }
}
