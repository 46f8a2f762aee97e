//! Time-domain check of the contact laws on a computed point.
//!
//! The harmonic balance enforces each law only on the retained harmonics, and the implicit
//! laws have several roots (BI_PLAN's cubic in particular): a branch can drift onto a
//! non-physical root while its residual, |γ| and energy spread stay small. Sampling the
//! solution in time and comparing each force series with the regularised law evaluated at
//! the sampled displacement catches that: on a physical branch the gap is truncation error
//! (measured ≤ 4e-3 of α·JEU on BI_PLAN, ≤ 2e-7 on PLAN), on a spurious root it is O(1).

use crate::nnm::error::Result;
use crate::nnm::model::fourier::{FftScratch, Sampler};
use crate::nnm::model::point_law::{eta_phys, PointLaw};
use crate::nnm::model::system::Layout;
use crate::nnm::Problem;
use std::ops::Range;

/// Above this defect (relative to α·JEU) the operator raises an alarm.
pub const LAW_DEFECT_ALARM: f64 = 0.1;

/// One shock as the check sees it.
struct CheckedShock {
    law: PointLaw,
    dofs: Vec<usize>,
    /// The contact unknowns holding the force components: f for PLAN/BI_PLAN, fx and fy
    /// for CERCLE.
    forces: Range<usize>,
    /// α·JEU, the unit of the defect; None for a law without a force of its own size (a
    /// cubic spring, `ContactLaw::force_unit`): the largest force of the orbit is its unit.
    scale: Option<f64>,
}

/// The check of one problem's laws, built once (η needs factorisations of K and M, the
/// sampling an FFT plan) and applied to every point of a branch.
pub(crate) struct LawCheck {
    shocks: Vec<CheckedShock>,
    /// 2(2H_nl+1) instants θ_j = 2πj/N of one period: twice as many as the force series
    /// has coefficients, so that a defect between the collocation instants shows too.
    sampler: Sampler,
    h_lin: usize,
    h_nonl: usize,
}

/// The samples of one shock's displacements and forces, and the transform's scratch: made
/// per check (one per branch end and per row, each costing a few transforms), so that one
/// `LawCheck` serves several threads.
struct CheckWork {
    ws: FftScratch,
    /// Samples, component-major: up to two displacement components, up to two forces.
    ut: Vec<f64>,
    ft: Vec<f64>,
}

impl LawCheck {
    pub fn new(problem: &Problem, lay: &Layout) -> Result<LawCheck> {
        let etas = eta_phys(problem)?;
        let shocks = problem
            .shocks
            .iter()
            .zip(etas)
            .map(|(s, eta)| CheckedShock {
                law: PointLaw {
                    law: s.law,
                    alpha: s.stiffness,
                    gap: s.gap,
                    eta,
                },
                dofs: s.dofs.clone(),
                forces: s.law.force_unknowns(),
                scale: s.law.force_unit(s.stiffness, s.gap),
            })
            .collect();
        Ok(LawCheck {
            shocks,
            sampler: Sampler::new(2 * lay.n_coef_nonl),
            h_lin: lay.h_lin,
            h_nonl: lay.h_nonl,
        })
    }

    /// The buffers of one check.
    fn work(&self) -> CheckWork {
        let n = self.sampler.n();
        CheckWork {
            ws: self.sampler.scratch(),
            ut: vec![0.0; 2 * n],
            ft: vec![0.0; 2 * n],
        }
    }

    /// Samples the displacement components of `shock` over one period into `ut`
    /// (component-major, by FFT); returns how many components (1, or 2 for a ring).
    fn sample_displacement(
        &self,
        shock: &CheckedShock,
        u: &[Vec<f64>],
        ut: &mut [f64],
        ws: &mut FftScratch,
    ) -> usize {
        let n = self.sampler.n();
        for (&d, out) in shock.dofs.iter().zip(ut.chunks_exact_mut(n)) {
            match u.get(d) {
                Some(s) => self.sampler.synth_with(s, self.h_lin, out, ws),
                None => out.fill(0.0),
            }
        }
        shock.dofs.len().min(2)
    }

    /// The largest penetration of the nonsmooth law over the shocks and the instants, in
    /// units of each shock's JEU (negative when the orbit never reaches an obstacle); None
    /// without shocks with an obstacle (a cubic spring has none and is skipped).
    /// `u`: displacement coefficients of each DOF.
    pub fn largest_penetration(&self, u: &[Vec<f64>]) -> Result<Option<f64>> {
        let n = self.sampler.n();
        let CheckWork { mut ws, mut ut, .. } = self.work();
        let mut largest: Option<f64> = None;
        for shock in self.shocks.iter().filter(|s| s.law.law.has_obstacle()) {
            let n_comp = self.sample_displacement(shock, u, &mut ut, &mut ws);
            let mut uj = [0.0; 2];
            for j in 0..n {
                for (c, v) in uj[..n_comp].iter_mut().enumerate() {
                    *v = ut[c * n + j];
                }
                let p = shock.law.penetration(&uj[..n_comp])? / shock.law.gap;
                largest = Some(largest.map_or(p, |l: f64| l.max(p)));
            }
        }
        Ok(largest)
    }

    /// Largest |f_series(t) − f_law(u(t))| / (α·JEU) over the shocks and the instants (a
    /// cubic spring's over its largest |f_law(u(t))|; 0 without shocks; `u`: displacement coefficients of each DOF; `contact`: per shock,
    /// its contact unknowns, the layout of `Point::x`, physical units), and the same
    /// relative to the force the law carries: per shock its defect over max(α·JEU, the largest |f_law(u(t))|), the worst
    /// over the shocks. Far into a stop (amplitudes of many JEU) the force is many α·JEU and
    /// a truncated force series misses it by a defect of O(1) α·JEU that is small beside it;
    /// on a non-physical root the series misses the law by the law's own size.
    pub fn defects(&self, u: &[Vec<f64>], contact: &[Vec<Vec<f64>>]) -> Result<(f64, f64)> {
        let mut worst = 0.0f64;
        let mut worst_rel = 0.0f64;
        let n = self.sampler.n();
        let CheckWork {
            mut ws,
            mut ut,
            mut ft,
        } = self.work();
        for (shock, unknowns) in self.shocks.iter().zip(contact) {
            // The largest |f_series − f_law| and |f_law| over the instants, divided by the
            // scale once (x ↦ x/scale is monotonic in floating point: the same maxima).
            let mut own = 0.0f64;
            let mut peak = shock.scale.unwrap_or(0.0);
            // Samples by FFT: within round-off of summing the series at each instant,
            // O(N log N) instead of O(N·H).
            let n_comp = self.sample_displacement(shock, u, &mut ut, &mut ws);
            let forces = unknowns.get(shock.forces.clone()).unwrap_or_default();
            let n_forces = forces.len().min(2);
            for (s, out) in forces.iter().zip(ft.chunks_exact_mut(n)) {
                self.sampler.synth_with(s, self.h_nonl, out, &mut ws);
            }
            let mut uj = [0.0; 2];
            for j in 0..n {
                for (c, v) in uj[..n_comp].iter_mut().enumerate() {
                    *v = ut[c * n + j];
                }
                let f_law = shock.law.force(&uj[..n_comp])?;
                for (i, fl) in f_law[..n_forces].iter().enumerate() {
                    let fs = ft[i * n + j];
                    own = own.max((fs - fl).abs());
                    peak = peak.max(fl.abs());
                }
            }
            let scale = shock.scale.unwrap_or(peak);
            if scale.is_nan() || scale <= 0.0 {
                // A spring that does not move: no force, no defect.
                continue;
            }
            let (own, peak) = (own / scale, peak / scale);
            worst = worst.max(own);
            worst_rel = worst_rel.max(own / peak);
        }
        Ok((worst, worst_rel))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::nnm::model::fourier;
    use crate::nnm::tests::{one_dof, settings};
    use crate::nnm::{
        contact_law_defect, continue_branches, start_from_mode, PostProcessor, Settings, ShockLaw,
    };

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

    /// The defect as first written: every series summed at each instant (O(N·H) sin/cos),
    /// an independent reference for the FFT sampling.
    fn defect_by_summation(problem: &Problem, s: &Settings, x: &[f64]) -> f64 {
        let u = crate::nnm::displacement_coefficients(problem, s, x).unwrap();
        let c = crate::nnm::contact_coefficients(problem, s, x).unwrap();
        let etas = eta_phys(problem).unwrap();
        let n = 2 * (2 * s.harmonics.h_nonl + 1);
        let mut worst = 0.0f64;
        for ((shock, eta), unknowns) in problem.shocks.iter().zip(etas).zip(&c) {
            let law = PointLaw {
                law: shock.law,
                alpha: shock.stiffness,
                gap: shock.gap,
                eta,
            };
            for j in 0..n {
                let theta = 2.0 * std::f64::consts::PI * j as f64 / n as f64;
                let ut: Vec<f64> = shock
                    .dofs
                    .iter()
                    .map(|&d| fourier::eval(&u[d], s.harmonics.h_lin, theta))
                    .collect();
                let f = fourier::eval(&unknowns[0], s.harmonics.h_nonl, theta);
                let fl = law.eval(&ut).unwrap().0[0];
                worst = worst.max((f - fl).abs() / (shock.stiffness * shock.gap));
            }
        }
        worst
    }

    /// The FFT sampling gives the defect of the direct summation to round-off, on branch
    /// points in and out of contact for PLAN and BI_PLAN.
    #[test]
    fn fft_sampling_matches_summing_the_series_at_each_instant() {
        for law in [ShockLaw::Plan, ShockLaw::BiPlan] {
            let problem = one_dof(law, 5e-5);
            let s = settings(5, 100, 6, 2);
            let start = start_from_mode(&problem, &s, &[1.0], 1.0, 10f64.sqrt()).unwrap();
            let out = continue_branches(&problem, &s, start, &mut |_, _| {});
            assert!(out.error.is_none());
            let post = PostProcessor::new(&problem, &s).unwrap();
            for p in &out.points {
                let by_fft = post.law_defect(&p.x).unwrap();
                let by_sum = defect_by_summation(&problem, &s, &p.x);
                // Round-off only, in units of α·JEU (measured ≤ 4e-16 here, defects
                // 3e-7..1e-4). 1e-14 leaves room for the direct sum's own error, which grows
                // with H and the force (sin(kθ) at arguments up to 2π·H); a sampling at the
                // wrong instants or of the wrong series would be off by the defect itself.
                assert!(
                    (by_fft - by_sum).abs() <= 1e-14,
                    "{law:?} E={}: {by_fft:e} vs {by_sum:e}",
                    p.energy
                );
            }
        }
    }
}
