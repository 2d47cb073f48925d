//! Case 6: the walkthrough (Fig. 13-15).
use super::*;

const CLAIM6: &str = "\"Unlike WCAM, our method provides a smooth variation of the adaptation color. Note that the WCAM results in a sudden change of the adaptation colors, especially at the beginning of the sequence. In addition, the WCAM adapts too early to the illuminant color of the third room.\" … \"The sudden change in the adaptation color in WCAM occurs between frames 5 and 10 (Figure 15). … Only the specular reflection of one light source on the bench changes significantly, which highly changes the adaptation color.\" (§5.3)";

/// Room boundaries of `builtin:three-rooms` along z (scenes/three-rooms/gen.py).
const ROOM2_START_Z: f32 = -5.0;
const ROOM2_MID_Z: f32 = -7.5;
const ROOM3_START_Z: f32 = -10.0;
/// "The beginning of the sequence": the first second (the path's first keyframe segment).
const BEGINNING_S: f64 = 1.0;

/// The walkthrough's shots with the frames where the camera crosses the rooms.
struct Walk<'a> {
    shots: &'a [Shot],
    /// Series names, in the order of each shot's readings.
    names: Vec<&'static str>,
    enter2: Option<u32>,
    mid2: Option<u32>,
    enter3: Option<u32>,
    last: u32,
}

impl Walk<'_> {
    fn uv(&self, k: usize, frame: u32) -> Option<DVec2> {
        self.shots
            .iter()
            .find(|s| s.frame == frame)
            .and_then(|s| s.readings[k].estimate.uv())
    }

    /// Δu′v′ of series `name` from frame `fr - 1` to `fr`.
    fn step_at(&self, name: &str, fr: u32) -> f64 {
        let Some(k) = self.names.iter().position(|n| *n == name) else {
            return f64::NAN;
        };
        match (
            fr.checked_sub(1).and_then(|f| self.uv(k, f)),
            self.uv(k, fr),
        ) {
            (Some(a), Some(b)) => delta_uv(a, b),
            _ => f64::NAN,
        }
    }

    /// The largest step of series `name` within `span`, and the frame it ends at.
    fn largest_step(&self, name: &str, span: &[&Shot]) -> (f64, Option<u32>) {
        span.iter()
            .skip(1)
            .map(|s| (self.step_at(name, s.frame), Some(s.frame)))
            .filter(|(d, _)| d.is_finite())
            .fold((f64::NAN, None), |best, x| {
                if best.0.is_nan() || x.0 > best.0 {
                    x
                } else {
                    best
                }
            })
    }

    /// Onset in room 3: the first frame after mid-room 2 at which series `k` has covered half
    /// of its way from its mid-room-2 value to its last-frame value.
    fn onset(&self, k: usize) -> Option<u32> {
        let (f2, p2) = self.mid2.and_then(|f| self.uv(k, f).map(|p| (f, p)))?;
        let total = delta_uv(p2, self.uv(k, self.last)?);
        self.shots
            .iter()
            .filter(|s| s.frame >= f2)
            .find(|s| {
                s.readings[k]
                    .estimate
                    .uv()
                    .is_some_and(|p| delta_uv(p, p2) >= 0.5 * total)
            })
            .map(|s| s.frame)
    }
}

pub(super) fn case6(runs: &[JobRun]) -> Result<(&'static str, Out), Failure> {
    let run = &runs[0];
    let mut o = Out::new();
    let fps = run.job.path.fps();
    let shots = &run.shots;
    let first = |pred: &dyn Fn(&Shot) -> bool| shots.iter().find(|s| pred(s)).map(|s| s.frame);
    let walk = Walk {
        shots,
        names: shots[0].readings.iter().map(|r| r.name).collect(),
        enter2: first(&|s| s.view.position.z < ROOM2_START_Z),
        mid2: first(&|s| s.view.position.z < ROOM2_MID_Z),
        enter3: first(&|s| s.view.position.z < ROOM3_START_Z),
        last: shots.last().map_or(0, |s| s.frame),
    };
    let _ = writeln!(o.md, "**Setup.** {}", setup_line(run));
    let _ = writeln!(
        o.md,
        "{} frames at {fps} fps along the scene's camera path. The camera enters room 2 (orange) at frame {}, reaches the middle of room 2 at frame {}, and enters room 3 (blue) at frame {}. Metrics of estimators.md §7.2 on each estimator's u′v′ series (`eyeadapt_color::series_metrics`, σ_s = 0.5 s); Δu′v′ per frame. \"Onset in room 3\" = the first frame after mid-room 2 at which the estimate has covered half of its way from its mid-room-2 value to its last-frame value.\n",
        shots.len(),
        opt_frame(walk.enter2),
        opt_frame(walk.mid2),
        opt_frame(walk.enter3)
    );
    o.metric("frame_enter_room2", walk.enter2.map_or(f64::NAN, f64::from));
    o.metric("frame_mid_room2", walk.mid2.map_or(f64::NAN, f64::from));
    o.metric("frame_enter_room3", walk.enter3.map_or(f64::NAN, f64::from));
    series_table(&walk, fps, &mut o)?;
    let mm = o.metrics.clone();
    let g = |k: &str| mm[k];
    let (ej, wj) = (g("eye.max_jump"), g("wcam.max_jump"));
    let (eh, wh) = (g("eye.hf_rms"), g("wcam.hf_rms"));
    o.claim(
        "eye varies smoothly, WCAM changes suddenly",
        vec![
            below("largest frame-to-frame jump, eye − WCAM", ej - wj, 0.0),
            below("high-frequency RMS, eye − WCAM", eh - wh, 0.0),
        ],
    );
    beginning(&walk, &mut o);
    let (eo, wo) = (g("eye.onset_room3"), g("wcam.onset_room3"));
    o.claim(
        "WCAM adapts too early to the third room's illuminant",
        vec![above(
            "half-way onset towards room 3's white, eye − WCAM (frames)",
            eo - wo,
            0.0,
        )],
    );
    Ok((CLAIM6, o))
}

/// The §7.2 metrics of every series: metrics and one table row each.
fn series_table(walk: &Walk, fps: f64, o: &mut Out) -> Result<(), Failure> {
    let mut t = Table::new(&[
        "estimator",
        "mean step",
        "p95 step",
        "max jump",
        "at frame (s)",
        "camera in",
        "total variation",
        "hf_rms",
        "steps > 0.004",
        "noise floor",
        "onset in room 3",
    ]);
    let params = SeriesParams::new(fps);
    for (k, name) in walk.names.iter().enumerate() {
        let pts: Vec<SeriesPoint> = walk
            .shots
            .iter()
            .map(|s| {
                let e = &s.readings[k].estimate;
                SeriesPoint {
                    frame: s.frame,
                    time: s.time,
                    uv: e.uv().map(|p| [p.x, p.y]),
                    std_err: e.std_err_uv,
                }
            })
            .collect();
        let m = series_metrics(&pts, &params)
            .map_err(|e| Failure::Other(format!("series metrics of {name}: {e}")))?;
        let jump_frame = m.max_jump_frame;
        let room = jump_frame
            .and_then(|jf| walk.shots.iter().find(|s| s.frame == jf))
            .map_or("–", |s| room_of(s.view.position.z));
        let onset = walk.onset(k);
        let j004 = m
            .jumps
            .iter()
            .find(|j| j.threshold == THETA_JND)
            .map_or(0, |j| j.count);
        for (key, v) in [
            ("mean_step", m.mean_step),
            ("p95_step", m.p95_step),
            ("max_jump", m.max_jump),
            ("max_jump_frame", jump_frame.map_or(f64::NAN, f64::from)),
            ("total_variation", m.total_variation),
            ("hf_rms", m.hf_rms),
            ("n_jumps_0.004", j004 as f64),
            ("noise_floor", m.noise_floor),
            ("onset_room3", onset.map_or(f64::NAN, f64::from)),
        ] {
            o.metric(format!("{name}.{key}"), v);
        }
        t.row(vec![
            if *name == WCAM_NO_BENCH {
                format!("`{name}` (diagnostic)")
            } else {
                format!("`{name}`")
            },
            f(m.mean_step, 5),
            f(m.p95_step, 5),
            f(m.max_jump, 5),
            jump_frame.map_or("–".into(), |jf| {
                format!("{jf} ({:.2} s)", m.max_jump_time.unwrap_or(f64::NAN))
            }),
            room.into(),
            f(m.total_variation, 4),
            f(m.hf_rms, 5),
            j004.to_string(),
            f(m.noise_floor, 5),
            opt_frame(onset),
        ]);
    }
    o.md.push_str(&t.render());
    Ok(())
}

/// The paper's frames 5 and 10 (its Fig. 15).
const FIG15: (u32, u32) = (5, 10);

/// The beginning of the walk (the paper's frames 5 and 10, Fig. 15) and the paper's
/// explanation: the specular reflection of a light on the bench.
fn beginning(walk: &Walk, o: &mut Out) {
    let begin: Vec<&Shot> = walk
        .shots
        .iter()
        .filter(|s| s.time <= BEGINNING_S)
        .collect();
    let (wjb, wfb) = walk.largest_step("wcam", &begin);
    let (ejb, efb) = walk.largest_step("eye", &begin);
    let (f5, f10) = FIG15;
    let k = |name: &str| walk.names.iter().position(|n| *n == name);
    let between = |name: &str| match k(name).map(|i| (walk.uv(i, f5), walk.uv(i, f10))) {
        Some((Some(a), Some(b))) => delta_uv(a, b),
        _ => f64::NAN,
    };
    let (dw, de, dnb) = (between("wcam"), between("eye"), between(WCAM_NO_BENCH));
    // How far the bench's pixels pull WCAM's white at frames 5 and 10.
    let pull = |fr: u32| match (k("wcam"), k(WCAM_NO_BENCH)) {
        (Some(a), Some(b)) => match (walk.uv(a, fr), walk.uv(b, fr)) {
            (Some(p), Some(q)) => delta_uv(p, q),
            _ => f64::NAN,
        },
        _ => f64::NAN,
    };
    let diag = |fr: u32, key: &str| {
        walk.shots
            .iter()
            .find(|s| s.frame == fr)
            .and_then(|s| s.diag.get(key).copied())
            .unwrap_or(f64::NAN)
    };
    let (p5, p10) = (pull(f5), pull(f10));
    let (h5, h10) = (diag(f5, "bench_peak"), diag(f10, "bench_peak"));
    for (key, v) in [
        ("wcam.begin_max_jump", wjb),
        ("wcam.begin_max_jump_frame", wfb.map_or(f64::NAN, f64::from)),
        ("eye.begin_max_jump", ejb),
        ("eye.begin_max_jump_frame", efb.map_or(f64::NAN, f64::from)),
        ("wcam.duv_5_10", dw),
        ("eye.duv_5_10", de),
        ("wcam_without_bench.duv_5_10", dnb),
        ("bench.pull_5", p5),
        ("bench.pull_10", p10),
        ("bench.peak_5", h5),
        ("bench.peak_10", h10),
        ("bench.share_5", diag(f5, "bench_share")),
        ("bench.share_10", diag(f10, "bench_share")),
    ] {
        o.metric(key, v);
    }
    let _ = writeln!(
        o.md,
        "\nFrames {f5} and {f10} (the paper's Fig. 15): the bench's brightest pixel is {} × the image's 99th-percentile luminance at frame {f5} and {} × at frame {f10} (above 1: a highlight stands out). Between the two frames WCAM moves by Δu′v′ {}, eye by {}, and WCAM without the bench's pixels (`{WCAM_NO_BENCH}`) by {}; the bench's pixels pull WCAM's white by {} at frame {f5} and {} at frame {f10}, and carry {} and {} of its weighted luminance sum. In the first {BEGINNING_S} s the largest WCAM step is {} at frame {}, eye's {} at frame {}.\n",
        f(h5, 2),
        f(h10, 2),
        f(dw, 5),
        f(de, 5),
        f(dnb, 5),
        f(p5, 5),
        f(p10, 5),
        pct(diag(f5, "bench_share")),
        pct(diag(f10, "bench_share")),
        f(wjb, 5),
        opt_frame(wfb),
        f(ejb, 5),
        opt_frame(efb),
    );
    o.claim(
        "(design check) a highlight on the bench appears or disappears between frames 5 and 10",
        vec![
            above(
                "brighter of frames 5, 10: bench peak / image p99",
                h5.max(h10),
                1.0,
            ),
            below(
                "dimmer of frames 5, 10: bench peak / image p99",
                h5.min(h10),
                1.0,
            ),
        ],
    );
    o.claim(
        "WCAM changes suddenly between frames 5 and 10, eye does not",
        vec![
            above("WCAM Δu′v′ from frame 5 to 10", dw, THETA_JND),
            above("Δu′v′ from frame 5 to 10, WCAM − eye", dw - de, 0.0),
        ],
    );
    o.claim(
        "the specular reflection on the bench is what changes WCAM's white",
        vec![
            above(
                "larger pull of the bench's pixels on WCAM, frame 5 or 10",
                p5.max(p10),
                THETA_JND,
            ),
            below(
                "Δu′v′ from frame 5 to 10, WCAM without bench − WCAM",
                dnb - dw,
                0.0,
            ),
        ],
    );
}

fn opt_frame(f: Option<u32>) -> String {
    f.map_or("–".into(), |v| v.to_string())
}

fn room_of(z: f32) -> &'static str {
    if z >= ROOM2_START_Z {
        "room 1"
    } else if z >= ROOM3_START_Z {
        "room 2"
    } else {
        "room 3"
    }
}
