//! The linear modes of the structure, (K, M) solved densely: what the frequency floor and
//! the internal-resonance alarm compare a branch with.

use crate::error::{Error, Result};
use crate::nnm::Problem;
use faer::linalg::triangular_solve::{
    solve_lower_triangular_in_place, solve_upper_triangular_in_place,
};
use faer::{Par, Side};

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
/// [`MAX_DENSE_DOFS`] or whose M is not positive definite (a DOF without mass).
pub fn linear_modes(problem: &Problem) -> Result<Option<Vec<LinearMode>>> {
    let n = problem.k.nrows();
    if n > MAX_DENSE_DOFS {
        return Ok(None);
    }
    let kd = problem.k.to_dense();
    let md = problem.m.to_dense();
    // A DOF without mass has no linear mode of finite frequency to resonate with: no check.
    let Ok(llt) = md.llt(Side::Lower) else {
        return Ok(None);
    };
    let l = llt.L();
    // C = L⁻¹ K L⁻ᵀ (symmetric; only its lower triangle is read).
    let mut x = kd.clone();
    solve_lower_triangular_in_place(l, x.as_mut(), Par::Seq);
    let mut c = x.transpose().to_owned();
    solve_lower_triangular_in_place(l, c.as_mut(), Par::Seq);
    let eig = c
        .self_adjoint_eigen(Side::Lower)
        .map_err(|e| Error::numerical(format!("dense eigensolver failed: {e:?}")))?;
    let mut y = eig.U().to_owned();
    solve_upper_triangular_in_place(l.transpose(), y.as_mut(), Par::Seq);
    let mut modes: Vec<LinearMode> = (0..n)
        .map(|i| LinearMode {
            number: 0,
            frequency: eig.S()[i].max(0.0).sqrt() / (2.0 * std::f64::consts::PI),
            shape: y.col_as_slice(i).to_vec(),
        })
        .collect();
    modes.sort_by(|a, b| a.frequency.total_cmp(&b.frequency));
    for (i, m) in modes.iter_mut().enumerate() {
        m.number = i + 1;
    }
    Ok(Some(modes))
}
