//! Instances and lights on animated glTF nodes move with the file's clock
//! (`tests/corpus/good/moving-lamp.gltf`: a floor lifted by 0.5 and a point light lifted from
//! y = 1 to y = 3 over one second; the camera stands still).
use eyeadapt_scene::{Light, gltf};
use glam::Vec3;
use std::path::Path;

fn scene() -> eyeadapt_scene::Scene {
    let repo = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    gltf::load_gltf(&repo.join("tests/corpus/good/moving-lamp.gltf")).unwrap()
}

fn lamp(s: &eyeadapt_scene::Scene) -> Vec3 {
    match s.lights[0] {
        Light::Point { position, .. } => position,
        ref other => panic!("{other:?}"),
    }
}

fn floor_offset(s: &eyeadapt_scene::Scene) -> Vec3 {
    s.instances[0].to_world.matrix.w_axis.truncate()
}

#[test]
fn animated_instances_and_lights_are_placed_for_any_time() {
    let s = scene();
    assert!(s.is_animated());
    let a = s.animation.as_ref().unwrap();
    assert_eq!(
        a.instances,
        vec![(0, 0)],
        "the floor instance, placed by node 0"
    );
    assert_eq!(
        (a.lights[0].0, a.lights[0].1),
        (0, 1),
        "the lamp, placed by node 1"
    );
    // As loaded: time 0.
    assert_eq!(lamp(&s), Vec3::new(0.0, 1.0, 0.0));
    assert_eq!(floor_offset(&s), Vec3::ZERO);
    let half = s.at_time(0.5);
    assert!((lamp(&half) - Vec3::new(0.0, 2.0, 0.0)).length() < 1e-6);
    assert!((floor_offset(&half) - Vec3::new(0.0, 0.25, 0.0)).length() < 1e-6);
    // After the last keyframe the nodes hold their last pose; the original is untouched.
    assert!((lamp(&s.at_time(7.0)) - Vec3::new(0.0, 3.0, 0.0)).length() < 1e-6);
    assert_eq!(lamp(&s), Vec3::new(0.0, 1.0, 0.0));
    // Moving content is scene content: the fingerprint covers it.
    assert_ne!(s.fingerprint(), {
        let mut still = s.clone();
        still.animation = None;
        still.fingerprint()
    });
}

#[test]
fn a_still_camera_follows_the_length_of_what_moves() {
    let path =
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../../tests/corpus/good/moving-lamp.gltf");
    let cam = gltf::load_camera(&path, None, None).unwrap();
    assert_eq!(cam.name, "Eye");
    assert_eq!(
        cam.range,
        (0.0, 1.0),
        "the lamp's and the floor's one second"
    );
}
