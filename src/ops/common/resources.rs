//! Whether a call fits: the operators compute an estimate of the memory and the work a call
//! needs from its keywords and the model size (`nnm::budget`) before anything is allocated,
//! and this module compares it with the memory this process may still use: the machine's
//! available memory, and the limits the process actually has (`RLIMIT_AS`, `RLIMIT_DATA`,
//! its cgroup's memory limit), whichever leaves least (`memory_limit`).

use crate::error::{Error, Result};
use crate::ops::OpContext;

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
            let used = status_kib(&status, field).unwrap_or(0.0) * 1024.0;
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

/// A `Name:   123 kB` field of `/proc/self/status`, in kB.
fn status_kib(status: &str, field: &str) -> Option<f64> {
    let line = status.lines().find(|l| l.starts_with(field))?;
    line.split_whitespace().nth(1)?.parse().ok()
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

/// Used when the machine's memory cannot be read: refuse only what no machine has.
const UNKNOWN_MACHINE_BYTES: f64 = 1024.0 * 1024.0 * 1024.0 * 1024.0;

/// Work (model operations, see `nnm::budget`) above which a call is announced as very long:
/// sdnd122a (6.7e9) runs in about a second, so this is several minutes.
pub const LONG_WORK_FLOPS: f64 = 1.0e12;

/// Human-readable size: "12.3 GB".
pub fn bytes_text(b: f64) -> String {
    if !b.is_finite() {
        return "more than any machine has".to_string();
    }
    let units = ["B", "kB", "MB", "GB", "TB", "PB", "EB"];
    let mut v = b;
    let mut i = 0;
    while v >= 1000.0 && i + 1 < units.len() {
        v /= 1000.0;
        i += 1;
    }
    if i + 1 == units.len() && v >= 1000.0 {
        return format!("{b:.1e} B");
    }
    format!("{v:.1} {}", units[i])
}

/// Refuse a call whose estimated peak memory `bytes` exceeds what the machine has.
/// `keyword` names the keyword(s) that set the size, `what` the allocation.
pub fn check_memory(keyword: &str, what: &str, bytes: f64) -> Result<()> {
    let (limit, source) = match memory_limit() {
        Some(l) => l,
        None => (
            UNKNOWN_MACHINE_BYTES,
            "(this machine's memory is unknown: no /proc/meminfo)".to_string(),
        ),
    };
    if bytes.is_finite() && bytes <= limit {
        return Ok(());
    }
    Err(Error::validation(format!(
        "{what} would need about {} of memory; {} available {source}",
        bytes_text(bytes),
        bytes_text(limit)
    ))
    .keyword(keyword.to_string())
    .hint("reduce the size keyword(s) named here"))
}

/// Warn (an alarm the user may silence) about a call whose estimated work is very long.
pub fn warn_long_work(
    ctx: &mut OpContext<'_>,
    keyword: &str,
    what: &str,
    flops: f64,
) -> Result<()> {
    if flops > LONG_WORK_FLOPS {
        ctx.alarm(
            "RESSOURCES_1",
            &format!(
                "{keyword}: {what} needs about {flops:.1e} floating-point operations: expect a very long run"
            ),
        )?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sizes_read_as_people_write_them() {
        assert_eq!(bytes_text(999.0), "999.0 B");
        assert_eq!(bytes_text(3.2e11), "320.0 GB");
        assert_eq!(bytes_text(f64::INFINITY), "more than any machine has");
    }

    #[test]
    fn what_cannot_fit_is_refused_naming_the_keyword() {
        let e = check_memory("RESOLUTION/NB_HARM_NONL", "the tangent", 1.0e30).unwrap_err();
        assert_eq!(e.keyword.as_deref(), Some("RESOLUTION/NB_HARM_NONL"));
        assert!(e.message.contains("memory"), "{e}");
        check_memory("X", "a vector", 1.0e3).unwrap();
    }

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
}
