//! The time schemes by Code_Aster's names (SCHEMA_TEMPS/SCHEMA), one file each:
//! DIFF_CENTRE (diff_centre.rs), NEWMARK (newmark.rs), and the adaptive explicit
//! Runge–Kutta pairs RUNGE_KUTTA_54 / RUNGE_KUTTA_32 (runge_kutta.rs, their tableaux;
//! Code_Aster's step, step control and driver in `transient/rk_loop.rs`, and aster-nl's
//! loop with event location, LOCALISATION_CHOC='OUI', in `transient/adaptive.rs`).
//!
//! ADAPT_ORDRE1 and ADAPT_ORDRE2 are Code_Aster's own adaptive schemes (adapt.rs, their
//! loop `transient/adapt_loop.rs`), and so is DEVOGE (Code_Aster's adaptive Devogelaere–Fu
//! scheme, its step and loop in `transient/devoge.rs`). ITMI, TRBDF2 and WILSON have no
//! equivalent here (`None`).

pub(crate) mod adapt;
pub(crate) mod diff_centre;
pub(crate) mod newmark;
pub(crate) mod runge_kutta;

pub use crate::transient::devoge::DevogeOptions;
pub use adapt::{AdaptOptions, AdaptOrder, VelocityFloor};

/// Which embedded pair an adaptive scheme uses.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum RkPair {
    /// Dormand–Prince 5(4), 7 stages (FSAL).
    DormandPrince54,
    /// Bogacki–Shampine 3(2), 4 stages (FSAL).
    BogackiShampine32,
}

/// Settings of RUNGE_KUTTA_54 / RUNGE_KUTTA_32 (SCHEMA_TEMPS keywords).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AdaptiveOptions {
    pub pair: RkPair,
    /// TOLERANCE (Code_Aster's default 1e-5). Code_Aster's algorithm (rk_loop.rs): the
    /// relative tolerance of its error estimate, per unknown, against the start's and the
    /// step's size (+ ALPHA). With `locate_contacts` (adaptive.rs): the local error of a
    /// step, relative to the largest |q| (resp. |v|) met so far, per component, in the max
    /// norm (floored near rest).
    pub tolerance: f64,
    /// ALPHA (default 0): added to the sizes of Code_Aster's error scales (rk_loop.rs);
    /// no effect with `locate_contacts`.
    pub alpha: f64,
    /// PAS_MINI: below it the integration stops with an error (default: 1e-10 of the
    /// first step, Code_Aster's; with `locate_contacts`, 1e-12 of the interval).
    /// PAS_MINI = PAS_MAXI makes Code_Aster's step fixed (PAS, unjudged).
    pub pas_mini: Option<f64>,
    /// PAS_MAXI (default: 1e10 times the first step, Code_Aster's; with
    /// `locate_contacts`, the interval).
    pub pas_maxi: Option<f64>,
    /// NMAX_ITER_PAS: consecutive rejections of one step allowed with `locate_contacts`
    /// (default 16); Code_Aster's algorithm has no such limit.
    pub nmax_iter_pas: usize,
    /// LOCALISATION_CHOC='OUI' (aster-nl extension): aster-nl's embedded pairs with their
    /// own error control and a step ending at every contact onset and release
    /// (adaptive.rs) instead of Code_Aster's algorithm (rk_loop.rs, the default).
    pub locate_contacts: bool,
    /// The most steps (accepted and rejected) before a runaway integration is stopped.
    pub max_steps: usize,
}

impl AdaptiveOptions {
    pub fn new(pair: RkPair) -> AdaptiveOptions {
        AdaptiveOptions {
            pair,
            tolerance: 1e-5,
            alpha: 0.0,
            pas_mini: None,
            pas_maxi: None,
            nmax_iter_pas: 16,
            locate_contacts: false,
            max_steps: 50_000_000,
        }
    }
}

/// SCHEMA_TEMPS.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Scheme {
    /// Explicit central difference (Code_Aster's default in GENE), in Code_Aster's
    /// kick-drift form (`diff_centre.rs`).
    DiffCentre,
    /// Newmark (BETA, GAMMA; defaults 0.25, 0.5: average acceleration), shock forces
    /// iterated at the end of the step (newmark.rs).
    Newmark { beta: f64, gamma: f64 },
    /// RUNGE_KUTTA_54 / RUNGE_KUTTA_32: Code_Aster's adaptive explicit Runge–Kutta
    /// (rk_loop.rs), or aster-nl's with event location at contact changes (adaptive.rs).
    Adaptive(AdaptiveOptions),
    /// Code_Aster's ADAPT_ORDRE1 / ADAPT_ORDRE2: explicit, the step set by the apparent
    /// frequency of the motion (adapt.rs).
    Adapt(AdaptOptions),
    /// Code_Aster's DEVOGE (Devogelaere–Fu, adaptive), in its form (`transient/devoge.rs`).
    Devoge(DevogeOptions),
}

impl Scheme {
    /// Code_Aster's SCHEMA names, with defaults (module doc for the mapping).
    pub fn from_name(name: &str) -> Option<Scheme> {
        Some(match name.trim() {
            "DIFF_CENTRE" => Scheme::DiffCentre,
            "NEWMARK" => Scheme::Newmark {
                beta: 0.25,
                gamma: 0.5,
            },
            "RUNGE_KUTTA_54" => Scheme::Adaptive(AdaptiveOptions::new(RkPair::DormandPrince54)),
            "DEVOGE" => Scheme::Devoge(DevogeOptions::default()),
            "RUNGE_KUTTA_32" => Scheme::Adaptive(AdaptiveOptions::new(RkPair::BogackiShampine32)),
            "ADAPT_ORDRE1" => Scheme::Adapt(AdaptOptions::new(AdaptOrder::One)),
            "ADAPT_ORDRE2" => Scheme::Adapt(AdaptOptions::new(AdaptOrder::Two)),
            _ => return None,
        })
    }
}
