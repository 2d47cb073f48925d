//! `eyeadapt bench --bvh-triangles N`: how the acceleration structure scales (issue 10, goal 4).
//! Builds the BVH of a generated mesh (a displaced terrain of N triangles) with the
//! renderer's own `Accel::build_with` (obvhs's binary BVH, its collapse to eight-wide nodes
//! and the copy into BVH order; obvhs's own CWBVH build is timed beside it), and reports build
//! time, memory and closest-hit and shadow-ray throughput through the renderer's own queries
//! (the AVX2 node test where the CPU has it, one traversal state reused per worker; before
//! 2026-12-05, the baseline node test and a fresh state per ray). The last line,
//! `bvh-bench: key=value …`, is for scripts (`scripts/bench/bvh-scale.sh`,
//! `scripts/bench/rays-vs-mitsuba.sh`).
use crate::args::BenchArgs;
use eyeadapt_sequencer::Failure;
use eyeadapt_tracer::{
    Accel, BvhBuildParams, InputTri, ObvhsBuildInput, PacketStack, WalkStack, build_params,
    hash_key, mix64,
};
use glam::Vec3A;
use rayon::prelude::*;
use std::time::Instant;

/// The obvhs presets by the names `--bvh-preset` takes, slowest build last.
const PRESETS: [(&str, BvhBuildParams); 6] = [
    ("fastest", BvhBuildParams::fastest_build()),
    ("very_fast", BvhBuildParams::very_fast_build()),
    ("fast", BvhBuildParams::fast_build()),
    ("medium", BvhBuildParams::medium_build()),
    ("slow", BvhBuildParams::slow_build()),
    ("very_slow", BvhBuildParams::very_slow_build()),
];

/// The preset's name; `BvhBuildParams` has no `PartialEq`, so the fields are compared through
/// `Debug`.
fn preset_name(p: &BvhBuildParams) -> &'static str {
    let want = format!("{p:?}");
    PRESETS
        .iter()
        .find(|(_, q)| format!("{q:?}") == want)
        .map_or("custom", |(name, _)| name)
}

/// Terrain height: a few octaves of sines, smooth like a real scan, with detail at several scales.
fn height(x: f32, z: f32) -> f32 {
    0.15 * libm::sinf(3.1 * x + 0.7) * libm::cosf(2.3 * z)
        + 0.05 * libm::sinf(11.0 * x + 5.0 * z)
        + 0.02 * libm::cosf(37.0 * x - 23.0 * z)
}

/// `triangles` triangles of a kx×kz grid of quads over [-1, 1]², displaced by [`height`]:
/// triangles of similar size with real spatial locality, as a scanned or tessellated model has
/// (not a random triangle soup, which no scene looks like).
fn terrain(triangles: u32) -> Vec<InputTri> {
    let quads = (triangles as usize).div_ceil(2).max(1);
    let kx = ((quads as f64).sqrt().round() as usize).max(1);
    let kz = quads.div_ceil(kx);
    let p = |i: usize, j: usize| {
        let x = -1.0 + 2.0 * i as f32 / kx as f32;
        let z = -1.0 + 2.0 * j as f32 / kz as f32;
        Vec3A::new(x, height(x, z), z)
    };
    let mut out = Vec::with_capacity(2 * kx * kz);
    for j in 0..kz {
        for i in 0..kx {
            let (a, b, c, d) = (p(i, j), p(i + 1, j), p(i + 1, j + 1), p(i, j + 1));
            for v in [[a, c, b], [a, d, c]] {
                out.push(InputTri {
                    v,
                    instance: 0,
                    prim: out.len() as u32,
                });
            }
        }
    }
    out.truncate(triangles as usize); // the last row may be partial
    out
}

/// Peak resident set (VmHWM) of this process, in bytes.
fn peak_rss() -> Option<u64> {
    let s = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = s.lines().find(|l| l.starts_with("VmHWM:"))?;
    let kb: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kb * 1024)
}

/// Two numbers in [0, 1) from the high and middle bits of a hash.
fn unit2(r: u64) -> (f32, f32) {
    let s = 1.0 / (1u64 << 24) as f32;
    ((r >> 40) as f32 * s, ((r >> 16) & 0xff_ffff) as f32 * s)
}

/// A uniform direction from a hash.
fn direction(r: u64) -> Vec3A {
    let (u, v) = unit2(r);
    let z = 1.0 - 2.0 * u;
    let s = (1.0 - z * z).max(0.0).sqrt();
    let phi = std::f32::consts::TAU * v;
    Vec3A::new(s * libm::cosf(phi), z, s * libm::sinf(phi))
}

/// Seconds for `f` and what it returned.
fn timed<T>(f: impl FnOnce() -> T) -> (f64, T) {
    let t = Instant::now();
    let r = f();
    (t.elapsed().as_secs_f64(), r)
}

/// Ray throughput of one ray set: rays per second and the share that hit (or were unoccluded).
struct RaySet {
    rays: u64,
    seconds: f64,
    count: usize,
}

impl RaySet {
    fn mrays(&self) -> f64 {
        self.rays as f64 / self.seconds / 1e6
    }
    fn percent(&self) -> f64 {
        100.0 * self.count as f64 / self.rays as f64
    }
}

const RAYS: u64 = 1 << 20;

/// The ray set made by `ray(i)` for i in 0..RAYS (origin, direction), made before the clock
/// starts, so that only the queries are timed (as Mitsuba's, `rays-vs-mitsuba.sh`, are).
fn make_rays(ray: impl Fn(u64) -> (Vec3A, Vec3A) + Sync + Send) -> Vec<(Vec3A, Vec3A)> {
    (0..RAYS).into_par_iter().map(ray).collect()
}

/// Times `hits(state, ray)` over `rays` in parallel, each worker reusing one traversal state
/// as the renderer does, and counts the rays it reports as hits.
fn ray_set(
    rays: &[(Vec3A, Vec3A)],
    hits: impl Fn(&mut WalkStack, (Vec3A, Vec3A)) -> bool + Sync,
) -> RaySet {
    let (seconds, count) = timed(|| {
        rays.par_iter()
            .with_min_len(1024)
            .map_init(WalkStack::default, |state, &r| hits(state, r))
            .filter(|&hit| hit)
            .count()
    });
    RaySet {
        rays: rays.len() as u64,
        seconds,
        count,
    }
}

/// Times the packet walk over `rays` eight at a time (eight neighbours of a row, as a pixel's
/// samples are in a render), each worker reusing one stack, and counts the hits.
fn packet_set(accel: &Accel, rays: &[(Vec3A, Vec3A)]) -> RaySet {
    let (seconds, count) = timed(|| {
        rays.par_chunks(8)
            .with_min_len(128)
            .map_init(PacketStack::default, |stack, group| {
                let (mut o, mut d) = ([Vec3A::ZERO; 8], [Vec3A::Z; 8]);
                for (l, &(a, b)) in group.iter().enumerate() {
                    (o[l], d[l]) = (a, b);
                }
                let active = (1u32 << group.len()) - 1;
                let hits = accel.intersect8_reusing(stack, o, d, active);
                hits.iter().filter(|h| h.is_some()).count()
            })
            .sum::<usize>()
    });
    RaySet {
        rays: rays.len() as u64,
        seconds,
        count,
    }
}

/// The ray sets, each 2^20 rays, the same on every run and thread count: primary rays one by
/// one and in packets of eight, inside rays, shadow rays.
fn trace_rays(accel: &Accel, n: u32) -> [RaySet; 4] {
    const SIDE: u64 = 1 << 10;
    let key = hash_key(&[0xB7B, n as u64]);
    let (lo, hi) = (accel.bounds_min, accel.bounds_max);
    let closest = |state: &mut WalkStack, (o, d): (Vec3A, Vec3A)| {
        accel
            .intersect_reusing(state, o, d, f32::INFINITY)
            .is_some()
    };

    // Primary-like: a 1024² pinhole camera outside the mesh, above and in front, looking at
    // its centre, in row order like a renderer's scanlines (coherent rays).
    let eye = Vec3A::new(0.0, 1.4, 2.4);
    let fwd = (Vec3A::ZERO - eye).normalize();
    let right = fwd.cross(Vec3A::Y).normalize();
    let up = right.cross(fwd);
    let half = libm::tanf(15.0f32.to_radians()); // a 30° field of view: the mesh fills most of it
    let rays = make_rays(|i| {
        let px = ((i % SIDE) as f32 + 0.5) / SIDE as f32 * 2.0 - 1.0;
        let py = 1.0 - ((i / SIDE) as f32 + 0.5) / SIDE as f32 * 2.0;
        (
            eye,
            (fwd + right * (px * half) + up * (py * half)).normalize(),
        )
    });
    let primary = ray_set(&rays, closest);
    let packets = packet_set(accel, &rays);

    // Inside: uniform origins in the mesh's bounds, uniform directions, like the bounces of a
    // path tracer (incoherent rays).
    let rays = make_rays(|i| {
        let r = mix64(key ^ i);
        let (u, v) = unit2(r);
        let w = unit2(mix64(r ^ 1)).0;
        (
            lo + (hi - lo) * Vec3A::new(u, v, w),
            direction(mix64(r ^ 2)),
        )
    });
    let inside = ray_set(&rays, closest);

    // Shadow: segments of length 0.5 from points a little above the terrain, in uniform
    // directions (next-event estimation's visibility test).
    let rays = make_rays(|i| {
        let r = mix64(key ^ (i + RAYS));
        let (u, v) = unit2(r);
        let (x, z) = (u * 2.0 - 1.0, v * 2.0 - 1.0);
        (
            Vec3A::new(x, height(x, z) + 0.02, z),
            direction(mix64(r ^ 3)),
        )
    });
    let shadow = ray_set(&rays, |state, (o, d)| {
        accel.unoccluded_reusing(state, o, d, 0.5)
    });
    [primary, packets, inside, shadow]
}

/// The timed builds: the renderer's and obvhs's alone, median and fastest, and the peak RSS
/// after the first build.
struct Builds {
    accel: Accel,
    times: Vec<f64>,
    obvhs_times: Vec<f64>,
    rss_end: Option<u64>,
}

fn build_runs(
    mesh: &[InputTri],
    obvhs_input: &ObvhsBuildInput,
    params: BvhBuildParams,
    runs: u32,
) -> Builds {
    // Small meshes build in microseconds: repeat them within a timed run so the clock resolves
    // them (about 100k triangles' worth per run); one build per run from 100k triangles up.
    let reps = 100_000usize.div_ceil(mesh.len()).clamp(1, 10_000);
    let mut times = Vec::new();
    let mut obvhs_times = Vec::new();
    let mut accel = None;
    let mut rss_end = None;
    for run in 0..runs.max(1) {
        drop(accel.take()); // the previous structure is not part of this build's peak
        let (s, built) = timed(|| {
            let mut built = Accel::build_with(mesh, params);
            for _ in 1..reps {
                built = Accel::build_with(mesh, params);
            }
            built
        });
        let s = s / reps as f64;
        if run == 0 {
            // Later builds can raise the peak a little through heap fragmentation (the
            // dropped structure's pages), which a renderer building once never sees.
            rss_end = peak_rss();
        }
        // obvhs's own CWBVH build of the same triangles, as a peer: it shares the PLOC build
        // and reinsertion with `Accel::build_with` and collapses them its own way.
        let (o, _) = timed(|| {
            for _ in 0..reps {
                obvhs_input.build(params);
            }
        });
        let o = o / reps as f64;
        println!("build {}: {s:.6} s; obvhs's CWBVH build {o:.6} s", run + 1);
        times.push(s);
        obvhs_times.push(o);
        accel = Some(built);
    }
    times.sort_by(f64::total_cmp);
    obvhs_times.sort_by(f64::total_cmp);
    Builds {
        accel: accel.expect("at least one run"),
        times,
        obvhs_times,
        rss_end,
    }
}

pub fn run(a: BenchArgs) -> Result<(), Failure> {
    let n = a.bvh_triangles.unwrap_or(1_000_000);
    let rss_start = peak_rss();
    let mesh = terrain(n);
    // For timing obvhs's own build; made before the baseline so it does not count as the build's.
    let obvhs_input = ObvhsBuildInput::new(&mesh);
    let rss_mesh = peak_rss();
    let params = match a.bvh_preset.as_deref() {
        Some(name) => PRESETS
            .iter()
            .find(|(p, _)| *p == name)
            .map(|(_, p)| *p)
            .ok_or_else(|| Failure::Input(format!("unknown BVH preset {name}")))?,
        None => build_params(mesh.len()),
    };
    let preset = preset_name(&params);
    let policy = if a.bvh_preset.is_some() {
        "--bvh-preset"
    } else {
        "the renderer's choice for the size"
    };
    let Builds {
        accel,
        times,
        obvhs_times,
        rss_end,
    } = build_runs(&mesh, &obvhs_input, params, a.runs);
    let build = times[times.len() / 2];
    let build_min = times[0];
    let obvhs = obvhs_times[obvhs_times.len() / 2];
    let tris = accel.triangle_count();
    let per_m = 1e6 / tris as f64;
    let threads = rayon::current_num_threads();
    let [primary, packets, inside, shadow] = trace_rays(&accel, n);
    let closest_mrays =
        (primary.rays + inside.rays) as f64 / (primary.seconds + inside.seconds) / 1e6;

    let mib = |b: f64| b / (1024.0 * 1024.0);
    let mem = accel.memory_bytes() as f64;
    println!(
        "BVH of {tris} triangles ({threads} threads, obvhs {preset}_build by {policy}): build \
         median {build:.6} s of {} (fastest {build_min:.6} s) = {:.2} M triangles/s; obvhs's \
         CWBVH build {obvhs:.6} s",
        times.len(),
        tris as f64 / build / 1e6
    );
    println!(
        "structure {:.1} MiB = {:.0} bytes = {:.1} MiB per million triangles (BVH nodes, \
         triangles in BVH order, shading data)",
        mib(mem),
        mem * per_m,
        mib(mem * per_m)
    );
    let (mut rss_peak, mut rss_build) = (f64::NAN, f64::NAN);
    if let (Some(s), Some(m), Some(e)) = (rss_start, rss_mesh, rss_end) {
        (rss_peak, rss_build) = (e as f64, e.saturating_sub(m) as f64);
        println!(
            "peak RSS after the first build {:.1} MiB: input mesh (and its copy for obvhs's build) +{:.1} MiB, build +{:.1} MiB = {:.1} MiB per million \
             triangles",
            mib(rss_peak),
            mib(m.saturating_sub(s) as f64),
            mib(rss_build),
            mib(rss_build * per_m)
        );
    }
    println!(
        "rays (2^20 each): primary {:.2} M rays/s ({:.1} % hit), in packets of eight {:.2} M \
         rays/s ({:.1} % hit), inside {:.2} M rays/s ({:.1} % hit), both closest-hit sets \
         {closest_mrays:.2} M rays/s; shadow {:.2} M rays/s ({:.1} % unoccluded)",
        primary.mrays(),
        primary.percent(),
        packets.mrays(),
        packets.percent(),
        inside.mrays(),
        inside.percent(),
        shadow.mrays(),
        shadow.percent()
    );
    println!(
        "bvh-bench: triangles={tris} threads={threads} preset={preset} runs={} build_s={build:.6} \
         build_min_s={build_min:.6} obvhs_s={obvhs:.6} mtris_per_s={:.3} memory_bytes_per_mtri={:.0} peak_rss_bytes={rss_peak:.0} \
         build_rss_bytes_per_mtri={:.0} primary_mrays_per_s={:.3} inside_mrays_per_s={:.3} \
         closest_mrays_per_s={closest_mrays:.3} shadow_mrays_per_s={:.3} primary_percent={:.2} \
         inside_percent={:.2} shadow_percent={:.2} packet_mrays_per_s={:.3} packet_percent={:.2}",
        times.len(),
        tris as f64 / build / 1e6,
        mem * per_m,
        rss_build * per_m,
        primary.mrays(),
        inside.mrays(),
        shadow.mrays(),
        primary.percent(),
        inside.percent(),
        shadow.percent(),
        packets.mrays(),
        packets.percent()
    );
    Ok(())
}
