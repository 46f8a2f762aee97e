//! Which solver of the bordered tangent a run uses (linear_solver.rs), chosen once at the
//! start and kept for the whole continuation.

use crate::nnm::error::Result;
use crate::nnm::model::system::System;
use crate::nnm::solve::linear_solver::{self, ReferenceSolver, StructuredSolver, TangentSolver};
use crate::nnm::{ContactMethod, Continuation};

/// How the bordered tangent is solved (linear_solver.rs). Results agree to round-off; the
/// engine uses `Structured`, the others are for tests and the bench.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum SolverKind {
    /// Schur complements of the contact blocks (route per shock by the cost model), V
    /// eliminated, one sparse LU of the condensed tangent.
    #[default]
    Structured,
    /// As `Structured` with every contact block on the given route.
    StructuredWith(ContactMethod),
    /// The whole tangent in one sparse LU, the determinant test from a dense minor of its
    /// inverse (the engine before issue 9).
    Reference,
}

pub(in crate::nnm) fn make_solver(
    sys: &System,
    cont: &Continuation,
    kind: SolverKind,
) -> Result<Box<dyn TangentSolver>> {
    let solves = linear_solver::solves_per_factorisation(cont.order);
    // The structured solver eliminates V through the autonomous problem's own rows (no
    // damping, the phase row): a forced response is solved whole (the reference solver,
    // which factorises `System::tangent` as it is).
    if sys.forced.is_some() {
        return Ok(Box::new(ReferenceSolver::default()));
    }
    Ok(match kind {
        SolverKind::Structured => Box::new(StructuredSolver::new(sys, solves, None)?),
        SolverKind::StructuredWith(m) => Box::new(StructuredSolver::new(sys, solves, Some(m))?),
        SolverKind::Reference => Box::new(ReferenceSolver::default()),
    })
}
