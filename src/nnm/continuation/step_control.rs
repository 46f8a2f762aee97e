//! How a run reacts to a branch that goes wrong (retries, the law and energy checks, the
//! no-progress guard) and how far its steps reach (the series or its Padé approximants):
//! the values come from the catalog (RESOLUTION).

use crate::nnm::continuation::frequency_floor::FrequencyFloor;

/// What a branch is evaluated on (RESOLUTION/APPROX_MAN).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Approximation {
    /// The power series up to Code_Aster's step length.
    #[default]
    Series,
    /// Padé approximants of the series, the step lengthened as far as they stay accurate
    /// (pade.rs, series_step.rs).
    Pade,
}

/// How the run reacts to a branch that goes wrong; the engine's own callers use
/// [`StepControl::none`].
#[derive(Clone, Debug, Default)]
pub struct StepControl {
    /// A failed correction is retried from the same series with a_max halved, at most
    /// this many times per branch, before the run stops.
    pub retries_max: usize,
    /// Stop with an error when the branch ends of this many consecutive branches stay
    /// within [`STALL_ENERGY`] in energy and [`STALL_FREQUENCY`] in frequency (0: never).
    pub stall_branches: usize,
    /// A branch whose corrected end violates its contact law in time by more than this is
    /// retried like a failed correction, then stops the run (None: not checked). The
    /// defect is ECART_LOI_CHOC (the row's `contact_law_defect`, in units of RIGI_NOR·JEU) divided
    /// by max(1, the largest law force in those units): the same as ECART_LOI_CHOC up to
    /// the first-contact regime, relative to the force far into a stop.
    pub law_defect_max: Option<f64>,
    /// A branch whose corrected end's contact forces carry a relative frequency defect
    /// (model/root_defect.rs) above both this and [`ROOT_JUMP_RATIO`] times the defect at the
    /// branch start has jumped to the other root of its law: it is retried with a shorter
    /// step (None: not checked).
    pub root_jump_max: Option<f64>,
    /// A branch whose end the Newton correction moved by more than this times the series
    /// step has landed on another family: it is retried with a shorter step (None: not
    /// checked).
    pub correction_ratio_max: Option<f64>,
    /// Likewise for the energy spread over the period (ECART_ENERGIE) of the corrected end.
    pub spread_max: Option<f64>,
    /// A branch whose corrected end's contact forces do less work on the displacement than
    /// this times its elastic virial (contact_work.rs: negative, the forces attract the
    /// structure on average; not a motion) is retried like a failed correction, then stops
    /// the run (None: not checked).
    pub work_min: Option<f64>,
    /// A branch whose corrected end needs a fictitious damping γ above this times ω to
    /// balance (AMOR_FICTIF_MAXI: not a periodic orbit of the conservative structure) is
    /// retried like a failed correction, then stops the run (None: not checked).
    pub gamma_max: Option<f64>,
    /// A branch whose corrected end lies below the linear frequency of its mode by more
    /// than the floor's tolerance, with no internal resonance in reach to explain it
    /// (frequency_floor.rs: not a motion, the contact laws only stiffen), is retried like a
    /// failed correction, then stops the run (None: not checked).
    pub frequency_floor: Option<FrequencyFloor>,
    /// What each branch is evaluated on.
    pub approximation: Approximation,
}

/// Relative spread of ENERGIE over the window of [`StepControl::stall_branches`] below which
/// a run counts as making no progress.
pub const STALL_ENERGY: f64 = 1.0e-2;
/// Relative spread of FREQUENCE over that window, likewise.
pub const STALL_FREQUENCY: f64 = 1.0e-3;

/// How many times the frequency defect of the contact forces may grow over one branch
/// before the branch counts as having jumped roots ([`StepControl::root_jump_max`]).
pub const ROOT_JUMP_RATIO: f64 = 10.0;

impl StepControl {
    /// No retry: a failed correction stops the run.
    pub fn none() -> StepControl {
        StepControl {
            retries_max: 0,
            stall_branches: 0,
            law_defect_max: None,
            root_jump_max: None,
            correction_ratio_max: None,
            spread_max: None,
            work_min: None,
            gamma_max: None,
            frequency_floor: None,
            approximation: Approximation::Series,
        }
    }
}
