//! The Slurm scheduler: the points to run go to one job array (`sbatch --array`), one task
//! per point, each task running `aster-nl sweep-task OUT LIST` which runs the point of its
//! line of LIST exactly as the local pool does. Slurm does the scheduling; the sweep only
//! submits, watches `squeue` and reads the points' `point.json`.

use super::layout::{self, Layout, Manifest};
use super::study::SlurmSettings;
use crate::error::{Error, ErrorKind, Result};
use std::path::{Path, PathBuf};
use std::process::Command;

/// One submitted array: its job id and the points of its tasks, task `i` running
/// `points[i]`.
#[derive(Clone, Debug)]
pub struct Submitted {
    pub job: String,
    pub points: Vec<usize>,
}

/// Write the job scripts and task lists of `pending` and submit them, in arrays of at most
/// `settings.array_chunk` tasks.
pub fn submit(
    layout: &Layout,
    manifest: &Manifest,
    pending: &[usize],
    settings: &SlurmSettings,
    exe: &Path,
    job_name: &str,
) -> Result<Vec<Submitted>> {
    let root = absolute(&layout.root)?;
    let slurm_dir = root.join(layout::SLURM);
    let stamp = format!("{:.0}", layout::now() * 1000.0);
    let mut out = Vec::new();
    for (c, chunk) in pending.chunks(settings.array_chunk.max(1)).enumerate() {
        let list = slurm_dir.join(format!("tasks-{stamp}-{c}.txt"));
        let mut text = String::new();
        for &i in chunk {
            text.push_str(&manifest.points[i].id);
            text.push('\n');
        }
        layout::write_atomic(&list, text.as_bytes())?;
        let script = slurm_dir.join(format!("job-{stamp}-{c}.sh"));
        let body = format!(
            "#!/bin/sh\n\
             # Written by aster-nl sweep: task i runs the point on line i+1 of the list.\n\
             # Submitted with: sbatch --job-name=... --output=... --array=0-(n-1) this-file\n\
             exec {exe} sweep-task {root} {list}\n",
            exe = sh_quote(exe),
            root = sh_quote(&root),
            list = sh_quote(&list),
        );
        layout::write_atomic(&script, body.as_bytes())?;
        let mut array = format!("--array=0-{}", chunk.len() - 1);
        if let Some(m) = settings.max_running {
            array.push_str(&format!("%{m}"));
        }
        let mut cmd = Command::new("sbatch");
        // Options on the command line, not as #SBATCH lines: no quoting rules to meet.
        let mut log = std::ffi::OsString::from("--output=");
        log.push(slurm_dir.join("%A_%a.out"));
        cmd.arg("--parsable")
            .arg(array)
            .arg(format!("--job-name={job_name}"))
            .arg(log);
        if let Some(p) = &settings.partition {
            cmd.arg(format!("--partition={p}"));
        }
        if let Some(t) = &settings.time {
            cmd.arg(format!("--time={t}"));
        }
        cmd.args(&settings.sbatch_args).arg(&script);
        let output = cmd.output().map_err(|e| {
            Error::new(ErrorKind::Io, format!("cannot run sbatch: {e}")).hint(
                "the Slurm scheduler needs sbatch and squeue on the PATH (docs/sweeps.md); \
                 `scheduler = \"local\"` runs the points on this machine",
            )
        })?;
        if !output.status.success() {
            let msg = String::from_utf8_lossy(&output.stderr).trim().to_string();
            return Err(Error::new(
                ErrorKind::Io,
                format!("sbatch refused the job array {}: {msg}", script.display()),
            )
            .hint("check [slurm] of the study (partition, time, sbatch_args)"));
        }
        // `--parsable` prints `jobid` or `jobid;cluster`.
        let stdout = String::from_utf8_lossy(&output.stdout);
        let job = stdout
            .trim()
            .split(';')
            .next()
            .filter(|j| !j.is_empty() && j.chars().all(|c| c.is_ascii_digit()))
            .ok_or_else(|| {
                Error::new(
                    ErrorKind::Io,
                    format!("sbatch printed '{}', not a job id", stdout.trim()),
                )
            })?
            .to_string();
        out.push(Submitted {
            job,
            points: chunk.to_vec(),
        });
    }
    Ok(out)
}

/// What `squeue` says of a set of jobs.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct QueueState {
    /// Tasks waiting to start.
    pub pending: usize,
    /// Tasks running (or completing).
    pub running: usize,
}

impl QueueState {
    pub fn is_empty(&self) -> bool {
        self.pending == 0 && self.running == 0
    }
}

/// Ask `squeue` about `jobs`. A job Slurm no longer knows has ended.
pub fn queue_state(jobs: &[String]) -> Result<QueueState> {
    if jobs.is_empty() {
        return Ok(QueueState::default());
    }
    // One line per task (-r), its state in short form.
    let output = Command::new("squeue")
        .args(["-h", "-r", "-o", "%t", "-j", &jobs.join(",")])
        .output()
        .map_err(|e| Error::new(ErrorKind::Io, format!("cannot run squeue: {e}")))?;
    let stderr = String::from_utf8_lossy(&output.stderr);
    if !output.status.success() {
        if stderr.contains("Invalid job id") {
            return Ok(QueueState::default());
        }
        return Err(Error::new(
            ErrorKind::Io,
            format!("squeue failed: {}", stderr.trim()),
        ));
    }
    let mut s = QueueState::default();
    for line in String::from_utf8_lossy(&output.stdout).lines() {
        match line.trim() {
            "PD" | "CF" | "RQ" | "RF" | "RH" | "S" => s.pending += 1,
            "" => {}
            _ => s.running += 1,
        }
    }
    Ok(s)
}

/// The per-task log Slurm writes (`#SBATCH --output`).
pub fn task_log(layout: &Layout, job: &str, task: usize) -> PathBuf {
    layout.slurm_dir().join(format!("{job}_{task}.out"))
}

/// Single-quoted for sh.
fn sh_quote(p: &Path) -> String {
    let s = p.to_string_lossy();
    format!("'{}'", s.replace('\'', "'\\''"))
}

fn absolute(p: &Path) -> Result<PathBuf> {
    std::path::absolute(p).map_err(|e| Error::new(ErrorKind::Io, format!("{}: {e}", p.display())))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn paths_are_quoted_for_sh() {
        assert_eq!(sh_quote(Path::new("/a b/c")), "'/a b/c'");
        assert_eq!(sh_quote(Path::new("/it's")), "'/it'\\''s'");
    }
}
