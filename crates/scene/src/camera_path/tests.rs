//! Camera-path behaviour: continuity, timing, orientation and validation.
use super::*;
use glam::DMat3;

fn key(time: f64, position: [f64; 3], orientation: Orientation) -> Keyframe {
    Keyframe {
        time,
        position: DVec3::from(position),
        orientation,
        fov_deg: None,
    }
}

fn look(at: [f64; 3]) -> Orientation {
    Orientation::LookAt {
        look_at: DVec3::from(at),
        up: DVec3::Y,
    }
}

fn yaw_pitch(yaw_deg: f64, pitch_deg: f64) -> Orientation {
    Orientation::YawPitch { yaw_deg, pitch_deg }
}

/// Uneven spacing *and* uneven timing, with turns: the case where a naive time mapping
/// breaks C1.
fn wiggly_path() -> CameraPath {
    let pts = [
        (0.0, [0.0, 1.6, 4.0]),
        (0.7, [1.0, 1.7, 3.5]),
        (3.0, [4.0, 1.5, 0.0]),
        (3.4, [4.2, 1.5, -0.5]),
        (6.0, [0.0, 2.0, -3.0]),
        (9.5, [-3.0, 1.6, 1.0]),
    ];
    let keyframes = pts
        .iter()
        .map(|&(t, p)| key(t, p, look([0.0, 1.0, 0.0])))
        .collect();
    CameraPath {
        fps: 24.0,
        keyframes,
    }
}

fn assert_close(a: DVec3, b: DVec3, tol: f64, what: &str) {
    assert!(
        (a - b).length() <= tol,
        "{what}: {a} vs {b} (|Δ| = {:e})",
        (a - b).length()
    );
}

/// One-sided second-order derivative estimates at t, from the left and from the right.
fn one_sided_velocities(path: &CameraPath, t: f64, h: f64) -> (DVec3, DVec3) {
    let p = |t: f64| path.sample(t).position;
    let left = (3.0 * p(t) - 4.0 * p(t - h) + p(t - 2.0 * h)) / (2.0 * h);
    let right = (-3.0 * p(t) + 4.0 * p(t + h) - p(t + 2.0 * h)) / (2.0 * h);
    (left, right)
}

#[test]
fn passes_through_every_keyframe_exactly() {
    let mut path = wiggly_path();
    path.keyframes[3].orientation = yaw_pitch(200.0, -20.0);
    path.validate().unwrap();
    for (i, k) in path.keyframes.iter().enumerate() {
        let pose = path.sample(k.time);
        assert_eq!(pose.position, k.position, "keyframe {i}");
        let expected = match k.orientation {
            Orientation::LookAt { look_at, up } => look_at_basis(k.position, look_at, up).unwrap(),
            Orientation::YawPitch { yaw_deg, pitch_deg } => {
                let (y, p) = (yaw_deg.to_radians(), pitch_deg.to_radians());
                let forward = DVec3::new(
                    -libm::sin(y) * libm::cos(p),
                    libm::sin(p),
                    -libm::cos(y) * libm::cos(p),
                );
                let right = DVec3::new(libm::cos(y), 0.0, -libm::sin(y));
                DMat3::from_cols(right, right.cross(forward), -forward)
            }
        };
        assert_close(pose.forward, -expected.z_axis, 1e-12, "forward");
        assert_close(pose.up, expected.y_axis, 1e-12, "up");
    }
}

#[test]
fn pose_basis_is_orthonormal_everywhere() {
    let path = wiggly_path();
    for n in 0..=1000 {
        let pose = path.sample(-1.0 + 12.0 * n as f64 / 1000.0);
        assert!((pose.forward.length() - 1.0).abs() < 1e-12);
        assert!((pose.up.length() - 1.0).abs() < 1e-12);
        assert!(pose.forward.dot(pose.up).abs() < 1e-12);
        assert!(pose.position.is_finite());
    }
}

#[test]
fn position_is_c1_in_time_at_every_interior_keyframe() {
    let path = wiggly_path();
    let keys = &path.keyframes;
    for (i, k) in keys.iter().enumerate().take(keys.len() - 1).skip(1) {
        let (left, right) = one_sided_velocities(&path, k.time, 1e-4);
        let scale = left.length().max(right.length());
        assert!(
            scale > 0.1,
            "keyframe {i} should be passed at speed, got {scale}"
        );
        assert_close(
            left,
            right,
            1e-4 * scale,
            &format!("velocity at keyframe {i}"),
        );
    }
}

/// Why the module does not map each segment's knot interval linearly onto its time
/// interval: on the same path that shortcut changes velocity abruptly at keyframes.
#[test]
fn naive_time_mapping_would_not_be_c1() {
    let path = wiggly_path();
    let keys = &path.keyframes;
    let naive = |i: usize, t: f64| {
        let h = path.knot_interval(i as isize);
        path.curve(
            i,
            (t - keys[i].time) / (keys[i + 1].time - keys[i].time) * h,
        )
    };
    let (i, e) = (2, 1e-6);
    let t = keys[i].time;
    let left = (naive(i - 1, t) - naive(i - 1, t - e)) / e;
    let right = (naive(i, t + e) - naive(i, t)) / e;
    let jump = (left - right).length() / left.length().max(right.length());
    // Here the speed changes by about half (0.49) at the keyframe.
    assert!(jump > 0.3, "relative velocity jump {jump}");
}

/// With keyframe times proportional to the centripetal knots, τ(t) is linear and the path
/// is the textbook centripetal Catmull-Rom spline, segment by segment.
#[test]
fn knot_proportional_timing_reproduces_the_classic_spline() {
    let mut path = wiggly_path();
    let mut t = 0.0;
    for i in 0..path.keyframes.len() {
        path.keyframes[i].time = t;
        if i + 1 < path.keyframes.len() {
            t += 0.8 * path.knot_interval(i as isize);
        }
    }
    let keys = &path.keyframes;
    for i in 0..keys.len() - 1 {
        for n in 0..=20 {
            let s = n as f64 / 20.0;
            let classic = path.curve(i, s * path.knot_interval(i as isize));
            let t = keys[i].time + s * (keys[i + 1].time - keys[i].time);
            assert_close(
                path.sample(t).position,
                classic,
                1e-12,
                &format!("segment {i} s {s}"),
            );
        }
    }
}

/// Random paths: finite everywhere, C1 at every keyframe, and progress along the curve never
/// reverses (τ(t) is non-decreasing on every segment and ends on its knot).
#[test]
fn property_random_paths_are_c1_and_finite() {
    let mut state = 7u64;
    let mut rand = move || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 11) as f64 / (1u64 << 53) as f64
    };
    for _ in 0..200 {
        let n = 2 + (rand() * 7.0) as usize;
        let mut t = rand();
        let mut keyframes = Vec::new();
        for _ in 0..n {
            let p = [rand() * 10.0 - 5.0, rand() * 3.0, rand() * 10.0 - 5.0];
            keyframes.push(key(
                t,
                p,
                yaw_pitch(rand() * 720.0 - 360.0, rand() * 180.0 - 90.0),
            ));
            t += 0.05 + rand() * 3.0;
        }
        let path = CameraPath {
            fps: 24.0,
            keyframes,
        };
        path.validate().unwrap();
        let keys = &path.keyframes;
        for k in keys.iter().take(n - 1).skip(1) {
            let (left, right) = one_sided_velocities(&path, k.time, 1e-5);
            let scale = left.length().max(right.length()).max(1e-3);
            assert_close(
                left,
                right,
                1e-3 * scale,
                &format!("velocity at t = {}", k.time),
            );
        }
        for i in 0..n - 1 {
            let (ta, tb) = (keys[i].time, keys[i + 1].time);
            let h = path.knot_interval(i as isize);
            let mut before = 0.0;
            for m in 0..=200 {
                let u = path.knot_progress(i, ta + (tb - ta) * m as f64 / 200.0);
                assert!(
                    u >= before - 1e-12 * h,
                    "segment {i}: τ went back from {before} to {u}"
                );
                before = u;
            }
            assert!(
                (before - h).abs() <= 1e-12 * h.max(1.0),
                "segment {i} ends at its knot"
            );
        }
        let (t0, t1) = (keys[0].time, keys[n - 1].time);
        for m in 0..=500 {
            let pose = path.sample(t0 + (t1 - t0) * m as f64 / 500.0);
            assert!(pose.position.is_finite() && pose.forward.is_finite() && pose.up.is_finite());
        }
    }
}

#[test]
fn straight_line_with_uniform_timing_has_uniform_speed() {
    let keyframes = (0..5)
        .map(|i| {
            key(
                i as f64 * 2.0,
                [i as f64 * 3.0, 1.0, -(i as f64) * 4.0],
                yaw_pitch(0.0, 0.0),
            )
        })
        .collect();
    let path = CameraPath {
        fps: 30.0,
        keyframes,
    };
    let speed = 5.0 / 2.0; // |(3, 0, −4)| per 2 s
    for n in 0..=800 {
        let t = 8.0 * n as f64 / 800.0;
        let expected = DVec3::new(1.5 * t, 1.0, -2.0 * t);
        assert_close(
            path.sample(t).position,
            expected,
            1e-12,
            &format!("t = {t}"),
        );
    }
    let (left, right) = one_sided_velocities(&path, 3.1, 1e-3);
    assert!((left.length() - speed).abs() < 1e-9 && (right.length() - speed).abs() < 1e-9);
}

#[test]
fn duplicate_positions_pause_without_nan() {
    let o = look([0.0, 0.0, -10.0]);
    let keyframes = vec![
        key(0.0, [0.0, 0.0, 0.0], o),
        key(1.0, [0.0, 0.0, 0.0], o), // repeated start: zero knot interval at the phantom side
        key(2.0, [2.0, 0.0, 0.0], o),
        key(3.0, [2.0, 0.0, 0.0], o), // the camera waits here…
        key(4.0, [2.0, 0.0, 0.0], o),
        key(5.0, [3.0, 1.0, 0.0], o),
    ];
    let path = CameraPath {
        fps: 24.0,
        keyframes,
    };
    path.validate().unwrap();
    for n in 0..=5000 {
        let t = 5.0 * n as f64 / 5000.0;
        let pose = path.sample(t);
        assert!(
            pose.position.is_finite() && pose.forward.is_finite(),
            "t = {t}"
        );
        if (3.0..=4.0).contains(&t) {
            assert_eq!(pose.position, DVec3::new(2.0, 0.0, 0.0), "t = {t}");
        }
        if t <= 1.0 {
            assert_eq!(pose.position, DVec3::ZERO, "t = {t}");
        }
    }
    // …and arrives and leaves at zero velocity, so velocity is continuous there too. It must
    // already be at rest at t = 2, where it reaches the position it then holds.
    for t in [1.0, 2.0, 3.0, 4.0] {
        let (left, right) = one_sided_velocities(&path, t, 1e-5);
        assert!(
            left.length() < 1e-6 && right.length() < 1e-6,
            "t = {t}: {left} {right}"
        );
    }
    let (left, right) = one_sided_velocities(&path, 1.5, 1e-4);
    assert!(left.length() > 0.5, "it does move between the pauses");
    assert_close(left, right, 1e-6, "velocity inside a segment");
}

#[test]
fn yaw_pitch_conventions() {
    let forward = |yaw, pitch| {
        let path = CameraPath {
            fps: 1.0,
            keyframes: vec![key(0.0, [0.0; 3], yaw_pitch(yaw, pitch))],
        };
        path.sample(0.0)
    };
    assert_close(forward(0.0, 0.0).forward, DVec3::NEG_Z, 1e-15, "yaw 0");
    assert_close(forward(90.0, 0.0).forward, DVec3::NEG_X, 1e-15, "yaw 90");
    assert_close(forward(180.0, 0.0).forward, DVec3::Z, 1e-15, "yaw 180");
    assert_close(forward(-90.0, 0.0).forward, DVec3::X, 1e-15, "yaw -90");
    let up30 = forward(0.0, 30.0);
    assert_close(
        up30.forward,
        DVec3::new(0.0, 0.5, -(0.75f64).sqrt()),
        1e-15,
        "pitch 30",
    );
    assert!(
        up30.up.y > 0.0 && up30.up.z > 0.0,
        "tilting up tips `up` backwards (+z, behind a camera facing −z): {}",
        up30.up
    );
    // No roll: the right axis stays horizontal, and is +x for yaw 0 (right-handed).
    let p = forward(37.0, -62.0);
    assert!(p.right().y.abs() < 1e-15);
    assert_close(forward(0.0, 0.0).right(), DVec3::X, 1e-15, "right");
    assert_close(forward(0.0, 90.0).forward, DVec3::Y, 1e-15, "straight up");
    // A yaw/pitch keyframe and the equivalent look_at agree.
    let path = CameraPath {
        fps: 1.0,
        keyframes: vec![key(0.0, [1.0, 2.0, 3.0], look([-4.0, 2.0, 3.0]))],
    };
    assert_close(
        path.sample(0.0).forward,
        forward(90.0, 0.0).forward,
        1e-15,
        "look_at −x",
    );
    assert_close(path.sample(0.0).up, DVec3::Y, 1e-15, "look_at up");
}

#[test]
fn slerp_takes_the_short_way() {
    // Yaw 0 and yaw 360 are the same rotation but opposite quaternions (q and −q).
    let path = CameraPath {
        fps: 10.0,
        keyframes: vec![
            key(0.0, [0.0; 3], yaw_pitch(0.0, 0.0)),
            key(1.0, [0.0; 3], yaw_pitch(360.0, 0.0)),
        ],
    };
    assert!(
        orientation_quat(&path.keyframes[0]).dot(orientation_quat(&path.keyframes[1])) < -0.999
    );
    for n in 0..=100 {
        let pose = path.sample(n as f64 / 100.0);
        assert_close(pose.forward, DVec3::NEG_Z, 1e-12, "no spin");
    }
    // 0° → 350° turns 10° clockwise, not 350° counter-clockwise.
    let path = CameraPath {
        fps: 10.0,
        keyframes: vec![
            key(0.0, [0.0; 3], yaw_pitch(0.0, 0.0)),
            key(1.0, [0.0; 3], yaw_pitch(350.0, 0.0)),
        ],
    };
    let half = (-5.0f64).to_radians();
    assert_close(
        path.sample(0.5).forward,
        DVec3::new(-libm::sin(half), 0.0, -libm::cos(half)),
        1e-12,
        "mid",
    );
}

#[test]
fn orientation_is_slerp_in_time() {
    let path = CameraPath {
        fps: 10.0,
        keyframes: vec![
            key(1.0, [0.0; 3], yaw_pitch(0.0, 0.0)),
            key(3.0, [5.0, 0.0, 0.0], yaw_pitch(90.0, 0.0)),
        ],
    };
    for n in 0..=10 {
        let s = n as f64 / 10.0;
        let a = (90.0 * s).to_radians();
        let pose = path.sample(1.0 + 2.0 * s);
        assert_close(
            pose.forward,
            DVec3::new(-libm::sin(a), 0.0, -libm::cos(a)),
            1e-12,
            "constant angular speed",
        );
    }
}

#[test]
fn fov_is_linear_and_optional() {
    let mut path = wiggly_path();
    assert_eq!(path.sample(1.0).fov_deg, None);
    for (i, k) in path.keyframes.iter_mut().enumerate() {
        k.fov_deg = Some(30.0 + 10.0 * i as f64);
    }
    assert!((path.sample(0.35).fov_deg.unwrap() - 35.0).abs() < 1e-12);
    assert_eq!(path.sample(3.0).fov_deg, Some(50.0));
    assert_eq!(path.sample(100.0).fov_deg, Some(80.0));
}

#[test]
fn clamps_outside_the_keyframe_range_and_single_keyframe_is_static() {
    let path = wiggly_path();
    assert_eq!(path.sample(-5.0), path.sample(0.0));
    assert_eq!(path.sample(f64::NAN), path.sample(0.0));
    assert_eq!(path.sample(1e9), path.sample(9.5));
    let still = CameraPath {
        fps: 24.0,
        keyframes: vec![key(2.0, [1.0, 2.0, 3.0], look([0.0; 3]))],
    };
    assert_eq!(still.frame_count(), 1);
    assert_eq!(still.sample(0.0), still.sample(7.0));
    assert_eq!(still.sample(7.0).position, DVec3::new(1.0, 2.0, 3.0));
}

#[test]
fn frame_count_and_times() {
    let path = |t0: f64, t1: f64, fps: f64| CameraPath {
        fps,
        keyframes: vec![
            key(t0, [0.0; 3], yaw_pitch(0.0, 0.0)),
            key(t1, [1.0, 0.0, 0.0], yaw_pitch(0.0, 0.0)),
        ],
    };
    assert_eq!(path(0.0, 10.0, 24.0).frame_count(), 241);
    assert_eq!(path(0.0, 1.01, 24.0).frame_count(), 25);
    assert_eq!(
        path(0.0, 2.3, 10.0).frame_count(),
        24,
        "2.3 s × 10 fps rounds to 22.999…"
    );
    assert_eq!(path(1.5, 2.5, 25.0).frame_count(), 26);
    let p = path(1.5, 2.5, 25.0);
    assert_eq!(p.frame_time(0), 1.5);
    assert!((p.frame_time(25) - 2.5).abs() < 1e-15);
    assert_eq!(
        CameraPath {
            fps: 24.0,
            keyframes: vec![]
        }
        .frame_count(),
        0
    );
    let ntsc = path(0.0, 10.0, 24000.0 / 1001.0);
    assert_eq!(ntsc.frame_count(), 240); // 239.76 frames fit, plus frame 0
}

#[test]
fn validation_reports_every_problem() {
    let keyframes = vec![
        Keyframe {
            fov_deg: Some(180.0),
            ..key(0.0, [0.0; 3], look([0.0; 3]))
        },
        key(
            0.0,
            [0.0; 3],
            Orientation::LookAt {
                look_at: DVec3::new(0.0, 5.0, 0.0),
                up: DVec3::Y,
            },
        ),
        key(f64::NAN, [0.0, f64::INFINITY, 0.0], yaw_pitch(0.0, 95.0)),
        Keyframe {
            fov_deg: Some(0.0),
            ..key(-1.0, [0.0; 3], look([1.0, 0.0, 0.0]))
        },
    ];
    let path = CameraPath {
        fps: 0.0,
        keyframes,
    };
    let problems: Vec<String> = path
        .validate()
        .unwrap_err()
        .iter()
        .map(|p| p.to_string())
        .collect();
    let expected = [
        "camera_path: fps must be a positive number, got 0",
        "camera_path: fov_deg is given on 2 of 4 keyframes; give it on all or none (a missing one would have to blend with the scene camera's)",
        "camera_path.keyframes[0]: look_at [0, 0, 0] equals the position",
        "camera_path.keyframes[0]: fov_deg 180 is outside (0, 180)",
        "camera_path.keyframes[1]: time 0 s must be after the previous keyframe's 0 s",
        "camera_path.keyframes[1]: up [0, 1, 0] is parallel to the view direction",
        "camera_path.keyframes[2]: time must be finite, got NaN",
        "camera_path.keyframes[2]: position [0.0, inf, 0.0] is not finite in single precision (coordinates must stay within ±3.4e38)",
        "camera_path.keyframes[2]: pitch_deg 95 is outside [-90, 90]",
        "camera_path.keyframes[3]: fov_deg 0 is outside (0, 180)",
    ];
    assert_eq!(problems, expected);
    let empty = CameraPath {
        fps: f64::NAN,
        keyframes: vec![],
    };
    let problems: Vec<String> = empty
        .validate()
        .unwrap_err()
        .iter()
        .map(|p| p.to_string())
        .collect();
    assert_eq!(
        problems,
        [
            "camera_path: fps must be a positive number, got NaN",
            "camera_path: needs at least 1 keyframe"
        ]
    );
    assert!(wiggly_path().validate().is_ok());
}

#[derive(Debug, Deserialize)]
struct Doc {
    camera_path: CameraPath,
}

fn parse(toml_src: &str) -> Result<CameraPath, String> {
    toml::from_str::<Doc>(toml_src)
        .map(|d| d.camera_path)
        .map_err(|e| e.to_string())
}

#[test]
fn toml_forms() {
    let path = parse(
        "[camera_path]\nfps = 24\n\
         [[camera_path.keyframes]]\ntime = 0\nposition = [0, 1.6, 4]\nlook_at = [0, 1.2, 0]\nup = [0, 0, -1]\n\
         [[camera_path.keyframes]]\ntime = 1\nposition = [0, 1.6, 4]\nyaw_deg = 180\n",
    )
    .unwrap();
    assert_eq!(path.fps, 24.0);
    assert_eq!(
        path.keyframes[0].orientation,
        Orientation::LookAt {
            look_at: DVec3::new(0.0, 1.2, 0.0),
            up: DVec3::NEG_Z
        }
    );
    assert_eq!(path.keyframes[1].orientation, yaw_pitch(180.0, 0.0));
    assert_eq!(path.keyframes[1].fov_deg, None);
}

#[test]
fn toml_errors_are_specific() {
    let head =
        "[camera_path]\nfps = 24\n[[camera_path.keyframes]]\ntime = 0\nposition = [0, 0, 0]\n";
    let cases = [
        (
            "look_at = [0, 0, -1]\nyaw_deg = 3\n",
            "give either `look_at` or `yaw_deg`/`pitch_deg`, not both",
        ),
        ("look_at = [0, 0, -1]\npitch_deg = 3\n", "not both"),
        (
            "yaw_deg = 3\nup = [0, 1, 0]\n",
            "`up` only applies with `look_at`",
        ),
        ("pitch_deg = 3\n", "`pitch_deg` needs `yaw_deg`"),
        ("fov_deg = 3\n", "a keyframe needs `look_at` or `yaw_deg`"),
        (
            "look_at = [0, 0, -1]\nlookat = 1\n",
            "unknown field `lookat`",
        ),
    ];
    for (rest, needle) in cases {
        let err = parse(&format!("{head}{rest}")).unwrap_err();
        assert!(err.contains(needle), "{rest:?} gave:\n{err}");
    }
    let err = parse("[camera_path]\nfps = 24\nkeyframes = []\nspeed = 2\n").unwrap_err();
    assert!(err.contains("unknown field `speed`"), "{err}");
}
