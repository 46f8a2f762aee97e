//! CPU time and peak memory of child processes (wait4), medians and fitted growth
//! exponents; this process's own are read by `crate::process`.

use crate::error::{Error, ErrorKind, Result};
use crate::process::seconds;
pub use crate::process::{peak_kb, reset_peak, rss_kb, self_cpu};
use std::path::Path;
use std::process::{Command, Stdio};

fn io(e: impl std::fmt::Display) -> Error {
    Error::new(ErrorKind::Io, format!("bench: {e}"))
}

/// A finished child process: exit code, CPU seconds (user + system), peak RSS (kB), output.
pub struct ChildRun {
    pub code: i32,
    pub cpu: f64,
    pub peak_kb: u64,
    pub stdout: String,
}

/// Run `program args…` in `dir`, stdout captured, stderr discarded.
pub fn run_child(program: &Path, args: &[&str], dir: &Path) -> Result<ChildRun> {
    let mut child = Command::new(program)
        .args(args)
        .current_dir(dir)
        .stdout(Stdio::piped())
        .stderr(Stdio::null())
        .spawn()
        .map_err(|e| io(format!("cannot start {}: {e}", program.display())))?;
    let mut stdout = String::new();
    if let Some(mut out) = child.stdout.take() {
        use std::io::Read;
        out.read_to_string(&mut stdout).map_err(io)?;
    }
    let pid = child.id() as libc::pid_t;
    let mut status = 0;
    // SAFETY: wait4 on our own child, writing into structs we own; std's Child is not
    // waited on afterwards (dropping it does not reap).
    let mut ru: libc::rusage = unsafe { std::mem::zeroed() };
    let rc = unsafe { libc::wait4(pid, &mut status, 0, &mut ru) };
    if rc != pid {
        return Err(io(format!("wait4 failed for {}", program.display())));
    }
    let code = if libc::WIFEXITED(status) {
        libc::WEXITSTATUS(status)
    } else {
        -1
    };
    Ok(ChildRun {
        code,
        cpu: seconds(ru.ru_utime) + seconds(ru.ru_stime),
        peak_kb: ru.ru_maxrss as u64,
        stdout,
    })
}

pub fn median(v: &mut [f64]) -> f64 {
    if v.is_empty() {
        return f64::NAN;
    }
    v.sort_by(|a, b| a.total_cmp(b));
    let n = v.len();
    if n % 2 == 1 {
        v[n / 2]
    } else {
        0.5 * (v[n / 2 - 1] + v[n / 2])
    }
}

/// Least-squares slope of log y against log x (the growth exponent).
pub fn exponent(points: &[(f64, f64)]) -> f64 {
    let pts: Vec<(f64, f64)> = points
        .iter()
        .filter(|(x, y)| *x > 0.0 && *y > 0.0 && y.is_finite())
        .map(|(x, y)| (x.ln(), y.ln()))
        .collect();
    let n = pts.len() as f64;
    if pts.len() < 2 {
        return f64::NAN;
    }
    let (mx, my) = (
        pts.iter().map(|p| p.0).sum::<f64>() / n,
        pts.iter().map(|p| p.1).sum::<f64>() / n,
    );
    let sxy: f64 = pts.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum();
    let sxx: f64 = pts.iter().map(|p| (p.0 - mx).powi(2)).sum();
    sxy / sxx
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn exponent_of_a_power_law_and_median() {
        let pts: Vec<(f64, f64)> = [10.0, 100.0, 1000.0]
            .iter()
            .map(|&x: &f64| (x, 3.0 * x.powf(1.5)))
            .collect();
        assert!((exponent(&pts) - 1.5).abs() < 1e-12);
        assert_eq!(median(&mut [3.0, 1.0, 2.0]), 2.0);
        assert_eq!(median(&mut [4.0, 1.0, 2.0, 3.0]), 2.5);
        assert!(self_cpu() >= 0.0);
    }
}
