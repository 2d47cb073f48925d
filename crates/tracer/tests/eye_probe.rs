//! EXPERIMENT driver (issue 23, goal 4; reverted right after its commit, kept in history): EYE_PROBE_CAMS, EYE_PROBE_VARIANTS, EYE_PROBE_N, EYE_PROBE_FRAMES.
//!
//! EYE_PROBE_DECOMP=1 EYE_PROBE_FRAMES=147 EYE_PROBE_CAMS=doorway2,doorway1,orange \
//!   EYE_PROBE_VARIANTS=base,all1+q,split2 cargo test --release -p eyeadapt-tracer \
//!   --test eye_probe -- --ignored --nocapture
//! Variants joined by '+': eyeall (every light from the eye), allK (every light at vertices
//! 1..=K), q (vertex 1's all-lights NEE on the path's QMC light sample), tauNN (lights below pick
//! probability NN % traced with probability P/NN %), splitK (K continuations per first
//! direction), rdir (random first direction), rrest (random after the first direction), rrN
//! (roulette from depth N), outfov (directions outside the frustum only), domNN (all-lights only
//! where no light's pick probability reaches NN %).
use eyeadapt_tracer::{
    EyeSettings, PROBE_COMPONENTS, PathSettings, ProbeVariant, SceneData, View, eye_probe,
};
use glam::{DVec3, Vec3};

fn uv(c: DVec3) -> (f64, f64) {
    let x = 0.4124564 * c.x + 0.3575761 * c.y + 0.1804375 * c.z;
    let y = 0.2126729 * c.x + 0.7151522 * c.y + 0.0721750 * c.z;
    let z = 0.0193339 * c.x + 0.1191920 * c.y + 0.9503041 * c.z;
    let d = x + 15.0 * y + 3.0 * z;
    (4.0 * x / d, 9.0 * y / d)
}

fn cpu() -> f64 {
    let s = std::fs::read_to_string("/proc/thread-self/stat").unwrap();
    let rest = &s[s.rfind(')').unwrap() + 2..];
    let f: Vec<&str> = rest.split_whitespace().collect();
    (f[11].parse::<f64>().unwrap() + f[12].parse::<f64>().unwrap()) / 100.0
}

fn seg(c: usize) -> usize {
    if c == 0 {
        1
    } else if c % 2 == 1 {
        c.div_ceil(2)
    } else {
        c / 2 + 1
    }
}

fn sigma(frames: &[DVec3]) -> f64 {
    let uvs: Vec<(f64, f64)> = frames.iter().map(|&c| uv(c)).collect();
    let n = uvs.len() as f64;
    let mu = uvs.iter().map(|p| p.0).sum::<f64>() / n;
    let mv = uvs.iter().map(|p| p.1).sum::<f64>() / n;
    let vu = uvs.iter().map(|p| (p.0 - mu).powi(2)).sum::<f64>() / (n - 1.0);
    let vv = uvs.iter().map(|p| (p.1 - mv).powi(2)).sum::<f64>() / (n - 1.0);
    (vu + vv).sqrt()
}

fn parse_variant(s: &str) -> ProbeVariant {
    let mut v = ProbeVariant::default();
    for t in s.split('+') {
        match t {
            "base" => {}
            "eyeall" => v.eye_all = true,
            "rdir" => v.random_dir = true,
            "rrest" => v.random_rest = true,
            "outfov" => v.out_fov = true,
            "q" => v.qmc_light = true,
            _ if t.starts_with("rr") => {}
            _ if t.starts_with("dom") => v.dominant = t[3..].parse::<f32>().unwrap() / 100.0,
            _ if t.starts_with("tau") => v.tau = t[3..].parse::<f32>().unwrap() / 100.0,
            _ if t.starts_with("all") => v.nee_all_upto = t[3..].parse().unwrap(),
            _ if t.starts_with("split") => v.split = t[5..].parse().unwrap(),
            _ => panic!("variant {t}"),
        }
    }
    v
}

#[test]
#[ignore]
fn eye_probe_table() {
    let scene = eyeadapt_scene::load_builtin("three-rooms").unwrap();
    let data = SceneData::new(&scene);
    let cams = std::env::var("EYE_PROBE_CAMS").unwrap_or("doorway2".into());
    let variants = std::env::var("EYE_PROBE_VARIANTS").unwrap_or("base".into());
    let n: u32 = std::env::var("EYE_PROBE_N")
        .map(|s| s.parse().unwrap())
        .unwrap_or(6144);
    let nf: u32 = std::env::var("EYE_PROBE_FRAMES")
        .map(|s| s.parse().unwrap())
        .unwrap_or(49);
    let decomp = std::env::var("EYE_PROBE_DECOMP").is_ok();
    for cam in cams.split(',') {
        let (pos, look) = match cam {
            "white" => (Vec3::new(0.6, 1.6, -0.6), Vec3::new(-0.6, 0.9, -4.0)),
            "orange" => (Vec3::new(0.2, 1.6, -7.2), Vec3::new(0.0, 1.5, -12.0)),
            "blue" => (Vec3::new(-0.1, 1.6, -11.0), Vec3::new(0.3, 1.45, -14.5)),
            "doorway1" => (Vec3::new(0.0, 1.6, -4.4), Vec3::new(0.0, 1.5, -9.0)),
            "doorway2" => (Vec3::new(0.0, 1.6, -9.6), Vec3::new(0.0, 1.5, -14.0)),
            _ => panic!("cam {cam}"),
        };
        let mut view = View::from_camera(scene.camera.as_ref().unwrap());
        view.position = pos;
        view.forward = (look - pos).normalize();
        view.up = Vec3::Y;
        for vs in variants.split(',') {
            let variant = parse_variant(vs);
            let settings = EyeSettings {
                samples: n,
                ..EyeSettings::default()
            };
            let path = PathSettings {
                max_depth: 8,
                rr_depth: vs
                    .split('+')
                    .find_map(|t| t.strip_prefix("rr").and_then(|x| x.parse::<u32>().ok()))
                    .unwrap_or(5),
            };
            let t0 = cpu();
            let frames: Vec<[DVec3; PROBE_COMPONENTS]> = (0..nf)
                .map(|f| eye_probe(&data, &view, &settings, f, path, &variant))
                .collect();
            let t = (cpu() - t0) / nf as f64;
            let totals: Vec<DVec3> = frames.iter().map(|c| c.iter().sum()).collect();
            let s = sigma(&totals);
            let mean: DVec3 = totals.iter().sum::<DVec3>() / nf as f64;
            let (mu, mv) = uv(mean);
            println!(
                "RESULT {cam:<9} {vs:<22} sigma {s:.3e}  cpu/frame {t:.4} s  eff(1/(s2 t)) {:.3e}  mean u'v' ({mu:.5}, {mv:.5}) Y {:.4}",
                1.0 / (s * s * t),
                0.2126729 * mean.x + 0.7151522 * mean.y + 0.0721750 * mean.z
            );
            if decomp {
                // Paths cut at max depth d: the components of at most d segments.
                let mut line = String::from("  cut at depth d=1..8 sigma:");
                for d in 1..=8 {
                    let part: Vec<DVec3> = frames
                        .iter()
                        .map(|c| {
                            (0..PROBE_COMPONENTS)
                                .filter(|&k| seg(k) <= d)
                                .map(|k| c[k])
                                .sum()
                        })
                        .collect();
                    line += &format!(" {:.2e}", sigma(&part));
                }
                println!("{line}");
                // Linearised variance share of each component (sums to sigma²).
                let h = 1e-6;
                let jac = |m: DVec3| -> [[f64; 3]; 2] {
                    let (u0, v0) = uv(m);
                    let mut j = [[0.0; 3]; 2];
                    for c in 0..3 {
                        let mut d = m;
                        d[c] += h * m[c].abs().max(1e-9);
                        let (u1, v1) = uv(d);
                        let dc = d[c] - m[c];
                        j[0][c] = (u1 - u0) / dc;
                        j[1][c] = (v1 - v0) / dc;
                    }
                    j
                };
                let j = jac(mean);
                let proj = |x: DVec3| -> (f64, f64) {
                    (
                        j[0][0] * x.x + j[0][1] * x.y + j[0][2] * x.z,
                        j[1][0] * x.x + j[1][1] * x.y + j[1][2] * x.z,
                    )
                };
                let cmean: Vec<DVec3> = (0..PROBE_COMPONENTS)
                    .map(|k| frames.iter().map(|c| c[k]).sum::<DVec3>() / nf as f64)
                    .collect();
                let mut line = String::from(
                    "  share of sigma² by component (eyeNEE, em1, nee1, em2, nee2, ...):",
                );
                let mut tot = 0.0;
                for k in 0..PROBE_COMPONENTS {
                    let mut acc = 0.0;
                    for (fi, c) in frames.iter().enumerate() {
                        let dk = proj(c[k] - cmean[k]);
                        let dt = proj(totals[fi] - mean);
                        acc += dk.0 * dt.0 + dk.1 * dt.1;
                    }
                    let share = acc / (nf as f64 - 1.0);
                    tot += share;
                    line += &format!(" {:+.2e}", share);
                }
                println!("{line}  (sum {:.3e} vs sigma² {:.3e})", tot, s * s);
                let mut line = String::from("  component mean luminance:");
                for m in &cmean {
                    line += &format!(
                        " {:.3}",
                        0.2126729 * m.x + 0.7151522 * m.y + 0.0721750 * m.z
                    );
                }
                println!("{line}");
            }
        }
    }
}
