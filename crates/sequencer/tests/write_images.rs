//! A frame's files are encoded in parallel (`pipeline::write_images`), but what the caller sees
//! is sequential: every file is there, and when several cannot be written the error names the
//! first of them in the written order (raw EXR, raw PNG, then each reading's adapted PNG), not
//! whichever thread failed first.
use eyeadapt_scene::load_builtin;
use eyeadapt_sequencer::adapt::{AdaptationSettings, EstimatorConfig};
use eyeadapt_sequencer::estimator::Estimator;
use eyeadapt_sequencer::pipeline::Sampling;
use eyeadapt_sequencer::still::{StillOptions, render_still};
use std::path::Path;

const ESTIMATORS: [Estimator; 3] = [
    Estimator::GreyWorld,
    Estimator::WhitePatch,
    Estimator::GreyEdge,
];

fn still(out: &Path) -> Result<(), String> {
    let scene = load_builtin("cornell-box").unwrap();
    let o = StillOptions {
        sampling: Sampling {
            width: Some(16),
            height: Some(16),
            spp: Some(1),
            ..Default::default()
        },
        exposure: 0.0,
        out: out.to_path_buf(),
    };
    render_still(
        &scene,
        &o,
        &ESTIMATORS,
        &EstimatorConfig::default(),
        &AdaptationSettings::default(),
    )
    .map(|_| ())
    .map_err(|e| e.to_string())
}

#[test]
fn every_file_is_written() {
    let t = tempfile::tempdir().unwrap();
    still(t.path()).unwrap();
    for f in [
        "raw.exr",
        "preview.png",
        "adapted_grey_world.png",
        "adapted_white_patch.png",
        "adapted_grey_edge.png",
    ] {
        let len = std::fs::metadata(t.path().join(f)).unwrap().len();
        assert!(len > 0, "{f} is empty");
    }
}

#[test]
fn the_first_failure_in_written_order_is_reported() {
    // A directory where a file should go makes its atomic rename fail. The last adapted PNG
    // is the quickest to encode and the raw EXR the slowest, so a "first to fail" rule would
    // name the PNG.
    for blocked in [
        vec!["adapted_grey_edge.png", "raw.exr"],
        vec!["adapted_grey_edge.png", "adapted_white_patch.png"],
    ] {
        let t = tempfile::tempdir().unwrap();
        for b in &blocked {
            std::fs::create_dir(t.path().join(b)).unwrap();
            std::fs::write(t.path().join(b).join("keep"), b"x").unwrap();
        }
        let err = still(t.path()).unwrap_err();
        let first = blocked[1];
        assert!(err.contains(first), "{blocked:?}: {err}");
        assert!(!err.contains(blocked[0]), "{blocked:?}: {err}");
        // What was there before is left alone.
        for b in &blocked {
            assert_eq!(std::fs::read(t.path().join(b).join("keep")).unwrap(), b"x");
        }
    }
}
