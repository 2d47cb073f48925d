//! `eyeadapt bench --bvh-triangles`: the machine-readable line that scripts/bench/bvh-scale.sh
//! parses, for the renderer's preset and an explicit one.
use std::process::Command;

/// Runs the BVH bench on one thread and returns its `key=value` pairs.
fn bench(extra: &[&str]) -> Vec<(String, String)> {
    bench_with(extra, "auto")
}

/// [`bench`] with `EYEADAPT_SIMD` set to `simd`.
fn bench_with(extra: &[&str], simd: &str) -> Vec<(String, String)> {
    let out = Command::new(env!("CARGO_BIN_EXE_eyeadapt"))
        .env("EYEADAPT_SIMD", simd)
        .args([
            "--threads",
            "1",
            "bench",
            "--bvh-triangles",
            "3001",
            "--runs",
            "1",
        ])
        .args(extra)
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "{stdout}{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let line = stdout
        .lines()
        .find_map(|l| l.strip_prefix("bvh-bench: "))
        .unwrap_or_else(|| panic!("no bvh-bench line in:\n{stdout}"));
    line.split(' ')
        .map(|kv| {
            let (k, v) = kv.split_once('=').unwrap();
            (k.to_string(), v.to_string())
        })
        .collect()
}

fn get<'a>(kv: &'a [(String, String)], key: &str) -> &'a str {
    &kv.iter().find(|(k, _)| k == key).unwrap().1
}

#[test]
fn bvh_bench_reports_every_figure() {
    let kv = bench(&[]);
    assert_eq!(
        get(&kv, "triangles"),
        "3001",
        "exactly the triangles asked for"
    );
    assert_eq!(get(&kv, "threads"), "1");
    assert_eq!(
        get(&kv, "preset"),
        "medium",
        "the renderer's choice at 3k triangles"
    );
    for key in [
        "build_s",
        "build_min_s",
        "obvhs_s",
        "mtris_per_s",
        "memory_bytes_per_mtri",
        "peak_rss_bytes",
        "build_rss_bytes_per_mtri",
        "primary_mrays_per_s",
        "inside_mrays_per_s",
        "closest_mrays_per_s",
        "shadow_mrays_per_s",
        "packet_mrays_per_s",
    ] {
        let v: f64 = get(&kv, key).parse().unwrap();
        assert!(v.is_finite() && v > 0.0, "{key}={v}");
    }
    // The ray sets' answers (rays-vs-mitsuba.sh compares them with Mitsuba's): some rays of
    // each set hit and some miss, and the baseline node test gives the same answers as the
    // wide one the bench uses where the CPU has it.
    let baseline = bench_with(&[], "baseline");
    for key in [
        "primary_percent",
        "inside_percent",
        "shadow_percent",
        "packet_percent",
    ] {
        let v: f64 = get(&kv, key).parse().unwrap();
        assert!(v > 5.0 && v < 95.0, "{key}={v}");
        assert_eq!(get(&kv, key), get(&baseline, key), "{key}");
    }
    // The primary rays in packets of eight hit what they hit one by one (only rays at a
    // shared edge may report the other triangle; none turns a hit into a miss here).
    assert_eq!(get(&kv, "packet_percent"), get(&kv, "primary_percent"));
}

#[test]
fn bvh_bench_takes_an_explicit_preset() {
    assert_eq!(
        get(&bench(&["--bvh-preset", "fastest"]), "preset"),
        "fastest"
    );
}
