//! The sign of the determinant of the bordered tangent from a small minor of its inverse
//! (the reference solver's way; the engine's solver reads it from its own factors).
//!
//! Why a second test beside the geometric-series one (anm.rs): the series sees a simple
//! bifurcation only when its terms happen to line up, which an exactly symmetric system
//! (a pitchfork where a mode localises) does not do: its branch is analytic through the
//! bifurcation. The determinant of the bordered tangent J = [R_X; tᵀ], on the other hand,
//! changes sign at every simple bifurcation point and nowhere else on a regular branch
//! (turning points in energy or frequency are regular points of an arclength continuation).
//!
//! Computing det J directly would need a dense factorisation of the contact blocks (each a
//! convolution operator, (2H_nl+1)² dense per law unknown). A small minor of J⁻¹ carries
//! the same sign information (Jacobi's complementary-minor identity):
//!     det (J⁻¹)_{C,R} = ± det J_{R̄,C̄} / det J,
//! with the sign fixed by the index sets. Take R = the velocity equations, the phase
//! condition and the border row, C = the displacement unknowns, ω and γ. The complement
//! J_{R̄,C̄} (displacement and law equations × velocity and law unknowns) is block-diagonal:
//! −I (U̇ = V) and A_ff, the harmonic balance of each law's derivative with respect to its
//! own unknowns. On the physical root of a regularised law that derivative has a fixed sign
//! at every instant (PLAN: √((u−s)² + 4ηs²/α) > 0; BI_PLAN: 1 − z + 2 f d/(α s²) > 0 with
//! d = u − f/α), so det A_ff keeps its sign along a branch and sign det (J⁻¹)_{C,R} changes
//! exactly where det J does. It costs n·(2H_l+1) + 2 solves with a factorisation already at
//! hand and one dense LU of that size, independent of NB_HARM_NONL. (That is the reference
//! solver's way; the engine's solver takes the sign from its own factors, linear_solver.rs.)

use crate::nnm::error::{Error, Result};
use crate::nnm::model::system::System;
use crate::nnm::solve::condensed_tangent::permutation_sign;
use faer::Mat;

/// Right-hand sides solved at once: bounds the memory to n·COLUMNS_PER_SOLVE values.
const COLUMNS_PER_SOLVE: usize = 256;

/// The rows R of J (velocity equations, phase condition, border) whose columns of J⁻¹ are
/// computed, and the unknowns C (displacements, ω, γ) read from them.
fn minor_indices(sys: &System) -> (Vec<usize>, Vec<usize>) {
    let lay = sys.lay;
    let block = lay.n * lay.n_coef_lin;
    let rows = (lay.v(0)..lay.v(0) + block).chain([lay.n_eq() - 1, lay.n_eq()]);
    let cols = (lay.u(0)..lay.u(0) + block).chain([lay.omega(), lay.gamma()]);
    (rows.collect(), cols.collect())
}

/// Sign (±1) of det (J⁻¹)_{C,R} (see the module doc) from the factorisation `solver` holds,
/// of J = [R_X(x); tᵀ] at the point to test (`solve_block` solves with it). Only its changes along a branch mean anything.
pub fn condensed_det_sign(
    sys: &System,
    solve_block: &dyn Fn(&mut [f64], usize) -> Result<()>,
) -> Result<f64> {
    let n = sys.lay.n_unk;
    let (rows, cols) = minor_indices(sys);
    let m = rows.len();
    let mut minor = Mat::<f64>::zeros(m, m);
    let mut rhs = Vec::with_capacity(n * COLUMNS_PER_SOLVE.min(m));
    for first in (0..m).step_by(COLUMNS_PER_SOLVE) {
        let chunk = &rows[first..(first + COLUMNS_PER_SOLVE).min(m)];
        rhs.clear();
        rhs.resize(n * chunk.len(), 0.0);
        for (c, &row) in chunk.iter().enumerate() {
            rhs[c * n + row] = 1.0;
        }
        solve_block(&mut rhs, chunk.len())?;
        for c in 0..chunk.len() {
            for (r, &unknown) in cols.iter().enumerate() {
                minor[(r, first + c)] = rhs[c * n + unknown];
            }
        }
    }
    dense_det_sign(&minor)
}

/// Sign of the determinant of a square dense matrix, from its partial-pivoting LU.
pub fn dense_det_sign(a: &Mat<f64>) -> Result<f64> {
    let m = a.nrows();
    let lu = a.partial_piv_lu();
    let u = lu.U();
    let mut sign = permutation_sign(lu.P().arrays().0);
    for i in 0..m {
        let d = u[(i, i)];
        if d == 0.0 || !d.is_finite() {
            return Err(Error::numerical(
                "the condensed tangent is singular: the bifurcation test cannot decide",
            ));
        }
        sign *= d.signum();
    }
    Ok(sign)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn dense_sign_matches_closed_form_determinants() {
        // det = 2·3 − 4·5 = −14 (a pivoting swap is needed since |5| > |2|).
        let a = Mat::from_fn(2, 2, |i, j| [[2.0, 4.0], [5.0, 3.0]][i][j]);
        assert_eq!(dense_det_sign(&a).unwrap(), -1.0);
        // A permutation of the identity: a 3-cycle is even, a transposition odd.
        let cyc = Mat::from_fn(3, 3, |i, j| if j == (i + 1) % 3 { 1.0 } else { 0.0 });
        assert_eq!(dense_det_sign(&cyc).unwrap(), 1.0);
        let swap = Mat::from_fn(3, 3, |i, j| {
            let p = [1, 0, 2];
            if j == p[i] {
                1.0
            } else {
                0.0
            }
        });
        assert_eq!(dense_det_sign(&swap).unwrap(), -1.0);
        let singular = Mat::from_fn(2, 2, |i, _| i as f64);
        assert!(dense_det_sign(&singular).is_err());
    }

    #[test]
    fn permutation_parity() {
        assert_eq!(permutation_sign(&[0, 1, 2, 3]), 1.0);
        assert_eq!(permutation_sign(&[1, 0, 2, 3]), -1.0);
        assert_eq!(permutation_sign(&[1, 2, 0, 3]), 1.0);
        assert_eq!(permutation_sign(&[1, 0, 3, 2]), 1.0);
        assert_eq!(permutation_sign(&[3, 0, 1, 2]), -1.0);
    }
}
