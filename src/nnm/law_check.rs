//! Time-domain check of the contact laws on a computed point.
//!
//! The harmonic balance enforces each law only on the retained harmonics, and the implicit
//! laws have several roots (BI_PLAN's cubic in particular): a branch can drift onto a
//! non-physical root while its residual, |γ| and energy spread stay small. Sampling the
//! solution in time and comparing each force series with the regularised law evaluated at
//! the sampled displacement catches that: on a physical branch the gap is truncation error
//! (measured ≤ 4e-3 of α·JEU on BI_PLAN, ≤ 2e-7 on PLAN), on a spurious root it is O(1).

use super::stability::{eta_phys, PointLaw};
use super::{contact_coefficients, displacement_coefficients, series, Problem, Settings, ShockLaw};
use crate::error::Result;

/// Above this defect (relative to α·JEU) the operator raises an alarm.
pub const LAW_DEFECT_ALARM: f64 = 0.1;

/// Largest |f_series(t) − f_law(u(t))| / (α·JEU) over the shocks and over 2(2H_nl+1)
/// instants of one period; 0 without shocks.
pub fn contact_law_defect(problem: &Problem, settings: &Settings, x: &[f64]) -> Result<f64> {
    if problem.shocks.is_empty() {
        return Ok(0.0);
    }
    let etas = eta_phys(problem)?;
    let u = displacement_coefficients(problem, settings, x)?;
    let c = contact_coefficients(problem, settings, x)?;
    let n_samples = 2 * (2 * settings.h_nonl + 1);
    let mut worst = 0.0f64;
    for ((shock, eta), unknowns) in problem.shocks.iter().zip(&etas).zip(&c) {
        let law = PointLaw {
            law: shock.law,
            alpha: shock.stiffness,
            gap: shock.gap,
            eta: *eta,
        };
        // Which series hold the force components: f for PLAN/BI_PLAN, fx and fy for CERCLE.
        let force_series: Vec<&Vec<f64>> = match shock.law {
            ShockLaw::Cercle { .. } => unknowns.iter().skip(2).take(2).collect(),
            _ => unknowns.iter().take(1).collect(),
        };
        let scale = shock.stiffness * shock.gap;
        for j in 0..n_samples {
            let theta = 2.0 * std::f64::consts::PI * j as f64 / n_samples as f64;
            let ut: Vec<f64> = shock
                .dofs
                .iter()
                .map(|&d| {
                    u.get(d)
                        .map_or(0.0, |s| series::eval(s, settings.h_lin, theta))
                })
                .collect();
            let (f_law, _) = law.eval(&ut)?;
            for (fs, fl) in force_series.iter().zip(&f_law) {
                let f_series = series::eval(fs, settings.h_nonl, theta);
                worst = worst.max((f_series - fl).abs() / scale);
            }
        }
    }
    Ok(worst)
}

#[cfg(test)]
mod tests {
    use super::super::tests::{one_dof, settings};
    use super::super::{continue_branches, start_from_mode};
    use super::*;

    /// On a physical PLAN branch the force series equals the law in time up to truncation;
    /// a force series with the wrong sign (a root that pulls the mass toward the stop) is
    /// O(1) away from it.
    #[test]
    fn physical_branch_passes_and_a_wrong_root_is_caught() {
        let problem = one_dof(ShockLaw::Plan, 5e-5);
        let s = settings(5, 100, 8, 1);
        let start = start_from_mode(&problem, &s, &[1.0], 1.0, 10f64.sqrt()).unwrap();
        let out = continue_branches(&problem, &s, start, &mut |_, _| {});
        assert!(out.error.is_none());
        let last = out.points.last().unwrap();
        let healthy = contact_law_defect(&problem, &s, &last.x).unwrap();
        // PLAN with H_nl = 100 at these energies: measured 2.2e-4 on the last point.
        assert!(healthy < 1e-3, "{healthy}");
        // The other root of f² − αf(u − g) − αη = 0 is f ≈ α(u − g) inside the gap: a
        // force pulling the mass toward the stop. Put it in place of the force series,
        // which sits after U and V (1 DOF × (2·5+1) coefficients each).
        let mut wrong = last.x.clone();
        let (alpha, g) = (50.0, 0.01);
        let off = 2 * (2 * 5 + 1);
        for v in &mut wrong[off..off + 2 * 100 + 1] {
            *v = 0.0;
        }
        wrong[off] = alpha * (last.x[0] - g);
        for k in 1..=5 {
            wrong[off + k] = alpha * last.x[k];
            wrong[off + 100 + k] = alpha * last.x[5 + k];
        }
        let defect = contact_law_defect(&problem, &s, &wrong).unwrap();
        assert!(defect > 0.5, "{defect}");
    }
}
