//! Craig–Bampton reduction of a structure onto a few retained DOFs and its fixed-interface
//! normal modes.
//!
//! The free DOFs split into the retained set B (the shock DOFs) and the interior I. The
//! basis T has one column per retained DOF, its constraint mode (unit motion of that DOF,
//! the others of B held, the interior in static equilibrium: ψ = −K_II⁻¹ K_IB), and one
//! column per fixed-interface mode (K_II φ = ω² M_II φ, M_II-orthonormal, zero on B):
//!
//! ```text
//!         B     modes
//! T = [ I_B     0  ]   B
//!     [ Ψ       Φ  ]   I
//! ```
//!
//! The reduced coordinates are the retained DOFs' own displacements, then the modal
//! amplitudes, so a law acting on a retained DOF reads it unchanged. The reduced matrices
//! are Tᵀ K T (the condensed stiffness of B and diag(ω²), coupled only by round-off) and
//! Tᵀ M T (the retained block, its coupling with the modes, and the identity): an
//! arrowhead, stored as such. Why constraint modes rather than free-interface modes with
//! attachment modes: the shock DOFs stay physical coordinates, and the static response of
//! the whole structure to the shock forces is exact whatever the number of modes kept;
//! what truncation loses is the dynamic part of the interior modes above the cut-off, of
//! relative order (ω_harmonic / ω_cut)².

use crate::error::{Error, Result};
use crate::linalg::eigen::shift::{FactorKind, ShiftedFactor};
use crate::linalg::eigen::sym::{dot, SymSparse};
use crate::linalg::eigen::{frequency, omega2_of, solve_modes_sym, EigenOptions, ModeRequest};
use crate::linalg::sparse::{from_triplets, reduced};
use faer::sparse::SparseColMat;

/// Which fixed-interface modes the basis keeps.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum ModeCut {
    /// The `n` lowest (fewer if the interior has fewer DOFs).
    Count(usize),
    /// Every mode up to this frequency (Hz).
    UpTo(f64),
}

/// A relative pivot of K_II below this means the interior is not held by the retained DOFs
/// and the supports (a mechanism once the shock DOFs are fixed): no constraint mode exists.
const SINGULAR_PIVOT: f64 = 1e-13;

/// Largest relative residual of a fixed-interface mode kept. The basis needs a subspace,
/// not exact modes: the reduced matrices are exact projections on whatever columns it has
/// (the couplings of an inexact mode are computed, [`EXACT_MODE`]). The high modes of a
/// fine beam mesh come out of the dense solver with residuals of 1e-5 (148 interior DOFs,
/// modes near 16 kHz), refused by CALC_MODES's 1e-6 and still good basis vectors; 1e-2
/// refuses only a failed solve.
const BASIS_MODE_RESIDUAL: f64 = 1e-2;

/// Shift-invert Lanczos's convergence tolerance for the fixed-interface modes (CALC_MODES:
/// 1e-12). The basis needs a subspace ([`BASIS_MODE_RESIDUAL`]); the modes it gives still
/// have residuals far below [`EXACT_MODE`] (measured below).
const BASIS_LANCZOS_TOL: f64 = 1e-9;

/// A mode whose relative residual is at most this (CALC_MODES's own acceptance) is taken
/// as exact: its coupling with the other modes (φᵢᵀKφⱼ, about the residual times ω², and
/// φᵢᵀMφⱼ, zero for M-orthonormal vectors) is not computed. Dropping it moves a low
/// frequency by the residual times the share of the high modes in the low motion, of order
/// (ω/ω_i)²: far below the truncation. Measured on the 10⁵-DOF tube (364 Lanczos modes):
/// with a bound of 1e-10 the couplings of the modes it counted as inexact filled the
/// matrices and the branches took 217 s instead of 3 to 5 s, for the same last row to 1.4e-7.
const EXACT_MODE: f64 = 1e-6;

/// The basis of a Craig–Bampton reduction.
#[derive(Clone, Debug)]
pub struct Reduction {
    /// Free DOFs of the full model.
    pub n: usize,
    /// The retained DOFs (indices into the free DOFs), the first reduced coordinates.
    pub retained: Vec<usize>,
    /// ω² of the fixed-interface modes kept, ascending (the last reduced coordinates).
    pub omega2: Vec<f64>,
    /// The relative residual of each of those modes (‖Kφ − ω²Mφ‖ relative, linalg/eigen).
    pub residuals: Vec<f64>,
    /// The columns of T, `n` entries each: one per retained DOF, then one per mode.
    pub columns: Vec<Vec<f64>>,
}

impl Reduction {
    /// Number of reduced coordinates.
    pub fn size(&self) -> usize {
        self.columns.len()
    }

    /// Tᵀ K T of the stiffness on the free DOFs: the condensed stiffness of the retained
    /// DOFs and the diagonal φᵢᵀKφᵢ of the modes (ω², to their residual). The blocks the
    /// construction makes zero are not stored: a constraint mode is K-orthogonal to any
    /// vector zero on the retained DOFs (φᵀKψ = φᵀ(K_II ψ_I + K_IB) = 0), and exact modes
    /// to each other.
    pub fn project_stiffness(
        &self,
        k: &SparseColMat<usize, f64>,
    ) -> Result<SparseColMat<usize, f64>> {
        self.project(k, "stiffness", false)
    }

    /// Tᵀ M T of the mass on the free DOFs: the retained DOFs' block, their inertial
    /// coupling with every mode, and the modes' diagonal (1, M-orthonormal); the zero
    /// coupling of exact modes with each other is not stored.
    pub fn project_mass(&self, m: &SparseColMat<usize, f64>) -> Result<SparseColMat<usize, f64>> {
        self.project(m, "mass", true)
    }

    /// Tᵀ A T without the entries that are zero by construction: an arrowhead (retained
    /// block, retained–modal block when `coupled`, modal diagonal), plus the couplings of
    /// every mode that is not exact ([`EXACT_MODE`]) so that the projection stays exact
    /// whatever the modes' accuracy. Symmetric, both triangles stored. Its sparsity is what
    /// keeps the harmonic balance's linear part cheap on hundreds of modes.
    fn project(
        &self,
        a: &SparseColMat<usize, f64>,
        what: &str,
        coupled: bool,
    ) -> Result<SparseColMat<usize, f64>> {
        let sym = SymSparse::from_faer(a, what)?;
        if sym.n != self.n {
            return Err(Error::internal(format!(
                "{what} matrix has {} DOFs, the reduction basis {}",
                sym.n, self.n
            )));
        }
        let b = self.retained.len();
        // A mode without a residual, or with a NaN one, is not known exact.
        let exact = |c: usize| self.residuals.get(c - b).is_some_and(|&r| r <= EXACT_MODE);
        let inexact = |c: usize| c >= b && !exact(c);
        // A t_i of the retained columns, kept: a mode's coupling with them is (A t_i)ᵀ t_j.
        // A mode's own column needs A t_j only when it couples with other modes (inexact);
        // its diagonal is the quadratic form, one read-only sweep of A instead of a product
        // (a scatter into a vector of n) and a dot.
        let mut a_ret: Vec<Vec<f64>> = Vec::with_capacity(b);
        let mut at = vec![0.0; self.n];
        let mut t = Vec::new();
        let mut push = |i: usize, j: usize, v: f64| {
            t.push((i, j, v));
            if i != j {
                t.push((j, i, v));
            }
        };
        for (j, tj) in self.columns.iter().enumerate() {
            if j < b {
                let mut a_tj = vec![0.0; self.n];
                sym.mul(tj, &mut a_tj);
                for i in 0..=j {
                    push(i, j, dot(&self.columns[i], &a_tj));
                }
                a_ret.push(a_tj);
                continue;
            }
            if coupled {
                for (i, a_ti) in a_ret.iter().enumerate() {
                    push(i, j, dot(a_ti, tj));
                }
            }
            let modal: Vec<usize> = (b..j).filter(|&i| inexact(i) || inexact(j)).collect();
            if modal.is_empty() {
                push(j, j, sym.quadratic(tj));
            } else {
                sym.mul(tj, &mut at);
                for i in modal.into_iter().chain([j]) {
                    push(i, j, dot(&self.columns[i], &at));
                }
            }
        }
        let r = self.size();
        from_triplets(r, r, &t)
    }

    /// The full-model vector T q of reduced coordinates `q`, into `out` (`n` entries).
    pub fn expand_into(&self, q: &[f64], out: &mut [f64]) {
        out.fill(0.0);
        for (qj, tj) in q.iter().zip(&self.columns) {
            if *qj != 0.0 {
                for (o, t) in out.iter_mut().zip(tj) {
                    *o += qj * t;
                }
            }
        }
    }

    /// Per full-model DOF, the series `per_coordinate` gives per reduced coordinate (all of
    /// one length: Fourier coefficients, time samples), each entry expanded by T.
    pub fn expand_series(&self, per_coordinate: &[Vec<f64>]) -> Vec<Vec<f64>> {
        let len = per_coordinate.first().map_or(0, Vec::len);
        let mut out = vec![vec![0.0; len]; self.n];
        for (series, tj) in per_coordinate.iter().zip(&self.columns) {
            for (o, &t) in out.iter_mut().zip(tj) {
                if t != 0.0 {
                    for (oi, si) in o.iter_mut().zip(series) {
                        *oi += t * si;
                    }
                }
            }
        }
        out
    }

    /// The reduced coordinates of a full-model vector `u`: its retained DOFs, and the modal
    /// amplitudes of what is left on the interior once the constraint modes are taken out
    /// (φᵢᵀ M (u − Ψ u_B), exact for the M-orthonormal fixed-interface modes). T of the
    /// result equals `u` when `u` lies in the span of the basis.
    pub fn coordinates(&self, m: &SymSparse, u: &[f64]) -> Result<Vec<f64>> {
        if u.len() != self.n || m.n != self.n {
            return Err(Error::internal(format!(
                "a vector of {} entries against a reduction of {} DOFs",
                u.len(),
                self.n
            )));
        }
        let b = self.retained.len();
        let mut q: Vec<f64> = self.retained.iter().map(|&i| u[i]).collect();
        let mut rest = u.to_vec();
        for (qj, tj) in q.iter().zip(&self.columns[..b]) {
            for (r, t) in rest.iter_mut().zip(tj) {
                *r -= qj * t;
            }
        }
        let mut m_rest = vec![0.0; self.n];
        m.mul(&rest, &mut m_rest);
        q.extend(self.columns[b..].iter().map(|phi| dot(phi, &m_rest)));
        Ok(q)
    }
}

/// The Craig–Bampton basis of the free-DOF matrices `k`, `m` retaining the DOFs `retained`
/// (distinct indices into the free DOFs) with the fixed-interface modes `cut` asks for, in
/// at most `max_columns` columns (refused before any mode is computed when more are needed:
/// the caller sizes it from the memory available and a bound of its own).
pub fn craig_bampton(
    k: &SparseColMat<usize, f64>,
    m: &SparseColMat<usize, f64>,
    retained: &[usize],
    cut: ModeCut,
    max_columns: usize,
) -> Result<Reduction> {
    let n = k.nrows();
    let mut is_retained = vec![false; n];
    for &i in retained {
        match is_retained.get_mut(i) {
            Some(r) if !*r => *r = true,
            Some(_) => {
                return Err(Error::internal(format!(
                    "DOF {i} retained twice in a reduction"
                )))
            }
            None => {
                return Err(Error::internal(format!(
                    "retained DOF {i} outside the {n} free DOFs"
                )))
            }
        }
    }
    let interior: Vec<usize> = (0..n).filter(|&i| !is_retained[i]).collect();
    let ni = interior.len();
    // One matrix's triplets at a time, freed before the modes are computed (24 bytes per
    // entry of the full model: 0.6 GB for K and M at 10⁶ DOFs).
    let k_ii = SymSparse::from_faer(&reduced(n, &triplets(k), &is_retained)?, "stiffness")?;
    let m_ii = SymSparse::from_faer(&reduced(n, &triplets(m), &is_retained)?, "mass")?;

    // Constraint modes: Ψ = −K_II⁻¹ K_IB, one solve per retained DOF.
    let mut columns = Vec::with_capacity(retained.len());
    if !retained.is_empty() && ni > 0 {
        let not_held = || {
            Error::validation(
                "the structure is not held once its shock DOFs are fixed (the stiffness of the \
                 other DOFs is singular or not positive): the constraint modes of the reduction \
                 do not exist",
            )
            .hint("block the rigid-body motions of the structure, or compute without REDUCTION")
        };
        let mut factor =
            ShiftedFactor::new(&k_ii, &m_ii, 0.0, FactorKind::Auto).map_err(|_| not_held())?;
        if factor.negative_count() > 0 || factor.min_relative_pivot() < SINGULAR_PIVOT {
            return Err(not_held());
        }
        // Column b of K, whichever triangles its storage holds.
        let k_full = SymSparse::from_faer(k, "stiffness")?;
        let (mut unit, mut k_col) = (vec![0.0; n], vec![0.0; n]);
        for &b in retained {
            unit[b] = 1.0;
            k_full.mul(&unit, &mut k_col);
            unit[b] = 0.0;
            let mut rhs: Vec<f64> = interior.iter().map(|&i| -k_col[i]).collect();
            factor.solve_in_place(&mut rhs);
            let mut col = vec![0.0; n];
            col[b] = 1.0;
            for (p, &i) in interior.iter().enumerate() {
                col[i] = rhs[p];
            }
            columns.push(col);
        }
    } else {
        for &b in retained {
            let mut col = vec![0.0; n];
            col[b] = 1.0;
            columns.push(col);
        }
    }

    // Fixed-interface modes. A band is asked as its count of lowest modes (Sylvester's inertia at the cut-off,
    // one factorisation): shift-invert Lanczos asked for a band of the clustered spectrum of
    // a multi-span tube (5088 DOFs, every mode up to 8.9 kHz) returned a mode with a residual
    // of 0.1, asked for the same modes by count it converged.
    let modes_asked = match cut {
        _ if ni == 0 => 0,
        ModeCut::Count(c) => c.min(ni),
        ModeCut::UpTo(f) => ShiftedFactor::new(&k_ii, &m_ii, omega2_of(f), FactorKind::Auto)
            .map_err(|_| {
                Error::validation(format!(
                    "the cut-off {f:e} Hz is a frequency of the structure with its shock DOFs held"
                ))
                .hint("move the cut-off a little")
            })?
            .negative_count(),
    };
    if retained.len() + modes_asked > max_columns {
        return Err(Error::validation(format!(
            "the reduction basis would have {} columns of {n} DOFs ({} shock DOF(s), \
             {modes_asked} mode(s)), more than the {max_columns} allowed (by the memory \
             available, and at most a few thousand: a basis is meant to be small)",
            retained.len() + modes_asked,
            retained.len()
        ))
        .hint("lower the cut-off (FREQ_COUPURE, COEF_COUPURE) or NB_MODE"));
    }
    let request = ModeRequest::Smallest { n: modes_asked };
    let wants_modes = modes_asked > 0;
    let (mut omega2, mut residuals) = (Vec::new(), Vec::new());
    if wants_modes {
        let opts = EigenOptions {
            max_residual: BASIS_MODE_RESIDUAL,
            tol: BASIS_LANCZOS_TOL,
            ..EigenOptions::default()
        };
        let modes = solve_modes_sym(&k_ii, &m_ii, &request, &opts)?;
        residuals = modes.residuals;
        for (w, v) in modes.omega2.into_iter().zip(modes.vectors) {
            let mut col = vec![0.0; n];
            for (p, &i) in interior.iter().enumerate() {
                col[i] = v[p];
            }
            omega2.push(w);
            columns.push(col);
        }
    }
    Ok(Reduction {
        n,
        retained: retained.to_vec(),
        omega2,
        residuals,
        columns,
    })
}

/// The cut-off frequency (Hz) of a mode count: the frequency of the highest mode kept.
pub fn highest_frequency(red: &Reduction) -> Option<f64> {
    red.omega2.last().map(|&w| frequency(w))
}

/// The Rayleigh quotient xᵀKx / xᵀMx: ω² of a mode shape `x` on a (reduced) model.
pub fn rayleigh(
    k: &SparseColMat<usize, f64>,
    m: &SparseColMat<usize, f64>,
    x: &[f64],
) -> Result<f64> {
    let ks = SymSparse::from_faer(k, "stiffness")?;
    let ms = SymSparse::from_faer(m, "mass")?;
    Ok(ks.form(x, x) / ms.form(x, x))
}

fn triplets(a: &SparseColMat<usize, f64>) -> Vec<(usize, usize, f64)> {
    let sym = a.symbolic();
    let (cp, ri, v) = (sym.col_ptr(), sym.row_idx(), a.val());
    let mut t = Vec::with_capacity(v.len());
    for j in 0..a.ncols() {
        for p in cp[j]..cp[j + 1] {
            t.push((ri[p], j, v[p]));
        }
    }
    t
}

#[cfg(test)]
mod tests;
