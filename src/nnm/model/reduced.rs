//! A problem on a Craig–Bampton basis (REDUCTION): the shock DOFs kept as the first
//! coordinates, the fixed-interface modes after them (linalg/craig_bampton.rs), the
//! matrices projected and each shock moved onto the coordinates of its DOFs. The engine
//! then solves the reduced problem as any other; a full-model shape enters it through its
//! reduced coordinates.

use crate::linalg::craig_bampton::{craig_bampton, rayleigh, ModeCut, Reduction};
use crate::linalg::eigen::sym::SymSparse;
use crate::nnm::error::{Error, Result};
use crate::nnm::model::problem::{Problem, Shock};

/// The DOFs the shocks act on, each once, in the order the shocks name them: the retained
/// DOFs of the basis.
pub fn shock_dofs(full: &Problem) -> Vec<usize> {
    let mut out: Vec<usize> = Vec::new();
    for d in full.shocks.iter().flat_map(|s| &s.dofs) {
        if !out.contains(d) {
            out.push(*d);
        }
    }
    out
}

/// The Craig–Bampton basis of `full` retaining its shock DOFs, with the modes `cut` asks
/// for, in at most `max_columns` columns.
pub fn shock_basis(full: &Problem, cut: ModeCut, max_columns: usize) -> Result<Reduction> {
    Ok(craig_bampton(
        &full.k,
        &full.m,
        &shock_dofs(full),
        cut,
        max_columns,
    )?)
}

/// The problem on the coordinates of `basis`: Tᵀ K T, Tᵀ M T, and each shock on the
/// coordinates of its DOFs.
pub fn reduced_problem(full: &Problem, basis: &Reduction) -> Result<Problem> {
    if basis.n != full.k.nrows() {
        return Err(Error::input(format!(
            "the reduction basis has {} DOFs, the structure {} free DOFs: it belongs to \
             other matrices",
            basis.n,
            full.k.nrows()
        )));
    }
    let shocks = full
        .shocks
        .iter()
        .map(|s| {
            let dofs = s
                .dofs
                .iter()
                .map(|d| {
                    basis.retained.iter().position(|r| r == d).ok_or_else(|| {
                        Error::store("the reduction basis does not retain the DOFs of its shocks")
                    })
                })
                .collect::<Result<Vec<_>>>()?;
            Ok(Shock { dofs, ..s.clone() })
        })
        .collect::<Result<Vec<_>>>()?;
    Ok(Problem {
        forcing: None,
        k: basis.project_stiffness(&full.k)?,
        m: basis.project_mass(&full.m)?,
        shocks,
    })
}

/// A basis with the full mass matrix, which turns a full-model shape (a linear mode to
/// start from) into reduced coordinates.
pub struct Reduced {
    pub basis: Reduction,
    mass: SymSparse,
}

impl Reduced {
    pub fn new(basis: Reduction, full: &Problem) -> Result<Reduced> {
        Ok(Reduced {
            basis,
            mass: SymSparse::from_faer(&full.m, "mass")?,
        })
    }

    /// A linear mode of the full model (shape on the free DOFs) as a start on the reduced
    /// `problem`: its reduced coordinates and the pulsation the reduced model gives that
    /// shape (its Rayleigh quotient: the reduced model's own mode to round-off when the
    /// basis holds the mode, within the truncation error otherwise).
    pub fn start_mode(&self, problem: &Problem, shape: &[f64]) -> Result<(Vec<f64>, f64)> {
        let q = self.basis.coordinates(&self.mass, shape)?;
        let omega2 = rayleigh(&problem.k, &problem.m, &q)?;
        Ok((q, omega2.max(0.0).sqrt()))
    }
}
