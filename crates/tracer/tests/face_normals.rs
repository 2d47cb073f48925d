//! A flat-shaded mesh exported with its faces' normals as vertex normals (the Cornell box of
//! Mitsuba's data, most architectural OBJ exports) renders exactly as without them: the tracer
//! finds they are the geometric normals and skips interpolating them (`interaction.rs`).
mod common;

use common::{frame_hash, settings};
use eyeadapt_scene::Scene;
use eyeadapt_tracer::{SceneData, View, render};
use glam::Vec3;

/// `scene` with every mesh's triangles unshared (three vertices each) and given their face
/// normals as vertex normals; `turn` tilts the first vertex normal of every triangle by that
/// many radians about its first edge.
fn with_face_normals(scene: &Scene, turn: f32) -> Scene {
    let mut s = scene.clone();
    for mesh in &mut s.meshes {
        let (mut positions, mut normals) = (Vec::new(), Vec::new());
        mesh.uvs = per_corner(&mesh.indices, &mesh.uvs);
        mesh.colors = per_corner(&mesh.indices, &mesh.colors);
        for t in &mesh.indices {
            let v = t.map(|k| mesh.positions[k as usize]);
            let (e1, e2) = (v[1] - v[0], v[2] - v[0]);
            let n = e1.cross(e2).normalize_or_zero();
            let tilted = glam::Quat::from_axis_angle(e1.normalize_or(Vec3::X), turn) * n;
            positions.extend(v);
            normals.extend([tilted, n, n]);
        }
        mesh.indices = (0..mesh.indices.len() as u32)
            .map(|i| [3 * i, 3 * i + 1, 3 * i + 2])
            .collect();
        mesh.positions = positions;
        mesh.normals = normals;
    }
    s
}

/// Per-vertex values `a` (if any) for triangles `indices` unshared.
fn per_corner<T: Copy>(indices: &[[u32; 3]], a: &[T]) -> Vec<T> {
    match a.is_empty() {
        true => Vec::new(),
        false => indices.iter().flatten().map(|&k| a[k as usize]).collect(),
    }
}

#[test]
fn face_normals_render_as_without_normals_and_smoothing_does_not() {
    let scene = eyeadapt_scene::load_builtin("cornell-box").unwrap();
    let mut view = View::from_camera(scene.camera.as_ref().unwrap());
    (view.width, view.height) = (16, 16);
    let frame = |s: &Scene| frame_hash(&render(&SceneData::new(s), &view, &settings(4, 5, 4)));
    let plain = frame(&scene);
    assert!(
        scene.meshes.iter().all(|m| m.normals.is_empty()),
        "the built-in box has no normals of its own"
    );
    assert_eq!(frame(&with_face_normals(&scene, 0.0)), plain);
    // Normals 2° off their faces are the mesh's smoothing: interpolated, they move the bits.
    assert_ne!(frame(&with_face_normals(&scene, 0.035)), plain);
}
