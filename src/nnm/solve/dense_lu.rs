//! Dense LU with partial pivoting whose storage is reused from one factorisation to the
//! next (faer's in-place kernels, one thread: the blocks factorised here are at most a few
//! thousand rows, where hand-offs between threads cost more than they save on 2 cores).

use crate::nnm::error::{Error, Result};
use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::lu::partial_pivoting::{factor, solve};
use faer::perm::PermRef;
use faer::{Conj, MatMut, MatRef, Par};

#[derive(Default)]
pub struct DenseLu {
    dim: usize,
    /// L (strictly lower, unit diagonal implied) and U, column-major dim × dim.
    lu: Vec<f64>,
    perm: Vec<usize>,
    perm_inv: Vec<usize>,
    factor_mem: Option<MemBuffer>,
    solve_mem: Option<(usize, MemBuffer)>,
    /// Parity of the row permutation (±1), ready for the determinant sign.
    perm_sign: f64,
    factored: bool,
}

/// A `Vec` of `len` zeros, or an out-of-memory error naming what needed it.
pub fn try_zeroed(len: usize, what: &str) -> Result<Vec<f64>> {
    let mut v = Vec::new();
    v.try_reserve_exact(len)
        .map_err(|_| out_of_memory(len, what))?;
    v.resize(len, 0.0);
    Ok(v)
}

pub fn out_of_memory(values: usize, what: &str) -> Error {
    Error::numerical(format!(
        "out of memory: {what} needs {:.1} MB ({values} values)",
        values as f64 * 8.0 / 1e6
    ))
}

impl DenseLu {
    /// The matrix storage to fill (column-major dim × dim), grown when `dim` grows; the
    /// caller writes every entry before `factor`.
    pub fn storage(&mut self, dim: usize) -> Result<&mut [f64]> {
        if self.lu.len() != dim * dim {
            self.lu = try_zeroed(dim * dim, "a dense contact block")?;
            self.perm = vec![0; dim];
            self.perm_inv = vec![0; dim];
            self.factor_mem = None;
            self.solve_mem = None;
        }
        self.dim = dim;
        self.factored = false;
        Ok(&mut self.lu)
    }

    /// The storage as it is (after `storage(dim)`), to fill block by block.
    pub fn storage_mut(&mut self) -> &mut [f64] {
        self.factored = false;
        &mut self.lu
    }

    /// Factor what `storage` holds.
    pub fn factor(&mut self) -> Result<()> {
        let n = self.dim;
        if self.factor_mem.is_none() {
            let req = factor::lu_in_place_scratch::<usize, f64>(n, n, Par::Seq, Default::default());
            self.factor_mem =
                Some(MemBuffer::try_new(req).map_err(|_| out_of_memory(n, "LU scratch"))?);
        }
        let mem = self
            .factor_mem
            .as_mut()
            .ok_or_else(|| Error::internal("LU scratch missing"))?;
        let (info, _) = factor::lu_in_place(
            MatMut::from_column_major_slice_mut(&mut self.lu, n, n),
            &mut self.perm,
            &mut self.perm_inv,
            Par::Seq,
            MemStack::new(mem),
            Default::default(),
        );
        self.perm_sign = if info.transposition_count % 2 == 0 {
            1.0
        } else {
            -1.0
        };
        for i in 0..n {
            let d = self.lu[i * n + i];
            if d == 0.0 || !d.is_finite() {
                return Err(Error::numerical(format!(
                    "a dense contact block is singular (pivot {i} of {n} is {d:e})"
                )));
            }
        }
        self.factored = true;
        Ok(())
    }

    /// Sign of the determinant of the factored matrix.
    #[cfg(test)]
    pub fn det_sign(&self) -> f64 {
        let n = self.dim;
        (0..n).fold(self.perm_sign, |s, i| s * self.lu[i * n + i].signum())
    }

    /// Solve in place for `ncols` right-hand sides stored column after column.
    pub fn solve(&mut self, rhs: &mut [f64], ncols: usize) -> Result<()> {
        let n = self.dim;
        if !self.factored || rhs.len() != n * ncols {
            return Err(Error::internal(
                "dense solve without a factorisation or of the wrong size",
            ));
        }
        if ncols == 0 {
            return Ok(());
        }
        let fresh = !matches!(&self.solve_mem, Some((c, _)) if *c >= ncols);
        if fresh {
            let req = solve::solve_in_place_scratch::<usize, f64>(n, ncols, Par::Seq);
            let mem = MemBuffer::try_new(req)
                .map_err(|_| out_of_memory(n * ncols, "LU solve scratch"))?;
            self.solve_mem = Some((ncols, mem));
        }
        let mem = match &mut self.solve_mem {
            Some((_, m)) => m,
            None => return Err(Error::internal("LU solve scratch missing")),
        };
        let a = MatRef::from_column_major_slice(&self.lu, n, n);
        // SAFETY-free: the permutation arrays come from `lu_in_place` on this matrix.
        let perm = PermRef::new_checked(&self.perm, &self.perm_inv, n);
        solve::solve_in_place_with_conj(
            a,
            a,
            perm,
            Conj::No,
            MatMut::from_column_major_slice_mut(rhs, n, ncols),
            Par::Seq,
            MemStack::new(mem),
        );
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn solves_and_signs_a_small_system_and_reuses_storage() {
        let mut lu = DenseLu::default();
        // [[2, 4], [5, 3]]: det = −14, a pivoting swap.
        let a = lu.storage(2).unwrap();
        a.copy_from_slice(&[2.0, 5.0, 4.0, 3.0]);
        lu.factor().unwrap();
        assert_eq!(lu.det_sign(), -1.0);
        let mut b = vec![6.0, 8.0, 2.0, 5.0];
        lu.solve(&mut b, 2).unwrap();
        // x = (1, 1) and (1, 0).
        for (v, w) in b.iter().zip([1.0, 1.0, 1.0, 0.0]) {
            assert!((v - w).abs() < 1e-14, "{b:?}");
        }
        let a = lu.storage(2).unwrap();
        a.copy_from_slice(&[1.0, 0.0, 0.0, 0.0]);
        assert!(lu.factor().is_err());
    }
}
