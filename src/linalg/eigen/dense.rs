//! Dense generalized symmetric eigensolver for small models: every mode at once.
//!
//! Inverse form (used whenever K + δM is definite, δ > 0 tiny: K positive semi-definite,
//! rigid-body modes allowed, M possibly singular): K + δM = LLᵀ, C = L⁻¹ML⁻ᵀ,
//! C y = μ y with μ = 1/(ω² + δ), φ = L⁻ᵀy/√μ (M-orthonormal); μ ≈ 0 are the infinite
//! frequencies of massless DOFs and are dropped. The low modes come out with full relative
//! accuracy however badly K is conditioned.
//! Direct form (K indefinite, M definite): M = LLᵀ, C = L⁻¹KL⁻ᵀ, C y = ω² y, φ = L⁻ᵀy.

use super::sym::SymSparse;
use crate::error::{Error, Result};
use faer::linalg::triangular_solve::{
    solve_lower_triangular_in_place, solve_upper_triangular_in_place,
};
use faer::{Mat, Par, Side};

/// All finite eigenpairs (ω² ascending), vectors M-orthonormal.
pub struct DenseModes {
    pub omega2: Vec<f64>,
    pub vectors: Vec<Vec<f64>>,
    /// Number of infinite eigenvalues dropped (massless DOFs).
    pub infinite: usize,
    /// Number of modes dropped above what double precision resolves (μ ≤ 0 by round-off
    /// with M definite: the top of the spectrum of a badly conditioned K).
    pub unresolved: usize,
    /// δ of the inverse form (Cholesky of K + δM); NaN for the direct form.
    pub delta: f64,
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

pub fn solve_dense(k: &SymSparse, m: &SymSparse, delta: f64) -> Result<DenseModes> {
    let n = k.n;
    let kd = k.to_dense();
    let md = m.to_dense();
    // Preferred: the inverse form, whose largest μ (the low modes CALC_MODES is mostly
    // asked for) keep full relative accuracy even when K is badly conditioned (beams).
    // δ = 0 when K is safely definite (exact, and no cancellation in 1/μ − δ); otherwise
    // (rigid-body modes, round-off pivots) the small δ given by the caller.
    if let Ok(llt) = kd.llt(Side::Lower) {
        let l = llt.L();
        let healthy = (0..n).all(|i| {
            let kii = kd[(i, i)].abs();
            kii > 0.0 && l[(i, i)] * l[(i, i)] > 1e-10 * kii
        });
        if healthy {
            return inverse_form(l, &md, 0.0);
        }
    }
    let mut a = kd.clone();
    for j in 0..n {
        for i in 0..n {
            a[(i, j)] += delta * md[(i, j)];
        }
    }
    if let Ok(llt) = a.llt(Side::Lower) {
        return inverse_form(llt.L(), &md, delta);
    }
    // K + δM not definite (K indefinite): the direct form needs M definite.
    let llt = md.llt(Side::Lower).map_err(|_| {
        Error::numerical(
            "the mass matrix is singular and the stiffness matrix is not positive definite on \
             the DOFs without mass: the eigenproblem is not well posed",
        )
        .hint("give every free DOF some mass, or block the massless DOFs")
    })?;
    let l = llt.L();
    let c = congruence(l, &kd);
    let eig = c
        .self_adjoint_eigen(Side::Lower)
        .map_err(|e| Error::numerical(format!("dense eigensolver failed: {e:?}")))?;
    let mut y = eig.U().to_owned();
    solve_upper_triangular_in_place(l.transpose(), y.as_mut(), Par::Seq);
    Ok(DenseModes {
        omega2: (0..n).map(|i| eig.S()[i]).collect(),
        vectors: (0..n).map(|j| y.col(j).iter().copied().collect()).collect(),
        infinite: 0,
        unresolved: 0,
        delta: f64::NAN,
    })
}

/// K + δM = LLᵀ, C = L⁻¹ML⁻ᵀ, μ = 1/(ω² + δ).
fn inverse_form(l: faer::MatRef<'_, f64>, md: &Mat<f64>, delta: f64) -> Result<DenseModes> {
    let n = l.nrows();
    let c = congruence(l, md);
    let eig = c
        .self_adjoint_eigen(Side::Lower)
        .map_err(|e| Error::numerical(format!("dense eigensolver failed: {e:?}")))?;
    let mu_max = (0..n).map(|i| eig.S()[i].abs()).fold(0.0, f64::max);
    let mut y = eig.U().to_owned();
    solve_upper_triangular_in_place(l.transpose(), y.as_mut(), Par::Seq);
    let mut pairs: Vec<(f64, Vec<f64>)> = Vec::new();
    let mut infinite = 0;
    let mut unresolved = 0;
    // μ at round-off level relative to the largest is an infinite frequency when M is
    // singular; with M definite it is a genuine (if inaccurate) high mode of a badly
    // conditioned K and is kept. Only in that case is M's Cholesky worth trying.
    let threshold = 1e3 * f64::EPSILON * mu_max;
    let m_singular = (0..n).any(|j| eig.S()[j] <= threshold) && md.llt(Side::Lower).is_err();
    for j in 0..n {
        let mu = eig.S()[j];
        if m_singular && mu <= threshold {
            infinite += 1;
            continue;
        }
        // μ ≤ 0 with M definite: ω² + δ beyond 1/(ε·μ_max), a mode of a K too badly
        // conditioned for double precision to resolve (the rotations of a fine beam mesh);
        // it has no frequency to give and is dropped, as the infinite ones.
        if mu <= 0.0 {
            unresolved += 1;
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
        unresolved,
        delta,
    })
}
