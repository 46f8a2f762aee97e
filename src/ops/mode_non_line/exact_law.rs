//! MODE_NON_LINE's RESOLUTION/CORR_LOI_EXACTE (an aster-nl extension, docs/mode_non_line.md):
//! every stored row corrected on the exact (unregularised) penalty law by
//! `nnm::exact_law`, its frequency in the extra column FREQUENCE_LOI_EXACTE. Glue only: the
//! keywords, the size check with the keyword named, the column's cells and the alarms.

use crate::args::Args;
use crate::error::Result;
use crate::nnm::exact_law::{self, ExactLawSettings, HeldEnergy};
use crate::nnm::{Point, Problem, Settings};
use crate::ops::common::progress::Progress;
use crate::ops::common::resources;
use crate::ops::OpContext;
use crate::table::Cell;

/// The extra column: the exact-law frequency (Hz) at the row's ENERGIE_MOYENNE.
pub const COLUMN: &str = "FREQUENCE_LOI_EXACTE";

const KEYWORD: &str = "MODE_NON_LINE/RESOLUTION/CORR_LOI_EXACTE";

/// A row whose correction failed: its cell is empty.
const ALARM: &str = "MODE_NON_LINE_6";

/// Failed rows named one by one; the rest are counted in one more alarm.
const NAMED_FAILURES: usize = 10;

/// The correction's settings when CORR_LOI_EXACTE = 'OUI' (defaults and bounds: the
/// catalog), converging to PREC_NEWTON within ITER_NEWTON_MAXI as the branch ends do.
pub fn settings(args: &Args, s: &Settings) -> Result<Option<ExactLawSettings>> {
    let r = args.req_fact("RESOLUTION")?;
    if r.req_text("CORR_LOI_EXACTE")? != "OUI" {
        return Ok(None);
    }
    let per_coef = r.req_count("NB_ECHAN_LOI_EXACTE")?;
    Ok(Some(ExactLawSettings {
        h_lin: s.harmonics.h_lin,
        samples: exact_law::samples_for(s.harmonics.h_lin, per_coef),
        prec: s.continuation.prec_newton,
        iter_max: s.continuation.iter_newton_max,
        held: HeldEnergy::Mean,
    }))
}

/// Refuses, before any computation, a model too large for the dense correction, and one
/// whose dense tangent does not fit in memory.
pub fn check(problem: &Problem, set: &ExactLawSettings) -> Result<()> {
    let n = problem.k.nrows();
    exact_law::check_size(n, set.h_lin).map_err(|e| {
        crate::error::Error::from(e).keyword(KEYWORD).hint(format!(
            "the correction is dense (at most {} unknowns): lower NB_HARM_LINE, or leave \
             CORR_LOI_EXACTE='NON' on a model of this size",
            exact_law::MAX_DENSE
        ))
    })?;
    let dim = exact_law::dense_size(n, set.h_lin) as f64;
    resources::check_memory(
        KEYWORD,
        "the exact-law correction's dense tangent",
        8.0 * dim * (dim + 8.0) + 8.0 * 16.0 * set.samples as f64,
    )
}

/// The cells of FREQUENCE_LOI_EXACTE for `points` (rows `first_order`, `first_order` + 1,
/// ...): the corrected frequency, or an empty cell and an alarm naming the row and why.
pub fn cells(
    ctx: &mut OpContext<'_>,
    problem: &Problem,
    set: &ExactLawSettings,
    points: &[Point],
    first_order: i64,
) -> Result<Vec<Cell>> {
    let mut cells = Vec::with_capacity(points.len());
    let mut failed: Vec<(i64, String)> = Vec::new();
    let mut iterations = 0;
    // A dense LU of up to MAX_DENSE unknowns per row, a few times: minutes on the largest
    // model accepted, so it shows progress as the branches do.
    let progress = Progress::new(ctx.progress, points.len() as u64, "CORR_LOI_EXACTE", "rows");
    for (j, p) in points.iter().enumerate() {
        progress.inc();
        match exact_law::correct_point(problem, set, p) {
            Ok(c) if c.frequency.is_finite() && c.frequency > 0.0 => {
                iterations = iterations.max(c.iterations);
                cells.push(Cell::R(c.frequency));
            }
            Ok(c) => {
                failed.push((
                    first_order + j as i64,
                    format!("the corrected orbit has frequency {:e} Hz", c.frequency),
                ));
                cells.push(Cell::Null);
            }
            Err(e) => {
                failed.push((first_order + j as i64, e.message));
                cells.push(Cell::Null);
            }
        }
    }
    progress.finish();
    if ctx.info >= 1 {
        ctx.say(&format!(
            "  CORR_LOI_EXACTE: {} of {} row(s) corrected on the exact law ({} samples per \
             period, at most {iterations} Newton iteration(s)); column {COLUMN}",
            points.len() - failed.len(),
            points.len(),
            set.samples
        ))?;
    }
    for (order, why) in failed.iter().take(NAMED_FAILURES) {
        ctx.alarm(
            ALARM,
            &format!(
                "row NUME_ORDRE {order}: the exact-law correction (CORR_LOI_EXACTE) failed: \
                 {why}; its {COLUMN} is left empty"
            ),
        )?;
    }
    if failed.len() > NAMED_FAILURES {
        ctx.alarm(
            ALARM,
            &format!(
                "{} more row(s) whose exact-law correction failed (NUME_ORDRE {} to {}): their \
                 {COLUMN} is left empty",
                failed.len() - NAMED_FAILURES,
                failed[NAMED_FAILURES].0,
                failed[failed.len() - 1].0
            ),
        )?;
    }
    Ok(cells)
}
