//! Whether a band of forcing frequencies can hold a resonance of a structure with shocks:
//! REPONSE_FORCEE_NL refuses a band that cannot (a band in the wrong unit, or far from
//! every mode, gives a flat curve that answers nothing).
//!
//! The regularised laws' tangent stiffness lies between 0 (open) and RIGI_NOR (closed) on
//! each component of a shock (PLAN's and BI_PLAN's hyperbola df/du = αf/(2f − α(u − g)) is
//! below α; a ring's radial tangent is below α and its hoop stiffness F/r below α too), so
//! the j-th natural frequency of the structure stiffened anywhere along a motion lies
//! between f_j(K) and f_j(K_c), K_c = K + RIGI_NOR on every shock DOF (eigenvalues grow with
//! the stiffness). A resonance of harmonic k of the forcing (k ≤ NB_HARM_LINE, the
//! harmonics the balance carries: a superharmonic resonance at f_j/k) needs k·f within
//! [f_j(K), f_j(K_c)]. The band is said to hold none only when every k·f of it is more than
//! [`MARGIN`] away from all those intervals (damping moves a peak below f_j; modes
//! coupled by the shocks move the backbone). A law without an obstacle (a cubic spring)
//! stiffens without bound: no band is refused then.
//!
//! Counting, not solving: the number of natural frequencies below a value is Sylvester's
//! inertia of K − ω²M (one LDLᵀ), so the test costs two factorisations per interval of
//! the merged harmonics' bands, and no mode.

use crate::linalg::eigen::counts_below;
use crate::nnm::error::Result;
use crate::nnm::Problem;
use faer::sparse::{SparseColMat, Triplet};
use std::f64::consts::PI;

/// Relative margin around each interval [f_j(K), f_j(K_c)] of possible resonance.
pub const MARGIN: f64 = 0.1;

/// True when no harmonic k ≤ `h_lin` of a forcing frequency in [`f_min`, `f_max`] (Hz) can
/// meet a natural frequency of `problem`'s structure with its shocks open or closed (module
/// doc); false when one can, or when a law has no obstacle.
pub fn holds_no_resonance(problem: &Problem, h_lin: usize, f_min: f64, f_max: f64) -> Result<bool> {
    if problem.shocks.iter().any(|s| !s.law.has_obstacle()) {
        return Ok(false);
    }
    let closed = closed_stiffness(problem)?;
    // The harmonics' bands [k f_min, k f_max], merged where they overlap, each widened by
    // the margin: a resonance j is possible in [a, b] iff f_j(K) ≤ b and f_j(K_c) ≥ a, and
    // since f_j(K) ≤ f_j(K_c) for every j, iff #{f_j(K) < b} > #{f_j(K_c) < a}.
    let intervals = harmonic_bands(h_lin.max(1), f_min, f_max);
    let omega2 = |f: f64| (2.0 * PI * f).powi(2);
    let uppers: Vec<f64> = intervals
        .iter()
        .map(|&(_, b)| omega2(b / (1.0 - MARGIN)))
        .collect();
    let lowers: Vec<f64> = intervals
        .iter()
        .map(|&(a, _)| omega2(a / (1.0 + MARGIN)))
        .collect();
    let open_below = counts_below(&problem.k, &problem.m, &uppers)?;
    let closed_below = counts_below(&closed, &problem.m, &lowers)?;
    Ok(open_below
        .iter()
        .zip(&closed_below)
        .all(|(open, closed)| open <= closed))
}

/// [k·f_min, k·f_max] for k = 1..=h, merged where they overlap, in increasing order.
fn harmonic_bands(h: usize, f_min: f64, f_max: f64) -> Vec<(f64, f64)> {
    let mut out: Vec<(f64, f64)> = Vec::new();
    for k in 1..=h {
        let (a, b) = (k as f64 * f_min, k as f64 * f_max);
        match out.last_mut() {
            Some(last) if a <= last.1 => last.1 = last.1.max(b),
            _ => out.push((a, b)),
        }
    }
    out
}

/// K with RIGI_NOR added on the diagonal of every shock DOF.
fn closed_stiffness(problem: &Problem) -> Result<SparseColMat<usize, f64>> {
    let k = &problem.k;
    let sym = k.symbolic();
    let (cp, ri, v) = (sym.col_ptr(), sym.row_idx(), k.val());
    let mut t: Vec<Triplet<usize, usize, f64>> = Vec::with_capacity(v.len() + 4);
    for col in 0..k.ncols() {
        for p in cp[col]..cp[col + 1] {
            t.push(Triplet::new(ri[p], col, v[p]));
        }
    }
    for s in &problem.shocks {
        for &d in &s.dofs {
            t.push(Triplet::new(d, d, s.stiffness));
        }
    }
    SparseColMat::try_new_from_triplets(k.nrows(), k.ncols(), &t).map_err(|e| {
        crate::nnm::error::Error::internal(format!(
            "the stiffness with the shocks closed could not be assembled: {e:?}"
        ))
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::nnm::tests::one_dof;
    use crate::nnm::ShockLaw;

    // One DOF, k = 10, m = 1: f_open = √10/2π = 0.5033 Hz; a stop of RIGI_NOR 50 closes it
    // to √60/2π = 1.2328 Hz.

    #[test]
    fn a_band_between_open_and_closed_holds_a_resonance() {
        let p = one_dof(ShockLaw::Plan, 1e-4);
        assert!(!holds_no_resonance(&p, 1, 0.6, 0.7).unwrap());
        // Touching the open frequency, and the closed one.
        assert!(!holds_no_resonance(&p, 1, 0.3, 0.51).unwrap());
        assert!(!holds_no_resonance(&p, 1, 1.2, 1.3).unwrap());
    }

    #[test]
    fn a_band_far_above_the_closed_frequency_holds_none() {
        let p = one_dof(ShockLaw::Plan, 1e-4);
        assert!(holds_no_resonance(&p, 1, 2.0, 3.0).unwrap());
        // Just past the margin above 1.2328 Hz: 1.2328·1.1 = 1.356.
        assert!(holds_no_resonance(&p, 1, 1.37, 1.5).unwrap());
        assert!(!holds_no_resonance(&p, 1, 1.34, 1.5).unwrap());
    }

    #[test]
    fn a_band_below_the_modes_holds_a_superharmonic_one_when_the_balance_carries_it() {
        let p = one_dof(ShockLaw::Plan, 1e-4);
        // 0.12..0.14 Hz: 3f = 0.36..0.42 (open 0.5033 is 20 % above: outside the margin),
        // 4f = 0.48..0.56 meets it.
        assert!(holds_no_resonance(&p, 3, 0.12, 0.14).unwrap());
        assert!(!holds_no_resonance(&p, 4, 0.12, 0.14).unwrap());
    }

    #[test]
    fn a_cubic_spring_never_excludes_a_band() {
        let mut p = one_dof(ShockLaw::RESSORT_CUBIQUE, 0.0);
        p.shocks[0].gap = 0.0;
        assert!(!holds_no_resonance(&p, 1, 50.0, 60.0).unwrap());
    }

    #[test]
    fn harmonic_bands_merge_where_they_overlap() {
        assert_eq!(harmonic_bands(1, 1.0, 2.0), vec![(1.0, 2.0)]);
        // [1,1.5], [2,3], [3,4.5], [4,6]: the last three overlap.
        assert_eq!(harmonic_bands(4, 1.0, 1.5), vec![(1.0, 1.5), (2.0, 6.0)]);
    }
}
