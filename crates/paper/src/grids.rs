//! Each case's sensitivity grid: what the paper's text leaves open for that case, with the
//! levels written from the text before any run of them (docs/paper.md quotes the text). The
//! first level of every parameter is the baseline, the design the committed results had.
//!
//! WCAM's weight reading enters every case; its specular mode only case 6, the one scene with
//! a surface that is not Lambertian (the bench): on Lambertian surfaces the three modes give
//! the same bits (`crates/tracer/tests/wcam_specular.rs`; the test below checks the scenes).
use crate::study::{Config, Level, Param, WCAM_SPECULAR, WCAM_WEIGHT, grid, level};

fn wcam_weight(quick: bool) -> Param {
    let mut levels = vec![level("linear", &[(WCAM_WEIGHT, "linear".into())])];
    if !quick {
        levels.push(level("power", &[(WCAM_WEIGHT, "power".into())]));
    }
    Param {
        name: "WCAM weight",
        levels,
    }
}

/// WCAM's specular mode (estimators.md §2.3): `exclude_delta` is `include` wherever no surface
/// has a delta lobe (case 6 has none), so the grid has the two that differ.
fn wcam_specular(quick: bool) -> Param {
    let mut levels = vec![level("include", &[(WCAM_SPECULAR, "include".into())])];
    if !quick {
        levels.push(level(
            "diffuse only",
            &[(WCAM_SPECULAR, "diffuse_only".into())],
        ));
    }
    Param {
        name: "WCAM specular",
        levels,
    }
}

fn v3(x: f64, y: f64, z: f64) -> String {
    format!("[{x:?}, {y:?}, {z:?}]")
}

fn param(name: &'static str, levels: Vec<Level>) -> Param {
    Param { name, levels }
}

/// Case 1: the camera in front of, or just inside, the open Cornell box, gaze horizontal
/// (the distances of case 3; heights: the box's middle and higher).
fn case1(quick: bool) -> Vec<Param> {
    let zs: &[f64] = if quick { &[-0.8] } else { &[-0.8, -0.4, 0.02] };
    let ys: &[f64] = if quick { &[0.273] } else { &[0.273, 0.36] };
    vec![
        param(
            "camera z",
            zs.iter()
                .map(|&z| level(format!("{z} m"), &[("camera_z", format!("{z:?}"))]))
                .collect(),
        ),
        param(
            "camera height",
            ys.iter()
                .map(|&y| level(format!("{y} m"), &[("camera_y", format!("{y:?}"))]))
                .collect(),
        ),
        wcam_weight(quick),
    ]
}

/// Case 2: the camera's place in the room (x ∈ [−2, 2], z ∈ [−2.5, 2.5]), 1.5 m high, always
/// looking at the back wall's read-out (the box and the sphere stay below it).
fn case2(quick: bool) -> Vec<Param> {
    // Near the front wall (the baseline), the front left corner, mid-room, mid-room right.
    let places: &[[f64; 3]] = if quick {
        &[[0.3, 1.5, 2.1]]
    } else {
        &[
            [0.3, 1.5, 2.1],
            [-1.5, 1.5, 2.1],
            [0.3, 1.5, 0.3],
            [1.5, 1.5, 0.3],
        ]
    };
    vec![
        param(
            "camera (x, z)",
            places
                .iter()
                .map(|p| {
                    let label = format!("({}, {}) m", p[0], p[2]);
                    level(label, &[("camera_position", v3(p[0], p[1], p[2]))])
                })
                .collect(),
        ),
        wcam_weight(quick),
    ]
}

/// The closing wall of case 3's box: 0.73 grey at z = 0, facing into the box.
const FRONT_WALL: &str = "# The front wall that closes the box (sensitivity study).\n[[shapes]]\ntype = \"quad\"\nmaterial = \"white\"\ncorner = [0.0, 0.0, 0.0]\nu = [0.556, 0.0, 0.0]\nv = [0.0, 0.549, 0.0]\n";

/// Case 3's camera distances (z of the eye; the box's open face is z = 0).
const CASE3_Z: [f64; 3] = [-0.8, -0.4, 0.02];
const CASE3_Y: [f64; 3] = [0.273, 0.18, 0.36];

fn case3(quick: bool) -> Vec<Param> {
    let zs: &[f64] = if quick { &[-0.8, 0.02] } else { &CASE3_Z };
    let ys: &[f64] = if quick { &[0.273] } else { &CASE3_Y };
    let z_levels = zs
        .iter()
        .map(|&z| level(format!("{z} m"), &[("camera_z", format!("{z:?}"))]))
        .collect();
    let y_levels = ys
        .iter()
        .map(|&y| level(format!("{y} m"), &[("camera_y", format!("{y:?}"))]))
        .collect();
    vec![
        param("camera z", z_levels),
        param("camera height", y_levels),
        param(
            "box",
            vec![
                level("open", &[("front_wall", String::new())]),
                level("closed", &[("front_wall", FRONT_WALL.into())]),
            ],
        ),
        wcam_weight(quick),
    ]
}

/// A closed box needs the camera inside it.
pub(crate) fn case3_keep(c: &Config) -> bool {
    let inside = c
        .get("camera_z")
        .and_then(|z| z.parse::<f64>().ok())
        .is_some_and(|z| z > 0.0);
    c.get("front_wall").is_none_or(str::is_empty) || inside
}

/// Case 4's spot: half-angle of the cone (its full-intensity core is ¾ of it) and intensity
/// as a multiple of the built-in scene's (10, 0.4, 0.4) W/sr. The cones keep the premise
/// ("only lights the only white object", "partially lit"): 5° is the widest whose every ray
/// meets the statue first (scripts/paper/spot_design.py), 4° and 3° light less of it
/// (`cases/design.rs` checks all three).
fn case4(quick: bool) -> Vec<Param> {
    let cones: &[f64] = if quick { &[5.0, 3.0] } else { &[5.0, 4.0, 3.0] };
    let scales: &[f64] = if quick {
        &[1.0, 4.0]
    } else {
        &[1.0, 4.0, 16.0]
    };
    vec![
        param(
            "spot cone",
            cones
                .iter()
                .map(|&c| {
                    level(
                        format!("{c}°"),
                        &[
                            ("spot_cone_deg", format!("{c:?}")),
                            ("spot_falloff_deg", format!("{:?}", 0.75 * c)),
                        ],
                    )
                })
                .collect(),
        ),
        param(
            "spot intensity",
            scales
                .iter()
                .map(|&k| {
                    level(
                        format!("{k}×"),
                        &[("spot_intensity", v3(10.0 * k, 0.4 * k, 0.4 * k))],
                    )
                })
                .collect(),
        ),
        wcam_weight(quick),
    ]
}

/// Case 5's doorway: the partition at x = 5 between the rooms, the opening z ∈ [−3.4, −0.6].
const DOOR_X: f64 = 5.0;
const DOOR_Z: f64 = -2.0;
const JAMB_Z: f64 = -0.6;

/// The point 4 m from `p` along yaw `deg` (from +x towards +z), level.
fn ahead(p: [f64; 3], deg: f64) -> String {
    let a = deg.to_radians();
    v3(p[0] + 4.0 * libm::cos(a), p[1], p[2] + 4.0 * libm::sin(a))
}

/// One camera place of case 5 and its four gazes, by the text's definitions of the views:
/// view 3 looks at the doorway's centre ("only the second room is visible"), view 2 at its
/// jamb on the +z side (the doorway fills half the frame: "both rooms are visible"), view 1
/// 40° further (the doorway out of the 36.9° wide frustum: "the second room is not visible"),
/// and the supplementary view faces away from the doorway.
fn case5_place(label: String, p: [f64; 3]) -> Level {
    let yaw = |z: f64| libm::atan2(z - p[2], DOOR_X - p[0]).to_degrees();
    let jamb = yaw(JAMB_Z);
    level(
        label,
        &[
            ("camera_position", v3(p[0], p[1], p[2])),
            ("look_at_1", ahead(p, jamb + 40.0)),
            ("look_at_2", ahead(p, jamb)),
            ("look_at_3", ahead(p, yaw(DOOR_Z))),
            ("look_at_4", ahead(p, 180.0)),
        ],
    )
}

/// Case 5: where in room 1 the camera stands, as distance from the doorway and offset from its
/// axis (towards +z). The baseline keeps `configs/two-rooms.toml`'s views (yaw 60°, 20°, 0°,
/// 180°; the rules above give 59.3°, 19.3°, 0°, 180° there). Offsets stay small enough that
/// view 3's frustum still fits the doorway.
fn case5(quick: bool) -> Vec<Param> {
    let baseline = level(
        "4, 0 m",
        &[
            ("camera_position", v3(1.0, 1.5, -2.0)),
            ("look_at_1", "[3.0, 1.5, 1.464102]".into()),
            ("look_at_2", "[4.75877, 1.5, -0.6319194]".into()),
            ("look_at_3", "[5.0, 1.5, -2.0]".into()),
            ("look_at_4", "[-3.0, 1.5, -2.0]".into()),
        ],
    );
    let mut places = vec![baseline];
    if !quick {
        for (d, off) in [(4.0, 0.3), (2.5, 0.0), (2.5, 0.3)] {
            let label = format!("{d}, {off} m");
            places.push(case5_place(label, [DOOR_X - d, 1.5, DOOR_Z + off]));
        }
    }
    vec![
        param("camera (from the doorway, off its axis)", places),
        wcam_weight(quick),
    ]
}

/// Case 6's bench: GGX roughness α of its coating. A highlight that comes and goes within the
/// five frames the text names needs a lobe (≈ 2α wide in reflected direction) narrower than
/// the reflection's sweep over them: α at most a third of the sweep, 0.067 rad, so 0.01 (the
/// coating's smallest) first, then 0.015 and 0.02; the built-in scene's 0.03 is too rough
/// (`cases/design.rs` checks every level).
fn case6(quick: bool) -> Vec<Param> {
    let rs: &[f64] = if quick { &[0.01] } else { &[0.01, 0.015, 0.02] };
    vec![
        param(
            "bench roughness",
            rs.iter()
                .map(|&r| level(format!("{r}"), &[("bench_roughness", format!("{r:?}"))]))
                .collect(),
        ),
        wcam_weight(quick),
        wcam_specular(quick),
    ]
}

fn keep_all(_: &Config) -> bool {
    true
}

/// The parameters of case `number` and the configurations of its grid.
pub fn case_grid(number: u32, quick: bool) -> (Vec<Param>, Vec<Config>) {
    let (params, keep): (Vec<Param>, fn(&Config) -> bool) = match number {
        1 => (case1(quick), keep_all),
        2 => (case2(quick), keep_all),
        3 => (case3(quick), case3_keep),
        4 => (case4(quick), keep_all),
        5 => (case5(quick), keep_all),
        6 => (case6(quick), keep_all),
        _ => (vec![wcam_weight(quick)], keep_all),
    };
    let configs = grid(&params, keep);
    (params, configs)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn case5_rules_give_the_baseline_views_within_a_degree() {
        let l = case5_place("b".into(), [1.0, 1.5, -2.0]);
        let (_, configs) = case_grid(5, false);
        let base = &configs[0];
        let yaw = |s: &str| {
            let v: Vec<f64> = s
                .trim_matches(['[', ']'])
                .split(',')
                .map(|x| x.trim().parse().unwrap())
                .collect();
            libm::atan2(v[2] + 2.0, v[0] - 1.0).to_degrees()
        };
        for k in ["look_at_1", "look_at_2", "look_at_3", "look_at_4"] {
            let rule = l.fill.iter().find(|(n, _)| *n == k).unwrap().1.as_str();
            let d = yaw(rule) - yaw(base.get(k).unwrap());
            assert!(d.abs() < 1.0, "{k}: {d}");
        }
    }

    /// Cases 1, 2 and 5: the baseline renders exactly what `configs/<job>.toml` does.
    #[test]
    fn the_baselines_of_the_built_in_scenes_are_their_configs_jobs() {
        let dir = std::env::temp_dir().join(format!("eyeadapt-grids-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let load = |name: &str, text: &str| {
            let p = dir.join(format!("{name}.toml"));
            std::fs::write(&p, text).unwrap();
            let o = eyeadapt_sequencer::job::JobOverrides::default();
            eyeadapt_sequencer::job::load_job(Some(&p), &o).unwrap()
        };
        for case in crate::CASES
            .iter()
            .filter(|c| [1, 2, 5].contains(&c.number))
        {
            let (_, configs) = case_grid(case.number, false);
            for (name, job, _) in case.jobs {
                let filled = crate::shot::fill_template(job, &configs[0], name).unwrap();
                let config = std::fs::read_to_string(
                    std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
                        .join(format!("../../configs/{name}.toml")),
                )
                .unwrap();
                let (a, b) = (load(name, &filled), load(name, &config));
                assert_eq!(a.frames.as_slice(), b.frames.as_slice(), "{name}");
                for &f in a.frames.as_slice() {
                    let (va, vb) = (a.view(f), b.view(f));
                    assert_eq!(va.position, vb.position, "{name} {f}");
                    assert!((va.forward - vb.forward).length() < 1e-6, "{name} {f}");
                }
                assert_eq!((a.width, a.height, a.spp), (b.width, b.height, b.spp));
                assert_eq!(a.estimator_config, b.estimator_config, "{name}");
            }
        }
        let _ = std::fs::remove_dir_all(&dir);
    }

    /// The specular mode is left out where it cannot matter: every surface Lambertian.
    #[test]
    fn only_case_6_has_a_surface_that_is_not_lambertian() {
        for case in crate::CASES {
            let (params, configs) = case_grid(case.number, false);
            let has = params.iter().any(|p| p.name == "WCAM specular");
            assert_eq!(has, case.number == 6, "case {}", case.number);
            for (name, job, template) in case.jobs {
                let job = crate::shot::fill_template(job, &configs[0], name).unwrap();
                let scene = match template {
                    Some(t) => {
                        let text = crate::shot::fill_template(t, &configs[0], name).unwrap();
                        let beside =
                            concat!(env!("CARGO_MANIFEST_DIR"), "/../../paper/scenes/s.toml");
                        eyeadapt_scene::load_scene_str(&text, std::path::Path::new(beside)).unwrap()
                    }
                    None => {
                        let b = job.split("builtin:").nth(1).unwrap();
                        eyeadapt_scene::load_builtin(b.split('"').next().unwrap()).unwrap()
                    }
                };
                let lambertian = scene
                    .materials
                    .iter()
                    .all(|m| matches!(m.bsdf, eyeadapt_scene::Bsdf::Diffuse { .. }));
                assert_eq!(!lambertian, case.number == 6, "case {} {name}", case.number);
            }
        }
    }
}
