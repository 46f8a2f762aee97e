//! REPONSE_FORCEE_NL's STABILITE and MODULE_MAX columns: the Floquet analysis of each row
//! (`nnm::stability`, which treats a forced problem's points without a trivial pair), read
//! from STABILITE, TOLERANCE and SCHEMA_TEMPS; the alarm that lists INDETERMINE rows.

use crate::args::Args;
use crate::error::Result;
use crate::nnm::error::Setting;
use crate::nnm::stability::{Floquet, FloquetAnalyser, Verdict};
use crate::nnm::{Point, Problem, Settings};
use crate::ops::calc_stabilite::floquet_settings;
use crate::ops::common::resources::{check_memory, warn_long_work};
use crate::ops::OpContext;
use crate::table::print::format_e;

/// Every row's Floquet analysis, or None with STABILITE='NON'.
pub(super) fn analyse(
    ctx: &mut OpContext<'_>,
    args: &Args,
    problem: &Problem,
    settings: &Settings,
    points: &[Point],
) -> Result<Option<Vec<Floquet>>> {
    if args.req_text("STABILITE")? == "NON" {
        return Ok(None);
    }
    // Defaults are the catalog's (commands/REPONSE_FORCEE_NL.toml).
    let (tolerance, integrator, n_inst) = floquet_settings(args)?;
    let n = problem.k.nrows();
    check_memory(
        "REPONSE_FORCEE_NL/STABILITE",
        &format!("the monodromy matrix of {n} DOF(s)"),
        crate::nnm::budget::floquet_bytes(n),
    )?;
    warn_long_work(
        ctx,
        "REPONSE_FORCEE_NL/STABILITE",
        &format!(
            "the stability of {} row(s), {n_inst} steps per period each (STABILITE='NON' skips it)",
            points.len()
        ),
        crate::nnm::budget::floquet_flops(n, n_inst) * points.len() as f64,
    )?;
    let analyser = FloquetAnalyser::new(problem, settings.harmonics)?;
    let mut out = Vec::with_capacity(points.len());
    for (j, p) in points.iter().enumerate() {
        let f = analyser
            .floquet(&p.x, n_inst, integrator, tolerance)
            .map_err(|mut e| {
                // The rows are this operator's, not a MODE_NON_LINE table's: named below.
                if e.setting == Some(Setting::StabilityRows) {
                    e.setting = None;
                }
                crate::error::Error::from(e).keyword(format!(
                    "REPONSE_FORCEE_NL/STABILITE (row NUME_ORDRE={})",
                    j + 1
                ))
            })?;
        out.push(f);
    }
    let count = |v: Verdict| out.iter().filter(|f| f.verdict == v).count();
    let undecided: Vec<usize> = (0..out.len())
        .filter(|&j| out[j].verdict == Verdict::Indeterminate)
        .collect();
    ctx.say(&format!(
        "  stability: {} STABLE, {} INSTABLE, {} INDETERMINE (TOLERANCE={tolerance:e})",
        count(Verdict::Stable),
        count(Verdict::Unstable),
        undecided.len()
    ))?;
    if !undecided.is_empty() {
        ctx.alarm("REPONSE_FORCEE_NL_2", &undecided_message(&out, &undecided))?;
    }
    Ok(Some(out))
}

/// The alarm for INDETERMINE rows: a multiplier above 1 + TOLERANCE but within the band
/// √(2·orbit defect) the orbit's accuracy leaves.
fn undecided_message(out: &[Floquet], rows: &[usize]) -> String {
    let listed: Vec<String> = rows.iter().take(10).map(|j| (j + 1).to_string()).collect();
    let more = if rows.len() > 10 { ", ..." } else { "" };
    let worst = rows
        .iter()
        .map(|&j| out[j].orbit_defect)
        .fold(0.0, f64::max);
    format!(
        "{} row(s) INDETERMINE (NUME_ORDRE {}{more}): their largest multiplier modulus \
         (MODULE_MAX) is above 1 + TOLERANCE but within sqrt(2 x orbit defect) of 1, the \
         orbit defect (up to {}) measuring how far the harmonic-balance orbit and the time \
         integration are from a periodic solution of the linearised equations. Raise \
         NB_HARM_LINE (the usual cause: the stop's kink needs more harmonics) or \
         SCHEMA_TEMPS/NB_INST.",
        rows.len(),
        listed.join(", "),
        format_e(worst, 2)
    )
}
