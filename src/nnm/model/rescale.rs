//! Lengths rescaled along the branch: once the motion outgrows the length unit by
//! [`RESCALE_AT`], the unknowns are re-expressed in a unit of the motion's own size.
//!
//! Why: a piecewise-linear stop makes the problem homogeneous at large amplitude, but in
//! units of the largest JEU the scaled displacements grow without bound while the law
//! equations are quadratic in them. Round-off then grows like ε‖X‖² against a residual
//! measured relative to ‖X‖: far up a branch (sdnd122a with NB_BRANCHE 400, amplitude
//! 7e6 JEU) every correction stopped "at the round-off floor", the step-length safeguard
//! halved the series step to nothing and the run stalled. Re-expressed in a length of the
//! motion's size, every equation is of order one again and round-off stays relative.
//!
//! The laws are written for any length unit (law/: the gap enters as s = JEU/length, the
//! regularisation as PARA_REGUL·k_ref times powers of s), so a new unit changes no law,
//! only the numbers that represent it. Stiffness, mass and pulsation units are kept: k_ref
//! and m_ref fix the regularisation's meaning (system::Scaling::new).
//!
//! The determinant test survives a change of unit: unknowns and equations are both scaled
//! by positive factors, and the new border is the old tangent scaled by the unknowns'
//! factors, so the sign of the bordered tangent's determinant is unchanged (docs/nnm.md).

use crate::nnm::error::{Error, Setting};
use crate::nnm::model::point::unit_factors;
use crate::nnm::model::system::{Scaling, System};
use crate::nnm::{Point, Problem};

/// Scaled displacement amplitude (largest |coefficient| of U) above which the lengths are
/// rescaled. Large enough that the branches of the testcases (sdnd122a reaches 134 JEU
/// in its 105 branches) never rescale and keep their results to the bit; small enough that
/// round-off stays about ε·RESCALE_AT relative (1e-13), far below PREC_NEWTON.
pub(in crate::nnm) const RESCALE_AT: f64 = 1.0e3;

/// The largest |coefficient| of the displacement block of `x` (scaled units).
pub(in crate::nnm) fn motion_amplitude(sys: &System, x: &[f64]) -> f64 {
    let nu = sys.lay.n * sys.lay.n_coef_lin;
    x[..nu].iter().fold(0.0f64, |m, v| m.max(v.abs()))
}

/// The scaling whose length unit is the motion's amplitude, when `x` has outgrown the
/// current unit by [`RESCALE_AT`] and every stop of `problem` is rescalable ([`all_rescalable`]); None
/// otherwise.
pub(in crate::nnm) fn rescaled(problem: &Problem, sys: &System, x: &[f64]) -> Option<Scaling> {
    outgrown(
        &sys.scaling,
        all_rescalable(problem),
        motion_amplitude(sys, x),
    )
}

/// Whether a law's recast keeps round-off relative in a length unit of the motion's size:
/// PLAN (f² − αf(u − s) − αηs² = 0) and CERCLE with LOI_CERCLE='RAYON' (the same law on
/// the radial distance r, with r² = d_x² + d_y² and f_x r = f d_x, f_y r = f d_y: every
/// equation homogeneous in the lengths, the gap and η only in the small terms). BI_PLAN
/// and the secant ring ('SECANTE') compute z = (f/α − u)²/s² from terms of size
/// (u/JEU)²: in a smaller s the cancellation is no better, and measured on
/// testcases/hard/biplan_long (a one-DOF BI_PLAN stop run to ENER_MAX 1e15 J) the rescaled
/// run stopped short and its test failed; they keep Code_Aster's unit. Each law says which
/// it is (`ContactLaw::rescalable`, model/law/); this asks every stop of `problem` (a run,
/// above, and a restart, start.rs).
pub(in crate::nnm) fn all_rescalable(problem: &Problem) -> bool {
    problem.shocks.iter().all(|s| s.law.rescalable())
}

/// Why a branch end accepted at its round-off floor (newton.rs) ends the run, if it does:
/// when some stop is not rescalable ([`all_rescalable`]) and the motion exceeds [`RESCALE_AT`] times the
/// largest JEU, the floor is the amplitude's doing (BI_PLAN's and the secant ring's
/// equations lose digits like (amplitude/JEU)², in any length unit), and every branch
/// further up would end at a higher one. Issue 34 asks that no row past first contact be
/// accepted at the floor merely because the amplitude is large: the branch is not stored
/// and the run ends there, its rows all solved to PREC_NEWTON. Measured on the files of
/// testcases/ run with NB_BRANCHE 400: before, cercle_centre, cercle_offset and
/// cercle_whirl (secant rings, and BI_PLAN stops in the same files) stored rows above
/// 1e14 J at the floor, RESIDU up to 2.8e-3 against PREC_NEWTON 1e-9; now none does, and
/// cercle_whirl and cercle_offset pass their RESIDU tests (cercle_centre still fails its
/// own on uncorrected rows inside branches, docs/hard_cases.md).
pub(in crate::nnm) fn floor_far_up(
    problem: &Problem,
    sys: &System,
    x_end: &[f64],
    end: &Point,
    prec_newton: f64,
) -> Option<Error> {
    let largest_gap = problem.largest_gap().unwrap_or(0.0);
    if all_rescalable(problem) || largest_gap <= 0.0 {
        return None;
    }
    let amplitude = motion_amplitude(sys, x_end) * sys.scaling.length / largest_gap;
    (amplitude > RESCALE_AT).then(|| {
        Error::numerical(format!(
            "the branch end (ENERGIE = {:.6e}, FREQUENCE = {:.6e} Hz) was solved only to its \
             round-off level, RESIDU = {:.3e} > PREC_NEWTON = {prec_newton:.1e}, with the motion \
             {amplitude:.3e} times the largest JEU: the equations of BI_PLAN and of the secant \
             ring (LOI_CERCLE='SECANTE') lose digits like (amplitude/JEU)², so no branch further \
             up can be solved to PREC_NEWTON; that branch was not stored",
            end.energy, end.frequency, end.residual
        ))
        .setting(Setting::NewtonPrecision)
        .hint(
            "the rows stored are solved to PREC_NEWTON; to go further up, raise PREC_NEWTON \
             (the rows beyond are then solved to it), or bound the run below this ENERGIE with \
             ENER_MAX",
        )
    })
}

/// The one rule of a change of length unit, for a run (above) and for a restart from a
/// stored row (start.rs): `amplitude` is the motion's in units of `scaling.length`; only
/// problems whose stops are all rescalable ([`all_rescalable`]) change unit.
pub(in crate::nnm) fn outgrown(
    scaling: &Scaling,
    all_rescalable: bool,
    amplitude: f64,
) -> Option<Scaling> {
    (all_rescalable && amplitude.is_finite() && amplitude > RESCALE_AT).then_some(Scaling {
        length: scaling.length * amplitude,
        ..*scaling
    })
}

/// `v` (a point or a direction in the units of `from`) in the units of `to`.
pub(in crate::nnm) fn convert(from: &System, to: &System, v: &[f64]) -> Vec<f64> {
    v.iter()
        .zip(unit_factors(from))
        .zip(unit_factors(to))
        .map(|((x, f), t)| x * f / t)
        .collect()
}

/// A direction `v` of `from` in the units of `to`, normed to 1 (a tangent, a border).
pub(in crate::nnm) fn convert_direction(from: &System, to: &System, v: &[f64]) -> Vec<f64> {
    let mut w = convert(from, to, v);
    let n = w.iter().map(|a| a * a).sum::<f64>().sqrt();
    if n > 0.0 && n.is_finite() {
        w.iter_mut().for_each(|a| *a /= n);
    }
    w
}

/// Why the run ends after branch `b` when `scaling`'s length unit (the motion's amplitude)
/// has outgrown the largest JEU by 1/ε: the gaps are then below the round-off of the
/// motion, the stops are numerically gapless and the problem exactly homogeneous, so every
/// further branch would only scale the same orbit (same frequency, ENERGIE ∝ amplitude²)
/// until the numbers overflow. None while the gaps still count.
pub(in crate::nnm) fn homogeneous_limit(
    problem: &Problem,
    scaling: &Scaling,
    b: usize,
) -> Option<String> {
    // A law without a JEU (a cubic spring) keeps the problem from being homogeneous at
    // any amplitude: the branches go on changing the orbit.
    if problem.stops().count() < problem.shocks.len() {
        return None;
    }
    let gap = problem.largest_gap()?;
    (gap < f64::EPSILON * scaling.length).then(|| {
        format!(
            "after branch {b} the motion's amplitude ({:.3e} m) exceeds the largest JEU \
             ({gap:.3e} m) by more than 1/epsilon = {:.1e}: the gaps are below the round-off of \
             the motion, the stops act as gapless and every further branch would only scale \
             the same orbit (same FREQUENCE, ENERGIE growing as the amplitude squared)",
            scaling.length,
            1.0 / f64::EPSILON
        )
    })
}
