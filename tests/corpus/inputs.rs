//! `scene/`, `xml/`, `gltf/` (files `eyeadapt render` reads) and `obj/` (an OBJ and its MTL,
//! rendered as a scratch scene's only shape): every case exits 2 with its location and
//! message, into a directory holding a good render that stays byte-for-byte unchanged.
use super::harness::*;

#[test]
fn bad_scenes_exit_2_with_their_location_and_leave_a_render_alone() {
    let t = tempfile::tempdir().unwrap();
    let root = t.path();
    let render_out = good_render(root);
    let before = snapshots(&[&render_out]);
    let mut outcomes = Vec::new();
    for (case, path, x) in cases("scene", "toml")
        .into_iter()
        .chain(cases("xml", "xml"))
        .chain(cases("gltf", "gltf"))
    {
        let (code, err) = run(eyeadapt()
            .arg("render")
            .arg(&path)
            .args(RENDER)
            .arg("--out")
            .arg(&render_out));
        outcomes.push(check(&case, code, &err, &x));
    }
    for (case, path, x) in cases("obj", "obj") {
        // A scene in a scratch directory whose only shape is the corpus OBJ (absolute path, so
        // its MTL resolves next to it).
        let d = root.join("obj-scenes").join(path.file_stem().unwrap());
        std::fs::create_dir_all(&d).unwrap();
        let scene = d.join("scene.toml");
        std::fs::write(
            &scene,
            format!(
                "[camera]\nposition = [0.3, 0.3, 3.0]\nlook_at = [0.3, 0.3, 0.0]\nfov_deg = 45.0\n\
                 width = 8\nheight = 6\n\n[[shapes]]\ntype = \"obj\"\nfile = {:?}\n\n\
                 [environment]\nradiance = [1.0, 1.0, 1.0]\n",
                path.to_str().unwrap()
            ),
        )
        .unwrap();
        let (code, err) = run(eyeadapt()
            .arg("render")
            .arg(&scene)
            .args(RENDER)
            .arg("--out")
            .arg(&render_out));
        let mut o = check(&case, code, &err, &x);
        if !err.contains("scene.toml:10:") {
            o.problems.push(format!(
                "the scene's `file` line (scene.toml:10) not named:\n{err}"
            ));
        }
        outcomes.push(o);
    }
    assert_unchanged(&[&render_out], &before);
    finish(
        &outcomes,
        &[("scene", 59), ("xml", 39), ("gltf", 7), ("obj", 17)],
    );
}
