//! DIFF_CENTRE: the explicit central difference in velocity-Verlet form, second order,
//! symplectic without damping and friction:
//!   v_{n+½} = v_n + h/2 a_n,  q_{n+1} = q_n + h v_{n+½},
//!   a_{n+1} = M⁻¹ f(t_{n+1}, q_{n+1}, ṽ),  v_{n+1} = v_{n+½} + h/2 a_{n+1},
//! where velocity-dependent forces (C, AMOR_NOR, friction) see the explicit prediction
//! ṽ = v_{n+½} + h/2 a_n. Stable for h < 2/ω_max, ω_max² the largest eigenvalue of
//! M⁻¹(K + K_shocks) with every shock's RIGI_NOR (and RIGI_TAN with friction) engaged
//! ([`stability_limit`]; damping lowers the limit a little further and is not counted).

use crate::transient::dis_choc::Shock;
use crate::transient::error::{try_zeros, TransientError};
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

/// The scheme's workspace.
pub(crate) struct DiffCentre {
    vh: Vec<f64>,
}

impl DiffCentre {
    pub fn new(n: usize) -> Result<DiffCentre, TransientError> {
        Ok(DiffCentre {
            vh: try_zeros("DIFF_CENTRE's workspace", n)?,
        })
    }

    /// One step from t to t + h; `ws.evals` holds the shocks at the new state.
    #[allow(clippy::too_many_arguments)]
    pub fn step(
        &mut self,
        model: &Model,
        shocks: &[Shock],
        t: f64,
        h: f64,
        q: &mut [f64],
        v: &mut [f64],
        a: &mut [f64],
        ws: &mut Work,
    ) -> Result<(), TransientError> {
        for i in 0..q.len() {
            self.vh[i] = v[i] + 0.5 * h * a[i];
            q[i] += h * self.vh[i];
            v[i] = self.vh[i] + 0.5 * h * a[i];
        }
        model.acceleration(shocks, t + h, q, v, a, ws)?;
        for i in 0..q.len() {
            v[i] = self.vh[i] + 0.5 * h * a[i];
        }
        Ok(())
    }
}
