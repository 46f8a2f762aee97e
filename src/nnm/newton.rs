//! Newton correction of a point: [L_t(X); tᵀ] δ = (−R(X), 0), the border t fixing the
//! position along the branch (correction orthogonal to t).

use super::anm::norm;
use super::linear_solver::BorderedSolver;
use super::system::System;
use crate::error::{Error, Result};

/// Corrects `x` in place until ‖R‖ ≤ `tol`. Returns (iterations, final ‖R‖).
pub fn correct(
    sys: &System,
    solver: &mut dyn BorderedSolver,
    x: &mut [f64],
    border: &[f64],
    tol: f64,
    max_iter: usize,
) -> Result<(usize, f64)> {
    let n = sys.lay.n_unk;
    let mut it = 0;
    loop {
        let r = sys.residual(x);
        let nr = norm(&r);
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
        solver.factor(n, &sys.tangent(x, border))?;
        let mut d: Vec<f64> = r.iter().map(|v| -v).collect();
        d.push(0.0);
        solver.solve(&mut d)?;
        for (xi, di) in x.iter_mut().zip(&d) {
            *xi += di;
        }
        it += 1;
    }
}
