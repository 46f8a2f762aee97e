//! A point of a branch as the user sees it (physical units, Code_Aster's ENERGIE) and the
//! conversions between the engine's scaled unknowns and physical ones.

use crate::nnm::model::energy;
use crate::nnm::model::system::System;

#[derive(Clone, Debug)]
pub struct Point {
    pub omega: f64,
    /// Hz.
    pub frequency: f64,
    /// Code_Aster's ENERGIE (J).
    pub energy: f64,
    /// Full unknown vector, physical units (layout in the module doc).
    pub x: Vec<f64>,
    /// ‖R(X)‖/max(1, ‖X‖) of the scaled equations.
    pub residual: f64,
    /// Unfolding parameter (1/s).
    pub gamma: f64,
    /// Relative spread of the total energy over one period sampled in time.
    pub energy_spread: f64,
    /// ENERGIE's formula averaged over one period (J; `energy::energy_mean_ca`).
    pub energy_mean: f64,
    pub bifurcation: bool,
    pub branch: usize,
    pub harm_max: usize,
    /// Retries of this branch with a shorter series step before its correction converged
    /// (on the branch's corrected end row; 0 on the others).
    pub step_retries: usize,
    /// The correction was accepted at the round-off floor (newton.rs), not below
    /// PREC_NEWTON.
    pub at_floor: bool,
    /// ECART_LOI_CHOC and the same relative to the force the law carries
    /// (`PostProcessor::law_defects`), when the run has already checked this point against
    /// its contact law (the branch ends, StepControl::law_defect_max): the table takes them
    /// instead of sampling the law a second time.
    pub law_defect: Option<(f64, f64)>,
}

/// Physical value of each unknown per scaled unit.
pub(in crate::nnm) fn unit_factors(sys: &System) -> Vec<f64> {
    let lay = sys.lay;
    let scaling = sys.scaling;
    let force = scaling.stiffness * scaling.length;
    let mut f = vec![scaling.length; lay.n * lay.n_coef_lin];
    f.extend(std::iter::repeat_n(
        scaling.length * scaling.omega,
        lay.n * lay.n_coef_lin,
    ));
    for sh in &sys.shocks {
        let per = sh
            .law
            .with(|l| l.own_units(force, scaling.length, scaling.stiffness));
        for &u in &per {
            f.extend(std::iter::repeat_n(u, lay.n_coef_nonl));
        }
    }
    f.extend([scaling.omega, scaling.omega]);
    f
}

pub(in crate::nnm) fn finite(v: &[f64]) -> bool {
    v.iter().all(|x| x.is_finite())
}

pub(in crate::nnm) fn make_point(
    sys: &System,
    x: &[f64],
    residual: f64,
    branch: usize,
    bifurcation: bool,
) -> Point {
    let lay = sys.lay;
    let scaling = sys.scaling;
    let e_scale = scaling.stiffness * scaling.length * scaling.length;
    let energy = energy::energy_ca(sys, x);
    let omega = x[lay.omega()] * scaling.omega;
    let xp: Vec<f64> = x
        .iter()
        .zip(unit_factors(sys))
        .map(|(v, f)| v * f)
        .collect();
    Point {
        omega,
        frequency: omega / (2.0 * std::f64::consts::PI),
        energy: energy * e_scale,
        x: xp,
        residual,
        gamma: x[lay.gamma()] * scaling.omega,
        energy_spread: energy::energy_spread(sys, x, energy),
        energy_mean: energy::energy_mean_ca(sys, x) * e_scale,
        bifurcation,
        branch,
        harm_max: energy::harm_max(sys, x),
        step_retries: 0,
        at_floor: false,
        law_defect: None,
    }
}

pub(in crate::nnm) fn to_scaled(sys: &System, x: &[f64]) -> Vec<f64> {
    x.iter()
        .zip(unit_factors(sys))
        .map(|(v, f)| v / f)
        .collect()
}
