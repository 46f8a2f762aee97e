//! EHMAN: branches of nonlinear normal modes of M Ü + K U + Pᵀ F = 0 with localised shocks,
//! by harmonic balance and the asymptotic numerical method (design: ehman.md). Pure
//! numerics: physical units in and out, no SQL, no keywords parsing.
//!
//! Conventions the operator glue relies on:
//! - Fourier coefficients are ordered like Code_Aster's output: 0, C1..CH, S1..SH.
//! - `Point::x` is the full unknown vector in physical units, laid out as: U (n DOFs ×
//!   (2H_l+1), DOF after DOF), V (velocities, same layout, m/s), the contact unknowns of each
//!   shock in order (PLAN: f; BI_PLAN: f, z (dimensionless); CERCLE: f, r, fx, fy; each
//!   2H_nl+1 coefficients; forces in N, r in m), then ω (rad/s) and γ (1/s, the unfolding
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
mod energy;
pub mod exact;
mod law_check;
mod laws;
mod linear_solver;
mod newton;
mod post;
mod quadrature;
mod resolution;
mod series;
pub mod stability;
mod system;

#[cfg(test)]
mod hard_tests;
#[cfg(test)]
mod reference;
#[cfg(test)]
mod tests;

pub use law_check::{contact_law_defect, LAW_DEFECT_ALARM};
pub use linear_solver::{BorderedSolver, SparseLu};
pub use post::{PostProcessor, RowOutputs};
pub use quadrature::{check_degenerate_pair, start_from_mode_pair, QUAD_FREQ_TOL};
pub use resolution::{resolution_warnings, tail_ratio};

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
    pub bifurcation: bool,
    pub branch: usize,
    pub harm_max: usize,
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
    let force = sc.k * sc.g;
    let mut f = vec![sc.g; l.n * l.nl];
    f.extend(std::iter::repeat_n(sc.g * sc.w, l.n * l.nl));
    for sh in &sys.shocks {
        let per: &[f64] = match sh.law {
            ScaledLaw::Plan => &[force],
            ScaledLaw::BiPlan => &[force, 1.0],
            ScaledLaw::Cercle { .. } => &[force, sc.g, force, force],
        };
        for &u in per {
            f.extend(std::iter::repeat_n(u, l.nn));
        }
    }
    f.extend([sc.w, sc.w]);
    f
}

fn finite(v: &[f64]) -> bool {
    v.iter().all(|x| x.is_finite())
}

fn in_branch(mut e: Error, b: usize) -> Error {
    e.message = format!("branch {b}: {}", e.message);
    e
}

/// A ring error naming its shock (CHOC occurrence, 1-based): a model may carry several.
fn ring_error(i: usize, e: Error) -> Error {
    Error {
        message: format!("CHOC {}: {}", i + 1, e.message),
        keyword: Some(format!("CHOC[{}]/ORIG_OBST", i + 1)),
        ..e
    }
}

/// Samples of the contact unknowns consistent with the displacements of `x` (scaled).
fn init_contact(sys: &System, x: &mut [f64]) -> Result<()> {
    let l = sys.lay;
    let smp = sys.sampler();
    let ns = smp.n();
    for (i, sh) in sys.shocks.iter().enumerate() {
        let u: Vec<Vec<f64>> = sh
            .dofs
            .iter()
            .map(|&d| {
                let mut s = vec![0.0; ns];
                smp.synth(&x[l.u(d)..l.u(d) + l.nl], l.hl, &mut s);
                s
            })
            .collect();
        let own = laws::own_from_u(sh.law, sh.s, sh.alpha, sh.eta, &u).map_err(|e| {
            if matches!(sh.law, ScaledLaw::Cercle { .. }) {
                ring_error(i, e)
            } else {
                e
            }
        })?;
        for (v, mut s) in own.into_iter().enumerate() {
            let o = sh.offset + v * l.nn;
            smp.analyse(&mut s, l.hn, &mut x[o..o + l.nn]);
        }
    }
    Ok(())
}

/// CERCLE: r(t) must stay positive and away from the ring centre.
fn check_rings(sys: &System, x: &[f64]) -> Result<()> {
    let l = sys.lay;
    let smp = sys.sampler();
    for (i, sh) in sys.shocks.iter().enumerate() {
        if let ScaledLaw::Cercle { ex, ey } = sh.law {
            let name = |e: Error| ring_error(i, e);
            let mut s = vec![vec![0.0; smp.n()]; 3];
            smp.synth(&x[sh.offset + l.nn..sh.offset + 2 * l.nn], l.hn, &mut s[0]);
            for c in 0..2 {
                let d = sh.dofs[c];
                smp.synth(&x[l.u(d)..l.u(d) + l.nl], l.hl, &mut s[c + 1]);
            }
            // Both the unknown r and the true distance must stay clear of zero.
            laws::check_ring_radius(&s[0], sh.s).map_err(name)?;
            let dist: Vec<f64> = (0..smp.n())
                .map(|j| (s[1][j] - ex).hypot(s[2][j] - ey))
                .collect();
            laws::check_ring_radius(&dist, sh.s).map_err(name)?;
        }
    }
    Ok(())
}

/// The border guess at a start point: its displacement and velocity part (the branch
/// leaves a point mostly by scaling its motion).
fn motion_border(sys: &System, x: &[f64]) -> Vec<f64> {
    let l = sys.lay;
    let mut b = vec![0.0; l.n_unk];
    b[..2 * l.n * l.nl].copy_from_slice(&x[..2 * l.n * l.nl]);
    let n = anm::norm(&b);
    b.iter_mut().for_each(|v| *v /= n);
    b
}

fn make_point(sys: &System, x: &[f64], residual: f64, branch: usize, bifurcation: bool) -> Point {
    let l = sys.lay;
    let sc = sys.sc;
    let e_scale = sc.k * sc.g * sc.g;
    let energy = energy::energy_ca(sys, x);
    let omega = x[l.omega()] * sc.w;
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
        gamma: x[l.gamma()] * sc.w,
        energy_spread: energy::energy_spread(sys, x, energy),
        bifurcation,
        branch,
        harm_max: energy::harm_max(sys, x),
    }
}

fn start(sys: System, settings: &Settings, mut x: Vec<f64>) -> Result<StartState> {
    if !finite(&x) {
        return Err(Error::numerical("the start point is not finite"));
    }
    check_rings(&sys, &x)?;
    let border = motion_border(&sys, &x);
    if !finite(&border) {
        return Err(
            Error::input("the start point has no motion (all displacements are zero)")
                .keyword("ETAT_INIT"),
        );
    }
    let mut solver = SparseLu::default();
    let (it, res) = newton::correct(
        &sys,
        &mut solver,
        &mut x,
        &border,
        settings.prec_newton,
        settings.iter_newton_max,
    )
    .map_err(|e| Error {
        message: format!("start point: {}", e.message),
        ..e
    })?;
    check_rings(&sys, &x)?;
    let point = make_point(&sys, &x, res, 0, false);
    Ok(StartState {
        travel: None,
        border: motion_border(&sys, &x),
        x,
        scaling: sys.sc,
        ref_dof: sys.ref_dof,
        point,
        newton_iterations: it,
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
    let phys_per_coef = if problem.shocks.is_empty() { 1.0 } else { sc.g };
    let om = omega_lin / sc.w;
    let mut x = vec![0.0; l.n_unk];
    for i in 0..n {
        let u = coef_ampl * mode[i] * phys_per_coef / sc.g;
        x[l.u(i) + series::ic(1)] = u;
        x[l.v(i) + series::is(l.hl, 1)] = -om * u;
    }
    x[l.omega()] = om;
    init_contact(&sys, &mut x)?;
    start(sys, settings, x)
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
    start(sys, settings, xs)
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
    let mut points = Vec::new();
    let error = run(problem, settings, start, on_branch, &mut points).err();
    Outcome { points, error }
}

fn run(
    problem: &Problem,
    settings: &Settings,
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
    let mut solver = SparseLu::default();
    // A second factorisation for the points inside a branch where the bifurcation test
    // looks for the sign change (the main one holds the next branch's tangent then).
    let mut probe = SparseLu::default();
    let mut x0 = st.x;
    let border = st.border;
    solver
        .factor(sys.lay.n_unk, &sys.tangent(&x0, &border))
        .map_err(|e| in_branch(e, 1))?;
    let det_sign_at = |solver: &SparseLu| {
        if settings.det_test {
            bifurcation::condensed_det_sign(&sys, solver).ok()
        } else {
            None
        }
    };
    let mut det_sign = det_sign_at(&solver);
    let mut prev_tangent: Option<Vec<f64>> = None;
    // DIR_EVOLUTION (module doc): −1 forward, +1 backward.
    let forward = settings.direction < 0;
    let travel: Option<Vec<f64>> = st.travel.map(|t| {
        t.iter()
            .zip(unit_factors(&sys))
            .map(|(v, f)| v / f)
            .collect()
    });
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
        let mut ser =
            anm::compute(&sys, &mut solver, &x0, &params, &orient).map_err(|e| in_branch(e, b))?;
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
            if r.is_finite() && r <= credible {
                break;
            }
            ser.a_max *= 0.5;
        }
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
        // The corrected end point; x0 stays the series origin until every point is out.
        let mut x_end = Vec::new();
        for i in 1..=np {
            let a = ser.a_max * i as f64 / np as f64;
            let mut x = ser.eval(&x0, a);
            if !finite(&x) {
                return Err(in_branch(
                    Error::numerical(format!("the series diverged at a = {a:.3e} (point {i})")),
                    b,
                ));
            }
            let mut res = newton::relative(&sys.residual(&x), &x);
            if i == np {
                let (it, r) = newton::correct(
                    &sys,
                    &mut solver,
                    &mut x,
                    &tangent,
                    settings.prec_newton,
                    settings.iter_newton_max,
                )
                .map_err(|e| in_branch(e, b))?;
                newton_iterations = it;
                res = r;
                check_rings(&sys, &x).map_err(|e| in_branch(e, b))?;
                x_end = x.clone();
            }
            let p = make_point(&sys, &x, res, b, series_bif == Some(i));
            if !(p.energy.is_finite() && p.omega.is_finite() && p.energy_spread.is_finite()) {
                return Err(in_branch(
                    Error::numerical(format!("energy or frequency not finite at point {i}")),
                    b,
                ));
            }
            branch_points.push(p);
        }
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
            solver.factor(sys.lay.n_unk, &sys.tangent(&x0, &tangent))
        };
        let end_sign = match end_factor {
            Ok(()) => det_sign_at(&solver),
            Err(_) => None,
        };
        if let (Some(s0), Some(s1)) = (det_sign, end_sign) {
            if s0 != s1 {
                let row = first_row_past_sign_change(&sys, &mut probe, &ser, &x_start, np, s1);
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
        };
        let go_on = on_branch(&report, &branch_points);
        out.extend(branch_points);
        if !go_on || last {
            break;
        }
        end_factor.map_err(|e| in_branch(e, b + 1))?;
        prev_tangent = Some(tangent);
    }
    Ok(())
}

/// The first point of a branch (1-based, among its `np` points) where the bordered tangent's
/// determinant already has the sign `end_sign` of the branch end: the first row past the
/// bifurcation. Points whose test cannot decide count as not yet past it.
fn first_row_past_sign_change(
    sys: &System,
    probe: &mut SparseLu,
    ser: &anm::Series,
    x_start: &[f64],
    np: usize,
    end_sign: f64,
) -> usize {
    for i in 1..np {
        let a = ser.a_max * i as f64 / np as f64;
        let x = ser.eval(x_start, a);
        let t = ser.unit_tangent(a);
        let sign = probe
            .factor(sys.lay.n_unk, &sys.tangent(&x, &t))
            .and_then(|_| bifurcation::condensed_det_sign(sys, probe));
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
    let omega = xs[l.omega()] * sc.w;
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
        .map(|i| samp(&xs[l.u(i)..l.u(i) + l.nl], l.hl, sc.g))
        .collect();
    let velocity = (0..l.n)
        .map(|i| samp(&xs[l.v(i)..l.v(i) + l.nl], l.hl, sc.g * sc.w))
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
                        &xs[sh.offset + v * l.nn..sh.offset + (v + 1) * l.nn],
                        l.hn,
                        sc.k * sc.g,
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
/// (PLAN: f; BI_PLAN: f, z; CERCLE: f, r, fx, fy), physical.
pub fn contact_coefficients(
    problem: &Problem,
    settings: &Settings,
    x: &[f64],
) -> Result<Vec<Vec<Vec<f64>>>> {
    post::Unknowns::new(problem, settings)?.contact(x)
}
