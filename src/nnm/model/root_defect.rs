//! Which root of its regularised law a point's contact forces sit on, judged by what it
//! does to the frequency (docs/nnm.md, "Which root of the law").
//!
//! Each regularised law has two roots for the force at a given displacement: the physical
//! one (a penalty force in contact, η-small out of it) and a spurious one (η-small in
//! contact, an adhesive penalty force out of it). The harmonic balance converges on either:
//! where the two cross (at grazing) a series step can leave along the spurious family,
//! whose frequency stays that of the free structure. ECART_LOI_CHOC, relative to
//! RIGI_NOR·JEU, is small on that family while the penetration is small, although the
//! frequency is already wrong.
//!
//! The measure here weighs the departure by its effect on the frequency. By virtual work
//! with the motion itself, ω²⟨u̇, M u̇⟩ = ⟨u, K u⟩ + ⟨u, f⟩ (⟨·,·⟩ the mean over the period,
//! f the contact forces on the structure); replacing f by the physical root's force at the
//! same motion, own(u), changes ω² by ⟨u, f − own(u)⟩ / ⟨u̇, M u̇⟩. Its half,
//!
//!   δ = |⟨u, f − own(u)⟩| / (2 (⟨u, K u⟩ + |⟨u, own(u)⟩|)),
//!
//! is the relative frequency error the contact forces carry to first order: of the order of
//! the harmonic truncation on the physical family, of the frequency shift due to contact on
//! the spurious one, and never large where contact barely matters (near grazing both
//! families, and this measure, are close).

use crate::nnm::error::Result;
use crate::nnm::model::contact_samples::shock_displacements;
use crate::nnm::model::law;
use crate::nnm::model::system::System;

/// δ of the module doc at `x` (scaled unknowns); 0 without shocks.
pub(in crate::nnm) fn frequency_defect(sys: &System, x: &[f64]) -> Result<f64> {
    if sys.shocks.is_empty() {
        return Ok(0.0);
    }
    let lay = sys.lay;
    let smp = sys.sampler();
    let ns = smp.n();
    let mut work_defect = 0.0;
    let mut work_law = 0.0;
    let mut ws = smp.scratch();
    let mut force = vec![0.0; ns];
    for sh in &sys.shocks {
        let u = shock_displacements(sys, sh, x);
        let own = law::own_from_u(sh.law, sh.gap, sh.alpha, sh.eta, &u)?;
        for &(c, v) in &sh.eqs.forces {
            let o = sh.offset + v * lay.n_coef_nonl;
            smp.synth_with(&x[o..o + lay.n_coef_nonl], lay.h_nonl, &mut force, &mut ws);
            for ((&f, &p), &uc) in force.iter().zip(&own[v]).zip(&u[c]) {
                work_defect += (f - p) * uc;
                work_law += p * uc;
            }
        }
    }
    let (work_defect, work_law) = (work_defect / ns as f64, work_law / ns as f64);
    let stiffness = mean_stiffness_work(sys, x);
    let scale = stiffness + work_law.abs();
    if scale > 0.0 {
        Ok(work_defect.abs() / (2.0 * scale))
    } else {
        Ok(0.0)
    }
}

/// ⟨u, K u⟩ by Parseval: the means multiply in full, each cosine and sine pair by ½.
fn mean_stiffness_work(sys: &System, x: &[f64]) -> f64 {
    let lay = sys.lay;
    let nl = lay.n_coef_lin;
    let mut sum = 0.0;
    for &(i, j, a) in &sys.k.entries {
        let (ui, uj) = (&x[lay.u(i)..lay.u(i) + nl], &x[lay.u(j)..lay.u(j) + nl]);
        let harmonics: f64 = ui[1..].iter().zip(&uj[1..]).map(|(p, q)| p * q).sum();
        sum += a * (ui[0] * uj[0] + 0.5 * harmonics);
    }
    sum
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::nnm::model::problem::ShockLaw;
    use crate::nnm::model::system::{Scaling, System};
    use crate::nnm::tests::{one_dof, settings};

    /// The wall of sdnd122 (k = 10, JEU = 0.01, RIGI_NOR = 50, PARA_REGUL 1e-12: the law's
    /// physical root is α·max(0, u − JEU) to 1e-5 of it) moved as u = A cos θ, A = 1.5 JEU,
    /// with every contact force zero, the family that ignores the stop. In scaled units
    /// (JEU = 1, k = 1, α = 5) the work of the law's force over the period is
    /// W = (αA/π)·(A(θc/2 + sin 2θc/4) − sin θc), θc = acos(1/A), and ⟨u, Ku⟩ = A²/2, so
    /// δ = W / (2(A²/2 + W)) exactly; the sampled measure agrees to the quadrature of the
    /// kink (the samples are N = fft_size(3·H_nl) points of the period).
    #[test]
    fn zero_forces_in_contact_carry_the_exact_frequency_defect() {
        let problem = one_dof(ShockLaw::Plan, 1e-12);
        let s = settings(3, 200, 1, 1);
        let sys = System::new(&problem, &s, Scaling::new(&problem, 1.0, 0).unwrap(), 0).unwrap();
        let (a, alpha) = (1.5, 5.0);
        let mut x = vec![0.0; sys.lay.n_unk];
        x[sys.lay.u(0) + 1] = a;
        let tc = (1.0f64 / a).acos();
        let w =
            alpha * a / std::f64::consts::PI * (a * (tc / 2.0 + (2.0 * tc).sin() / 4.0) - tc.sin());
        let exact = w / (2.0 * (a * a / 2.0 + w));
        let delta = frequency_defect(&sys, &x).unwrap();
        // δ = 0.177 here, matched to 3.5e-6 relative (measured): the kink of max(0, u − 1)
        // limits the sampled mean to O(1/N²), N = 1024 samples, and PARA_REGUL 1e-12
        // shifts the root by 1e-5·α·JEU near the kink only.
        assert!(
            (delta / exact - 1.0).abs() < 1e-4,
            "{delta} against {exact}"
        );

        // With the force of the law itself in place (its samples analysed back to H_nl
        // harmonics), what remains is the truncation's share in the harmonics of u, none
        // here (u has one harmonic): round-off (measured 2.9e-17).
        crate::nnm::model::contact_samples::init_contact(&sys, &mut x).unwrap();
        let physical = frequency_defect(&sys, &x).unwrap();
        assert!(physical < 1e-3 * exact, "{physical} against {exact}");
    }
}
