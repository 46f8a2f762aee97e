//! The regularised contact laws of the engine evaluated pointwise in physical units, with
//! their derivatives: the tangent stiffness J(t) = ∂F/∂u that the variational equation needs.
//!
//! Same laws as `laws.rs` (which works on Fourier series in scaled units); written out
//! here in closed form per sample. With α = RIGI_NOR, g = JEU and
//! η = PARA_REGUL·k_ref·JEU² (`eta_phys`):
//! - PLAN:    f² − α f (u − g) − α η = 0, positive root; df/du = α f / √(α²(u−g)² + 4αη).
//! - BI_PLAN: f ((f − α u)² − α² g²) + α² η u = 0 on the root through f(0) = 0 (the engine's
//!   branch); df/du by implicit differentiation.
//! - CERCLE:  r = |u − e|, force φ(r) n with n = (u − e)/r,
//!   ∂F/∂u = φ'(r) n nᵀ + (φ/r)(I − n nᵀ); φ is PLAN's law at r − g ('RAYON', R5.07.01
//!   eq. 12) or BI_PLAN's at r ('SECANTE'). BI_PLAN's φ is odd, so with 'SECANTE' φ(r)/r and
//!   the force are smooth through the centre, where F = 0 and ∂F/∂u = φ'(0) I. PLAN's φ(0)
//!   is positive, so with 'RAYON' the force flips across the centre and φ/r is unbounded
//!   there; exactly at the centre (an instant of measure zero) the force is taken as zero
//!   and the tangent as φ'(0) I, its radial part.
//!
//! Sign: the force enters M Ü + K U + Pᵀ F = 0 with a plus sign (as in the engine's
//! residual), so a compressed stop (u > g for PLAN) has f > 0 and J adds to K.

use crate::error::{Error, Result};
use crate::nnm::model::system::Scaling;
use crate::nnm::{CercleForm, Problem, ShockLaw};

/// Physical regularisation η of each shock: PARA_REGUL·k_ref·JEU², with k_ref the engine's
/// reference stiffness (1/(K⁻¹)pp at the last component of the first shock with the
/// largest JEU, `Scaling::new`).
pub(crate) fn eta_phys(problem: &Problem) -> Result<Vec<f64>> {
    if problem.shocks.is_empty() {
        return Ok(Vec::new());
    }
    // With shocks the amplitude and fallback DOF arguments are not used by the scaling.
    let scaling = Scaling::new(problem, 1.0, 0)?;
    Ok(problem
        .shocks
        .iter()
        .map(|s| s.regul * scaling.stiffness * s.gap * s.gap)
        .collect())
}

/// One shock's law in physical units.
#[derive(Clone, Copy, Debug)]
pub struct PointLaw {
    pub law: ShockLaw,
    pub alpha: f64,
    pub gap: f64,
    pub eta: f64,
}

/// PLAN force and df/du at penetration d = u − g, without cancellation on either side.
/// The root is the engine's (`nnm::laws::plan_force`, c = η).
fn plan(d: f64, alpha: f64, eta: f64) -> (f64, f64) {
    let q = (alpha * alpha * d * d + 4.0 * alpha * eta).sqrt();
    let f = crate::nnm::model::laws::plan_force(d, alpha, eta);
    (f, alpha * f / q)
}

/// BI_PLAN force and df/du. For u > 0 the root lies in (max(0, α(u−g)), α u), where
/// ψ(f) = f (1 − ((f − αu)/(αg))²) − (η/g²) u goes from negative to positive; the law is odd.
fn biplan(u: f64, alpha: f64, g: f64, eta: f64) -> Result<(f64, f64)> {
    let ep = eta / (g * g);
    let ag = alpha * g;
    if alpha <= ep {
        return Err(Error::input(format!(
            "BI_PLAN: PARA_REGUL is too large for RIGI_NOR (η/JEU² = {ep:e} ≥ RIGI_NOR = {alpha:e}); \
             the regularised law has no restoring branch"
        ))
        .keyword("CHOC/PARA_REGUL"));
    }
    let (sign, ua) = if u < 0.0 { (-1.0, -u) } else { (1.0, u) };
    // The root is the engine's bisection (`nnm::laws::biplan_force`, whose η is η/g²).
    let f = crate::nnm::model::laws::biplan_force(ua, g, alpha, ep);
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

impl PointLaw {
    /// A ring's force magnitude φ(r) and φ'(r) at radial distance r ≥ 0.
    fn radial(&self, form: CercleForm, r: f64) -> Result<(f64, f64)> {
        match form {
            CercleForm::Radial => Ok(plan(r - self.gap, self.alpha, self.eta)),
            CercleForm::Secant => biplan(r, self.alpha, self.gap, self.eta),
        }
    }

    /// Number of displacement components (1, or 2 for CERCLE).
    pub fn n_comp(&self) -> usize {
        match self.law {
            ShockLaw::Cercle { .. } => 2,
            _ => 1,
        }
    }

    /// Force components at displacement `u`, without their Jacobian and without
    /// allocating (the first `n_comp` entries; the law check samples it at every instant).
    pub fn force(&self, u: &[f64]) -> Result<[f64; 2]> {
        let comp = |i: usize| {
            u.get(i)
                .copied()
                .ok_or_else(|| Error::internal("contact law component missing"))
        };
        match self.law {
            ShockLaw::Plan => Ok([
                crate::nnm::model::laws::plan_force(comp(0)? - self.gap, self.alpha, self.eta),
                0.0,
            ]),
            ShockLaw::BiPlan => Ok([biplan(comp(0)?, self.alpha, self.gap, self.eta)?.0, 0.0]),
            ShockLaw::Cercle { origin, form } => {
                let (dx, dy) = (comp(0)? - origin[0], comp(1)? - origin[1]);
                let r = dx.hypot(dy);
                let (f, _) = self.radial(form, r)?;
                if r == 0.0 {
                    return Ok([0.0, 0.0]);
                }
                Ok([f * dx / r, f * dy / r])
            }
        }
    }

    /// The penetration of the nonsmooth law at displacement `u` (PLAN u − g, BI_PLAN
    /// |u| − g, CERCLE |u − e| − g): negative while the structure is clear of the obstacle.
    pub fn penetration(&self, u: &[f64]) -> Result<f64> {
        let comp = |i: usize| {
            u.get(i)
                .copied()
                .ok_or_else(|| Error::internal("contact law component missing"))
        };
        Ok(match self.law {
            ShockLaw::Plan => comp(0)? - self.gap,
            ShockLaw::BiPlan => comp(0)?.abs() - self.gap,
            ShockLaw::Cercle { origin, .. } => {
                (comp(0)? - origin[0]).hypot(comp(1)? - origin[1]) - self.gap
            }
        })
    }

    /// Force components and their Jacobian (row-major n_comp × n_comp) at displacement `u`.
    pub fn eval(&self, u: &[f64]) -> Result<(Vec<f64>, Vec<f64>)> {
        let comp = |i: usize| {
            u.get(i)
                .copied()
                .ok_or_else(|| Error::internal("contact law component missing"))
        };
        match self.law {
            ShockLaw::Plan => {
                let (f, df) = plan(comp(0)? - self.gap, self.alpha, self.eta);
                Ok((vec![f], vec![df]))
            }
            ShockLaw::BiPlan => {
                let (f, df) = biplan(comp(0)?, self.alpha, self.gap, self.eta)?;
                Ok((vec![f], vec![df]))
            }
            ShockLaw::Cercle { origin, form } => {
                let (dx, dy) = (comp(0)? - origin[0], comp(1)? - origin[1]);
                let r = dx.hypot(dy);
                let (f, df) = self.radial(form, r)?;
                if r == 0.0 {
                    // The centre: no force, and the radial tangent in every direction
                    // (φ/r → φ'(0) with 'SECANTE'; module doc for 'RAYON').
                    return Ok((vec![0.0, 0.0], vec![df, 0.0, 0.0, df]));
                }
                let (nx, ny) = (dx / r, dy / r);
                let t = f / r;
                let j = vec![
                    df * nx * nx + t * (1.0 - nx * nx),
                    (df - t) * nx * ny,
                    (df - t) * nx * ny,
                    df * ny * ny + t * (1.0 - ny * ny),
                ];
                Ok((vec![f * nx, f * ny], j))
            }
        }
    }
}
