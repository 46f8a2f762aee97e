//! The linear modes of the structure, (K, M) solved densely: what the frequency floor and
//! the internal-resonance alarm compare a branch with.

use crate::linalg::eigen::{frequency, solve_modes, EigenOptions, Method, ModeRequest};
use crate::nnm::error::Result;
use crate::nnm::Problem;
use faer::Side;

/// Largest model (free DOFs) whose linear modes are computed densely for the check.
pub const MAX_DENSE_DOFS: usize = 600;
/// A linear mode of (K, M): number (1-based, by increasing frequency), frequency (Hz) and
/// shape on the free DOFs (mass-normalised).
#[derive(Clone, Debug)]
pub struct LinearMode {
    pub number: usize,
    pub frequency: f64,
    pub shape: Vec<f64>,
}

/// Every linear mode of (K, M) by increasing frequency, or None for a model larger than
/// [`MAX_DENSE_DOFS`], whose M is not positive definite (a DOF without mass) or whose
/// eigensolve fails.
pub fn linear_modes(problem: &Problem) -> Result<Option<Vec<LinearMode>>> {
    let n = problem.k.nrows();
    if n > MAX_DENSE_DOFS {
        return Ok(None);
    }
    // A DOF without mass has no linear mode of finite frequency to resonate with: no check.
    if problem.m.to_dense().llt(Side::Lower).is_err() {
        return Ok(None);
    }
    // CALC_MODES's dense solver, in its inverse form (Cholesky of K + δM): the low modes
    // keep their relative accuracy whatever the highest frequency of the model. The direct
    // form L⁻¹KL⁻ᵀ (Cholesky of M) lost it on a reduction basis keeping modes up to 5000
    // times the first: 51.38 Hz for a first mode at 52.05 Hz. Every mode is returned, the
    // least accurate high ones too (the checks compare the branch with the low ones).
    let opts = EigenOptions {
        force: Some(Method::Dense),
        max_residual: f64::INFINITY,
        ..EigenOptions::default()
    };
    // The checks are advice on the branch, not part of it: a solve that fails (a matrix
    // with a NaN) leaves the run without them, as a massless DOF does.
    let Ok(set) = solve_modes(&problem.k, &problem.m, &ModeRequest::Smallest { n }, &opts) else {
        return Ok(None);
    };
    Ok(Some(
        set.omega2
            .iter()
            .zip(set.vectors)
            .enumerate()
            .map(|(i, (&w, shape))| LinearMode {
                number: i + 1,
                frequency: frequency(w),
                shape,
            })
            .collect(),
    ))
}
