//! The solver of the bordered tangent, kept behind one trait so that a cheaper one (e.g. a
//! Krylov solver preconditioned in the time domain, ehman.md §9) can replace it.

use crate::error::{Error, Result};
use faer::prelude::*;
use faer::sparse::linalg::solvers::{Lu, SymbolicLu};
use faer::sparse::{Argsort, Pair, SparseColMat, SymbolicSparseColMat, Triplet};

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
