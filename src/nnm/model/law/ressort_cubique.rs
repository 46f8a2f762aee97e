//! RESSORT_CUBIQUE: a cubic spring f = k₃·u³ on one displacement component (aster-nl
//! extension, MODE_NON_LINE/RESSORT_CUBIQUE; Duffing's oscillator when alone on one DOF).
//!
//! Quadratic recast, scaled unknowns f (the force, first) and w (u²):
//! f − β w u = 0 and w − u² = 0, with β = k₃·L²/k_ref the ratio of the cubic force to the
//! reference stiffness's at one length unit L (the law carries L: `unit`, set by
//! `ShockLaw::scaled`; RAIDEUR is `Shock::stiffness`, so α = k₃/k_ref). Each product is
//! the exact product of the series truncated to NB_HARM_NONL, as for the stops: w is exact
//! when NB_HARM_NONL ≥ 2·NB_HARM_LINE and then the harmonics 0..NB_HARM_LINE of f that the
//! structure feels are those of k₃u³ (classical harmonic balance of the displacement).
//! Pointwise Jacobian in (f, w): [[1, −βu], [0, 1]], determinant 1 at every instant.
//!
//! The spring has no obstacle: no JEU, no penetration, no regularisation (CHOC's JEU and
//! PARA_REGUL are 0 in its `Shock`), and it acts at every amplitude. Its exact law is
//! itself; its energy is ¼k₃u⁴; it stiffens (k₃ > 0), so the frequency floor holds. It is
//! rescalable: in a length unit L′ its equations are the same with β′ = k₃L′²/k_ref.

use super::{component as comp, lin_term, quad_term, samples, ContactLaw, LawEqs, Var};
use crate::nnm::error::{Error, Result, Setting};

/// The cubic spring, in equations whose lengths are in units of `unit` metres (1 for the
/// pointwise law in physical units).
#[derive(Clone, Copy, Debug)]
pub struct RessortCubique {
    pub unit: f64,
}

impl RessortCubique {
    /// The cubic coefficient in the law's units: α·unit² (α = k₃/k_ref scaled, k₃ physical).
    fn beta(&self, alpha: f64) -> f64 {
        alpha * self.unit * self.unit
    }
}

impl ContactLaw for RessortCubique {
    /// Only RAIDEUR counts: finite and positive (a softening spring would lose the
    /// frequency floor and can lose its restoring force).
    fn validate(&self, _gap: f64, stiffness: f64, _regul: f64) -> Result<()> {
        if !(stiffness.is_finite() && stiffness > 0.0) {
            return Err(Error::input(format!(
                "RAIDEUR of a cubic spring must be finite and positive, got {stiffness}"
            ))
            .setting(Setting::CubicStiffness));
        }
        Ok(())
    }

    fn n_comp(&self) -> usize {
        1
    }

    fn n_own(&self) -> usize {
        2
    }

    fn own_units(&self, force: f64, length: f64, _stiffness: f64) -> Vec<f64> {
        vec![force, length * length]
    }

    fn rescalable(&self) -> bool {
        true
    }

    fn has_obstacle(&self) -> bool {
        false
    }

    /// No force of its own size: the defect is judged against the orbit's largest force.
    fn force_unit(&self, _alpha: f64, _gap: f64) -> Option<f64> {
        None
    }

    fn equations(&self, _s: f64, alpha: f64, _eta: f64) -> LawEqs {
        use Var::{Own, U};
        LawEqs {
            n_own: 2,
            quad: vec![
                quad_term(0, -self.beta(alpha), Own(1), U(0)),
                quad_term(1, -1.0, U(0), U(0)),
            ],
            lin: vec![lin_term(0, 1.0, Own(0)), lin_term(1, 1.0, Own(1))],
            cst: vec![],
            forces: vec![(0, 0)],
        }
    }

    fn own_from_u(&self, _s: f64, alpha: f64, _eta: f64, u: &[Vec<f64>]) -> Result<Vec<Vec<f64>>> {
        let beta = self.beta(alpha);
        let u0 = samples(u, 0)?;
        let w: Vec<f64> = u0.iter().map(|&x| x * x).collect();
        let f = w.iter().zip(u0).map(|(&w, &x)| beta * w * x).collect();
        Ok(vec![f, w])
    }

    /// Never in contact: there is no obstacle.
    fn penetration(&self, _u: [f64; 2], _gap: f64) -> f64 {
        f64::NEG_INFINITY
    }

    /// ¼βu⁴ (physical: ¼k₃u⁴): the spring's potential, part of ENERGIE.
    fn energy(&self, u: [f64; 2], alpha: f64, _gap: f64) -> f64 {
        0.25 * self.beta(alpha) * u[0].powi(4)
    }

    fn mean_energy(&self, u: [f64; 2], alpha: f64, gap: f64) -> f64 {
        self.energy(u, alpha, gap)
    }

    fn force(&self, u: &[f64], alpha: f64, _gap: f64, _eta: f64) -> Result<[f64; 2]> {
        let x = comp(u, 0)?;
        Ok([self.beta(alpha) * x * x * x, 0.0])
    }

    fn eval(&self, u: &[f64], alpha: f64, _gap: f64, _eta: f64) -> Result<(Vec<f64>, Vec<f64>)> {
        let (x, b) = (comp(u, 0)?, self.beta(alpha));
        Ok((vec![b * x * x * x], vec![3.0 * b * x * x]))
    }

    /// Not regularised: the exact law is the law.
    fn exact_force(&self, u: [f64; 2], alpha: f64, _gap: f64) -> ([f64; 2], [f64; 4]) {
        let (x, b) = (u[0], self.beta(alpha));
        ([b * x * x * x, 0.0], [3.0 * b * x * x, 0.0, 0.0, 0.0])
    }

    /// Its stiffness grows from 0 with the amplitude: no constant shift of the linear
    /// frequency, and no linear range far below contact (the frequency floor's check there
    /// is skipped).
    fn stiffness_at_rest(&self, _gap: f64, _eta: f64) -> Option<f64> {
        None
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The recast's own unknowns solve its equations sample by sample, their Jacobian in
    /// (f, w) has determinant 1, and the pointwise law is k₃u³ with tangent 3k₃u².
    #[test]
    fn own_unknowns_solve_the_recast_and_the_pointwise_law_is_cubic() {
        let law = RessortCubique { unit: 0.02 };
        let alpha = 3.5;
        let beta = alpha * 0.02 * 0.02;
        let eqs = law.equations(0.0, alpha, 0.0);
        let u = vec![vec![-2.0, -0.3, 0.0, 0.7, 1.9]];
        let own = law.own_from_u(0.0, alpha, 0.0, &u).unwrap();
        for (j, &x) in u[0].iter().enumerate() {
            let (f, w) = (own[0][j], own[1][j]);
            let mut r = [0.0; 2];
            for t in &eqs.lin {
                r[t.eq] += t.coef * if t.var == Var::Own(0) { f } else { w };
            }
            for t in &eqs.quad {
                let v = |v: Var| match v {
                    Var::Own(0) => f,
                    Var::Own(_) => w,
                    Var::U(_) => x,
                };
                r[t.eq] += t.coef * v(t.a) * v(t.b);
            }
            assert!(
                r.iter().all(|v| v.abs() <= 1e-15 * (1.0 + f.abs())),
                "{r:?}"
            );
            assert!((f - beta * x * x * x).abs() <= 1e-15 * f.abs());
        }
        let phys = RessortCubique { unit: 1.0 };
        let (f, j) = phys.eval(&[0.3], 2.0, 0.0, 0.0).unwrap();
        assert!((f[0] - 2.0 * 0.027).abs() < 1e-16 && (j[0] - 6.0 * 0.09).abs() < 1e-15);
        assert_eq!(phys.exact_force([0.3, 0.0], 2.0, 0.0).0[0], f[0]);
        assert!((phys.energy([0.3, 0.0], 2.0, 0.0) - 0.5 * 0.0081).abs() < 1e-18);
        assert!(
            phys.validate(0.0, 0.0, 0.0).is_err() && phys.validate(0.0, f64::NAN, 0.0).is_err()
        );
    }
}
