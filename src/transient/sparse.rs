//! [`SparseStructure`]: physical matrices on the free DOFs (BASE_CALCUL='PHYS', an
//! aster-nl extension), lower-triangle triplets, products through
//! [`crate::linalg::eigen::sym::SymSparse`] and faer's sparse LDLᵀ (AMD ordering, as
//! `linalg/eigen/shift.rs`) for M and for a_m M + a_c C + a_k K.

use super::error::{invalid, TransientError};
use super::structure::{LinearSolver, Structure};
use crate::linalg::eigen::sym::SymSparse;
use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::cholesky::ldlt::factor::LdltRegularization;
use faer::sparse::linalg::cholesky::{
    factorize_symbolic_cholesky, CholeskySymbolicParams, LdltRef, SymbolicCholesky,
    SymmetricOrdering,
};
use faer::sparse::{SparseColMat, Triplet};
use faer::{Conj, MatMut, Side};
use std::cell::RefCell;

/// Lower-triangle triplets (i, j, value).
type Triplets<'a> = &'a [(usize, usize, f64)];

/// LDLᵀ of a sparse symmetric matrix with its solve workspace.
struct SparseLdlt {
    symbolic: SymbolicCholesky<usize>,
    values: Vec<f64>,
    stack: MemBuffer,
}

impl SparseLdlt {
    /// Factorises Σ w_i A_i given as lower triplets (i ≥ j), a diagonal entry kept for
    /// every row. A zero or negative pivot (M or the implicit matrix not definite) is an
    /// error.
    fn new(n: usize, parts: &[(Triplets, f64)], what: &str) -> Result<SparseLdlt, TransientError> {
        let singular = |detail: String| TransientError::Singular {
            what: format!("{what} ({detail})"),
        };
        let mut t = Vec::with_capacity(n + parts.iter().map(|p| p.0.len()).sum::<usize>());
        for i in 0..n {
            t.push(Triplet::new(i, i, 0.0));
        }
        for &(entries, w) in parts {
            if w == 0.0 {
                continue;
            }
            for &(i, j, v) in entries {
                let (i, j) = if i >= j { (i, j) } else { (j, i) };
                t.push(Triplet::new(i, j, w * v));
            }
        }
        let a = SparseColMat::try_new_from_triplets(n, n, &t)
            .map_err(|e| singular(format!("{e:?}")))?;
        let symbolic = factorize_symbolic_cholesky(
            a.symbolic(),
            Side::Lower,
            SymmetricOrdering::Amd,
            CholeskySymbolicParams::default(),
        )
        .map_err(|e| singular(format!("{e:?}")))?;
        let mut values = vec![0.0; symbolic.len_val()];
        let par = faer::Par::Seq;
        let mut buf = MemBuffer::try_new(
            symbolic.factorize_numeric_ldlt_scratch::<f64>(par, Default::default()),
        )
        .map_err(|_| TransientError::OutOfMemory {
            what: format!("factorising {what}"),
            bytes: 0,
        })?;
        symbolic
            .factorize_numeric_ldlt(
                &mut values,
                a.as_ref(),
                Side::Lower,
                LdltRegularization::default(),
                par,
                MemStack::new(&mut buf),
                Default::default(),
            )
            .map_err(|e| singular(format!("{e:?}")))?;
        let stack =
            MemBuffer::try_new(symbolic.solve_in_place_scratch::<f64>(1, par)).map_err(|_| {
                TransientError::OutOfMemory {
                    what: format!("the solve workspace of {what}"),
                    bytes: 0,
                }
            })?;
        let f = SparseLdlt {
            symbolic,
            values,
            stack,
        };
        Ok(f)
    }

    fn solve(&mut self, x: &mut [f64]) {
        let n = x.len();
        let rhs = MatMut::from_column_major_slice_mut(x, n, 1);
        LdltRef::new(&self.symbolic, &self.values).solve_in_place_with_conj(
            Conj::No,
            rhs,
            faer::Par::Seq,
            MemStack::new(&mut self.stack),
        );
    }
}

impl LinearSolver for SparseLdlt {
    fn solve(&mut self, x: &mut [f64]) -> Result<(), TransientError> {
        SparseLdlt::solve(self, x);
        if x.iter().all(|v| v.is_finite()) {
            Ok(())
        } else {
            Err(TransientError::Singular {
                what: "the implicit matrix (the solve gave NaN)".into(),
            })
        }
    }
}

/// Physical M, K, C (lower-triangle triplets of the free DOFs).
pub struct SparseStructure {
    n: usize,
    m_t: Vec<(usize, usize, f64)>,
    k_t: Vec<(usize, usize, f64)>,
    c_t: Option<Vec<(usize, usize, f64)>>,
    m: SymSparse,
    k: SymSparse,
    c: Option<SymSparse>,
    mass_factor: RefCell<SparseLdlt>,
}

fn check_triplets(what: &str, n: usize, t: &[(usize, usize, f64)]) -> Result<(), TransientError> {
    match t
        .iter()
        .find(|&&(i, j, v)| i >= n || j >= n || !v.is_finite())
    {
        Some(&(i, j, v)) => Err(invalid(
            what,
            format!("entry ({i}, {j}) = {v:e} is outside the {n} free DOFs or not finite"),
        )),
        None => Ok(()),
    }
}

impl SparseStructure {
    /// From lower-triangle triplets (i ≥ j; an upper entry is read as its transpose;
    /// duplicates are summed). M must be positive definite on the free DOFs.
    pub fn new(
        n: usize,
        mass: Vec<(usize, usize, f64)>,
        stiffness: Vec<(usize, usize, f64)>,
        damping: Option<Vec<(usize, usize, f64)>>,
    ) -> Result<SparseStructure, TransientError> {
        check_triplets("MATR_MASS", n, &mass)?;
        check_triplets("MATR_RIGI", n, &stiffness)?;
        if let Some(c) = &damping {
            check_triplets("MATR_AMOR", n, c)?;
        }
        let mass_factor = SparseLdlt::new(n, &[(&mass, 1.0)], "MATR_MASS")?;
        let m = SymSparse::from_lower_triplets(n, &mass);
        // A definite M has positive pivots; faer's LDLᵀ does not pivot, so check them via
        // the diagonal of the factor indirectly: M must have a positive diagonal.
        if m.diag().iter().any(|&d| d <= 0.0) {
            return Err(TransientError::Singular {
                what: "MATR_MASS (a free DOF has no mass)".into(),
            });
        }
        Ok(SparseStructure {
            n,
            k: SymSparse::from_lower_triplets(n, &stiffness),
            c: damping
                .as_ref()
                .map(|c| SymSparse::from_lower_triplets(n, c)),
            m,
            m_t: mass,
            k_t: stiffness,
            c_t: damping,
            mass_factor: RefCell::new(mass_factor),
        })
    }
}

impl Structure for SparseStructure {
    fn n(&self) -> usize {
        self.n
    }

    fn apply_stiffness(&self, q: &[f64], out: &mut [f64]) {
        self.k.mul(q, out);
    }

    fn apply_damping(&self, v: &[f64], out: &mut [f64]) {
        match &self.c {
            Some(c) => c.mul(v, out),
            None => out.iter_mut().for_each(|o| *o = 0.0),
        }
    }

    fn apply_mass(&self, a: &[f64], out: &mut [f64]) {
        self.m.mul(a, out);
    }

    fn has_damping(&self) -> bool {
        self.c.is_some()
    }

    fn solve_mass(&self, rhs: &mut [f64]) -> Result<(), TransientError> {
        let mut f = self
            .mass_factor
            .try_borrow_mut()
            .map_err(|_| TransientError::Singular {
                what: "MATR_MASS (its factor is in use)".into(),
            })?;
        f.solve(rhs);
        Ok(())
    }

    fn factor(
        &self,
        a_m: f64,
        a_c: f64,
        a_k: f64,
    ) -> Result<Box<dyn LinearSolver + '_>, TransientError> {
        let mut parts: Vec<(Triplets, f64)> = vec![(&self.m_t, a_m), (&self.k_t, a_k)];
        if let Some(c) = &self.c_t {
            parts.push((c, a_c));
        }
        Ok(Box::new(SparseLdlt::new(
            self.n,
            &parts,
            "the implicit matrix a_m M + a_c C + a_k K",
        )?))
    }
}
