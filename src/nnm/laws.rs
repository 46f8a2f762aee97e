//! Regularised contact laws recast as quadratic equations, in scaled units (lengths divided
//! by the largest JEU g_ref, forces by k_ref·g_ref; see `system::Scaling`).
//!
//! Each law lists its own unknown series and its equations as constant, linear and quadratic
//! terms; the tangent is derived from the same list (system.rs), so residual and Jacobian
//! cannot disagree. With s = JEU/g_ref, α = RIGI_NOR/k_ref and η = PARA_REGUL:
//! - PLAN (f):             f²/α − f (u − s) − η s² = 0
//!   (Code_Aster's F(F/α − (u/JEU − 1)) = η with F = f/(k_ref·JEU), i.e. the physical law
//!   f(f − α(u−g)) = α η_phys with η_phys = PARA_REGUL·k_ref·JEU²).
//! - BI_PLAN (f, z):       f − η u − f z = 0,   z − (f/α − u)²/s² = 0
//!   (Code_Aster's F − η u/JEU − F Z = 0, Z = (F/α − u/JEU)²; the sign of eq. (9) of R5.07.01).
//! - CERCLE (f, r, fx, fy): f²/α − f (r − s) − η s² = 0,  r² − (ux−ex)² − (uy−ey)² = 0,
//!   fx r − f (ux−ex) = 0,  fy r − f (uy−ey) = 0.

use crate::error::{Error, Result};

/// A variable a law equation depends on: one of its own unknown series (H_nl harmonics) or a
/// displacement component of its DOFs (H_l harmonics, zero-padded to H_nl).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Var {
    Own(usize),
    U(usize),
}

/// coef · a · b added to equation `eq`.
#[derive(Clone, Copy, Debug)]
pub struct Term {
    pub eq: usize,
    pub coef: f64,
    pub a: Var,
    pub b: Var,
}

/// coef · var added to equation `eq`.
#[derive(Clone, Copy, Debug)]
pub struct Lin {
    pub eq: usize,
    pub coef: f64,
    pub var: Var,
}

#[derive(Clone, Copy, Debug, PartialEq)]
pub enum ScaledLaw {
    Plan,
    BiPlan,
    /// Ring centre in scaled units.
    Cercle {
        ex: f64,
        ey: f64,
    },
}

/// The equations of one shock: as many as its own unknowns.
#[derive(Clone, Debug)]
pub struct LawEqs {
    pub n_own: usize,
    pub quad: Vec<Term>,
    pub lin: Vec<Lin>,
    /// Constants (on the mean, harmonic 0) per equation.
    pub cst: Vec<(usize, f64)>,
    /// (component, own variable) pairs: the force each component receives.
    pub forces: Vec<(usize, usize)>,
}

fn t(eq: usize, coef: f64, a: Var, b: Var) -> Term {
    Term { eq, coef, a, b }
}
fn l(eq: usize, coef: f64, var: Var) -> Lin {
    Lin { eq, coef, var }
}

/// The equations of a law with scaled gap `s`, stiffness `alpha`, PARA_REGUL `eta`.
pub fn equations(law: ScaledLaw, s: f64, alpha: f64, eta: f64) -> LawEqs {
    use Var::{Own, U};
    match law {
        ScaledLaw::Plan => LawEqs {
            n_own: 1,
            quad: vec![t(0, 1.0 / alpha, Own(0), Own(0)), t(0, -1.0, Own(0), U(0))],
            lin: vec![l(0, s, Own(0))],
            cst: vec![(0, -eta * s * s)],
            forces: vec![(0, 0)],
        },
        ScaledLaw::BiPlan => {
            let c = 1.0 / (s * s);
            LawEqs {
                n_own: 2,
                quad: vec![
                    t(0, -1.0, Own(0), Own(1)),
                    t(1, -c / (alpha * alpha), Own(0), Own(0)),
                    t(1, 2.0 * c / alpha, Own(0), U(0)),
                    t(1, -c, U(0), U(0)),
                ],
                lin: vec![l(0, 1.0, Own(0)), l(0, -eta, U(0)), l(1, 1.0, Own(1))],
                cst: vec![],
                forces: vec![(0, 0)],
            }
        }
        ScaledLaw::Cercle { ex, ey } => LawEqs {
            n_own: 4,
            quad: vec![
                t(0, 1.0 / alpha, Own(0), Own(0)),
                t(0, -1.0, Own(0), Own(1)),
                t(1, 1.0, Own(1), Own(1)),
                t(1, -1.0, U(0), U(0)),
                t(1, -1.0, U(1), U(1)),
                t(2, 1.0, Own(2), Own(1)),
                t(2, -1.0, Own(0), U(0)),
                t(3, 1.0, Own(3), Own(1)),
                t(3, -1.0, Own(0), U(1)),
            ],
            lin: vec![
                l(0, s, Own(0)),
                l(1, 2.0 * ex, U(0)),
                l(1, 2.0 * ey, U(1)),
                l(2, ex, Own(0)),
                l(3, ey, Own(0)),
            ],
            cst: vec![(0, -eta * s * s), (1, -(ex * ex + ey * ey))],
            forces: vec![(0, 2), (1, 3)],
        },
    }
}

/// Positive root of f²/α − f d − c = 0 (c > 0), without cancellation.
fn plan_force(d: f64, alpha: f64, c: f64) -> f64 {
    let q = (d * d + 4.0 * c / alpha).sqrt();
    if d > 0.0 {
        0.5 * alpha * (d + q)
    } else if q - d > 0.0 {
        2.0 * c / (q - d)
    } else {
        0.0
    }
}

/// Root of f(1 − (f/α − u)²/s²) = η u on the branch that is α(u ∓ s) in contact and
/// η u/(1 − u²/s²) inside the gap: for u > 0 it lies in (max(0, α(u−s)), α u), where the
/// function goes from negative to positive; the law is odd in u.
fn biplan_force(u: f64, s: f64, alpha: f64, eta: f64) -> f64 {
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

/// Samples of a law's own unknowns from samples of its displacement components (a start
/// point: consistent with the law sample by sample, then projected on the harmonics).
pub fn own_from_u(
    law: ScaledLaw,
    s: f64,
    alpha: f64,
    eta: f64,
    u: &[Vec<f64>],
) -> Result<Vec<Vec<f64>>> {
    let c = eta * s * s;
    let comp = |i: usize| {
        u.get(i)
            .ok_or_else(|| Error::internal("law component missing"))
    };
    match law {
        ScaledLaw::Plan => Ok(vec![comp(0)?
            .iter()
            .map(|&x| plan_force(x - s, alpha, c))
            .collect()]),
        ScaledLaw::BiPlan => {
            let f: Vec<f64> = comp(0)?
                .iter()
                .map(|&x| biplan_force(x, s, alpha, eta))
                .collect();
            let z = f
                .iter()
                .zip(comp(0)?)
                .map(|(&f, &x)| (f / alpha - x).powi(2) / (s * s))
                .collect();
            Ok(vec![f, z])
        }
        ScaledLaw::Cercle { ex, ey } => {
            let (ux, uy) = (comp(0)?, comp(1)?);
            let r: Vec<f64> = ux
                .iter()
                .zip(uy)
                .map(|(x, y)| ((x - ex).powi(2) + (y - ey).powi(2)).sqrt())
                .collect();
            check_ring_radius(&r, s)?;
            let f: Vec<f64> = r.iter().map(|&r| plan_force(r - s, alpha, c)).collect();
            let fx = (0..r.len()).map(|i| f[i] * (ux[i] - ex) / r[i]).collect();
            let fy = (0..r.len()).map(|i| f[i] * (uy[i] - ey) / r[i]).collect();
            Ok(vec![f, r, fx, fy])
        }
    }
}

/// Closest approach to the ring centre allowed, relative to the ring radius: closer, r(t)
/// has a kink too sharp for the retained harmonics and the operator "multiply by r" (E3,
/// E4) becomes singular where r → 0.
pub const RING_CENTRE_TOL: f64 = 1e-3;

/// r(t) must stay on its positive root, away from the ring centre.
pub fn check_ring_radius(r: &[f64], s: f64) -> Result<()> {
    let rmin = r.iter().copied().fold(f64::INFINITY, f64::min);
    if !rmin.is_finite() || rmin <= RING_CENTRE_TOL * s {
        return Err(Error::numerical(format!(
            "CERCLE: the orbit passes through the ring centre (smallest radial distance {:.3e} × JEU); \
             the radial distance r(t) is not smooth there and its equations become singular",
            rmin / s
        ))
        .keyword("CHOC/ORIG_OBST")
        .hint("a motion through the ring centre along one axis is a BI_PLAN problem; use OBSTACLE='BI_PLAN' or offset ORIG_OBST"));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn biplan_root_solves_the_law_and_is_odd() {
        let (s, a, e) = (1.0, 5.0, 1e-3);
        for &u in &[0.3, 0.99, 1.0, 1.2, 3.0] {
            let f = biplan_force(u, s, a, e);
            let z = (f / a - u).powi(2) / (s * s);
            assert!((f - e * u - f * z).abs() < 1e-10 * (1.0 + f.abs()));
            assert_eq!(biplan_force(-u, s, a, e), -f);
        }
        // Far in contact the force is close to α(u − s).
        assert!((biplan_force(3.0, s, a, e) - a * 2.0).abs() < 1e-2);
    }

    #[test]
    fn plan_root_is_positive_and_smooth_max() {
        let (a, c) = (50.0, 5e-5);
        for &d in &[-1.0, -1e-3, 0.0, 1e-3, 1.0] {
            let f = plan_force(d, a, c);
            assert!(f > 0.0);
            assert!((f * f / a - f * d - c).abs() < 1e-12 * (1.0 + f * f));
        }
    }
}
