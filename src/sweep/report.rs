//! What a sweep tells the user: a line per point as it ends (with the counts of the whole
//! sweep: done / failed / running / waiting), Slurm's queue as it changes, and the summary.

use super::layout::{Layout, Manifest, Outcome};
use super::local::Event;
use super::slurm::{QueueState, Submitted};
use super::study::{Scheduler, Study};
use super::{SweepOptions, SweepSummary};
use std::io::Write;

/// Counts across the sweep as it runs.
pub struct Progress {
    total: usize,
    /// Points that were up to date before this run.
    skipped: usize,
    to_run: usize,
    finished: usize,
    ok: usize,
    nook: usize,
    failed: usize,
    running: usize,
    labels: Vec<String>,
    last_queue: Option<QueueState>,
}

impl Progress {
    pub fn new(layout: &Layout, manifest: &Manifest, pending: &[usize]) -> Progress {
        let _ = layout;
        Progress {
            total: manifest.points.len(),
            skipped: manifest.points.len() - pending.len(),
            to_run: pending.len(),
            finished: 0,
            ok: 0,
            nook: 0,
            failed: 0,
            running: 0,
            labels: manifest
                .points
                .iter()
                .map(|p| {
                    manifest
                        .params
                        .iter()
                        .zip(&p.values)
                        .map(|(n, v)| format!("{n}={}", v.display()))
                        .collect::<Vec<_>>()
                        .join(" ")
                })
                .collect(),
            last_queue: None,
        }
    }

    pub fn header(&self, log: &mut dyn Write, study: &Study, opts: &SweepOptions) {
        let how = match study.scheduler {
            Scheduler::Local => "local processes",
            Scheduler::Slurm => "a Slurm job array",
        };
        let what = if opts.merge_only {
            "--merge-only: nothing runs".to_string()
        } else {
            format!(
                "{} to run on {how}, {} up to date",
                self.to_run, self.skipped
            )
        };
        let _ = writeln!(
            log,
            "sweep {}: {} point(s) of {} ({}), {what}; output {}",
            study.path.display(),
            self.total,
            study.template.display(),
            study.params.join(" x "),
            study.out.display()
        );
    }

    pub fn event(&mut self, log: &mut dyn Write, ev: &Event) {
        match ev {
            Event::Started(_) => self.running += 1,
            Event::Finished(i, s) => {
                self.running = self.running.saturating_sub(1);
                self.finished += 1;
                match s.outcome {
                    Outcome::Ok => self.ok += 1,
                    Outcome::Nook => self.nook += 1,
                    Outcome::Failed => self.failed += 1,
                }
                let note = if s.error.is_empty() {
                    String::new()
                } else {
                    format!(": {}", s.error)
                };
                let width = self.to_run.to_string().len();
                let _ = writeln!(
                    log,
                    "[{:>width$}/{}] {:<6} {} ({:.2} s){note}   | done {}, failed {}, running {}, waiting {}",
                    self.finished,
                    self.to_run,
                    s.outcome.name(),
                    self.labels.get(*i).map_or("", String::as_str),
                    s.seconds,
                    self.ok + self.nook,
                    self.failed,
                    self.running,
                    self.to_run.saturating_sub(self.finished + self.running),
                );
            }
        }
    }

    pub fn submitted(&mut self, log: &mut dyn Write, arrays: &[Submitted]) {
        for a in arrays {
            let _ = writeln!(
                log,
                "submitted Slurm job array {} ({} task(s))",
                a.job,
                a.points.len()
            );
        }
    }

    /// A line when Slurm's queue changes.
    pub fn poll(&mut self, log: &mut dyn Write, q: &QueueState) {
        if self.last_queue.as_ref() == Some(q) {
            return;
        }
        self.last_queue = Some(*q);
        let _ = writeln!(
            log,
            "slurm: {} task(s) waiting, {} running",
            q.pending, q.running
        );
    }
}

/// The summary printed at the end of a sweep.
pub fn summary_text(s: &SweepSummary) -> String {
    let mut t = String::new();
    let ok = s.count(Some(Outcome::Ok));
    let nook = s.count(Some(Outcome::Nook));
    let failed = s.count(Some(Outcome::Failed));
    let missing = s.count(None);
    let ran = s.points.iter().filter(|p| p.ran_now).count();
    if !s.submitted.is_empty() {
        t.push_str(&format!(
            "\nsweep: {} point(s): {ran} submitted to Slurm as job(s) {}; \
             `aster-nl sweep STUDY --status` shows the progress; running the sweep again \
             once they end merges the results (and reruns what failed)\n",
            s.points.len(),
            s.submitted.join(", ")
        ));
        return t;
    }
    t.push_str(&format!(
        "\nsweep: {} point(s): {ok} ok, {nook} nook, {failed} failed, {missing} not run ({ran} run now, {} from earlier runs)\n",
        s.points.len(),
        s.points
            .iter()
            .filter(|p| !p.ran_now && p.status.is_some())
            .count(),
    ));
    let bad: Vec<_> = s
        .points
        .iter()
        .filter(|p| p.status.as_ref().is_none_or(|st| st.outcome != Outcome::Ok))
        .collect();
    if !bad.is_empty() {
        t.push_str("points not ok:\n");
        for p in bad {
            match &p.status {
                Some(st) => {
                    t.push_str(&format!(
                        "  {:<6} {}: {}\n",
                        st.outcome.name(),
                        p.label,
                        st.error
                    ));
                    let report = p.dir.join(super::point::POINT_ERR);
                    if report.is_file() {
                        t.push_str(&format!("         {}\n", report.display()));
                    }
                }
                None => t.push_str(&format!("  {:<6} {}\n", "-", p.label)),
            }
        }
    }
    if let Some((db, r)) = &s.merged {
        t.push_str(&format!(
            "merged: {} ({} run(s), {} table(s), {} row(s); SWEEP_POINTS lists every point)\n",
            db.display(),
            r.runs,
            r.tables,
            r.rows
        ));
    }
    if let Some(p) = &s.picture {
        let files: Vec<String> = p.files.iter().map(|f| f.display().to_string()).collect();
        t.push_str(&format!(
            "picture: {} ({}, {} curve(s), colour {})\n",
            files.join(", "),
            p.table,
            p.curves,
            p.colour
        ));
        if let Some((db, _)) = &s.merged {
            let group = s.params.join(", ");
            t.push_str(&format!(
                "query: sqlite3 -header {} \"SELECT {group}, MAX(FREQUENCE), MAX(ENERGIE) FROM {} GROUP BY {group}\"\n",
                db.display(),
                p.table
            ));
        }
    } else if let Some(n) = &s.picture_note {
        t.push_str(n);
        t.push('\n');
    }
    t
}

/// Where a sweep stands (`--status`).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct StatusReport {
    pub total: usize,
    pub ok: usize,
    pub nook: usize,
    pub failed: usize,
    pub running: usize,
    pub not_run: usize,
    pub queue: Option<QueueState>,
    pub lines: Vec<String>,
}

impl StatusReport {
    pub fn read(layout: &Layout, manifest: &Manifest, queue: Option<QueueState>) -> StatusReport {
        let mut r = StatusReport {
            total: manifest.points.len(),
            queue,
            ..StatusReport::default()
        };
        for p in &manifest.points {
            let label = manifest
                .params
                .iter()
                .zip(&p.values)
                .map(|(n, v)| format!("{n}={}", v.display()))
                .collect::<Vec<_>>()
                .join(" ");
            let (state, note) = match (layout.status(&p.id), layout.running(&p.id)) {
                (Some(s), _) => {
                    match s.outcome {
                        Outcome::Ok => r.ok += 1,
                        Outcome::Nook => r.nook += 1,
                        Outcome::Failed => r.failed += 1,
                    }
                    (s.outcome.name().to_string(), s.error)
                }
                (None, Some(run)) => {
                    r.running += 1;
                    (
                        "running".to_string(),
                        format!("{} on {}", run.ran_on, run.host),
                    )
                }
                (None, None) => {
                    r.not_run += 1;
                    ("-".to_string(), String::new())
                }
            };
            r.lines.push(if note.is_empty() {
                format!("  {state:<8} {label}")
            } else {
                format!("  {state:<8} {label}: {note}")
            });
        }
        r
    }

    pub fn text(&self) -> String {
        let mut t = format!(
            "{} point(s): {} ok, {} nook, {} failed, {} running, {} not run\n",
            self.total, self.ok, self.nook, self.failed, self.running, self.not_run
        );
        if let Some(q) = &self.queue {
            t.push_str(&format!(
                "slurm: {} task(s) waiting, {} running\n",
                q.pending, q.running
            ));
        }
        for l in &self.lines {
            t.push_str(l);
            t.push('\n');
        }
        t
    }
}
