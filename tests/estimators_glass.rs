//! The field-of-view estimators behind glass (issue 19): WCAM and NCNS read their AOVs at the
//! first non-specular hit (docs/job-format.md, "Behind glass"), so a neutral window pane
//! between the camera and a lamp-lit room changes neither their reading nor the eye sensor's
//! beyond the pane's small loss of light; with the pane's own (specular) surface in the AOVs
//! instead, WCAM and NCNS would see no white surface at all.
use std::process::Command;

/// A closed grey room lit by a warm ceiling lamp; with `pane`, a glass partition (a thin
/// dielectric) fills the room's cross-section 0.4 m in front of the camera.
fn room(pane: bool) -> String {
    let q = |corner: [f32; 3], u: [f32; 3], v: [f32; 3], m: &str| {
        format!(
            "[[shapes]]\ntype = \"quad\"\nmaterial = \"{m}\"\ncorner = {corner:?}\nu = {u:?}\nv = {v:?}\n\n"
        )
    };
    let mut s = String::from(
        "[camera]\nposition = [0.0, 1.2, 1.6]\nlook_at = [0.3, 1.0, -2.0]\nfov_deg = 60.0\nwidth = 48\nheight = 32\n\n\
         [[materials]]\nname = \"white\"\ntype = \"diffuse\"\nreflectance = [0.8, 0.8, 0.8]\n\n\
         [[materials]]\nname = \"blue\"\ntype = \"diffuse\"\nreflectance = [0.1, 0.2, 0.6]\n\n\
         [[materials]]\nname = \"pane\"\ntype = \"thin_dielectric\"\nior = 1.5\n\n\
         [[materials]]\nname = \"lamp\"\ntype = \"diffuse\"\nreflectance = [0.5, 0.5, 0.5]\nemission = [9.7, 5.3, 1.9]\n\n",
    );
    s += &q([-2.0, 0.0, -2.0], [0.0, 0.0, 4.0], [4.0, 0.0, 0.0], "white");
    s += &q([-2.0, 3.0, -2.0], [4.0, 0.0, 0.0], [0.0, 0.0, 4.0], "white");
    s += &q([-2.0, 0.0, -2.0], [4.0, 0.0, 0.0], [0.0, 3.0, 0.0], "white");
    s += &q([-2.0, 0.0, 2.0], [0.0, 3.0, 0.0], [4.0, 0.0, 0.0], "white");
    s += &q([-2.0, 0.0, -2.0], [0.0, 3.0, 0.0], [0.0, 0.0, 4.0], "blue");
    s += &q([2.0, 0.0, -2.0], [0.0, 0.0, 4.0], [0.0, 3.0, 0.0], "white");
    s += &q([-0.5, 2.99, -0.5], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0], "lamp");
    if pane {
        s += &q([-2.0, 0.0, 1.2], [4.0, 0.0, 0.0], [0.0, 3.0, 0.0], "pane");
    }
    s
}

/// (estimator, u′, v′) of every row of a render of `scene`.
fn render(scene: &str) -> Vec<(String, f64, f64)> {
    let dir = tempfile::tempdir().unwrap();
    let p = dir.path().join("scene.toml");
    std::fs::write(&p, scene).unwrap();
    let out = dir.path().join("out");
    let o = Command::new(env!("CARGO_BIN_EXE_eyeadapt"))
        .args(["render", p.to_str().unwrap(), "--spp", "32"])
        .args(["--eye-samples", "16384", "--estimators", "eye,wcam,ncns"])
        .args(["--out", out.to_str().unwrap()])
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let csv = std::fs::read_to_string(out.join("adaptation.csv")).unwrap();
    let mut lines = csv.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let col = |n: &str| header.iter().position(|h| *h == n).unwrap();
    let (e, u, v) = (col("estimator"), col("u_prime"), col("v_prime"));
    lines
        .map(|l| {
            let f: Vec<&str> = l.split(',').collect();
            (
                f[e].to_string(),
                f[u].parse().unwrap_or(f64::NAN),
                f[v].parse().unwrap_or(f64::NAN),
            )
        })
        .collect()
}

#[test]
fn wcam_ncns_and_eye_read_the_room_behind_a_pane() {
    let open = render(&room(false));
    let glazed = render(&room(true));
    // The lamp's chromaticity (u′v′ of linear sRGB (9.7, 5.3, 1.9)).
    for name in ["eye", "wcam", "ncns"] {
        let find = |rows: &[(String, f64, f64)]| {
            let r = rows.iter().find(|r| r.0 == name).unwrap();
            (r.1, r.2)
        };
        let (a, b) = (find(&open), find(&glazed));
        let d = ((a.0 - b.0).powi(2) + (a.1 - b.1).powi(2)).sqrt();
        eprintln!("{name}: open {a:?}, behind the pane {b:?}, Δu′v′ {d:.2e}");
        assert!(
            a.0.is_finite() && b.0.is_finite(),
            "{name} undefined: {a:?} {b:?}"
        );
        // Well below a just-noticeable difference (0.004): the pane is neutral.
        assert!(d < 1.5e-3, "{name}: Δu′v′ {d:.2e} ({a:?} vs {b:?})");
    }
}
