//! `eyeadapt bench --bvh-triangles N`: how the acceleration structure scales. Builds the BVH of
//! a generated mesh (a displaced terrain of N triangles) and reports build time, memory and
//! closest-hit and shadow-ray throughput.
use crate::args::BenchArgs;
use eyeadapt_sequencer::Failure;
use eyeadapt_tracer::{Accel, BvhBuildParams, InputTri, build_params, hash_key, mix64};
use glam::Vec3A;
use std::time::Instant;

/// A k×k grid of quads over [-1, 1]², heights from a few octaves of sines: smooth like a real
/// scan or terrain, with triangles of similar size, so the BVH sees realistic locality.
fn terrain(triangles: u32) -> Vec<InputTri> {
    let k = ((triangles as f64 / 2.0).sqrt().round() as usize).max(1);
    let h = |x: f32, z: f32| {
        0.15 * (3.1 * x + 0.7).sin() * (2.3 * z).cos()
            + 0.05 * (11.0 * x + 5.0 * z).sin()
            + 0.02 * (37.0 * x - 23.0 * z).cos()
    };
    let p = |i: usize, j: usize| {
        let x = -1.0 + 2.0 * i as f32 / k as f32;
        let z = -1.0 + 2.0 * j as f32 / k as f32;
        Vec3A::new(x, h(x, z), z)
    };
    let mut out = Vec::with_capacity(2 * k * k);
    for j in 0..k {
        for i in 0..k {
            let (a, b, c, d) = (p(i, j), p(i + 1, j), p(i + 1, j + 1), p(i, j + 1));
            for v in [[a, c, b], [a, d, c]] {
                out.push(InputTri {
                    v,
                    n: None,
                    material: 0,
                    light: u32::MAX,
                });
            }
        }
    }
    out
}

/// Peak resident set (VmHWM) of this process, in bytes.
fn peak_rss() -> Option<u64> {
    let s = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = s.lines().find(|l| l.starts_with("VmHWM:"))?;
    let kb: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kb * 1024)
}

fn preset(name: &str) -> BvhBuildParams {
    match name {
        "fastest" => BvhBuildParams::fastest_build(),
        "very_fast" => BvhBuildParams::very_fast_build(),
        "fast" => BvhBuildParams::fast_build(),
        "slow" => BvhBuildParams::slow_build(),
        "very_slow" => BvhBuildParams::very_slow_build(),
        _ => BvhBuildParams::medium_build(),
    }
}

/// A uniform direction from two hashed numbers.
fn direction(r: u64) -> Vec3A {
    let u = (r >> 40) as f32 / (1u64 << 24) as f32;
    let v = ((r >> 16) & 0xff_ffff) as f32 / (1u64 << 24) as f32;
    let z = 1.0 - 2.0 * u;
    let s = (1.0 - z * z).max(0.0).sqrt();
    let phi = std::f32::consts::TAU * v;
    Vec3A::new(s * phi.cos(), z, s * phi.sin())
}

pub fn run(a: BenchArgs) -> Result<(), Failure> {
    let n = a.bvh_triangles.unwrap_or(1_000_000);
    let rss_start = peak_rss();
    let mesh = terrain(n);
    let rss_mesh = peak_rss();
    let (params, preset_name) = match a.bvh_preset.as_deref() {
        Some(p) => (preset(p), p.to_string()),
        None => (build_params(mesh.len()), "default for the size".to_string()),
    };
    let mut times = Vec::new();
    let mut accel = None;
    for run in 0..a.runs.max(1) {
        drop(accel.take()); // the previous structure is not part of this build's peak
        let t = Instant::now();
        let built = Accel::build_with(&mesh, params);
        let s = t.elapsed().as_secs_f64();
        println!("build {}: {s:.3} s", run + 1);
        times.push(s);
        accel = Some(built);
    }
    let accel = accel.expect("at least one run");
    let rss_end = peak_rss();
    times.sort_by(f64::total_cmp);
    let build = times[times.len() / 2];
    let tris = accel.triangle_count();
    let per_m = 1e6 / tris as f64;

    // Rays: camera-like rays from above looking down at the terrain, and shadow-like rays
    // between points near the surface. Deterministic, so every run traces the same set.
    let rays = 1u64 << 20;
    let key = hash_key(&[0xB7B, n as u64]);
    let closest = || {
        use rayon::prelude::*;
        (0..rays)
            .into_par_iter()
            .filter(|&i| {
                let r = mix64(key ^ i);
                let x = (r >> 40) as f32 / (1u64 << 24) as f32 * 2.0 - 1.0;
                let z = ((r >> 16) & 0xff_ffff) as f32 / (1u64 << 24) as f32 * 2.0 - 1.0;
                let o = Vec3A::new(x * 0.5, 1.5, z * 0.5);
                let mut d = direction(mix64(r));
                d.y = -d.y.abs() - 0.3;
                accel.intersect(o, d.normalize(), f32::INFINITY).is_some()
            })
            .count()
    };
    let shadow = || {
        use rayon::prelude::*;
        (0..rays)
            .into_par_iter()
            .filter(|&i| {
                let r = mix64(key ^ (i + rays));
                let x = (r >> 40) as f32 / (1u64 << 24) as f32 * 2.0 - 1.0;
                let z = ((r >> 16) & 0xff_ffff) as f32 / (1u64 << 24) as f32 * 2.0 - 1.0;
                let o = Vec3A::new(x, 0.25, z);
                accel.unoccluded(o, direction(mix64(r)), 0.5)
            })
            .count()
    };
    let t = Instant::now();
    let hits = closest();
    let t_closest = t.elapsed().as_secs_f64();
    let t = Instant::now();
    let free = shadow();
    let t_shadow = t.elapsed().as_secs_f64();

    let mib = |b: u64| b as f64 / (1024.0 * 1024.0);
    println!(
        "BVH of {tris} triangles ({} threads, preset {preset_name}): build median {build:.3} s \
         of {} = {:.2} M triangles/s",
        rayon::current_num_threads(),
        times.len(),
        tris as f64 / build / 1e6
    );
    println!(
        "structure {:.1} MiB = {:.1} MiB per million triangles (BVH nodes, triangles in BVH \
         order, shading data)",
        mib(accel.memory_bytes() as u64),
        mib(accel.memory_bytes() as u64) * per_m
    );
    if let (Some(s), Some(m), Some(e)) = (rss_start, rss_mesh, rss_end) {
        println!(
            "peak RSS {:.1} MiB: input mesh +{:.1} MiB, build +{:.1} MiB = {:.1} MiB per \
             million triangles",
            mib(e),
            mib(m.saturating_sub(s)),
            mib(e.saturating_sub(m)),
            mib(e.saturating_sub(m)) * per_m
        );
    }
    println!(
        "rays: closest hit {:.2} M rays/s ({:.1} % hit), shadow {:.2} M rays/s ({:.1} % \
         unoccluded)",
        rays as f64 / t_closest / 1e6,
        100.0 * hits as f64 / rays as f64,
        rays as f64 / t_shadow / 1e6,
        100.0 * free as f64 / rays as f64
    );
    Ok(())
}
