//! Newton correction of a point: [L_t(X); tᵀ] δ = (−R(X), 0), the border t fixing the
//! position along the branch (correction orthogonal to t).

use super::anm::norm;
use super::linear_solver::TangentSolver;
use super::system::System;
use crate::error::{Error, Result};

/// ‖R(X)‖ / max(1, ‖X‖, ‖|K||U|‖), scaled units: the residual we report (RESIDU) and test
/// against PREC_NEWTON. Relative to the point's size because round-off in the quadratic
/// terms grows like ε‖X‖², which an absolute threshold cannot beat far up a branch; and
/// relative to the stiffness terms because the round-off of K U is ε‖|K||U|‖, which grows
/// with the mesh (the scaled K of a chain grows like n, of a bending beam like n³: a
/// 10⁴-DOF beam's Newton stalled at 2e-8 with the first two terms alone). For a model
/// whose scaled stiffness is O(1) (one DOF, k_ref = k) ‖|K||U|‖ ≤ ‖X‖ and the measure is the
/// former ‖R‖/max(1, ‖X‖).
pub fn relative(sys: &System, r: &[f64], x: &[f64]) -> f64 {
    norm(r) / norm(x).max(1.0).max(sys.stiffness_term_norm(x))
}

/// Corrects `x` in place until ‖R‖ ≤ `tol`. Returns (iterations, final relative residual).
pub fn correct(
    sys: &System,
    solver: &mut dyn TangentSolver,
    x: &mut [f64],
    border: &[f64],
    tol: f64,
    max_iter: usize,
) -> Result<(usize, f64)> {
    let mut it = 0;
    loop {
        let r = sys.residual(x);
        let nr = relative(sys, &r, x);
        if !nr.is_finite() {
            return Err(Error::numerical(format!(
                "the residual is not finite after {it} Newton iteration(s)"
            )));
        }
        if nr <= tol {
            return Ok((it, nr));
        }
        if it >= max_iter {
            return Err(Error::numerical(format!(
                "Newton correction did not converge: ‖R‖ = {nr:.3e} > PREC_NEWTON = {tol:.1e} after {it} iterations"
            ))
            .keyword("RESOLUTION/ITER_NEWTON_MAXI")
            .hint("lower PREC_MAN (shorter branches), raise ITER_NEWTON_MAXI, or raise NB_HARM_NONL / PARA_REGUL"));
        }
        solver.factor(sys, x, border)?;
        let mut d: Vec<f64> = r.iter().map(|v| -v).collect();
        d.push(0.0);
        solver.solve(sys, &mut d)?;
        // A correction at the 12th digit of X: what residual remains is round-off in the
        // quadratic terms (it grows like ε‖X‖² far up a branch), not a lack of convergence.
        if norm(&d) <= 1e-12 * norm(x).max(1.0) {
            for (xi, di) in x.iter_mut().zip(&d) {
                *xi += di;
            }
            return Ok((it + 1, relative(sys, &sys.residual(x), x)));
        }
        // Full step unless it increases the residual (a start point far from the branch,
        // e.g. a linear mode placed deep into contact): then halve it a few times.
        let x_old = x.to_vec();
        let mut step = 1.0;
        for _ in 0..12 {
            for ((xi, xo), di) in x.iter_mut().zip(&x_old).zip(&d) {
                *xi = xo + step * di;
            }
            let rn = relative(sys, &sys.residual(x), x);
            if rn.is_finite() && rn < nr {
                break;
            }
            step *= 0.5;
        }
        it += 1;
    }
}
