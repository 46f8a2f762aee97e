//! Thick-restart Lanczos (symmetric Krylov–Schur) for the shift-invert operator
//! Op = (K − σM)⁻¹M, which is self-adjoint in the M inner product ⟨x, y⟩ = xᵀMy.
//! Its eigenvalues θ = 1/(ω² − σ) are largest in modulus for the modes closest to σ.
//!
//! Every new Krylov vector is M-orthogonalised to working precision against the whole
//! basis and against `locked` vectors (modes already found in an earlier pass: explicit
//! deflation, which is how a second copy of a multiple eigenvalue gets found): by the
//! three-term recurrence and one full Gram–Schmidt pass, a second one when that pass
//! removed much ([`orthogonalise_step`]), and by two full passes at a cycle's first column. Each basis vector is kept with
//! its product by M, so that those inner products need no product by M, and neither does
//! the operator (Op v = (K − σM)⁻¹ (M v) starts from the stored M v): one product by M per
//! new vector, for its norm. The basis and its M-products are column-major blocks
//! ([`LanczosWork`], reused from one run to the next), so that a Gram–Schmidt pass is two
//! matrix–vector products and a restart or the final Ritz vectors one matrix
//! product (faer's kernels), instead of loops of dots and axpys over separate vectors.
//! Memory: 2(ncv + 1) vectors of length n plus small ncv × ncv matrices.

use super::sym::{dot, SymSparse};
use crate::error::{Error, Result};
use faer::linalg::matmul::matmul;
use faer::{Accum, Mat, MatMut, MatRef, Par, Side};

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

/// The memory of a Lanczos run, kept by the caller so that the runs of one problem (the
/// slices of spectrum slicing, the deflated passes) reuse it instead of allocating and
/// zeroing 2(ncv + 1)·n values each time.
#[derive(Default)]
pub struct LanczosWork {
    /// Basis vectors, column-major n × (ncv + 1).
    v: Vec<f64>,
    /// Their products by M, same layout.
    mv: Vec<f64>,
    w: Vec<f64>,
    mw: Vec<f64>,
    /// Gram–Schmidt coefficients against the basis and against the locked vectors.
    c: Vec<f64>,
    c_locked: Vec<f64>,
    /// Rows of a block times the kept Ritz vectors, for the restarts ([`rotate`]).
    rows: Vec<f64>,
}

impl LanczosWork {
    /// Room for `cols` basis vectors of length `n` (grows, never shrinks: the next slice
    /// has about the same size).
    fn reserve(&mut self, n: usize, cols: usize) {
        for buf in [&mut self.v, &mut self.mv] {
            if buf.len() < n * cols {
                buf.resize(n * cols, 0.0);
            }
        }
        for buf in [&mut self.w, &mut self.mw] {
            buf.resize(n, 0.0);
        }
        if self.c.len() < cols {
            self.c.resize(cols, 0.0);
        }
    }
}

/// Deterministic pseudo-random vector (xorshift) written into `out`: reproducible runs.
fn random_into(out: &mut [f64], seed: &mut u64) {
    for x in out.iter_mut() {
        *seed ^= *seed << 13;
        *seed ^= *seed >> 7;
        *seed ^= *seed << 17;
        *x = (*seed >> 11) as f64 / (1u64 << 53) as f64 - 0.5;
    }
}

/// `k` column-major vectors of length `n` with their M-products.
#[derive(Clone, Copy)]
struct Block<'a> {
    v: &'a [f64],
    mv: &'a [f64],
    n: usize,
    k: usize,
}

impl<'a> Block<'a> {
    fn v(&self) -> MatRef<'a, f64> {
        MatRef::from_column_major_slice(&self.v[..self.n * self.k], self.n, self.k)
    }
    fn mv(&self) -> MatRef<'a, f64> {
        MatRef::from_column_major_slice(&self.mv[..self.n * self.k], self.n, self.k)
    }
}

fn col_mat(x: &[f64]) -> MatRef<'_, f64> {
    MatRef::from_column_major_slice(x, x.len(), 1)
}

fn col_mat_mut(x: &mut [f64]) -> MatMut<'_, f64> {
    let n = x.len();
    MatMut::from_column_major_slice_mut(x, n, 1)
}

/// c = (M V)ᵀ w: the M inner products of `w` with the block's vectors.
fn m_dots(set: Block, w: &[f64], c: &mut [f64]) {
    if set.k > 0 {
        let c = &mut c[..set.k];
        matmul(
            col_mat_mut(c),
            Accum::Replace,
            set.mv().transpose(),
            col_mat(w),
            1.0,
            Par::Seq,
        );
    }
}

/// w −= V c.
fn subtract_combination(set: Block, c: &[f64], w: &mut [f64]) {
    if set.k > 0 {
        matmul(
            col_mat_mut(w),
            Accum::Add,
            set.v(),
            col_mat(&c[..set.k]),
            -1.0,
            Par::Seq,
        );
    }
}

/// M-orthogonalise `w` against `basis` and `locked` (classical Gram–Schmidt twice, the
/// M inner products read from the stored M-products); the coefficients against `basis`
/// are accumulated into `h`, `mw` gets M w; returns the M-norm of the remainder.
#[allow(clippy::too_many_arguments)]
fn orthogonalise(
    w: &mut [f64],
    basis: Block,
    locked: Block,
    m: &SymSparse,
    mw: &mut [f64],
    h: &mut [f64],
    c: &mut [f64],
    c_locked: &mut [f64],
) -> f64 {
    h[..basis.k].iter_mut().for_each(|x| *x = 0.0);
    for _pass in 0..2 {
        gram_schmidt_pass(w, basis, locked, h, c, c_locked);
    }
    m.mul(w, mw);
    dot(w, mw).max(0.0).sqrt()
}

/// One classical Gram–Schmidt pass of `w` against `basis` and `locked` (the M inner
/// products from the stored M-products, into `c` and `c_locked`); the coefficients against
/// `basis` are added to `h`.
fn gram_schmidt_pass(
    w: &mut [f64],
    basis: Block,
    locked: Block,
    h: &mut [f64],
    c: &mut [f64],
    c_locked: &mut [f64],
) {
    m_dots(basis, w, c);
    m_dots(locked, w, c_locked);
    subtract_combination(basis, c, w);
    subtract_combination(locked, c_locked, w);
    h.iter_mut()
        .zip(&c[..basis.k])
        .for_each(|(hi, ci)| *hi += ci);
}

/// One Lanczos step's orthogonalisation of `w` = Op v_j, j > the cycle's first column:
/// the three-term recurrence first (w −= β_{j−1} v_{j−1}, then its component along v_j,
/// both O(n)), which removes in exact arithmetic every component along the basis, then one
/// classical Gram–Schmidt pass against the whole basis and the locked vectors, which removes
/// what round-off left (of order ε‖Op v_j‖). The recurrence is the first of the "twice is
/// enough" passes, so the basis keeps M-orthogonality to working precision, as with two
/// full passes, at half their cost (the full passes read the n × j blocks V and M V, the
/// whole of the step's cost on a large model). The guard of Daniel, Gragg, Kaufman and
/// Stewart (η = 1/√2): if the full pass removed more than the remainder keeps (‖c‖ > β,
/// the remainder under 1/√2 of what the pass started from, with ‖before‖² = ‖c‖² + β² for
/// an M-orthonormal basis), the recurrence did not leave round-off only and a second full
/// pass follows. Coefficients go to `h` (the recurrence's and the passes' summed), `mw`
/// gets M w; returns the M-norm of the remainder.
#[allow(clippy::too_many_arguments)]
fn orthogonalise_step(
    w: &mut [f64],
    basis: Block,
    locked: Block,
    beta_prev: f64,
    m: &SymSparse,
    mw: &mut [f64],
    h: &mut [f64],
    c: &mut [f64],
    c_locked: &mut [f64],
) -> f64 {
    let (n, j) = (basis.n, basis.k - 1);
    h[..basis.k].iter_mut().for_each(|x| *x = 0.0);
    if j > 0 {
        let prev = &basis.v[(j - 1) * n..j * n];
        w.iter_mut()
            .zip(prev)
            .for_each(|(x, p)| *x -= beta_prev * p);
        h[j - 1] = beta_prev;
    }
    let alpha = dot(&basis.mv[j * n..(j + 1) * n], w);
    w.iter_mut()
        .zip(&basis.v[j * n..(j + 1) * n])
        .for_each(|(x, v)| *x -= alpha * v);
    h[j] = alpha;
    let mut beta = 0.0;
    for pass in 0..2 {
        gram_schmidt_pass(w, basis, locked, h, c, c_locked);
        m.mul(w, mw);
        beta = dot(w, mw).max(0.0).sqrt();
        let removed: f64 = c[..basis.k]
            .iter()
            .chain(&c_locked[..locked.k])
            .map(|x| x * x)
            .sum();
        if pass == 0 && removed <= beta * beta {
            break;
        }
    }
    beta
}

/// Rows of a block per product of [`rotate`]: 512 rows of 100 kept vectors (400 KB) stay in
/// the cache until they are copied back.
const ROTATE_ROWS: usize = 512;

/// A[:, ..s.ncols()] ← A[:, ..s.nrows()] S in place for the column-major n-row block `a`,
/// one band of rows at a time through `rows` (the new columns are combinations of the old
/// ones, so they cannot be written over them directly).
fn rotate(a: &mut [f64], n: usize, s: MatRef<'_, f64>, rows: &mut Vec<f64>) {
    let (old, new) = (s.nrows(), s.ncols());
    if old == 0 || new == 0 {
        return;
    }
    if rows.len() < ROTATE_ROWS * new {
        rows.resize(ROTATE_ROWS * new, 0.0);
    }
    for start in (0..n).step_by(ROTATE_ROWS) {
        let r = ROTATE_ROWS.min(n - start);
        {
            let src = MatRef::from_column_major_slice_with_stride(
                &a[start..start + (old - 1) * n + r],
                r,
                old,
                n,
            );
            let dst = MatMut::from_column_major_slice_mut(&mut rows[..r * new], r, new);
            matmul(dst, Accum::Replace, src, s, 1.0, Par::Seq);
        }
        for c in 0..new {
            a[c * n + start..c * n + start + r].copy_from_slice(&rows[c * r..(c + 1) * r]);
        }
    }
}

/// Stores x / by and mx / by as basis column `j`.
fn store_column(
    work_v: &mut [f64],
    work_mv: &mut [f64],
    n: usize,
    j: usize,
    x: &[f64],
    mx: &[f64],
    by: f64,
) {
    for (d, s) in work_v[j * n..(j + 1) * n].iter_mut().zip(x) {
        *d = s / by;
    }
    for (d, s) in work_mv[j * n..(j + 1) * n].iter_mut().zip(mx) {
        *d = s / by;
    }
}

/// Steps between two convergence tests inside a cycle. Testing only when the basis is full
/// ran every slice of spectrum slicing to its last vector, where a step costs the most
/// (Gram–Schmidt over the whole basis); the 40-mode slices of a 2×10⁴-DOF bar converged
/// 0 to 8 steps before the end of their 100-vector cycle. A test is an eigensolve of the
/// small projected matrix (about a millisecond at 100 vectors); testing every 8 steps
/// measured slower than every 4 (the overshoot).
const CHECK_EVERY: usize = 4;

/// The Ritz pairs of the symmetric part of the first `len` columns of the projected matrix
/// `h`: vectors (columns of `s`), values `theta`, and `order`, largest |θ| first.
struct Ritz {
    s: Mat<f64>,
    theta: Vec<f64>,
    order: Vec<usize>,
}

impl Ritz {
    fn of(h: &[Vec<f64>], len: usize) -> Result<Ritz> {
        let t = Mat::<f64>::from_fn(len, len, |i, j| 0.5 * (h[i][j] + h[j][i]));
        let eig = t
            .self_adjoint_eigen(Side::Lower)
            .map_err(|e| Error::numerical(format!("projected eigenproblem failed: {e:?}")))?;
        let theta: Vec<f64> = (0..len).map(|i| eig.S()[i]).collect();
        let mut order: Vec<usize> = (0..len).collect();
        order.sort_by(|&a, &b| theta[b].abs().total_cmp(&theta[a].abs()));
        Ok(Ritz {
            s: eig.U().to_owned(),
            theta,
            order,
        })
    }

    /// Whether the first `want` pairs of `order` meet the convergence test, `beta` the
    /// coefficient of the residual direction (|β s_last,i| ≤ tol |θ_i| + 1e-14 max |θ|).
    fn converged(&self, beta: f64, want: usize, tol: f64) -> bool {
        let last = self.theta.len() - 1;
        let theta_max = self.theta.iter().fold(0.0f64, |a, x| a.max(x.abs()));
        self.order[..want].iter().all(|&i| {
            (beta * self.s[(last, i)]).abs() <= tol * self.theta[i].abs() + 1e-14 * theta_max
        })
    }
}

/// Whether the `nev` Ritz pairs of largest |θ| of the first `len` columns of `h` meet the
/// convergence test (the same test as at the end of a cycle).
fn ritz_converged(h: &[Vec<f64>], len: usize, nev: usize, tol: f64) -> Result<bool> {
    Ok(Ritz::of(h, len)?.converged(h[len][len - 1], nev.min(len), tol))
}

/// Runs thick-restart Lanczos. `solve(y)` sets y ← (K − σM)⁻¹ y, so that Op x is
/// `solve` applied to M x.
pub fn lanczos(
    n: usize,
    m: &SymSparse,
    mut solve: impl FnMut(&mut [f64]),
    locked: &[Vec<f64>],
    p: &LanczosParams,
    work: &mut LanczosWork,
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
    let mut op_count = 0;
    work.reserve(n, ncv + 1);
    // The locked vectors as one block with their M-products (empty but for deflated passes).
    let nl = locked.len();
    let mut lv = Vec::with_capacity(n * nl);
    let mut lmv = vec![0.0; n * nl];
    for (x, mx) in locked.iter().zip(lmv.chunks_exact_mut(n.max(1))) {
        lv.extend_from_slice(x);
        m.mul(x, mx);
    }
    work.c_locked.resize(nl, 0.0);
    let lock = Block {
        v: &lv,
        mv: &lmv,
        n,
        k: nl,
    };
    let LanczosWork {
        v,
        mv,
        w,
        mw,
        c,
        c_locked,
        rows,
    } = work;
    let mut hcol = vec![0.0; ncv + 1];

    // Start in the range of Op (purges directions of infinite eigenvalues when M is
    // singular, and of locked modes).
    let mut len = 0;
    for _attempt in 0..5 {
        random_into(w, &mut seed);
        m.mul(w, mw);
        solve(mw);
        std::mem::swap(w, mw);
        op_count += 1;
        let none = Block {
            v: &[],
            mv: &[],
            n,
            k: 0,
        };
        let nrm = orthogonalise(w, none, lock, m, mw, &mut hcol, c, c_locked);
        if nrm > 0.0 && nrm.is_finite() {
            store_column(v, mv, n, 0, w, mw, nrm);
            len = 1;
            break;
        }
    }
    if len == 0 {
        return Err(Error::numerical(
            "Lanczos could not build a start vector: the mass matrix is zero on the free DOFs",
        ));
    }

    // h[i][j] = ⟨v_i, Op v_j⟩_M, (ncv+1) × ncv.
    let mut h = vec![vec![0.0; ncv]; ncv + 1];
    let mut k0 = 0; // first column to compute in this cycle
    for _restart in 0..=p.max_restarts {
        let mut ncur = ncv;
        let mut exhausted = false;
        for j in k0..ncv {
            w.copy_from_slice(&mv[j * n..(j + 1) * n]);
            solve(w);
            op_count += 1;
            let cur = Block {
                v: &v[..],
                mv: &mv[..],
                n,
                k: j + 1,
            };
            // The cycle's first column couples with every kept Ritz vector (the restart's
            // arrow): two full passes. Later ones follow the three-term recurrence.
            let mut beta = if j == k0 {
                orthogonalise(w, cur, lock, m, mw, &mut hcol, c, c_locked)
            } else {
                let beta_prev = h[j][j - 1];
                orthogonalise_step(w, cur, lock, beta_prev, m, mw, &mut hcol, c, c_locked)
            };
            for (i, ci) in hcol[..=j].iter().enumerate() {
                h[i][j] = *ci;
            }
            let scale = hcol[..=j].iter().fold(0.0f64, |a, x| a.max(x.abs()));
            if beta.is_nan() || beta <= 1e-13 * scale {
                // Invariant subspace: continue with a fresh direction, coupling 0.
                beta = 0.0;
                let mut fresh = false;
                for _attempt in 0..5 {
                    random_into(w, &mut seed);
                    m.mul(w, mw);
                    solve(mw);
                    std::mem::swap(w, mw);
                    op_count += 1;
                    let cur = Block {
                        v: &v[..],
                        mv: &mv[..],
                        n,
                        k: j + 1,
                    };
                    let nrm = orthogonalise(w, cur, lock, m, mw, &mut hcol, c, c_locked);
                    if nrm > 1e-13 * scale && nrm.is_finite() {
                        store_column(v, mv, n, j + 1, w, mw, nrm);
                        fresh = true;
                        break;
                    }
                }
                if !fresh {
                    // The whole reachable space is spanned: stop with what we have.
                    ncur = j + 1;
                    exhausted = true;
                    h[j + 1][j] = 0.0;
                    break;
                }
            } else {
                store_column(v, mv, n, j + 1, w, mw, beta);
            }
            h[j + 1][j] = beta;
            let len = j + 1;
            if len < ncv
                && len >= nev + 2
                && (len - k0) % CHECK_EVERY == 0
                && ritz_converged(&h, len, nev, p.tol)?
            {
                ncur = len;
                break;
            }
        }

        let ritz = Ritz::of(&h, ncur)?;
        let (s, theta, order) = (&ritz.s, &ritz.theta, &ritz.order);
        let beta_last = if exhausted { 0.0 } else { h[ncur][ncur - 1] };
        let want = nev.min(ncur);
        let converged = ritz.converged(beta_last, want, p.tol);

        let keep = if converged || exhausted {
            want
        } else {
            // Keep the wanted pairs and half the rest: the thick restart.
            (nev + (ncv - nev) / 2).min(ncv - 1)
        };
        // New basis = V S[:, kept].
        let kept: Vec<usize> = order[..keep].to_vec();
        let sk = Mat::<f64>::from_fn(ncur, keep, |r, a| s[(r, kept[a])]);
        rotate(v, n, sk.as_ref(), rows);
        if converged || exhausted {
            return Ok(LanczosOut {
                theta: kept.iter().map(|&c| theta[c]).collect(),
                vectors: v[..n * keep].chunks_exact(n).map(<[f64]>::to_vec).collect(),
                op_count,
            });
        }
        // The M-products follow by the same combination (no product by M), and the
        // residual direction continues the Krylov space.
        rotate(mv, n, sk.as_ref(), rows);
        v.copy_within(ncur * n..(ncur + 1) * n, keep * n);
        mv.copy_within(ncur * n..(ncur + 1) * n, keep * n);
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

#[cfg(test)]
mod tests {
    use super::*;

    fn pseudo_random(len: usize, seed: u64) -> Vec<f64> {
        let mut s = seed;
        let mut out = vec![0.0; len];
        random_into(&mut out, &mut s);
        out
    }

    #[test]
    fn rotate_matches_the_column_sums() {
        // 1300 rows: two full bands of ROTATE_ROWS and a partial one.
        let (n, old, new) = (1300, 7, 4);
        let a0 = pseudo_random(n * old, 3);
        let s = Mat::<f64>::from_fn(old, new, |r, c| ((r * 5 + c * 3) % 11) as f64 - 5.0);
        let mut a = a0.clone();
        let mut rows = Vec::new();
        rotate(&mut a, n, s.as_ref(), &mut rows);
        for c in 0..new {
            for i in 0..n {
                let exact: f64 = (0..old).map(|r| a0[r * n + i] * s[(r, c)]).sum();
                let size: f64 = (0..old).map(|r| (a0[r * n + i] * s[(r, c)]).abs()).sum();
                // Only the order of the additions may differ: a few ε of the terms' sizes.
                assert!((a[c * n + i] - exact).abs() <= 1e-14 * size, "({i}, {c})");
            }
        }
    }

    #[test]
    fn orthogonalise_matches_plain_gram_schmidt() {
        // A diagonal M, and 5 M-orthonormal vectors built by plain Gram–Schmidt.
        let n = 900;
        let diag: Vec<f64> = (0..n).map(|i| 1.0 + (i % 7) as f64).collect();
        let entries: Vec<(usize, usize, f64)> =
            diag.iter().enumerate().map(|(i, &d)| (i, i, d)).collect();
        let m = SymSparse::from_lower_triplets(n, &entries);
        let m_dot = |x: &[f64], y: &[f64]| -> f64 {
            x.iter()
                .zip(y)
                .zip(&diag)
                .map(|((a, b), d)| a * b * d)
                .sum()
        };
        let k = 5;
        let (mut v, mut mv) = (Vec::new(), Vec::new());
        for j in 0..k {
            let mut x = pseudo_random(n, 11 + j as u64);
            for _pass in 0..2 {
                for i in 0..j {
                    let c = m_dot(&v[i * n..(i + 1) * n], &x);
                    for (xr, vr) in x.iter_mut().zip(&v[i * n..(i + 1) * n]) {
                        *xr -= c * vr;
                    }
                }
            }
            let nrm = m_dot(&x, &x).sqrt();
            x.iter_mut().for_each(|e| *e /= nrm);
            mv.extend(x.iter().zip(&diag).map(|(a, d)| a * d));
            v.extend(x);
        }
        let w0 = pseudo_random(n, 99);
        let mut w = w0.clone();
        let (mut mw, mut h, mut c) = (vec![0.0; n], vec![0.0; k], vec![0.0; k]);
        let basis = Block {
            v: &v,
            mv: &mv,
            n,
            k,
        };
        let none = Block {
            v: &[],
            mv: &[],
            n,
            k: 0,
        };
        let nrm = orthogonalise(&mut w, basis, none, &m, &mut mw, &mut h, &mut c, &mut []);
        let scale = m_dot(&w0, &w0).sqrt();
        for i in 0..k {
            let vi = &v[i * n..(i + 1) * n];
            // The coefficients are the M inner products with the start vector, and what is
            // left is M-orthogonal to the basis, both to round-off (n·ε of the sizes).
            assert!((h[i] - m_dot(vi, &w0)).abs() <= 1e-13 * scale, "h[{i}]");
            assert!(m_dot(vi, &w).abs() <= 1e-13 * scale, "⟨v{i}, w⟩");
        }
        assert!((nrm - m_dot(&w, &w).sqrt()).abs() <= 1e-14 * scale);
        for i in 0..n {
            assert!((mw[i] - diag[i] * w[i]).abs() <= 1e-15 * w[i].abs());
        }

        // The step's orthogonalisation: whatever coefficient the recurrence is given for
        // v_{j−1} (the true one, a wrong one, or one 10⁶ off: one pass would then leave
        // about ε·10⁶ along v_{j−1}, 100 times the bound below, so the second pass must
        // run), the coefficients are the M inner products with the start vector (to
        // round-off of the terms summed) and the remainder is M-orthogonal to the basis.
        let exact_prev = m_dot(&v[(k - 2) * n..(k - 1) * n], &w0);
        for beta_prev in [exact_prev, exact_prev + 3.0, 0.0, exact_prev + 1e6] {
            let h_tol = 1e-13 * scale + 1e-15 * (beta_prev - exact_prev).abs();
            let mut w = w0.clone();
            let nrm = orthogonalise_step(
                &mut w,
                basis,
                none,
                beta_prev,
                &m,
                &mut mw,
                &mut h,
                &mut c,
                &mut [],
            );
            for i in 0..k {
                let vi = &v[i * n..(i + 1) * n];
                assert!(
                    (h[i] - m_dot(vi, &w0)).abs() <= h_tol,
                    "β {beta_prev}: h[{i}]"
                );
                assert!(
                    m_dot(vi, &w).abs() <= 1e-13 * scale,
                    "β {beta_prev}: ⟨v{i}, w⟩"
                );
            }
            assert!((nrm - m_dot(&w, &w).sqrt()).abs() <= 1e-14 * scale);
            for i in 0..n {
                assert!((mw[i] - diag[i] * w[i]).abs() <= 1e-15 * w[i].abs());
            }
        }
    }
}
