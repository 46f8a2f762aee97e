//! Thick-restart Lanczos (symmetric Krylov–Schur) for the shift-invert operator
//! Op = (K − σM)⁻¹M, which is self-adjoint in the M inner product ⟨x, y⟩ = xᵀMy.
//! Its eigenvalues θ = 1/(ω² − σ) are largest in modulus for the modes closest to σ.
//!
//! Every new Krylov vector is M-orthogonalised twice against the whole basis and against
//! `locked` vectors (modes already found in an earlier pass: explicit deflation, which is
//! how a second copy of a multiple eigenvalue gets found). Memory: (ncv + 1) vectors of
//! length n plus small ncv × ncv matrices.

use super::sym::{dot, SymSparse};
use crate::error::{Error, Result};
use faer::{Mat, Side};

pub struct LanczosParams {
    /// Number of wanted Ritz pairs (largest |θ|).
    pub nev: usize,
    /// Basis size before a restart (> nev).
    pub ncv: usize,
    /// Convergence: ‖Op y − θ y‖_M ≤ tol·|θ| (+ a round-off floor).
    pub tol: f64,
    pub max_restarts: usize,
    pub seed: u64,
}

pub struct LanczosOut {
    /// Ritz values θ of the converged pairs, largest |θ| first.
    pub theta: Vec<f64>,
    /// M-orthonormal Ritz vectors.
    pub vectors: Vec<Vec<f64>>,
    /// Number of operator applications.
    pub op_count: usize,
}

/// Deterministic pseudo-random start vector (xorshift): reproducible runs.
fn random_vector(n: usize, seed: &mut u64) -> Vec<f64> {
    (0..n)
        .map(|_| {
            *seed ^= *seed << 13;
            *seed ^= *seed >> 7;
            *seed ^= *seed << 17;
            (*seed >> 11) as f64 / (1u64 << 53) as f64 - 0.5
        })
        .collect()
}

/// M-orthogonalise `w` against `basis` and `locked` (two passes); returns the coefficients
/// against `basis` and the M-norm of the remainder.
fn orthogonalise(
    w: &mut [f64],
    basis: &[Vec<f64>],
    locked: &[Vec<f64>],
    m: &SymSparse,
    mw: &mut [f64],
) -> (Vec<f64>, f64) {
    let mut h = vec![0.0; basis.len()];
    for _pass in 0..2 {
        m.mul(w, mw);
        for (hi, v) in h.iter_mut().zip(basis) {
            let c = dot(v, mw);
            *hi += c;
            axpy(-c, v, w);
        }
        for v in locked {
            let c = dot(v, mw);
            axpy(-c, v, w);
        }
    }
    m.mul(w, mw);
    let nrm = dot(w, mw).max(0.0).sqrt();
    (h, nrm)
}

fn axpy(a: f64, x: &[f64], y: &mut [f64]) {
    for (yi, xi) in y.iter_mut().zip(x) {
        *yi += a * xi;
    }
}

/// Runs thick-restart Lanczos. `op(x, y)` sets y = Op x.
pub fn lanczos(
    n: usize,
    m: &SymSparse,
    mut op: impl FnMut(&[f64], &mut [f64]),
    locked: &[Vec<f64>],
    p: &LanczosParams,
) -> Result<LanczosOut> {
    let room = n.saturating_sub(locked.len());
    if p.nev == 0 || room == 0 {
        return Ok(LanczosOut {
            theta: vec![],
            vectors: vec![],
            op_count: 0,
        });
    }
    let nev = p.nev.min(room);
    let ncv = p.ncv.max(nev + 2).min(room);
    let mut seed = p.seed.max(1);
    let mut mw = vec![0.0; n];
    let mut op_count = 0;

    // Start in the range of Op (purges directions of infinite eigenvalues when M is
    // singular, and of locked modes).
    let mut v0 = vec![0.0; n];
    let mut basis: Vec<Vec<f64>> = Vec::with_capacity(ncv + 1);
    for _attempt in 0..5 {
        let r = random_vector(n, &mut seed);
        op(&r, &mut v0);
        op_count += 1;
        let (_, nrm) = orthogonalise(&mut v0, &[], locked, m, &mut mw);
        if nrm > 0.0 && nrm.is_finite() {
            v0.iter_mut().for_each(|x| *x /= nrm);
            basis.push(v0.clone());
            break;
        }
    }
    if basis.is_empty() {
        return Err(Error::numerical(
            "Lanczos could not build a start vector: the mass matrix is zero on the free DOFs",
        ));
    }

    // h[i][j] = ⟨v_i, Op v_j⟩_M, (ncv+1) × ncv.
    let mut h = vec![vec![0.0; ncv]; ncv + 1];
    let mut k0 = 0; // first column to compute in this cycle
    let mut w = vec![0.0; n];
    for _restart in 0..=p.max_restarts {
        let mut ncur = ncv;
        for j in k0..ncv {
            op(&basis[j], &mut w);
            op_count += 1;
            let (c, mut beta) = orthogonalise(&mut w, &basis, locked, m, &mut mw);
            for (i, ci) in c.iter().enumerate() {
                h[i][j] = *ci;
            }
            let scale = c.iter().fold(0.0f64, |a, x| a.max(x.abs()));
            if beta.is_nan() || beta <= 1e-13 * scale {
                // Invariant subspace: continue with a fresh direction, coupling 0.
                beta = 0.0;
                let mut fresh = false;
                for _attempt in 0..5 {
                    let r = random_vector(n, &mut seed);
                    op(&r, &mut w);
                    op_count += 1;
                    let (_, nrm) = orthogonalise(&mut w, &basis, locked, m, &mut mw);
                    if nrm > 1e-13 * scale && nrm.is_finite() {
                        w.iter_mut().for_each(|x| *x /= nrm);
                        fresh = true;
                        break;
                    }
                }
                if !fresh {
                    // The whole reachable space is spanned: stop with what we have.
                    ncur = j + 1;
                    h[j + 1][j] = 0.0;
                    break;
                }
            } else {
                w.iter_mut().for_each(|x| *x /= beta);
            }
            h[j + 1][j] = beta;
            basis.push(w.clone());
        }

        // Ritz pairs of the symmetric part of the projected matrix.
        let t = Mat::<f64>::from_fn(ncur, ncur, |i, j| 0.5 * (h[i][j] + h[j][i]));
        let eig = t
            .self_adjoint_eigen(Side::Lower)
            .map_err(|e| Error::numerical(format!("projected eigenproblem failed: {e:?}")))?;
        let s = eig.U();
        let theta: Vec<f64> = (0..ncur).map(|i| eig.S()[i]).collect();
        let mut order: Vec<usize> = (0..ncur).collect();
        order.sort_by(|&a, &b| theta[b].abs().total_cmp(&theta[a].abs()));
        let beta_last = if ncur < ncv { 0.0 } else { h[ncur][ncur - 1] };
        let theta_max = theta.iter().fold(0.0f64, |a, x| a.max(x.abs()));
        let resid = |i: usize| (beta_last * s[(ncur - 1, i)]).abs();
        let want = nev.min(ncur);
        let converged = order[..want]
            .iter()
            .all(|&i| resid(i) <= p.tol * theta[i].abs() + 1e-14 * theta_max);
        let exhausted = ncur < ncv;

        let keep = if converged || exhausted {
            want
        } else {
            // Keep the wanted pairs and half the rest: the thick restart.
            (nev + (ncv - nev) / 2).min(ncv - 1)
        };
        // New basis = V S[:, kept].
        let kept: Vec<usize> = order[..keep].to_vec();
        let mut new_basis: Vec<Vec<f64>> = Vec::with_capacity(ncv + 1);
        for &c in &kept {
            let mut y = vec![0.0; n];
            for (r, v) in basis.iter().take(ncur).enumerate() {
                axpy(s[(r, c)], v, &mut y);
            }
            new_basis.push(y);
        }
        if converged || exhausted {
            return Ok(LanczosOut {
                theta: kept.iter().map(|&c| theta[c]).collect(),
                vectors: new_basis,
                op_count,
            });
        }
        // The residual direction continues the Krylov space.
        new_basis.push(basis[ncur].clone());
        basis = new_basis;
        for row in h.iter_mut() {
            row.iter_mut().for_each(|x| *x = 0.0);
        }
        for (a, &c) in kept.iter().enumerate() {
            h[a][a] = theta[c];
            h[keep][a] = beta_last * s[(ncur - 1, c)];
        }
        k0 = keep;
    }
    Err(Error::numerical(format!(
        "shift-invert Lanczos did not converge {nev} modes after {} restarts",
        p.max_restarts
    ))
    .hint("ask for fewer modes, or a frequency band closer to the modes wanted"))
}
