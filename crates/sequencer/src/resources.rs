//! Memory check before a render starts: a request whose framebuffers and BVH cannot fit in
//! this machine's memory fails at once with an estimate, instead of aborting on an allocation
//! (or being OOM-killed) hours into a job.
//!
//! The estimate is the peak of one frame in flight:
//!
//! - [`BYTES_PER_PIXEL`](crate::resources::BYTES_PER_PIXEL) per pixel: the film's f64 accumulators (144 B) live together with the
//!   frame's f32 beauty and AOVs (72 B); writing the EXR copies the 18 channels again, and an
//!   adapted EXR clones the frame. Measured: peak RSS of `eyeadapt render` grows by 217 B per
//!   pixel from 1024² to 2048² (230 MB → 898 MB, also with every estimator, and the same for
//!   a one-frame `sequence`).
//! - [`BYTES_PER_TRIANGLE`](crate::resources::BYTES_PER_TRIANGLE) per triangle: the scene's mesh, the BVH input, the obvhs build
//!   (its binary BVH, collapsed to eight-wide nodes), the BVH-ordered triangles and the
//!   per-slot shading data. Measured: 454 B per triangle from 0.33 M to 2.6 M triangles
//!   (147 MB → 1.14 GB), with obvhs's CWBVH; the tracer's own collapse since peaks lower
//!   (a 1M-triangle render 437.5 → 421.0 MB), so the figure stays an upper bound.
//!
//! The limit is the least of: physical memory (`MemTotal` from `/proc/meminfo`); the memory
//! limit of this process's cgroup and of every cgroup above it (v2 `memory.max`, v1
//! `memory.limit_in_bytes`: a Slurm or container limit); and the address space still free
//! under `ulimit -v` (`RLIMIT_AS` from `/proc/self/limits`, less the `VmSize` already mapped).
//! Swap is not counted: a path tracer paging to swap does not finish. A request above the
//! limit can never run here, whatever else the machine does: [`Failure::Input`] (exit 2). A
//! request within the limit but above `MemAvailable` (memory in use by other processes right
//! now) is [`Failure::Transient`] (exit 75): a retry, later or on another node, can succeed.
//! Where `/proc/meminfo` cannot be read (not Linux) nothing is checked.
use crate::error::Failure;
use std::path::{Path, PathBuf};

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
    /// The lowest cgroup memory limit of this process's cgroup and its ancestors, if any.
    pub cgroup_limit: Option<u64>,
    /// `ulimit -v` (the soft `RLIMIT_AS`) and the address space already mapped (`VmSize`),
    /// when there is such a limit.
    pub address_space: Option<(u64, u64)>,
}

impl Memory {
    /// Reads `/proc/meminfo`, the cgroup limits and `RLIMIT_AS`; `None` where there is no
    /// `/proc/meminfo`.
    pub fn current() -> Option<Memory> {
        let text = std::fs::read_to_string("/proc/meminfo").ok()?;
        let (total, available) = parse_meminfo(&text)?;
        let cgroups = std::fs::read_to_string("/proc/self/cgroup").unwrap_or_default();
        Some(Memory {
            total,
            available,
            cgroup_limit: cgroup_limit(Path::new("/sys/fs/cgroup"), &cgroups),
            address_space: address_space(),
        })
    }

    /// The most a render may use: physical memory, the cgroup limit or the free address
    /// space, whichever is lowest.
    pub fn limit(&self) -> u64 {
        let mut limit = self.cgroup_limit.map_or(self.total, |c| c.min(self.total));
        if let Some((max, used)) = self.address_space {
            limit = limit.min(max.saturating_sub(used));
        }
        limit
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

/// The lowest memory limit over this process's cgroups (`cgroups`: the text of
/// `/proc/self/cgroup`) and all their ancestors, under the cgroup mount `root`: v2's
/// `memory.max` (the `0::` line; the unified tree at `root` or `root/unified`) and v1's
/// `memory.limit_in_bytes` (the line whose controllers include `memory`, under `root/memory`).
/// `max` and unreadable files are no limit.
pub fn cgroup_limit(root: &Path, cgroups: &str) -> Option<u64> {
    let mut found: Option<u64> = None;
    let mut look = |base: PathBuf, rel: &str, file: &str| {
        let mut dir = base.join(rel.trim_start_matches('/'));
        loop {
            if let Some(v) = std::fs::read_to_string(dir.join(file))
                .ok()
                .and_then(|t| t.trim().parse::<u64>().ok())
            {
                found = Some(found.map_or(v, |f| f.min(v)));
            }
            if dir == base || !dir.pop() || !dir.starts_with(&base) {
                break;
            }
        }
    };
    for line in cgroups.lines() {
        let mut parts = line.splitn(3, ':');
        let (Some(_), Some(controllers), Some(rel)) = (parts.next(), parts.next(), parts.next())
        else {
            continue;
        };
        if controllers.is_empty() {
            look(root.to_path_buf(), rel, "memory.max");
            look(root.join("unified"), rel, "memory.max");
        } else if controllers.split(',').any(|c| c == "memory") {
            look(root.join("memory"), rel, "memory.limit_in_bytes");
        }
    }
    found
}

/// (`ulimit -v` in bytes, `VmSize` in bytes) when the address space is limited.
fn address_space() -> Option<(u64, u64)> {
    let limits = std::fs::read_to_string("/proc/self/limits").ok()?;
    let max = parse_address_limit(&limits)?;
    let status = std::fs::read_to_string("/proc/self/status").unwrap_or_default();
    let used = status
        .lines()
        .find_map(|l| l.strip_prefix("VmSize:"))
        .and_then(|v| v.split_whitespace().next()?.parse::<u64>().ok())
        .map_or(0, |kib| kib.saturating_mul(1024));
    Some((max, used))
}

/// The soft limit of `Max address space` in the text of `/proc/self/limits` (bytes), if it is
/// not `unlimited`.
pub fn parse_address_limit(limits: &str) -> Option<u64> {
    let line = limits
        .lines()
        .find(|l| l.starts_with("Max address space"))?;
    line["Max address space".len()..]
        .split_whitespace()
        .next()?
        .parse()
        .ok()
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
        let source = match (mem.cgroup_limit, mem.address_space) {
            (_, Some((max, used))) if max.saturating_sub(used) == limit => format!(
                "the address-space limit (ulimit -v) is {} of which {} is mapped already \
                 (MemTotal {} in /proc/meminfo)",
                gib(max),
                gib(used),
                gib(mem.total)
            ),
            (Some(c), _) if c < mem.total => format!(
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
            address_space: None,
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
    fn ulimit_v_is_a_limit_less_what_is_mapped_already() {
        let limits = "Limit                     Soft Limit           Hard Limit           Units     \n\
                      Max stack size            8388608              unlimited            bytes     \n\
                      Max address space         1610612736           unlimited            bytes     \n";
        assert_eq!(parse_address_limit(limits), Some(1_610_612_736));
        assert_eq!(
            parse_address_limit(
                "Max address space         unlimited            unlimited            bytes"
            ),
            None
        );
        let m = Memory {
            address_space: Some((1_610_612_736, 100 << 20)),
            ..mem()
        };
        assert_eq!(m.limit(), 1_610_612_736 - (100 << 20));
        let f = check_estimate("the render", &estimate(4096, 4096, 0), &m).unwrap_err();
        assert_eq!(f.exit_code(), 2);
        assert!(f.to_string().contains("ulimit -v"), "{f}");
    }

    #[test]
    fn cgroup_limits_of_v1_and_v2_and_their_ancestors_count() {
        let d = tempfile::tempdir().unwrap();
        let root = d.path();
        let put = |rel: &str, v: &str| {
            let p = root.join(rel);
            std::fs::create_dir_all(p.parent().unwrap()).unwrap();
            std::fs::write(p, v).unwrap();
        };
        // v2: the job's own cgroup has no limit, its parent (a Slurm job step's) has one.
        put("slurm/job_7/memory.max", "2147483648\n");
        put("slurm/job_7/step_0/memory.max", "max\n");
        assert_eq!(
            cgroup_limit(root, "0::/slurm/job_7/step_0\n"),
            Some(2 << 30)
        );
        // v1 (this machine's hybrid layout): the memory controller's tree.
        put("memory/box/memory.limit_in_bytes", "1073741824\n");
        let hybrid = "4:memory:/box\n1:cpu,cpuacct:/\n0::/\n";
        assert_eq!(cgroup_limit(root, hybrid), Some(1 << 30));
        assert_eq!(cgroup_limit(root, "0::/elsewhere\n"), None);
    }

    #[test]
    fn saturates_instead_of_overflowing() {
        let e = estimate(u32::MAX, u32::MAX, usize::MAX);
        assert_eq!(e.total, u64::MAX);
    }
}
