//! `render`, `sequence` and `paper` share one frame pipeline: the same frame of the same job
//! gives the same CSV rows and the same pixels and AOVs whichever command rendered it.
//!
//! This compares the commands with each other in one run, so it holds on any CPU. That the
//! pipeline's output did not change across a refactoring is checked by comparing two binaries
//! on one machine (`scripts/same-output.sh OLD NEW`), not by hard-coded checksums, which
//! could differ with the CPU's libm/FMA variants.
use eyeadapt_paper::PaperOptions;
use eyeadapt_sequencer::job::{JobOverrides, load_job};
use eyeadapt_sequencer::output::read_exr;
use eyeadapt_sequencer::pipeline::Sampling;
use eyeadapt_sequencer::progress::LogFormat;
use eyeadapt_sequencer::sequence::{SequenceOptions, run_sequence};
use eyeadapt_sequencer::still::{StillOptions, render_still};
use std::path::Path;

/// Every channel of an EXR as bits (equal bits = equal pixels, whatever the compressor did).
fn exr_bits(p: &Path) -> Vec<u32> {
    let f = read_exr(p).unwrap();
    [&f.rgb, &f.albedo, &f.achromatic, &f.irradiance, &f.normal]
        .into_iter()
        .flat_map(|c| c.iter().flatten().map(|v| v.to_bits()))
        .chain(f.depth.iter().map(|v| v.to_bits()))
        .chain(f.emitter.iter().map(|v| v.to_bits()))
        .collect()
}

#[test]
fn render_sequence_and_paper_give_the_same_frame() {
    let t = tempfile::tempdir().unwrap();
    // Paper case 1 (one frame of `configs/cornell-orange.toml` over builtin:cornell-orange),
    // quick variant (64×64, 16 spp) with a small eye budget.
    let paper = PaperOptions {
        quick: true,
        cases: vec![1],
        eye_samples: Some(256),
        ..PaperOptions::new(t.path().join("paper"))
    };
    eyeadapt_paper::run(&paper).unwrap();
    let work = paper.work_dir().join("case1-cornell-orange");
    let paper_csv = std::fs::read_to_string(work.join("cornell-orange.csv")).unwrap();

    // The same job file and settings as a sequence.
    let sampling = Sampling {
        width: Some(64),
        height: Some(64),
        spp: Some(16),
        seed: Some(0),
        ..Default::default()
    };
    let overrides = JobOverrides {
        sampling,
        eye_samples: Some(256),
    };
    let job = load_job(Some(&work.join("cornell-orange.toml")), &overrides).unwrap();
    let seq = t.path().join("seq");
    let o = SequenceOptions {
        out: seq.clone(),
        selection: None,
        chunk: None,
        force: false,
        verify: false,
        log_format: LogFormat::Plain,
        plain_progress: true,
        stop: None,
    };
    run_sequence(&job, &o).unwrap();
    let rows = std::fs::read_to_string(seq.join("rows/frame_000000.csv")).unwrap();

    // And the scene as a still, with the job's estimators (all and eye_fov).
    let still = t.path().join("still");
    std::fs::create_dir_all(&still).unwrap();
    let so = StillOptions {
        sampling,
        exposure: job.exposure,
        out: still.clone(),
    };
    let r = render_still(
        &job.scene,
        &so,
        &job.estimators,
        &job.estimator_config,
        &job.adaptation,
    )
    .unwrap();
    assert_eq!(r.frame.readings.len(), 9, "every estimator ran");
    let still_csv = std::fs::read_to_string(still.join("adaptation.csv")).unwrap();

    let header = eyeadapt_sequencer::adapt::CSV_HEADER;
    assert_eq!(rows.lines().count(), 9);
    assert_eq!(paper_csv, format!("{header}\n{rows}"), "paper vs sequence");
    assert_eq!(still_csv, format!("{header}\n{rows}"), "render vs sequence");
    let seq_exr = exr_bits(&seq.join("frames/raw/frame_000000.exr"));
    assert_eq!(
        exr_bits(&work.join("cornell-orange_frame_000000.exr")),
        seq_exr
    );
    assert_eq!(exr_bits(&still.join("raw.exr")), seq_exr);
    for e in ["eye", "wcam", "grey_edge"] {
        assert_eq!(
            std::fs::read(still.join(format!("adapted_{e}.png"))).unwrap(),
            std::fs::read(seq.join(format!("frames/{e}/frame_000000.png"))).unwrap(),
            "{e}"
        );
    }
}
