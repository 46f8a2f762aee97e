//! The regularised contact laws of the engine evaluated pointwise in physical units, with
//! their derivatives: the tangent stiffness J(t) = ∂F/∂u that the variational equation needs.
//!
//! Same laws as `law/` (which works on Fourier series in scaled units); written out
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

use crate::nnm::error::{Error, Result};
use crate::nnm::model::system::Scaling;
use crate::nnm::{Problem, ShockLaw};

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

impl PointLaw {
    /// Number of displacement components (1, or 2 for CERCLE).
    pub fn n_comp(&self) -> usize {
        self.law.n_comp()
    }

    /// Force components at displacement `u`, without their Jacobian and without
    /// allocating (the first `n_comp` entries; the law check samples it at every instant).
    pub fn force(&self, u: &[f64]) -> Result<[f64; 2]> {
        self.law
            .with(|l| l.force(u, self.alpha, self.gap, self.eta))
    }

    /// The penetration of the nonsmooth law at displacement `u` (PLAN u − g, BI_PLAN
    /// |u| − g, CERCLE |u − e| − g): negative while the structure is clear of the obstacle.
    pub fn penetration(&self, u: &[f64]) -> Result<f64> {
        let n = self.n_comp();
        if u.len() < n {
            return Err(Error::internal("contact law component missing"));
        }
        let comps = [u[0], if n > 1 { u[1] } else { 0.0 }];
        Ok(self.law.with(|l| l.penetration(comps, self.gap)))
    }

    /// Force components and their Jacobian (row-major n_comp × n_comp) at displacement `u`.
    pub fn eval(&self, u: &[f64]) -> Result<(Vec<f64>, Vec<f64>)> {
        self.law.with(|l| l.eval(u, self.alpha, self.gap, self.eta))
    }
}
