//! Tangent and linear solvers: the bordered tangent of the harmonic-balance system solved
//! by its structure (the contact blocks by their Toeplitz, parity or GMRES routes, the
//! condensed tangent, dense LU), the choice of route, and what a call will cost before
//! anything is allocated. Uses the model; knows nothing of branches.

pub mod budget;
pub(in crate::nnm) mod condensed_det;
pub(in crate::nnm) mod condensed_tangent;
pub(in crate::nnm) mod contact;
pub(in crate::nnm) mod dense_lu;
pub(in crate::nnm) mod gmres;
pub(in crate::nnm) mod linear_solver;
pub(in crate::nnm) mod parity_block;
pub(in crate::nnm) mod solver_kind;
pub(in crate::nnm) mod toeplitz;
