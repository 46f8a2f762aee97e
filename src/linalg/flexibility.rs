//! How much of a structure's static flexibility along a direction a modal basis holds: a
//! truncated basis of normal modes sees a shock's node stiffer than it is (the modes left
//! out carry the rest of its static deflection), which Code_Aster users correct with the
//! static mode of the shock's DOF. For a direction r over the free DOFs, the static
//! flexibility is rᵀK⁻¹r and the basis's Σ_j (φ_jᵀr)²/(φ_jᵀKφ_j), φ_j K-orthogonal.

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
/// `k` and in the basis `basis` (free DOFs, K-orthogonal vectors). `None` when K is
/// singular or not definite, or a vector of the basis has no stiffness (a rigid mode).
pub fn flexibilities(
    k: &SymSparse,
    rows: &[Vec<f64>],
    basis: &[Vec<f64>],
) -> Result<Option<Vec<Flexibility>>> {
    let stiffness: Vec<f64> = basis.iter().map(|phi| k.form(phi, phi)).collect();
    if stiffness.iter().any(|&s| s <= 0.0 || s.is_nan()) {
        return Ok(None);
    }
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
        let modal = basis
            .iter()
            .zip(&stiffness)
            .map(|(phi, s)| dot(phi, r).powi(2) / s)
            .sum();
        out.push(Flexibility { statics, modal });
    }
    Ok(Some(out))
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

    #[test]
    fn a_free_structure_has_no_static_flexibility() {
        let k = SymSparse::from_lower_triplets(2, &[(0, 0, 1.0), (1, 0, -1.0), (1, 1, 1.0)]);
        assert_eq!(flexibilities(&k, &[vec![1.0, 0.0]], &[]).unwrap(), None);
    }
}
