//! Newton correction of a point: [L_t(X); tᵀ] δ = (−R(X), 0), the border t fixing the
//! position along the branch (correction orthogonal to t).

use crate::nnm::continuation::anm::norm;
use crate::nnm::error::{Error, Result, Setting};
use crate::nnm::model::system::System;
use crate::nnm::model::workspace::Workspace;
use crate::nnm::solve::linear_solver::TangentSolver;

/// ‖R(X)‖ / max(1, ‖X‖), scaled units: the residual we report (RESIDU) and test against
/// PREC_NEWTON. Relative to the point's size because round-off in the quadratic terms
/// grows like ε‖X‖², which an absolute threshold cannot beat far up a branch.
pub fn relative(r: &[f64], x: &[f64]) -> f64 {
    norm(r) / norm(x).max(1.0)
}

/// Margin of [`roundoff_floor`] over [`stiffness_roundoff`]. Measured where corrections
/// stall at round-off (instrumented runs of 2026-12-07: every MODE_NON_LINE file of testcases/, the
/// bench's POU_D_E bars of 26 to 2 501 elements and its 15-span bar of 1 024): at 0.05 to
/// 1.06 times ε‖|K||U|‖/max(1, ‖X‖), so ten covers them. It was 10³ before, which let a
/// correction that had converged to a wrong point and stalled there (a start deep into a
/// stiff contact on a 200-element beam: RESIDU 3.4e-5, 4.6e3 times ε‖|K||U|‖, 2.4e4 times
/// the observed noise) pass as round-off.
const ROUNDOFF_MARGIN: f64 = 10.0;

/// ε‖|K||U|‖ / max(1, ‖X‖) (componentwise absolute values, units of [`relative`]): what
/// evaluating the stiffness terms K U at `x` may be off by in floating point. It grows
/// with the mesh (the scaled K of a chain grows like n, of a bending beam like n³): a
/// 10⁴-DOF beam's Newton stalls near 2e-8 whatever the iterations. For models whose scaled
/// stiffness is O(1) it is far below any PREC_NEWTON.
pub fn stiffness_roundoff(sys: &System, x: &[f64]) -> f64 {
    f64::EPSILON * sys.stiffness_term_norm(x) / norm(x).max(1.0)
}

/// What the residual of an exact solution may still be from round-off alone, in the units
/// of [`relative`]: [`stiffness_roundoff`] with the margin of [`ROUNDOFF_MARGIN`].
pub fn roundoff_floor(sys: &System, x: &[f64]) -> f64 {
    ROUNDOFF_MARGIN * stiffness_roundoff(sys, x)
}

/// Ulps by which [`observed_noise`] perturbs every unknown.
const NOISE_ULPS: f64 = 4.0;

/// How far above the round-off level a stalled residual may be and still be accepted
/// ([`correct`]): the level is an estimate (one perturbation, not a bound).
const FLOOR_FACTOR: f64 = 10.0;

/// Iterations without halving the residual before a correction counts as stalled.
const STALL_ITERATIONS: usize = 3;

/// The residual's round-off level seen at `x` (units of [`relative`]): R recomputed at `x`
/// with every unknown moved by a few ulps (alternating signs), minus R(x). A solution stored
/// in floating point is uncertain by that much, so no correction can bring the residual
/// below it; it grows with the conditioning of the equations at `x` (a stiff regularised
/// contact law makes the contact rows steep in u), which [`roundoff_floor`] does not see.
pub fn observed_noise(sys: &System, x: &[f64], r: &[f64], ws: &mut Workspace) -> f64 {
    let xp: Vec<f64> = x
        .iter()
        .enumerate()
        .map(|(i, v)| {
            let s = if i % 2 == 0 { 1.0 } else { -1.0 };
            v * (1.0 + s * NOISE_ULPS * f64::EPSILON)
        })
        .collect();
    let rp = sys.residual(&xp, ws);
    let d: Vec<f64> = rp.iter().zip(r).map(|(a, b)| a - b).collect();
    relative(&d, x)
}

/// The outcome of a correction.
#[derive(Clone, Copy, Debug)]
pub struct Correction {
    pub iterations: usize,
    /// Final relative residual (RESIDU).
    pub residual: f64,
    /// Accepted above the target because it had stopped decreasing at the round-off level,
    /// or because the last correction changed X only in its 12th digit (the rules of
    /// [`correct`]); the caller raises an alarm.
    pub at_floor: bool,
}

/// Corrects `x` in place until ‖R‖ ≤ `tol`. Round-off rule (docs/nnm.md): a residual above
/// `tol` is still accepted, flagged `at_floor`, when it has stopped decreasing (not halved
/// over the last [`STALL_ITERATIONS`] iterations, and not above the smallest residual seen
/// by more than a factor 2: a growing residual is a failure) at the level round-off allows:
/// at most [`FLOOR_FACTOR`] × max([`observed_noise`], [`roundoff_floor`]). Below the
/// deterministic floor alone a stalled residual is accepted silently, as before.
pub fn correct(
    sys: &System,
    ws: &mut Workspace,
    solver: &mut dyn TangentSolver,
    x: &mut [f64],
    border: &[f64],
    tol: f64,
    max_iter: usize,
) -> Result<Correction> {
    let mut it = 0;
    let mut history: Vec<f64> = Vec::new();
    let done = |iterations: usize, residual: f64, at_floor: bool| Correction {
        iterations,
        residual,
        at_floor,
    };
    // The iteration's buffers, made once: the residual, the correction (one more entry,
    // the border's row) and the point the step is taken from.
    let mut r = vec![0.0; sys.lay.n_eq()];
    let mut d = vec![0.0; x.len()];
    let mut x_old = x.to_vec();
    loop {
        sys.residual_into(x, &mut r, ws);
        let nr = relative(&r, x);
        if !nr.is_finite() {
            return Err(Error::numerical(format!(
                "the residual is not finite after {it} Newton iteration(s)"
            )));
        }
        if nr <= tol {
            return Ok(done(it, nr, false));
        }
        let previous = history.last().copied().unwrap_or(f64::INFINITY);
        // Stalled (less than halved by the last iteration) at what round-off allows.
        if it > 0 && nr > 0.5 * previous && nr <= roundoff_floor(sys, x) {
            return Ok(done(it, nr, false));
        }
        history.push(nr);
        let stalled = history.len() > STALL_ITERATIONS && {
            let h = &history[history.len() - 1 - STALL_ITERATIONS..];
            let best = history.iter().copied().fold(f64::INFINITY, f64::min);
            nr > 0.5 * h[0] && nr <= 2.0 * best
        };
        if stalled || it >= max_iter {
            let level = observed_noise(sys, x, &r, ws).max(roundoff_floor(sys, x));
            if history.len() > STALL_ITERATIONS && stalled && nr <= FLOOR_FACTOR * level {
                return Ok(done(it, nr, true));
            }
        }
        if it >= max_iter {
            return Err(Error::numerical(format!(
                "Newton correction did not converge: ‖R‖ = {nr:.3e} > PREC_NEWTON = {tol:.1e} after {it} iterations"
            ))
            .setting(Setting::NewtonIterations)
            .hint("lower PREC_MAN (shorter branches), raise ITER_NEWTON_MAXI, or raise NB_HARM_NONL / PARA_REGUL"));
        }
        solver.factor(sys, x, border)?;
        let last = d.len() - 1;
        for (di, v) in d[..last].iter_mut().zip(&r) {
            *di = -v;
        }
        d[last] = 0.0;
        solver.solve(sys, &mut d)?;
        // A correction at the 12th digit of X: what residual remains is round-off in the
        // quadratic terms (it grows like ε‖X‖² far up a branch), not a lack of convergence.
        // Accepted, but flagged when it is still above the target, so that the caller says
        // so (the rows are then as accurate as the arithmetic allows, not to PREC_NEWTON).
        if norm(&d) <= 1e-12 * norm(x).max(1.0) {
            for (xi, di) in x.iter_mut().zip(&d) {
                *xi += di;
            }
            sys.residual_into(x, &mut r, ws);
            let residual = relative(&r, x);
            return Ok(done(it + 1, residual, residual > tol));
        }
        // Full step unless it increases the residual (a start point far from the branch,
        // e.g. a linear mode placed deep into contact): then halve it a few times.
        x_old.copy_from_slice(x);
        let mut step = 1.0;
        for _ in 0..12 {
            for ((xi, xo), di) in x.iter_mut().zip(&x_old).zip(&d) {
                *xi = xo + step * di;
            }
            sys.residual_into(x, &mut r, ws);
            let rn = relative(&r, x);
            if rn.is_finite() && rn < nr {
                break;
            }
            step *= 0.5;
        }
        it += 1;
    }
}

/// The polish of a start point (start.rs): Newton corrections beyond PREC_NEWTON, down to
/// the round-off level ([`correct`] with a zero target ends there: stalled at the floor),
/// within `max_iter` more iterations; when they do not get there the point is left as it
/// was. A start from a linear mode at first contact with a stiff stop passes PREC_NEWTON
/// after one iteration while still off the branch by more than the series' first steps
/// forgive (docs/hard_cases.md, "The grazing start": the continuation then follows a
/// non-physical family); the iterations left cost a few solves once per run. Returns the
/// iterations kept and the final relative residual.
pub fn polish(
    sys: &System,
    ws: &mut Workspace,
    solver: &mut dyn TangentSolver,
    x: &mut [f64],
    border: &[f64],
    max_iter: usize,
) -> Result<(usize, f64)> {
    let before = x.to_vec();
    let residual = relative(&sys.residual(x, ws), x);
    match correct(sys, ws, solver, x, border, 0.0, max_iter) {
        Ok(c) if c.residual <= residual => Ok((c.iterations, c.residual)),
        _ => {
            x.copy_from_slice(&before);
            Ok((0, residual))
        }
    }
}
