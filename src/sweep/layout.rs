//! The sweep's output directory, the only place a sweep writes:
//!
//! ```text
//! OUT/sweep.json               the manifest: parameters, points, Slurm jobs submitted
//! OUT/sweep.lock               held while a sweep runs or submits (pid, host)
//! OUT/points/<id>/<stem>.comm  the point's command file (the template with its values)
//! OUT/points/<id>/<stem>.db    the point's own SQLite study (one writer per file)
//! OUT/points/<id>/run.log      what `aster-nl run` printed (stdout, then stderr)
//! OUT/points/<id>/point.json   the point's values and outcome (written last, atomically)
//! OUT/points/<id>/running.json written when the point starts, removed when it ends
//! OUT/slurm/                   job scripts, task lists and Slurm's per-task logs
//! OUT/sweep.db                 the merged database
//! OUT/curves.png, curves.svg   the family of frequency–energy curves
//! ```
//!
//! A directory that exists, is not empty and has no `sweep.json` is not a sweep's: it is
//! refused, so a sweep never writes over files that are not its own.

use super::study::Point;
use super::value::ParamValue;
use crate::error::{Error, ErrorKind, Result};
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};
use std::time::{SystemTime, UNIX_EPOCH};

pub const MANIFEST: &str = "sweep.json";
pub const LOCK: &str = "sweep.lock";
pub const POINTS: &str = "points";
pub const SLURM: &str = "slurm";
pub const MERGED: &str = "sweep.db";
pub const CURVES: &str = "curves";
pub const POINT_STATUS: &str = "point.json";
pub const POINT_RUNNING: &str = "running.json";
pub const POINT_LOG: &str = "run.log";

/// The manifest: what the sweep is, so that a task (on a compute node) and a later rerun
/// know the points without the study file.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
pub struct Manifest {
    /// Format of this file.
    pub version: u32,
    pub study: PathBuf,
    pub template: PathBuf,
    /// File name of each point's command file (the template's), e.g. `wall.comm`.
    pub comm_name: String,
    pub params: Vec<String>,
    pub points: Vec<ManifestPoint>,
    /// Units mapped for every point.
    pub units: Vec<(i64, PathBuf)>,
    /// Seconds one point may run (local pool; Slurm tasks get `--time`).
    pub timeout: Option<f64>,
    /// Slurm jobs submitted for this sweep and not yet seen finished.
    #[serde(default)]
    pub slurm_jobs: Vec<String>,
}

pub const MANIFEST_VERSION: u32 = 1;

#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
pub struct ManifestPoint {
    pub id: String,
    pub values: Vec<ParamValue>,
}

/// How a point ended.
#[derive(Clone, Copy, Debug, Serialize, Deserialize, PartialEq, Eq)]
#[serde(rename_all = "lowercase")]
pub enum Outcome {
    /// Exit 0.
    Ok,
    /// Exit 1: the run finished, a TEST_* check was NOOK; its results are kept.
    Nook,
    /// Any other end: an error stopped the run, a signal, a time-out, a task that vanished.
    Failed,
}

impl Outcome {
    pub fn name(self) -> &'static str {
        match self {
            Outcome::Ok => "ok",
            Outcome::Nook => "nook",
            Outcome::Failed => "failed",
        }
    }
}

/// `point.json`: the values and what happened. Written once the run has ended.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
pub struct PointStatus {
    pub id: String,
    pub params: Vec<String>,
    pub values: Vec<ParamValue>,
    pub outcome: Outcome,
    /// The run's exit code, if it exited.
    pub exit_code: Option<i32>,
    /// One line saying why the point failed (empty when it did not).
    pub error: String,
    pub seconds: f64,
    /// The point's database, relative to the point's directory (`<stem>.db`).
    pub db: String,
    /// Hash of the command file that ran: a rerun after a change of the template reruns.
    pub comm_hash: String,
    /// Seconds since the Unix epoch when the point ended.
    pub finished_at: f64,
    /// Where it ran: `local` or `slurm <job>_<task>`.
    pub ran_on: String,
}

/// `running.json`.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
pub struct Running {
    pub pid: u32,
    pub host: String,
    pub started_at: f64,
    pub ran_on: String,
}

/// The sweep's directory.
#[derive(Clone, Debug)]
pub struct Layout {
    pub root: PathBuf,
}

impl Layout {
    /// Open `root` as a sweep directory, creating it if needed. Refuses a directory that
    /// holds files and no manifest (not ours), and a file in its place.
    pub fn create(root: &Path) -> Result<Layout> {
        // Absolute: the points run with their own directory as working directory.
        let root = &absolute(root)?;
        if root.exists() {
            if !root.is_dir() {
                return Err(io_err(format!(
                    "the sweep's output {} exists and is not a directory",
                    root.display()
                ))
                .hint("choose another directory with --out or `out =` in the study"));
            }
            let has_manifest = root.join(MANIFEST).is_file();
            let empty = std::fs::read_dir(root)
                .map_err(|e| io_err(format!("cannot read {}: {e}", root.display())))?
                .next()
                .is_none();
            if !has_manifest && !empty {
                return Err(io_err(format!(
                    "{} is not empty and is not a sweep's directory (no {MANIFEST}): a sweep only writes into a directory of its own",
                    root.display()
                ))
                .hint("choose another directory with --out or `out =` in the study"));
            }
        }
        for d in [root.to_path_buf(), root.join(POINTS), root.join(SLURM)] {
            std::fs::create_dir_all(&d)
                .map_err(|e| io_err(format!("cannot create {}: {e}", d.display())))?;
        }
        Ok(Layout {
            root: root.to_path_buf(),
        })
    }

    /// An existing sweep directory (for tasks and `--status`).
    pub fn open(root: &Path) -> Result<Layout> {
        let root = &absolute(root)?;
        if !root.join(MANIFEST).is_file() {
            return Err(io_err(format!(
                "{} is not a sweep's directory: no {MANIFEST}",
                root.display()
            )));
        }
        Ok(Layout {
            root: root.to_path_buf(),
        })
    }

    pub fn manifest_path(&self) -> PathBuf {
        self.root.join(MANIFEST)
    }
    pub fn point_dir(&self, id: &str) -> PathBuf {
        self.root.join(POINTS).join(id)
    }
    pub fn slurm_dir(&self) -> PathBuf {
        self.root.join(SLURM)
    }
    pub fn merged(&self) -> PathBuf {
        self.root.join(MERGED)
    }
    pub fn curves(&self) -> PathBuf {
        self.root.join(CURVES)
    }

    pub fn read_manifest(&self) -> Result<Manifest> {
        let m: Manifest = read_json(&self.manifest_path())?;
        if m.version != MANIFEST_VERSION {
            return Err(io_err(format!(
                "{}: format {} is not the one this aster-nl writes ({MANIFEST_VERSION})",
                self.manifest_path().display(),
                m.version
            )));
        }
        Ok(m)
    }

    pub fn write_manifest(&self, m: &Manifest) -> Result<()> {
        write_json_atomic(&self.manifest_path(), m)
    }

    /// The outcome recorded for a point, if any (a file that cannot be read counts as
    /// none: the point runs again).
    pub fn status(&self, id: &str) -> Option<PointStatus> {
        read_json(&self.point_dir(id).join(POINT_STATUS)).ok()
    }

    pub fn running(&self, id: &str) -> Option<Running> {
        read_json(&self.point_dir(id).join(POINT_RUNNING)).ok()
    }

    /// Take the sweep's lock; a lock left by a process of this host that no longer exists is
    /// taken over. The lock is released when the guard drops.
    pub fn lock(&self) -> Result<LockGuard> {
        let path = self.root.join(LOCK);
        for _ in 0..2 {
            match std::fs::OpenOptions::new()
                .write(true)
                .create_new(true)
                .open(&path)
            {
                Ok(mut f) => {
                    use std::io::Write;
                    let me = Running {
                        pid: std::process::id(),
                        host: hostname(),
                        started_at: now(),
                        ran_on: "sweep".into(),
                    };
                    let text = serde_json::to_string(&me)
                        .map_err(|e| Error::internal(format!("lock: {e}")))?;
                    f.write_all(text.as_bytes())
                        .map_err(|e| io_err(format!("cannot write {}: {e}", path.display())))?;
                    return Ok(LockGuard { path });
                }
                Err(e) if e.kind() == std::io::ErrorKind::AlreadyExists => {
                    let holder: Option<Running> = read_json(&path).ok();
                    match holder {
                        Some(h) if h.host == hostname() && !process_alive(h.pid) => {
                            // Left by a sweep that was killed: ours to take over.
                            std::fs::remove_file(&path).map_err(|e| {
                                io_err(format!("cannot remove {}: {e}", path.display()))
                            })?;
                        }
                        Some(h) => {
                            return Err(io_err(format!(
                                "another sweep (pid {} on {}) is using {}",
                                h.pid,
                                h.host,
                                self.root.display()
                            ))
                            .hint(format!(
                                "wait for it to finish; if it is gone, remove {}",
                                path.display()
                            )))
                        }
                        None => {
                            return Err(io_err(format!(
                                "{} exists and cannot be read",
                                path.display()
                            ))
                            .hint("if no sweep is running in this directory, remove it"))
                        }
                    }
                }
                Err(e) => return Err(io_err(format!("cannot create {}: {e}", path.display()))),
            }
        }
        Err(io_err(format!("cannot take the lock {}", path.display())))
    }
}

/// Removes the lock file when dropped.
#[derive(Debug)]
pub struct LockGuard {
    path: PathBuf,
}

impl Drop for LockGuard {
    fn drop(&mut self) {
        let _ = std::fs::remove_file(&self.path);
    }
}

/// A directory name for a point: readable (`JEU=0.01,RIGI_NOR=50.0`) when its values
/// allow it, else `p-` and a hash of them. Depends only on the values, so a point keeps
/// its directory when the grid grows or shrinks around it.
pub fn point_id(params: &[String], p: &Point) -> String {
    let readable = params
        .iter()
        .zip(&p.values)
        .map(|(n, v)| format!("{n}={}", v.display()))
        .collect::<Vec<_>>()
        .join(",");
    let safe = readable
        .chars()
        .all(|c| c.is_ascii_alphanumeric() || "=,._+-".contains(c));
    if safe && readable.len() <= 120 && !readable.starts_with('.') {
        readable
    } else {
        format!("p-{:016x}", fnv1a(readable.as_bytes()))
    }
}

/// FNV-1a, 64 bits: a stable hash (Rust's `DefaultHasher` may change between releases).
pub fn fnv1a(bytes: &[u8]) -> u64 {
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    for b in bytes {
        h ^= u64::from(*b);
        h = h.wrapping_mul(0x0000_0100_0000_01b3);
    }
    h
}

pub fn text_hash(text: &str) -> String {
    format!("{:016x}", fnv1a(text.as_bytes()))
}

pub fn now() -> f64 {
    SystemTime::now()
        .duration_since(UNIX_EPOCH)
        .map_or(0.0, |d| d.as_secs_f64())
}

pub fn hostname() -> String {
    std::fs::read_to_string("/proc/sys/kernel/hostname")
        .ok()
        .map(|s| s.trim().to_string())
        .filter(|s| !s.is_empty())
        .or_else(|| std::env::var("HOSTNAME").ok())
        .unwrap_or_else(|| "localhost".into())
}

/// Whether a process of this host still exists (where /proc cannot tell, assume it does:
/// a lock is then never taken from a live sweep).
fn process_alive(pid: u32) -> bool {
    let proc_root = Path::new("/proc");
    if !proc_root.join("self").exists() {
        return true;
    }
    proc_root.join(pid.to_string()).exists()
}

fn absolute(p: &Path) -> Result<PathBuf> {
    std::path::absolute(p).map_err(|e| io_err(format!("{}: {e}", p.display())))
}

pub fn io_err(msg: String) -> Error {
    Error::new(ErrorKind::Io, msg)
}

pub fn read_json<T: serde::de::DeserializeOwned>(path: &Path) -> Result<T> {
    let text = std::fs::read_to_string(path)
        .map_err(|e| io_err(format!("cannot read {}: {e}", path.display())))?;
    serde_json::from_str(&text).map_err(|e| {
        io_err(format!(
            "{}: not a file this aster-nl wrote: {e}",
            path.display()
        ))
    })
}

/// Write through a temporary file and a rename, so a reader never sees half a file.
pub fn write_json_atomic<T: Serialize>(path: &Path, value: &T) -> Result<()> {
    let text =
        serde_json::to_string_pretty(value).map_err(|e| Error::internal(format!("json: {e}")))?;
    write_atomic(path, text.as_bytes())
}

pub fn write_atomic(path: &Path, bytes: &[u8]) -> Result<()> {
    let tmp = temp_sibling(path);
    std::fs::write(&tmp, bytes)
        .map_err(|e| io_err(format!("cannot write {}: {e}", tmp.display())))?;
    std::fs::rename(&tmp, path).map_err(|e| {
        let _ = std::fs::remove_file(&tmp);
        io_err(format!("cannot write {}: {e}", path.display()))
    })
}

/// `dir/.name.tmp-<pid>`: beside the file (a rename stays on one file system).
pub fn temp_sibling(path: &Path) -> PathBuf {
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    path.with_file_name(format!(".{name}.tmp-{}", std::process::id()))
}
