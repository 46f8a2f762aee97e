//! Sparse glue over faer: triplets -> `SparseColMat`, restriction to the free DOFs.

use crate::error::{Error, Result};
use faer::sparse::{SparseColMat, Triplet};

/// Sum duplicate (row, col) entries; the result is sorted by (row, col).
pub fn consolidate(mut t: Vec<(usize, usize, f64)>) -> Vec<(usize, usize, f64)> {
    t.sort_by_key(|&(r, c, _)| (r, c));
    let mut out: Vec<(usize, usize, f64)> = Vec::with_capacity(t.len());
    for (r, c, v) in t {
        match out.last_mut() {
            Some(last) if last.0 == r && last.1 == c => last.2 += v,
            _ => out.push((r, c, v)),
        }
    }
    out
}

/// A `nrows × ncols` sparse matrix from triplets (duplicates are summed).
pub fn from_triplets(
    nrows: usize,
    ncols: usize,
    t: &[(usize, usize, f64)],
) -> Result<SparseColMat<usize, f64>> {
    let entries: Vec<Triplet<usize, usize, f64>> =
        t.iter().map(|&(r, c, v)| Triplet::new(r, c, v)).collect();
    if let Some(bad) = t.iter().find(|&&(r, c, _)| r >= nrows || c >= ncols) {
        return Err(Error::internal(format!(
            "matrix entry ({}, {}) outside {nrows}×{ncols}",
            bad.0, bad.1
        )));
    }
    SparseColMat::try_new_from_triplets(nrows, ncols, &entries)
        .map_err(|e| Error::numerical(format!("cannot build the sparse matrix: {e:?}")))
}

/// Map full index -> reduced index (None for eliminated DOFs).
pub fn reduction_map(n: usize, eliminated: &[bool]) -> (usize, Vec<Option<usize>>) {
    let mut next = 0;
    let map = (0..n)
        .map(|i| {
            if eliminated.get(i).copied().unwrap_or(false) {
                None
            } else {
                next += 1;
                Some(next - 1)
            }
        })
        .collect();
    (next, map)
}

/// The matrix of the free DOFs (rows and columns of eliminated DOFs removed).
pub fn reduced(
    n: usize,
    t: &[(usize, usize, f64)],
    eliminated: &[bool],
) -> Result<SparseColMat<usize, f64>> {
    let (m, map) = reduction_map(n, eliminated);
    let kept: Vec<(usize, usize, f64)> = t
        .iter()
        .filter_map(|&(r, c, v)| match (map.get(r)?, map.get(c)?) {
            (Some(rr), Some(cc)) => Some((*rr, *cc, v)),
            _ => None,
        })
        .collect();
    from_triplets(m, m, &kept)
}

/// The diagonal of a square sparse matrix (a missing entry is 0).
pub fn diagonal(a: &SparseColMat<usize, f64>) -> Vec<f64> {
    let n = a.nrows().min(a.ncols());
    let mut d = vec![0.0; n];
    for (j, dj) in d.iter_mut().enumerate() {
        let rows = a.symbolic().row_idx_of_col_raw(j);
        let vals = a.val_of_col(j);
        for (&i, &v) in rows.iter().zip(vals) {
            if i == j {
                *dj += v;
            }
        }
    }
    d
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn duplicates_sum_and_reduction_drops_rows() {
        let t = consolidate(vec![
            (1, 1, 2.0),
            (0, 0, 1.0),
            (1, 1, 3.0),
            (2, 0, 4.0),
            (0, 2, 4.0),
        ]);
        assert_eq!(t, vec![(0, 0, 1.0), (0, 2, 4.0), (1, 1, 5.0), (2, 0, 4.0)]);
        let r = reduced(3, &t, &[false, true, false]).unwrap().to_dense();
        assert_eq!((r.nrows(), r.ncols()), (2, 2));
        assert_eq!(r[(0, 0)], 1.0);
        assert_eq!(r[(1, 0)], 4.0);
        assert_eq!(r[(1, 1)], 0.0);
        assert!(from_triplets(2, 2, &[(2, 0, 1.0)]).is_err());
    }
}
