//! BI_PLAN: two stops at ±JEU on one displacement component.
//!
//! Scaled unknowns f, z; equations f − η u − f z = 0 and z − (f/α − u)²/s² = 0 (Code_Aster's
//! F − η u/JEU − F Z = 0, Z = (F/α − u/JEU)², with its sign; docs/ehman.md §2). Pointwise:
//! f((f − αu)² − α²g²) + α²ηu = 0 on the root through f(0) = 0, odd in u; df/du by implicit
//! differentiation. z is built from terms of size (u/JEU)², so a smaller length unit does
//! not help the cancellation: BI_PLAN keeps Code_Aster's unit far up a branch.

use super::{component as comp, lin_term, quad_term, samples, ContactLaw, LawEqs, Var};
use crate::nnm::error::{Error, Result, Setting};

/// The two-sided stop.
#[derive(Clone, Copy, Debug)]
pub struct BiPlan;

/// Root of f(1 − (f/α − u)²/s²) = η u on the branch that is α(u ∓ s) in contact and
/// η u/(1 − u²/s²) inside the gap: for u > 0 it lies in (max(0, α(u−s)), α u), where the
/// function goes from negative to positive; the law is odd in u. Also CALC_STABILITE's.
pub(crate) fn biplan_force(u: f64, s: f64, alpha: f64, eta: f64) -> f64 {
    if u == 0.0 {
        return 0.0;
    }
    let (sign, u) = if u < 0.0 { (-1.0, -u) } else { (1.0, u) };
    let phi = |f: f64| f * (1.0 - (f / alpha - u).powi(2) / (s * s)) - eta * u;
    let (mut lo, mut hi) = ((alpha * (u - s)).max(0.0), alpha * u);
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if phi(mid) < 0.0 {
            lo = mid;
        } else {
            hi = mid;
        }
        if hi - lo <= 1e-15 * hi.abs().max(1e-300) {
            break;
        }
    }
    sign * 0.5 * (lo + hi)
}

/// BI_PLAN force and df/du in physical units. For u > 0 the root lies in
/// (max(0, α(u−g)), α u), where ψ(f) = f (1 − ((f − αu)/(αg))²) − (η/g²) u goes from
/// negative to positive; the law is odd.
pub(super) fn biplan_pointwise(u: f64, alpha: f64, g: f64, eta: f64) -> Result<(f64, f64)> {
    let ep = eta / (g * g);
    let ag = alpha * g;
    if alpha <= ep {
        return Err(Error::input(format!(
            "BI_PLAN: PARA_REGUL is too large for RIGI_NOR (η/JEU² = {ep:e} ≥ RIGI_NOR = {alpha:e}); \
             the regularised law has no restoring branch"
        ))
        .setting(Setting::ShockRegularisation));
    }
    let (sign, ua) = if u < 0.0 { (-1.0, -u) } else { (1.0, u) };
    // The root is the engine's bisection (`biplan_force`, whose η is η/g²).
    let f = biplan_force(ua, g, alpha, ep);
    // Implicit derivative of ψ(f, u) = 0 (the same in u and −u since the law is odd).
    let w = (f - alpha * ua) / ag;
    let psi_f = 1.0 - w * w - 2.0 * f * w / ag;
    let psi_u = 2.0 * f * w / g - ep;
    if !(psi_f.is_finite() && psi_f > 0.0) {
        return Err(Error::numerical(format!(
            "BI_PLAN: the regularised law is singular at u = {u:e} (∂ψ/∂f = {psi_f:e})"
        )));
    }
    Ok((sign * f, -psi_u / psi_f))
}

impl ContactLaw for BiPlan {
    fn n_comp(&self) -> usize {
        1
    }

    fn n_own(&self) -> usize {
        2
    }

    fn own_units(&self, force: f64, _length: f64, _stiffness: f64) -> Vec<f64> {
        vec![force, 1.0]
    }

    fn rescalable(&self) -> bool {
        false
    }

    fn equations(&self, s: f64, alpha: f64, eta: f64) -> LawEqs {
        use Var::{Own, U};
        let c = 1.0 / (s * s);
        LawEqs {
            n_own: 2,
            quad: vec![
                quad_term(0, -1.0, Own(0), Own(1)),
                quad_term(1, -c / (alpha * alpha), Own(0), Own(0)),
                quad_term(1, 2.0 * c / alpha, Own(0), U(0)),
                quad_term(1, -c, U(0), U(0)),
            ],
            lin: vec![
                lin_term(0, 1.0, Own(0)),
                lin_term(0, -eta, U(0)),
                lin_term(1, 1.0, Own(1)),
            ],
            cst: vec![],
            forces: vec![(0, 0)],
        }
    }

    fn own_from_u(&self, s: f64, alpha: f64, eta: f64, u: &[Vec<f64>]) -> Result<Vec<Vec<f64>>> {
        let u0 = samples(u, 0)?;
        let f: Vec<f64> = u0.iter().map(|&x| biplan_force(x, s, alpha, eta)).collect();
        let z = f
            .iter()
            .zip(u0)
            .map(|(&f, &x)| (f / alpha - x).powi(2) / (s * s))
            .collect();
        Ok(vec![f, z])
    }

    fn penetration(&self, u: [f64; 2], gap: f64) -> f64 {
        u[0].abs() - gap
    }

    fn force(&self, u: &[f64], alpha: f64, gap: f64, eta: f64) -> Result<[f64; 2]> {
        Ok([biplan_pointwise(comp(u, 0)?, alpha, gap, eta)?.0, 0.0])
    }

    fn eval(&self, u: &[f64], alpha: f64, gap: f64, eta: f64) -> Result<(Vec<f64>, Vec<f64>)> {
        let (f, df) = biplan_pointwise(comp(u, 0)?, alpha, gap, eta)?;
        Ok((vec![f], vec![df]))
    }

    fn exact_force(&self, u: [f64; 2], alpha: f64, gap: f64) -> ([f64; 2], [f64; 4]) {
        if u[0].abs() > gap {
            (
                [alpha * (u[0] - gap * u[0].signum()), 0.0],
                [alpha, 0.0, 0.0, 0.0],
            )
        } else {
            ([0.0; 2], [0.0; 4])
        }
    }

    fn stiffness_at_rest(&self, gap: f64, eta: f64) -> Option<f64> {
        // Two sides, each as stiff as PLAN's at rest.
        Some(2.0 * eta / (gap * gap))
    }
}
