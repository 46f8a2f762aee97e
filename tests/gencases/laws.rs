//! The contact laws in physical units, as the references evaluate them at one instant.
//!
//! - PLAN (stop at u = JEU): the regularised force is the root of f² − αf(u − g) − αη = 0
//!   (R5.07.01 eq. 8), f = (αd + √(α²d² + 4αη))/2 with d = u − g, evaluated without
//!   cancellation inside the gap; the nonsmooth law is α·max(0, d).
//! - BI_PLAN (stops at ±JEU): f((f − αu)² − α²g²) + α²ηu = 0 (eq. 9 with z eliminated), the
//!   root between α(|u| − g)⁺ and α|u| (the left side is strictly decreasing there), by
//!   bracketed Newton; nonsmooth α·sign(u)·max(0, |u| − g).
//! - CERCLE (ring of radius g centred at c): eq. (12), PLAN's law in the radial distance
//!   z = |u − c| with the force along u − c, F = f·(u − c)/z. The seed writes the direction
//!   as u itself (f_x z − f u_x = 0); that is the same for a centred ring, and off centre only
//!   u − c gives a force field that derives from a potential (without one no family of
//!   periodic orbits exists), so u − c it is. At the centre (z = 0) the regularised force
//!   keeps the magnitude f(−g) ≈ η/g but its direction is undefined: the field jumps across
//!   the centre by 2η/g. An orbit through the centre crosses that jump; the integrator's
//!   step control shrinks the step there, and `ode.rs` refines its tolerance until the
//!   period no longer moves (the centre singularity costs accuracy only locally).
//!
//! η = PARA_REGUL·k_ref·JEU² (Code_Aster's scaling: docs/nnm.md). The force enters the
//! equations as M ü + K u + Pᵀ F = 0, so F > 0 pushes the DOF back toward −∞.

#[derive(Debug, Clone, Copy)]
pub enum Kind {
    Plan,
    BiPlan,
    Cercle { centre: [f64; 2] },
}

#[derive(Debug, Clone, Copy)]
pub struct Shock {
    pub kind: Kind,
    pub px: usize,
    pub py: usize,
    pub gap: f64,
    pub alpha: f64,
    pub eta: f64,
    /// false: the nonsmooth (penalty) law, the limit η → 0.
    pub regularised: bool,
}

/// PLAN's regularised force at penetration d (physical units).
pub fn plan_force(alpha: f64, eta: f64, d: f64) -> f64 {
    let q = (alpha * alpha * d * d + 4.0 * alpha * eta).sqrt();
    if d >= 0.0 {
        0.5 * (alpha * d + q)
    } else {
        2.0 * alpha * eta / (q - alpha * d)
    }
}

/// BI_PLAN's regularised force at displacement u.
pub fn biplan_force(alpha: f64, eta: f64, gap: f64, u: f64) -> f64 {
    let a = u.abs();
    if a == 0.0 {
        return 0.0;
    }
    let psi = |f: f64| {
        f * ((f - alpha * a).powi(2) - alpha * alpha * gap * gap) + alpha * alpha * eta * a
    };
    let dpsi =
        |f: f64| (f - alpha * a).powi(2) - alpha * alpha * gap * gap + 2.0 * f * (f - alpha * a);
    let (mut lo, mut hi) = ((alpha * (a - gap)).max(0.0), alpha * a);
    let mut f = lo;
    for _ in 0..200 {
        let p = psi(f);
        if p > 0.0 {
            lo = f;
        } else {
            hi = f;
        }
        let d = dpsi(f);
        let mut next = if d < 0.0 { f - p / d } else { f64::NAN };
        if !(next > lo && next < hi) {
            next = 0.5 * (lo + hi);
        }
        if (next - f).abs() <= 1e-15 * next.abs() || next <= lo || next >= hi {
            f = next;
            break;
        }
        f = next;
    }
    f.copysign(u)
}

impl Shock {
    /// The force on the shock's DOFs (x, y).
    pub fn force(&self, u: &[f64]) -> (f64, f64) {
        let (a, g, e) = (self.alpha, self.gap, self.eta);
        match self.kind {
            Kind::Plan => {
                let d = u[self.px] - g;
                let f = if self.regularised {
                    plan_force(a, e, d)
                } else {
                    a * d.max(0.0)
                };
                (f, 0.0)
            }
            Kind::BiPlan => {
                let x = u[self.px];
                let f = if self.regularised {
                    biplan_force(a, e, g, x)
                } else {
                    a * (x.abs() - g).max(0.0) * x.signum()
                };
                (f, 0.0)
            }
            Kind::Cercle { centre } => {
                let (dx, dy) = (u[self.px] - centre[0], u[self.py] - centre[1]);
                let z = dx.hypot(dy);
                if z == 0.0 {
                    return (0.0, 0.0);
                }
                let f = if self.regularised {
                    plan_force(a, e, z - g)
                } else {
                    a * (z - g).max(0.0)
                };
                (f * dx / z, f * dy / z)
            }
        }
    }

    /// The signed penetration of the nonsmooth law at displacement u (positive in contact).
    pub fn penetration(&self, u: &[f64]) -> f64 {
        match self.kind {
            Kind::Plan => u[self.px] - self.gap,
            Kind::BiPlan => u[self.px].abs() - self.gap,
            Kind::Cercle { centre } => {
                (u[self.px] - centre[0]).hypot(u[self.py] - centre[1]) - self.gap
            }
        }
    }

    /// The penalty energy ENERGIE counts (Code_Aster's definition): ½α·(penetration)².
    pub fn penalty_energy(&self, u: &[f64]) -> f64 {
        0.5 * self.alpha * self.penetration(u).max(0.0).powi(2)
    }

    /// The magnitude of the force (for the spectrum of the contact force).
    /// A ring's radial distance |u − c|, one of eq. (12)'s unknowns (None for the planes):
    /// its series, truncated to NB_HARM_NONL like the force's, has a kink where the orbit
    /// crosses the centre even when the force is smooth there.
    pub fn radial_distance(&self, u: &[f64]) -> Option<f64> {
        match self.kind {
            Kind::Cercle { centre } => Some((u[self.px] - centre[0]).hypot(u[self.py] - centre[1])),
            _ => None,
        }
    }

    pub fn force_magnitude(&self, u: &[f64]) -> f64 {
        let (fx, fy) = self.force(u);
        match self.kind {
            Kind::Cercle { .. } => fx.hypot(fy),
            _ => fx,
        }
    }
}
