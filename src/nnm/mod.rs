//! EHMAN: branches of nonlinear normal modes of M Ü + K U + Pᵀ F = 0 with localised shocks,
//! by harmonic balance and the asymptotic numerical method (design: docs/ehman.md). Pure
//! numerics: physical units in and out, no SQL, no keywords parsing.
//!
//! Conventions the operator glue relies on:
//! - Fourier coefficients are ordered like Code_Aster's output: 0, C1..CH, S1..SH.
//! - `Point::x` is the full unknown vector in physical units, laid out as: U (n DOFs ×
//!   (2H_l+1), DOF after DOF), V (velocities, same layout, m/s), the contact unknowns of each
//!   shock in order (PLAN: f; BI_PLAN: f, z; CERCLE: fx, fy, λ, z; z dimensionless, λ in N/m; each
//!   2H_nl+1 coefficients; forces in N), then ω (rad/s) and γ (1/s, the unfolding
//!   parameter, zero on an exact solution). Without any shock H_nl is taken equal to H_l.
//! - ENERGIE is Code_Aster's (see `energy.rs`); `energy_spread` is our a-posteriori check.
//! - `Settings::direction` (DIR_EVOLUTION): −1 goes forward, +1 backward. From a linear
//!   mode, forward is toward increasing amplitude; backward toward decreasing amplitude
//!   first, through zero and up again along the same orbits half a period later. From a
//!   stored point given its direction of travel ([`StartState::travelling`]), forward goes
//!   on that way and backward turns back. Code_Aster's sign comes from a random bordering
//!   vector; this rule follows the paths of its validation cases (docs/mode_non_line.md).
//! - Branch numbers in reports start at 1.

// The shared `Error` (a contract of the crate) is large; boxing it here would diverge from
// every other module.
#![allow(clippy::result_large_err)]

mod anm;
mod bifurcation;
pub mod budget;
mod contact;
mod dense_lu;
mod energy;
pub mod exact;
mod gmres;
mod law_check;
mod laws;
mod linear_solver;
mod newton;
mod post;
mod quadrature;
mod reduced;
mod resolution;
mod route_timing;
mod series;
pub mod stability;
mod system;
mod toeplitz;

#[cfg(test)]
mod hard_tests;
#[cfg(test)]
mod reference;
#[cfg(test)]
mod solver_tests;
#[cfg(test)]
mod tests;

pub use contact::Method as ContactMethod;
pub use law_check::{contact_law_defect, LAW_DEFECT_ALARM};
pub use linear_solver::{BorderedSolver, SparseLu};
use linear_solver::{ReferenceSolver, StructuredSolver, TangentSolver};
pub use post::{PostProcessor, RowOutputs};
pub use quadrature::{check_degenerate_pair, start_from_mode_pair, QUAD_FREQ_TOL};
pub use resolution::{resolution_warnings, tail_ratio};
pub use route_timing::{contact_route_timings, RouteRow};

use crate::error::{Error, Result};
use faer::sparse::SparseColMat;
use laws::ScaledLaw;
use system::{Scaling, System};

#[derive(Clone, Copy, Debug, PartialEq)]
pub enum ShockLaw {
    Plan,
    BiPlan,
    Cercle { origin: [f64; 2] },
}

#[derive(Clone, Debug)]
pub struct Shock {
    pub law: ShockLaw,
    /// 1 index into the reduced DOFs for PLAN/BI_PLAN (obstacle on the + side for PLAN),
    /// 2 for CERCLE.
    pub dofs: Vec<usize>,
    /// JEU.
    pub gap: f64,
    /// RIGI_NOR.
    pub stiffness: f64,
    /// PARA_REGUL, dimensionless as in Code_Aster (η_phys = PARA_REGUL·k_ref·JEU²).
    pub regul: f64,
}

#[derive(Clone, Debug)]
pub struct Problem {
    /// Stiffness and mass reduced to the free DOFs, n×n.
    pub k: SparseColMat<usize, f64>,
    pub m: SparseColMat<usize, f64>,
    pub shocks: Vec<Shock>,
}

#[derive(Clone, Debug)]
pub struct Settings {
    pub h_lin: usize,
    pub h_nonl: usize,
    pub n_branches: usize,
    /// NB_PAS_MAN.
    pub n_points_per_branch: usize,
    /// NB_ORDRE_MAN.
    pub order: usize,
    pub prec_man: f64,
    pub prec_newton: f64,
    pub iter_newton_max: usize,
    /// CRIT_ORDR_BIFURCATION.
    pub bif_terms: usize,
    /// RESI_RELA_BIFURCATION.
    pub bif_tol: f64,
    /// TEST_BIFURCATION = 'SERIE_DETERMINANT': also test the sign of the bordered
    /// tangent's determinant at every branch end (bifurcation.rs).
    pub det_test: bool,
    /// DIR_EVOLUTION: −1 forward, +1 backward (module doc).
    pub direction: i32,
}

#[derive(Clone, Debug)]
pub struct Point {
    pub omega: f64,
    /// Hz.
    pub frequency: f64,
    /// Code_Aster's ENERGIE (J).
    pub energy: f64,
    /// Full unknown vector, physical units (layout in the module doc).
    pub x: Vec<f64>,
    /// ‖R(X)‖/max(1, ‖X‖) of the scaled equations.
    pub residual: f64,
    /// Unfolding parameter (1/s).
    pub gamma: f64,
    /// Relative spread of the total energy over one period sampled in time.
    pub energy_spread: f64,
    /// ENERGIE's formula averaged over one period (J; `energy::energy_mean_ca`).
    pub energy_mean: f64,
    pub bifurcation: bool,
    pub branch: usize,
    pub harm_max: usize,
    /// Retries of this branch with a shorter series step before its correction converged
    /// (on the branch's corrected end row; 0 on the others).
    pub step_retries: usize,
    /// The correction was accepted at the round-off floor (newton.rs), not below
    /// PREC_NEWTON.
    pub at_floor: bool,
}

#[derive(Clone, Debug)]
pub struct BranchReport {
    pub branch: usize,
    pub points: usize,
    pub freq_range: (f64, f64),
    pub energy_range: (f64, f64),
    pub a_max: f64,
    pub newton_iterations: usize,
    pub bifurcation: bool,
    /// Retries with a halved step before the correction converged.
    pub step_retries: usize,
    /// The end point was accepted at the round-off floor (newton.rs).
    pub at_floor: bool,
}

/// How the run reacts to a branch that goes wrong; the values come from the catalog
/// (RESOLUTION), the engine's own callers use [`StepControl::none`].
#[derive(Clone, Copy, Debug, Default)]
pub struct StepControl {
    /// A failed correction is retried from the same series with a_max halved, at most
    /// this many times per branch, before the run stops.
    pub retries_max: usize,
    /// Stop with an error when the branch ends of this many consecutive branches stay
    /// within [`STALL_ENERGY`] in energy and [`STALL_FREQUENCY`] in frequency (0: never).
    pub stall_branches: usize,
    /// A branch whose corrected end violates its contact law in time by more than this is
    /// retried like a failed correction, then stops the run (None: not checked). The
    /// defect is ECART_LOI_CHOC ([`contact_law_defect`], in units of RIGI_NOR·JEU) divided
    /// by max(1, the largest law force in those units): the same as ECART_LOI_CHOC up to
    /// the first-contact regime, relative to the force far into a stop.
    pub law_defect_max: Option<f64>,
    /// Likewise for the energy spread over the period (ECART_ENERGIE) of the corrected end.
    pub spread_max: Option<f64>,
}

/// Relative spread of ENERGIE over the window of [`StepControl::stall_branches`] below which
/// a run counts as making no progress.
pub const STALL_ENERGY: f64 = 1.0e-2;
/// Relative spread of FREQUENCE over that window, likewise.
pub const STALL_FREQUENCY: f64 = 1.0e-3;

impl StepControl {
    /// No retry: a failed correction stops the run.
    pub fn none() -> StepControl {
        StepControl {
            retries_max: 0,
            stall_branches: 0,
            law_defect_max: None,
            spread_max: None,
        }
    }
}

/// How the bordered tangent is solved (linear_solver.rs). Results agree to round-off; the
/// engine uses `Structured`, the others are for tests and the bench.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum SolverKind {
    /// Schur complements of the contact blocks (route per shock by the cost model), V
    /// eliminated, one sparse LU of the reduced system.
    #[default]
    Structured,
    /// As `Structured` with every contact block on the given route.
    StructuredWith(ContactMethod),
    /// The whole tangent in one sparse LU, the determinant test from a dense minor of its
    /// inverse (the engine before issue 9).
    Reference,
}

fn make_solver(
    sys: &System,
    settings: &Settings,
    kind: SolverKind,
) -> Result<Box<dyn TangentSolver>> {
    let solves = linear_solver::solves_per_factorisation(settings.order);
    Ok(match kind {
        SolverKind::Structured => Box::new(StructuredSolver::new(sys, solves, None)?),
        SolverKind::StructuredWith(m) => Box::new(StructuredSolver::new(sys, solves, Some(m))?),
        SolverKind::Reference => Box::new(ReferenceSolver::default()),
    })
}

/// A corrected point to continue from.
#[derive(Clone, Debug)]
pub struct StartState {
    /// The direction the stored branch travelled at the start point (physical units, the
    /// layout of `x`); None from linear modes.
    travel: Option<Vec<f64>>,
    x: Vec<f64>,
    scaling: Scaling,
    ref_dof: usize,
    border: Vec<f64>,
    /// The corrected start point (physical units).
    pub point: Point,
    pub newton_iterations: usize,
    /// The solver the continuation uses (and the start used).
    pub solver: SolverKind,
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

/// Forward (DIR_EVOLUTION = −1) from a linear mode: the motion grows along `x1`, measured
/// by its time-averaged ½uᵀKu + ½vᵀMv (the energy norm of the orbit). Counting only the
/// harmonic amplitudes, without the mean, is not enough: at first contact with a very
/// stiff stop the harmonics can grow while the orbit's energy falls (the mean backs off the
/// stop), which is not what "toward increasing amplitude" means to a user reading ENERGIE.
fn motion_grows(sys: &System, x0: &[f64], x1: &[f64]) -> bool {
    // The measure is quadratic in X: the centred difference with step 1 is exact.
    let plus: Vec<f64> = x0.iter().zip(x1).map(|(a, c)| a + c).collect();
    let minus: Vec<f64> = x0.iter().zip(x1).map(|(a, c)| a - c).collect();
    energy::mean_quadratic_energy(sys, &plus) > energy::mean_quadratic_energy(sys, &minus)
}

pub struct Outcome {
    pub points: Vec<Point>,
    /// A failed correction (or any numerical failure) stops the run; the points computed
    /// before it are kept.
    pub error: Option<Error>,
}

/// One period sampled in time, physical units.
#[derive(Clone, Debug)]
pub struct TimeHistory {
    pub t: Vec<f64>,
    /// Per DOF, per instant.
    pub displacement: Vec<Vec<f64>>,
    pub velocity: Vec<Vec<f64>>,
    /// Per shock, per component (PLAN/BI_PLAN: 1, CERCLE: x and y), per instant.
    pub contact_force: Vec<Vec<Vec<f64>>>,
}

/// Physical value of each unknown per scaled unit.
fn unit_factors(sys: &System) -> Vec<f64> {
    let l = sys.lay;
    let sc = sys.sc;
    let force = sc.stiffness * sc.length;
    let mut f = vec![sc.length; l.n * l.n_coef_lin];
    f.extend(std::iter::repeat_n(
        sc.length * sc.omega,
        l.n * l.n_coef_lin,
    ));
    for sh in &sys.shocks {
        let per: &[f64] = match sh.law {
            ScaledLaw::Plan => &[force],
            ScaledLaw::BiPlan => &[force, 1.0],
            ScaledLaw::Cercle { .. } => &[force, force, sc.stiffness, 1.0],
        };
        for &u in per {
            f.extend(std::iter::repeat_n(u, l.n_coef_nonl));
        }
    }
    f.extend([sc.omega, sc.omega]);
    f
}

fn finite(v: &[f64]) -> bool {
    v.iter().all(|x| x.is_finite())
}

fn in_branch(mut e: Error, b: usize) -> Error {
    e.message = format!("branch {b}: {}", e.message);
    e
}

/// Samples of the contact unknowns consistent with the displacements of `x` (scaled).
fn init_contact(sys: &System, x: &mut [f64]) -> Result<()> {
    let l = sys.lay;
    let smp = sys.sampler();
    let ns = smp.n();
    for sh in &sys.shocks {
        let u: Vec<Vec<f64>> = sh
            .dofs
            .iter()
            .map(|&d| {
                let mut s = vec![0.0; ns];
                smp.synth(&x[l.u(d)..l.u(d) + l.n_coef_lin], l.h_lin, &mut s);
                s
            })
            .collect();
        let own = laws::own_from_u(sh.law, sh.gap, sh.alpha, sh.eta, &u)?;
        for (v, mut s) in own.into_iter().enumerate() {
            let o = sh.offset + v * l.n_coef_nonl;
            smp.analyse(&mut s, l.h_nonl, &mut x[o..o + l.n_coef_nonl]);
        }
    }
    Ok(())
}

/// The border guess at a start point: its displacement and velocity part (the branch
/// leaves a point mostly by scaling its motion).
fn motion_border(sys: &System, x: &[f64]) -> Vec<f64> {
    let l = sys.lay;
    let mut b = vec![0.0; l.n_unk];
    b[..2 * l.n * l.n_coef_lin].copy_from_slice(&x[..2 * l.n * l.n_coef_lin]);
    let n = anm::norm(&b);
    b.iter_mut().for_each(|v| *v /= n);
    b
}

fn make_point(sys: &System, x: &[f64], residual: f64, branch: usize, bifurcation: bool) -> Point {
    let l = sys.lay;
    let sc = sys.sc;
    let e_scale = sc.stiffness * sc.length * sc.length;
    let energy = energy::energy_ca(sys, x);
    let omega = x[l.omega()] * sc.omega;
    let xp: Vec<f64> = x
        .iter()
        .zip(unit_factors(sys))
        .map(|(v, f)| v * f)
        .collect();
    Point {
        omega,
        frequency: omega / (2.0 * std::f64::consts::PI),
        energy: energy * e_scale,
        x: xp,
        residual,
        gamma: x[l.gamma()] * sc.omega,
        energy_spread: energy::energy_spread(sys, x, energy),
        energy_mean: energy::energy_mean_ca(sys, x) * e_scale,
        bifurcation,
        branch,
        harm_max: energy::harm_max(sys, x),
        step_retries: 0,
        at_floor: false,
    }
}

fn start(
    sys: System,
    settings: &Settings,
    mut x: Vec<f64>,
    kind: SolverKind,
) -> Result<StartState> {
    if !finite(&x) {
        return Err(Error::numerical("the start point is not finite"));
    }
    let border = motion_border(&sys, &x);
    if !finite(&border) {
        return Err(
            Error::input("the start point has no motion (all displacements are zero)")
                .keyword("ETAT_INIT"),
        );
    }
    let mut solver = make_solver(&sys, settings, kind)?;
    let corr = newton::correct(
        &sys,
        solver.as_mut(),
        &mut x,
        &border,
        settings.prec_newton,
        settings.iter_newton_max,
    )
    .map_err(|e| Error {
        message: format!("start point: {}", e.message),
        ..e
    })?;
    let it = corr.iterations;
    let mut point = make_point(&sys, &x, corr.residual, 0, false);
    point.at_floor = corr.at_floor;
    Ok(StartState {
        travel: None,
        border: motion_border(&sys, &x),
        x,
        scaling: sys.sc,
        ref_dof: sys.ref_dof,
        point,
        newton_iterations: it,
        solver: kind,
    })
}

/// The DOF whose velocity is zero at t = 0: the first free DOF as in Code_Aster (so that
/// ENERGIE, taken at ωt = π/2, is evaluated at the same instant of the motion), unless it
/// barely moves in the mode (the condition would then be degenerate): then the DOF that
/// moves most.
fn phase_dof(amplitudes: &[f64]) -> usize {
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
    modes: &[(&[f64], &str)],
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
            .keyword(format!("ETAT_INIT/{key}")));
        }
    }
    if !(coef_ampl.is_finite() && coef_ampl > 0.0) {
        return Err(
            Error::input(format!("COEF_AMPL must be positive, got {coef_ampl}"))
                .keyword("ETAT_INIT/COEF_AMPL"),
        );
    }
    if !(omega_lin.is_finite() && omega_lin > 0.0) {
        return Err(Error::input(format!(
            "the linear pulsation must be positive, got {omega_lin}"
        ))
        .keyword("ETAT_INIT/NUME_ORDRE"));
    }
    Ok(n)
}

/// Start from a linear mode (largest component 1) scaled by `coef_ampl` as Code_Aster does:
/// with shocks the scaled displacement is coef_ampl·mode, so COEF_AMPL = 1 gives an
/// amplitude equal to the largest JEU; without shocks the physical amplitude is
/// coef_ampl·mode. The contact unknowns follow from their laws; the point is then
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
        &[(mode, "NUME_ORDRE")],
        coef_ampl,
        omega_lin,
    )?;
    let p = (0..n)
        .max_by(|&a, &b| mode[a].abs().total_cmp(&mode[b].abs()))
        .unwrap_or(0);
    let mp = mode[p].abs();
    if mp == 0.0 {
        return Err(Error::input("the linear mode is zero").keyword("ETAT_INIT/NUME_ORDRE"));
    }
    let sc = Scaling::new(problem, coef_ampl * mp, p)?;
    let sys = System::new(problem, settings, sc, phase_dof(mode))?;
    let l = sys.lay;
    let phys_per_coef = if problem.shocks.is_empty() {
        1.0
    } else {
        sc.length
    };
    let om = omega_lin / sc.omega;
    let mut x = vec![0.0; l.n_unk];
    for i in 0..n {
        let u = coef_ampl * mode[i] * phys_per_coef / sc.length;
        x[l.u(i) + series::ic(1)] = u;
        x[l.v(i) + series::is(l.h_lin, 1)] = -om * u;
    }
    x[l.omega()] = om;
    init_contact(&sys, &mut x)?;
    start(sys, settings, x, kind)
}

/// Number of unknowns of `x` for this problem and these settings.
pub fn unknown_count(problem: &Problem, settings: &Settings) -> usize {
    system::Layout::of(problem, settings).0.n_unk
}

/// Scaling and reference DOF for a stored physical point.
fn system_for_point(problem: &Problem, settings: &Settings, x: &[f64]) -> Result<System> {
    post::Unknowns::new(problem, settings)?.check(x)?;
    let n = problem.k.nrows();
    let nl = series::len(settings.h_lin);
    let amp = |i: usize| x[i * nl + series::ic(1)].hypot(x[i * nl + series::is(settings.h_lin, 1)]);
    let p = (0..n)
        .max_by(|&a, &b| amp(a).total_cmp(&amp(b)))
        .unwrap_or(0);
    let sc = Scaling::new(problem, amp(p), p)?;
    let amps: Vec<f64> = (0..n).map(amp).collect();
    System::new(problem, settings, sc, phase_dof(&amps))
}

fn to_scaled(sys: &System, x: &[f64]) -> Vec<f64> {
    x.iter()
        .zip(unit_factors(sys))
        .map(|(v, f)| v / f)
        .collect()
}

/// Restart from a stored point (physical `Point::x`), Newton-corrected.
pub fn start_from_point(problem: &Problem, settings: &Settings, x: &[f64]) -> Result<StartState> {
    let sys = system_for_point(problem, settings, x)?;
    let xs = to_scaled(&sys, x);
    start(sys, settings, xs, SolverKind::default())
}

/// Continue `settings.n_branches` branches from `start`; `on_branch` is called after each.
pub fn continue_branches(
    problem: &Problem,
    settings: &Settings,
    start: StartState,
    on_branch: &mut dyn FnMut(&BranchReport, &[Point]),
) -> Outcome {
    continue_while(problem, settings, start, &mut |r, p| {
        on_branch(r, p);
        true
    })
}

/// As [`continue_branches`], but stops after the first branch for which `on_branch` returns
/// false (e.g. once the energy has passed a bound); at most `settings.n_branches` branches.
pub fn continue_while(
    problem: &Problem,
    settings: &Settings,
    start: StartState,
    on_branch: &mut dyn FnMut(&BranchReport, &[Point]) -> bool,
) -> Outcome {
    continue_controlled(problem, settings, StepControl::none(), start, on_branch)
}

/// As [`continue_while`], with `control` deciding what happens to a branch that fails.
pub fn continue_controlled(
    problem: &Problem,
    settings: &Settings,
    control: StepControl,
    start: StartState,
    on_branch: &mut dyn FnMut(&BranchReport, &[Point]) -> bool,
) -> Outcome {
    let mut points = Vec::new();
    let error = run(problem, settings, control, start, on_branch, &mut points).err();
    Outcome { points, error }
}

fn run(
    problem: &Problem,
    settings: &Settings,
    control: StepControl,
    st: StartState,
    on_branch: &mut dyn FnMut(&BranchReport, &[Point]) -> bool,
    out: &mut Vec<Point>,
) -> Result<()> {
    let sys = System::new(problem, settings, st.scaling, st.ref_dof)?;
    if st.x.len() != sys.lay.n_unk {
        return Err(Error::internal("start state does not match the problem"));
    }
    let params = anm::AnmParams {
        order: settings.order,
        prec: settings.prec_man,
        bif_terms: settings.bif_terms,
        bif_tol: settings.bif_tol,
    };
    let mut solver = make_solver(&sys, settings, st.solver)?;
    // A second factorisation for the points inside a branch where the bifurcation test
    // looks for the sign change (the main one holds the next branch's tangent then); made
    // when first needed.
    let mut probe: Option<Box<dyn TangentSolver>> = None;
    // The contact law checked in time at every branch end, when asked for (StepControl).
    let law_check = match control.law_defect_max {
        Some(_) if !problem.shocks.is_empty() => Some(PostProcessor::new(problem, settings)?),
        _ => None,
    };
    let mut x0 = st.x;
    let border = st.border;
    solver
        .factor(&sys, &x0, &border)
        .map_err(|e| in_branch(e, 1))?;
    let det_sign_at = |solver: &mut dyn TangentSolver| {
        if settings.det_test {
            solver.det_sign(&sys).ok()
        } else {
            None
        }
    };
    let mut det_sign = det_sign_at(solver.as_mut());
    let mut prev_tangent: Option<Vec<f64>> = None;
    // DIR_EVOLUTION (module doc): −1 forward, +1 backward.
    let forward = settings.direction < 0;
    let travel: Option<Vec<f64>> = st.travel.map(|t| {
        t.iter()
            .zip(unit_factors(&sys))
            .map(|(v, f)| v / f)
            .collect()
    });
    // (energy, frequency) of every branch end, for the no-progress guard.
    let mut ends: Vec<(f64, f64)> = Vec::new();
    for b in 1..=settings.n_branches {
        let orient = |x1: &[f64]| -> f64 {
            let ahead = match (&prev_tangent, &travel) {
                (Some(t), _) => return if anm::dot(x1, t) < 0.0 { -1.0 } else { 1.0 },
                (None, Some(t)) => anm::dot(x1, t) > 0.0,
                (None, None) => motion_grows(&sys, &x0, x1),
            };
            if ahead == forward {
                1.0
            } else {
                -1.0
            }
        };
        let mut ser = anm::compute(&sys, solver.as_mut(), &x0, &params, &orient)
            .map_err(|e| in_branch(e, b))?;
        if b == 1 && anm::dot(&ser.terms[0], &border) < 0.0 {
            // The start was factorised with the motion as border, the branch leaves against
            // it: det [R_X; bᵀ] = (b·t)·det [R_X; tᵀ], so the start's sign flips with it (or
            // a backward start would be flagged as a bifurcation).
            det_sign = det_sign.map(|s| -s);
        }
        // Safeguard: the step-length estimate assumes the series converges at a_max; where it
        // does not (nearly homogeneous regimes far up a branch, where the estimate grows
        // without bound), the end residual says so: halve the step until it is credible.
        let credible = 1e3 * settings.prec_man.max(settings.prec_newton);
        for _ in 0..40 {
            let xe = ser.eval(&x0, ser.a_max);
            let r = newton::relative(&sys.residual(&xe), &xe);
            if r.is_finite() && r <= credible.max(newton::roundoff_floor(&sys, &xe)) {
                break;
            }
            ser.a_max *= 0.5;
        }
        let np = settings.n_points_per_branch;
        // A failed correction is retried from the same series with a_max halved (the series
        // is more accurate closer to its origin), at most `control.retries_max` times.
        let mut step_retries = 0;
        let (mut branch_points, x_end, newton_iterations, tangent) = loop {
            let attempt = branch_points_of(&sys, solver.as_mut(), settings, &ser, &x0, b)?
                .and_then(|done| {
                    match done.0.last() {
                        Some(end) => off_the_law(&control, law_check.as_ref(), end)?,
                        None => None,
                    }
                    .map_or(Ok(done), Err)
                });
            match attempt {
                Ok(done) => break done,
                Err(_) if step_retries < control.retries_max => {
                    step_retries += 1;
                    ser.a_max *= 0.5;
                }
                Err(e) if step_retries > 0 => {
                    let e = Error {
                        message: format!(
                            "{} (also with the series step halved {step_retries} times, a_max = {:.3e})",
                            e.message, ser.a_max
                        ),
                        ..e
                    };
                    return Err(in_branch(e, b));
                }
                Err(e) => return Err(in_branch(e, b)),
            }
        };
        if let Some(p) = branch_points.last_mut() {
            p.step_retries = step_retries;
        }
        let at_floor = branch_points.last().is_some_and(|p| p.at_floor);
        if let Some(p) = branch_points.last() {
            ends.push((p.energy, p.frequency));
        }
        let stalled = no_progress(&ends, control.stall_branches);
        // NB_PAS_MAN ≥ 1 (system::validate): the last point is the corrected end.
        let x_start = std::mem::replace(&mut x0, x_end);
        // The next branch starts from the corrected end point with this branch's end tangent
        // as border: factor that tangent now, and compare the sign of its determinant with
        // the one at the start of this branch. A failure belongs to the next branch: this
        // one is reported first.
        let last = b == settings.n_branches;
        let end_factor = if last && !settings.det_test {
            Ok(())
        } else {
            solver.factor(&sys, &x0, &tangent)
        };
        let end_sign = match end_factor {
            Ok(()) => det_sign_at(solver.as_mut()),
            Err(_) => None,
        };
        if let (Some(s0), Some(s1)) = (det_sign, end_sign) {
            if s0 != s1 {
                let probe = match &mut probe {
                    Some(p) => p,
                    None => probe.insert(make_solver(&sys, settings, st.solver)?),
                };
                let row = first_row_past_sign_change(&sys, probe.as_mut(), &ser, &x_start, np, s1);
                if let Some(p) = branch_points.get_mut(row - 1) {
                    p.bifurcation = true;
                }
            }
        }
        det_sign = end_sign;
        let range = |f: &dyn Fn(&Point) -> f64| {
            branch_points
                .iter()
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), p| {
                    (lo.min(f(p)), hi.max(f(p)))
                })
        };
        let report = BranchReport {
            branch: b,
            points: branch_points.len(),
            freq_range: range(&|p| p.frequency),
            energy_range: range(&|p| p.energy),
            a_max: ser.a_max,
            newton_iterations,
            bifurcation: branch_points.iter().any(|p| p.bifurcation),
            step_retries,
            at_floor,
        };
        let go_on = on_branch(&report, &branch_points);
        out.extend(branch_points);
        if !go_on || last {
            break;
        }
        if let Some((e, f)) = stalled {
            let w = control.stall_branches;
            return Err(in_branch(
                Error::numerical(format!(
                    "no progress over the last {w} branches: ENERGIE stayed within {:.0} % of {e:.6e} \
                     and FREQUENCE within {:.1} % of {f:.6e} Hz (a_max = {:.3e})",
                    100.0 * STALL_ENERGY,
                    100.0 * STALL_FREQUENCY,
                    ser.a_max
                ))
                .keyword("RESOLUTION/NB_BRANCHE_SANS_PROGRES")
                .hint(
                    "the series steps have collapsed (typically at the onset of a stiff contact, or far up a \
                     nearly homogeneous branch where round-off dominates): if the branch has reached what you \
                     need, bound the run with ENER_MAX, FREQ_MAX or DEPL_MAX; otherwise raise PARA_REGUL, \
                     NB_HARM_LINE, or lower PREC_MAN",
                ),
                b,
            ));
        }
        end_factor.map_err(|e| in_branch(e, b + 1))?;
        prev_tangent = Some(tangent);
    }
    Ok(())
}

/// Why a corrected branch end is not a point of the physical family although its residual
/// converged, if it is not (StepControl::law_defect_max, spread_max): the error a retry
/// with a shorter step may cure, else the one that stops the run.
fn off_the_law(
    control: &StepControl,
    law_check: Option<&PostProcessor>,
    end: &Point,
) -> Result<Option<Error>> {
    if let (Some(max), Some(check)) = (control.law_defect_max, law_check) {
        let defect = check.relative_law_defect(&end.x)?;
        if defect.is_nan() || defect > max {
            return Ok(Some(
                Error::numerical(format!(
                    "the branch end satisfies its contact law in time only to {defect:.3e} x \
                     max(RIGI_NOR*JEU, largest contact force) > ECART_LOI_CHOC_MAXI = {max:.3e} \
                     (ENERGIE = {:.6e}, FREQUENCE = {:.6e} Hz): the branch has left the physical \
                     root of the regularised law (a converged solution of the harmonic balance \
                     that is not a motion of the system)",
                    end.energy, end.frequency
                ))
                .keyword("RESOLUTION/ECART_LOI_CHOC_MAXI")
                .hint(
                    "lower PREC_MAN (1e-9 or below: shorter series steps do not jump across to \
                     the other root of the law), raise PARA_REGUL, or raise NB_HARM_NONL",
                ),
            ));
        }
    }
    if let Some(max) = control.spread_max {
        let spread = end.energy_spread;
        if spread.is_nan() || spread > max {
            return Ok(Some(
                Error::numerical(format!(
                    "the energy of the branch end varies over the period by ECART_ENERGIE = \
                     {spread:.3e} > ECART_ENERGIE_MAXI = {max:.3e} (ENERGIE = {:.6e}, FREQUENCE \
                     = {:.6e} Hz): the point is not a periodic orbit of the system to that \
                     accuracy",
                    end.energy, end.frequency
                ))
                .keyword("RESOLUTION/ECART_ENERGIE_MAXI")
                .hint(
                    "raise NB_HARM_LINE (a stiff stop needs many harmonics of the displacement), \
                     lower PREC_MAN, or raise PARA_REGUL",
                ),
            ));
        }
    }
    Ok(None)
}

/// The window's (energy, frequency) when the last `window` + 1 branch ends all lie within
/// [`STALL_ENERGY`] and [`STALL_FREQUENCY`] of each other (relative spreads).
fn no_progress(ends: &[(f64, f64)], window: usize) -> Option<(f64, f64)> {
    if window == 0 || ends.len() <= window {
        return None;
    }
    let w = &ends[ends.len() - 1 - window..];
    let spread = |f: &dyn Fn(&(f64, f64)) -> f64| {
        let (lo, hi) = w
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), p| {
                (lo.min(f(p)), hi.max(f(p)))
            });
        (hi - lo) / hi.abs().max(f64::MIN_POSITIVE)
    };
    let last = w[w.len() - 1];
    (spread(&|p| p.0) < STALL_ENERGY && spread(&|p| p.1) < STALL_FREQUENCY).then_some(last)
}

/// The points of one branch: the series evaluated at a_max·i/np, the last one corrected.
/// Ok(Err(e)): the correction failed (retryable with a shorter step); Err: anything else.
/// Returns the points, the corrected end, the Newton iterations and the end tangent.
type BranchPoints = (Vec<Point>, Vec<f64>, usize, Vec<f64>);

fn branch_points_of(
    sys: &System,
    solver: &mut dyn TangentSolver,
    settings: &Settings,
    ser: &anm::Series,
    x0: &[f64],
    b: usize,
) -> Result<std::result::Result<BranchPoints, Error>> {
    let np = settings.n_points_per_branch;
    let mut branch_points = Vec::with_capacity(np);
    let mut newton_iterations = 0;
    let tangent = ser.unit_tangent(ser.a_max);
    if !finite(&tangent) {
        return Err(in_branch(
            Error::numerical("the branch tangent is not finite"),
            b,
        ));
    }
    let series_bif = ser
        .bifurcation
        .map(|ab| (((ab / ser.a_max) * np as f64).round() as usize).clamp(1, np));
    let mut x_end = Vec::new();
    for i in 1..=np {
        let a = ser.a_max * i as f64 / np as f64;
        let mut x = ser.eval(x0, a);
        if !finite(&x) {
            return Err(in_branch(
                Error::numerical(format!("the series diverged at a = {a:.3e} (point {i})")),
                b,
            ));
        }
        let mut res = newton::relative(&sys.residual(&x), &x);
        let mut at_floor = false;
        if i == np {
            let corr = match newton::correct(
                sys,
                solver,
                &mut x,
                &tangent,
                settings.prec_newton,
                settings.iter_newton_max,
            ) {
                Ok(c) => c,
                Err(e) => return Ok(Err(e)),
            };
            newton_iterations = corr.iterations;
            res = corr.residual;
            at_floor = corr.at_floor;
            x_end = x.clone();
        }
        let mut p = make_point(sys, &x, res, b, series_bif == Some(i));
        p.at_floor = at_floor;
        if !(p.energy.is_finite() && p.omega.is_finite() && p.energy_spread.is_finite()) {
            return Err(in_branch(
                Error::numerical(format!("energy or frequency not finite at point {i}")),
                b,
            ));
        }
        if p.frequency <= 0.0 {
            // Not a periodic orbit: the series has jumped off the family (a shorter step
            // stays closer to its origin).
            return Ok(Err(Error::numerical(format!(
                "the frequency is not positive at point {i} ({:.6e} Hz): the branch has left the \
                 family of periodic orbits",
                p.frequency
            ))
            .keyword("RESOLUTION/PREC_MAN")
            .hint(
                "lower PREC_MAN (shorter, more accurate branches) or raise PARA_REGUL",
            )));
        }
        branch_points.push(p);
    }
    Ok(Ok((branch_points, x_end, newton_iterations, tangent)))
}

/// The first point of a branch (1-based, among its `np` points) where the bordered tangent's
/// determinant already has the sign `end_sign` of the branch end: the first row past the
/// bifurcation. Points whose test cannot decide count as not yet past it.
fn first_row_past_sign_change(
    sys: &System,
    probe: &mut dyn TangentSolver,
    ser: &anm::Series,
    x_start: &[f64],
    np: usize,
    end_sign: f64,
) -> usize {
    for i in 1..np {
        let a = ser.a_max * i as f64 / np as f64;
        let x = ser.eval(x_start, a);
        let t = ser.unit_tangent(a);
        let sign = probe.factor(sys, &x, &t).and_then(|_| probe.det_sign(sys));
        if sign.ok() == Some(end_sign) {
            return i;
        }
    }
    np
}

/// One period sampled at `n_inst` instants t_j = j·T/(n_inst − 1), j = 0..n_inst−1 (both
/// ends included), physical units.
pub fn time_history(
    problem: &Problem,
    settings: &Settings,
    x: &[f64],
    n_inst: usize,
) -> Result<TimeHistory> {
    let sys = system_for_point(problem, settings, x)?;
    let xs = to_scaled(&sys, x);
    let l = sys.lay;
    let sc = sys.sc;
    let omega = xs[l.omega()] * sc.omega;
    if !(omega.is_finite() && omega > 0.0) || n_inst < 2 {
        return Err(
            Error::input("a time history needs ω > 0 and at least 2 instants").keyword("NB_INST"),
        );
    }
    let th: Vec<f64> = (0..n_inst)
        .map(|j| 2.0 * std::f64::consts::PI * j as f64 / (n_inst - 1) as f64)
        .collect();
    let samp = |s: &[f64], h: usize, f: f64| {
        th.iter()
            .map(|&t| f * series::eval(s, h, t))
            .collect::<Vec<f64>>()
    };
    let displacement = (0..l.n)
        .map(|i| samp(&xs[l.u(i)..l.u(i) + l.n_coef_lin], l.h_lin, sc.length))
        .collect();
    let velocity = (0..l.n)
        .map(|i| {
            samp(
                &xs[l.v(i)..l.v(i) + l.n_coef_lin],
                l.h_lin,
                sc.length * sc.omega,
            )
        })
        .collect();
    let contact_force = sys
        .shocks
        .iter()
        .map(|sh| {
            sh.eqs
                .forces
                .iter()
                .map(|&(_, v)| {
                    samp(
                        &xs[sh.offset + v * l.n_coef_nonl..sh.offset + (v + 1) * l.n_coef_nonl],
                        l.h_nonl,
                        sc.stiffness * sc.length,
                    )
                })
                .collect()
        })
        .collect();
    Ok(TimeHistory {
        t: th.iter().map(|t| t / omega).collect(),
        displacement,
        velocity,
        contact_force,
    })
}

/// Fourier coefficients (0, C1..CH_l, S1..SH_l) of the displacement of each DOF (physical).
/// For many points of one problem, build a [`PostProcessor`] once instead.
/// Instants per harmonic of the displacement at which [`largest_displacement`] samples.
const MAX_SAMPLES_PER_HARMONIC: usize = 8;

/// The largest |u_i(t)| over the DOFs and one period (physical units), sampled at
/// 8·NB_HARM_LINE + 2 instants (the sampled maximum of a sum of H harmonics is within a few
/// per cent of the true one at that density).
pub fn largest_displacement(problem: &Problem, settings: &Settings, x: &[f64]) -> Result<f64> {
    let th = time_history(
        problem,
        settings,
        x,
        MAX_SAMPLES_PER_HARMONIC * settings.h_lin + 2,
    )?;
    Ok(th
        .displacement
        .iter()
        .flatten()
        .fold(0.0f64, |m, u| m.max(u.abs())))
}

pub fn displacement_coefficients(
    problem: &Problem,
    settings: &Settings,
    x: &[f64],
) -> Result<Vec<Vec<f64>>> {
    post::Unknowns::new(problem, settings)?.displacement(x)
}

/// Fourier coefficients of the velocity of each DOF (physical).
pub fn velocity_coefficients(
    problem: &Problem,
    settings: &Settings,
    x: &[f64],
) -> Result<Vec<Vec<f64>>> {
    post::Unknowns::new(problem, settings)?.velocity(x)
}

/// Fourier coefficients (0, C1..CH_nl, S1..SH_nl) of each contact unknown of each shock
/// (PLAN: f; BI_PLAN: f, z; CERCLE: fx, fy, λ, z), physical.
pub fn contact_coefficients(
    problem: &Problem,
    settings: &Settings,
    x: &[f64],
) -> Result<Vec<Vec<Vec<f64>>>> {
    post::Unknowns::new(problem, settings)?.contact(x)
}
