//! What the driver asks of a corrected branch end besides its residual: how far the point
//! is from meeting its contact laws in time, and whether its contact forces do the work of
//! a motion. The continuation only asks; the analysis room answers (`PostProcessor`), so
//! the driver never names a contact law.

use crate::nnm::error::Result;

/// The checks of a branch end that need the problem's laws (StepControl::law_defect_max,
/// StepControl::work_min).
pub trait EndCheck {
    /// The law defect of the point `x` (physical units): ECART_LOI_CHOC in units of
    /// RIGI_NOR·JEU, and the same relative to the force the law carries.
    fn law_defects(&self, x: &[f64]) -> Result<(f64, f64)>;

    /// The work ratio of a point that is not a motion (the work of its contact forces on
    /// the displacement over the period, relative to the elastic virial, below
    /// `work_min`), None for one that may be.
    fn not_a_motion(&self, x: &[f64], work_min: f64) -> Result<Option<f64>>;
}
