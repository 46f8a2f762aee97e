//! aster-nl: Code_Aster-style command files for nonlinear modal analysis, with every
//! result kept in an SQLite concept store.
//!
//! Modules, one concern each (docs/architecture.md draws them and their contracts):
//! - [`value`], [`args`], [`error`]: the shared contracts (evaluated calls, validated
//!   keywords, errors as values); [`suggest`]: the one "did you mean" rule.
//! - [`lang`]: the `.comm` language (pest grammar, evaluation to [`value::CommandCall`]s).
//! - [`catalog`]: operator catalogs from `commands/` and validation into [`args::Args`].
//! - [`export`]: Code_Aster `.export` files (command file, logical units).
//! - [`store`]: the SQLite concept store (no numerics).
//! - [`mesh`], [`model`]: meshes, models, element matrices and assembly.
//! - [`linalg`]: sparse/dense linear algebra glue and eigen solvers over faer.
//! - [`nnm`]: the nonlinear normal mode engine (EHMAN), pure numerics, no SQL.
//! - [`table`], [`function`]: in-memory tables and functions (filters, sorts, interpolation).
//! - [`transient`]: transient dynamics with shocks (DYNA_VIBRA TRAN, DIS_CHOC), no SQL.
//! - [`plot`]: pictures (PNG, SVG), no SQL.
//! - [`ops`]: one thin file per operator.
//! - [`interp`]: runs a command file, one store transaction per operator, or checks it
//!   (`aster-nl check`); [`check_groups`]: the mesh groups a check knows.
//! - [`bench`]: speed and memory of MODE_NON_LINE (`aster-nl bench`).
//! - [`accuracy`]: the measured accuracy-versus-time study of the engine (`aster-nl accuracy`).
//! - [`sweep`]: parametric sweeps, one `aster-nl run` process per point, local or Slurm,
//!   merged into one SQLite file (`aster-nl sweep`, `aster-nl merge`).

// `result_large_err`, decided once for the crate: `Error` carries a location, a keyword and
// a hint for the user, so it is larger than clippy's budget for error types, on purpose; it
// is returned once per failed call, never on a hot path, so boxing it would buy nothing.
// Binaries and integration tests are crates of their own and repeat this allow, citing it.
#![allow(clippy::result_large_err)]

pub mod accuracy;
pub mod args;
pub mod bench;
pub mod catalog;
pub mod check_groups;
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
pub mod process;
pub mod store;
pub mod suggest;
pub mod sweep;
pub mod table;
pub mod text_file;
pub mod transient;
pub mod value;
