//! What this process uses and may still use, read from the operating system in one place:
//! its CPU time (getrusage), its resident memory now and at its peak (/proc/self/status),
//! and the memory it may still allocate (the machine's available memory, its rlimits, its
//! cgroup's limit). Linux; a value that cannot be read is reported as unknown, never as an
//! error. The operators' memory checks (ops/common/resources.rs), the per-operator times
//! of a run (interp.rs) and the bench (bench/measure.rs) read it here.

/// Seconds of a `timeval` (getrusage, wait4).
pub fn seconds(t: libc::timeval) -> f64 {
    t.tv_sec as f64 + 1e-6 * t.tv_usec as f64
}

/// User + system CPU seconds of this process so far (all threads).
pub fn self_cpu() -> f64 {
    // SAFETY: getrusage writes one rusage struct, which we own.
    let mut ru: libc::rusage = unsafe { std::mem::zeroed() };
    let rc = unsafe { libc::getrusage(libc::RUSAGE_SELF, &mut ru) };
    if rc != 0 {
        return f64::NAN;
    }
    seconds(ru.ru_utime) + seconds(ru.ru_stime)
}

/// A `Name:   123 kB` field of the text of `/proc/self/status`, in kB.
fn status_kib(status: &str, field: &str) -> Option<u64> {
    let line = status.lines().find(|l| l.starts_with(field))?;
    line.split_whitespace().nth(1)?.parse().ok()
}

/// A field of this process's `/proc/self/status`, in kB.
fn status_kb(key: &str) -> Option<u64> {
    status_kib(&std::fs::read_to_string("/proc/self/status").ok()?, key)
}

/// Current resident set (kB).
pub fn rss_kb() -> u64 {
    status_kb("VmRSS:").unwrap_or(0)
}

/// Peak resident set since the start or the last `reset_peak` (kB).
pub fn peak_kb() -> u64 {
    status_kb("VmHWM:").unwrap_or(0)
}

/// Reset the peak resident set to the current one (Linux: "5" > /proc/self/clear_refs).
pub fn reset_peak() -> bool {
    std::fs::write("/proc/self/clear_refs", "5").is_ok()
}

/// Memory this process may still use, in bytes: `MemAvailable` of `/proc/meminfo`
/// (`MemTotal` on kernels without it); `None` where the file cannot be read.
pub fn available_memory() -> Option<f64> {
    let text = std::fs::read_to_string("/proc/meminfo").ok()?;
    let field = |name: &str| -> Option<f64> {
        let line = text.lines().find(|l| l.starts_with(name))?;
        let kib: f64 = line.split_whitespace().nth(1)?.parse().ok()?;
        Some(kib * 1024.0)
    };
    field("MemAvailable:").or_else(|| field("MemTotal:"))
}

/// The tightest bound on what this process may still allocate, in bytes, and where it
/// comes from ("on this machine", "under the address-space limit (ulimit -v)"...); `None`
/// when nothing can be read.
pub fn memory_limit() -> Option<(f64, String)> {
    let status = std::fs::read_to_string("/proc/self/status").unwrap_or_default();
    let mut limits: Vec<(f64, String)> = Vec::new();
    if let Some(m) = available_memory() {
        limits.push((m, "on this machine".to_string()));
    }
    // The process's own size counts against its rlimits (VmSize for RLIMIT_AS, VmData
    // for RLIMIT_DATA); a limit of the kernel's "infinity" is no limit.
    for (resource, field, name) in [
        (
            libc::RLIMIT_AS,
            "VmSize:",
            "under this process's address-space limit (ulimit -v)",
        ),
        (
            libc::RLIMIT_DATA,
            "VmData:",
            "under this process's data-size limit (ulimit -d)",
        ),
    ] {
        if let Some(max) = rlimit(resource) {
            let used = status_kib(&status, field).map_or(0.0, |k| k as f64) * 1024.0;
            limits.push(((max - used).max(0.0), name.to_string()));
        }
    }
    if let Some(room) = cgroup_room() {
        limits.push((
            room,
            "under the memory limit of this process's cgroup".to_string(),
        ));
    }
    limits.into_iter().min_by(|a, b| a.0.total_cmp(&b.0))
}

/// The soft limit of `resource`, `None` when unlimited or unreadable.
fn rlimit(resource: libc::__rlimit_resource_t) -> Option<f64> {
    let mut r = libc::rlimit {
        rlim_cur: 0,
        rlim_max: 0,
    };
    // SAFETY: getrlimit writes the limit into the struct we own.
    let ok = unsafe { libc::getrlimit(resource, &mut r) } == 0;
    (ok && r.rlim_cur != libc::RLIM_INFINITY).then_some(r.rlim_cur as f64)
}

/// What the cgroup (v2 `memory.max`, or v1 `memory.limit_in_bytes`) of this process leaves:
/// its limit minus its current use, the least over the cgroup and its ancestors.
fn cgroup_room() -> Option<f64> {
    let membership = std::fs::read_to_string("/proc/self/cgroup").ok()?;
    let mut best: Option<f64> = None;
    let mut consider = |dir: &std::path::Path, max: &str, current: &str| {
        let mut d = Some(dir);
        while let Some(here) = d {
            let read = |f: &str| std::fs::read_to_string(here.join(f)).ok();
            if let (Some(m), Some(c)) = (read(max), read(current)) {
                if let Some(room) = cgroup_headroom(&m, &c) {
                    best = Some(best.map_or(room, |b: f64| b.min(room)));
                }
            }
            d = here.parent().filter(|p| p.starts_with("/sys/fs/cgroup"));
        }
    };
    for line in membership.lines() {
        let mut parts = line.splitn(3, ':');
        let (Some(_), Some(controllers), Some(rel)) = (parts.next(), parts.next(), parts.next())
        else {
            continue;
        };
        let rel = rel.trim_start_matches('/');
        if controllers.is_empty() {
            let dir = std::path::Path::new("/sys/fs/cgroup").join(rel);
            consider(&dir, "memory.max", "memory.current");
        } else if controllers.split(',').any(|c| c == "memory") {
            let dir = std::path::Path::new("/sys/fs/cgroup/memory").join(rel);
            consider(&dir, "memory.limit_in_bytes", "memory.usage_in_bytes");
        }
    }
    best
}

/// Room left under a cgroup memory limit from the texts of its limit and current-use files;
/// `None` for no limit (`max`, or v1's near-2⁶³ "unlimited").
pub fn cgroup_headroom(max: &str, current: &str) -> Option<f64> {
    let max = max.trim();
    if max == "max" {
        return None;
    }
    let max: f64 = max.parse().ok()?;
    if max >= 1.0e18 {
        return None;
    }
    let current: f64 = current.trim().parse().unwrap_or(0.0);
    Some((max - current).max(0.0))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cgroup_limits_read_as_the_kernel_writes_them() {
        assert_eq!(cgroup_headroom("max\n", "12345\n"), None);
        assert_eq!(cgroup_headroom("9223372036854771712\n", "1\n"), None);
        assert_eq!(
            cgroup_headroom("4294967296\n", "1073741824\n"),
            Some(3.0 * 1073741824.0)
        );
        // Over the limit (reclaim pending): no room, not a negative size.
        assert_eq!(cgroup_headroom("100\n", "200\n"), Some(0.0));
        assert_eq!(cgroup_headroom("garbage", "1"), None);
    }

    #[test]
    fn the_limit_is_never_above_the_machine() {
        let (limit, _) = memory_limit().unwrap();
        if let Some(machine) = available_memory() {
            assert!(limit <= machine);
        }
    }

    #[test]
    fn this_process_has_cpu_time_and_resident_memory() {
        let t0 = self_cpu();
        let mut x = 0.0f64;
        for i in 0..2_000_000 {
            x += (i as f64).sqrt();
        }
        assert!(x > 0.0);
        assert!(self_cpu() >= t0 && t0.is_finite());
        assert!(rss_kb() > 0 && peak_kb() >= rss_kb());
        assert_eq!(status_kib("VmRSS:\t  1234 kB\n", "VmRSS:"), Some(1234));
    }
}
