//! EHMAN stage 5, the report: what each branch tells its caller (the branch report and the
//! errors that name their branch), and the no-progress guard that ends a run whose steps
//! have collapsed.

use crate::nnm::continuation::step_control::{STALL_ENERGY, STALL_FREQUENCY};
use crate::nnm::error::{Error, Setting};
use crate::nnm::Point;

#[derive(Clone, Debug)]
pub struct BranchReport {
    pub branch: usize,
    pub points: usize,
    pub freq_range: (f64, f64),
    pub energy_range: (f64, f64),
    pub a_max: f64,
    pub newton_iterations: usize,
    pub bifurcation: bool,
    /// Retries with a halved step before the correction converged.
    pub step_retries: usize,
    /// The end point was accepted at the round-off floor (newton.rs).
    pub at_floor: bool,
}

pub(in crate::nnm) fn in_branch(mut e: Error, b: usize) -> Error {
    e.message = format!("branch {b}: {}", e.message);
    e
}

/// The window's (energy, frequency) when the last `window` + 1 branch ends all lie within
/// [`STALL_ENERGY`] and [`STALL_FREQUENCY`] of each other (relative spreads).
pub(in crate::nnm) fn no_progress(ends: &[(f64, f64)], window: usize) -> Option<(f64, f64)> {
    if window == 0 || ends.len() <= window {
        return None;
    }
    let w = &ends[ends.len() - 1 - window..];
    let spread = |f: &dyn Fn(&(f64, f64)) -> f64| {
        let (lo, hi) = w
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), p| {
                (lo.min(f(p)), hi.max(f(p)))
            });
        (hi - lo) / hi.abs().max(f64::MIN_POSITIVE)
    };
    let last = w[w.len() - 1];
    (spread(&|p| p.0) < STALL_ENERGY && spread(&|p| p.1) < STALL_FREQUENCY).then_some(last)
}

/// The report of branch `b` from its points (the last one the corrected end).
pub(in crate::nnm) fn branch_report(
    b: usize,
    points: &[Point],
    a_max: f64,
    newton_iterations: usize,
    step_retries: usize,
    at_floor: bool,
) -> BranchReport {
    let range = |f: &dyn Fn(&Point) -> f64| {
        points
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), p| {
                (lo.min(f(p)), hi.max(f(p)))
            })
    };
    BranchReport {
        branch: b,
        points: points.len(),
        freq_range: range(&|p| p.frequency),
        energy_range: range(&|p| p.energy),
        a_max,
        newton_iterations,
        bifurcation: points.iter().any(|p| p.bifurcation),
        step_retries,
        at_floor,
    }
}

/// The error that ends a run whose last `window` branch ends stayed at (`energy`,
/// `frequency`) (see [`no_progress`]).
pub(in crate::nnm) fn stalled(window: usize, energy: f64, frequency: f64, a_max: f64) -> Error {
    Error::numerical(format!(
        "no progress over the last {window} branches: ENERGIE stayed within {:.0} % of {energy:.6e} \
         and FREQUENCE within {:.1} % of {frequency:.6e} Hz (a_max = {a_max:.3e})",
        100.0 * STALL_ENERGY,
        100.0 * STALL_FREQUENCY,
    ))
    .setting(Setting::BranchesWithoutProgress)
    .hint(
        "the series steps have collapsed (typically at the onset of a stiff contact, or far up a \
         nearly homogeneous branch where round-off dominates): if the branch has reached what you \
         need, bound the run with ENER_MAX, FREQ_MAX or DEPL_MAX; otherwise raise PARA_REGUL, \
         NB_HARM_LINE, or lower PREC_MAN",
    )
}
