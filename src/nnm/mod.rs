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
//! - `Continuation::direction` (DIR_EVOLUTION): −1 goes forward, +1 backward. From a linear
//!   mode, forward is toward increasing amplitude; backward toward decreasing amplitude
//!   first, through zero and up again along the same orbits half a period later. From a
//!   stored point given its direction of travel ([`StartState::travelling`]), forward goes
//!   on that way and backward turns back. Code_Aster's sign comes from a random bordering
//!   vector; this rule follows the paths of its validation cases (docs/mode_non_line.md).
//! - Branch numbers in reports start at 1.
//!
//! The method, room by room (docs/nnm.md, "Rooms", lists every file): the problem, its
//! settings and its laws (model/problem.rs, model/law/, model/system.rs); the tangent's
//! solvers (solve/); stage 1, the start (continuation/start.rs, continuation/quadrature.rs);
//! stage 2, the series step (continuation/series_step.rs over continuation/anm.rs); stage 3,
//! the correction of the branch end (continuation/correction.rs over
//! continuation/newton.rs); stage 4, the bifurcation test (continuation/bifurcation.rs);
//! stage 5, the report (continuation/report.rs); the driver that chains them branch after
//! branch (continuation/driver.rs); a point as the user sees it (model/point.rs) and as a
//! motion (analysis/orbit.rs).

// The shared `Error` (a contract of the crate) is large: `clippy::result_large_err` is
// allowed once at the crate root (src/lib.rs), with the reason.

// The engine's errors: typed, naming a setting, not a keyword (the operators name it).
pub mod error;

// The rooms, lowest first: a room uses itself and the rooms declared before it, never one
// declared after it (`tests::doors` checks it; docs/nnm.md lists their files).
mod model;

mod solve;

mod continuation;

mod analysis;

// The front door: the continuation with the analysis room's checks of each branch end.
mod follow;

#[cfg(test)]
mod tests;

pub use analysis::{error_sources, exact_law, stability};
pub use model::exact;
pub use solve::budget;

pub use analysis::amplitude::peak_amplitude;
pub use analysis::band::{holds_no_resonance, MARGIN as RESONANCE_MARGIN};
pub use analysis::below_contact::{regularisation_alarm, ClearRow};
pub use analysis::law_check::LAW_DEFECT_ALARM;
pub use analysis::orbit::{
    contact_coefficients, displacement_coefficients, largest_displacement, time_history,
    velocity_coefficients, TimeHistory,
};
pub use analysis::post::{contact_law_defect, PostProcessor, RowOutputs};
pub use analysis::resolution::{accuracy_warning, resolution_warnings, tail_ratio};
pub use analysis::resonance::resonance_alarm;
pub use analysis::route_timing::{contact_route_timings, RouteRow};
pub use continuation::correction::relative_gamma;
pub use continuation::driver::Outcome;
pub use continuation::forced_start::start_forced;
pub use continuation::frequency_floor::FrequencyFloor;
pub use continuation::quadrature::{check_degenerate_pair, start_from_mode_pair, QUAD_FREQ_TOL};
pub use continuation::report::BranchReport;
pub(crate) use continuation::start::check_start;
pub use continuation::start::{
    start_from_mode, start_from_mode_using, start_from_point, StartState,
};
pub use continuation::step_control::{Approximation, StepControl, STALL_ENERGY, STALL_FREQUENCY};
pub use follow::{continue_branches, continue_controlled, continue_while};
pub use model::linear_modes::{linear_modes, LinearMode};
pub use model::point::Point;
pub use model::problem::{
    CercleForm, Continuation, Forcing, Harmonics, Problem, Settings, Shock, ShockLaw,
};
pub use model::reduced::{reduced_problem, shock_basis, Reduced};
pub use model::system::unknown_count;
pub use solve::contact::Method as ContactMethod;
pub use solve::linear_solver::{BorderedSolver, SparseLu};
pub use solve::solver_kind::SolverKind;
