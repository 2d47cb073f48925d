//! What the fuzz targets found: the inputs that once crashed them still do not, and the
//! MTL line that crashed tobj is a warning.
use super::harness::*;
use std::path::PathBuf;

/// The fuzz targets' checks (`fuzz/fuzz_targets/checks.rs`), run here on every input kept in
/// `tests/corpus/fuzz-regressions/TARGET/`: inputs that once crashed a target, and a few seeds.
#[path = "../../fuzz/fuzz_targets/checks.rs"]
mod checks;

#[test]
fn fuzz_regressions_no_longer_crash() {
    type Check = fn(&[u8]);
    let targets: [(&str, Check); 4] = [
        ("scene_toml", checks::scene_toml),
        ("obj", checks::obj),
        ("frame_spec", checks::frame_spec),
        ("mitsuba_xml", checks::mitsuba_xml),
    ];
    let mut ran = 0;
    let mut crashed = Vec::new();
    for (target, check) in targets {
        let dir = corpus().join("fuzz-regressions").join(target);
        let Ok(entries) = std::fs::read_dir(&dir) else {
            continue;
        };
        let mut files: Vec<PathBuf> = entries.map(|e| e.unwrap().path()).collect();
        files.sort();
        for f in files {
            let data = std::fs::read(&f).unwrap();
            if std::panic::catch_unwind(|| check(&data)).is_err() {
                crashed.push(f.display().to_string());
            }
            ran += 1;
        }
    }
    println!("fuzz regressions: {ran} inputs, {} crashed", crashed.len());
    assert!(crashed.is_empty(), "still crashing: {crashed:?}");
}

/// Found by the `obj` fuzz target: tobj 4.0.5 panics (exit 101) on an MTL colour line with
/// fewer than three numbers. Like any malformed MTL it now only costs the material: a warning
/// naming `file.mtl:LINE`, and the error material.
#[test]
fn short_mtl_colour_line_is_a_warning_not_a_panic() {
    let t = tempfile::tempdir().unwrap();
    let d = t.path();
    std::fs::write(
        d.join("mesh.obj"),
        "mtllib mesh.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl paint\nf 1 2 3\n",
    )
    .unwrap();
    for line in ["Kd 0.5 0.5", "Ke 1", "Ka", "Ks 0 0"] {
        std::fs::write(d.join("mesh.mtl"), format!("newmtl paint\n{line}\n")).unwrap();
        std::fs::write(
            d.join("scene.toml"),
            "[camera]\nposition = [0.3, 0.3, 3.0]\nlook_at = [0.3, 0.3, 0.0]\nfov_deg = 45.0\n\
             width = 8\nheight = 6\n\n[[shapes]]\ntype = \"obj\"\nfile = \"mesh.obj\"\n\n\
             [environment]\nradiance = [1.0, 1.0, 1.0]\n",
        )
        .unwrap();
        let (code, err) = run(eyeadapt()
            .arg("render")
            .arg(d.join("scene.toml"))
            .args(RENDER)
            .arg("--out")
            .arg(d.join("out")));
        assert_eq!(code, 0, "{line}: {err}");
        assert!(
            err.contains("mesh.mtl:2:") && err.contains("needs three numbers"),
            "{line}: {err}"
        );
    }
}
