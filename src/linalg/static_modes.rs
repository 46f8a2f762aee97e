//! Static deformations of a structure held on its supports (MODE_STATIQUE): one sparse
//! factorisation of the free-DOF stiffness K_ff, then one solve per deformation.
//!
//! - A constraint mode (MODE_STAT) is the shape of a unit imposed displacement of a
//!   blocked DOF s, the other blocked DOFs held: u_s = 1 and K_ff u_f = −K_fs. The right-hand
//!   side is the column of K at s, restricted to the free DOFs, with its sign changed.
//! - An attachment mode (FORCE_NODALE) is the response to a unit force on a free DOF:
//!   K_ff u_f = e_d.
//! - A pseudo-mode (PSEUDO_MODE) is the response to the inertial load of a unit
//!   acceleration of the whole structure along a direction Δ: K_ff u_f = M_ff Δ_f.
//!
//! The right-hand sides are built by the caller (it knows the numbering); this module
//! solves them and says when the structure is not held (K_ff singular or not definite),
//! in which case no static deformation exists.

use super::eigen::shift::{FactorKind, ShiftedFactor};
use super::eigen::sym::SymSparse;

/// Below this smallest relative pivot K_ff is taken as singular: the free DOFs can move
/// without deforming anything (a rigid-body motion or a mechanism).
const SINGULAR_PIVOT: f64 = 1e-12;

/// Why the static deformations cannot be computed.
#[derive(Clone, Debug, PartialEq)]
pub enum StaticError {
    /// K_ff is singular or not positive definite: the supports do not hold the structure.
    NotHeld,
    /// A right-hand side is not the size of K_ff.
    Size { expected: usize, got: usize },
    /// A solution is not finite.
    NotFinite(usize),
}

/// The factorised stiffness of the free DOFs.
pub struct StaticSolver {
    factor: ShiftedFactor,
    n: usize,
}

impl StaticSolver {
    /// Factorises `k_ff`; `NotHeld` when it is singular or indefinite.
    pub fn new(k_ff: &SymSparse) -> Result<StaticSolver, StaticError> {
        let factor = ShiftedFactor::new(k_ff, k_ff, 0.0, FactorKind::Auto)
            .map_err(|_| StaticError::NotHeld)?;
        if factor.negative_count() > 0 || factor.min_relative_pivot() < SINGULAR_PIVOT {
            return Err(StaticError::NotHeld);
        }
        Ok(StaticSolver { factor, n: k_ff.n })
    }

    /// The solutions u of K_ff u = r, one per right-hand side, in order.
    pub fn solve_all(&mut self, rhs: Vec<Vec<f64>>) -> Result<Vec<Vec<f64>>, StaticError> {
        let mut out = Vec::with_capacity(rhs.len());
        for (i, mut r) in rhs.into_iter().enumerate() {
            if r.len() != self.n {
                return Err(StaticError::Size {
                    expected: self.n,
                    got: r.len(),
                });
            }
            self.factor.solve_in_place(&mut r);
            if !r.iter().all(|v| v.is_finite()) {
                return Err(StaticError::NotFinite(i));
            }
            out.push(r);
        }
        Ok(out)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Three unit springs in series between two walls, the masses' DOFs free: K_ff of a
    /// chain wall–1–2–3–wall is tridiagonal (2, −1).
    fn held_chain() -> SymSparse {
        SymSparse::from_lower_triplets(
            3,
            &[
                (0, 0, 2.0),
                (1, 0, -1.0),
                (1, 1, 2.0),
                (2, 1, -1.0),
                (2, 2, 2.0),
            ],
        )
    }

    #[test]
    fn constraint_mode_is_the_linear_interpolation_between_the_supports() {
        // Moving the left wall by 1 (the right held): the exact static shape of a uniform
        // chain is linear, 3/4, 1/2, 1/4. The right-hand side is −K_fs = (1, 0, 0).
        let mut s = StaticSolver::new(&held_chain()).unwrap();
        let u = s.solve_all(vec![vec![1.0, 0.0, 0.0]]).unwrap();
        for (got, want) in u[0].iter().zip([0.75, 0.5, 0.25]) {
            assert!((got - want).abs() < 1e-14, "{got} vs {want}");
        }
    }

    #[test]
    fn attachment_mode_is_the_flexibility_column() {
        // K⁻¹ of the (2, −1) tridiagonal of size 3 is (1/4)·[[3,2,1],[2,4,2],[1,2,3]].
        let mut s = StaticSolver::new(&held_chain()).unwrap();
        let u = s.solve_all(vec![vec![0.0, 1.0, 0.0]]).unwrap();
        for (got, want) in u[0].iter().zip([0.5, 1.0, 0.5]) {
            assert!((got - want).abs() < 1e-14, "{got} vs {want}");
        }
    }

    #[test]
    fn a_free_floating_chain_is_not_held() {
        // Two masses joined by one spring, no support: K is singular.
        let k = SymSparse::from_lower_triplets(2, &[(0, 0, 1.0), (1, 0, -1.0), (1, 1, 1.0)]);
        assert_eq!(StaticSolver::new(&k).err(), Some(StaticError::NotHeld));
    }

    #[test]
    fn a_right_hand_side_of_the_wrong_size_is_refused() {
        let mut s = StaticSolver::new(&held_chain()).unwrap();
        assert_eq!(
            s.solve_all(vec![vec![1.0]]).err(),
            Some(StaticError::Size {
                expected: 3,
                got: 1
            })
        );
    }
}
