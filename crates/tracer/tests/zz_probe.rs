use eyeadapt_tracer::{Guiding, SceneData, View, render};
mod common;

fn relmse(a: &[[f32; 3]], b: &[[f32; 3]]) -> (f64, f64) {
    let mut rel = 0.0;
    let mut dim = 0.0;
    let mut nd = 0;
    for (x, y) in a.iter().zip(b) {
        let ly = (y[0] + y[1] + y[2]) as f64 / 3.0;
        let e: f64 = (0..3).map(|c| ((x[c] - y[c]) as f64).powi(2)).sum::<f64>() / 3.0;
        rel += e / (ly * ly + 1e-2);
        if ly < 0.3 {
            dim += e;
            nd += 1;
        }
    }
    (rel / a.len() as f64, (dim / nd.max(1) as f64).sqrt())
}

fn cpu() -> f64 {
    let s = std::fs::read_to_string("/proc/self/stat").unwrap();
    let f: Vec<&str> = s.rsplit(')').next().unwrap().split_whitespace().collect();
    (f[11].parse::<f64>().unwrap() + f[12].parse::<f64>().unwrap()) / 100.0
}

fn rmse(a: &[[f32; 3]], b: &[[f32; 3]]) -> f64 {
    let s: f64 = a
        .iter()
        .zip(b)
        .map(|(x, y)| (0..3).map(|c| ((x[c] - y[c]) as f64).powi(2)).sum::<f64>())
        .sum();
    (s / (3 * a.len()) as f64).sqrt()
}

#[test]
#[ignore]
fn probe() {
    let name = std::env::var("SCENE").unwrap_or("interior".into());
    let w: u32 = std::env::var("W")
        .map(|v| v.parse().unwrap())
        .unwrap_or(160);
    let refspp: u32 = std::env::var("REFSPP")
        .map(|v| v.parse().unwrap())
        .unwrap_or(1024);
    let scene = if name.ends_with(".toml") {
        eyeadapt_scene::load_scene_str(
            &std::fs::read_to_string(&name).unwrap(),
            std::path::Path::new(&name),
        )
        .unwrap()
    } else {
        eyeadapt_scene::load_builtin(&name).unwrap()
    };
    let mut view = View::from_camera(scene.camera.as_ref().unwrap());
    view.height = view.height * w / view.width;
    view.width = w;
    let data = SceneData::new(&scene);
    let cache = format!("/tmp/g/ref-{}-{w}-{refspp}.bin", name.replace("/", "_"));
    let reference: Vec<[f32; 3]> = match std::fs::read(&cache) {
        Ok(b) => b
            .chunks(12)
            .map(|c| [0, 1, 2].map(|i| f32::from_le_bytes(c[4 * i..4 * i + 4].try_into().unwrap())))
            .collect(),
        Err(_) => {
            let mut s = common::settings(refspp, 999, 8);
            s.guiding = Guiding::Off;
            let f = render(&data, &view, &s);
            let b: Vec<u8> = f
                .rgb
                .iter()
                .flatten()
                .flat_map(|v| v.to_le_bytes())
                .collect();
            std::fs::write(&cache, b).unwrap();
            f.rgb
        }
    };
    let spps: Vec<u32> = std::env::var("SPPS")
        .unwrap_or("16,64".into())
        .split(",")
        .map(|v| v.parse().unwrap())
        .collect();
    for spp in spps {
        let gs: Vec<Guiding> = if std::env::var("ONLY_ON").is_ok() {
            vec![Guiding::On]
        } else if std::env::var("ONLY_OFF").is_ok() {
            vec![Guiding::Off]
        } else {
            vec![Guiding::Off, Guiding::On]
        };
        for g in gs {
            let mut s = common::settings(spp, 1, 8);
            s.guiding = g;
            let c0 = cpu();
            let f = render(&data, &view, &s);
            let cput = cpu() - c0;
            let e = rmse(&f.rgb, &reference);
            let mut ppm = format!("P6 {} {} 255\n", view.width, view.height).into_bytes();
            for px in &f.rgb {
                for c in px {
                    ppm.push(((c * 8.0).max(0.0).powf(1.0 / 2.2).min(1.0) * 255.0) as u8);
                }
            }
            std::fs::write(format!("/tmp/g/out-{spp}-{g:?}.ppm"), ppm).unwrap();
            let t = f.stats.seconds;
            let mean: f64 =
                f.rgb.iter().flatten().map(|&v| v as f64).sum::<f64>() / (3 * f.rgb.len()) as f64;
            let refmean: f64 = reference.iter().flatten().map(|&v| v as f64).sum::<f64>()
                / (3 * reference.len()) as f64;
            let (rel, dim) = relmse(&f.rgb, &reference);
            println!(
                "{name} spp {spp} {g:?}: cpu {cput:.2}s relmse {rel:.5} rmse_dim {dim:.5} t {t:.2}s rmse {e:.5} eff {:.1} mean {mean:.5} ref {refmean:.5}",
                1.0 / (e * e * t)
            );
        }
    }
}
