//! The condensed tangent: the bordered tangent with V and the contact unknowns eliminated.
//!
//! The velocity unknowns follow from the U rows exactly (Ω D δU + D U0 δΩ − δV = r_U, no
//! division), the contact unknowns from their blocks (δF = A_ff⁻¹ r_f − W δu_s,
//! contact.rs). What remains, over δU (n·(2H_l+1)), δΩ and δγ, is
//!
//!   [K + M(Ω²D² + γΩD) − Σ Pᵀ C W]  δU + M((ΩD + γ) D U0 + D V0) δΩ + M V0 δγ   (velocity rows)
//!   Σ_k k δus_k(ref)                                                           (phase row)
//!   δz_j                                                                       (local border)
//!
//! Per harmonic k the structural block is K − (kΩ)²M on cos and sin, coupled by ±γΩk M:
//! the pattern of K ∪ M, never denser. The contact Schur complements are dense
//! (n_comp·(2H_l+1))² blocks at the shock DOFs; Ω and γ are two dense columns (COLAMD
//! orders them last); the border is the single entry of a *local* border e_j (the true
//! border, dense, is recovered by one kernel correction in linear_solver.rs). The pattern is
//! fixed for a problem: the column ordering (COLAMD) is computed once and every numeric
//! factorisation reuses it and the factor storage. The factorisation is faer's simplicial
//! LU with partial pivoting, whose factors are accessible: the sign of the determinant is
//! the parities of the row and column permutations times the signs of U's diagonal.

use crate::nnm::error::{Error, Result};
use crate::nnm::model::fourier;
use crate::nnm::model::system::System;
use crate::nnm::solve::dense_lu::out_of_memory;
use faer::dyn_stack::{MemBuffer, MemStack};
use faer::perm::PermRef;
use faer::sparse::linalg::colamd;
use faer::sparse::linalg::lu::simplicial::{self, SimplicialLu};
use faer::sparse::linalg::LuError;
use faer::sparse::{FaerError, SparseColMatRef, SymbolicSparseColMatRef};
use faer::{Conj, MatMut, Par};
use std::collections::BTreeMap;

/// One entry of K ∪ M (scaled), with whether M has it.
#[derive(Clone, Copy, Debug)]
struct Pair {
    row: usize,
    col: usize,
    k: f64,
    m: f64,
    has_m: bool,
}

/// What the values of the condensed matrix depend on besides K and M.
pub struct Linearisation<'a> {
    pub omega: f64,
    pub gamma: f64,
    /// The Ω column and the γ column, per velocity row (length n·nl).
    pub col_omega: &'a [f64],
    pub col_gamma: &'a [f64],
    /// Per shock: its Schur block C W (m × m, column-major, component-major ordering).
    pub schur: &'a [Vec<f64>],
}

pub struct CondensedTangent {
    n: usize,
    n_coef_lin: usize,
    h_lin: usize,
    nr: usize,
    pairs: Vec<Pair>,
    /// DOFs whose mass row has entries (their velocity rows receive the Ω and γ columns).
    mass_rows: Vec<usize>,
    /// Per shock: its DOFs (component order).
    shock_dofs: Vec<Vec<usize>>,
    ref_dof: usize,
    /// Pattern without the border row (sorted CSC) and, per emitted entry, its position.
    col_ptr: Vec<usize>,
    row_idx: Vec<usize>,
    pos: Vec<usize>,
    vals: Vec<f64>,
    /// The matrix factorised: pattern plus the border entry in column `border`.
    a_col_ptr: Vec<usize>,
    a_row_idx: Vec<usize>,
    a_vals: Vec<f64>,
    border: usize,
    col_perm: Vec<usize>,
    col_perm_inv: Vec<usize>,
    col_perm_sign: f64,
    row_perm: Vec<usize>,
    row_perm_inv: Vec<usize>,
    lu: SimplicialLu<usize, f64>,
    factor_mem: MemBuffer,
    solve_mem: MemBuffer,
    det_sign: f64,
    factored: bool,
    pub factorisations: usize,
}

/// (−1)^(m − number of cycles) of the permutation given by its forward array.
pub fn permutation_sign(fwd: &[usize]) -> f64 {
    let m = fwd.len();
    let mut seen = vec![false; m];
    let mut cycles = 0;
    for start in 0..m {
        if seen[start] {
            continue;
        }
        cycles += 1;
        let mut i = start;
        while !seen[i] {
            seen[i] = true;
            i = fwd[i];
        }
    }
    if (m - cycles).is_multiple_of(2) {
        1.0
    } else {
        -1.0
    }
}

fn lu_error(e: LuError, nr: usize, nnz: usize) -> Error {
    match e {
        LuError::Generic(FaerError::OutOfMemory) => Error::numerical(format!(
            "out of memory while factorising the condensed tangent ({nr} unknowns, {nnz} nonzeros before fill-in)"
        )),
        LuError::Generic(e) => Error::numerical(format!(
            "the condensed tangent ({nr} unknowns) could not be factorised ({e:?})"
        )),
        LuError::SymbolicSingular { index } => Error::numerical(format!(
            "the bordered tangent is singular (no pivot at step {index} of {nr})"
        ))
        .hint("the branch may have reached a turning point of ω that the border cannot resolve"),
    }
}

impl CondensedTangent {
    pub fn new(sys: &System) -> Result<CondensedTangent> {
        let lay = sys.lay;
        let (n, nl) = (lay.n, lay.n_coef_lin);
        let nr = n * nl + 2;
        let mut union: BTreeMap<(usize, usize), Pair> = BTreeMap::new();
        for &(row, col, a) in &sys.k.entries {
            let p = union.entry((col, row)).or_insert(Pair {
                row,
                col,
                k: 0.0,
                m: 0.0,
                has_m: false,
            });
            p.k += a;
        }
        for &(row, col, a) in &sys.m.entries {
            let p = union.entry((col, row)).or_insert(Pair {
                row,
                col,
                k: 0.0,
                m: 0.0,
                has_m: false,
            });
            p.m += a;
            p.has_m = true;
        }
        let pairs: Vec<Pair> = union.into_values().collect();
        let mut has_mass = vec![false; n];
        for p in &pairs {
            if p.has_m {
                has_mass[p.row] = true;
            }
        }
        let mass_rows = (0..n).filter(|&i| has_mass[i]).collect();
        let mut rs = CondensedTangent {
            n,
            n_coef_lin: nl,
            h_lin: lay.h_lin,
            nr,
            pairs,
            mass_rows,
            shock_dofs: sys.shocks.iter().map(|s| s.dofs.clone()).collect(),
            ref_dof: sys.ref_dof,
            col_ptr: Vec::new(),
            row_idx: Vec::new(),
            pos: Vec::new(),
            vals: Vec::new(),
            a_col_ptr: Vec::new(),
            a_row_idx: Vec::new(),
            a_vals: Vec::new(),
            border: 0,
            col_perm: vec![0; nr],
            col_perm_inv: vec![0; nr],
            col_perm_sign: 1.0,
            row_perm: vec![0; nr],
            row_perm_inv: vec![0; nr],
            lu: SimplicialLu::new(),
            factor_mem: MemBuffer::try_new(simplicial::factorize_simplicial_numeric_lu_scratch::<
                usize,
                f64,
            >(nr, nr))
            .map_err(|_| out_of_memory(4 * nr, "the sparse LU workspace"))?,
            solve_mem: MemBuffer::try_new(simplicial::solve_in_place_scratch::<usize, f64>(
                nr,
                1,
                Par::Seq,
            ))
            .map_err(|_| out_of_memory(nr, "the sparse solve workspace"))?,
            det_sign: 0.0,
            factored: false,
            factorisations: 0,
        };
        rs.build_pattern()?;
        Ok(rs)
    }

    /// Every entry of the matrix but the border, in a fixed order; `lin` None: pattern only.
    fn visit(&self, lin: Option<&Linearisation>, f: &mut dyn FnMut(usize, usize, f64)) {
        let (nl, hl) = (self.n_coef_lin, self.h_lin);
        let (om, ga) = lin.map_or((0.0, 0.0), |lay| (lay.omega, lay.gamma));
        let u = |i: usize| i * nl;
        for p in &self.pairs {
            let (r, c) = (u(p.row), u(p.col));
            f(r, c, p.k);
            for k in 1..=hl {
                let kf = k as f64;
                let diag = p.k - om * om * kf * kf * p.m;
                let (ck, sk) = (fourier::ic(k), fourier::is(hl, k));
                f(r + ck, c + ck, diag);
                f(r + sk, c + sk, diag);
                if p.has_m {
                    f(r + ck, c + sk, ga * om * kf * p.m);
                    f(r + sk, c + ck, -ga * om * kf * p.m);
                }
            }
        }
        let (co, cg) = (self.n * nl, self.n * nl + 1);
        for &i in &self.mass_rows {
            for j in 0..nl {
                let row = u(i) + j;
                f(row, co, lin.map_or(0.0, |lay| lay.col_omega[row]));
                f(row, cg, lin.map_or(0.0, |lay| lay.col_gamma[row]));
            }
        }
        for (s, dofs) in self.shock_dofs.iter().enumerate() {
            let m = dofs.len() * nl;
            for (cc, &dc) in dofs.iter().enumerate() {
                for jc in 0..nl {
                    let col = cc * nl + jc;
                    for (cr, &dr) in dofs.iter().enumerate() {
                        for jr in 0..nl {
                            let row = cr * nl + jr;
                            let v = lin.map_or(0.0, |lay| -lay.schur[s][col * m + row]);
                            f(u(dr) + jr, u(dc) + jc, v);
                        }
                    }
                }
            }
        }
        for k in 1..=hl {
            f(self.n * nl, u(self.ref_dof) + fourier::is(hl, k), k as f64);
        }
    }

    fn build_pattern(&mut self) -> Result<()> {
        let nr = self.nr;
        let mut entries: Vec<(usize, usize)> = Vec::new();
        self.visit(None, &mut |r, c, _| entries.push((c, r)));
        let mut order: Vec<usize> = (0..entries.len()).collect();
        order.sort_by_key(|&k| entries[k]);
        let mut pos = vec![0; entries.len()];
        let mut col_ptr = vec![0usize; nr + 1];
        let mut row_idx = Vec::with_capacity(entries.len());
        let mut last: Option<(usize, usize)> = None;
        for &k in &order {
            let (c, r) = entries[k];
            if last != Some((c, r)) {
                row_idx.push(r);
                col_ptr[c + 1] += 1;
                last = Some((c, r));
            }
            pos[k] = row_idx.len() - 1;
        }
        for c in 0..nr {
            col_ptr[c + 1] += col_ptr[c];
        }
        self.vals = vec![0.0; row_idx.len()];
        self.a_col_ptr = vec![0; nr + 1];
        self.a_row_idx = vec![0; row_idx.len() + 1];
        self.a_vals = vec![0.0; row_idx.len() + 1];
        self.col_ptr = col_ptr;
        self.row_idx = row_idx;
        self.pos = pos;
        // Column ordering once, on the pattern without the border (one entry, wherever it
        // lands, changes the fill by at most one row).
        self.order_columns()?;
        self.col_perm_sign = permutation_sign(&self.col_perm);
        Ok(())
    }

    /// The column ordering, from the structure of the condensed matrix rather than from a
    /// fill-reducing ordering of all of it: away from the shock DOFs the harmonics do not
    /// couple (per harmonic k, K − (kΩ)²M on cos and sin, coupled by ±γΩkM), so the
    /// matrix is one block per harmonic with the pattern of K ∪ M, bordered by the columns
    /// the harmonics share. Order: COLAMD of K ∪ M (n × n) once, repeated for each
    /// harmonic (cos then sin of each DOF), the harmonic blocks one after the other; then
    /// every coefficient of the shock DOFs and of the phase condition's DOF (their Schur
    /// blocks and the phase row couple the harmonics); then Ω and γ (dense columns). The
    /// fill of each block is that of K ∪ M's LU, not that of a matrix 2H_l+1 times wider.
    fn order_columns(&mut self) -> Result<()> {
        let (n, nl, hl, nr) = (self.n, self.n_coef_lin, self.h_lin, self.nr);
        let mut cp = vec![0usize; n + 1];
        let mut ri = Vec::with_capacity(self.pairs.len());
        // `pairs` is sorted by (column, row) (the BTreeMap's keys).
        for p in &self.pairs {
            cp[p.col + 1] += 1;
            ri.push(p.row);
        }
        for c in 0..n {
            cp[c + 1] += cp[c];
        }
        let (mut fwd, mut inv) = (vec![0usize; n], vec![0usize; n]);
        let sym = SymbolicSparseColMatRef::new_checked(n, n, &cp, None, &ri);
        let mut mem = MemBuffer::try_new(colamd::order_scratch::<usize>(n, n, ri.len()))
            .map_err(|_| out_of_memory(ri.len(), "the column ordering"))?;
        colamd::order(
            &mut fwd,
            &mut inv,
            sym,
            colamd::Control::default(),
            MemStack::new(&mut mem),
        )
        .map_err(|e| lu_error(LuError::Generic(e), nr, ri.len()))?;
        let mut shared = vec![false; n];
        for d in self.shock_dofs.iter().flatten() {
            shared[*d] = true;
        }
        shared[self.ref_dof] = true;
        let mut order = Vec::with_capacity(nr);
        for k in 0..=hl {
            for &d in fwd.iter().filter(|&&d| !shared[d]) {
                order.push(d * nl + fourier::ic(k));
                if k > 0 {
                    order.push(d * nl + fourier::is(hl, k));
                }
            }
        }
        for &d in fwd.iter().filter(|&&d| shared[d]) {
            order.extend(d * nl..(d + 1) * nl);
        }
        order.extend([n * nl, n * nl + 1]);
        debug_assert_eq!(order.len(), nr);
        for (new, &old) in order.iter().enumerate() {
            self.col_perm_inv[old] = new;
        }
        self.col_perm = order;
        Ok(())
    }

    /// Assemble with `lin` and the local border e_`border`, and factorise.
    pub fn factor(&mut self, lin: &Linearisation, border: usize) -> Result<()> {
        self.factored = false;
        self.factorisations += 1;
        let mut vals = std::mem::take(&mut self.vals);
        vals.fill(0.0);
        let mut k = 0;
        let pos = std::mem::take(&mut self.pos);
        self.visit(Some(lin), &mut |_, _, v| {
            vals[pos[k]] += v;
            k += 1;
        });
        self.pos = pos;
        // Insert the border entry (row nr − 1, the largest index: last in its column).
        let nr = self.nr;
        let mut q = 0;
        for c in 0..nr {
            self.a_col_ptr[c] = q;
            let (s, e) = (self.col_ptr[c], self.col_ptr[c + 1]);
            self.a_row_idx[q..q + e - s].copy_from_slice(&self.row_idx[s..e]);
            self.a_vals[q..q + e - s].copy_from_slice(&vals[s..e]);
            q += e - s;
            if c == border {
                self.a_row_idx[q] = nr - 1;
                self.a_vals[q] = 1.0;
                q += 1;
            }
        }
        self.a_col_ptr[nr] = q;
        self.vals = vals;
        self.border = border;
        let a = SparseColMatRef::new(
            SymbolicSparseColMatRef::new_checked(nr, nr, &self.a_col_ptr, None, &self.a_row_idx),
            &self.a_vals,
        );
        let col_perm = PermRef::new_checked(&self.col_perm, &self.col_perm_inv, nr);
        simplicial::factorize_simplicial_numeric_lu(
            &mut self.row_perm,
            &mut self.row_perm_inv,
            &mut self.lu,
            a,
            col_perm,
            MemStack::new(&mut self.factor_mem),
        )
        .map_err(|e| lu_error(e, nr, q))?;
        // det = sign(P_r)·sign(P_c)·Π U_jj (L has a unit diagonal).
        let u = self.lu.u_factor_unsorted();

        let mut sign = permutation_sign(&self.row_perm) * self.col_perm_sign;
        for j in 0..nr {
            let rows = u.row_idx_of_col_raw(j);
            let d = rows
                .iter()
                .zip(u.val_of_col(j))
                .find(|(r, _)| **r == j)
                .map_or(0.0, |(_, v)| *v);
            if d == 0.0 || !d.is_finite() {
                return Err(Error::numerical(format!(
                    "the bordered tangent is singular (pivot {j} of {nr} is {d:e})"
                ))
                .hint("the branch may have reached a turning point of ω that the border cannot resolve"));
            }
            sign *= d.signum();
        }
        self.det_sign = sign;
        self.factored = true;
        Ok(())
    }

    /// Sign of the determinant of the factorised condensed matrix.
    pub fn det_sign(&self) -> f64 {
        self.det_sign
    }

    /// Solve in place (length nr).
    pub fn solve(&mut self, rhs: &mut [f64]) -> Result<()> {
        if !self.factored || rhs.len() != self.nr {
            return Err(Error::internal(
                "condensed solve without a factorisation or of the wrong size",
            ));
        }
        let nr = self.nr;
        self.lu.solve_in_place_with_conj(
            PermRef::new_checked(&self.row_perm, &self.row_perm_inv, nr),
            PermRef::new_checked(&self.col_perm, &self.col_perm_inv, nr),
            Conj::No,
            MatMut::from_column_major_slice_mut(rhs, nr, 1),
            Par::Seq,
            MemStack::new(&mut self.solve_mem),
        );
        if rhs.iter().any(|v| !v.is_finite()) {
            return Err(Error::numerical(
                "the bordered tangent is numerically singular (solution not finite)",
            ));
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn permutation_parity() {
        assert_eq!(permutation_sign(&[0, 1, 2, 3]), 1.0);
        assert_eq!(permutation_sign(&[1, 0, 2, 3]), -1.0);
        assert_eq!(permutation_sign(&[1, 2, 0, 3]), 1.0);
        assert_eq!(permutation_sign(&[1, 0, 3, 2]), 1.0);
        assert_eq!(permutation_sign(&[3, 0, 1, 2]), -1.0);
    }
}
