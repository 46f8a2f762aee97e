//! Floquet stability of a forced, damped periodic solution (REPONSE_FORCEE_NL's rows):
//! M Ü + C U̇ + K U + Pᵀ F(PU) = f cos ωt, linearised along the orbit into
//! M δÜ + C δU̇ + K_t(t) δU = 0 and integrated over one forcing period T = 2π/ω
//! (`integrate.rs`, the same Newmark or RK4 as CALC_STABILITE with the C terms).
//!
//! What differs from the conservative analysis (`stability.rs`): the forced system is not
//! autonomous, so there is no trivial pair at +1 (a time shift of the orbit is not a
//! solution: the force fixes the phase) and the verdict uses all 2n multipliers. The damping
//! puts every multiplier of a linear system strictly inside the unit circle
//! (Π|μ| = det Φ = exp(−T tr M⁻¹C)); a turning point of the curve is where one real
//! multiplier crosses +1 (saddle-node), so the rows between two folds of a bent resonance
//! have one real multiplier above 1.
//!
//! The orbit defect keeps its meaning (how far the linearised flow is from carrying the
//! orbit's own tangent once round): ẏ = (U̇, Ü) is not a solution of the homogeneous
//! equation here, but of M z̈ + C ż + K_t z = −ω f sin ωt (the time derivative of the forced
//! equation), so the tangent is propagated with that source (one more column) and the
//! defect is ‖z(T) − ẏ(0)‖/‖ẏ(0)‖ in (u, v/ω) units: zero for an exact orbit and an exact
//! integration, the harmonic-balance truncation and the integrator's error otherwise. The
//! verdict and its band are CALC_STABILITE's (`verdict`) with the largest modulus of all
//! multipliers: STABLE at most 1 + TOLERANCE, INSTABLE beyond 1 + max(TOLERANCE,
//! √(2·defect)), INDETERMINE in between. The √ band was measured for the pair that leaves
//! the unit circle through +1 on a conservative family; at a fold of a forced curve a
//! single simple multiplier crosses +1 and moves by O(defect) only, so the band is
//! conservative here (it never calls INSTABLE a row it should not).

use super::{orbit_defect_of, sorted_multipliers, verdict, Floquet, Linearised, Verdict};
use crate::nnm::error::{Error, Result};
use faer::Mat;

/// The damping matrix and the force amplitudes of a forced problem (physical, dense).
#[derive(Clone)]
pub(crate) struct ForcedTerms {
    pub c: Mat<f64>,
    pub f: Vec<f64>,
}

impl ForcedTerms {
    /// d/dt (f cos ωt) = −ω f sin ωt: the source of the tangent's column.
    pub fn source(&self, omega: f64, t: f64) -> Vec<f64> {
        let s = -omega * (omega * t).sin();
        self.f.iter().map(|fi| s * fi).collect()
    }
}

/// Multipliers (all of them), the orbit defect and the verdict from the propagated
/// fundamental matrix `full` (2n × (2n + 1): Φ(T) and the tangent's image z(T)).
pub(super) fn analyse(lin: &Linearised, full: &Mat<f64>, tolerance: f64) -> Result<Floquet> {
    let n2 = 2 * lin.n;
    if full.ncols() != n2 + 1 {
        return Err(Error::internal(
            "forced monodromy without its tangent column",
        ));
    }
    let phi = Mat::from_fn(n2, n2, |i, j| full[(i, j)]);
    let multipliers = sorted_multipliers(&phi)?;
    let max_modulus = multipliers.first().map(|m| m.0.hypot(m.1)).unwrap_or(0.0);
    let z: Vec<f64> = full.col_as_slice(n2).to_vec();
    let orbit_defect = orbit_defect_of(lin, &z);
    let (verdict, band) = verdict(max_modulus, orbit_defect, tolerance);
    Ok(Floquet {
        stable: verdict == Verdict::Stable,
        verdict,
        band,
        nontrivial: multipliers.clone(),
        multipliers,
        max_modulus,
        max_nontrivial_modulus: max_modulus,
        trivial_distance: f64::NAN,
        orbit_defect,
    })
}
