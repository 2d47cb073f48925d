//! `report` on small synthetic sequence directories with known answers.
use eyeadapt_color::{
    Cat, D65_XYZ, Estimate, adaptation_matrix_rgb, delta_e_2000, rgb_to_xyz, xyz_to_lab, xyz_to_uv,
};
use eyeadapt_report::{ReportOptions, VideoOutcome, report};
use eyeadapt_sequencer::adapt::{CSV_HEADER, csv_row};
use eyeadapt_sequencer::manifest::{FrameEntry, Manifest, file_entry};
use eyeadapt_sequencer::output::{atomic_write_bytes, write_exr, write_png};
use eyeadapt_sequencer::pipeline::frame_name;
use eyeadapt_sequencer::settings::RunSettings;
use eyeadapt_tracer::Frame;
use glam::{DVec3, Vec3};
use std::collections::{BTreeMap, HashMap};
use std::path::Path;

const W: usize = 8;
const H: usize = 6;
const FPS: f64 = 24.0;

/// A textured frame with one emitter pixel.
fn frame() -> Frame {
    let n = W * H;
    let rgb: Vec<[f32; 3]> = (0..n)
        .map(|i| {
            let (x, y) = ((i % W) as f32, (i / W) as f32);
            [0.1 + 0.05 * x, 0.15 + 0.04 * y, 0.08 + 0.01 * x * y]
        })
        .collect();
    let mut emitter = vec![0.0; n];
    emitter[0] = 1.0;
    Frame {
        width: W,
        height: H,
        rgb,
        albedo: vec![[0.5; 3]; n],
        achromatic: vec![[0.1; 3]; n],
        irradiance: vec![[1.0; 3]; n],
        normal: vec![[0.0, 0.0, 1.0]; n],
        depth: vec![1.0; n],
        emitter,
        hit: vec![1.0; n],
        stats: Default::default(),
    }
}

/// Writes a sequence directory: `whites[estimator][k]` is frame k's white (`None`:
/// undefined), with raw EXRs (when `exr`) and PNG previews, the CSV and the manifest.
fn write_sequence(
    dir: &Path,
    whites: &[(&'static str, Vec<Option<DVec3>>)],
    filters: &str,
    exr: bool,
) {
    let n = whites[0].1.len();
    let fr = frame();
    let mut frames = BTreeMap::new();
    let mut csv = format!("{CSV_HEADER}\n");
    for f in 0..n as u32 {
        let time = f as f64 / FPS;
        let mut files = Vec::new();
        if exr {
            let rel = format!("frames/raw/{}", frame_name(f, "exr"));
            write_exr(&dir.join(&rel), &fr).unwrap();
            files.push(rel);
        }
        let rel = format!("frames/raw/{}", frame_name(f, "png"));
        write_png(&dir.join(&rel), &fr.rgb, W, H, 0.0).unwrap();
        files.push(rel);
        let mut rows = String::new();
        for (name, ws) in whites {
            let estimate = match ws[f as usize] {
                Some(w) => Estimate::new(w, 100),
                None => Estimate::undefined("no_white_pixels"),
            };
            rows.push_str(&csv_row(f, time, name, &estimate, &[], Vec3::ZERO));
            let rel = format!("frames/{name}/{}", frame_name(f, "png"));
            write_png(&dir.join(&rel), &fr.rgb, W, H, 0.0).unwrap();
            files.push(rel);
        }
        let rel = format!("rows/{}", frame_name(f, "csv"));
        atomic_write_bytes(&dir.join(&rel), rows.as_bytes()).unwrap();
        files.push(rel);
        csv.push_str(&rows);
        frames.insert(
            f,
            FrameEntry {
                time_s: time,
                files: files.iter().map(|r| file_entry(dir, r).unwrap()).collect(),
                invalid_samples: 0,
            },
        );
    }
    std::fs::write(dir.join("adaptation.csv"), csv).unwrap();
    let settings = RunSettings {
        width: W as u32,
        height: H as u32,
        spp: 1,
        max_depth: 8,
        rr_depth: 5,
        seed: 0,
        fps: FPS,
        cat: Cat::Cat02,
        degree: 1.0,
        eye_samples: 100,
        eye_min_samples: 100,
        eye_target_std_err_uv: 0.0,
        eye_common_random_numbers: true,
        wcam_w: 2.0,
        temporal_filters: filters
            .split(',')
            .filter(|f| !f.is_empty())
            .map(|f| f.parse().unwrap())
            .collect(),
        exposure: 0.0,
        scene: "synthetic".into(),
    };
    let m = Manifest {
        format: 1,
        tool: "eyeadapt test".into(),
        job_name: "synthetic".into(),
        job_source: "test".into(),
        job_hash: "0".repeat(64),
        planned: format!("0-{}", n - 1),
        job_frames: format!("0-{}", n - 1),
        estimators: whites.iter().map(|(e, _)| e.to_string()).collect(),
        fps: FPS,
        settings,
        frames,
    };
    m.save(dir).unwrap();
}

/// The contents of every `<text>` element of an SVG, trimmed.
fn svg_texts(svg: &str) -> Vec<String> {
    svg.split("<text")
        .skip(1)
        .filter_map(|t| {
            let body = &t[t.find('>')? + 1..];
            Some(body[..body.find("</text>")?].trim().to_string())
        })
        .collect()
}

/// coherence.csv as estimator → column → value.
fn coherence(dir: &Path) -> HashMap<String, HashMap<String, f64>> {
    let text = std::fs::read_to_string(dir.join("coherence.csv")).unwrap();
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    lines
        .map(|l| {
            let cells: Vec<&str> = l.split(',').collect();
            assert_eq!(cells.len(), header.len(), "{l}");
            let values = header
                .iter()
                .zip(&cells)
                .skip(3)
                .map(|(h, c)| (h.to_string(), c.parse::<f64>().unwrap()))
                .collect();
            (cells[0].to_string(), values)
        })
        .collect()
}

fn orange() -> DVec3 {
    rgb_to_xyz(DVec3::new(1.0, 0.6, 0.3))
}

#[test]
fn constant_series_give_zeros_and_filtered_rows_equal_the_input() {
    let dir = tempfile::tempdir().unwrap();
    let n = 12;
    write_sequence(
        dir.path(),
        &[
            ("eye", vec![Some(D65_XYZ * 3.0); n]),
            ("wcam", vec![Some(orange() * 0.2); n]),
        ],
        "fairchild,artistic",
        true,
    );
    let s = report(dir.path(), &ReportOptions::default()).unwrap();
    assert_eq!(
        s.estimators,
        [
            "eye",
            "wcam",
            "eye+fairchild",
            "wcam+fairchild",
            "eye+artistic",
            "wcam+artistic"
        ]
    );
    assert_eq!(s.derived_rows, 4 * n);
    assert!(s.y_n.unwrap() > 0.0);
    let c = coherence(dir.path());
    for est in &s.estimators {
        let m = &c[est];
        assert_eq!(m["n_points"], n as f64, "{est}");
        for k in [
            "max_jump",
            "mean_step",
            "total_variation",
            "n_jumps_0.001",
            "n_jumps_0.004",
            "n_jumps_0.007",
            "hf_rms",
            "accel_rms",
        ] {
            assert!(m[k].abs() < 1e-12, "{est} {k} = {}", m[k]);
        }
        for k in [
            "dE_cat_mean",
            "dE_cat_max",
            "dE_cat_grey_max",
            "sum_dE_raw",
            "sum_dE_adp",
        ] {
            assert_eq!(m[k], 0.0, "{est} {k}");
        }
        assert_eq!(m["n_dE_cat_gt_1"], 0.0);
        assert_eq!(m["n_image_frames"], (n - 1) as f64);
        assert!(
            m["flicker_ratio"].is_nan(),
            "a static raw sequence has no ratio"
        );
    }
    // Ratios to eye: 0/0 is NaN, eye against itself is 1 where defined.
    assert!(c["eye"]["max_jump_vs_eye"].is_nan());

    // Derived rows: one per frame and filter, the constant input white itself.
    let csv = std::fs::read_to_string(dir.path().join("adaptation.csv")).unwrap();
    let lines: Vec<&str> = csv.lines().collect();
    assert_eq!(lines[0], CSV_HEADER);
    assert_eq!(lines.len(), 1 + 2 * n + 4 * n);
    // Frame rows first, as written by the sequencer, then derived rows.
    assert!(lines[1..=2 * n].iter().all(|l| !l.contains('+')));
    let derived: Vec<Vec<&str>> = lines[1 + 2 * n..]
        .iter()
        .map(|l| l.split(',').collect())
        .collect();
    let want = orange() / orange().y;
    let want_uv = xyz_to_uv(want).unwrap();
    for est in ["wcam+fairchild", "wcam+artistic"] {
        let rows: Vec<&Vec<&str>> = derived.iter().filter(|r| r[2] == est).collect();
        assert_eq!(rows.len(), n, "{est}");
        for (k, r) in rows.iter().enumerate() {
            assert_eq!(r[0], k.to_string());
            let v = |i: usize| r[i].parse::<f64>().unwrap();
            assert!((v(3) - want.x).abs() < 1e-12 && v(4) == 1.0 && (v(5) - want.z).abs() < 1e-12);
            assert!((v(8) - want_uv.x).abs() < 1e-12 && (v(9) - want_uv.y).abs() < 1e-12);
            assert_eq!(r[17], "1", "valid");
            assert_eq!(r[18], "", "no flags");
        }
    }
    // Derived rows are sorted by frame.
    let frames: Vec<u32> = derived.iter().map(|r| r[0].parse().unwrap()).collect();
    assert!(frames.windows(2).all(|w| w[0] <= w[1]));
}

#[test]
fn a_step_is_one_jump_and_the_filter_smooths_it() {
    let dir = tempfile::tempdir().unwrap();
    let n = 16;
    let step_at = 9;
    let eye: Vec<Option<DVec3>> = (0..n)
        .map(|k| Some(if k < step_at { D65_XYZ } else { orange() }))
        .collect();
    let mut wcam = vec![Some(orange()); n];
    wcam[4] = None; // undefined: splits the series, adapts with D65
    write_sequence(
        dir.path(),
        &[("eye", eye), ("wcam", wcam)],
        "fairchild",
        true,
    );
    let s = report(dir.path(), &ReportOptions::default()).unwrap();
    assert!(
        s.notes.iter().any(|n| n.contains("wcam: 1 of 16")),
        "{:?}",
        s.notes
    );
    let c = coherence(dir.path());
    let eye = &c["eye"];
    let d65 = xyz_to_uv(D65_XYZ).unwrap();
    let o = xyz_to_uv(orange()).unwrap();
    let jump = (o - d65).length();
    assert!(jump > 0.007);
    assert!((eye["max_jump"] - jump).abs() < 1e-12);
    assert_eq!(eye["max_jump_frame"], step_at as f64);
    for th in ["0.001", "0.004", "0.007"] {
        assert_eq!(eye[&format!("n_jumps_{th}")], 1.0);
    }
    assert!((eye["total_variation"] - jump).abs() < 1e-12);
    assert!((eye["tortuosity"] - 1.0).abs() < 1e-9);
    // The image metrics see one change of white: at frame step_at.
    assert_eq!(eye["n_dE_cat_gt_1"], 1.0);
    assert_eq!(eye["dE_cat_max_frame"], step_at as f64);
    let grey = |m: glam::DMat3| {
        xyz_to_lab(
            eyeadapt_color::M_RGB_TO_XYZ * (m * DVec3::splat(0.18)).max(DVec3::ZERO),
            D65_XYZ,
        )
    };
    let direct = delta_e_2000(
        grey(adaptation_matrix_rgb(Cat::Cat02, D65_XYZ, D65_XYZ, 1.0)),
        grey(adaptation_matrix_rgb(Cat::Cat02, orange(), D65_XYZ, 1.0)),
    );
    assert!((eye["dE_cat_grey_max"] - direct).abs() < 1e-9, "{direct}");
    assert!((eye["dE_cat_grey_mean"] - direct / (n - 1) as f64).abs() < 1e-9);
    // Raw frames do not change: every adapted change is excess.
    assert_eq!(eye["sum_dE_raw"], 0.0);
    assert_eq!(eye["n_excess"], 1.0);

    // wcam: undefined frame 4 splits the series in two constant runs.
    let wcam = &c["wcam"];
    assert_eq!(wcam["n_points"], 15.0);
    assert_eq!(wcam["n_segments"], 2.0);
    assert_eq!(wcam["max_jump"], 0.0);
    // …but its images adapt with D65 at frame 4: two white changes (3→4, 4→5).
    assert_eq!(wcam["n_dE_cat_gt_1"], 2.0);
    assert_eq!(wcam["max_jump_vs_eye"], 0.0);

    // The fairchild filter spreads the step over many frames: no jump above 0.004.
    let f = &c["eye+fairchild"];
    assert!(f["max_jump"] < 0.5 * jump, "{}", f["max_jump"]);
    assert_eq!(f["n_jumps_0.004"], 0.0);
    assert!(f["max_jump_vs_eye"] < 0.5);
    // The filtered wcam holds its last output through the undefined frame.
    let csv = std::fs::read_to_string(dir.path().join("adaptation.csv")).unwrap();
    let held: Vec<&str> = csv
        .lines()
        .filter(|l| l.starts_with("4,") && l.contains(",wcam+fairchild,"))
        .collect();
    assert_eq!(held.len(), 1);
    assert!(held[0].contains(",1,undefined_input,"), "{}", held[0]);
    assert_eq!(c["wcam+fairchild"]["n_segments"], 1.0);
}

#[test]
fn report_files_name_every_estimator_and_rerunning_changes_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let n = 6;
    let ramp: Vec<Option<DVec3>> = (0..n)
        .map(|k| Some(D65_XYZ.lerp(orange(), k as f64 / n as f64)))
        .collect();
    write_sequence(
        dir.path(),
        &[
            ("eye", ramp.clone()),
            ("wcam", ramp.clone()),
            ("grey_world", ramp),
        ],
        "fairchild",
        true,
    );
    let first = report(dir.path(), &ReportOptions::default()).unwrap();
    let read = |rel: &str| std::fs::read(dir.path().join(rel)).unwrap();
    let csv1 = read("adaptation.csv");
    let coh1 = read("coherence.csv");
    let html = String::from_utf8(read("report.html")).unwrap();
    for e in &first.estimators {
        assert!(html.contains(&format!(">{e}<")), "report.html lacks {e}");
    }
    assert!(html.contains("eyeadapt ") && html.contains("temporal_filters"));
    // Per-frame estimates: 5 plots; the filter: key figure, steps, dE_cat.
    assert_eq!(html.matches("<svg").count(), 8, "5 + 3 plots inline");
    // The answer first, then the key figure, then what each estimator measures; the
    // sortable table further down.
    let at = |needle: &str| html.find(needle).unwrap_or_else(|| panic!("no {needle}"));
    assert!(at("The answer") < at("<svg"));
    assert!(at("<svg") < at("What each estimator measures"));
    assert!(at("What each estimator measures") < at("<table class=\"sortable\">"));
    assert!(html.contains("eye's largest step is") && html.contains("wcam's"));
    assert!(
        html.contains("the mean colour of the frame"),
        "grey_world's sentence"
    );
    let plots = [
        ("adaptation", true),
        ("colour_strips", false),
        ("chromaticity", false),
        ("steps", true),
        ("de_cat", true),
    ];
    for (plot, filtered_too) in plots {
        let raw = svg_texts(&String::from_utf8(read(&format!("plots/{plot}.svg"))).unwrap());
        let filtered = filtered_too.then(|| {
            svg_texts(&String::from_utf8(read(&format!("plots/{plot}_fairchild.svg"))).unwrap())
        });
        assert_eq!(
            dir.path()
                .join(format!("plots/{plot}_fairchild.svg"))
                .exists(),
            filtered_too
        );
        for e in ["eye", "wcam", "grey_world"] {
            // eye is named in the small multiples' key line rather than in a panel of its own.
            let names = |texts: &[String], name: &str| {
                texts
                    .iter()
                    .any(|t| t == name || (t.starts_with("black: ") && t.contains(name)))
            };
            assert!(names(&raw, e), "{plot}.svg lacks {e}: {raw:?}");
            if let Some(filtered) = &filtered {
                let f = format!("{e}+fairchild");
                let f = if e == "eye" && plot != "adaptation" {
                    "eye".to_string()
                } else {
                    f
                };
                assert!(
                    names(filtered, &f),
                    "{plot}_fairchild.svg lacks {f}: {filtered:?}"
                );
            }
        }
        // Axis descriptions with units.
        assert!(
            raw.iter().any(|t| t == "time (s)"
                || t == "u′ (CIE 1976 UCS, unitless)"
                || t.starts_with("frame (")),
            "{plot}: {raw:?}"
        );
    }
    assert!(first.files.contains(&"coherence_frames.csv".to_string()));

    let second = report(dir.path(), &ReportOptions::default()).unwrap();
    assert_eq!(second.derived_rows, first.derived_rows);
    assert_eq!(
        read("adaptation.csv"),
        csv1,
        "derived rows are replaced, not added"
    );
    assert_eq!(read("coherence.csv"), coh1);
    // The row files (the sequencer's source of truth) are untouched.
    let rows = std::fs::read_to_string(dir.path().join("rows/frame_000000.csv")).unwrap();
    assert!(!rows.contains('+'));
}

#[test]
fn without_raw_exrs_the_image_metrics_are_undefined_and_said_so() {
    let dir = tempfile::tempdir().unwrap();
    write_sequence(dir.path(), &[("eye", vec![Some(D65_XYZ); 4])], "", false);
    let s = report(dir.path(), &ReportOptions::default()).unwrap();
    assert_eq!(s.estimators, ["eye"]);
    assert_eq!(s.derived_rows, 0);
    assert!(s.y_n.is_none());
    assert!(
        s.notes.iter().any(|n| n.contains("no raw EXR")),
        "{:?}",
        s.notes
    );
    let c = coherence(dir.path());
    assert!(c["eye"]["dE_cat_mean"].is_nan());
    assert_eq!(c["eye"]["max_jump"], 0.0);
    assert!(!dir.path().join("plots/de_cat.svg").exists());
    assert!(dir.path().join("plots/steps.svg").exists());
}

#[test]
fn not_a_sequence_directory_is_bad_input() {
    let dir = tempfile::tempdir().unwrap();
    let e = report(dir.path(), &ReportOptions::default()).unwrap_err();
    assert_eq!(e.exit_code(), 2, "{e}");
}

#[test]
fn video_without_ffmpeg_is_skipped_with_a_message() {
    let dir = tempfile::tempdir().unwrap();
    write_sequence(dir.path(), &[("eye", vec![Some(D65_XYZ); 3])], "", true);
    let opts = ReportOptions {
        video: true,
        ffmpeg: "eyeadapt-test-no-such-ffmpeg".into(),
        ..Default::default()
    };
    let s = report(dir.path(), &opts).unwrap();
    match s.video {
        VideoOutcome::Skipped(why) => {
            assert!(
                why.contains("not found") && why.contains("--video"),
                "{why}"
            )
        }
        other => panic!("{other:?}"),
    }
    assert!(dir.path().join("report.html").exists());
    assert!(!dir.path().join("video").exists());
}

/// Needs ffmpeg with libx264 on PATH (Debian: `apt-get install ffmpeg`). Without it the test
/// only says so, unless `EYEADAPT_REQUIRE_FFMPEG=1` (set by CI), where it fails.
#[test]
fn video_with_ffmpeg_writes_one_movie_per_estimator_and_the_side_by_side() {
    let have = std::process::Command::new("ffmpeg")
        .arg("-version")
        .output()
        .is_ok_and(|o| o.status.success());
    if !have {
        assert!(
            std::env::var("EYEADAPT_REQUIRE_FFMPEG").is_err(),
            "EYEADAPT_REQUIRE_FFMPEG is set but ffmpeg is not on PATH"
        );
        eprintln!("ffmpeg not on PATH: the real-encoder video test did not run");
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let n = 5;
    write_sequence(
        dir.path(),
        &[
            ("eye", vec![Some(D65_XYZ); n]),
            ("wcam", vec![Some(orange()); n]),
        ],
        "",
        true,
    );
    let opts = ReportOptions {
        video: true,
        ..Default::default()
    };
    let s = report(dir.path(), &opts).unwrap();
    let VideoOutcome::Written { files, problems } = s.video else {
        panic!("{:?}", s.video)
    };
    assert!(problems.is_empty(), "{problems:?}");
    let names: Vec<String> = files
        .iter()
        .map(|f| f.file_name().unwrap().to_string_lossy().into_owned())
        .collect();
    assert_eq!(
        names,
        ["raw.mp4", "eye.mp4", "wcam.mp4", "raw_wcam_eye.mp4"]
    );
    let plain = probe_all(&files, n);
    assert_eq!(plain[0], (W, H), "raw.mp4 is the raw previews");
    // --overlay: the same movies, each with a frame/time strip under the picture.
    let opts = ReportOptions {
        overlay: true,
        ..opts
    };
    let s = report(dir.path(), &opts).unwrap();
    let VideoOutcome::Written { files, problems } = s.video else {
        panic!("{:?}", s.video)
    };
    assert!(problems.is_empty(), "{problems:?}");
    let overlaid = probe_all(&files, n);
    for ((f, a), b) in files.iter().zip(&plain).zip(&overlaid) {
        assert_eq!(a.0, b.0, "{}: same width", f.display());
        assert!(
            b.1 > a.1,
            "{}: the strip adds height: {a:?} {b:?}",
            f.display()
        );
    }
    let temps: Vec<_> = std::fs::read_dir(dir.path().join("video"))
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n.starts_with('.'))
        .collect();
    assert!(temps.is_empty(), "temporary files left: {temps:?}");
}

/// (width, height) of each movie, checked to be H.264 yuv420p with `n` frames.
fn probe_all(files: &[std::path::PathBuf], n: usize) -> Vec<(usize, usize)> {
    let mut sizes = Vec::new();
    for f in files {
        let probe = std::process::Command::new("ffprobe")
            .args([
                "-v",
                "error",
                "-count_frames",
                "-select_streams",
                "v:0",
                "-show_entries",
                "stream=codec_name,pix_fmt,width,height,nb_read_frames",
                "-of",
                "csv=p=0",
            ])
            .arg(f)
            .output()
            .unwrap();
        let out = String::from_utf8_lossy(&probe.stdout).trim().to_string();
        let cells: Vec<&str> = out.split(',').collect();
        assert_eq!(cells[0], "h264", "{out}");
        assert_eq!(cells[3], "yuv420p", "{out}");
        assert_eq!(cells[4], n.to_string(), "{out}");
        if f.ends_with("raw_wcam_eye.mp4") {
            assert_eq!(
                cells[1],
                (3 * W).to_string(),
                "three panels side by side: {out}"
            );
            assert!(
                cells[2].parse::<usize>().unwrap() > H,
                "label strip on top: {out}"
            );
        } else {
            assert_eq!(cells[1], W.to_string(), "{out}");
        }
        sizes.push((cells[1].parse().unwrap(), cells[2].parse().unwrap()));
    }
    sizes
}
