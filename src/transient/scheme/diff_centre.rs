//! DIFF_CENTRE: Code_Aster's explicit central difference, in its own form (the "Euler"
//! step of its DYNA_VIBRA integrator): a kick then a drift,
//!   v_{n+1} = v_n + h a_n,  q_{n+1} = q_n + h v_{n+1},
//!   a_{n+1} = M⁻¹ f(t_{n+1}, q_{n+1}, v_{n+1}).
//! The positions are those of the central difference q_{n+1} − 2q_n + q_{n−1} = h² a_n
//! (second order, symplectic without damping and friction); the velocity carried is the
//! backward difference (q_{n+1} − q_n)/h, the central difference's half-step velocity,
//! which is what velocity-dependent forces (C, AMOR_NOR, friction) see and what is
//! archived as VITE: first order as a velocity at t_{n+1} (error h/2·a).
//! Why this form rather than velocity Verlet (the same positions without damping, a
//! second-order velocity): it is Code_Aster's, so a file run here and there gives the same
//! numbers. Measured on Code_Aster's multi-support shock case (a damped oscillator hitting
//! a wall, 5000 steps): its NON_REGRESSION values (6 digits) reproduced to 1e-10..3e-9
//! absolute; velocity Verlet was off by up to 2.4e-6 on values of 1e-6..4e-4.
//! Stable for h < 2/ω_max, ω_max² the largest eigenvalue of M⁻¹(K + K_shocks) with every
//! shock's RIGI_NOR (and RIGI_TAN with friction) engaged ([`stability_limit`]; damping
//! lowers the limit a little further and is not counted).

use crate::transient::dis_choc::Shock;
use crate::transient::error::TransientError;
use crate::transient::structure::Structure;
use crate::transient::system::{Model, Work};

/// ω_max of the structure with the shocks' stiffness bounds added: converged
/// (`Structure::max_eigenvalue`), or a rough estimate from below after `iterations` steps.
pub(crate) fn max_pulsation(
    structure: &dyn Structure,
    shocks: &[Shock],
    iterations: Option<usize>,
) -> Result<f64, TransientError> {
    let bounds: Vec<[[f64; 3]; 3]> = shocks.iter().map(Shock::stiffness_bound).collect();
    let extra = |x: &[f64], out: &mut [f64]| {
        for (s, b) in shocks.iter().zip(&bounds) {
            let u = s.relative_rows().apply(x);
            let f = [
                b[0][0] * u[0] + b[0][1] * u[1] + b[0][2] * u[2],
                b[1][0] * u[0] + b[1][1] * u[1] + b[1][2] * u[2],
                b[2][0] * u[0] + b[2][1] * u[1] + b[2][2] * u[2],
            ];
            s.relative_rows().add_transpose(f, out);
        }
    };
    let lambda = match iterations {
        None => structure.max_eigenvalue(&extra)?,
        Some(k) => structure.max_eigenvalue_estimate(&extra, k)?,
    };
    Ok(lambda.max(0.0).sqrt())
}

/// (2/ω_max, ω_max) of the structure with the shocks' stiffness bounds added.
pub(crate) fn stability_limit(
    structure: &dyn Structure,
    shocks: &[Shock],
) -> Result<(f64, f64), TransientError> {
    let omega = max_pulsation(structure, shocks, None)?;
    let limit = if omega > 0.0 {
        2.0 / omega
    } else {
        f64::INFINITY
    };
    Ok((limit, omega))
}

/// The scheme (it needs no workspace: each step updates q, v, a in place).
pub(crate) struct DiffCentre;

impl DiffCentre {
    /// One step from t to t + h; `ws.evals` holds the shocks at the new state.
    #[allow(clippy::too_many_arguments)]
    pub fn step(
        &self,
        model: &Model,
        shocks: &[Shock],
        t: f64,
        h: f64,
        q: &mut [f64],
        v: &mut [f64],
        a: &mut [f64],
        ws: &mut Work,
    ) -> Result<(), TransientError> {
        for ((qi, vi), ai) in q.iter_mut().zip(v.iter_mut()).zip(a.iter()) {
            *vi += h * ai;
            *qi += h * *vi;
        }
        model.acceleration(shocks, t + h, q, v, a, ws)
    }
}
