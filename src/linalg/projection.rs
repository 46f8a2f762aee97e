//! Projection on a basis of vectors Φ = [φ_1 … φ_m] (PROJ_MATR_BASE, PROJ_VECT_BASE,
//! REST_GENE_PHYS): ΦᵀAΦ, Φᵀf, the coordinates q of a displacement (ΦᵀMΦ q = ΦᵀM u), and
//! the expansion Φq. Vectors are in the full numbering (every DOF, eliminated ones zero).

use crate::error::{Error, Result};
use faer::linalg::solvers::Solve;
use faer::{Mat, Side};

/// y = A x for A given by its (row, col, value) entries, both triangles stored.
fn apply(n: usize, entries: &[(usize, usize, f64)], x: &[f64], y: &mut [f64]) {
    y[..n].fill(0.0);
    for &(i, j, v) in entries {
        y[i] += v * x[j];
    }
}

fn check_basis(n: usize, basis: &[Vec<f64>]) -> Result<()> {
    match basis.iter().position(|phi| phi.len() != n) {
        Some(k) => Err(Error::internal(format!(
            "basis vector {} has {} values for {n} DOFs",
            k + 1,
            basis[k].len()
        ))),
        None => Ok(()),
    }
}

/// ΦᵀAΦ, row-major m × m, for A of size n given by its entries (both triangles).
pub fn project_matrix(
    n: usize,
    entries: &[(usize, usize, f64)],
    basis: &[Vec<f64>],
) -> Result<Vec<f64>> {
    check_basis(n, basis)?;
    if let Some(&(i, j, _)) = entries.iter().find(|e| e.0 >= n || e.1 >= n) {
        return Err(Error::internal(format!(
            "matrix entry ({i}, {j}) outside its size {n}"
        )));
    }
    let m = basis.len();
    let mut out = vec![0.0; m * m];
    let mut a_phi = vec![0.0; n];
    for (j, phi_j) in basis.iter().enumerate() {
        apply(n, entries, phi_j, &mut a_phi);
        for (i, phi_i) in basis.iter().enumerate() {
            out[i * m + j] = dot(phi_i, &a_phi);
        }
    }
    Ok(out)
}

/// Φᵀf.
pub fn project_vector(basis: &[Vec<f64>], f: &[f64]) -> Result<Vec<f64>> {
    check_basis(f.len(), basis)?;
    Ok(basis.iter().map(|phi| dot(phi, f)).collect())
}

/// The coordinates q of u on the basis in the metric of M: (ΦᵀMΦ) q = ΦᵀM u, the
/// M-orthogonal projection (exact when u is a combination of the vectors). With `mass`
/// None, the Euclidean metric. Fails when ΦᵀMΦ is not positive definite (vectors that are
/// dependent, or that M does not see).
pub fn coordinates(
    basis: &[Vec<f64>],
    mass: Option<&[(usize, usize, f64)]>,
    u: &[f64],
) -> Result<Vec<f64>> {
    let n = u.len();
    check_basis(n, basis)?;
    let m = basis.len();
    let (gram, rhs) = match mass {
        Some(entries) => {
            let g = project_matrix(n, entries, basis)?;
            let mut mu = vec![0.0; n];
            apply(n, entries, u, &mut mu);
            (g, project_vector(basis, &mu)?)
        }
        None => {
            let mut g = vec![0.0; m * m];
            for i in 0..m {
                for j in 0..m {
                    g[i * m + j] = dot(&basis[i], &basis[j]);
                }
            }
            (g, project_vector(basis, u)?)
        }
    };
    let g = Mat::from_fn(m, m, |i, j| gram[i * m + j]);
    let llt = g.llt(Side::Lower).map_err(|_| {
        Error::numerical(
            "the vectors of the basis are dependent in the mass metric (ΦᵀMΦ is not positive \
             definite): a displacement cannot be given coordinates on it",
        )
    })?;
    let mut q = Mat::from_fn(m, 1, |i, _| rhs[i]);
    llt.solve_in_place(q.as_mut());
    Ok((0..m).map(|i| q[(i, 0)]).collect())
}

/// Φq into `out` (length n).
pub fn expand_into(basis: &[Vec<f64>], q: &[f64], out: &mut [f64]) {
    out.fill(0.0);
    for (phi, &c) in basis.iter().zip(q) {
        if c != 0.0 {
            for (o, p) in out.iter_mut().zip(phi) {
                *o += c * p;
            }
        }
    }
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A = [[2, -1, 0], [-1, 2, -1], [0, -1, 2]] by entries.
    fn tridiagonal() -> Vec<(usize, usize, f64)> {
        vec![
            (0, 0, 2.0),
            (0, 1, -1.0),
            (1, 0, -1.0),
            (1, 1, 2.0),
            (1, 2, -1.0),
            (2, 1, -1.0),
            (2, 2, 2.0),
        ]
    }

    #[test]
    fn projection_on_unit_vectors_picks_the_entries() {
        let basis = vec![vec![1.0, 0.0, 0.0], vec![0.0, 0.0, 1.0]];
        let p = project_matrix(3, &tridiagonal(), &basis).unwrap();
        assert_eq!(p, vec![2.0, 0.0, 0.0, 2.0]);
    }

    #[test]
    fn projection_of_a_general_basis_is_phi_t_a_phi() {
        // φ1 = (1, 1, 1): Aφ1 = (1, 0, 1); φ2 = (1, 0, -1): Aφ2 = (2, 0, -2).
        let basis = vec![vec![1.0, 1.0, 1.0], vec![1.0, 0.0, -1.0]];
        let p = project_matrix(3, &tridiagonal(), &basis).unwrap();
        assert_eq!(p, vec![2.0, 0.0, 0.0, 4.0]);
        assert_eq!(
            project_vector(&basis, &[1.0, 2.0, 3.0]).unwrap(),
            vec![6.0, -2.0]
        );
    }

    #[test]
    fn coordinates_recover_a_combination_in_either_metric() {
        let basis = vec![vec![1.0, 1.0, 0.0], vec![0.0, 1.0, 2.0]];
        let q = [0.75, -2.0];
        let mut u = vec![0.0; 3];
        expand_into(&basis, &q, &mut u);
        for mass in [None, Some(tridiagonal())] {
            let c = coordinates(&basis, mass.as_deref(), &u).unwrap();
            // A 2 × 2 Cholesky solve of an exact combination: round-off only.
            assert!(
                (c[0] - q[0]).abs() < 1e-14 && (c[1] - q[1]).abs() < 1e-14,
                "{c:?}"
            );
        }
    }

    #[test]
    fn dependent_vectors_are_refused() {
        let basis = vec![vec![1.0, 0.0, 0.0], vec![2.0, 0.0, 0.0]];
        assert!(coordinates(&basis, None, &[1.0, 0.0, 0.0]).is_err());
    }
}
