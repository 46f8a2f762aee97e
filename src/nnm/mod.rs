//! EHMAN: branches of nonlinear normal modes of M Ü + K U + Pᵀ F = 0 with localised shocks,
//! by harmonic balance and the asymptotic numerical method (design: docs/ehman.md). Pure
//! numerics: physical units in and out, no SQL, no keywords parsing.
//!
//! Conventions the operator glue relies on:
//! - Fourier coefficients are ordered like Code_Aster's output: 0, C1..CH, S1..SH.
//! - `Point::x` is the full unknown vector in physical units, laid out as: U (n DOFs ×
//!   (2H_l+1), DOF after DOF), V (velocities, same layout, m/s), the contact unknowns of each
//!   shock in order (PLAN: f; BI_PLAN: f, z; CERCLE: fx, fy, r, f with LOI_CERCLE='RAYON', fx,
//!   fy, λ, z with 'SECANTE'; z dimensionless, r in m, λ in N/m; each 2H_nl+1 coefficients;
//!   forces in N), then ω (rad/s) and γ (1/s, the unfolding
//!   parameter, zero on an exact solution). Without any shock H_nl is taken equal to H_l.
//! - ENERGIE is Code_Aster's (see `energy.rs`); `energy_spread` is our a-posteriori check.
//! - `Settings::direction` (DIR_EVOLUTION): −1 goes forward, +1 backward. From a linear
//!   mode, forward is toward increasing amplitude; backward toward decreasing amplitude
//!   first, through zero and up again along the same orbits half a period later. From a
//!   stored point given its direction of travel ([`StartState::travelling`]), forward goes
//!   on that way and backward turns back. Code_Aster's sign comes from a random bordering
//!   vector; this rule follows the paths of its validation cases (docs/mode_non_line.md).
//! - Branch numbers in reports start at 1.
//!
//! The method, file by file (docs/nnm.md has the table): the problem and its settings
//! (problem.rs); stage 1, the start (start.rs, quadrature.rs); stage 2, the series step
//! (series_step.rs over anm.rs); stage 3, the correction of the branch end (correction.rs
//! over newton.rs); stage 4, the bifurcation test (bifurcation.rs); stage 5, the report
//! (report.rs); the driver that chains them branch after branch (continuation.rs); a point
//! as the user sees it (point.rs) and as a motion (orbit.rs).

// The shared `Error` (a contract of the crate) is large: `clippy::result_large_err` is
// allowed once at the crate root (src/lib.rs), with the reason.

mod anm;
mod below_contact;
mod bifurcation;
pub mod budget;
mod condensed_det;
mod contact;
mod contact_work;
mod continuation;
mod correction;
mod cosine_sampler;
mod dense_lu;
mod energy;
pub mod error_sources;
pub mod exact;
pub mod exact_law;
mod fold_guard;
mod frequency_floor;
mod gmres;
mod law_check;
mod laws;
mod linear_solver;
mod low_synth;
mod newton;
mod orbit;
mod pade;
mod parity_block;
mod point;
mod point_law;
mod post;
mod problem;
mod quadrature;
mod reduced;
mod report;
mod rescale;
mod resolution;
mod resonance;
mod root_check;
mod route_timing;
mod series;
mod series_step;
mod solver_kind;
pub mod stability;
mod start;
mod step_control;
mod system;
mod toeplitz;
mod vector;

#[cfg(test)]
mod cercle_eq12_tests;
#[cfg(test)]
mod hard_tests;
#[cfg(test)]
mod reference;
#[cfg(test)]
mod resonance_tests;
#[cfg(test)]
mod solver_tests;
#[cfg(test)]
mod tests;

pub use below_contact::{regularisation_alarm, ClearRow};
pub use contact::Method as ContactMethod;
pub use continuation::{continue_branches, continue_controlled, continue_while, Outcome};
pub use correction::relative_gamma;
pub use frequency_floor::FrequencyFloor;
pub use law_check::LAW_DEFECT_ALARM;
pub use linear_solver::{BorderedSolver, SparseLu};
pub use orbit::{
    contact_coefficients, displacement_coefficients, largest_displacement, time_history,
    velocity_coefficients, TimeHistory,
};
pub use point::Point;
pub use post::{contact_law_defect, PostProcessor, RowOutputs};
pub use problem::{CercleForm, Problem, Settings, Shock, ShockLaw};
pub use quadrature::{check_degenerate_pair, start_from_mode_pair, QUAD_FREQ_TOL};
pub use report::BranchReport;
pub use resolution::{resolution_warnings, tail_ratio};
pub use resonance::{linear_modes, resonance_alarm, LinearMode};
pub use route_timing::{contact_route_timings, RouteRow};
pub use solver_kind::SolverKind;
pub(crate) use start::check_start;
pub use start::{start_from_mode, start_from_mode_using, start_from_point, StartState};
pub use step_control::{Approximation, StepControl, STALL_ENERGY, STALL_FREQUENCY};
pub use system::unknown_count;
