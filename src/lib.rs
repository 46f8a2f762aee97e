//! aster-nl: Code_Aster-style command files for nonlinear modal analysis, with every
//! result kept in an SQLite concept store.
//!
//! Modules, one concern each:
//! - [`lang`]: the `.comm` language (pest grammar, evaluation to [`value::CommandCall`]s).
//! - [`catalog`]: operator catalogs from `commands/` and validation into [`args::Args`].
//! - [`store`]: the SQLite concept store (no numerics).
//! - [`mesh`], [`model`]: meshes, models, element matrices and assembly.
//! - [`linalg`]: sparse/dense linear algebra glue and eigen solvers over faer.
//! - [`nnm`]: the nonlinear normal mode engine (EHMAN), pure numerics, no SQL.
//! - [`table`], [`function`]: in-memory tables and functions (filters, sorts, interpolation).
//! - [`ops`]: one thin file per operator.
//! - [`interp`]: runs a command file, one store transaction per operator.
//! - [`study`]: the measured accuracy-versus-time study of the engine (`aster-nl study`).
//! - [`sweep`]: parametric sweeps, one `aster-nl run` process per point, local or Slurm,
//!   merged into one SQLite file (`aster-nl sweep`, `aster-nl merge`).

// `Error` carries a location, a keyword and a hint for the user: it is larger than clippy's
// default budget for error types, on purpose, and never sits on a hot path.
#![allow(clippy::result_large_err)]

pub mod args;
pub mod catalog;
pub mod error;
pub mod export;
pub mod function;
pub mod interp;
pub mod lang;
pub mod linalg;
pub mod mesh;
pub mod model;
pub mod nnm;
pub mod ops;
pub mod plot;
pub mod store;
pub mod study;
pub mod suggest;
pub mod sweep;
pub mod table;
pub mod value;
