//! The continuation driver: branch after branch, the EHMAN stages in order — the series
//! step (series_step.rs), the correction of the branch end (correction.rs), the
//! factorisation of the next branch's tangent and the determinant test (bifurcation.rs),
//! the report (report.rs) — until NB_BRANCHE branches, the caller's bound, or an error.

use crate::nnm::continuation::anm::{self, AnmParams};
use crate::nnm::continuation::bifurcation::DeterminantWatch;
use crate::nnm::continuation::correction::{correct_branch, CorrectedBranch};
use crate::nnm::continuation::end_check::EndCheck;
use crate::nnm::continuation::fold_guard::{BrokenTurn, EnergyTrend, CLEARANCE_DEFECT};
use crate::nnm::continuation::report::{branch_report, in_branch, no_progress, stalled};
use crate::nnm::continuation::series_step::{series_step, Orientation};
use crate::nnm::error::{Error, Result, Setting};
use crate::nnm::model::point::to_scaled;
use crate::nnm::model::rescale;
use crate::nnm::model::system::System;
use crate::nnm::solve::solver_kind::make_solver;
use crate::nnm::{BranchReport, Point, Problem, Settings, StartState, StepControl};

pub struct Outcome {
    pub points: Vec<Point>,
    /// A failed correction (or any numerical failure) stops the run; the points computed
    /// before it are kept.
    pub error: Option<Error>,
    /// Why the run ended before NB_BRANCHE although nothing failed (the homogeneous limit
    /// of its stops, rescale.rs); None when it ran its branches or was stopped otherwise.
    pub limit: Option<String>,
}

/// Continue at most `settings.n_branches` branches from `start`, `control` deciding what
/// happens to a branch that fails and `law_check` answering its checks of a branch end (None
/// when there is nothing to check); stops after the first branch for which `on_branch`
/// returns false.
pub(in crate::nnm) fn continue_checked(
    problem: &Problem,
    settings: &Settings,
    control: StepControl,
    law_check: Option<&dyn EndCheck>,
    start: StartState,
    on_branch: &mut dyn FnMut(&BranchReport, &[Point]) -> bool,
) -> Outcome {
    let mut outcome = Outcome {
        points: Vec::new(),
        error: None,
        limit: None,
    };
    outcome.error = run(
        problem,
        settings,
        control,
        law_check,
        start,
        on_branch,
        &mut outcome,
    )
    .err();
    outcome
}

/// The branches, into `outcome`'s points and limit; the error that ended them, if any.
fn run(
    problem: &Problem,
    settings: &Settings,
    control: StepControl,
    law_check: Option<&dyn EndCheck>,
    start_state: StartState,
    on_branch: &mut dyn FnMut(&BranchReport, &[Point]) -> bool,
    outcome: &mut Outcome,
) -> Result<()> {
    let mut sys = System::new(problem, settings, start_state.scaling, start_state.ref_dof)?;
    let mut ws = sys.workspace();
    if start_state.x.len() != sys.lay.n_unk {
        return Err(Error::internal("start state does not match the problem"));
    }
    let params = AnmParams {
        order: settings.continuation.order,
        prec: settings.continuation.prec_man,
        bif_terms: settings.continuation.bif_terms,
        bif_tol: settings.continuation.bif_tol,
    };
    let kind = start_state.solver;
    let mut solver = make_solver(&sys, &settings.continuation, kind)?;
    let mut x0 = start_state.x;
    let border = start_state.border;
    solver
        .factor(&sys, &x0, &border)
        .map_err(|e| in_branch(e, 1))?;
    let mut det = DeterminantWatch::new(settings.continuation.det_test, &sys, solver.as_mut());
    // DIR_EVOLUTION (module doc): −1 forward, +1 backward.
    let travel = start_state.travel.map(|t: Vec<f64>| to_scaled(&sys, &t));
    let mut orientation = Orientation::new(settings.continuation.direction < 0, travel);
    // (energy, frequency) of every branch end, for the no-progress guard.
    let mut ends: Vec<(f64, f64)> = Vec::new();
    // The frequency defect of the corrected end of the previous branch, the next start.
    let mut start_defect = None;
    // Turns of ENERGIE, for the broken-turn guard (fold_guard.rs).
    let mut trend = EnergyTrend::default();
    for b in 1..=settings.continuation.n_branches {
        let mut series = series_step(
            &sys,
            &mut ws,
            solver.as_mut(),
            &x0,
            &params,
            &settings.continuation,
            control.approximation,
            &orientation,
        )
        .map_err(|e| in_branch(e, b))?;
        if b == 1 && anm::dot(&series.terms[0], &border) < 0.0 {
            // The start was factorised with the motion as border, the branch leaves against
            // it: det [R_X; bᵀ] = (b·t)·det [R_X; tᵀ], so the start's sign flips with it (or
            // a backward start would be flagged as a bifurcation).
            det.border_reversed();
        }
        let CorrectedBranch {
            mut points,
            x_end,
            newton_iterations,
            tangent,
            step_retries,
            end_defect,
        } = correct_branch(
            &sys,
            &mut ws,
            solver.as_mut(),
            settings,
            &control,
            law_check,
            &mut series,
            &x0,
            start_defect,
            b,
        )?;
        let at_floor = points.last().is_some_and(|p| p.at_floor);
        // Far into a stop that is not rescaled, a floor is the amplitude's: the branch is
        // not stored and the run ends (rescale::floor_far_up).
        if let Some(end) = points.last().filter(|p| p.at_floor) {
            if let Some(e) = rescale::floor_far_up(
                problem,
                &sys,
                &x_end,
                end,
                settings.continuation.prec_newton,
            ) {
                return Err(in_branch(e, b));
            }
        }
        if let Some(p) = points.last() {
            ends.push((p.energy, p.frequency));
        }
        let stall = no_progress(&ends, control.stall_branches);
        // NB_PAS_MAN ≥ 1 (system::validate): the last point is the corrected end.
        let x_start = std::mem::replace(&mut x0, x_end);
        start_defect = end_defect;
        // The next branch starts from the corrected end point with this branch's end tangent
        // as border: factor that tangent now, and compare the sign of its determinant with
        // the one at the start of this branch. A failure belongs to the next branch: this
        // one is reported first.
        let last = b == settings.continuation.n_branches;
        let end_factor = if last && !settings.continuation.det_test {
            Ok(())
        } else {
            solver.factor(&sys, &x0, &tangent)
        };
        let end_sign = match end_factor {
            Ok(()) => det.sign(&sys, solver.as_mut()),
            Err(_) => None,
        };
        det.branch_ended(
            &sys,
            end_sign,
            &series,
            &x_start,
            settings.continuation.n_points_per_branch,
            &mut points,
            || make_solver(&sys, &settings.continuation, kind),
        )?;
        // A turn of ENERGIE where the law has come apart: the rows up to the top are
        // reported and kept, the run stops (fold_guard.rs).
        let broken = trend.branch(&points);
        if let Some(turn) = &broken {
            points.truncate(turn.keep);
        }
        let go_on = points.is_empty() || {
            let report = branch_report(
                b,
                &points,
                series.a_max,
                newton_iterations,
                step_retries,
                at_floor,
            );
            on_branch(&report, &points)
        };
        outcome.points.extend(points);
        if let Some(turn) = broken {
            return Err(in_branch(turned_back(&turn), b));
        }
        if !go_on || last {
            break;
        }
        if let Some((e, f)) = stall {
            return Err(in_branch(
                stalled(control.stall_branches, e, f, series.a_max),
                b,
            ));
        }
        end_factor.map_err(|e| in_branch(e, b + 1))?;
        match rescale::rescaled(problem, &sys, &x0) {
            // The motion has outgrown the length unit: the next branch runs in a unit of
            // its own size (rescale.rs), its start and border re-expressed and factorised.
            Some(scaling) => {
                if let Some(why) = rescale::homogeneous_limit(problem, &scaling, b) {
                    outcome.limit = Some(why);
                    break;
                }
                let next = System::new(problem, settings, scaling, sys.ref_dof)?;
                x0 = rescale::convert(&sys, &next, &x0);
                let border = rescale::convert_direction(&sys, &next, &tangent);
                orientation.units_changed(&sys, &next);
                sys = next;
                ws = sys.workspace();
                solver = make_solver(&sys, &settings.continuation, kind)?;
                solver
                    .factor(&sys, &x0, &border)
                    .map_err(|e| in_branch(e, b + 1))?;
                det.units_changed();
                orientation.continue_along(border);
            }
            None => orientation.continue_along(tangent),
        }
    }
    Ok(())
}

/// The error that stops a run at a broken turn (fold_guard.rs).
fn turned_back(turn: &BrokenTurn) -> Error {
    Error::numerical(format!(
        "the branch turns back in ENERGIE at {:.6e} J (FREQUENCE {:.6e} Hz) where its contact \
         law holds in time only to {:.3e} x RIGI_NOR*JEU (column ECART_LOI_CHOC) > {:.1}: the \
         force series no longer tells contact from clearance, and past the turn the branch \
         follows a root of the truncated harmonic balance, not a motion (a family turns back \
         at an internal resonance with its law held); the rows after the turn were not stored",
        turn.energy, turn.frequency, turn.defect, CLEARANCE_DEFECT
    ))
    .setting(Setting::HarmNonl)
    .hint(
        "raise NB_HARM_NONL (the rows near the turn are the least accurate: their contact law \
         is the least resolved), or stop the continuation below that ENERGIE",
    )
}
