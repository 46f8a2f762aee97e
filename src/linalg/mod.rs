//! Linear algebra glue over faer: sparse matrices (`sparse`) and the symmetric generalized
//! eigen solvers of CALC_MODES (`eigen` and its parts: dense, shift-invert Lanczos,
//! normalisation).

pub mod eigen;
pub mod eigen_dense;
pub mod eigen_lanczos;
pub mod eigen_norm;
pub mod eigen_shift;
pub mod eigen_sym;
pub mod sparse;
