//! Symmetric sparse matrices as the eigen solvers see them: the lower triangle only, in
//! compressed columns. Assembled matrices may come with both triangles stored or with one
//! triangle only; [`SymSparse::from_faer`] accepts either so the solvers never care.

use crate::error::{Error, Result};
use faer::sparse::{SparseColMat, Triplet};

/// Lower triangle (diagonal included) of a symmetric matrix, compressed by columns.
#[derive(Clone, Debug)]
pub struct SymSparse {
    pub n: usize,
    col_ptr: Vec<usize>,
    row_idx: Vec<usize>,
    val: Vec<f64>,
}

impl SymSparse {
    /// Takes a square symmetric matrix stored with both triangles, or only its lower or
    /// only its upper triangle. With both triangles stored, the lower one is used (the
    /// matrix is trusted to be symmetric: assembly of symmetric element matrices makes it so).
    pub fn from_faer(a: &SparseColMat<usize, f64>, what: &str) -> Result<Self> {
        let n = a.nrows();
        if a.ncols() != n {
            return Err(Error::internal(format!(
                "{what} matrix is {}x{}, a square matrix is needed",
                n,
                a.ncols()
            )));
        }
        let sym = a.symbolic();
        let cp = sym.col_ptr();
        let ri = sym.row_idx();
        let vals = a.val();
        let (mut has_lower, mut has_upper) = (false, false);
        for j in 0..n {
            for &i in &ri[cp[j]..cp[j + 1]] {
                has_lower |= i > j;
                has_upper |= i < j;
            }
        }
        // Upper-only storage is read transposed; in every other case keep i >= j.
        let transpose = has_upper && !has_lower;
        let mut cols: Vec<Vec<(usize, f64)>> = vec![Vec::new(); n];
        for j in 0..n {
            for p in cp[j]..cp[j + 1] {
                let (i, v) = (ri[p], vals[p]);
                if !v.is_finite() {
                    return Err(Error::numerical(format!(
                        "{what} matrix has a non-finite coefficient at ({}, {})",
                        i + 1,
                        j + 1
                    )));
                }
                if transpose && i <= j {
                    cols[i].push((j, v));
                } else if !transpose && i >= j {
                    cols[j].push((i, v));
                }
            }
        }
        let mut col_ptr = Vec::with_capacity(n + 1);
        let mut row_idx = Vec::new();
        let mut val = Vec::new();
        col_ptr.push(0);
        for c in cols {
            for (i, v) in c {
                row_idx.push(i);
                val.push(v);
            }
            col_ptr.push(row_idx.len());
        }
        Ok(SymSparse {
            n,
            col_ptr,
            row_idx,
            val,
        })
    }

    /// Builds directly from lower-triangle triplets (i >= j); duplicates are summed.
    pub fn from_lower_triplets(n: usize, entries: &[(usize, usize, f64)]) -> Self {
        let mut cols: Vec<Vec<(usize, f64)>> = vec![Vec::new(); n];
        for &(i, j, v) in entries {
            let (i, j) = if i >= j { (i, j) } else { (j, i) };
            if j < n && i < n {
                cols[j].push((i, v));
            }
        }
        let mut col_ptr = vec![0];
        let mut row_idx = Vec::new();
        let mut val = Vec::new();
        for mut c in cols {
            c.sort_by_key(|e| e.0);
            let start = row_idx.len();
            for (i, v) in c {
                if row_idx.len() > start && row_idx.last() == Some(&i) {
                    if let Some(last) = val.last_mut() {
                        *last += v;
                    }
                } else {
                    row_idx.push(i);
                    val.push(v);
                }
            }
            col_ptr.push(row_idx.len());
        }
        SymSparse {
            n,
            col_ptr,
            row_idx,
            val,
        }
    }

    pub fn nnz_lower(&self) -> usize {
        self.val.len()
    }

    /// y = A x using the symmetry of the stored lower triangle.
    pub fn mul(&self, x: &[f64], y: &mut [f64]) {
        y.iter_mut().for_each(|v| *v = 0.0);
        for j in 0..self.n {
            let xj = x[j];
            let mut acc = 0.0;
            for p in self.col_ptr[j]..self.col_ptr[j + 1] {
                let i = self.row_idx[p];
                let a = self.val[p];
                y[i] += a * xj;
                if i != j {
                    acc += a * x[i];
                }
            }
            y[j] += acc;
        }
    }

    /// xᵀ A y.
    pub fn form(&self, x: &[f64], y: &[f64]) -> f64 {
        let mut ay = vec![0.0; self.n];
        self.mul(y, &mut ay);
        dot(x, &ay)
    }

    /// xᵀ A x from the stored lower triangle, without forming A x: a read-only sweep (each
    /// off-diagonal entry counted twice), cheaper than [`SymSparse::mul`]'s scatter and
    /// allocation when only the form is wanted.
    pub fn quadratic(&self, x: &[f64]) -> f64 {
        let mut sum = 0.0;
        for (j, &xj) in x.iter().enumerate().take(self.n) {
            let r = self.col_ptr[j]..self.col_ptr[j + 1];
            let mut col = 0.0;
            for (&i, &a) in self.row_idx[r.clone()].iter().zip(&self.val[r]) {
                col += if i == j { 0.5 * a * xj } else { a * x[i] };
            }
            sum += 2.0 * xj * col;
        }
        sum
    }

    /// |x|ᵀ |A| |x| (entrywise absolute values): what bounds the rounding error of xᵀ A x
    /// computed from the stored entries.
    pub fn abs_form(&self, x: &[f64]) -> f64 {
        let mut sum = 0.0;
        for j in 0..self.n {
            for p in self.col_ptr[j]..self.col_ptr[j + 1] {
                let i = self.row_idx[p];
                let t = (self.val[p] * x[i] * x[j]).abs();
                sum += if i == j { t } else { 2.0 * t };
            }
        }
        sum
    }

    pub fn diag(&self) -> Vec<f64> {
        (0..self.n)
            .map(|j| {
                (self.col_ptr[j]..self.col_ptr[j + 1])
                    .filter(|&p| self.row_idx[p] == j)
                    .map(|p| self.val[p])
                    .sum()
            })
            .collect()
    }

    /// Dense copy (both triangles), for the dense solver only.
    pub fn to_dense(&self) -> faer::Mat<f64> {
        let mut a = faer::Mat::<f64>::zeros(self.n, self.n);
        for j in 0..self.n {
            for p in self.col_ptr[j]..self.col_ptr[j + 1] {
                let i = self.row_idx[p];
                a[(i, j)] += self.val[p];
                if i != j {
                    a[(j, i)] += self.val[p];
                }
            }
        }
        a
    }

    /// Lower triangle of K − σM as a faer matrix, with every diagonal entry present (the
    /// factorisation needs the diagonal in the pattern even where K and M have none).
    pub fn shifted_lower(
        k: &SymSparse,
        m: &SymSparse,
        sigma: f64,
    ) -> Result<SparseColMat<usize, f64>> {
        let n = k.n;
        let mut t = Vec::with_capacity(k.val.len() + m.val.len() + n);
        for i in 0..n {
            t.push(Triplet::new(i, i, 0.0));
        }
        for (a, s) in [(k, 1.0), (m, -sigma)] {
            if s == 0.0 {
                continue;
            }
            for j in 0..n {
                for p in a.col_ptr[j]..a.col_ptr[j + 1] {
                    t.push(Triplet::new(a.row_idx[p], j, s * a.val[p]));
                }
            }
        }
        SparseColMat::try_new_from_triplets(n, n, &t)
            .map_err(|e| Error::numerical(format!("could not build K - σM: {e:?}")))
    }

    /// The lower pattern of K − σM for every σ (the entries of K and of M, and the whole
    /// diagonal, as [`SymSparse::shifted_lower`] assembles them for σ ≠ 0), with K's values,
    /// and M's values on the same pattern (zero where M has no entry).
    pub fn shift_pattern(
        k: &SymSparse,
        m: &SymSparse,
    ) -> Result<(SparseColMat<usize, f64>, Vec<f64>)> {
        let n = k.n;
        // The same triplets with K's values, then with M's: the same positions, so the same
        // compressed pattern, entry for entry.
        let build = |take_k: bool| {
            let mut t = Vec::with_capacity(k.val.len() + m.val.len() + n);
            for i in 0..n {
                t.push(Triplet::new(i, i, 0.0));
            }
            for (a, is_k) in [(k, true), (m, false)] {
                for j in 0..n {
                    for p in a.col_ptr[j]..a.col_ptr[j + 1] {
                        let v = if is_k == take_k { a.val[p] } else { 0.0 };
                        t.push(Triplet::new(a.row_idx[p], j, v));
                    }
                }
            }
            SparseColMat::try_new_from_triplets(n, n, &t)
                .map_err(|e| Error::numerical(format!("could not build K - σM: {e:?}")))
        };
        let with_k = build(true)?;
        let with_m = build(false)?;
        let (a, b) = (with_k.symbolic(), with_m.symbolic());
        if a.col_ptr() != b.col_ptr() || a.row_idx() != b.row_idx() {
            return Err(Error::internal(
                "the patterns of K and M on K - σM differ between two assemblies",
            ));
        }
        let m_val = with_m.val().to_vec();
        Ok((with_k, m_val))
    }
}

pub fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

pub fn norm2(a: &[f64]) -> f64 {
    dot(a, a).sqrt()
}
