//! PLAN: a unilateral stop at JEU on one displacement component.
//!
//! Scaled unknown f, equation f²/α − f (u − s) − η s² = 0 (Code_Aster's
//! F(F/α − (u/JEU − 1)) = η with F = f/(k_ref·JEU); physically f(f − α(u−g)) = α η_phys with
//! η_phys = PARA_REGUL·k_ref·JEU²). Pointwise: the positive root, and df/du =
//! α f / √(α²(u−g)² + 4αη). Every term is homogeneous in the lengths but the small η s², so
//! far up a branch the unknowns can be rescaled (rescale.rs).

use super::{component as comp, lin_term, quad_term, samples, ContactLaw, LawEqs, Var};
use crate::nnm::error::Result;

/// The unilateral stop.
#[derive(Clone, Copy, Debug)]
pub struct Plan;

/// Positive root of f²/α − f d − c = 0 (c > 0), without cancellation. Also CALC_STABILITE's
/// pointwise law (point_law.rs): one root for both.
pub(crate) fn plan_force(d: f64, alpha: f64, c: f64) -> f64 {
    let q = (d * d + 4.0 * c / alpha).sqrt();
    if d > 0.0 {
        0.5 * alpha * (d + q)
    } else if q - d > 0.0 {
        2.0 * c / (q - d)
    } else {
        0.0
    }
}

/// PLAN force and df/du at penetration d = u − g in physical units, without cancellation on
/// either side (the root of [`plan_force`] with c = η).
pub(super) fn plan_pointwise(d: f64, alpha: f64, eta: f64) -> (f64, f64) {
    let q = (alpha * alpha * d * d + 4.0 * alpha * eta).sqrt();
    let f = plan_force(d, alpha, eta);
    (f, alpha * f / q)
}

impl ContactLaw for Plan {
    fn n_comp(&self) -> usize {
        1
    }

    fn n_own(&self) -> usize {
        1
    }

    fn own_units(&self, force: f64, _length: f64, _stiffness: f64) -> Vec<f64> {
        vec![force]
    }

    fn rescalable(&self) -> bool {
        true
    }

    fn equations(&self, s: f64, alpha: f64, eta: f64) -> LawEqs {
        use Var::{Own, U};
        LawEqs {
            n_own: 1,
            quad: vec![
                quad_term(0, 1.0 / alpha, Own(0), Own(0)),
                quad_term(0, -1.0, Own(0), U(0)),
            ],
            lin: vec![lin_term(0, s, Own(0))],
            cst: vec![(0, -eta * s * s)],
            forces: vec![(0, 0)],
        }
    }

    fn own_from_u(&self, s: f64, alpha: f64, eta: f64, u: &[Vec<f64>]) -> Result<Vec<Vec<f64>>> {
        let c = eta * s * s;
        let u0 = samples(u, 0)?;
        Ok(vec![u0
            .iter()
            .map(|&x| plan_force(x - s, alpha, c))
            .collect()])
    }

    fn penetration(&self, u: [f64; 2], gap: f64) -> f64 {
        u[0] - gap
    }

    fn force(&self, u: &[f64], alpha: f64, gap: f64, eta: f64) -> Result<[f64; 2]> {
        Ok([plan_force(comp(u, 0)? - gap, alpha, eta), 0.0])
    }

    fn eval(&self, u: &[f64], alpha: f64, gap: f64, eta: f64) -> Result<(Vec<f64>, Vec<f64>)> {
        let (f, df) = plan_pointwise(comp(u, 0)? - gap, alpha, eta);
        Ok((vec![f], vec![df]))
    }

    fn exact_force(&self, u: [f64; 2], alpha: f64, gap: f64) -> ([f64; 2], [f64; 4]) {
        if u[0] > gap {
            ([alpha * (u[0] - gap), 0.0], [alpha, 0.0, 0.0, 0.0])
        } else {
            ([0.0; 2], [0.0; 4])
        }
    }

    fn stiffness_at_rest(&self, gap: f64, eta: f64) -> Option<f64> {
        Some(1.0 * eta / (gap * gap))
    }
}
