//! Dense generalized symmetric eigensolver for small models: every mode at once.
//!
//! With M positive definite: M = LLᵀ, C = L⁻¹KL⁻ᵀ, C y = ω² y, φ = L⁻ᵀy (M-orthonormal).
//! With M singular (DOFs without mass): A = K + δM = LLᵀ (δ > 0 small, so A is definite
//! when K is definite on the massless DOFs), C = L⁻¹ML⁻ᵀ, C y = μ y with μ = 1/(ω² + δ);
//! μ ≈ 0 are the infinite frequencies of the massless DOFs and are dropped.

use super::eigen_sym::SymSparse;
use crate::error::{Error, Result};
use faer::linalg::triangular_solve::{solve_lower_triangular_in_place, solve_upper_triangular_in_place};
use faer::{Mat, Par, Side};

/// All finite eigenpairs (ω² ascending), vectors M-orthonormal.
pub struct DenseModes {
    pub omega2: Vec<f64>,
    pub vectors: Vec<Vec<f64>>,
    /// Number of infinite eigenvalues dropped (massless DOFs).
    pub infinite: usize,
}

/// L⁻¹ A L⁻ᵀ for a lower-triangular L.
fn congruence(l: faer::MatRef<'_, f64>, a: &Mat<f64>) -> Mat<f64> {
    let mut x = a.clone();
    solve_lower_triangular_in_place(l, x.as_mut(), Par::Seq);
    let mut c = x.transpose().to_owned();
    solve_lower_triangular_in_place(l, c.as_mut(), Par::Seq);
    // Round-off makes C slightly unsymmetric; only the lower triangle is read below.
    c
}

pub fn solve_dense(k: &SymSparse, m: &SymSparse, shift_scale: f64) -> Result<DenseModes> {
    let n = k.n;
    let kd = k.to_dense();
    let md = m.to_dense();
    if let Ok(llt) = md.llt(Side::Lower) {
        let l = llt.L();
        let c = congruence(l, &kd);
        let eig = c
            .self_adjoint_eigen(Side::Lower)
            .map_err(|e| Error::numerical(format!("dense eigensolver failed: {e:?}")))?;
        let mut y = eig.U().to_owned();
        solve_upper_triangular_in_place(l.transpose(), y.as_mut(), Par::Seq);
        let omega2 = (0..n).map(|i| eig.S()[i]).collect();
        let vectors = (0..n).map(|j| y.col(j).iter().copied().collect()).collect();
        return Ok(DenseModes {
            omega2,
            vectors,
            infinite: 0,
        });
    }
    // M singular: shifted reduction.
    let delta = shift_scale;
    let mut a = kd.clone();
    for j in 0..n {
        for i in 0..n {
            a[(i, j)] += delta * md[(i, j)];
        }
    }
    let llt = a.llt(Side::Lower).map_err(|_| {
        Error::numerical(
            "the mass matrix is singular and the stiffness matrix is not positive definite on \
             the DOFs without mass: the eigenproblem is not well posed",
        )
        .hint("give every free DOF some mass, or block the massless DOFs")
    })?;
    let l = llt.L();
    let c = congruence(l, &md);
    let eig = c
        .self_adjoint_eigen(Side::Lower)
        .map_err(|e| Error::numerical(format!("dense eigensolver failed: {e:?}")))?;
    let mu_max = (0..n).map(|i| eig.S()[i].abs()).fold(0.0, f64::max);
    let mut y = eig.U().to_owned();
    solve_upper_triangular_in_place(l.transpose(), y.as_mut(), Par::Seq);
    let mut pairs: Vec<(f64, Vec<f64>)> = Vec::new();
    let mut infinite = 0;
    for j in 0..n {
        let mu = eig.S()[j];
        // μ at round-off level relative to the largest: an infinite frequency.
        if mu <= 1e3 * f64::EPSILON * mu_max {
            infinite += 1;
            continue;
        }
        let s = 1.0 / mu.sqrt(); // φᵀMφ = μ before scaling
        let v: Vec<f64> = y.col(j).iter().map(|x| x * s).collect();
        pairs.push((1.0 / mu - delta, v));
    }
    pairs.sort_by(|a, b| a.0.total_cmp(&b.0));
    let (omega2, vectors) = pairs.into_iter().unzip();
    Ok(DenseModes {
        omega2,
        vectors,
        infinite,
    })
}
