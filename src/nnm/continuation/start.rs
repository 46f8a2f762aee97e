//! EHMAN stage 1, the start: a first point of the branch, from a linear mode scaled by
//! COEF_AMPL or from a stored point (ETAT_INIT), Newton-corrected at fixed amplitude
//! (docs/ehman.md §4). The start from a pair of modes in quadrature is quadrature.rs.

use crate::nnm::error::{Error, Result, Setting};
use crate::nnm::model::contact_samples::init_contact;
use crate::nnm::model::point::{finite, make_point, to_scaled};
use crate::nnm::model::problem::Harmonics;
use crate::nnm::model::system::{self, Scaling, System};
use crate::nnm::model::unknowns::Unknowns;
use crate::nnm::model::workspace::Workspace;
use crate::nnm::solve::linear_solver::TangentSolver;
use crate::nnm::solve::solver_kind::{make_solver, SolverKind};
use crate::nnm::{
    continuation::anm, continuation::newton, model::fourier, Continuation, Point, Problem, Settings,
};

/// A corrected point to continue from.
#[derive(Clone, Debug)]
pub struct StartState {
    /// The direction the stored branch travelled at the start point (physical units, the
    /// layout of `x`); None from linear modes.
    pub(in crate::nnm) travel: Option<Vec<f64>>,
    pub(in crate::nnm) x: Vec<f64>,
    pub(in crate::nnm) scaling: Scaling,
    pub(in crate::nnm) ref_dof: usize,
    pub(in crate::nnm) border: Vec<f64>,
    /// The corrected start point (physical units).
    pub point: Point,
    pub newton_iterations: usize,
    /// The solver the continuation uses (and the start used).
    pub solver: SolverKind,
    /// When the start from linear modes could not be corrected at the amplitude asked: the
    /// fraction of it at which it was ([`approach_in_amplitude`]), and why the full
    /// amplitude failed. The caller says so (alarm MODE_NON_LINE_11).
    pub approached: Option<(f64, String)>,
}

impl StartState {
    /// The same start, continued relative to `travel`: the direction (physical units, the
    /// layout of `Point::x`) in which the stored branch was travelling at this point, e.g.
    /// the chord to the next stored row. DIR_EVOLUTION = −1 then goes on that way, +1 turns
    /// back. Only the sign of its projection on the new tangent is used.
    pub fn travelling(mut self, travel: Vec<f64>) -> Result<StartState> {
        if travel.len() != self.x.len() || !finite(&travel) || travel.iter().all(|&v| v == 0.0) {
            return Err(Error::internal(format!(
                "direction of travel: {} finite values, not all zero, expected {}",
                travel.len(),
                self.x.len()
            )));
        }
        self.travel = Some(travel);
        Ok(self)
    }
}

/// The border guess at a start point: its displacement and velocity part (the branch
/// leaves a point mostly by scaling its motion).
pub(in crate::nnm) fn motion_border(sys: &System, x: &[f64]) -> Vec<f64> {
    let lay = sys.lay;
    let mut b = vec![0.0; lay.n_unk];
    b[..2 * lay.n * lay.n_coef_lin].copy_from_slice(&x[..2 * lay.n * lay.n_coef_lin]);
    let n = anm::norm(&b);
    b.iter_mut().for_each(|v| *v /= n);
    b
}

/// Where a start point's guess comes from, which decides how far it is corrected.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(in crate::nnm) enum Guess {
    /// Built from linear modes: corrected to PREC_NEWTON (approached in amplitude when that
    /// fails, [`approach_in_amplitude`]), then polished to the round-off level
    /// ([`newton::polish`]).
    LinearModes,
    /// A stored, already corrected point: corrected to PREC_NEWTON only, so that a restart
    /// continues from exactly the point the first run continued from.
    StoredPoint,
}

pub(in crate::nnm) fn start(
    sys: System,
    settings: &Settings,
    mut x: Vec<f64>,
    kind: SolverKind,
    guess: Guess,
) -> Result<StartState> {
    if !finite(&x) {
        return Err(Error::numerical("the start point is not finite"));
    }
    let border = motion_border(&sys, &x);
    if !finite(&border) {
        return Err(
            Error::input("the start point has no motion (all displacements are zero)")
                .setting(Setting::Start),
        );
    }
    let mut solver = make_solver(&sys, &settings.continuation, kind)?;
    let mut ws = sys.workspace();
    let guess_x = x.clone();
    let mut approached = None;
    let corr = match newton::correct(
        &sys,
        &mut ws,
        solver.as_mut(),
        &mut x,
        &border,
        settings.continuation.prec_newton,
        settings.continuation.iter_newton_max,
    ) {
        Ok(c) => c,
        Err(e) => {
            let approach = match guess {
                Guess::LinearModes => {
                    x.copy_from_slice(&guess_x);
                    approach_in_amplitude(
                        &sys,
                        &mut ws,
                        solver.as_mut(),
                        &settings.continuation,
                        &mut x,
                    )
                }
                Guess::StoredPoint => None,
            };
            match approach {
                Some(a) => {
                    if a.fraction < 1.0 {
                        approached = Some((a.fraction, e.message.clone()));
                    }
                    a.correction
                }
                None => return Err(start_error(e, guess)),
            }
        }
    };
    let (polished, residual) = match guess {
        Guess::LinearModes if !corr.at_floor => newton::polish(
            &sys,
            &mut ws,
            solver.as_mut(),
            &mut x,
            &border,
            settings.continuation.iter_newton_max,
        )?,
        _ => (0, corr.residual),
    };
    let it = corr.iterations + polished;
    let mut point = make_point(&sys, &x, residual, 0, false);
    point.at_floor = corr.at_floor;
    Ok(StartState {
        travel: None,
        border: motion_border(&sys, &x),
        x,
        scaling: sys.scaling,
        ref_dof: sys.ref_dof,
        point,
        newton_iterations: it,
        solver: kind,
        approached,
    })
}

/// The error of a start that could not be corrected at all: from a linear mode the
/// amplitude is the user's choice and the usual cause.
fn start_error(e: Error, guess: Guess) -> Error {
    let mut err = Error {
        message: format!("start point: {}", e.message),
        ..e
    };
    if guess == Guess::LinearModes {
        let usual = err.hint.take();
        err.setting = Some(Setting::StartAmplitude);
        err = err.hint(format!(
            "the start guess is the linear mode scaled by COEF_AMPL (approached from smaller \
             amplitudes too): start at a smaller COEF_AMPL, the continuation then climbs to \
             the higher energies{}",
            usual.map(|h| format!("; else {h}")).unwrap_or_default()
        ));
    }
    err
}

/// Sub-steps of [`approach_in_amplitude`], at most.
const APPROACH_STEPS_MAX: usize = 24;

/// A start corrected by [`approach_in_amplitude`]: at `fraction` (≤ 1) of the amplitude of
/// the guess.
#[derive(Clone, Copy, Debug)]
struct Approach {
    correction: newton::Correction,
    fraction: f64,
}

/// The start at the amplitude of `x` (a linear-mode guess whose Newton correction failed:
/// at or past first contact with a stiff or strongly regularised stop the linear mode can
/// be too far from the orbit) approached from a smaller amplitude: the motion scaled by
/// s = ½ (halved again while that fails), corrected, then s raised toward 1 with each
/// corrected point scaled up as the next guess, the raise halved when a correction fails.
/// The amplitude constraint is the border: each correction keeps the guess's amplitude.
/// `x` is left at the largest amplitude corrected within [`APPROACH_STEPS_MAX`]
/// corrections: the full one, or a fraction of it when the corrections stall on the way
/// (measured on a 200-element cantilever whose mid-span ring is reached at 0.6 of the
/// asked amplitude: every correction past it stalled at RESIDU 1e-6 to 6e-5, where the
/// continuation from below crosses first contact in a few branches). None when not even a
/// smaller amplitude could be corrected (`x` is then unspecified).
fn approach_in_amplitude(
    sys: &System,
    ws: &mut Workspace,
    solver: &mut dyn TangentSolver,
    cont: &Continuation,
    x: &mut [f64],
) -> Option<Approach> {
    let motion = 2 * sys.lay.n * sys.lay.n_coef_lin;
    let target = x.to_vec();
    let at = |s: f64, from: &[f64], s_from: f64, x: &mut [f64]| -> Option<()> {
        x.copy_from_slice(from);
        x[..motion].iter_mut().for_each(|v| *v *= s / s_from);
        init_contact(sys, x).ok()
    };
    let correct = |x: &mut [f64], solver: &mut dyn TangentSolver, ws: &mut Workspace| {
        let border = motion_border(sys, x);
        newton::correct(
            sys,
            ws,
            solver,
            x,
            &border,
            cont.prec_newton,
            cont.iter_newton_max,
        )
        .ok()
    };
    let mut s = 0.5;
    let mut steps = 0;
    // A corrected point below the target amplitude.
    let mut best = loop {
        steps += 1;
        at(s, &target, 1.0, x)?;
        if let Some(c) = correct(x, solver, ws) {
            break c;
        }
        if steps >= APPROACH_STEPS_MAX {
            return None;
        }
        s *= 0.5;
    };
    let mut ds = s.min(1.0 - s);
    let mut from = x.to_vec();
    while steps < APPROACH_STEPS_MAX {
        steps += 1;
        let next = (s + ds).min(1.0);
        if at(next, &from, s, x).is_none() {
            break;
        }
        match correct(x, solver, ws) {
            Some(c) if next == 1.0 => {
                return Some(Approach {
                    correction: c,
                    fraction: 1.0,
                })
            }
            Some(c) => {
                s = next;
                best = c;
                from.copy_from_slice(x);
            }
            None => ds *= 0.5,
        }
    }
    x.copy_from_slice(&from);
    Some(Approach {
        correction: best,
        fraction: s,
    })
}

/// The DOF whose velocity is zero at t = 0: the first free DOF as in Code_Aster (so that
/// ENERGIE, taken at ωt = π/2, is evaluated at the same instant of the motion), unless it
/// barely moves in the mode (the condition would then be degenerate): then the DOF that
/// moves most.
pub(in crate::nnm) fn phase_dof(amplitudes: &[f64]) -> usize {
    let big = amplitudes.iter().fold(0.0f64, |a, b| a.max(b.abs()));
    match amplitudes.first() {
        Some(a) if a.abs() > 1e-3 * big => 0,
        _ => (0..amplitudes.len())
            .max_by(|&a, &b| amplitudes[a].abs().total_cmp(&amplitudes[b].abs()))
            .unwrap_or(0),
    }
}

/// The checks shared by every start from linear modes: problem and settings agree, each
/// mode (with the keyword that chose it) has one finite value per DOF, COEF_AMPL and the
/// linear pulsation are positive. Returns the number of DOFs.
pub(crate) fn check_start(
    problem: &Problem,
    settings: &Settings,
    modes: &[(&[f64], Setting)],
    coef_ampl: f64,
    omega_lin: f64,
) -> Result<usize> {
    system::validate(problem, settings)?;
    let n = problem.k.nrows();
    for (v, key) in modes {
        if v.len() != n || !finite(v) {
            return Err(Error::input(format!(
                "the linear mode has {} finite components, {n} expected",
                v.len()
            ))
            .setting(*key));
        }
    }
    if !(coef_ampl.is_finite() && coef_ampl > 0.0) {
        return Err(
            Error::input(format!("COEF_AMPL must be positive, got {coef_ampl}"))
                .setting(Setting::StartAmplitude),
        );
    }
    if !(omega_lin.is_finite() && omega_lin > 0.0) {
        return Err(Error::input(format!(
            "the linear mode chosen has pulsation {omega_lin}: a rigid-body mode (or not a \
             vibration mode) has no periodic orbits to continue"
        ))
        .setting(Setting::StartMode)
        .hint(
            "start from an elastic mode (frequency above zero): the first NUME_ORDRE after \
             the rigid-body modes, or block the rigid-body motion (AFFE_CHAR_CINE, DDL_IMPO)",
        ));
    }
    Ok(n)
}

/// Start from a linear mode (largest component 1) scaled by `coef_ampl` as Code_Aster does:
/// with shocks the scaled displacement is coef_ampl·mode, so COEF_AMPL = 1 gives an
/// amplitude equal to the largest JEU; without shocks, or with laws that have no JEU (cubic
/// springs only), the physical amplitude is coef_ampl·mode. The contact unknowns follow from their laws; the point is then
/// Newton-corrected at fixed amplitude.
pub fn start_from_mode(
    problem: &Problem,
    settings: &Settings,
    mode: &[f64],
    coef_ampl: f64,
    omega_lin: f64,
) -> Result<StartState> {
    start_from_mode_using(
        problem,
        settings,
        mode,
        coef_ampl,
        omega_lin,
        SolverKind::default(),
    )
}

/// [`start_from_mode`] with the tangent solved by `kind` (continued with it too).
pub fn start_from_mode_using(
    problem: &Problem,
    settings: &Settings,
    mode: &[f64],
    coef_ampl: f64,
    omega_lin: f64,
    kind: SolverKind,
) -> Result<StartState> {
    let n = check_start(
        problem,
        settings,
        &[(mode, Setting::StartMode)],
        coef_ampl,
        omega_lin,
    )?;
    let p = (0..n)
        .max_by(|&a, &b| mode[a].abs().total_cmp(&mode[b].abs()))
        .unwrap_or(0);
    let mp = mode[p].abs();
    if mp == 0.0 {
        return Err(Error::input("the linear mode is zero").setting(Setting::StartMode));
    }
    let scaling = Scaling::new(problem, coef_ampl * mp, p)?;
    let sys = System::new(problem, settings, scaling, phase_dof(mode))?;
    let lay = sys.lay;
    // In units of the largest JEU; without one (no shocks, only cubic springs) in metres.
    let phys_per_coef = if problem.largest_gap().is_none() {
        1.0
    } else {
        scaling.length
    };
    let om = omega_lin / scaling.omega;
    let mut x = vec![0.0; lay.n_unk];
    for i in 0..n {
        let u = coef_ampl * mode[i] * phys_per_coef / scaling.length;
        x[lay.u(i) + fourier::ic(1)] = u;
        x[lay.v(i) + fourier::is(lay.h_lin, 1)] = -om * u;
    }
    x[lay.omega()] = om;
    init_contact(&sys, &mut x)?;
    start(sys, settings, x, kind, Guess::LinearModes)
}

/// Scaling and reference DOF for a stored physical point.
pub(in crate::nnm) fn system_for_point(
    problem: &Problem,
    harmonics: Harmonics,
    x: &[f64],
) -> Result<System> {
    Unknowns::new(problem, harmonics)?.check(x)?;
    let n = problem.k.nrows();
    let nl = fourier::len(harmonics.h_lin);
    let amp =
        |i: usize| x[i * nl + fourier::ic(1)].hypot(x[i * nl + fourier::is(harmonics.h_lin, 1)]);
    let p = (0..n)
        .max_by(|&a, &b| amp(a).total_cmp(&amp(b)))
        .unwrap_or(0);
    let scaling = Scaling::new(problem, amp(p), p)?;
    // A row far up a branch is restarted in the length unit the run had rescaled to
    // (rescale.rs), or its correction would meet the round-off the rescaling avoids.
    let all = crate::nnm::model::rescale::all_rescalable(problem);
    let scaling = crate::nnm::model::rescale::outgrown(&scaling, all, amp(p) / scaling.length)
        .unwrap_or(scaling);
    let amps: Vec<f64> = (0..n).map(amp).collect();
    System::of_harmonics(problem, harmonics, scaling, phase_dof(&amps))
}

/// Restart from a stored point (physical `Point::x`), Newton-corrected.
pub fn start_from_point(problem: &Problem, settings: &Settings, x: &[f64]) -> Result<StartState> {
    // The continuation's settings are checked first, as every start does.
    system::validate(problem, settings)?;
    let sys = system_for_point(problem, settings.into(), x)?;
    let xs = to_scaled(&sys, x);
    start(sys, settings, xs, SolverKind::default(), Guess::StoredPoint)
}
