//! The start of a forced response (REPONSE_FORCEE_NL): the steady state at the low end of
//! the frequency band, Newton-corrected at that fixed frequency from rest, and the
//! direction of increasing frequency the curve leaves along.

use crate::nnm::continuation::newton;
use crate::nnm::continuation::start::StartState;
use crate::nnm::error::{Error, Result, Setting};
use crate::nnm::model::contact_samples::init_contact;
use crate::nnm::model::point::make_point;
use crate::nnm::model::system::{self, Scaling, System};
use crate::nnm::solve::solver_kind::{make_solver, SolverKind};
use crate::nnm::{Problem, Settings};

/// The forced steady state at the pulsation `omega` (rad/s), to continue in increasing
/// frequency (`Continuation::direction` −1) or decreasing (+1). The guess is the structure
/// at rest with the contact unknowns of their laws there: the first Newton iteration is
/// then the linear response with the laws' tangent at rest, the next ones correct the
/// laws. The point is polished to the round-off level, as a start from linear modes is
/// (newton::polish): what the first series starts from is as exact as the arithmetic allows.
pub fn start_forced(problem: &Problem, settings: &Settings, omega: f64) -> Result<StartState> {
    let Some(forcing) = &problem.forcing else {
        return Err(Error::internal(
            "a forced start needs a force and a damping",
        ));
    };
    if !(omega.is_finite() && omega > 0.0) {
        return Err(
            Error::input(format!("the start pulsation must be positive, got {omega}"))
                .setting(Setting::StartFrequency),
        );
    }
    system::validate(problem, settings)?;
    // The DOF the force drives most: the reference DOF, and without a JEU the length unit
    // is its static deflection under that force alone (a unit, not a result).
    let p = (0..forcing.force.len())
        .max_by(|&a, &b| forcing.force[a].abs().total_cmp(&forcing.force[b].abs()))
        .unwrap_or(0);
    let kpp = system::diag(&problem.k, p);
    let unit = forcing.force[p].abs() / kpp.abs();
    let unit = if unit.is_finite() && unit > 0.0 {
        unit
    } else {
        1.0
    };
    let scaling = Scaling::new(problem, unit, p)?;
    let sys = System::new(problem, settings, scaling, p)?;
    let lay = sys.lay;
    let mut x = vec![0.0; lay.n_unk];
    x[lay.omega()] = omega / scaling.omega;
    init_contact(&sys, &mut x)?;
    // The correction keeps ω: the border is the direction of ω alone.
    let mut border = vec![0.0; lay.n_unk];
    border[lay.omega()] = 1.0;
    let kind = SolverKind::Reference;
    let mut solver = make_solver(&sys, &settings.continuation, kind)?;
    let mut ws = sys.workspace();
    let cont = &settings.continuation;
    let corr = newton::correct(
        &sys,
        &mut ws,
        solver.as_mut(),
        &mut x,
        &border,
        cont.prec_newton,
        cont.iter_newton_max,
    )
    .map_err(|e| {
        Error {
            message: format!("start point at FREQ_MIN: {}", e.message),
            ..e
        }
        .setting(Setting::StartFrequency)
        .hint(
            "the start is the steady state at FREQ_MIN, corrected from rest: choose FREQ_MIN \
             below the resonances, where the response is nearly linear",
        )
    })?;
    let (polished, residual) = match corr.at_floor {
        false => newton::polish(
            &sys,
            &mut ws,
            solver.as_mut(),
            &mut x,
            &border,
            cont.iter_newton_max,
        )?,
        true => (0, corr.residual),
    };
    let mut point = make_point(&sys, &x, residual, 0, false);
    point.at_floor = corr.at_floor;
    // The direction of travel in physical units: along ω (only its sign is used).
    let mut travel = vec![0.0; lay.n_unk];
    travel[lay.omega()] = 1.0;
    Ok(StartState {
        travel: Some(travel),
        x,
        scaling,
        ref_dof: p,
        border,
        point,
        newton_iterations: corr.iterations + polished,
        solver: kind,
        approached: None,
    })
}
