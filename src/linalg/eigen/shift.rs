//! Sparse LDLᵀ factorisation of the shifted matrix K − σM: the linear solves of
//! shift-invert Lanczos, and Sylvester's inertia (the number of negative pivots of
//! K − σM is the number of eigenvalues ω² < σ), which tells how many modes a band holds.
//!
//! The factorisation is faer's sparse Cholesky machinery in LDLᵀ form with an AMD
//! ordering and no pivoting. Without pivoting an indefinite K − σM can in principle give
//! an inaccurate factor; the callers therefore check the true residuals of the modes.

use super::sym::SymSparse;
use crate::error::{Error, Result};
use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::cholesky::ldlt::factor::LdltRegularization;
use faer::sparse::linalg::cholesky::{
    factorize_symbolic_cholesky, simplicial::SimplicialLdltRef, supernodal::SupernodalLdltRef,
    CholeskySymbolicParams, LdltRef, SymbolicCholesky, SymbolicCholeskyRaw, SymmetricOrdering,
};
use faer::sparse::linalg::SupernodalThreshold;
use faer::sparse::{SparseColMat, SparseColMatRef};
use faer::{Conj, MatMut, Side};
use std::rc::Rc;

/// Which factorisation variant faer uses (tests force each one; `Auto` elsewhere).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum FactorKind {
    #[default]
    Auto,
    Simplicial,
    Supernodal,
}

/// The pattern of K − σM common to every σ of one problem (the entries of K and of M and
/// the whole diagonal), the values of K and of M on it, and its symbolic factorisation
/// (AMD ordering and analysis). Spectrum slicing factorises tens of shifts of one problem;
/// with this each one only refills the values and factorises numerically, where
/// [`ShiftedFactor::new`] assembles from triplets, orders and analyses again.
pub struct ShiftPattern {
    /// The pattern (its values are K's).
    structure: SparseColMat<usize, f64>,
    k_val: Vec<f64>,
    /// M's values on the same pattern.
    m_val: Vec<f64>,
    k_diag: Vec<f64>,
    m_diag: Vec<f64>,
    symbolic: Rc<SymbolicCholesky<usize>>,
}

impl ShiftPattern {
    pub fn new(k: &SymSparse, m: &SymSparse, kind: FactorKind) -> Result<Self> {
        let (structure, m_val) = SymSparse::shift_pattern(k, m)?;
        let symbolic = Rc::new(symbolic_of(&structure, kind)?);
        Ok(ShiftPattern {
            k_val: structure.val().to_vec(),
            m_val,
            k_diag: k.diag(),
            m_diag: m.diag(),
            structure,
            symbolic,
        })
    }
}

/// AMD ordering and symbolic analysis of the lower triangle `a`.
fn symbolic_of(a: &SparseColMat<usize, f64>, kind: FactorKind) -> Result<SymbolicCholesky<usize>> {
    let params = CholeskySymbolicParams {
        supernodal_flop_ratio_threshold: match kind {
            FactorKind::Auto => SupernodalThreshold::AUTO,
            FactorKind::Simplicial => SupernodalThreshold::FORCE_SIMPLICIAL,
            FactorKind::Supernodal => SupernodalThreshold::FORCE_SUPERNODAL,
        },
        ..Default::default()
    };
    factorize_symbolic_cholesky(a.symbolic(), Side::Lower, SymmetricOrdering::Amd, params)
        .map_err(|e| Error::numerical(format!("symbolic factorisation of K - σM failed: {e:?}")))
}

/// LDLᵀ of K − σM, reusable for many solves.
pub struct ShiftedFactor {
    pub sigma: f64,
    symbolic: Rc<SymbolicCholesky<usize>>,
    values: Vec<f64>,
    /// Pivots D in the factor's (permuted) order.
    pivots: Vec<f64>,
    /// Diagonal of K − σM in the factor's order, to judge pivots relative to it.
    diag: Vec<f64>,
    stack: MemBuffer,
}

impl ShiftedFactor {
    pub fn new(k: &SymSparse, m: &SymSparse, sigma: f64, kind: FactorKind) -> Result<Self> {
        let a = SymSparse::shifted_lower(k, m, sigma)?;
        let symbolic = Rc::new(symbolic_of(&a, kind)?);
        let mut diag = k.diag();
        for (di, mi) in diag.iter_mut().zip(m.diag()) {
            *di -= sigma * mi;
        }
        Self::numeric(symbolic, a.as_ref(), sigma, diag)
    }

    /// The factor at σ on a problem's [`ShiftPattern`]: no assembly, ordering or symbolic
    /// analysis, and the same factor as [`ShiftedFactor::new`] on that pattern.
    pub fn from_pattern(p: &ShiftPattern, sigma: f64) -> Result<Self> {
        // k + (−σ)·m, the sum the triplet assembly of `new` makes of the same two entries.
        let values: Vec<f64> = p
            .k_val
            .iter()
            .zip(&p.m_val)
            .map(|(k, m)| k + (-sigma) * m)
            .collect();
        let a = SparseColMatRef::new(p.structure.symbolic(), &values);
        let diag = p
            .k_diag
            .iter()
            .zip(&p.m_diag)
            .map(|(k, m)| k - sigma * m)
            .collect();
        Self::numeric(Rc::clone(&p.symbolic), a, sigma, diag)
    }

    /// Numeric LDLᵀ of `a` (lower triangle of K − σM, `full_diag` its diagonal) on its
    /// symbolic factorisation.
    fn numeric(
        symbolic: Rc<SymbolicCholesky<usize>>,
        a: SparseColMatRef<'_, usize, f64>,
        sigma: f64,
        full_diag: Vec<f64>,
    ) -> Result<Self> {
        let n = a.nrows();
        let mut values = vec![0.0; symbolic.len_val()];
        let par = faer::get_global_parallelism();
        let mut buf = MemBuffer::try_new(
            symbolic.factorize_numeric_ldlt_scratch::<f64>(par, Default::default()),
        )
        .map_err(|_| Error::numerical("out of memory factorising K - σM"))?;
        symbolic
            .factorize_numeric_ldlt(
                &mut values,
                a,
                Side::Lower,
                LdltRegularization::default(),
                par,
                MemStack::new(&mut buf),
                Default::default(),
            )
            .map_err(|e| {
                Error::numerical(format!(
                    "K - σM is singular for σ = {sigma:e} ({e:?}): σ is an eigenvalue"
                ))
            })?;
        let pivots = extract_pivots(&symbolic, &values, n);
        let diag = match symbolic.perm() {
            Some(p) => p.arrays().0.iter().map(|&f| full_diag[f]).collect(),
            None => full_diag,
        };
        let stack = MemBuffer::try_new(symbolic.solve_in_place_scratch::<f64>(1, par))
            .map_err(|_| Error::numerical("out of memory for the solve workspace"))?;
        Ok(ShiftedFactor {
            sigma,
            symbolic,
            values,
            pivots,
            diag,
            stack,
        })
    }

    /// x ← (K − σM)⁻¹ x.
    pub fn solve_in_place(&mut self, x: &mut [f64]) {
        let n = x.len();
        let rhs = MatMut::from_column_major_slice_mut(x, n, 1);
        LdltRef::new(&self.symbolic, &self.values).solve_in_place_with_conj(
            Conj::No,
            rhs,
            faer::get_global_parallelism(),
            MemStack::new(&mut self.stack),
        );
    }

    /// Sylvester: number of eigenvalues of (K, M) strictly below σ.
    pub fn negative_count(&self) -> usize {
        self.pivots.iter().filter(|&&d| d < 0.0).count()
    }

    /// Smallest |pivot| relative to the diagonal entry it came from: a value near round-off
    /// means K − σM is numerically singular (σ at an eigenvalue, e.g. σ = 0 with rigid modes).
    pub fn min_relative_pivot(&self) -> f64 {
        let scale = self.diag.iter().fold(0.0f64, |a, d| a.max(d.abs()));
        self.pivots
            .iter()
            .zip(&self.diag)
            .map(|(p, d)| {
                let r = if d.abs() > 0.0 { d.abs() } else { scale };
                if r > 0.0 {
                    p.abs() / r
                } else {
                    0.0
                }
            })
            .fold(f64::INFINITY, f64::min)
    }
}

/// D of the LDLᵀ factor: first entry of each column (simplicial), diagonal of each
/// supernode's diagonal block (supernodal).
fn extract_pivots(symbolic: &SymbolicCholesky<usize>, values: &[f64], n: usize) -> Vec<f64> {
    let mut d = vec![0.0; n];
    match symbolic.raw() {
        SymbolicCholeskyRaw::Simplicial(s) => {
            let l = SimplicialLdltRef::new(s, values);
            let cp = l.symbolic().col_ptr();
            for (j, dj) in d.iter_mut().enumerate() {
                *dj = values[cp[j]];
            }
        }
        SymbolicCholeskyRaw::Supernodal(s) => {
            let l = SupernodalLdltRef::new(s, values);
            for sn in 0..s.n_supernodes() {
                let node = l.supernode(sn);
                let v = node.val();
                for c in 0..v.ncols() {
                    d[node.start() + c] = v[(c, c)];
                }
            }
        }
    }
    d
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Fixed-fixed chain K = tridiag(-1, 2, -1), M = I: eigenvalues 4 sin²(jπ/(2(N+1))).
    fn chain(n: usize) -> (SymSparse, SymSparse) {
        let mut kt = Vec::new();
        let mut mt = Vec::new();
        for i in 0..n {
            kt.push((i, i, 2.0));
            mt.push((i, i, 1.0));
            if i + 1 < n {
                kt.push((i + 1, i, -1.0));
            }
        }
        (
            SymSparse::from_lower_triplets(n, &kt),
            SymSparse::from_lower_triplets(n, &mt),
        )
    }

    #[test]
    fn inertia_counts_eigenvalues_below_shift_both_variants() {
        let n = 300;
        let (k, m) = chain(n);
        let lam = |j: usize| {
            let s = (j as f64 * std::f64::consts::PI / (2.0 * (n as f64 + 1.0))).sin();
            4.0 * s * s
        };
        for kind in [FactorKind::Simplicial, FactorKind::Supernodal] {
            for j in [1usize, 7, 150, 299] {
                // A shift halfway between eigenvalues j and j+1: exactly j below it.
                let sigma = if j < n {
                    0.5 * (lam(j) + lam(j + 1))
                } else {
                    lam(n) + 1.0
                };
                let f = ShiftedFactor::new(&k, &m, sigma, kind).unwrap();
                assert_eq!(
                    f.negative_count(),
                    j,
                    "{kind:?} σ between modes {j} and {}",
                    j + 1
                );
            }
        }
    }

    #[test]
    fn factor_on_the_shared_pattern_is_the_same_factor() {
        // The same pattern (K and M are both tridiagonal), so the same ordering and the same
        // sums k − σm: pivots and solves equal to the last bit.
        let n = 400;
        let (k, m) = chain(n);
        for kind in [FactorKind::Simplicial, FactorKind::Supernodal] {
            let pattern = ShiftPattern::new(&k, &m, kind).unwrap();
            for sigma in [0.37, 1.9, -0.2] {
                let mut a = ShiftedFactor::new(&k, &m, sigma, kind).unwrap();
                let mut b = ShiftedFactor::from_pattern(&pattern, sigma).unwrap();
                assert_eq!(a.negative_count(), b.negative_count());
                assert_eq!(a.pivots, b.pivots, "{kind:?} σ = {sigma}");
                let mut x: Vec<f64> = (0..n).map(|i| ((i * 5 % 17) as f64) - 8.0).collect();
                let mut y = x.clone();
                a.solve_in_place(&mut x);
                b.solve_in_place(&mut y);
                assert_eq!(x, y, "{kind:?} σ = {sigma}");
            }
        }
    }

    #[test]
    fn solve_reproduces_right_hand_side() {
        let n = 500;
        let (k, m) = chain(n);
        for kind in [FactorKind::Simplicial, FactorKind::Supernodal] {
            let sigma = 0.37; // inside the spectrum: an indefinite K − σM
            let mut f = ShiftedFactor::new(&k, &m, sigma, kind).unwrap();
            let b: Vec<f64> = (0..n).map(|i| ((i * 7 % 13) as f64) - 6.0).collect();
            let mut x = b.clone();
            f.solve_in_place(&mut x);
            let mut kx = vec![0.0; n];
            let mut mx = vec![0.0; n];
            k.mul(&x, &mut kx);
            m.mul(&x, &mut mx);
            let err: f64 = (0..n)
                .map(|i| (kx[i] - sigma * mx[i] - b[i]).abs())
                .fold(0.0, f64::max);
            // The shifted chain is well conditioned away from eigenvalues: residual at
            // round-off level times the matrix norm (≤ 4) and the solution size.
            let xmax = x.iter().fold(0.0f64, |a, v| a.max(v.abs()));
            assert!(err < 1e-10 * xmax.max(1.0), "{kind:?}: residual {err}");
        }
    }
}
