//! CERCLE: a ring of radius JEU around ORIG_OBST on two displacement components, in either
//! regularisation (CHOC/LOI_CERCLE, `CercleForm`).
//!
//! With d = (u_x − e_x, u_y − e_y) the displacement from the ring centre, r = |d|:
//! - 'RAYON', R5.07.01 eq. (12) as Code_Aster writes it (scaled unknowns f_x, f_y, r, φ):
//!   φ²/α − φ (r − s) − η s² = 0 (PLAN's law on the radial distance), r² − |d|² = 0,
//!   f_x r − φ d_x = 0, f_y r − φ d_y = 0. Homogeneous in the lengths but the small terms:
//!   rescalable far up a branch.
//! - 'SECANTE', aster-nl's (f_x, f_y, λ, z): F − λ d = 0, λ − η − λ z = 0,
//!   z − |F/α − d|²/s² = 0: BI_PLAN's law at the radial distance through the secant
//!   stiffness λ = |F|/r, which never divides by r. Keeps Code_Aster's unit far up.
//!
//! Pointwise (physical units): F = φ(r) n with n = d/r, ∂F/∂u = φ'(r) n nᵀ + (φ/r)(I − n nᵀ);
//! φ is PLAN's law at r − g ('RAYON') or BI_PLAN's at r ('SECANTE'). Exactly at the centre
//! (an instant of measure zero) the force is zero and the tangent φ'(0) I, its radial part.
//! The module doc of `law` discusses the degeneracy of 'RAYON' through the centre.

use super::bi_plan::{biplan_force, biplan_pointwise};
use super::plan::{plan_force, plan_pointwise};
use super::{component as comp, lin_term, quad_term, samples, ContactLaw, LawEqs, Lin, Term, Var};
use crate::nnm::error::Result;

/// Which regularisation of the ring law (CHOC/LOI_CERCLE).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CercleForm {
    /// R5.07.01 eq. (12), Code_Aster's: PLAN's regularised law on the radial distance r,
    /// the force along d/r (unknowns f_x, f_y, r, f).
    Radial,
    /// aster-nl's: BI_PLAN's law at the radial distance through a secant stiffness λ
    /// (unknowns f_x, f_y, λ, z), regular through the ring centre.
    Secant,
}

/// The ring, its centre in the units of the equations it is used in (metres for the
/// pointwise law, JEU_max for the scaled equations).
#[derive(Clone, Copy, Debug)]
pub struct Cercle {
    pub origin: [f64; 2],
    pub form: CercleForm,
}

/// R5.07.01 eq. (12) in scaled units: Own(0) = fx, Own(1) = fy, Own(2) = r, Own(3) = φ.
fn radial_equations(ex: f64, ey: f64, s: f64, alpha: f64, eta: f64) -> LawEqs {
    use Var::{Own, U};
    let mut quad = Vec::with_capacity(10);
    let mut lin = Vec::with_capacity(8);
    let mut cst = vec![(2, 0.0), (3, -eta * s * s)];
    for (comp, e) in [(0usize, ex), (1, ey)] {
        // f_c r − φ (u_c − e_c) = 0.
        quad.push(quad_term(comp, 1.0, Own(comp), Own(2)));
        quad.push(quad_term(comp, -1.0, Own(3), U(comp)));
        lin.push(lin_term(comp, e, Own(3)));
        // −(u_c − e_c)², expanded, in the equation of r.
        quad.push(quad_term(2, -1.0, U(comp), U(comp)));
        lin.push(lin_term(2, 2.0 * e, U(comp)));
        cst[0].1 -= e * e;
    }
    // r² in the equation of r; φ²/α − φ r + s φ in the equation of φ.
    quad.push(quad_term(2, 1.0, Own(2), Own(2)));
    quad.push(quad_term(3, 1.0 / alpha, Own(3), Own(3)));
    quad.push(quad_term(3, -1.0, Own(3), Own(2)));
    lin.push(lin_term(3, s, Own(3)));
    ring_eqs(quad, lin, cst)
}

/// A ring's equations from their terms, the zero ones dropped: four own unknowns, the
/// forces on the two components being the first two.
fn ring_eqs(quad: Vec<Term>, mut lin: Vec<Lin>, mut cst: Vec<(usize, f64)>) -> LawEqs {
    cst.retain(|&(_, v)| v != 0.0);
    lin.retain(|v| v.coef != 0.0);
    LawEqs {
        n_own: 4,
        quad,
        lin,
        cst,
        forces: vec![(0, 0), (1, 1)],
    }
}

/// The secant form in scaled units: Own(0) = Fx, Own(1) = Fy, Own(2) = λ, Own(3) = z.
fn secant_equations(ex: f64, ey: f64, s: f64, alpha: f64, eta: f64) -> LawEqs {
    use Var::{Own, U};
    // Components c = 0 (x), 1 (y), centre e_c, d_c = u_c − e_c.
    let c = 1.0 / (s * s);
    let mut quad = Vec::with_capacity(9);
    let mut lin = Vec::with_capacity(9);
    let mut cst = vec![(2, -eta), (3, 0.0)];
    for (comp, e) in [(0usize, ex), (1, ey)] {
        // F_c − λ d_c = 0.
        lin.push(lin_term(comp, 1.0, Own(comp)));
        quad.push(quad_term(comp, -1.0, Own(2), U(comp)));
        lin.push(lin_term(comp, e, Own(2)));
        // −(F_c/α − u_c + e_c)²/s², expanded, in the equation of z.
        quad.push(quad_term(3, -c / (alpha * alpha), Own(comp), Own(comp)));
        quad.push(quad_term(3, 2.0 * c / alpha, Own(comp), U(comp)));
        quad.push(quad_term(3, -c, U(comp), U(comp)));
        lin.push(lin_term(3, -2.0 * c * e / alpha, Own(comp)));
        lin.push(lin_term(3, 2.0 * c * e, U(comp)));
        cst[1].1 -= c * e * e;
    }
    // λ − η − λ z = 0.
    lin.push(lin_term(2, 1.0, Own(2)));
    quad.push(quad_term(2, -1.0, Own(2), Own(3)));
    lin.push(lin_term(3, 1.0, Own(3)));
    ring_eqs(quad, lin, cst)
}

impl Cercle {
    /// The force magnitude φ(r) and φ'(r) at radial distance r ≥ 0, physical units.
    fn radial(&self, r: f64, alpha: f64, gap: f64, eta: f64) -> Result<(f64, f64)> {
        match self.form {
            CercleForm::Radial => Ok(plan_pointwise(r - gap, alpha, eta)),
            CercleForm::Secant => biplan_pointwise(r, alpha, gap, eta),
        }
    }
}

impl ContactLaw for Cercle {
    fn n_comp(&self) -> usize {
        2
    }

    fn n_own(&self) -> usize {
        4
    }

    fn own_units(&self, force: f64, length: f64, stiffness: f64) -> Vec<f64> {
        match self.form {
            CercleForm::Radial => vec![force, force, length, force],
            CercleForm::Secant => vec![force, force, stiffness, 1.0],
        }
    }

    fn force_unknowns(&self) -> std::ops::Range<usize> {
        0..2
    }

    fn origin(&self) -> [f64; 2] {
        self.origin
    }

    fn rescalable(&self) -> bool {
        self.form == CercleForm::Radial
    }

    fn equations(&self, s: f64, alpha: f64, eta: f64) -> LawEqs {
        let [ex, ey] = self.origin;
        match self.form {
            CercleForm::Radial => radial_equations(ex, ey, s, alpha, eta),
            CercleForm::Secant => secant_equations(ex, ey, s, alpha, eta),
        }
    }

    fn own_from_u(&self, s: f64, alpha: f64, eta: f64, u: &[Vec<f64>]) -> Result<Vec<Vec<f64>>> {
        let c = eta * s * s;
        let [ex, ey] = self.origin;
        let (ux, uy) = (samples(u, 0)?, samples(u, 1)?);
        let n = ux.len().min(uy.len());
        let mut own = vec![vec![0.0; n]; 4];
        match self.form {
            CercleForm::Radial => {
                for i in 0..n {
                    let (dx, dy) = (ux[i] - ex, uy[i] - ey);
                    let r = dx.hypot(dy);
                    let phi = plan_force(r - s, alpha, c);
                    // The physical root r = |d|; exactly at the centre the direction is
                    // free and the instant carries no force (module doc of `law`).
                    let (nx, ny) = if r > 0.0 {
                        (dx / r, dy / r)
                    } else {
                        (0.0, 0.0)
                    };
                    own[0][i] = phi * nx;
                    own[1][i] = phi * ny;
                    own[2][i] = r;
                    own[3][i] = phi;
                }
            }
            CercleForm::Secant => {
                for i in 0..n {
                    let (dx, dy) = (ux[i] - ex, uy[i] - ey);
                    let r = dx.hypot(dy);
                    // BI_PLAN's magnitude at the radial distance; λ = φ/r → φ'(0) = η at
                    // the centre.
                    let phi = biplan_force(r, s, alpha, eta);
                    let lambda = if r > 0.0 { phi / r } else { eta };
                    own[0][i] = lambda * dx;
                    own[1][i] = lambda * dy;
                    own[2][i] = lambda;
                    own[3][i] = (phi / alpha - r).powi(2) / (s * s);
                }
            }
        }
        Ok(own)
    }

    fn penetration(&self, u: [f64; 2], gap: f64) -> f64 {
        (u[0] - self.origin[0]).hypot(u[1] - self.origin[1]) - gap
    }

    fn energy_penetration(&self, u: [f64; 2], gap: f64) -> f64 {
        // ENERGIE's own formula (Code_Aster's), kept as the stored tables computed it.
        let [ex, ey] = self.origin;
        ((u[0] - ex).powi(2) + (u[1] - ey).powi(2)).sqrt() - gap
    }

    fn force(&self, u: &[f64], alpha: f64, gap: f64, eta: f64) -> Result<[f64; 2]> {
        let (dx, dy) = (comp(u, 0)? - self.origin[0], comp(u, 1)? - self.origin[1]);
        let r = dx.hypot(dy);
        let (f, _) = self.radial(r, alpha, gap, eta)?;
        if r == 0.0 {
            return Ok([0.0, 0.0]);
        }
        Ok([f * dx / r, f * dy / r])
    }

    fn eval(&self, u: &[f64], alpha: f64, gap: f64, eta: f64) -> Result<(Vec<f64>, Vec<f64>)> {
        let (dx, dy) = (comp(u, 0)? - self.origin[0], comp(u, 1)? - self.origin[1]);
        let r = dx.hypot(dy);
        let (f, df) = self.radial(r, alpha, gap, eta)?;
        if r == 0.0 {
            // The centre: no force, and the radial tangent in every direction (φ/r → φ'(0)
            // with 'SECANTE'; module doc for 'RAYON').
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

    fn exact_force(&self, u: [f64; 2], alpha: f64, gap: f64) -> ([f64; 2], [f64; 4]) {
        let a = alpha;
        let d = [u[0] - self.origin[0], u[1] - self.origin[1]];
        let r = d[0].hypot(d[1]);
        if r > gap {
            let s = 1.0 - gap / r;
            let q = gap / (r * r * r);
            (
                [a * s * d[0], a * s * d[1]],
                [
                    a * (s + q * d[0] * d[0]),
                    a * q * d[0] * d[1],
                    a * q * d[1] * d[0],
                    a * (s + q * d[1] * d[1]),
                ],
            )
        } else {
            ([0.0; 2], [0.0; 4])
        }
    }

    fn stiffness_at_rest(&self, _gap: f64, _eta: f64) -> Option<f64> {
        None
    }
}
