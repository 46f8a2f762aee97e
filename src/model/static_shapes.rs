//! Static deformations on a numbering (MODE_STATIQUE, CALC_CHAR_SEISME): each request
//! becomes a right-hand side over the free DOFs, [`crate::linalg::static_modes`] solves
//! them all with one factorisation, and the solutions are written back in the full
//! numbering (blocked DOFs, LIAISON_DDL relations).
//!
//! The products with K and M use the full triplets (both triangles stored), so a term
//! between a free and a blocked DOF is seen: that coupling is what moves the free DOFs
//! when a blocked DOF is displaced.

use super::assembly::AssembledMatrix;
use super::dof::Cmp;
use crate::linalg::eigen::sym::SymSparse;
use crate::linalg::static_modes::{StaticError, StaticSolver};

/// One static deformation, by its full DOF index or its direction.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum StaticRequest {
    /// A unit displacement of this blocked DOF, the others held (constraint mode).
    Imposed(usize),
    /// A unit force on this free DOF (attachment mode).
    Force(usize),
    /// A unit acceleration of the whole structure along (x, y, z) (pseudo-mode): the load
    /// M·Δ, Δ the rigid translation.
    Acceleration([f64; 3]),
}

/// Why a request cannot be answered.
#[derive(Clone, Debug, PartialEq)]
pub enum StaticShapeError {
    Solver(StaticError),
    /// Imposed on a DOF that is not blocked, or a force on one that is.
    WrongStatus {
        dof: usize,
        blocked: bool,
    },
    /// A pseudo-mode without the mass matrix.
    NoMass,
    /// K and M are not on the same DOFs.
    Mismatch,
    /// The stiffness cannot be restricted to the free DOFs.
    Reduction(String),
}

/// y = A·x over the full numbering.
pub fn mul_full(a: &AssembledMatrix, x: &[f64]) -> Vec<f64> {
    let mut y = vec![0.0; a.size()];
    for &(i, j, v) in &a.triplets {
        if let (Some(yi), Some(xj)) = (y.get_mut(i), x.get(j)) {
            *yi += v * xj;
        }
    }
    y
}

/// xᵀ A y over the full numbering.
pub fn form_full(a: &AssembledMatrix, x: &[f64], y: &[f64]) -> f64 {
    let ay = mul_full(a, y);
    x.iter().zip(&ay).map(|(p, q)| p * q).sum()
}

/// The rigid translation Δ along `dir`: dir_x on every DX, dir_y on every DY, dir_z on
/// every DZ of the numbering (rotations 0).
pub fn rigid_translation(a: &AssembledMatrix, dir: [f64; 3]) -> Vec<f64> {
    a.numbering
        .dofs
        .iter()
        .map(|d| match d.cmp {
            Cmp::Dx => dir[0],
            Cmp::Dy => dir[1],
            Cmp::Dz => dir[2],
            _ => 0.0,
        })
        .collect()
}

/// The deformations asked, in order, each in the full numbering.
pub fn static_shapes(
    k: &AssembledMatrix,
    m: Option<&AssembledMatrix>,
    requests: &[StaticRequest],
) -> Result<Vec<Vec<f64>>, StaticShapeError> {
    if m.is_some_and(|m| !k.same_dofs(m)) {
        return Err(StaticShapeError::Mismatch);
    }
    let mut rhs = Vec::with_capacity(requests.len());
    for r in requests {
        rhs.push(right_hand_side(k, m, *r)?);
    }
    let mut out = solve_on_free(k, rhs)?;
    for (full, r) in out.iter_mut().zip(requests) {
        if let StaticRequest::Imposed(s) = r {
            if let Some(v) = full.get_mut(*s) {
                *v = 1.0;
            }
        }
    }
    Ok(out)
}

/// The static responses K⁻¹f to the loads `loads` (nodal forces over the full numbering;
/// their values on blocked DOFs are taken by the supports), each in the full numbering:
/// DYNA_LINE's static enrichment by the loads of its EXCIT (Code_Aster's MACRO_ELAS_MULT).
pub fn load_responses(
    k: &AssembledMatrix,
    loads: &[Vec<f64>],
) -> Result<Vec<Vec<f64>>, StaticShapeError> {
    let rhs = loads.iter().map(|f| k.row_on_free(f)).collect();
    solve_on_free(k, rhs)
}

/// One factorisation of K_ff, a solve per right-hand side, the solutions expanded to the
/// full numbering.
fn solve_on_free(
    k: &AssembledMatrix,
    rhs: Vec<Vec<f64>>,
) -> Result<Vec<Vec<f64>>, StaticShapeError> {
    let kr = k
        .reduced()
        .map_err(|e| StaticShapeError::Reduction(e.to_string()))?;
    let ks = SymSparse::from_faer(&kr, "stiffness")
        .map_err(|e| StaticShapeError::Reduction(e.to_string()))?;
    let mut solver = StaticSolver::new(&ks).map_err(StaticShapeError::Solver)?;
    let solutions = solver.solve_all(rhs).map_err(StaticShapeError::Solver)?;
    solutions
        .iter()
        .map(|x| {
            k.expand(x)
                .map_err(|e| StaticShapeError::Reduction(e.to_string()))
        })
        .collect()
}

/// The right-hand side of one request over the free DOFs.
fn right_hand_side(
    k: &AssembledMatrix,
    m: Option<&AssembledMatrix>,
    r: StaticRequest,
) -> Result<Vec<f64>, StaticShapeError> {
    let blocked = |i: usize| k.eliminated.get(i).copied().unwrap_or(false);
    let n = k.size();
    Ok(match r {
        StaticRequest::Imposed(s) => {
            if s >= n || !blocked(s) {
                return Err(StaticShapeError::WrongStatus {
                    dof: s,
                    blocked: false,
                });
            }
            let mut unit = vec![0.0; n];
            unit[s] = 1.0;
            let col = mul_full(k, &unit);
            k.row_on_free(&col).into_iter().map(|v| -v).collect()
        }
        StaticRequest::Force(d) => {
            if d >= n || k.reduced_index(d).is_none() {
                return Err(StaticShapeError::WrongStatus {
                    dof: d,
                    blocked: true,
                });
            }
            let mut unit = vec![0.0; n];
            unit[d] = 1.0;
            k.row_on_free(&unit)
        }
        StaticRequest::Acceleration(dir) => {
            let m = m.ok_or(StaticShapeError::NoMass)?;
            k.row_on_free(&mul_full(m, &rigid_translation(m, dir)))
        }
    })
}
