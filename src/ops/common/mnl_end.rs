//! How a MODE_NON_LINE run that ended before NB_BRANCHE is reported: an alarm that says
//! why and where when rows were computed, so that the file goes on and the commands after
//! it answer from those rows; an error when nothing usable was computed, when the failure
//! is not a numerical one, when it says the branch has left the physics (the law and
//! energy checks), or when the user asked alarms to be errors
//! (DEBUT(ERREUR=_F(ALARME='EXCEPTION'))).
//!
//! Code_Aster stops the whole study when MODE_NON_LINE cannot go on. A user writes
//! NB_BRANCHE generously, so a branch that has passed every energy the file tests and then
//! cannot continue would end a file whose answers were all computed as an error, skipping
//! every test after it; aster-nl keeps the rows and says so (docs/mode_non_line.md, "When
//! the continuation cannot go on").

use crate::error::{Error, ErrorKind, Result};
use crate::nnm::Point;
use crate::ops::OpContext;

/// The alarm of a run that ended before NB_BRANCHE with its rows stored.
pub const ALARM: &str = "MODE_NON_LINE_8";

/// The checks whose failure says the branch has left the motions of the system (its end
/// breaks its contact law, or its energy is not conserved) rather than that it cannot go
/// on: the rows just before are suspect too, so the run stops as an error and no file ends
/// with exit code 0 on a wrong branch.
const WRONG_BRANCH: &[&str] = &["ECART_LOI_CHOC_MAXI", "ECART_ENERGIE_MAXI"];

/// Reports how the continuation ended: `error` (a failure) or `limit` (a reason to stop
/// that is not one), after the `points` stored from NUME_ORDRE `first_order` on.
pub fn report(
    ctx: &mut OpContext<'_>,
    error: Option<Error>,
    limit: Option<&str>,
    points: &[Point],
    n_branches: usize,
    first_order: i64,
) -> Result<()> {
    let stored = stored_rows(points, first_order);
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
    let wrong_branch = e
        .keyword
        .as_deref()
        .is_some_and(|k| WRONG_BRANCH.iter().any(|w| k.ends_with(w)));
    let as_error = points.is_empty()
        || e.kind != ErrorKind::Numerical
        || wrong_branch
        || ctx.alarms_are_errors;
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
