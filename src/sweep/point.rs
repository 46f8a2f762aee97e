//! Running one point: `aster-nl run` as a separate process in the point's directory, its
//! output to files there, its outcome to `point.json`. The local pool and the Slurm tasks
//! both come here, so a point's files are the same wherever it ran.

use super::layout::{
    self, hostname, now, text_hash, Layout, Manifest, Outcome, PointStatus, Running, POINT_LOG,
    POINT_RUNNING, POINT_STATUS,
};
use crate::error::Result;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

/// What the run printed on stderr goes here (stdout goes to [`POINT_LOG`]).
pub const POINT_ERR: &str = "run.err";

/// The files of point `index` of the manifest.
pub struct PointFiles {
    pub dir: PathBuf,
    pub comm: PathBuf,
    pub db: PathBuf,
}

impl PointFiles {
    pub fn of(layout: &Layout, manifest: &Manifest, index: usize) -> PointFiles {
        let dir = layout.point_dir(&manifest.points[index].id);
        let comm = dir.join(&manifest.comm_name);
        let db = comm.with_extension("db");
        PointFiles { dir, comm, db }
    }
}

/// Run point `index` (its `.comm` already written) with the binary `exe`, and record the
/// outcome. `ran_on` says where (`local`, `slurm 12_3`). Errors are only those of the
/// sweep's own files; whatever the run does is an outcome.
pub fn run_point(
    layout: &Layout,
    manifest: &Manifest,
    index: usize,
    exe: &Path,
    ran_on: &str,
) -> Result<PointStatus> {
    let point = &manifest.points[index];
    let files = PointFiles::of(layout, manifest, index);
    let comm_text = std::fs::read_to_string(&files.comm)
        .map_err(|e| layout::io_err(format!("cannot read {}: {e}", files.comm.display())))?;
    layout::write_json_atomic(
        &files.dir.join(POINT_RUNNING),
        &Running {
            pid: std::process::id(),
            host: hostname(),
            started_at: now(),
            ran_on: ran_on.to_string(),
        },
    )?;
    // What an earlier run of this point left: our own outputs, replaced.
    for stale in [
        files.dir.join(POINT_STATUS),
        files.dir.join(POINT_LOG),
        files.dir.join(POINT_ERR),
        files.db.clone(),
        with_suffix(&files.db, "-journal"),
        with_suffix(&files.db, "-wal"),
        with_suffix(&files.db, "-shm"),
    ] {
        remove_if_exists(&stale)?;
    }
    let stdout = create(&files.dir.join(POINT_LOG))?;
    let stderr = create(&files.dir.join(POINT_ERR))?;
    let mut cmd = Command::new(exe);
    cmd.arg("run")
        .arg(&files.comm)
        .arg("--db")
        .arg(&files.db)
        .current_dir(&files.dir)
        .env("NO_COLOR", "1")
        .stdin(Stdio::null())
        .stdout(stdout)
        .stderr(stderr);
    for (n, p) in &manifest.units {
        let mut spec = std::ffi::OsString::from(format!("{n}="));
        spec.push(p.as_os_str());
        cmd.arg("--unit").arg(spec);
    }
    let start = Instant::now();
    let (exit_code, error) = match cmd.spawn() {
        Err(e) => (None, format!("cannot start {}: {e}", exe.display())),
        Ok(mut child) => {
            let limit = manifest.timeout.map(Duration::from_secs_f64);
            match wait(&mut child, limit) {
                Ok(Some(status)) => match status.code() {
                    Some(c) => (Some(c), String::new()),
                    None => (None, describe_signal(&status)),
                },
                Ok(None) => {
                    let _ = child.kill();
                    let _ = child.wait();
                    (
                        None,
                        format!(
                            "stopped after {} s (run.timeout of the study)",
                            limit.map_or(0.0, |l| l.as_secs_f64())
                        ),
                    )
                }
                Err(e) => (None, format!("lost the run: {e}")),
            }
        }
    };
    let seconds = start.elapsed().as_secs_f64();
    let outcome = match exit_code {
        Some(0) => Outcome::Ok,
        Some(1) => Outcome::Nook,
        _ => Outcome::Failed,
    };
    let error = match (outcome, error.is_empty()) {
        (Outcome::Failed, true) => {
            let text = std::fs::read_to_string(files.dir.join(POINT_ERR)).unwrap_or_default();
            first_error_line(&text).unwrap_or_else(|| {
                format!("aster-nl run exited with code {}", exit_code.unwrap_or(-1))
            })
        }
        (Outcome::Nook, _) => {
            let text = std::fs::read_to_string(files.dir.join(POINT_ERR)).unwrap_or_default();
            text.lines()
                .rev()
                .find(|l| l.contains("NOOK"))
                .unwrap_or("a TEST_* check was NOOK")
                .trim()
                .to_string()
        }
        _ => error,
    };
    let status = PointStatus {
        id: point.id.clone(),
        params: manifest.params.clone(),
        values: point.values.clone(),
        outcome,
        exit_code,
        error,
        seconds,
        db: files
            .db
            .file_name()
            .map(|n| n.to_string_lossy().into_owned())
            .unwrap_or_default(),
        comm_hash: text_hash(&comm_text),
        finished_at: now(),
        ran_on: ran_on.to_string(),
    };
    layout::write_json_atomic(&files.dir.join(POINT_STATUS), &status)?;
    remove_if_exists(&files.dir.join(POINT_RUNNING))?;
    Ok(status)
}

/// Record that a point ended without running to its end (a Slurm task that vanished).
pub fn record_lost(
    layout: &Layout,
    manifest: &Manifest,
    index: usize,
    error: String,
    ran_on: &str,
) -> Result<PointStatus> {
    let point = &manifest.points[index];
    let files = PointFiles::of(layout, manifest, index);
    let comm_text = std::fs::read_to_string(&files.comm).unwrap_or_default();
    let status = PointStatus {
        id: point.id.clone(),
        params: manifest.params.clone(),
        values: point.values.clone(),
        outcome: Outcome::Failed,
        exit_code: None,
        error,
        seconds: 0.0,
        db: files
            .db
            .file_name()
            .map(|n| n.to_string_lossy().into_owned())
            .unwrap_or_default(),
        comm_hash: text_hash(&comm_text),
        finished_at: now(),
        ran_on: ran_on.to_string(),
    };
    layout::write_json_atomic(&files.dir.join(POINT_STATUS), &status)?;
    remove_if_exists(&files.dir.join(POINT_RUNNING))?;
    Ok(status)
}

/// Wait for the child, at most `limit`: `Ok(None)` when the limit passed.
fn wait(
    child: &mut std::process::Child,
    limit: Option<Duration>,
) -> std::io::Result<Option<std::process::ExitStatus>> {
    let Some(limit) = limit else {
        return child.wait().map(Some);
    };
    let start = Instant::now();
    // Short runs are seen quickly; long ones are polled ten times a second.
    let mut pause = Duration::from_millis(2);
    loop {
        if let Some(s) = child.try_wait()? {
            return Ok(Some(s));
        }
        if start.elapsed() >= limit {
            return Ok(None);
        }
        std::thread::sleep(pause);
        pause = (pause * 2).min(Duration::from_millis(100));
    }
}

#[cfg(unix)]
fn describe_signal(status: &std::process::ExitStatus) -> String {
    use std::os::unix::process::ExitStatusExt;
    match status.signal() {
        Some(9) => "killed (signal 9: out of memory, or stopped by someone)".into(),
        Some(s) => format!("killed by signal {s}"),
        None => "ended without an exit code".into(),
    }
}

#[cfg(not(unix))]
fn describe_signal(_status: &std::process::ExitStatus) -> String {
    "ended without an exit code".into()
}

/// The error of a failed run, on one line: the message of aster-nl's report (its first
/// line, without the report's decoration) and the place it names.
pub fn first_error_line(stderr: &str) -> Option<String> {
    let mut lines = stderr.lines().map(str::trim).filter(|l| !l.is_empty());
    let head = lines.next()?;
    let head = head.trim_start_matches(['×', '!', ' ']).trim();
    let head = head.strip_prefix("Error:").unwrap_or(head).trim();
    let place = stderr.lines().find_map(|l| {
        let l = l.trim();
        if let Some(i) = l.find("╭─[") {
            return l[i + "╭─[".len()..].strip_suffix(']').map(str::to_string);
        }
        l.strip_prefix("-->").map(|p| p.trim().to_string())
    });
    // Only the file name of the place: the point's directory is in the summary already.
    let place = place.map(|p| match p.rsplit_once('/') {
        Some((_, tail)) => tail.to_string(),
        None => p,
    });
    Some(match place {
        Some(p) => format!("{head} ({p})"),
        None => head.to_string(),
    })
}

fn with_suffix(p: &Path, suffix: &str) -> PathBuf {
    let mut s = p.as_os_str().to_os_string();
    s.push(suffix);
    PathBuf::from(s)
}

fn remove_if_exists(p: &Path) -> Result<()> {
    match std::fs::remove_file(p) {
        Ok(()) => Ok(()),
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => Ok(()),
        Err(e) => Err(layout::io_err(format!(
            "cannot remove {}: {e}",
            p.display()
        ))),
    }
}

fn create(p: &Path) -> Result<std::fs::File> {
    std::fs::File::create(p)
        .map_err(|e| layout::io_err(format!("cannot create {}: {e}", p.display())))
}
