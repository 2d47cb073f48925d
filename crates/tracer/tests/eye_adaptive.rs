//! The eye sensor's adaptive budget: where it stops and what it returns never depend on the
//! thread count, and stopping after n paths gives exactly the fixed-budget reading of n paths.
use eyeadapt_tracer::{
    EYE_ROUND, EyeEstimate, EyeSettings, PathSettings, SceneData, View, eye_sensor,
    eye_sensor_until,
};

fn cornell() -> (SceneData, View) {
    let scene = eyeadapt_scene::resolve_scene("builtin:cornell-box").unwrap();
    let view = View::from_camera(scene.camera.as_ref().unwrap());
    (SceneData::new(&scene), view)
}

fn in_pool<T: Send>(threads: usize, f: impl FnOnce() -> T + Send) -> T {
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap()
        .install(f)
}

const PATH: PathSettings = PathSettings {
    max_depth: 8,
    rr_depth: 5,
};

#[test]
fn stopping_after_n_paths_equals_a_fixed_budget_of_n() {
    let (data, view) = cornell();
    let adaptive = EyeSettings {
        samples: 16_384,
        min_samples: 4096,
        ..EyeSettings::default()
    };
    // Stop at the second check: min_samples plus one round.
    let stop_at = 4096 + EYE_ROUND as u64;
    let stopped = eye_sensor_until(&data, &view, &adaptive, 3, PATH, |e| e.samples >= stop_at);
    assert_eq!(stopped.samples, stop_at);
    let fixed = eye_sensor(
        &data,
        &view,
        &EyeSettings {
            samples: stop_at as u32,
            ..EyeSettings::default()
        },
        3,
        PATH,
    );
    assert_eq!(stopped, fixed);
    // A rule that never accepts runs to the cap; one that always accepts stops at the minimum.
    let never = eye_sensor_until(&data, &view, &adaptive, 3, PATH, |_| false);
    assert_eq!(never.samples, 16_384);
    let always = eye_sensor_until(&data, &view, &adaptive, 3, PATH, |_| true);
    assert_eq!(always.samples, 4096);
}

#[test]
fn an_error_target_stops_at_the_same_path_on_any_thread_count() {
    let (data, view) = cornell();
    let s = EyeSettings {
        samples: 65_536,
        min_samples: 2048,
        ..EyeSettings::default()
    };
    let rel_err = |e: &EyeEstimate| {
        let m = e.mean_rgb.x + e.mean_rgb.y + e.mean_rgb.z;
        let var = e.cov_rgb.x_axis.x + e.cov_rgb.y_axis.y + e.cov_rgb.z_axis.z;
        var.sqrt() / m
    };
    // Half the relative error of the first 2048 paths: reached after roughly four times as many.
    let first = eye_sensor(&data, &view, &EyeSettings { samples: 2048, ..s }, 0, PATH);
    let target = 0.5 * rel_err(&first);
    let rule = |e: &EyeEstimate| rel_err(e) <= target;
    let runs: Vec<EyeEstimate> = [1, 2, 5]
        .iter()
        .map(|&t| in_pool(t, || eye_sensor_until(&data, &view, &s, 0, PATH, rule)))
        .collect();
    assert_eq!(runs[0], runs[1]);
    assert_eq!(runs[0], runs[2]);
    let n = runs[0].samples;
    assert!(n > 2048 && n < 65_536, "stopped after {n} paths");
    assert_eq!(
        (n - 2048) % EYE_ROUND as u64,
        0,
        "stops only on round boundaries"
    );
    assert!(rule(&runs[0]));
}

#[test]
fn a_zero_budget_reads_nothing_instead_of_panicking() {
    let (data, view) = cornell();
    let e = eye_sensor(
        &data,
        &view,
        &EyeSettings {
            samples: 0,
            ..EyeSettings::default()
        },
        0,
        PATH,
    );
    assert_eq!(e.samples, 0);
    assert_eq!(e.mean_rgb, glam::DVec3::ZERO);
}
