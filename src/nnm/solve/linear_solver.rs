//! Solvers of the bordered tangent J = [R_X(X0); tᵀ], behind one trait.
//!
//! - [`StructuredSolver`] (the engine's): V eliminated with the U rows, each shock's contact
//!   block by its Schur complement (contact.rs), the rest one sparse LU of fixed pattern
//!   (condensed_tangent.rs). The true border t is dense (the previous tangent); the condensed matrix
//!   carries a *local* border e_j instead (j: the condensed unknown where |t| is largest), and
//!   every solve of the true system is recovered exactly by one kernel correction: with y
//!   the solution of [R_X; e_jᵀ] y = (0, 1) (computed once per factorisation, R_X y = 0) and
//!   z' that of [R_X; e_jᵀ] z' = (r, 0), z = z' + ((ρ − tᵀz')/(tᵀy)) y solves
//!   [R_X; tᵀ] z = (r, ρ). Determinant: det[R_X; tᵀ] = det[R_X; e_jᵀ]·(tᵀy) (both expand
//!   along the border row with the same cofactors, and y is those cofactors over
//!   det[R_X; e_jᵀ]), and det[R_X; e_jᵀ] = c·Π det A_ff·det S (block elimination, c a sign
//!   fixed by the layout), so sign(det S)·sign(tᵀy) changes exactly where
//!   det J·Π det A_ff does: where the minor of condensed_det.rs's reference test does.
//! - [`ReferenceSolver`]: the whole tangent as triplets in one sparse LU ([`SparseLu`]),
//!   the determinant sign from a minor of its inverse (condensed_det.rs): the dense reference
//!   the tests compare the structured solver with.

use crate::nnm::error::{Error, Result};
use crate::nnm::model::fourier;
use crate::nnm::model::system::System;
use crate::nnm::model::vector::dot_in_order as dot;
use crate::nnm::model::vector::sub_scaled;
use crate::nnm::solve::condensed_tangent::{CondensedTangent, Linearisation};
use crate::nnm::solve::contact::{ContactBlock, Method};
use faer::prelude::*;
use faer::sparse::linalg::solvers::{Lu, SymbolicLu};
use faer::sparse::{Argsort, Pair, SparseColMat, SymbolicSparseColMat, Triplet};

/// A factorisation of the bordered tangent of one system, and solves with it.
pub trait TangentSolver {
    /// Factorise [R_X(x0); borderᵀ].
    fn factor(&mut self, sys: &System, x0: &[f64], border: &[f64]) -> Result<()>;
    /// Solve in place; `rhs` = (right-hand side of the n_eq equations, border value).
    fn solve(&mut self, sys: &System, rhs: &mut [f64]) -> Result<()>;
    /// ±1: the sign of det[R_X; borderᵀ] times a factor fixed for the problem (only its
    /// changes along a branch mean anything).
    fn det_sign(&mut self, sys: &System) -> Result<f64>;
}

/// The engine's solver (module doc).
pub struct StructuredSolver {
    condensed: CondensedTangent,
    contacts: Vec<ContactBlock>,
    /// Per shock: C W (m × m, column-major).
    schur: Vec<Vec<f64>>,
    /// Per shock: A_ff⁻¹ r_f of the current solve.
    q: Vec<Vec<f64>>,
    omega: f64,
    gamma: f64,
    /// D U0, and the Ω and γ columns of the condensed velocity rows (n·nl each).
    du0: Vec<f64>,
    col_omega: Vec<f64>,
    col_gamma: Vec<f64>,
    /// The true border and the kernel vector of the local-border system.
    t: Vec<f64>,
    y: Vec<f64>,
    ty: f64,
    red: Vec<f64>,
    tmp: Vec<f64>,
    tmp2: Vec<f64>,
    factored: bool,
}

/// Right-hand sides expected per factorisation (for the contact blocks' cost model):
/// NB_ORDRE_MAN series terms, a few Newton corrections.
pub fn solves_per_factorisation(order: usize) -> usize {
    order + 4
}

impl StructuredSolver {
    /// `force`: impose the contact route of every shock (tests, bench).
    pub fn new(sys: &System, solves: usize, force: Option<Method>) -> Result<StructuredSolver> {
        let lay = sys.lay;
        let nnl = lay.n * lay.n_coef_lin;
        let contacts = sys
            .shocks
            .iter()
            .enumerate()
            .map(|(i, sh)| ContactBlock::new(sh, i, &lay, solves, force))
            .collect::<Result<Vec<_>>>()?;
        let schur = sys
            .shocks
            .iter()
            .map(|sh| vec![0.0; (sh.dofs.len() * lay.n_coef_lin).pow(2)])
            .collect();
        let q = sys
            .shocks
            .iter()
            .map(|sh| vec![0.0; sh.eqs.n_own * lay.n_coef_nonl])
            .collect();
        Ok(StructuredSolver {
            condensed: CondensedTangent::new(sys)?,
            contacts,
            schur,
            q,
            omega: 0.0,
            gamma: 0.0,
            du0: vec![0.0; nnl],
            col_omega: vec![0.0; nnl],
            col_gamma: vec![0.0; nnl],
            t: vec![0.0; lay.n_unk],
            y: vec![0.0; lay.n_unk],
            ty: 0.0,
            red: vec![0.0; nnl + 2],
            tmp: vec![0.0; nnl],
            tmp2: vec![0.0; nnl],
            factored: false,
        })
    }

    /// Reduced border candidates: U entries and Ω, by decreasing |t|.
    fn border_candidates(&self, sys: &System) -> Vec<usize> {
        let lay = sys.lay;
        let nnl = lay.n * lay.n_coef_lin;
        let mut best: Vec<(f64, usize)> = Vec::with_capacity(4);
        let mut consider = |mag: f64, j: usize| {
            if mag > 0.0 && mag.is_finite() {
                best.push((mag, j));
                best.sort_by(|a, b| b.0.total_cmp(&a.0));
                best.truncate(3);
            }
        };
        for (j, v) in self.t[..nnl].iter().enumerate() {
            consider(v.abs(), j);
        }
        consider(self.t[lay.omega()].abs(), nnl);
        best.into_iter().map(|(_, j)| j).collect()
    }

    /// Full vector from a condensed solution `red` and the right-hand side `r` (None: zero),
    /// into `z` (length n_unk). Needs `q` (A_ff⁻¹ r_f) when `r` is given.
    fn expand(&mut self, sys: &System, r: Option<&[f64]>, z: &mut [f64]) {
        let lay = sys.lay;
        let (n, nl, hl, nn) = (lay.n, lay.n_coef_lin, lay.h_lin, lay.n_coef_nonl);
        let nnl = n * nl;
        let d_omega = self.red[nnl];
        // δV = Ω D δU + D U0 δΩ − r_U.
        for i in 0..n {
            let du = &self.red[i * nl..(i + 1) * nl];
            fourier::deriv(du, hl, &mut self.tmp[..nl]);
            for j in 0..nl {
                let mut v = self.omega * self.tmp[j] + self.du0[i * nl + j] * d_omega;
                if let Some(r) = r {
                    v -= r[lay.u(i) + j];
                }
                z[lay.v(i) + j] = v;
            }
        }
        // δF = A_ff⁻¹ r_f − W δu_s.
        for (s, sh) in sys.shocks.iter().enumerate() {
            let d = sh.eqs.n_own * nn;
            let f = &mut z[sh.offset..sh.offset + d];
            match r {
                Some(_) => f.copy_from_slice(&self.q[s]),
                None => f.fill(0.0),
            }
            let w = self.contacts[s].w();
            for (c, &dof) in sh.dofs.iter().enumerate() {
                let cols = &w[c * nl * d..(c + 1) * nl * d];
                subtract_columns(f, cols, &self.red[dof * nl..(dof + 1) * nl]);
            }
        }
        z[..nnl].copy_from_slice(&self.red[..nnl]);
        z[lay.omega()] = d_omega;
        z[lay.gamma()] = self.red[nnl + 1];
    }
}

/// f −= Σ_j coefs[j]·cols[j] (columns of f.len(), column-major), in column order, zero
/// coefficients skipped: δF = A_ff⁻¹ r_f − W δu (`expand`).
fn subtract_columns(f: &mut [f64], cols: &[f64], coefs: &[f64]) {
    for (&c, col) in coefs.iter().zip(cols.chunks_exact(f.len())) {
        if c != 0.0 {
            sub_scaled(f, c, col);
        }
    }
}

impl TangentSolver for StructuredSolver {
    fn factor(&mut self, sys: &System, x0: &[f64], border: &[f64]) -> Result<()> {
        self.factored = false;
        let lay = sys.lay;
        let (n, nl, hl, nn) = (lay.n, lay.n_coef_lin, lay.h_lin, lay.n_coef_nonl);
        if x0.len() != lay.n_unk || border.len() != lay.n_unk {
            return Err(Error::internal("tangent point or border of the wrong size"));
        }
        self.omega = x0[lay.omega()];
        self.gamma = x0[lay.gamma()];
        // D U0; q = (ΩD + γ) D U0 + D V0; Ω column M q, γ column M V0.
        for i in 0..n {
            let r = i * nl..(i + 1) * nl;
            fourier::deriv(&x0[lay.u(i)..lay.u(i) + nl], hl, &mut self.du0[r.clone()]);
            fourier::deriv(&self.du0[r.clone()], hl, &mut self.tmp[r.clone()]);
            fourier::deriv(&x0[lay.v(i)..lay.v(i) + nl], hl, &mut self.tmp2[r.clone()]);
            for j in r {
                self.tmp[j] = self.omega * self.tmp[j] + self.gamma * self.du0[j] + self.tmp2[j];
            }
        }
        self.col_omega.fill(0.0);
        sys.m.mul_blocks(&self.tmp, nl, &mut self.col_omega);
        self.col_gamma.fill(0.0);
        sys.m
            .mul_blocks(&x0[lay.v(0)..lay.v(0) + n * nl], nl, &mut self.col_gamma);
        // Contact blocks and their Schur complements C W.
        for (s, sh) in sys.shocks.iter().enumerate() {
            self.contacts[s].factor(sh, &lay, x0)?;
            let d = sh.eqs.n_own * nn;
            let m = sh.dofs.len() * nl;
            let w = self.contacts[s].w();
            let g = &mut self.schur[s];
            g.fill(0.0);
            for col in 0..m {
                let wc = &w[col * d..(col + 1) * d];
                for &(c, v) in &sh.eqs.forces {
                    for j in 0..nl {
                        if let Some(p) = fourier::map_index(j, hl, lay.h_nonl) {
                            g[col * m + c * nl + j] += wc[v * nn + p];
                        }
                    }
                }
            }
        }
        self.t.copy_from_slice(border);
        let candidates = self.border_candidates(sys);
        if candidates.is_empty() {
            return Err(Error::numerical(
                "the border has no displacement or frequency component",
            ));
        }
        let mut last_err = None;
        for j in candidates {
            let lin = Linearisation {
                omega: self.omega,
                gamma: self.gamma,
                col_omega: &self.col_omega,
                col_gamma: &self.col_gamma,
                schur: &self.schur,
            };
            if let Err(e) = self.condensed.factor(&lin, j) {
                last_err = Some(e);
                continue;
            }
            // Kernel: condensed right-hand side e_border, zero elsewhere.
            self.red.fill(0.0);
            let nr = self.red.len();
            self.red[nr - 1] = 1.0;
            self.condensed.solve(&mut self.red)?;
            let mut y = std::mem::take(&mut self.y);
            self.expand(sys, None, &mut y);
            self.y = y;
            self.ty = dot(&self.t, &self.y);
            if self.ty != 0.0 && self.ty.is_finite() {
                self.factored = true;
                return Ok(());
            }
            last_err = Some(Error::numerical("the bordered tangent is singular (the border is orthogonal to the kernel)")
                .hint("the branch may have reached a turning point of ω that the border cannot resolve"));
        }
        Err(last_err.unwrap_or_else(|| Error::internal("no border candidate")))
    }

    fn solve(&mut self, sys: &System, rhs: &mut [f64]) -> Result<()> {
        let lay = sys.lay;
        let (n, nl, hl, nn) = (lay.n, lay.n_coef_lin, lay.h_lin, lay.n_coef_nonl);
        let nnl = n * nl;
        if !self.factored || rhs.len() != lay.n_unk {
            return Err(Error::internal(
                "solve without a factorisation or of the wrong size",
            ));
        }
        let rho = rhs[lay.n_eq()];
        for (s, sh) in sys.shocks.iter().enumerate() {
            let d = sh.eqs.n_own * nn;
            self.q[s].copy_from_slice(&rhs[sh.offset..sh.offset + d]);
            self.contacts[s].solve(&mut self.q[s])?;
        }
        // Velocity rows: r_V + M (ΩD + γ) r_U − Pᵀ C A_ff⁻¹ r_f.
        for i in 0..n {
            let r = i * nl..(i + 1) * nl;
            fourier::deriv(&rhs[lay.u(i)..lay.u(i) + nl], hl, &mut self.tmp[r.clone()]);
            for j in r {
                self.tmp[j] = self.omega * self.tmp[j] + self.gamma * rhs[lay.u(0) + j];
            }
        }
        self.red[..nnl].copy_from_slice(&rhs[lay.v(0)..lay.v(0) + nnl]);
        sys.m.mul_blocks(&self.tmp, nl, &mut self.red[..nnl]);
        for (s, sh) in sys.shocks.iter().enumerate() {
            for &(c, v) in &sh.eqs.forces {
                let dof = sh.dofs[c];
                for j in 0..nl {
                    if let Some(p) = fourier::map_index(j, hl, lay.h_nonl) {
                        self.red[dof * nl + j] -= self.q[s][v * nn + p];
                    }
                }
            }
        }
        self.red[nnl] = rhs[lay.omega()];
        self.red[nnl + 1] = 0.0;
        self.condensed.solve(&mut self.red)?;
        let mut r_u = std::mem::take(&mut self.tmp2);
        r_u.copy_from_slice(&rhs[..nnl]);
        self.expand(sys, Some(&r_u), rhs);
        self.tmp2 = r_u;
        // The kernel correction to the true border.
        let c = (rho - dot(&self.t, rhs)) / self.ty;
        for (z, y) in rhs.iter_mut().zip(&self.y) {
            *z += c * y;
        }
        if rhs.iter().any(|v| !v.is_finite()) {
            return Err(Error::numerical(
                "the bordered tangent is numerically singular (solution not finite)",
            ));
        }
        Ok(())
    }

    fn det_sign(&mut self, _sys: &System) -> Result<f64> {
        if !self.factored {
            return Err(Error::internal("determinant sign without a factorisation"));
        }
        Ok(self.condensed.det_sign() * self.ty.signum())
    }
}

/// Factor a square sparse matrix given as triplets (duplicates add), then solve with it.
pub trait BorderedSolver {
    fn factor(&mut self, n: usize, triplets: &[Triplet<usize, usize, f64>]) -> Result<()>;
    /// Solve in place; `rhs` has length n.
    fn solve(&self, rhs: &mut [f64]) -> Result<()>;
    /// Solve for `ncols` right-hand sides stored column after column (length n·ncols).
    fn solve_block(&self, rhs: &mut [f64], ncols: usize) -> Result<()> {
        if ncols == 0 {
            return Ok(());
        }
        let n = rhs.len() / ncols;
        for col in rhs.chunks_mut(n) {
            self.solve(col)?;
        }
        Ok(())
    }
}

/// (row, col) sequence of the triplets, compressed pattern, sorting permutation.
type Assembly = (
    Vec<(usize, usize)>,
    SymbolicSparseColMat<usize>,
    Argsort<usize>,
);

/// faer sparse LU; the symbolic analysis is kept while the sparsity pattern repeats
/// (branch after branch, and at every Newton iteration, it does).
#[derive(Default)]
pub struct SparseLu {
    /// The (row, col) sequence of the last triplets, with its compressed pattern and the
    /// permutation that sorts the triplets into it: assembling the next matrix of the same
    /// sequence is then a gather, not a sort.
    assembly: Option<Assembly>,
    pattern: Option<(Vec<usize>, Vec<usize>, SymbolicLu<usize>)>,
    lu: Option<(usize, Lu<usize, f64>)>,
    /// Number of symbolic analyses done (for tests and reports).
    pub symbolic_count: usize,
}

impl BorderedSolver for SparseLu {
    fn factor(&mut self, n: usize, triplets: &[Triplet<usize, usize, f64>]) -> Result<()> {
        self.lu = None;
        let same_seq = match &self.assembly {
            Some((seq, sym, _)) => {
                sym.nrows() == n
                    && seq.len() == triplets.len()
                    && seq
                        .iter()
                        .zip(triplets)
                        .all(|(p, t)| p.0 == t.row && p.1 == t.col)
            }
            None => false,
        };
        if !same_seq {
            let idx: Vec<Pair<usize, usize>> =
                triplets.iter().map(|t| Pair::new(t.row, t.col)).collect();
            let (sym, argsort) =
                SymbolicSparseColMat::try_new_from_indices(n, n, &idx).map_err(|e| {
                    Error::internal(format!("bordered tangent could not be assembled: {e:?}"))
                })?;
            let seq = triplets.iter().map(|t| (t.row, t.col)).collect();
            self.assembly = Some((seq, sym, argsort));
        }
        let (_, sym, argsort) = self
            .assembly
            .as_ref()
            .ok_or_else(|| Error::internal("tangent pattern missing"))?;
        let vals: Vec<f64> = triplets.iter().map(|t| t.val).collect();
        let a = SparseColMat::new_from_argsort(sym.clone(), argsort, &vals).map_err(|e| {
            Error::internal(format!("bordered tangent could not be assembled: {e:?}"))
        })?;
        let same = match &self.pattern {
            Some((cp, ri, _)) => cp == a.symbolic().col_ptr() && ri == a.symbolic().row_idx(),
            None => false,
        };
        if !same {
            let sym = SymbolicLu::try_new(a.symbolic()).map_err(|e| {
                Error::numerical(format!("symbolic LU of the tangent failed: {e:?}"))
            })?;
            self.symbolic_count += 1;
            self.pattern = Some((
                a.symbolic().col_ptr().to_vec(),
                a.symbolic().row_idx().to_vec(),
                sym,
            ));
        }
        let sym = match &self.pattern {
            Some((_, _, s)) => s.clone(),
            None => return Err(Error::internal("symbolic LU missing")),
        };
        let lu = Lu::try_new_with_symbolic(sym, a.as_ref()).map_err(|e| {
            Error::numerical(format!("the bordered tangent is singular ({e:?})")).hint(
                "the branch may have reached a turning point of ω that the border cannot resolve",
            )
        })?;
        self.lu = Some((n, lu));
        Ok(())
    }

    fn solve(&self, rhs: &mut [f64]) -> Result<()> {
        self.solve_block(rhs, 1)
    }

    fn solve_block(&self, rhs: &mut [f64], ncols: usize) -> Result<()> {
        let (n, lu) = self
            .lu
            .as_ref()
            .ok_or_else(|| Error::internal("solve called before factor"))?;
        if rhs.len() != *n * ncols {
            return Err(Error::internal("right-hand sides of the wrong length"));
        }
        lu.solve_in_place(MatMut::from_column_major_slice_mut(rhs, *n, ncols));
        if rhs.iter().any(|v| !v.is_finite()) {
            return Err(Error::numerical(
                "the bordered tangent is numerically singular (solution not finite)",
            ));
        }
        Ok(())
    }
}

/// The whole tangent in one sparse LU (the engine before the structured solver): the
/// reference of the tests and of the bench's old/new comparison.
#[derive(Default)]
pub struct ReferenceSolver {
    pub lu: SparseLu,
}

impl TangentSolver for ReferenceSolver {
    fn factor(&mut self, sys: &System, x0: &[f64], border: &[f64]) -> Result<()> {
        self.lu.factor(sys.lay.n_unk, &sys.tangent(x0, border))
    }
    fn solve(&mut self, _sys: &System, rhs: &mut [f64]) -> Result<()> {
        BorderedSolver::solve(&self.lu, rhs)
    }
    fn det_sign(&mut self, sys: &System) -> Result<f64> {
        crate::nnm::solve::condensed_det::condensed_det_sign(sys, &|rhs, ncols| {
            self.lu.solve_block(rhs, ncols)
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn solves_and_reuses_pattern() {
        let t = |v: f64| {
            vec![
                Triplet::new(0, 0, 2.0),
                Triplet::new(1, 0, 1.0),
                Triplet::new(0, 1, v),
                Triplet::new(1, 1, 3.0),
            ]
        };
        let mut s = SparseLu::default();
        s.factor(2, &t(1.0)).unwrap();
        let mut b = vec![3.0, 4.0];
        s.solve(&mut b).unwrap();
        assert!((b[0] - 1.0).abs() < 1e-14 && (b[1] - 1.0).abs() < 1e-14);
        s.factor(2, &t(0.0)).unwrap();
        let mut b = vec![2.0, 4.0];
        s.solve(&mut b).unwrap();
        assert!((b[0] - 1.0).abs() < 1e-14 && (b[1] - 1.0).abs() < 1e-14);
        assert_eq!(s.symbolic_count, 1);
    }
}
