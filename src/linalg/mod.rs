//! Linear algebra glue over faer: sparse matrices (`sparse`) and the symmetric generalized
//! eigen solvers of CALC_MODES (`eigen/`: the driver in `eigen/mod.rs`, its parts dense,
//! shift-invert Lanczos, shifted factorisation, symmetric storage, normalisation).

pub mod craig_bampton;
pub mod eigen;
pub mod flexibility;
pub mod projection;
pub mod ritz;
pub mod sparse;
pub mod static_modes;
