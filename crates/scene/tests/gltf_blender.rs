//! glTF files as Blender writes them, checked against Blender itself.
//!
//! Blender (PyPI's `bpy`, installed by `scripts/blender/install.sh`) builds a two-room
//! walkthrough with a Bezier-keyframed camera that turns by 210°, exports it to `.glb` and
//! dumps its own evaluated camera `matrix_world` per frame. eyeadapt's camera pose at every
//! frame must equal Blender's within 1e-4. Without Blender the test says that it skipped,
//! unless `EYEADAPT_REQUIRE_BLENDER=1`, when it fails.
use eyeadapt_scene::gltf::load_camera;
use std::path::{Path, PathBuf};
use std::process::Command;

fn repo() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// The Python that has `bpy`, or why there is none.
fn blender_python() -> Result<PathBuf, String> {
    let out = Command::new("bash")
        .arg(repo().join("scripts/blender/install.sh"))
        .output()
        .map_err(|e| format!("cannot run scripts/blender/install.sh: {e}"))?;
    if out.status.success() {
        let path = String::from_utf8_lossy(&out.stdout).trim().to_string();
        Ok(PathBuf::from(path))
    } else {
        Err(String::from_utf8_lossy(&out.stderr).trim().to_string())
    }
}

fn skip_or_fail(why: &str) {
    if std::env::var("EYEADAPT_REQUIRE_BLENDER").as_deref() == Ok("1") {
        panic!("Blender is required (EYEADAPT_REQUIRE_BLENDER=1) but: {why}");
    }
    eprintln!("skipped: Blender (bpy) is not available: {why}");
}

fn vec3(v: &serde_json::Value) -> glam::DVec3 {
    let a: Vec<f64> = v
        .as_array()
        .expect("array")
        .iter()
        .map(|x| x.as_f64().expect("number"))
        .collect();
    glam::DVec3::new(a[0], a[1], a[2])
}

#[test]
fn camera_poses_match_blender_at_every_frame() {
    let python = match blender_python() {
        Ok(p) => p,
        Err(why) => return skip_or_fail(&why),
    };
    let dir = tempfile::tempdir().unwrap();
    let status = Command::new(&python)
        .arg(repo().join("scripts/blender/walkthrough.py"))
        .arg(dir.path())
        .args(["--frames", "48"])
        .output()
        .expect("run Blender");
    assert!(
        status.status.success(),
        "walkthrough.py failed: {}",
        String::from_utf8_lossy(&status.stderr)
    );
    let blender: serde_json::Value =
        serde_json::from_slice(&std::fs::read(dir.path().join("blender_camera.json")).unwrap())
            .unwrap();
    let fps = blender["fps"].as_f64().unwrap();
    let poses = blender["poses"].as_array().unwrap();
    let cam = load_camera(&dir.path().join("walkthrough.glb"), None, None).unwrap();
    assert_eq!(cam.name, "Eye");
    let motion = eyeadapt_scene::CameraMotion::Gltf {
        camera: Box::new(cam.clone()),
        fps,
    };
    assert_eq!(
        motion.frame_count(),
        poses.len(),
        "frames from time 0 to the end"
    );
    let fov = blender["yfov_deg"].as_f64().unwrap();
    assert!(
        (cam.fov_deg - fov).abs() < 1e-4,
        "yfov {} vs Blender {fov}",
        cam.fov_deg
    );
    let mut worst: f64 = 0.0;
    let mut turn: f64 = 0.0;
    let mut previous: Option<glam::DVec3> = None;
    for p in poses {
        let frame = p["frame"].as_u64().unwrap() as f64;
        let pose = cam.pose(frame / fps);
        for (ours, theirs) in [
            (pose.position, vec3(&p["position"])),
            (pose.forward, vec3(&p["forward"])),
            (pose.up, vec3(&p["up"])),
        ] {
            let d = (ours - theirs).abs().max_element();
            worst = worst.max(d);
            assert!(
                d <= 1e-4,
                "frame {frame}: {ours} vs Blender {theirs} (|Δ| {d:e})"
            );
        }
        // The authored turn: the gaze's heading about +y adds up to more than 180°.
        let flat = glam::DVec3::new(pose.forward.x, 0.0, pose.forward.z).normalize();
        if let Some(prev) = previous {
            turn += prev.angle_between(flat);
        }
        previous = Some(flat);
    }
    eprintln!(
        "{} frames, largest |Δ| against Blender {worst:e}, total turn {:.1}°",
        poses.len(),
        turn.to_degrees()
    );
    assert!(
        turn.to_degrees() > 180.0,
        "the camera turns by {}°",
        turn.to_degrees()
    );
}
