//! Issue 34's generator of MODE_NON_LINE cases and its independent references, shared by
//! the CI sample (`tests/generated.rs`) and the long campaign (`examples/campaign.rs`,
//! which includes this directory by `#[path]`). Nothing here calls `aster_nl::nnm`: the
//! references integrate the equations of motion with their own Runge–Kutta and Newton
//! (`shooting.rs`) or use closed forms (`exact.rs`). docs/hard_cases.md, "Generated
//! campaign", describes the space, the references and the bounds.

// Each of the two users needs only part of the module (the test does not print tables, the
// campaign does not run the references' self-tests).
#![allow(dead_code)]

pub mod eigen;
pub mod exact;
pub mod laws;
pub mod model;
pub mod ode;
pub mod rng;
pub mod run;
pub mod sample;
pub mod shooting;
pub mod write;
