//! The right-hand side shared by every scheme: f(t) − K q − C v + Σ shocks' generalized
//! forces (each shock evaluated from its committed state), the acceleration M⁻¹ of that,
//! and the commit of the shocks' states at an accepted step. Workspaces are allocated once.

use super::dis_choc::{Shock, ShockEval};
use super::error::{try_zeros, TransientError};
use super::problem::Forcing;
use super::structure::Structure;

/// The linear structure and the forcing.
pub(crate) struct Model<'a> {
    pub structure: &'a dyn Structure,
    pub forcing: &'a [Forcing],
}

/// Workspace of one right-hand side evaluation.
pub(crate) struct Work {
    pub r: Vec<f64>,
    tmp: Vec<f64>,
    /// Each shock's evaluation at the last state evaluated.
    pub evals: Vec<ShockEval>,
}

impl Work {
    pub fn new(n: usize, shocks: &[Shock]) -> Result<Work, TransientError> {
        let zero = shocks
            .iter()
            .map(|s| s.evaluate_at(0.0, &[], &[], &s.state))
            .collect();
        Ok(Work {
            r: try_zeros("the force workspace", n)?,
            tmp: try_zeros("the force workspace", n)?,
            evals: zero,
        })
    }
}

impl Model<'_> {
    /// ws.r ← f(t) − K q − C v + Σ_s Φ_sᵀ F_s(q, v); ws.evals updated.
    pub fn force(&self, shocks: &[Shock], t: f64, q: &[f64], v: &[f64], ws: &mut Work) {
        let s = self.structure;
        s.apply_stiffness(q, &mut ws.r);
        ws.r.iter_mut().for_each(|x| *x = -*x);
        if s.has_damping() {
            s.apply_damping(v, &mut ws.tmp);
            ws.r.iter_mut().zip(&ws.tmp).for_each(|(r, c)| *r -= c);
        }
        for f in self.forcing {
            let m = (f.multiplier)(t);
            if m != 0.0 {
                ws.r.iter_mut()
                    .zip(&f.generalized_force)
                    .for_each(|(r, g)| *r += m * g);
            }
        }
        for (shock, ev) in shocks.iter().zip(ws.evals.iter_mut()) {
            *ev = shock.evaluate_at(t, q, v, &shock.state);
            shock.add_generalized(ev, &mut ws.r);
        }
    }

    /// a ← M⁻¹ (f(t) − K q − C v + shocks).
    pub fn acceleration(
        &self,
        shocks: &[Shock],
        t: f64,
        q: &[f64],
        v: &[f64],
        a: &mut [f64],
        ws: &mut Work,
    ) -> Result<(), TransientError> {
        self.force(shocks, t, q, v, ws);
        a.copy_from_slice(&ws.r);
        self.structure.solve_mass(a)
    }
}

/// Accepts the states of the last evaluation (an accepted step).
pub(crate) fn commit(shocks: &mut [Shock], evals: &[ShockEval]) {
    for (s, e) in shocks.iter_mut().zip(evals) {
        s.state = e.sample.state;
    }
}

/// True when every value is finite.
pub(crate) fn finite(x: &[f64]) -> bool {
    x.iter().all(|v| v.is_finite())
}
