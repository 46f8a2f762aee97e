//! Parametric sweeps: one `.comm` template, many values of its top-level variables, one
//! independent `aster-nl run` per point (a separate process, its own SQLite file), run by
//! a bounded local pool or a Slurm job array, merged into one database at the end.
//!
//! - [`study`]: the study file (TOML): template, grid or list, units, scheduler, plot.
//! - [`template`]: the template's parameters and each point's command file.
//! - [`layout`]: the output directory, the manifest, the points' status files, the lock.
//! - [`point`]: running one point (both schedulers).
//! - [`local`], [`slurm`]: the two schedulers.
//! - [`merge`]: every table of every run in one SQLite file, parameters as columns.
//! - [`plot`]: the family of frequency–energy curves coloured by a parameter.
//! - [`report`]: progress lines and the summary.
//!
//! The sweep knows nothing of the engine: it writes files, starts the aster-nl binary and
//! reads SQLite. A rerun runs only the points that are missing, failed, or whose command
//! file changed.

pub mod cli;
pub mod layout;
pub mod local;
pub mod merge;
pub mod plot;
pub mod point;
pub mod report;
pub mod slurm;
pub mod study;
pub mod template;
pub mod value;

#[cfg(test)]
mod tests;

use crate::error::{Error, ErrorKind, Result};
use layout::{Layout, Manifest, ManifestPoint, Outcome, PointStatus, MANIFEST_VERSION};
use report::Progress;
use std::path::{Path, PathBuf};
use std::time::Duration;
use study::{Scheduler, Study};
use template::Template;

/// How to run a sweep (the command line's choices over the study file's).
#[derive(Clone, Debug)]
pub struct SweepOptions {
    pub study: PathBuf,
    /// Output directory instead of the study's.
    pub out: Option<PathBuf>,
    pub jobs: Option<usize>,
    pub scheduler: Option<Scheduler>,
    /// Slurm: wait for the arrays to end, then merge (else submit and return).
    pub wait: bool,
    /// Run nothing: merge and draw what the points have.
    pub merge_only: bool,
    /// The aster-nl binary that runs the points.
    pub exe: PathBuf,
    /// Seconds between two looks at Slurm's queue.
    pub poll: Duration,
}

/// One point at the end of a sweep.
#[derive(Clone, Debug, PartialEq)]
pub struct PointResult {
    pub id: String,
    pub label: String,
    /// `None`: it has not run (yet).
    pub status: Option<PointStatus>,
    /// It ran in this invocation (else it was up to date, or left alone).
    pub ran_now: bool,
    pub dir: PathBuf,
}

/// What a sweep did.
#[derive(Clone, Debug)]
pub struct SweepSummary {
    pub out: PathBuf,
    pub params: Vec<String>,
    pub points: Vec<PointResult>,
    /// Merged database and what went in, when the sweep merged.
    pub merged: Option<(PathBuf, merge::MergeReport)>,
    pub picture: Option<plot::FamilyPicture>,
    /// A note for the user about the picture (why there is none).
    pub picture_note: Option<String>,
    /// Slurm jobs submitted and not waited for.
    pub submitted: Vec<String>,
}

impl SweepSummary {
    pub fn count(&self, o: Option<Outcome>) -> usize {
        self.points
            .iter()
            .filter(|p| p.status.as_ref().map(|s| s.outcome) == o)
            .count()
    }
}

/// Prepare the directory, run what needs running, merge, draw. `log` receives the
/// progress lines.
pub fn run_sweep(opts: &SweepOptions, log: &mut dyn std::io::Write) -> Result<SweepSummary> {
    let mut study = Study::load(&opts.study)?;
    if let Some(out) = &opts.out {
        study.out = out.clone();
    }
    if let Some(s) = opts.scheduler {
        study.scheduler = s;
    }
    let template = Template::load(&study)?;
    let layout = Layout::create(&study.out)?;
    let _lock = layout.lock()?;

    let previous = layout.read_manifest().ok();
    let mut manifest = build_manifest(&study)?;
    manifest.slurm_jobs = previous.map(|m| m.slurm_jobs).unwrap_or_default();
    if !manifest.slurm_jobs.is_empty() {
        let q = slurm::queue_state(&manifest.slurm_jobs)?;
        if !q.is_empty() {
            return Err(Error::new(
                ErrorKind::Io,
                format!(
                    "Slurm job(s) {} of this sweep are still queued or running ({} waiting, {} running)",
                    manifest.slurm_jobs.join(", "),
                    q.pending,
                    q.running
                ),
            )
            .hint("`aster-nl sweep STUDY --status` shows the progress; wait for them, or scancel them"));
        }
        manifest.slurm_jobs.clear();
    }
    layout.write_manifest(&manifest)?;

    // Which points need to run: no outcome, a failure, a changed command file, or a lost
    // database. Their command files are written, their previous outcome removed.
    let mut pending = Vec::new();
    for (i, p) in manifest.points.iter().enumerate() {
        let files = point::PointFiles::of(&layout, &manifest, i);
        let text = template.render(&p.values);
        let up_to_date = layout.status(&p.id).is_some_and(|s| {
            s.outcome != Outcome::Failed
                && s.comm_hash == layout::text_hash(&text)
                && files.db.is_file()
        });
        if up_to_date || opts.merge_only {
            continue;
        }
        std::fs::create_dir_all(&files.dir)
            .map_err(|e| layout::io_err(format!("cannot create {}: {e}", files.dir.display())))?;
        if std::fs::read_to_string(&files.comm).ok().as_deref() != Some(text.as_str()) {
            layout::write_atomic(&files.comm, text.as_bytes())?;
        }
        for f in [layout::POINT_STATUS, layout::POINT_RUNNING] {
            let _ = std::fs::remove_file(files.dir.join(f));
        }
        pending.push(i);
    }

    let mut progress = Progress::new(&layout, &manifest, &pending);
    progress.header(log, &study, opts);
    let mut submitted = Vec::new();
    if !pending.is_empty() {
        match study.scheduler {
            Scheduler::Local => {
                let jobs = opts
                    .jobs
                    .or(study.jobs)
                    .unwrap_or_else(|| std::thread::available_parallelism().map_or(1, usize::from));
                local::run_pool(&layout, &manifest, &pending, jobs, &opts.exe, &mut |ev| {
                    progress.event(log, &ev)
                })?;
            }
            Scheduler::Slurm => {
                let exe = study.slurm.exe.clone().unwrap_or_else(|| opts.exe.clone());
                let name = format!(
                    "aster-nl-{}",
                    study
                        .path
                        .file_stem()
                        .map_or("sweep".into(), |s| s.to_string_lossy())
                );
                let arrays =
                    slurm::submit(&layout, &manifest, &pending, &study.slurm, &exe, &name)?;
                manifest.slurm_jobs = arrays.iter().map(|a| a.job.clone()).collect();
                layout.write_manifest(&manifest)?;
                progress.submitted(log, &arrays);
                if !opts.wait {
                    submitted = manifest.slurm_jobs.clone();
                } else {
                    wait_slurm(&layout, &manifest, &arrays, opts.poll, &mut progress, log)?;
                    manifest.slurm_jobs.clear();
                    layout.write_manifest(&manifest)?;
                }
            }
        }
    }

    let points: Vec<PointResult> = manifest
        .points
        .iter()
        .enumerate()
        .map(|(i, p)| PointResult {
            id: p.id.clone(),
            label: study::describe(&manifest.params, &study.points[i]),
            status: layout.status(&p.id),
            ran_now: pending.contains(&i),
            dir: layout.point_dir(&p.id),
        })
        .collect();
    let mut summary = SweepSummary {
        out: layout.root.clone(),
        params: manifest.params.clone(),
        points,
        merged: None,
        picture: None,
        picture_note: None,
        submitted,
    };
    if summary.submitted.is_empty() {
        let runs = run_inputs(&layout, &manifest);
        let merged = layout.merged();
        let report = merge::merge(&merged, &manifest.params, &runs)?;
        match plot::draw_family(
            &merged,
            study.plot.table.as_deref(),
            study.plot.colour.as_deref(),
            &layout.curves(),
        ) {
            Ok(Some(p)) => summary.picture = Some(p),
            Ok(None) => {
                summary.picture_note =
                    Some("no picture: the runs hold no MODE_NON_LINE table".into())
            }
            Err(e) => summary.picture_note = Some(format!("no picture: {}", e.message)),
        }
        summary.merged = Some((merged, report));
    }
    Ok(summary)
}

/// The manifest of a study: each point with its directory name.
fn build_manifest(study: &Study) -> Result<Manifest> {
    let mut points: Vec<ManifestPoint> = Vec::with_capacity(study.points.len());
    for p in &study.points {
        let id = layout::point_id(&study.params, p);
        if let Some(other) = points.iter().position(|q| q.id == id) {
            return Err(Error::input(format!(
                "points {} and {} would share the directory {id}",
                other + 1,
                points.len() + 1
            )));
        }
        points.push(ManifestPoint {
            id,
            values: p.values.clone(),
        });
    }
    let comm_name = study
        .template
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_else(|| "point.comm".into());
    let abs = |p: &Path| std::path::absolute(p).unwrap_or_else(|_| p.to_path_buf());
    Ok(Manifest {
        version: MANIFEST_VERSION,
        study: abs(&study.path),
        template: abs(&study.template),
        comm_name,
        params: study.params.clone(),
        points,
        units: study.units.iter().map(|(n, p)| (*n, abs(p))).collect(),
        timeout: study.timeout,
        slurm_jobs: Vec::new(),
    })
}

/// Watch the arrays until Slurm knows none of their tasks, then record the points whose
/// task ended without writing an outcome.
fn wait_slurm(
    layout: &Layout,
    manifest: &Manifest,
    arrays: &[slurm::Submitted],
    poll: Duration,
    progress: &mut Progress,
    log: &mut dyn std::io::Write,
) -> Result<()> {
    let jobs: Vec<String> = arrays.iter().map(|a| a.job.clone()).collect();
    let all: Vec<usize> = arrays
        .iter()
        .flat_map(|a| a.points.iter().copied())
        .collect();
    // Per point: 0 not seen, 1 seen running, 2 seen finished (reported once each).
    let mut seen = vec![0u8; all.len()];
    let mut report = |progress: &mut Progress, log: &mut dyn std::io::Write| {
        for (k, &i) in all.iter().enumerate() {
            let id = &manifest.points[i].id;
            if seen[k] < 2 {
                if let Some(s) = layout.status(id) {
                    if seen[k] == 0 {
                        progress.event(log, &local::Event::Started(i));
                    }
                    progress.event(log, &local::Event::Finished(i, s));
                    seen[k] = 2;
                } else if seen[k] == 0 && layout.running(id).is_some() {
                    progress.event(log, &local::Event::Started(i));
                    seen[k] = 1;
                }
            }
        }
    };
    let mut failures = 0;
    loop {
        std::thread::sleep(poll);
        let q = match slurm::queue_state(&jobs) {
            Ok(q) => {
                failures = 0;
                q
            }
            // The controller may be busy for a moment; a minute of failures is not that.
            Err(e) if failures * poll.as_millis() < 60_000 => {
                failures += 1;
                if failures == 1 {
                    let _ = writeln!(log, "squeue: {} (retrying)", e.message);
                }
                continue;
            }
            Err(e) => return Err(e),
        };
        report(progress, log);
        progress.poll(log, &q);
        if q.is_empty() {
            // Statuses written just before the tasks left the queue.
            report(progress, log);
            break;
        }
    }
    for a in arrays {
        for (task, &i) in a.points.iter().enumerate() {
            let id = &manifest.points[i].id;
            if layout.status(id).is_some() {
                continue;
            }
            let task_log = slurm::task_log(layout, &a.job, task);
            let tail = std::fs::read_to_string(&task_log).ok().and_then(|t| {
                t.lines()
                    .rev()
                    .find(|l| !l.trim().is_empty())
                    .map(str::to_string)
            });
            let msg = format!(
                "Slurm task {}_{task} ended without a result{} (log: {})",
                a.job,
                tail.map(|t| format!(": {}", t.trim())).unwrap_or_default(),
                task_log.display()
            );
            let s =
                point::record_lost(layout, manifest, i, msg, &format!("slurm {}_{task}", a.job))?;
            progress.event(log, &local::Event::Finished(i, s));
        }
    }
    Ok(())
}

/// Every point of the manifest as an input of the merge.
fn run_inputs(layout: &Layout, manifest: &Manifest) -> Vec<merge::RunInput> {
    manifest
        .points
        .iter()
        .map(|p| {
            let status = layout.status(&p.id);
            let dir = layout.point_dir(&p.id);
            let db = status
                .as_ref()
                .map(|s| dir.join(&s.db))
                .filter(|d| d.is_file());
            merge::RunInput {
                point: p.id.clone(),
                values: p.values.iter().cloned().map(Some).collect(),
                outcome: status.as_ref().map(|s| s.outcome),
                error: status.as_ref().map(|s| s.error.clone()).unwrap_or_default(),
                seconds: status.as_ref().map(|s| s.seconds),
                db,
            }
        })
        .collect()
}

/// Run one task of a Slurm array: the point on line `SLURM_ARRAY_TASK_ID` + 1 of `list`.
pub fn run_task(out: &Path, list: &Path, task: usize, exe: &Path) -> Result<PointStatus> {
    let layout = Layout::open(out)?;
    let manifest = layout.read_manifest()?;
    let text = std::fs::read_to_string(list)
        .map_err(|e| layout::io_err(format!("cannot read {}: {e}", list.display())))?;
    let id = text.lines().nth(task).map(str::trim).ok_or_else(|| {
        layout::io_err(format!(
            "{} has no line {} (task {task})",
            list.display(),
            task + 1
        ))
    })?;
    let index = manifest
        .points
        .iter()
        .position(|p| p.id == id)
        .ok_or_else(|| {
            layout::io_err(format!(
                "point {id} is not in {}",
                layout.manifest_path().display()
            ))
        })?;
    let job = std::env::var("SLURM_ARRAY_JOB_ID").unwrap_or_else(|_| "?".into());
    point::run_point(
        &layout,
        &manifest,
        index,
        exe,
        &format!("slurm {job}_{task}"),
    )
}

/// Where a sweep stands, without changing anything (`--status`).
pub fn status(study_path: &Path, out: Option<&Path>) -> Result<report::StatusReport> {
    let study = Study::load(study_path)?;
    let root = out.map_or(study.out.clone(), Path::to_path_buf);
    let layout = Layout::open(&root)?;
    let manifest = layout.read_manifest()?;
    let queue = if manifest.slurm_jobs.is_empty() {
        None
    } else {
        slurm::queue_state(&manifest.slurm_jobs).ok()
    };
    Ok(report::StatusReport::read(&layout, &manifest, queue))
}
