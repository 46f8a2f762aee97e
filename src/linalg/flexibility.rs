//! How much of a structure's static flexibility along a direction a modal basis holds: a
//! truncated basis of normal modes sees a shock's node stiffer than it is (the modes left
//! out carry the rest of its static deflection), which Code_Aster users correct with the
//! static mode of the shock's DOF. For a direction r over the free DOFs, the static
//! flexibility is rᵀK⁻¹r and the basis's rᵀΦ(ΦᵀKΦ)⁻¹Φᵀr: the flexibility of the
//! structure restricted to the span of Φ (the static response to r found by Ritz in that
//! span). For K-orthogonal vectors (normal modes) it is Σ_j (φ_jᵀr)²/(φ_jᵀKφ_j); a Ritz
//! basis (modes plus static modes, DEFI_BASE_MODALE) is not K-orthogonal, and the sum would
//! count the static mode's share twice.

use super::eigen::shift::ShiftedFactor;
use super::eigen::sym::SymSparse;
use super::eigen::FactorKind;
use crate::error::Result;

/// Static and modal flexibility along one direction.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Flexibility {
    pub statics: f64,
    pub modal: f64,
}

impl Flexibility {
    /// The share of the static flexibility the basis holds (1 for a complete basis).
    pub fn share(&self) -> f64 {
        if self.statics > 0.0 {
            self.modal / self.statics
        } else {
            1.0
        }
    }
}

/// Below this smallest relative pivot K is taken as singular (rigid-body motion): the
/// static flexibility is then infinite and no share can be given.
const SINGULAR_PIVOT: f64 = 1e-12;

/// The flexibility of each direction of `rows` (free DOFs) in the structure of stiffness
/// `k` and in the basis `basis` (free DOFs). `None` when K is singular or not definite, or
/// the basis has a direction without stiffness (a rigid mode, or vectors that depend on
/// each other: ΦᵀKΦ not positive definite).
pub fn flexibilities(
    k: &SymSparse,
    rows: &[Vec<f64>],
    basis: &[Vec<f64>],
) -> Result<Option<Vec<Flexibility>>> {
    let Some(reduced) = ReducedFlexibility::new(k, basis) else {
        return Ok(None);
    };
    let Ok(mut factor) = ShiftedFactor::new(k, k, 0.0, FactorKind::Auto) else {
        return Ok(None);
    };
    if factor.negative_count() > 0 || factor.min_relative_pivot() < SINGULAR_PIVOT {
        return Ok(None);
    }
    let mut out = Vec::with_capacity(rows.len());
    for r in rows {
        let mut x = r.clone();
        factor.solve_in_place(&mut x);
        let statics = dot(r, &x);
        let b: Vec<f64> = basis.iter().map(|phi| dot(phi, r)).collect();
        out.push(Flexibility {
            statics,
            modal: reduced.form(&b),
        });
    }
    Ok(Some(out))
}

/// The Cholesky factor of the reduced stiffness ΦᵀKΦ (m × m), for bᵀ(ΦᵀKΦ)⁻¹b.
struct ReducedFlexibility {
    llt: Option<faer::linalg::solvers::Llt<f64>>,
}

impl ReducedFlexibility {
    /// `None` when ΦᵀKΦ is not positive definite.
    fn new(k: &SymSparse, basis: &[Vec<f64>]) -> Option<ReducedFlexibility> {
        let m = basis.len();
        if m == 0 {
            return Some(ReducedFlexibility { llt: None });
        }
        let n = k.n;
        let mut kphi = vec![0.0; n];
        let mut g = faer::Mat::<f64>::zeros(m, m);
        for (j, pj) in basis.iter().enumerate() {
            k.mul(pj, &mut kphi);
            for (i, pi) in basis.iter().enumerate() {
                g[(i, j)] = dot(pi, &kphi);
            }
        }
        // Symmetrise the round-off of the products before factorising.
        for j in 0..m {
            for i in 0..j {
                let v = 0.5 * (g[(i, j)] + g[(j, i)]);
                g[(i, j)] = v;
                g[(j, i)] = v;
            }
        }
        let llt = g.llt(faer::Side::Lower).ok()?;
        Some(ReducedFlexibility { llt: Some(llt) })
    }

    /// bᵀ(ΦᵀKΦ)⁻¹b (0 for an empty basis).
    fn form(&self, b: &[f64]) -> f64 {
        let Some(llt) = &self.llt else {
            return 0.0;
        };
        let rhs = faer::Mat::<f64>::from_fn(b.len(), 1, |i, _| b[i]);
        let x = faer::linalg::solvers::Solve::solve(llt, &rhs);
        (0..b.len()).map(|i| b[i] * x[(i, 0)]).sum()
    }
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A chain of three unit springs from a wall: K = [[2, -1, 0], [-1, 2, -1], [0, -1, 1]].
    fn chain() -> SymSparse {
        SymSparse::from_lower_triplets(
            3,
            &[
                (0, 0, 2.0),
                (1, 0, -1.0),
                (1, 1, 2.0),
                (2, 1, -1.0),
                (2, 2, 1.0),
            ],
        )
    }

    /// The static flexibility at the free end is 3 (three springs in series); a basis of
    /// every eigenvector holds all of it, the first one alone a share below 1, and no
    /// vector at all none.
    #[test]
    fn the_free_end_of_a_chain() {
        let k = chain();
        let end = vec![vec![0.0, 0.0, 1.0]];
        let dense = k.to_dense();
        let eig = dense.self_adjoint_eigen(faer::Side::Lower).unwrap();
        let v = eig.U();
        let all: Vec<Vec<f64>> = (0..3)
            .map(|j| (0..3).map(|i| v[(i, j)]).collect())
            .collect();
        let f = flexibilities(&k, &end, &all).unwrap().unwrap();
        // A 3 × 3 factorisation and eigen decomposition: round-off only.
        assert!((f[0].statics - 3.0).abs() < 1e-13, "{f:?}");
        assert!((f[0].share() - 1.0).abs() < 1e-13, "{f:?}");
        let first = flexibilities(&k, &end, &all[..1]).unwrap().unwrap();
        assert!(
            first[0].share() < 1.0 && first[0].share() > 0.5,
            "{first:?}"
        );
        let none = flexibilities(&k, &end, &[]).unwrap().unwrap();
        assert_eq!(none[0].modal, 0.0);
    }

    /// A Ritz basis: the first mode plus the static deflection K⁻¹r of the free end, not
    /// K-orthogonal. It holds the end's whole static flexibility (the static response lies
    /// in its span): share 1 to round-off, where the sum over K-orthogonal vectors would
    /// count the first mode's part twice (share above 1).
    #[test]
    fn a_ritz_basis_with_the_static_mode_holds_all_of_it() {
        let k = chain();
        let dense = k.to_dense();
        let eig = dense.self_adjoint_eigen(faer::Side::Lower).unwrap();
        let v = eig.U();
        let first: Vec<f64> = (0..3).map(|i| v[(i, 0)]).collect();
        // K⁻¹ e_3 = (1, 2, 3) for this chain.
        let statics = vec![1.0, 2.0, 3.0];
        let f = flexibilities(&k, &[vec![0.0, 0.0, 1.0]], &[first, statics])
            .unwrap()
            .unwrap();
        assert!((f[0].share() - 1.0).abs() < 1e-13, "{f:?}");
    }

    #[test]
    fn dependent_vectors_give_no_share() {
        let k = chain();
        let f = flexibilities(
            &k,
            &[vec![0.0, 0.0, 1.0]],
            &[vec![1.0, 2.0, 3.0], vec![2.0, 4.0, 6.0]],
        )
        .unwrap();
        assert_eq!(f, None);
    }

    #[test]
    fn a_free_structure_has_no_static_flexibility() {
        let k = SymSparse::from_lower_triplets(2, &[(0, 0, 1.0), (1, 0, -1.0), (1, 1, 1.0)]);
        assert_eq!(flexibilities(&k, &[vec![1.0, 0.0]], &[]).unwrap(), None);
    }
}
