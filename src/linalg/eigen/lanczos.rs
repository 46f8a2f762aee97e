//! Thick-restart Lanczos (symmetric Krylov–Schur) for the shift-invert operator
//! Op = (K − σM)⁻¹M, which is self-adjoint in the M inner product ⟨x, y⟩ = xᵀMy.
//! Its eigenvalues θ = 1/(ω² − σ) are largest in modulus for the modes closest to σ.
//!
//! Every new Krylov vector is M-orthogonalised twice against the whole basis and against
//! `locked` vectors (modes already found in an earlier pass: explicit deflation, which is
//! how a second copy of a multiple eigenvalue gets found). Each basis vector is kept with
//! its product by M, so that those inner products need no product by M (one per new
//! vector, for its norm). Memory: 2(ncv + 1) vectors of length n plus small ncv × ncv
//! matrices.

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

/// Rows per block of the Gram–Schmidt kernels: a block of `w` (32 KB) stays in cache while
/// every basis vector passes over it.
const BLOCK: usize = 4096;

/// Vectors with their products by M, so that an M inner product against one costs a dot.
#[derive(Default)]
struct MVectors {
    v: Vec<Vec<f64>>,
    mv: Vec<Vec<f64>>,
}

impl MVectors {
    fn push(&mut self, v: Vec<f64>, mv: Vec<f64>) {
        self.v.push(v);
        self.mv.push(mv);
    }

    fn len(&self) -> usize {
        self.v.len()
    }

    /// `vectors` with their M-products computed here.
    fn of(vectors: &[Vec<f64>], m: &SymSparse) -> MVectors {
        let mut out = MVectors::default();
        for v in vectors {
            let mut mv = vec![0.0; v.len()];
            m.mul(v, &mut mv);
            out.push(v.clone(), mv);
        }
        out
    }
}

/// c_i = ⟨v_i, w⟩_M = (M v_i)·w for every vector of `set`, blocked over rows.
fn m_dots(set: &MVectors, w: &[f64]) -> Vec<f64> {
    let mut c = vec![0.0; set.len()];
    for start in (0..w.len()).step_by(BLOCK) {
        let end = (start + BLOCK).min(w.len());
        let wb = &w[start..end];
        for (ci, mv) in c.iter_mut().zip(&set.mv) {
            *ci += dot8(&mv[start..end], wb);
        }
    }
    c
}

/// w −= Σ c_i v_i, blocked over rows.
fn subtract_combination(w: &mut [f64], vectors: &[Vec<f64>], c: &[f64]) {
    let n = w.len();
    for start in (0..n).step_by(BLOCK) {
        let end = (start + BLOCK).min(n);
        let wb = &mut w[start..end];
        for (v, &ci) in vectors.iter().zip(c) {
            if ci != 0.0 {
                axpy(-ci, &v[start..end], wb);
            }
        }
    }
}

/// y = Σ_r coef(r) v_r over the first `count` vectors, blocked over rows.
fn combination(
    vectors: &[Vec<f64>],
    count: usize,
    coef: impl Fn(usize) -> f64,
    n: usize,
) -> Vec<f64> {
    let c: Vec<f64> = (0..count).map(coef).collect();
    let mut y = vec![0.0; n];
    subtract_combination(&mut y, &vectors[..count], &c);
    y.iter_mut().for_each(|x| *x = -*x);
    y
}

/// A dot product with eight independent partial sums: the sum is not one chain of
/// dependent additions, so it runs at the memory's speed.
fn dot8(a: &[f64], b: &[f64]) -> f64 {
    let mut acc = [0.0f64; 8];
    let (ca, cb) = (a.chunks_exact(8), b.chunks_exact(8));
    let (ra, rb) = (ca.remainder(), cb.remainder());
    for (x, y) in ca.zip(cb) {
        for k in 0..8 {
            acc[k] += x[k] * y[k];
        }
    }
    let tail: f64 = ra.iter().zip(rb).map(|(x, y)| x * y).sum();
    acc.iter().sum::<f64>() + tail
}

/// M-orthogonalise `w` against `basis` and `locked` (classical Gram–Schmidt twice, the
/// M inner products read from the stored M-products); returns the coefficients against
/// `basis` and the M-norm of the remainder, with `mw` = M w.
fn orthogonalise(
    w: &mut [f64],
    basis: &MVectors,
    locked: &MVectors,
    m: &SymSparse,
    mw: &mut [f64],
) -> (Vec<f64>, f64) {
    let mut h = vec![0.0; basis.len()];
    for _pass in 0..2 {
        let c = m_dots(basis, w);
        let cl = m_dots(locked, w);
        subtract_combination(w, &basis.v, &c);
        subtract_combination(w, &locked.v, &cl);
        h.iter_mut().zip(&c).for_each(|(hi, ci)| *hi += ci);
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

fn scaled(x: &[f64], by: f64) -> Vec<f64> {
    x.iter().map(|v| v / by).collect()
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
    let locked = MVectors::of(locked, m);

    // Start in the range of Op (purges directions of infinite eigenvalues when M is
    // singular, and of locked modes).
    let mut v0 = vec![0.0; n];
    let mut basis = MVectors::default();
    let none = MVectors::default();
    for _attempt in 0..5 {
        let r = random_vector(n, &mut seed);
        op(&r, &mut v0);
        op_count += 1;
        let (_, nrm) = orthogonalise(&mut v0, &none, &locked, m, &mut mw);
        if nrm > 0.0 && nrm.is_finite() {
            basis.push(scaled(&v0, nrm), scaled(&mw, nrm));
            break;
        }
    }
    if basis.len() == 0 {
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
            op(&basis.v[j], &mut w);
            op_count += 1;
            let (c, mut beta) = orthogonalise(&mut w, &basis, &locked, m, &mut mw);
            for (i, ci) in c.iter().enumerate() {
                h[i][j] = *ci;
            }
            let scale = c.iter().fold(0.0f64, |a, x| a.max(x.abs()));
            let next = if beta.is_nan() || beta <= 1e-13 * scale {
                // Invariant subspace: continue with a fresh direction, coupling 0.
                beta = 0.0;
                let mut fresh = None;
                for _attempt in 0..5 {
                    let r = random_vector(n, &mut seed);
                    op(&r, &mut w);
                    op_count += 1;
                    let (_, nrm) = orthogonalise(&mut w, &basis, &locked, m, &mut mw);
                    if nrm > 1e-13 * scale && nrm.is_finite() {
                        fresh = Some((scaled(&w, nrm), scaled(&mw, nrm)));
                        break;
                    }
                }
                match fresh {
                    Some(pair) => pair,
                    None => {
                        // The whole reachable space is spanned: stop with what we have.
                        ncur = j + 1;
                        h[j + 1][j] = 0.0;
                        break;
                    }
                }
            } else {
                (scaled(&w, beta), scaled(&mw, beta))
            };
            h[j + 1][j] = beta;
            basis.push(next.0, next.1);
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
        let new_vectors: Vec<Vec<f64>> = kept
            .iter()
            .map(|&c| combination(&basis.v, ncur, |r| s[(r, c)], n))
            .collect();
        if converged || exhausted {
            return Ok(LanczosOut {
                theta: kept.iter().map(|&c| theta[c]).collect(),
                vectors: new_vectors,
                op_count,
            });
        }
        // The residual direction continues the Krylov space.
        let mut restarted = MVectors::of(&new_vectors, m);
        let last = basis.v.swap_remove(ncur);
        let last_m = basis.mv.swap_remove(ncur);
        restarted.push(last, last_m);
        basis = restarted;
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
