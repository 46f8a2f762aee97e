//! Start from a degenerate pair of linear modes in quadrature (aster-nl extension of
//! ETAT_INIT, keyword NUME_ORDRE_QUAD): the second mode a quarter period behind the first.
//! One real mode always gives a planar orbit; on an isotropic support (a node with equal
//! stiffness in two directions, an axisymmetric shaft) the pair in quadrature is a whirl,
//! the orbit that rolls around a CERCLE ring instead of crossing its centre.

use crate::nnm::continuation::start::{phase_dof, start, Guess};
use crate::nnm::error::{Error, Result, Setting};
use crate::nnm::model::contact_samples::init_contact;
use crate::nnm::model::system::{Scaling, System};
use crate::nnm::{model::fourier, Problem, Settings, StartState};
use faer::sparse::SparseColMat;

/// Largest relative difference between the two linear frequencies. A whirl is a periodic
/// orbit only if the pair is degenerate; an eigen-solver returns a truly degenerate pair
/// equal to ~1e-12, while a split above 1e-6 is a real (e.g. mesh-induced) anisotropy under
/// which the linear motion of the pair is not periodic and the start a poor guess.
pub const QUAD_FREQ_TOL: f64 = 1e-6;

/// xᵀ M y.
fn m_dot(m: &SparseColMat<usize, f64>, x: &[f64], y: &[f64]) -> f64 {
    let sym = m.symbolic();
    let (cp, ri, v) = (sym.col_ptr(), sym.row_idx(), m.val());
    (0..m.ncols())
        .map(|j| (cp[j]..cp[j + 1]).map(|p| x[ri[p]] * v[p]).sum::<f64>() * y[j])
        .sum()
}

/// The check of the pair's frequencies (Hz in the message), on its own for the glue and
/// its tests.
pub fn check_degenerate_pair(omega: f64, omega_quad: f64) -> Result<()> {
    // Two zero pulsations pass here: the start then refuses the zero pulsation itself.
    let scale = omega.abs().max(omega_quad.abs());
    let rel = if scale > 0.0 {
        (omega_quad - omega).abs() / scale
    } else {
        0.0
    };
    if rel.is_finite() && rel <= QUAD_FREQ_TOL {
        return Ok(());
    }
    let hz = |w: f64| w / (2.0 * std::f64::consts::PI);
    Err(Error::input(format!(
        "the mode in quadrature has frequency {:.9e} Hz and the first mode {:.9e} Hz \
         (relative difference {rel:.2e} > {QUAD_FREQ_TOL:.0e}): a whirl needs a degenerate pair",
        hz(omega_quad),
        hz(omega)
    ))
    .setting(Setting::StartQuadratureMode)
    .hint(
        "give in NUME_ORDRE_QUAD the other mode of the same frequency (isotropic or \
         axisymmetric support), or drop NUME_ORDRE_QUAD to start from one mode (planar orbit)",
    ))
}

/// Start from `mode` (on the cosine terms) and `quad` (on the sine terms), both linear modes
/// of the pulsations `omega_lin` and `omega_quad`, which must be equal within
/// [`QUAD_FREQ_TOL`]. `quad` is first made M-orthogonal to `mode` and given its modal mass
/// (so that an isotropic pair gives a circular whirl whatever basis the eigen-solver chose);
/// the combined motion is normalised to a largest DOF amplitude of 1 and scaled by
/// `coef_ampl` as in [`crate::nnm::start_from_mode`]. The time origin is then shifted so that the
/// reference DOF of the phase condition (chosen as for a restart) has a cosine term only.
pub fn start_from_mode_pair(
    problem: &Problem,
    settings: &Settings,
    mode: &[f64],
    quad: &[f64],
    coef_ampl: f64,
    omega_lin: f64,
    omega_quad: f64,
) -> Result<StartState> {
    let n = crate::nnm::check_start(
        problem,
        settings,
        &[
            (mode, Setting::StartMode),
            (quad, Setting::StartQuadratureMode),
        ],
        coef_ampl,
        omega_lin,
    )?;
    check_degenerate_pair(omega_lin, omega_quad)?;

    // Gram–Schmidt in the mass metric: both vectors stay in the (degenerate) eigenspace.
    let mm = m_dot(&problem.m, mode, mode);
    if !(mm.is_finite() && mm > 0.0) {
        return Err(Error::input(format!(
            "the linear mode has no positive modal mass (φᵀMφ = {mm:e})"
        ))
        .setting(Setting::StartMode));
    }
    let proj = m_dot(&problem.m, mode, quad) / mm;
    let q: Vec<f64> = quad.iter().zip(mode).map(|(b, a)| b - proj * a).collect();
    let qq = m_dot(&problem.m, &q, &q);
    // Relative to the mode's own modal mass: below this the two shapes are the same one.
    if !(qq.is_finite() && qq > 1e-12 * mm) {
        return Err(Error::input(
            "the mode in quadrature is collinear with the first mode: their combination is a planar orbit",
        )
        .setting(Setting::StartQuadratureMode)
        .hint("give the other mode of the degenerate pair"));
    }
    let qs = (mm / qq).sqrt();
    let s: Vec<f64> = q.iter().map(|v| v * qs).collect();

    // Shift the time origin: the reference DOF then has zero velocity at t = 0.
    let amps: Vec<f64> = mode.iter().zip(&s).map(|(c, s)| c.hypot(*s)).collect();
    let p = (0..n)
        .max_by(|&a, &b| amps[a].total_cmp(&amps[b]))
        .unwrap_or(0);
    let big = amps[p];
    let r = phase_dof(&amps);
    let theta = s[r].atan2(mode[r]);
    let (ct, st) = (theta.cos() / big, theta.sin() / big);
    let cos_terms: Vec<f64> = mode.iter().zip(&s).map(|(c, s)| c * ct + s * st).collect();
    let sin_terms: Vec<f64> = mode.iter().zip(&s).map(|(c, s)| s * ct - c * st).collect();

    let scaling = Scaling::new(problem, coef_ampl, p)?;
    let sys = System::new(problem, settings, scaling, r)?;
    let lay = sys.lay;
    // In units of the largest JEU; without one (no shocks, only cubic springs) in metres.
    let phys_per_coef = if problem.largest_gap().is_none() {
        1.0
    } else {
        scaling.length
    };
    let om = omega_lin / scaling.omega;
    let mut x = vec![0.0; lay.n_unk];
    for i in 0..n {
        let (uc, us) = (
            coef_ampl * cos_terms[i] * phys_per_coef / scaling.length,
            coef_ampl * sin_terms[i] * phys_per_coef / scaling.length,
        );
        // u = uc cos ωt + us sin ωt, so v = ω us cos ωt − ω uc sin ωt.
        x[lay.u(i) + fourier::ic(1)] = uc;
        x[lay.u(i) + fourier::is(lay.h_lin, 1)] = us;
        x[lay.v(i) + fourier::ic(1)] = om * us;
        x[lay.v(i) + fourier::is(lay.h_lin, 1)] = -om * uc;
    }
    x[lay.omega()] = om;
    init_contact(&sys, &mut x)?;
    start(
        sys,
        settings,
        x,
        crate::nnm::SolverKind::default(),
        Guess::LinearModes,
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::nnm::tests::{settings, sparse};
    use crate::nnm::{continue_branches, CercleForm, Shock, ShockLaw};

    /// Isotropic node (k in x and y, m = 1) in a centred ring of radius `g` (secant law).
    fn isotropic(k: f64, g: f64, alpha: f64, regul: f64) -> Problem {
        isotropic_with(k, g, alpha, regul, CercleForm::Secant)
    }

    fn isotropic_with(k: f64, g: f64, alpha: f64, regul: f64, form: CercleForm) -> Problem {
        Problem {
            forcing: None,
            k: sparse(2, &[(0, 0, k), (1, 1, k)]),
            m: sparse(2, &[(0, 0, 1.0), (1, 1, 1.0)]),
            shocks: vec![Shock {
                law: ShockLaw::Cercle {
                    origin: [0.0, 0.0],
                    form,
                },
                dofs: vec![0, 1],
                gap: g,
                stiffness: alpha,
                regul,
            }],
        }
    }

    use crate::nnm::model::exact::regularised_ring_force as ring_force;

    #[test]
    fn whirl_from_a_rotated_degenerate_pair_into_contact() {
        // The eigen-solver may return any basis of the degenerate pair: here rotated by 30°,
        // normalised to largest component 1, and the second one given twice the modal mass
        // (the start must rescale it). Started inside the ring (radius 0.9 JEU), the branch
        // must run into contact as a circular whirl: |u_x| = |u_y| (first harmonic, to 1e-6),
        // no higher harmonics, and ω² = (k + f(r)/r)/m, f the regularised ring force (exact
        // for a circular orbit: constant radius, constant force), within 1e-7 relative. Both
        // ring laws: 'SECANTE' (f: BI_PLAN's law at r, `ring_force`) and 'RAYON' (R5.07.01
        // eq. 12: f the root of f² − αf(r − g) − αη = 0, η = PARA_REGUL·k·g², written out
        // here by the quadratic formula).
        for form in [CercleForm::Secant, CercleForm::Radial] {
            whirl_into_contact(form);
        }
    }

    fn whirl_into_contact(form: CercleForm) {
        let (k, g, alpha, regul) = (10.0, 0.01, 50.0, 1e-4);
        let p = isotropic_with(k, g, alpha, regul, form);
        let mut s = settings(3, 20, 12, 1);
        s.continuation.prec_man = 1e-8;
        let b = 30f64.to_radians();
        let (c, sn) = (b.cos(), b.sin());
        let mode = [1.0, sn / c];
        let quad = [-2.0 * sn / c, 2.0];
        let st = start_from_mode_pair(&p, &s, &mode, &quad, 0.9, k.sqrt(), k.sqrt()).unwrap();
        // Inside the ring: the (nearly) linear whirl, radius 0.9 JEU to 1e-3 (the correction
        // keeps the projection on the motion fixed, not the radius; measured 2.8e-4).
        let hl = s.harmonics.h_lin;
        let nl = 2 * hl + 1;
        let x0 = &st.point.x;
        let r0 = x0[1].hypot(x0[1 + hl]);
        assert!((r0 / (0.9 * g) - 1.0).abs() < 1e-3, "{r0}");
        let out = continue_branches(&p, &s, st, &mut |_, _| {});
        assert!(out.error.is_none(), "{:?}", out.error);
        // ε = PARA_REGUL·k_ref, k_ref = k (diagonal stiffness).
        let eps = regul * k;
        let mut worst = 0.0f64;
        for q in &out.points {
            assert!(q.residual <= s.continuation.prec_newton, "{}", q.residual);
            let ax = q.x[1].hypot(q.x[1 + hl]);
            let ay = q.x[nl + 1].hypot(q.x[nl + 1 + hl]);
            assert!((ax / ay - 1.0).abs() < 1e-6, "{ax} {ay}");
            let higher: f64 = (2..=hl)
                .map(|h| q.x[h].hypot(q.x[hl + h]) + q.x[nl + h].hypot(q.x[nl + hl + h]))
                .sum();
            assert!(higher < 1e-9 * ax, "{higher}");
            let f = match form {
                CercleForm::Secant => ring_force(ax, g, alpha, eps),
                CercleForm::Radial => {
                    let (d, eta) = (ax - g, regul * k * g * g);
                    0.5 * (alpha * d + (alpha * alpha * d * d + 4.0 * alpha * eta).sqrt())
                }
            };
            let closed = (k + f / ax).sqrt();
            worst = worst.max((q.omega / closed - 1.0).abs());
        }
        let last = out.points.last().unwrap();
        let r_end = last.x[1].hypot(last.x[1 + hl]);
        println!("pair whirl {form:?}: worst rel ω error {worst:.2e}, end radius {r_end:.4e}");
        assert!(
            r_end > 1.1 * g,
            "the branch did not reach contact: r = {r_end}"
        );
        assert!(worst < 1e-7);
        assert!(out.points.windows(2).all(|w| w[1].energy > w[0].energy));
    }

    #[test]
    fn a_whirl_restarts_where_it_stopped() {
        // The start puts the time origin where a restart from a stored point puts it (same
        // reference DOF, zero velocity there): restarting from point 2 of a 4-branch run
        // must retrace points 3 and 4 (the series does not depend on the border; measured
        // 1.0e-14 relative in ω and energy, asserted 1e-10).
        let (k, g) = (10.0, 0.01);
        let p = isotropic(k, g, 50.0, 1e-4);
        let mut s = settings(3, 20, 4, 1);
        s.continuation.prec_man = 1e-8;
        let b = 30f64.to_radians();
        let mode = [b.cos(), b.sin()];
        let quad = [-b.sin(), b.cos()];
        let st = start_from_mode_pair(&p, &s, &mode, &quad, 1.05, k.sqrt(), k.sqrt()).unwrap();
        let whole = continue_branches(&p, &s, st, &mut |_, _| {});
        assert!(whole.error.is_none(), "{:?}", whole.error);
        let st = crate::nnm::start_from_point(&p, &s, &whole.points[1].x).unwrap();
        let mut s2 = s.clone();
        s2.continuation.n_branches = 2;
        let rest = continue_branches(&p, &s2, st, &mut |_, _| {});
        assert!(rest.error.is_none(), "{:?}", rest.error);
        assert_eq!(rest.points.len(), 2);
        let mut worst = 0.0f64;
        for (a, b) in whole.points[2..].iter().zip(&rest.points) {
            worst = worst.max((a.omega / b.omega - 1.0).abs());
            worst = worst.max((a.energy / b.energy - 1.0).abs());
            assert!(
                (a.omega / b.omega - 1.0).abs() < 1e-10,
                "{} {}",
                a.omega,
                b.omega
            );
            assert!(
                (a.energy / b.energy - 1.0).abs() < 1e-10,
                "{} {}",
                a.energy,
                b.energy
            );
        }
        println!("whirl restart: worst relative difference {worst:.2e}");
    }

    #[test]
    fn the_pair_must_be_degenerate_and_distinct() {
        let p = isotropic(10.0, 0.01, 50.0, 1e-4);
        let s = settings(3, 20, 1, 1);
        let w = 10f64.sqrt();
        // Frequencies 10 and 25 rad²/s²: error naming the keyword and both frequencies.
        let e = start_from_mode_pair(&p, &s, &[1.0, 0.0], &[0.0, 1.0], 0.9, w, 5.0).unwrap_err();
        assert_eq!(
            e.setting,
            Some(crate::nnm::error::Setting::StartQuadratureMode),
            "{e}"
        );
        assert!(e.message.contains("7.957747155e-1 Hz"), "{e}");
        assert!(e.message.contains("5.032921210e-1 Hz"), "{e}");
        assert!(e.hint.is_some());
        // Just outside the tolerance fails, just inside passes.
        assert!(check_degenerate_pair(w, w * (1.0 + 2.0 * QUAD_FREQ_TOL)).is_err());
        assert!(check_degenerate_pair(w, w * (1.0 + 0.5 * QUAD_FREQ_TOL)).is_ok());
        // The same shape twice is a planar orbit, refused.
        let e = start_from_mode_pair(&p, &s, &[1.0, 0.5], &[-2.0, -1.0], 0.9, w, w).unwrap_err();
        assert_eq!(
            e.setting,
            Some(crate::nnm::error::Setting::StartQuadratureMode),
            "{e}"
        );
        assert!(e.message.contains("collinear"), "{e}");
    }
}
