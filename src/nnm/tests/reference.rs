//! The exact references of the engine tests now live in `exact.rs` (also used by the
//! accuracy study); this alias keeps the tests' imports.

pub use crate::nnm::model::exact::Oscillator;
