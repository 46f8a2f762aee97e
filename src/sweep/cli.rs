//! The command line of `aster-nl sweep`, `aster-nl merge` and `aster-nl sweep-task` (what a
//! Slurm task runs), so that `main.rs` only names them.
//!
//! Exit codes of `sweep`: 0 every point ok, 1 some point NOOK (none failed), 2 the sweep
//! itself could not run (its study file, its directory, the scheduler), 3 some point failed
//! or did not run (the summary lists them).

use super::layout::{self, Outcome, PointStatus, POINT_STATUS};
use super::merge::{self, RunInput};
use super::study::Scheduler;
use super::value::ParamValue;
use super::{report, SweepOptions};
use crate::error::{Error, ErrorKind, Result};
use crate::lang;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::Duration;

pub const EXIT_NOOK: u8 = 1;
pub const EXIT_ERROR: u8 = 2;
pub const EXIT_POINTS_FAILED: u8 = 3;

#[derive(clap::Args, Debug)]
pub struct SweepArgs {
    /// The study file (TOML): template, [grid] or [list] of parameter values, [units],
    /// [run], [slurm], [plot] (docs/sweeps.md).
    pub study: PathBuf,
    /// Output directory (default: the study's `out`, else <study>.sweep beside it).
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// Local processes at once (default: the study's [run] jobs, else the cores).
    #[arg(long, short = 'j')]
    pub jobs: Option<usize>,
    /// Submit the points as a Slurm job array (overrides [run] scheduler).
    #[arg(long, conflicts_with = "local")]
    pub slurm: bool,
    /// Run the points on this machine (overrides [run] scheduler).
    #[arg(long)]
    pub local: bool,
    /// Slurm: submit and return without waiting (run the sweep again to merge).
    #[arg(long)]
    pub no_wait: bool,
    /// Run nothing: merge and draw what the points already have.
    #[arg(long, conflicts_with = "status")]
    pub merge_only: bool,
    /// Print where the sweep stands (done / failed / running / not run) and return.
    #[arg(long)]
    pub status: bool,
}

#[derive(clap::Args, Debug)]
pub struct MergeArgs {
    /// The merged database to write (replaced only if it is a merged database itself).
    pub out: PathBuf,
    /// Run databases. A `point.json` beside a database (a sweep's point) gives its
    /// parameters and outcome.
    #[arg(required = true)]
    pub runs: Vec<PathBuf>,
}

#[derive(clap::Args, Debug)]
pub struct TaskArgs {
    /// The sweep's directory.
    pub out: PathBuf,
    /// The task list: line i+1 names the point of task i.
    pub list: PathBuf,
    /// Task number (default: $SLURM_ARRAY_TASK_ID).
    #[arg(long)]
    pub task: Option<usize>,
}

fn fail(e: &Error) -> ExitCode {
    eprintln!("{}", lang::render(e, None));
    ExitCode::from(EXIT_ERROR)
}

/// Render an error with the text of the file it points into (the study, the template).
fn fail_located(e: &Error) -> ExitCode {
    let src = e
        .location
        .as_ref()
        .and_then(|loc| {
            std::fs::read_to_string(&loc.file)
                .ok()
                .map(|t| (loc.file.clone(), t))
        })
        .map(|(name, text)| lang::Source { name, text });
    eprintln!("{}", lang::render(e, src.as_ref()));
    ExitCode::from(EXIT_ERROR)
}

pub fn sweep(args: &SweepArgs) -> ExitCode {
    if args.status {
        return match super::status(&args.study, args.out.as_deref()) {
            Ok(r) => {
                print!("{}", r.text());
                ExitCode::SUCCESS
            }
            Err(e) => fail_located(&e),
        };
    }
    let exe = match std::env::current_exe() {
        Ok(e) => e,
        Err(e) => {
            return fail(&Error::new(
                ErrorKind::Io,
                format!("cannot find the aster-nl binary: {e}"),
            ))
        }
    };
    let opts = SweepOptions {
        study: args.study.clone(),
        out: args.out.clone(),
        jobs: args.jobs,
        scheduler: if args.slurm {
            Some(Scheduler::Slurm)
        } else if args.local {
            Some(Scheduler::Local)
        } else {
            None
        },
        wait: !args.no_wait,
        merge_only: args.merge_only,
        exe,
        poll: Duration::from_secs(1),
    };
    if args.jobs == Some(0) {
        return fail(&Error::input("--jobs 0: at least one process is needed"));
    }
    let mut err = std::io::stderr();
    let summary = match super::run_sweep(&opts, &mut err) {
        Ok(s) => s,
        Err(e) => return fail_located(&e),
    };
    print!("{}", report::summary_text(&summary));
    if !summary.submitted.is_empty() {
        return ExitCode::SUCCESS;
    }
    if summary.count(Some(Outcome::Failed)) + summary.count(None) > 0 {
        ExitCode::from(EXIT_POINTS_FAILED)
    } else if summary.count(Some(Outcome::Nook)) > 0 {
        ExitCode::from(EXIT_NOOK)
    } else {
        ExitCode::SUCCESS
    }
}

pub fn merge(args: &MergeArgs) -> ExitCode {
    let (params, runs) = match runs_from_files(&args.runs) {
        Ok(r) => r,
        Err(e) => return fail(&e),
    };
    match merge::merge(&args.out, &params, &runs) {
        Ok(r) => {
            let failed = runs
                .iter()
                .filter(|r| r.outcome == Some(Outcome::Failed))
                .count();
            println!(
                "merged {} run(s) into {}: {} table(s), {} row(s){}; parameters: {}",
                r.runs,
                args.out.display(),
                r.tables,
                r.rows,
                if failed > 0 {
                    format!(" ({failed} failed run(s) listed in SWEEP_POINTS only)")
                } else {
                    String::new()
                },
                if params.is_empty() {
                    "none (no point.json beside the databases)".to_string()
                } else {
                    params.join(", ")
                }
            );
            ExitCode::SUCCESS
        }
        Err(e) => fail(&e),
    }
}

pub fn task(args: &TaskArgs) -> ExitCode {
    let task = match args.task {
        Some(t) => t,
        None => match std::env::var("SLURM_ARRAY_TASK_ID")
            .ok()
            .and_then(|t| t.trim().parse().ok())
        {
            Some(t) => t,
            None => {
                return fail(&Error::input(
                    "sweep-task: no --task and no SLURM_ARRAY_TASK_ID: this command is what a Slurm array task runs",
                ))
            }
        },
    };
    let exe = match std::env::current_exe() {
        Ok(e) => e,
        Err(e) => {
            return fail(&Error::new(
                ErrorKind::Io,
                format!("cannot find the aster-nl binary: {e}"),
            ))
        }
    };
    match super::run_task(&args.out, &args.list, task, &exe) {
        Ok(s) => {
            println!(
                "point {}: {}{}",
                s.id,
                s.outcome.name(),
                if s.error.is_empty() {
                    String::new()
                } else {
                    format!(": {}", s.error)
                }
            );
            // A failed point fails its task, so Slurm's own accounting shows it too.
            if s.outcome == Outcome::Failed {
                ExitCode::from(EXIT_POINTS_FAILED)
            } else {
                ExitCode::SUCCESS
            }
        }
        Err(e) => fail(&e),
    }
}

/// Runs given as database files: the parameters and outcome come from the `point.json`
/// beside each (when it names that database); the parameters of all runs, in order of
/// first appearance, become the merge's.
pub fn runs_from_files(paths: &[PathBuf]) -> Result<(Vec<String>, Vec<RunInput>)> {
    let mut params: Vec<String> = Vec::new();
    let mut found: Vec<(PathBuf, Option<PointStatus>)> = Vec::new();
    for p in paths {
        if !p.is_file() {
            return Err(Error::new(
                ErrorKind::Io,
                format!("{}: no such database", p.display()),
            ));
        }
        let sidecar = p.parent().unwrap_or(Path::new("")).join(POINT_STATUS);
        let status = layout::read_json::<PointStatus>(&sidecar)
            .ok()
            .filter(|s| p.file_name().is_some_and(|n| n.to_string_lossy() == s.db));
        if let Some(s) = &status {
            for n in &s.params {
                if !params.contains(n) {
                    params.push(n.clone());
                }
            }
        }
        found.push((p.clone(), status));
    }
    let mut runs = Vec::with_capacity(found.len());
    for (i, (p, status)) in found.into_iter().enumerate() {
        let values: Vec<Option<ParamValue>> = params
            .iter()
            .map(|n| {
                status.as_ref().and_then(|s| {
                    s.params
                        .iter()
                        .position(|m| m == n)
                        .and_then(|k| s.values.get(k).cloned())
                })
            })
            .collect();
        let point = status
            .as_ref()
            .map_or_else(|| p.display().to_string(), |s| s.id.clone());
        if runs.iter().any(|r: &RunInput| r.point == point) {
            return Err(Error::input(format!(
                "run {} ({}) is given twice",
                i + 1,
                p.display()
            )));
        }
        runs.push(RunInput {
            point,
            values,
            // A database without a sidecar is taken as it is.
            outcome: Some(status.as_ref().map_or(Outcome::Ok, |s| s.outcome)),
            error: status.as_ref().map(|s| s.error.clone()).unwrap_or_default(),
            seconds: status.as_ref().map(|s| s.seconds),
            db: Some(p),
        });
    }
    Ok((params, runs))
}
