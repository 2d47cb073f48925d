//! The same bits on any x86-64 node: glibc picks FMA and AVX2 variants of `exp`, `sin`, `acos`, …
//! at run time on CPUs that have them, and a farm mixes old and new nodes. A run with those
//! variants switched off (`GLIBC_TUNABLES=glibc.cpu.hwcaps=-AVX2,-FMA`, what an x86-64 node
//! without them would pick) must write the same frames and the same adaptation colours.
//! eyeadapt's own code calls none of them (`clippy.toml`); this guards against a dependency that
//! would. The baseline run also sets `EYEADAPT_SIMD=baseline`, so it traverses with the SSE2
//! node tests where the other run uses the AVX2 ones (`crates/tracer/src/isa.rs`). Other glibc
//! *versions* are `scripts/glibc-determinism.sh`'s check.
mod common;

use std::path::{Path, PathBuf};
use std::process::Command;

const NO_FMA: &str = "glibc.cpu.hwcaps=-AVX2_Usable,-FMA_Usable,-AVX2,-FMA";

fn eyeadapt(no_fma: bool) -> Command {
    let mut c = Command::new(env!("CARGO_BIN_EXE_eyeadapt"));
    if no_fma {
        c.env("GLIBC_TUNABLES", NO_FMA)
            .env("EYEADAPT_SIMD", "baseline");
    } else {
        c.env_remove("EYEADAPT_SIMD");
    }
    c
}

/// Whether this CPU has FMA (otherwise both runs pick the same variants and the test shows
/// nothing about them).
fn cpu_has_fma() -> bool {
    std::fs::read_to_string("/proc/cpuinfo").is_ok_and(|s| {
        s.lines()
            .any(|l| l.starts_with("flags") && l.split_whitespace().any(|f| f == "fma"))
    })
}

/// The dynamic loader's platform name and active hwcaps levels (x86-64-v2/v3/v4), as the
/// tunable leaves them. Either shows the tunable working: on some CPUs (an AMD EPYC with
/// AVX-512, say) the platform is plain "x86_64" either way and only the levels change.
fn loader_platform(no_fma: bool) -> Option<String> {
    let mut c = Command::new("/lib64/ld-linux-x86-64.so.2");
    c.arg("--list-diagnostics");
    if no_fma {
        c.env("GLIBC_TUNABLES", NO_FMA);
    }
    let out = c.output().ok()?;
    let text = String::from_utf8_lossy(&out.stdout);
    let field = |key: &str| {
        text.lines()
            .find_map(|l| l.strip_prefix(key).map(str::to_owned))
    };
    let platform = field("dl_platform=")?;
    let levels = field("dl_hwcaps_subdirs_active=").unwrap_or_default();
    Some(format!("{platform} hwcaps {levels}"))
}

fn render(scene: &str, out: &Path, no_fma: bool) {
    let st = eyeadapt(no_fma)
        .args([
            "render", scene, "--width", "40", "--height", "24", "--spp", "4",
        ])
        .arg("--out")
        .arg(out)
        .output()
        .unwrap();
    assert!(st.status.success(), "{scene}: {st:?}");
}

fn sequence(out: &Path, no_fma: bool) {
    let st = eyeadapt(no_fma)
        .args([
            "sequence", "--frames", "0-1", "--width", "32", "--height", "18",
        ])
        .args([
            "--spp",
            "2",
            "--eye-samples",
            "512",
            "--no-report",
            "--no-progress-bar",
        ])
        .arg("--out")
        .arg(out)
        .output()
        .unwrap();
    assert!(st.status.success(), "{st:?}");
}

#[test]
fn frames_and_adaptation_colours_do_not_depend_on_the_cpus_fma() {
    if !cfg!(all(target_arch = "x86_64", target_os = "linux")) {
        return;
    }
    let has_fma = cpu_has_fma();
    let platforms = (loader_platform(false), loader_platform(true));
    if has_fma && platforms.0.is_some() {
        // The tunable is honoured (else the comparison below would compare a run with itself).
        assert_ne!(platforms.0, platforms.1);
    } else if has_fma {
        eprintln!("the loader has no --list-diagnostics: cannot check that the tunable applies");
    } else {
        eprintln!("this CPU has no FMA: both runs use glibc's baseline variants");
    }
    let tmp = std::env::temp_dir().join(format!("eyeadapt-cpu-features-{}", std::process::id()));
    let repo = Path::new(env!("CARGO_MANIFEST_DIR"));
    let glass = repo.join("scenes/mitsuba-glass/glass-on-table.xml");
    let scenes = [
        "builtin:interior",
        "builtin:three-rooms",
        glass.to_str().unwrap(),
    ];
    let run = |no_fma: bool| -> Vec<(String, Vec<u8>)> {
        let dir = tmp.join(if no_fma { "baseline" } else { "native" });
        let mut files = Vec::new();
        for (k, scene) in scenes.iter().enumerate() {
            let out = dir.join(format!("render-{k}"));
            render(scene, &out, no_fma);
            files.push((
                format!("{scene} raw.exr"),
                std::fs::read(out.join("raw.exr")).unwrap(),
            ));
        }
        let out: PathBuf = dir.join("sequence");
        sequence(&out, no_fma);
        for f in ["adaptation.csv", "frames/raw/frame_000001.exr"] {
            files.push((format!("sequence {f}"), std::fs::read(out.join(f)).unwrap()));
        }
        files
    };
    let native = run(false);
    let baseline = run(true);
    std::fs::remove_dir_all(&tmp).ok();
    for ((name, a), (_, b)) in native.iter().zip(&baseline) {
        assert!(
            a == b,
            "{name}: different bits with glibc's FMA variants and eyeadapt's AVX2 node tests switched off"
        );
    }
}

/// [`common::tiny_render`] with `EYEADAPT_SIMD=simd`.
fn tiny_render(simd: &str, out: &Path) -> std::process::Output {
    common::tiny_render(out)
        .env("EYEADAPT_SIMD", simd)
        .output()
        .unwrap()
}

#[test]
fn an_unknown_eyeadapt_simd_value_is_refused_before_anything_is_written() {
    let out = std::env::temp_dir().join(format!("eyeadapt-simd-refused-{}", std::process::id()));
    let st = tiny_render("avx512", &out);
    let stderr = String::from_utf8_lossy(&st.stderr);
    assert_eq!(st.status.code(), Some(2), "{stderr}");
    assert!(
        stderr.contains("EYEADAPT_SIMD") && stderr.contains("\"avx512\""),
        "{stderr}"
    );
    assert!(!out.exists(), "{} was created", out.display());
    // The accepted values run.
    for v in ["auto", "baseline"] {
        let st = tiny_render(v, &out);
        assert!(st.status.success(), "{v}: {st:?}");
    }
    std::fs::remove_dir_all(&out).ok();
}
