//! Memory check before a render starts: a request whose framebuffers and BVH cannot fit in
//! this machine's memory fails at once with an estimate, instead of aborting on an allocation
//! (or being OOM-killed) hours into a job.
//!
//! The estimate is the peak of one frame in flight:
//!
//! - [`BYTES_PER_PIXEL`] per pixel: the film's f64 accumulators (144 B) live together with the
//!   frame's f32 beauty and AOVs (72 B); writing the EXR copies the 18 channels again, and an
//!   adapted EXR clones the frame. Measured: peak RSS of `eyeadapt render` grows by 217 B per
//!   pixel from 1024² to 2048² (230 MB → 898 MB, also with every estimator, and the same for
//!   a one-frame `sequence`).
//! - [`BYTES_PER_TRIANGLE`] per triangle: the scene's mesh, the BVH input, the obvhs build
//!   (BVH2 then CWBVH), the BVH-ordered triangles and the per-slot shading data. Measured:
//!   454 B per triangle from 0.33 M to 2.6 M triangles (147 MB → 1.14 GB).
//!
//! The limit is physical memory: `MemTotal` from `/proc/meminfo`, lowered by the cgroup v2
//! `memory.max` of this process (a Slurm or container limit) when there is one. Swap is not
//! counted: a path tracer paging to swap does not finish. A request above the limit can never
//! run here, whatever else the machine does: [`Failure::Input`] (exit 2). A request within the
//! limit but above `MemAvailable` (memory in use by other processes right now) is
//! [`Failure::Transient`] (exit 75): a retry, later or on another node, can succeed. Where
//! `/proc/meminfo` cannot be read (not Linux) nothing is checked.
use crate::error::Failure;

/// Peak bytes per pixel of one frame in flight (accumulators, AOVs, one output copy).
pub const BYTES_PER_PIXEL: u64 = 256;
/// Peak bytes per triangle while the BVH is built and afterwards.
pub const BYTES_PER_TRIANGLE: u64 = 512;
/// Everything else: code, scene tables, thread stacks, the sample tables.
pub const BASE_BYTES: u64 = 64 << 20;

/// What a render needs, by part.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Estimate {
    pub width: u32,
    pub height: u32,
    pub triangles: u64,
    pub framebuffers: u64,
    pub bvh: u64,
    pub total: u64,
}

/// The estimate for a `width`×`height` frame of a scene with `triangles` triangles.
pub fn estimate(width: u32, height: u32, triangles: usize) -> Estimate {
    let pixels = width as u64 * height as u64;
    let framebuffers = pixels.saturating_mul(BYTES_PER_PIXEL);
    let bvh = (triangles as u64).saturating_mul(BYTES_PER_TRIANGLE);
    Estimate {
        width,
        height,
        triangles: triangles as u64,
        framebuffers,
        bvh,
        total: framebuffers.saturating_add(bvh).saturating_add(BASE_BYTES),
    }
}

/// This machine's memory, in bytes.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Memory {
    /// `MemTotal`.
    pub total: u64,
    /// `MemAvailable`.
    pub available: u64,
    /// The cgroup v2 `memory.max` of this process, when it is not `max`.
    pub cgroup_limit: Option<u64>,
}

impl Memory {
    /// Reads `/proc/meminfo` and this process's cgroup limit; `None` where there is no
    /// `/proc/meminfo`.
    pub fn current() -> Option<Memory> {
        let text = std::fs::read_to_string("/proc/meminfo").ok()?;
        let (total, available) = parse_meminfo(&text)?;
        Some(Memory {
            total,
            available,
            cgroup_limit: cgroup_limit(),
        })
    }

    /// The most a render may use: physical memory or the cgroup limit, whichever is lower.
    pub fn limit(&self) -> u64 {
        self.cgroup_limit.map_or(self.total, |c| c.min(self.total))
    }
}

/// (`MemTotal`, `MemAvailable`) in bytes from the text of `/proc/meminfo` (`MemFree` stands in
/// for `MemAvailable` on kernels before 3.14).
pub fn parse_meminfo(text: &str) -> Option<(u64, u64)> {
    let field = |name: &str| -> Option<u64> {
        let line = text.lines().find(|l| l.starts_with(name))?;
        let mut words = line[name.len()..].split_whitespace();
        let kib: u64 = words.next()?.parse().ok()?;
        Some(kib.saturating_mul(1024))
    };
    let total = field("MemTotal:")?;
    let available = field("MemAvailable:").or_else(|| field("MemFree:"))?;
    Some((total, available))
}

/// `memory.max` of this process's cgroup (v2), if set.
fn cgroup_limit() -> Option<u64> {
    let cg = std::fs::read_to_string("/proc/self/cgroup").ok()?;
    let rel = cg.lines().find_map(|l| l.strip_prefix("0::"))?;
    let p = std::path::Path::new("/sys/fs/cgroup")
        .join(rel.trim_start_matches('/'))
        .join("memory.max");
    std::fs::read_to_string(p).ok()?.trim().parse().ok()
}

fn gib(bytes: u64) -> String {
    format!("{:.1} GiB", bytes as f64 / (1u64 << 30) as f64)
}

/// Refuses `e` on `mem` (see the module documentation for the exit codes); `what` names the
/// request in the message.
pub fn check_estimate(what: &str, e: &Estimate, mem: &Memory) -> Result<(), Failure> {
    let detail = || {
        format!(
            "{what} needs about {} ({}x{} framebuffers with AOVs: {}; BVH of {} triangles: {})",
            gib(e.total),
            e.width,
            e.height,
            gib(e.framebuffers),
            e.triangles,
            gib(e.bvh)
        )
    };
    let limit = mem.limit();
    if e.total > limit {
        let source = match mem.cgroup_limit {
            Some(c) if c < mem.total => format!(
                "the cgroup memory limit is {} (MemTotal {} in /proc/meminfo)",
                gib(c),
                gib(mem.total)
            ),
            _ => format!(
                "this machine has {} (MemTotal in /proc/meminfo)",
                gib(mem.total)
            ),
        };
        return Err(Failure::Input(format!(
            "{} but {source}, MemAvailable {}: lower the resolution or split the geometry",
            detail(),
            gib(mem.available)
        )));
    }
    if e.total > mem.available {
        return Err(Failure::Transient(format!(
            "{} but only {} is available now (MemAvailable in /proc/meminfo; MemTotal {})",
            detail(),
            gib(mem.available),
            gib(mem.total)
        )));
    }
    Ok(())
}

/// Checks a render of `width`×`height` over `triangles` triangles against this machine.
pub fn check_render(what: &str, width: u32, height: u32, triangles: usize) -> Result<(), Failure> {
    match Memory::current() {
        Some(mem) => check_estimate(what, &estimate(width, height, triangles), &mem),
        None => Ok(()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const MEMINFO: &str = "MemTotal:       24576000 kB\nMemFree:         1000000 kB\nMemAvailable:   20000000 kB\nBuffers:           10 kB\n";

    fn mem() -> Memory {
        let (total, available) = parse_meminfo(MEMINFO).unwrap();
        Memory {
            total,
            available,
            cgroup_limit: None,
        }
    }

    #[test]
    fn meminfo_is_read_in_bytes() {
        assert_eq!(
            parse_meminfo(MEMINFO),
            Some((24_576_000 * 1024, 20_000_000 * 1024))
        );
        assert_eq!(
            parse_meminfo("MemTotal: 100 kB\nMemFree: 7 kB\n"),
            Some((102_400, 7 * 1024))
        );
        assert_eq!(parse_meminfo("nothing"), None);
    }

    #[test]
    fn huge_frames_are_impossible_and_say_why() {
        let e = estimate(32768, 32768, 1000);
        assert!(e.framebuffers >= 32768 * 32768 * 72, "at least the AOVs");
        let f = check_estimate("the render", &e, &mem()).unwrap_err();
        assert_eq!(f.exit_code(), 2);
        let m = f.to_string();
        for part in [
            "32768x32768",
            "256.0 GiB",
            "MemTotal",
            "23.4 GiB",
            "MemAvailable",
        ] {
            assert!(m.contains(part), "{part} missing from {m}");
        }
    }

    #[test]
    fn busy_memory_is_transient_and_small_jobs_pass() {
        let e = estimate(8192, 8192, 10_000_000); // 16 GiB + 4.8 GiB
        let busy = Memory {
            available: 4 << 30,
            ..mem()
        };
        let f = check_estimate("the job", &e, &busy).unwrap_err();
        assert_eq!(f.exit_code(), 75, "{f}");
        assert!(check_estimate("the job", &estimate(320, 180, 100_000), &busy).is_ok());
    }

    #[test]
    fn a_cgroup_limit_below_physical_memory_wins() {
        let m = Memory {
            cgroup_limit: Some(2 << 30),
            ..mem()
        };
        let f = check_estimate("the job", &estimate(4096, 4096, 0), &m).unwrap_err();
        assert_eq!(f.exit_code(), 2);
        assert!(
            f.to_string().contains("cgroup memory limit is 2.0 GiB"),
            "{f}"
        );
    }

    #[test]
    fn saturates_instead_of_overflowing() {
        let e = estimate(u32::MAX, u32::MAX, usize::MAX);
        assert_eq!(e.total, u64::MAX);
    }
}
