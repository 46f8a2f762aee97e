//! How a MODE_NON_LINE run that ended before NB_BRANCHE is reported: an alarm that says
//! why and where when rows were computed, so that the file goes on and the commands after
//! it answer from those rows; an error when nothing usable was computed, when the failure
//! is not a numerical one, or when the user asked alarms to be errors
//! (DEBUT(ERREUR=_F(ALARME='EXCEPTION'))). When the failure says the branch has left the
//! physics (the law and energy checks at a branch end), the rows at the end of the branch
//! that already break their contact law beyond LAW_DEFECT_ALARM are not stored
//! ([`rows_kept`]): the file goes on from the rows that are motions of the system, and no
//! row of the wrong branch is in the table.
//!
//! Code_Aster stops the whole study when MODE_NON_LINE cannot go on. A user writes
//! NB_BRANCHE generously, so a branch that has passed every energy the file tests and then
//! cannot continue would end a file whose answers were all computed as an error, skipping
//! every test after it; aster-nl keeps the rows and says so (docs/mode_non_line.md, "When
//! the continuation cannot go on").

use crate::error::{Error, ErrorKind, Result};
use crate::nnm::error::Error as EngineError;
use crate::nnm::Point;
use crate::ops::OpContext;

/// The alarm of a run that ended before NB_BRANCHE with its rows stored.
pub const ALARM: &str = "MODE_NON_LINE_8";

/// Whether the failure says the branch has left the motions of the system (a branch-end
/// check: ECART_LOI_CHOC_MAXI, ECART_ENERGIE_MAXI, TRAVAIL_CHOC_MINI, BAISSE_FREQ_MAXI,
/// AMOR_FICTIF_MAXI; `Setting::says_wrong_branch`) rather than that it cannot go on: the
/// rows just before may be off the law too ([`rows_kept`]).
fn is_wrong_branch(e: &EngineError) -> bool {
    e.setting.is_some_and(|s| s.says_wrong_branch())
}

/// Whether `error` may cut rows off the end of the table ([`rows_kept`]).
pub fn cuts_rows(error: Option<&EngineError>) -> bool {
    error.is_some_and(is_wrong_branch)
}

/// How many of the computed rows are stored: all of them, except after a wrong-branch
/// failure, where the trailing rows that are not motions of the system (`motions[i]`
/// false: a relative law defect, ECART_LOI_CHOC judged as ECART_LOI_CHOC_MAXI is, above
/// `LAW_DEFECT_ALARM`, or contact forces that attract the structure on average,
/// TRAVAIL_CHOC_MINI) are dropped: past the last row that is one, the branch is no longer a
/// motion of the system.
pub fn rows_kept(error: Option<&EngineError>, motions: &[bool]) -> usize {
    match error {
        Some(e) if is_wrong_branch(e) => motions.iter().rposition(|&ok| ok).map_or(0, |i| i + 1),
        _ => motions.len(),
    }
}

/// Reports how the continuation ended: `error` (a failure) or `limit` (a reason to stop
/// that is not one), after the `points` stored from NUME_ORDRE `first_order` on.
pub fn report(
    ctx: &mut OpContext<'_>,
    error: Option<Error>,
    limit: Option<&str>,
    points: &[Point],
    dropped: usize,
    n_branches: usize,
    first_order: i64,
) -> Result<()> {
    let mut stored = stored_rows(points, first_order);
    if dropped > 0 {
        stored = format!(
            "{stored}; the {dropped} row(s) computed after them are not motions of the system \
             (contact law broken by more than {} x max(RIGI_NOR*JEU, largest contact force), or \
             contact forces that attract the structure on average, below TRAVAIL_CHOC_MINI, or a \
             frequency off the family of the mode, BAISSE_FREQ_MAXI) and were not stored",
            crate::nnm::LAW_DEFECT_ALARM
        );
    }
    if let Some(why) = limit {
        ctx.alarm(
            ALARM,
            &format!("MODE_NON_LINE stopped before NB_BRANCHE = {n_branches}: {why}; {stored}"),
        )?;
    }
    let Some(e) = error else {
        return Ok(());
    };
    let restart = "restart from the last row with ETAT_INIT=_F(MODE_NON_LINE=..., NUME_ORDRE=...)";
    let as_error = points.is_empty() || e.kind != ErrorKind::Numerical || ctx.alarms_are_errors;
    if as_error {
        // Keep every branch computed so far (committed), then stop the run. The engine's
        // own hint (what to change) is kept in front of the restart advice.
        let keep = format!("the rows computed before the failure are stored; {restart}");
        let hint = match &e.hint {
            Some(h) => format!("{h}; {keep}"),
            None => keep,
        };
        ctx.deferred_error = Some(e.keyword("MODE_NON_LINE").hint(hint));
        return Ok(());
    }
    let knob = e
        .keyword
        .as_deref()
        .map(|k| format!(" [{k}]"))
        .unwrap_or_default();
    let advice = e
        .hint
        .as_deref()
        .map(|h| format!("; {h}"))
        .unwrap_or_default();
    ctx.alarm(
        ALARM,
        &format!(
            "MODE_NON_LINE could not go on to NB_BRANCHE = {n_branches}: {}{knob}{advice}; {stored}; \
             the commands after it answer from these rows (an error there if they need more); \
             {restart}; DEBUT(ERREUR=_F(ALARME='EXCEPTION')) makes this an error",
            e.message
        ),
    )
}

/// "N row(s) stored, NUME_ORDRE a to b, up to ENERGIE e J at FREQUENCE f Hz".
fn stored_rows(points: &[Point], first_order: i64) -> String {
    let Some(last) = points.last() else {
        return "no row was stored".to_string();
    };
    let (emax, fmax) = points.iter().fold((0.0f64, 0.0f64), |(e, f), p| {
        (e.max(p.energy), f.max(p.frequency))
    });
    format!(
        "{} row(s) stored, NUME_ORDRE {first_order} to {} (the last at ENERGIE {:.6e} J, \
         FREQUENCE {:.6e} Hz; largest ENERGIE {emax:.6e} J, largest FREQUENCE {fmax:.6e} Hz)",
        points.len(),
        first_order + points.len() as i64 - 1,
        last.energy,
        last.frequency
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_wrong_branch_drops_only_its_trailing_rows_that_are_not_motions() {
        use crate::nnm::error::Setting;
        let law = EngineError::numerical("off the law").setting(Setting::LawDefectMax);
        let energy = EngineError::numerical("energy").setting(Setting::EnergySpreadMax);
        let work = EngineError::numerical("attracts").setting(Setting::ContactWorkMin);
        let newton = EngineError::numerical("no convergence").setting(Setting::NewtonIterations);
        let d = [true, false, true, false, false];
        // The suspect row 2 is followed by a motion: only rows 4 and 5 go.
        assert_eq!(rows_kept(Some(&law), &d), 3);
        assert_eq!(rows_kept(Some(&energy), &d), 3);
        assert_eq!(rows_kept(Some(&work), &d), 3);
        // No motion at all: nothing stored (the run is then an error).
        assert_eq!(rows_kept(Some(&law), &[false, false]), 0);
        // Any other end keeps every row.
        assert_eq!(rows_kept(Some(&newton), &d), 5);
        assert_eq!(rows_kept(None, &d), 5);
    }
}
