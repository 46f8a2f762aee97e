//! Newton correction of a point: [L_t(X); tᵀ] δ = (−R(X), 0), the border t fixing the
//! position along the branch (correction orthogonal to t).

use super::anm::norm;
use super::linear_solver::TangentSolver;
use super::system::System;
use crate::error::{Error, Result};

/// ‖R(X)‖ / max(1, ‖X‖), scaled units: the residual we report and test against PREC_NEWTON.
/// Relative to the point's size because round-off in the quadratic terms grows like
/// ε‖X‖², which an absolute threshold cannot beat far up a branch.
pub fn relative(r: &[f64], x: &[f64]) -> f64 {
    norm(r) / norm(x).max(1.0)
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
        let nr = relative(&r, x);
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
            return Ok((it + 1, relative(&sys.residual(x), x)));
        }
        // Full step unless it increases the residual (a start point far from the branch,
        // e.g. a linear mode placed deep into contact): then halve it a few times.
        let x_old = x.to_vec();
        let mut step = 1.0;
        for _ in 0..12 {
            for ((xi, xo), di) in x.iter_mut().zip(&x_old).zip(&d) {
                *xi = xo + step * di;
            }
            let rn = relative(&sys.residual(x), x);
            if rn.is_finite() && rn < nr {
                break;
            }
            step *= 0.5;
        }
        it += 1;
    }
}
