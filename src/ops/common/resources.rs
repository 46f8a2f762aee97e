//! Whether a call fits: the operators compute an estimate of the memory and the work a call
//! needs from its keywords and the model size (`nnm::budget`) before anything is allocated,
//! and this module compares it with the memory this process may still use: the machine's
//! available memory, and the limits the process actually has (`RLIMIT_AS`, `RLIMIT_DATA`,
//! its cgroup's memory limit), whichever leaves least (`crate::process::memory_limit`).

use crate::error::{Error, Result};
use crate::ops::OpContext;
use crate::process::memory_limit;

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
}
