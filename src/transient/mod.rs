//! Transient dynamics with localized shocks: the numerics of Code_Aster's DYNA_VIBRA
//! TYPE_CALCUL='TRAN' (DYNA_TRAN_MODAL) with COMPORTEMENT RELATION='DIS_CHOC'. Pure
//! numerics: no SQL, no keywords, no store.
//!
//! Equations, on a generalized (modal) basis, BASE_CALCUL='GENE':
//!   M q̈ + C q̇ + K q = Σ_i f_i g_i(t) + Σ_s Φ_sᵀ F_s(Φ_s q, Φ_s q̇),
//! q the generalized coordinates, f_i g_i(t) the EXCIT terms (a vector times FONC_MULT or
//! COEF_MULT), and for each shock s, Φ_s the rows giving the global translations DX, DY,
//! DZ of its node 1 (and of node 2 for a two-node shock) and F_s the DIS_CHOC force in the
//! obstacle's frame (`dis_choc.rs`, geometry in `obstacle.rs`; node 2 receives −F_s), or
//! for RELATION='FLAMBAGE' the normal force of the buckling law (`flambage.rs`). The
//! same equations on the physical basis (M, K, C sparse on the free DOFs, Φ_s a selection
//! of rows: BASE_CALCUL='PHYS') are an aster-nl extension. The structure is a
//! [`Structure`]: [`DenseStructure`] (diagonal or full generalized matrices, modal damping
//! ratios) or [`SparseStructure`].
//!
//! Schemes ([`Scheme`], Code_Aster's SCHEMA names through [`Scheme::from_name`]):
//! - DIFF_CENTRE: Code_Aster's explicit central difference (v += h a, then q += h v),
//!   order 2 in positions, the velocity carried being the half step's; symplectic
//!   without damping or friction; stable for PAS < 2/ω_max, ω_max of M⁻¹(K + shocks'
//!   RIGI_NOR/RIGI_TAN), checked before the run ([`TransientError::Unstable`]).
//! - NEWMARK (BETA, GAMMA; 0.25/0.5 by default): order 2, unconditionally stable for the
//!   linear part; the shock forces are iterated to convergence at each step (Newton with a
//!   low-rank Woodbury update of the once-factorised matrix).
//! - RUNGE_KUTTA_54 (Dormand–Prince 5(4)) and RUNGE_KUTTA_32 (Bogacki–Shampine 3(2)):
//!   Code_Aster's adaptive step, its error estimate with TOLERANCE (default 1e-5) and
//!   ALPHA, PAS_MINI, PAS_MAXI, its retry rule and driver, in its form (`rk_loop.rs`); with
//!   LOCALISATION_CHOC='OUI' (aster-nl extension) aster-nl's own error control and event
//!   location at contact onsets/releases, the step shortened so that they fall on step
//!   boundaries (`adaptive.rs`).
//! - DEVOGE: Code_Aster's adaptive Devogelaere–Fu scheme in its form (order 4, 3 with
//!   damping; its error estimate, step control and landing on the archive instants:
//!   `devoge.rs`).
//! - ADAPT_ORDRE1 / ADAPT_ORDRE2: Code_Aster's own explicit schemes whose step follows the
//!   apparent frequency of the motion (NB_POIN_PERIODE points per period), in its form
//!   (`scheme/adapt.rs`, loop `adapt_loop.rs`).
//!
//! Shock states (stick anchor, stick/slip flag) advance only at accepted steps. The result
//! is a [`Trajectory`]: archived instants (every k-th step, or listed instants: hit
//! exactly by the adaptive schemes, interpolated by the fixed-step ones), q, v, a, each
//! shock's [`ShockSample`] (FN, FT1, FT2, VN, VT1, VT2, DXLOC, DYLOC, DZLOC, VINT1..20) and
//! the located contact events. Archive sizes are checked before allocation; workspaces are
//! allocated once, nothing in the step loops.
//!
//! With moving supports (MULT_APPUI) q is the motion relative to the supports and each
//! shock's nodes follow the supports' displacements on top of Φ q (support.rs).
//!
//! Files: error.rs (typed errors, conversion to `crate::error::Error`), structure.rs (the
//! trait), contact_time.rs (how long a contact lasts, to judge a fixed step), support.rs (moving
//! supports), dense.rs, sparse.rs, obstacle.rs, dis_choc.rs, flambage.rs (the buckling
//! law and its internal variables), problem.rs (forcing, grid,
//! archive, trajectory), system.rs (the right-hand side), scheme/ (one file per scheme),
//! fixed.rs, rk_loop.rs, adaptive.rs, adapt_loop.rs and devoge.rs (the loops), archive.rs (recording), integrate.rs (the
//! driver), impact_stats.rs (POST_DYNA_MODA_T's impact and wear statistics of the
//! archived samples), tests/.

mod adapt_loop;
mod adaptive;
mod archive;
pub mod contact_time;
pub mod dense;
mod devoge;
pub mod dis_choc;
mod driver;
pub mod error;
mod fixed;
pub mod flambage;
pub mod impact_stats;
pub mod integrate;
pub mod obstacle;
pub mod problem;
mod rk_loop;
pub mod scheme;
pub mod sparse;
pub mod structure;
pub mod support;
mod system;

#[cfg(test)]
mod tests;

pub use contact_time::contact_pulsations;
pub use dense::{DenseMatrix, DenseStructure};
pub use devoge::DevogeOptions;
pub use dis_choc::{
    optimized_tangential_damping, Friction, NodeRows, Shock, ShockSample, ShockSpec, ShockState,
};
pub use error::TransientError;
pub use flambage::{Buckling, BucklingSpec, BucklingState};
pub use integrate::{integrate, integrate_from};
pub use obstacle::{LocalFrame, ObstacleKind};
pub use problem::{Archive, ContactEvent, Forcing, TimeGrid, Trajectory};
pub use scheme::{AdaptOptions, AdaptOrder, AdaptiveOptions, RkPair, Scheme, VelocityFloor};
pub use sparse::SparseStructure;
pub use structure::{LinearSolver, Structure};
pub use support::{SupportMotion, SupportTerm, TimeFn};
