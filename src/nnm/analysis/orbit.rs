//! A stored point seen as a motion: one period sampled in time, its largest displacement,
//! and the Fourier coefficients of each unknown in physical units (for REST_MODE_NONL,
//! CALC_STABILITE and the tables).

use crate::nnm::continuation::start::system_for_point;
use crate::nnm::error::{Error, Result, Setting};
use crate::nnm::model::point::to_scaled;
use crate::nnm::model::unknowns::Unknowns;
use crate::nnm::{model::fourier, Harmonics, Problem};

/// One period sampled in time, physical units.
#[derive(Clone, Debug)]
pub struct TimeHistory {
    pub t: Vec<f64>,
    /// Per DOF, per instant.
    pub displacement: Vec<Vec<f64>>,
    pub velocity: Vec<Vec<f64>>,
    /// Exact second derivative of the displacement series: ü = ω² d²u/dθ², with
    /// d²/dθ² (c_k cos kθ + s_k sin kθ) = −k² (c_k cos kθ + s_k sin kθ).
    pub acceleration: Vec<Vec<f64>>,
    /// Per shock, per component (PLAN/BI_PLAN: 1, CERCLE: x and y), per instant.
    pub contact_force: Vec<Vec<Vec<f64>>>,
}

/// One period sampled at `n_inst` instants t_j = j·T/(n_inst − 1), j = 0..n_inst−1 (both
/// ends included), physical units.
pub fn time_history(
    problem: &Problem,
    harmonics: impl Into<Harmonics>,
    x: &[f64],
    n_inst: usize,
) -> Result<TimeHistory> {
    let sys = system_for_point(problem, harmonics.into(), x)?;
    let xs = to_scaled(&sys, x);
    let lay = sys.lay;
    let scaling = sys.scaling;
    let omega = xs[lay.omega()] * scaling.omega;
    if !(omega.is_finite() && omega > 0.0) || n_inst < 2 {
        return Err(
            Error::input("a time history needs ω > 0 and at least 2 instants")
                .setting(Setting::OrbitInstants),
        );
    }
    let th: Vec<f64> = (0..n_inst)
        .map(|j| 2.0 * std::f64::consts::PI * j as f64 / (n_inst - 1) as f64)
        .collect();
    let samp = |s: &[f64], h: usize, f: f64| {
        let mut v = fourier::eval_uniform(s, h, n_inst - 1);
        v.iter_mut().for_each(|y| *y *= f);
        v
    };
    let displacement = (0..lay.n)
        .map(|i| {
            samp(
                &xs[lay.u(i)..lay.u(i) + lay.n_coef_lin],
                lay.h_lin,
                scaling.length,
            )
        })
        .collect();
    let velocity = (0..lay.n)
        .map(|i| {
            samp(
                &xs[lay.v(i)..lay.v(i) + lay.n_coef_lin],
                lay.h_lin,
                scaling.length * scaling.omega,
            )
        })
        .collect();
    let acceleration = (0..lay.n)
        .map(|i| {
            let u = &xs[lay.u(i)..lay.u(i) + lay.n_coef_lin];
            samp(
                &second_derivative(u, lay.h_lin),
                lay.h_lin,
                scaling.length * omega * omega,
            )
        })
        .collect();
    let contact_force = sys
        .shocks
        .iter()
        .map(|sh| {
            sh.eqs
                .forces
                .iter()
                .map(|&(_, v)| {
                    samp(
                        &xs[sh.offset + v * lay.n_coef_nonl..sh.offset + (v + 1) * lay.n_coef_nonl],
                        lay.h_nonl,
                        scaling.stiffness * scaling.length,
                    )
                })
                .collect()
        })
        .collect();
    Ok(TimeHistory {
        t: th.iter().map(|t| t / omega).collect(),
        displacement,
        velocity,
        acceleration,
        contact_force,
    })
}

/// d²/dθ² of a series `[x0, c1..cH, s1..sH]`, exactly: harmonic k is multiplied by −k².
fn second_derivative(x: &[f64], h: usize) -> Vec<f64> {
    let mut d1 = vec![0.0; x.len()];
    let mut d2 = vec![0.0; x.len()];
    fourier::deriv(x, h, &mut d1);
    fourier::deriv(&d1, h, &mut d2);
    d2
}

/// Instants per harmonic of the displacement at which [`largest_displacement`] samples.
const MAX_SAMPLES_PER_HARMONIC: usize = 8;

/// The largest |u_i(t)| over the DOFs and one period (physical units), sampled at
/// 8·NB_HARM_LINE + 2 instants (the sampled maximum of a sum of H harmonics is within a few
/// per cent of the true one at that density).
pub fn largest_displacement(
    problem: &Problem,
    harmonics: impl Into<Harmonics>,
    x: &[f64],
) -> Result<f64> {
    let harmonics = harmonics.into();
    let th = time_history(
        problem,
        harmonics,
        x,
        MAX_SAMPLES_PER_HARMONIC * harmonics.h_lin + 2,
    )?;
    Ok(th
        .displacement
        .iter()
        .flatten()
        .fold(0.0f64, |m, u| m.max(u.abs())))
}

/// Fourier coefficients (0, C1..CH_l, S1..SH_l) of the displacement of each DOF (physical).
/// For many points of one problem, build a `PostProcessor` (analysis/post.rs) once instead.
pub fn displacement_coefficients(
    problem: &Problem,
    harmonics: impl Into<Harmonics>,
    x: &[f64],
) -> Result<Vec<Vec<f64>>> {
    Unknowns::new(problem, harmonics)?.displacement(x)
}

/// Fourier coefficients of the velocity of each DOF (physical).
pub fn velocity_coefficients(
    problem: &Problem,
    harmonics: impl Into<Harmonics>,
    x: &[f64],
) -> Result<Vec<Vec<f64>>> {
    Unknowns::new(problem, harmonics)?.velocity(x)
}

/// Fourier coefficients (0, C1..CH_nl, S1..SH_nl) of each contact unknown of each shock
/// (PLAN: f; BI_PLAN: f, z; CERCLE: fx, fy, r, φ, or fx, fy, λ, z with LOI_CERCLE='SECANTE'),
/// physical.
pub fn contact_coefficients(
    problem: &Problem,
    harmonics: impl Into<Harmonics>,
    x: &[f64],
) -> Result<Vec<Vec<Vec<f64>>>> {
    Unknowns::new(problem, harmonics)?.contact(x)
}
