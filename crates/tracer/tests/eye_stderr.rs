//! The eye sensor's standard error is honest: over independent seeds, the spread of the
//! readings matches the error each reading reports (issue 22: the i.i.d. formula overstated
//! the stratified estimator's error about twofold).
use eyeadapt_tracer::{EYE_REPLICATES, EyeSettings, PathSettings, SceneData, View, eye_sensor};

const PATH: PathSettings = PathSettings {
    max_depth: 8,
    rr_depth: 5,
};

fn ratio_reported_to_empirical(scene: &str, seeds: u64, samples: u32) -> [f64; 3] {
    let scene = eyeadapt_scene::resolve_scene(scene).unwrap();
    let view = View::from_camera(scene.camera.as_ref().unwrap());
    let data = SceneData::new(&scene);
    let runs: Vec<_> = (0..seeds)
        .map(|seed| {
            let s = EyeSettings {
                samples,
                seed,
                ..EyeSettings::default()
            };
            eye_sensor(&data, &view, &s, 0, PATH)
        })
        .collect();
    let k = runs.len() as f64;
    std::array::from_fn(|c| {
        let xs: Vec<f64> = runs.iter().map(|e| e.mean_rgb[c]).collect();
        let m = xs.iter().sum::<f64>() / k;
        let empirical = (xs.iter().map(|x| (x - m).powi(2)).sum::<f64>() / (k - 1.0)).sqrt();
        let reported = (runs.iter().map(|e| e.cov_rgb.col(c)[c]).sum::<f64>() / k).sqrt();
        reported / empirical
    })
}

#[test]
fn reported_error_matches_the_spread_over_seeds() {
    // 40 seeds: the empirical spread itself is known to about ±11 %, the reported one
    // (15 degrees of freedom per reading, averaged over 40) to a few percent.
    for scene in ["builtin:cornell-box", "builtin:cornell-green-floor"] {
        let r = ratio_reported_to_empirical(scene, 40, 4096);
        for (c, v) in r.iter().enumerate() {
            assert!(
                (0.7..=1.4).contains(v),
                "{scene} channel {c}: reported / empirical standard error = {v:.2} ({r:?})"
            );
        }
    }
}

#[test]
fn too_few_paths_for_two_replicates_report_no_error_instead_of_nonsense() {
    let scene = eyeadapt_scene::resolve_scene("builtin:cornell-box").unwrap();
    let view = View::from_camera(scene.camera.as_ref().unwrap());
    let data = SceneData::new(&scene);
    let one = EyeSettings {
        samples: 1,
        ..EyeSettings::default()
    };
    let e = eye_sensor(&data, &view, &one, 0, PATH);
    assert_eq!(e.samples, 1);
    assert_eq!(e.cov_rgb, glam::DMat3::ZERO);
    let two = EyeSettings {
        samples: 2 * EYE_REPLICATES as u32,
        ..one
    };
    let e = eye_sensor(&data, &view, &two, 0, PATH);
    assert!(e.cov_rgb.x_axis.x > 0.0);
}
