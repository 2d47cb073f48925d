//! Estimators on rendered scenes with known answers (issue 3, acceptance 4 and 5).
use std::process::Command;

/// A closed grey room (every surface reflectance `rho`) lit by one ceiling quad of `light`.
fn room(rho: f32, light: [f32; 3]) -> String {
    let q = |corner: [f32; 3], u: [f32; 3], v: [f32; 3], m: &str| {
        format!(
            "[[shapes]]\ntype = \"quad\"\nmaterial = \"{m}\"\ncorner = {corner:?}\nu = {u:?}\nv = {v:?}\n\n"
        )
    };
    let mut s = format!(
        "[camera]\nposition = [0.0, 1.2, 1.6]\nlook_at = [0.0, 1.1, -2.0]\nfov_deg = 60.0\nwidth = 48\nheight = 32\n\n\
         [[materials]]\nname = \"grey\"\ntype = \"diffuse\"\nreflectance = [{rho}, {rho}, {rho}]\n\n\
         [[materials]]\nname = \"lamp\"\ntype = \"diffuse\"\nreflectance = [0.5, 0.5, 0.5]\nemission = {light:?}\n\n"
    );
    // Floor, ceiling, four walls of a 4 x 3 x 4 room centred on x = 0, z in [-2, 2].
    s += &q([-2.0, 0.0, -2.0], [0.0, 0.0, 4.0], [4.0, 0.0, 0.0], "grey");
    s += &q([-2.0, 3.0, -2.0], [4.0, 0.0, 0.0], [0.0, 0.0, 4.0], "grey");
    s += &q([-2.0, 0.0, -2.0], [4.0, 0.0, 0.0], [0.0, 3.0, 0.0], "grey");
    s += &q([-2.0, 0.0, 2.0], [0.0, 3.0, 0.0], [4.0, 0.0, 0.0], "grey");
    s += &q([-2.0, 0.0, -2.0], [0.0, 3.0, 0.0], [0.0, 0.0, 4.0], "grey");
    s += &q([2.0, 0.0, -2.0], [0.0, 0.0, 4.0], [0.0, 3.0, 0.0], "grey");
    // The lamp faces down (u x v = -y).
    s += &q([-0.5, 2.99, -0.5], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0], "lamp");
    s
}

fn render(scene: &str, estimators: &str) -> (tempfile::TempDir, String) {
    let dir = tempfile::tempdir().unwrap();
    let p = dir.path().join("scene.toml");
    std::fs::write(&p, scene).unwrap();
    let o = Command::new(env!("CARGO_BIN_EXE_eyeadapt"))
        .args([
            "render",
            p.to_str().unwrap(),
            "--spp",
            "16",
            "--eye-samples",
            "16384",
            "--estimators",
            estimators,
        ])
        .args(["--out", dir.path().join("out").to_str().unwrap()])
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let csv = std::fs::read_to_string(dir.path().join("out/adaptation.csv")).unwrap();
    (dir, csv)
}

/// (estimator, u', v') of every row.
fn whites(csv: &str) -> Vec<(String, f64, f64)> {
    let mut lines = csv.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let col = |n: &str| header.iter().position(|h| *h == n).unwrap();
    let (e, u, v) = (col("estimator"), col("u_prime"), col("v_prime"));
    lines
        .map(|l| {
            let f: Vec<&str> = l.split(',').collect();
            (
                f[e].to_string(),
                f[u].parse().unwrap(),
                f[v].parse().unwrap(),
            )
        })
        .collect()
}

#[test]
fn every_estimator_returns_d65_under_a_white_light_on_white_surfaces() {
    let (_d, csv) = render(&room(0.73, [8.0, 8.0, 8.0]), "all,eye_fov");
    let d65 = (0.197_830_006_6, 0.468_319_994_9);
    let w = whites(&csv);
    assert_eq!(w.len(), 9);
    for (name, u, v) in w {
        let duv = ((u - d65.0).powi(2) + (v - d65.1).powi(2)).sqrt();
        assert!(duv <= 1e-3, "{name}: Δu′v′ from D65 = {duv:.2e}");
    }
}

/// Mean HSV saturation (sRGB-encoded, as the paper read it) over the back wall's central region.
fn wall_saturation(png: &std::path::Path) -> f64 {
    let img = image::open(png).unwrap().to_rgb8();
    let (w, h) = img.dimensions();
    let mut sum = 0.0;
    let mut n = 0.0;
    for y in h / 4..h / 2 {
        for x in w / 3..2 * w / 3 {
            let p = img.get_pixel(x, y).0.map(|c| c as f64 / 255.0);
            let max = p.iter().cloned().fold(0.0, f64::max);
            let min = p.iter().cloned().fold(1.0, f64::min);
            sum += if max > 0.0 { (max - min) / max } else { 0.0 };
            n += 1.0;
        }
    }
    sum / n
}

#[test]
fn white_world_orange_light_reads_neutral_after_eye_and_wcam() {
    // About 2700 K in linear sRGB (a blackbody's chromaticity, luminance-scaled).
    let (d, csv) = render(&room(0.73, [10.0, 5.2, 1.8]), "eye,wcam");
    let out = d.path().join("out");
    let raw = wall_saturation(&out.join("preview.png"));
    assert!(raw > 0.2, "the raw image must look orange (S = {raw:.3})");
    for est in ["eye", "wcam"] {
        let s = wall_saturation(&out.join(format!("adapted_{est}.png")));
        assert!(
            s < 0.01,
            "{est}: wall saturation after adaptation {s:.4} (raw {raw:.3})\n{csv}"
        );
    }
}
