//! EHMAN stage 2, the series step: the ANM series of a branch at its start point (anm.rs),
//! oriented the way the user asked (DIR_EVOLUTION, module doc of nnm), and its length a_max
//! reduced until the series is credible at its end.

use crate::nnm::continuation::anm::{self, AnmParams, Series};
use crate::nnm::continuation::newton;
use crate::nnm::continuation::pade::Pade;
use crate::nnm::error::Result;
use crate::nnm::model::energy;
use crate::nnm::model::system::System;
use crate::nnm::model::workspace::Workspace;
use crate::nnm::solve::linear_solver::TangentSolver;
use crate::nnm::{Approximation, Continuation};

/// Which way a branch leaves its start point (the sign of the series' first term).
pub(in crate::nnm) struct Orientation {
    /// DIR_EVOLUTION = −1.
    forward: bool,
    /// From a stored point: the direction the stored branch travelled (scaled units).
    travel: Option<Vec<f64>>,
    /// The previous branch's end tangent, once there is one: the path goes on along it.
    prev_tangent: Option<Vec<f64>>,
}

impl Orientation {
    pub(in crate::nnm) fn new(forward: bool, travel: Option<Vec<f64>>) -> Orientation {
        Orientation {
            forward,
            travel,
            prev_tangent: None,
        }
    }

    /// The next branch continues the path along `tangent` (this branch's end tangent).
    pub(in crate::nnm) fn continue_along(&mut self, tangent: Vec<f64>) {
        self.prev_tangent = Some(tangent);
    }

    /// The unknowns are re-expressed from the units of `from` to those of `to`
    /// (rescale.rs): so are the directions the orientation compares with.
    pub(in crate::nnm) fn units_changed(&mut self, from: &System, to: &System) {
        for t in [&mut self.travel, &mut self.prev_tangent]
            .into_iter()
            .flatten()
        {
            *t = crate::nnm::model::rescale::convert_direction(from, to, t);
        }
    }

    /// ±1: the sign X_1 must take at `x0`.
    fn sign(&self, sys: &System, x0: &[f64], x1: &[f64]) -> f64 {
        let ahead = match (&self.prev_tangent, &self.travel) {
            (Some(t), _) => return if anm::dot(x1, t) < 0.0 { -1.0 } else { 1.0 },
            (None, Some(t)) => anm::dot(x1, t) > 0.0,
            (None, None) => motion_grows(sys, x0, x1),
        };
        if ahead == self.forward {
            1.0
        } else {
            -1.0
        }
    }
}

/// Forward (DIR_EVOLUTION = −1) from a linear mode: the motion grows along `x1`, measured
/// by its time-averaged ½uᵀKu + ½vᵀMv (the energy norm of the orbit). Counting only the
/// harmonic amplitudes, without the mean, is not enough: at first contact with a very
/// stiff stop the harmonics can grow while the orbit's energy falls (the mean backs off the
/// stop), which is not what "toward increasing amplitude" means to a user reading ENERGIE.
pub(in crate::nnm) fn motion_grows(sys: &System, x0: &[f64], x1: &[f64]) -> bool {
    // The measure is quadratic in X: the centred difference with step 1 is exact.
    let plus: Vec<f64> = x0.iter().zip(x1).map(|(a, c)| a + c).collect();
    let minus: Vec<f64> = x0.iter().zip(x1).map(|(a, c)| a - c).collect();
    energy::mean_quadratic_energy(sys, &plus) > energy::mean_quadratic_energy(sys, &minus)
}

/// The series of the branch starting at `x0`, `solver` holding the factorised tangent there.
#[allow(clippy::too_many_arguments)]
pub(in crate::nnm) fn series_step(
    sys: &System,
    ws: &mut Workspace,
    solver: &mut dyn TangentSolver,
    x0: &[f64],
    params: &AnmParams,
    cont: &Continuation,
    approximation: Approximation,
    orientation: &Orientation,
) -> Result<Series> {
    let mut series = anm::compute(sys, ws, solver, x0, params, &|x1: &[f64]| {
        orientation.sign(sys, x0, x1)
    })?;
    // Safeguard: the step-length estimate assumes the series converges at a_max; where it
    // does not (nearly homogeneous regimes far up a branch, where the estimate grows
    // without bound), the end residual says so: halve the step until it is credible.
    let credible = 1e3 * cont.prec_man.max(cont.prec_newton);
    for _ in 0..40 {
        let xe = series.eval(x0, series.a_max);
        let r = newton::relative(&sys.residual(&xe, ws), &xe);
        if r.is_finite()
            && r <= credible.max(SERIES_ROUNDOFF_MARGIN * newton::stiffness_roundoff(sys, &xe))
        {
            break;
        }
        series.a_max *= 0.5;
    }
    if approximation == Approximation::Pade {
        extend_by_pade(sys, ws, x0, cont, &mut series);
    }
    Ok(series)
}

/// The series end's residual is credible up to this many times the round-off of the
/// stiffness terms ([`newton::stiffness_roundoff`]): a step end is then corrected by Newton,
/// whose own acceptance is much tighter ([`newton::roundoff_floor`]).
const SERIES_ROUNDOFF_MARGIN: f64 = 1.0e3;

/// Largest reduced step ā = a/a_series tried for the Padé approximant.
const PADE_REACH_MAX: f64 = 10.0;
/// Growth of ā between the tries.
const PADE_REACH_FACTOR: f64 = 1.1;
/// Q below this (Q(0) = 1) counts as at a pole of the approximant: the step ends before.
const PADE_POLE_MARGIN: f64 = 0.1;

/// The step extended past the series' own a_max by its Padé approximant (pade.rs), as far as
/// the approximant's residual stays within what the series gives at its a_max (or PREC_MAN,
/// if larger) and before Q's first pole; the approximant then serves the whole branch.
fn extend_by_pade(
    sys: &System,
    ws: &mut Workspace,
    x0: &[f64],
    cont: &Continuation,
    series: &mut Series,
) {
    let s = series.a_max;
    let Some(p) = Pade::new(&series.terms, s) else {
        return;
    };
    let xs = series.eval_series(x0, s);
    let threshold = newton::relative(&sys.residual(&xs, ws), &xs).max(cont.prec_man);
    let pole = p
        .first_pole_within(PADE_REACH_MAX, 1000, PADE_POLE_MARGIN)
        .unwrap_or(f64::INFINITY);
    let mut best = s;
    let mut ab = PADE_REACH_FACTOR;
    while ab <= PADE_REACH_MAX && ab * s < pole {
        let x = p.eval(x0, ab * s);
        let r = newton::relative(&sys.residual(&x, ws), &x);
        if !(r.is_finite() && r <= threshold) {
            break;
        }
        best = ab * s;
        ab *= PADE_REACH_FACTOR;
    }
    if best > s {
        series.a_max = best;
        series.pade = Some(p);
    }
}
