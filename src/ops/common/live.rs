//! MODE_NON_LINE's live view: the rows of every branch written, as the branch ends, to a
//! live file beside the study (`store::live`) that a reader can query while the run goes
//! on. Watching is a convenience: a live file that cannot be created or written gives one
//! alarm and the computation goes on; the study never depends on it.

use super::super::OpContext;
use crate::error::Result;
use crate::nnm::Point;
use crate::store::live::{LiveFile, LiveRow};

/// The live view of one MODE_NON_LINE call (inactive for an in-memory study).
pub struct LiveView {
    file: Option<LiveFile>,
    /// Why the view stopped, reported once at the end.
    failed: Option<String>,
}

impl LiveView {
    /// Start the live view of `concept`: its file is named to the user at once.
    pub fn start(ctx: &mut OpContext<'_>, concept: &str) -> Result<LiveView> {
        let Some(study) = ctx.store.path().map(std::path::Path::to_path_buf) else {
            return Ok(LiveView {
                file: None,
                failed: None,
            });
        };
        match LiveFile::create(&study, concept) {
            Ok(f) => {
                ctx.say(&format!(
                    "MODE_NON_LINE {concept}: rows so far in {} while it runs \
                     (SELECT * FROM {concept})",
                    f.path().display()
                ))?;
                Ok(LiveView {
                    file: Some(f),
                    failed: None,
                })
            }
            Err(e) => Ok(LiveView {
                file: None,
                failed: Some(e.message),
            }),
        }
    }

    /// Append the rows of one branch (called from the engine's per-branch callback).
    pub fn branch(&mut self, branch: usize, points: &[Point]) {
        let Some(f) = &mut self.file else { return };
        let rows: Vec<LiveRow> = points
            .iter()
            .map(|p| LiveRow {
                branch: p.branch,
                frequency: p.frequency,
                energy: p.energy,
                bifurcation: p.bifurcation,
            })
            .collect();
        if let Err(e) = f.branch(branch, &rows) {
            self.failed = Some(e.message);
            self.file = None;
        }
    }

    /// Mark the live file with how the engine ended (`ok`: every branch computed), and
    /// report a live view that could not be kept.
    pub fn finish(self, ctx: &mut OpContext<'_>, ok: bool) -> Result<()> {
        if let Some(f) = self.file {
            if let Err(e) = f.finish(if ok { "DONE" } else { "FAILED" }) {
                return ctx.alarm("MODE_NON_LINE_6", &format!("live file: {}", e.message));
            }
        }
        if let Some(why) = self.failed {
            return ctx.alarm(
                "MODE_NON_LINE_6",
                &format!("no live view of the rows while the operator ran: {why}; the results are unaffected"),
            );
        }
        Ok(())
    }
}
