//! Floquet analysis tests: discrete closed forms on linear systems, the pointwise laws
//! against the engine's, Newmark against RK4 on sdnd122, and an orbit that loses stability.

use super::*;
use crate::nnm::{
    contact_coefficients, continue_branches, displacement_coefficients, start_from_mode,
    CercleForm, Point, Problem, Settings, Shock, ShockLaw,
};
use faer::sparse::{SparseColMat, Triplet};
use std::f64::consts::PI;

fn sparse(n: usize, e: &[(usize, usize, f64)]) -> SparseColMat<usize, f64> {
    let t: Vec<Triplet<usize, usize, f64>> =
        e.iter().map(|&(r, c, v)| Triplet::new(r, c, v)).collect();
    SparseColMat::try_new_from_triplets(n, n, &t).unwrap()
}

pub(super) fn settings(hl: usize, hn: usize, branches: usize) -> Settings {
    let mut s = crate::nnm::tests::settings(hl, hn, branches, 1);
    s.continuation.prec_man = 1e-10;
    s
}

/// The start point and the branch points that follow it.
pub(super) fn branch(
    problem: &Problem,
    s: &Settings,
    mode: &[f64],
    coef: f64,
    omega: f64,
) -> Vec<Point> {
    let st = start_from_mode(problem, s, mode, coef, omega).unwrap();
    let mut pts = vec![st.point.clone()];
    let out = continue_branches(problem, s, st, &mut |_, _| {});
    if let Some(e) = &out.error {
        panic!("run failed after {} points: {e}", out.points.len());
    }
    pts.extend(out.points);
    pts
}

pub(super) fn shock(law: ShockLaw, dofs: Vec<usize>) -> Shock {
    Shock {
        law,
        dofs,
        gap: 0.01,
        stiffness: 50.0,
        regul: 5e-5,
    }
}

/// sdnd122: m = 1, k = 10, stop at JEU = 0.01, RIGI_NOR = 50, PARA_REGUL = 5e-5.
fn sdnd122() -> Problem {
    Problem {
        forcing: None,
        k: sparse(1, &[(0, 0, 10.0)]),
        m: sparse(1, &[(0, 0, 1.0)]),
        shocks: vec![shock(ShockLaw::Plan, vec![0])],
    }
}

/// Two unit masses, each grounded by k = 10, coupled by `kc`.
pub(super) fn pair(kc: f64, shocks: Vec<Shock>) -> Problem {
    let k = 10.0;
    Problem {
        forcing: None,
        k: sparse(
            2,
            &[(0, 0, k + kc), (0, 1, -kc), (1, 0, -kc), (1, 1, k + kc)],
        ),
        m: sparse(2, &[(0, 0, 1.0), (1, 1, 1.0)]),
        shocks,
    }
}

/// Every expected multiplier has its own computed one within `tol`.
fn assert_multipliers(got: &[(f64, f64)], want: &[(f64, f64)], tol: f64, what: &str) {
    assert_eq!(got.len(), want.len(), "{what}");
    let mut left: Vec<(f64, f64)> = got.to_vec();
    for w in want {
        let (i, d) = left
            .iter()
            .enumerate()
            .map(|(i, g)| (i, (g.0 - w.0).hypot(g.1 - w.1)))
            .min_by(|a, b| a.1.total_cmp(&b.1))
            .unwrap();
        assert!(
            d < tol,
            "{what}: expected {w:?}, nearest at {d:e}; got {got:?}"
        );
        left.remove(i);
    }
}

fn cmul(a: (f64, f64), b: (f64, f64)) -> (f64, f64) {
    (a.0 * b.0 - a.1 * b.1, a.0 * b.1 + a.1 * b.0)
}

fn cpow(a: (f64, f64), n: usize) -> (f64, f64) {
    (0..n).fold((1.0, 0.0), |p, _| cmul(p, a))
}

/// One-step amplification of y' = λ y by each integrator, for z = λh: Newmark average
/// acceleration is the trapezoidal rule, (1 + z/2)/(1 − z/2); RK4 is Σ_{k≤4} z^k/k!.
fn amplification(integrator: Integrator, z: (f64, f64)) -> (f64, f64) {
    match integrator {
        Integrator::Newmark => {
            let (a, b) = ((1.0 + 0.5 * z.0, 0.5 * z.1), (1.0 - 0.5 * z.0, -0.5 * z.1));
            let d = b.0 * b.0 + b.1 * b.1;
            cmul(a, (b.0 / d, -b.1 / d))
        }
        Integrator::Rk4 => {
            let mut term = (1.0, 0.0);
            let mut sum = (1.0, 0.0);
            for k in 1..=4 {
                term = cmul(term, z);
                term = (term.0 / k as f64, term.1 / k as f64);
                sum = (sum.0 + term.0, sum.1 + term.1);
            }
            sum
        }
    }
}

/// The discrete monodromy multipliers of a linear system M Ü + K U = 0 whose M⁻¹K has
/// eigenvalues `lambda2` (ω² > 0: oscillating; < 0: diverging): for each, the first-order
/// eigenvalues ±√(−λ²) advanced by `n` steps of `h`.
fn discrete_multipliers(
    integrator: Integrator,
    lambda2: &[f64],
    h: f64,
    n: usize,
) -> Vec<(f64, f64)> {
    lambda2
        .iter()
        .flat_map(|&w2| {
            let l = if w2 >= 0.0 {
                (0.0, w2.sqrt())
            } else {
                ((-w2).sqrt(), 0.0)
            };
            [l, (-l.0, -l.1)]
        })
        .map(|l| cpow(amplification(integrator, (l.0 * h, l.1 * h)), n))
        .collect()
}

#[test]
fn linear_chain_gives_the_discrete_closed_form_multipliers_on_the_unit_circle() {
    // Grounded chain k = 10 / m = 1: M⁻¹K = [[20, −10], [−10, 10]], ω² = 10(3 ∓ √5)/2.
    let p = Problem {
        forcing: None,
        k: sparse(
            2,
            &[(0, 0, 20.0), (0, 1, -10.0), (1, 0, -10.0), (1, 1, 10.0)],
        ),
        m: sparse(2, &[(0, 0, 1.0), (1, 1, 1.0)]),
        shocks: vec![],
    };
    let w2 = [5.0 * (3.0 - 5f64.sqrt()), 5.0 * (3.0 + 5f64.sqrt())];
    let mode = [1.0, (20.0 - w2[0]) / 10.0];
    let s = settings(3, 3, 1);
    let st = start_from_mode(&p, &s, &mode, 1e-3, w2[0].sqrt()).unwrap();
    let x = &st.point.x;
    // The stored ω is the linear one: the period integrated over is exact.
    assert!((st.point.omega / w2[0].sqrt() - 1.0).abs() < 1e-10);
    let n = 400;
    let t = 2.0 * PI / st.point.omega;
    for integ in [Integrator::Newmark, Integrator::Rk4] {
        let f = floquet(&p, &s, x, n, integ, 1e-2).unwrap();
        // The discrete schemes have closed-form multipliers: only round-off (~1e-13 per
        // step over 400 steps) separates them from the computed ones.
        let want = discrete_multipliers(integ, &w2, t / n as f64, n);
        assert_multipliers(&f.multipliers, &want, 1e-10, &format!("{integ:?}"));
        // And the schemes approach the exact e^{±iω_j T}: phase error ≤ ω_j T (ω_j h)²/12
        // (trapezoidal; RK4's is far smaller), here ≤ 4e-3.
        let exact: Vec<(f64, f64)> = w2
            .iter()
            .flat_map(|&w| {
                let a = w.sqrt() * t;
                [(a.cos(), a.sin()), (a.cos(), -a.sin())]
            })
            .collect();
        assert_multipliers(&f.multipliers, &exact, 4e-3, &format!("{integ:?} vs exact"));
        // |μ| = 1 up to round-off for the trapezoidal rule, 1 − O((ωh)⁶ N) for RK4.
        assert!(
            f.stable && (f.max_modulus - 1.0).abs() < 1e-9,
            "{integ:?}: {f:?}"
        );
        // The trivial pair is the mode's own pair, at +1 up to the phase error.
        assert!(f.trivial_distance < 1e-3 && f.orbit_defect < 1e-3, "{f:?}");
    }
}

#[test]
fn a_negative_stiffness_mode_gives_a_real_multiplier_above_one() {
    // M⁻¹K = [[1, 2], [2, 1]]: ω² = 3 (mode [1, 1]) and −1 (mode [1, −1], diverging as
    // e^{t}); over any period T the exact multipliers include e^{±T}. No shock: the orbit
    // only sets T, so it is built directly.
    let p = Problem {
        forcing: None,
        k: sparse(2, &[(0, 0, 1.0), (0, 1, 2.0), (1, 0, 2.0), (1, 1, 1.0)]),
        m: sparse(2, &[(0, 0, 1.0), (1, 1, 1.0)]),
        shocks: vec![],
    };
    let omega = 3f64.sqrt();
    let h = 2;
    let coefs = vec![vec![0.0, 1e-3, 0.0, 0.0, 0.0]; 2];
    let lin = Linearised::new(&p, Orbit::new(coefs, h, omega).unwrap()).unwrap();
    let t = lin.orbit.period();
    let n = 500;
    for integ in [Integrator::Newmark, Integrator::Rk4] {
        let phi = monodromy(&lin, n, integ).unwrap();
        let f = analyse(&lin, &phi, 1e-2).unwrap();
        let want = discrete_multipliers(integ, &[3.0, -1.0], t / n as f64, n);
        // Relative round-off on a multiplier of e^{3.6} ≈ 38.
        assert_multipliers(&f.multipliers, &want, 1e-9 * 38.0, &format!("{integ:?}"));
        // Exact e^{T} within the schemes' error, (σh)² T/12 relative for the trapezoidal rule.
        assert!(
            (f.max_modulus / t.exp() - 1.0).abs() < 1e-4,
            "{integ:?}: {} vs {}",
            f.max_modulus,
            t.exp()
        );
        assert!(!f.stable && (f.max_nontrivial_modulus - f.max_modulus).abs() < 1e-12);
    }
}

#[test]
fn eta_phys_and_the_laws_match_the_engine_scaled_laws() {
    // k_ref = 1/(K⁻¹)pp at the stop's DOF: K = [[11, −1], [−1, 11]] gives 120/11 (not
    // K_pp = 11), so η_phys = PARA_REGUL·(120/11)·JEU².
    use crate::nnm::model::law::own_from_u;
    use crate::nnm::model::system::Scaling;
    for law in [ShockLaw::Plan, ShockLaw::BiPlan] {
        let p = pair(1.0, vec![shock(law, vec![1])]);
        let eta = eta_phys(&p).unwrap()[0];
        assert!((eta / (5e-5 * 120.0 / 11.0 * 1e-4) - 1.0).abs() < 1e-14);
        let scaling = Scaling::new(&p, 1.0, 0).unwrap();
        let pl = PointLaw {
            law,
            alpha: 50.0,
            gap: 0.01,
            eta,
        };
        let us: Vec<f64> = (0..41).map(|i| -0.03 + 0.0015 * i as f64).collect();
        let scaled = law.scaled(scaling.length);
        let u_s: Vec<f64> = us.iter().map(|u| u / scaling.length).collect();
        let own = own_from_u(
            scaled,
            0.01 / scaling.length,
            50.0 / scaling.stiffness,
            5e-5,
            &[u_s],
        )
        .unwrap();
        for (u, f_s) in us.iter().zip(&own[0]) {
            let f_engine = f_s * scaling.stiffness * scaling.length;
            let f = pl.eval(&[*u]).unwrap().0[0];
            // Two closed forms of the same root (bisection to 1e-15 for BI_PLAN).
            assert!(
                (f - f_engine).abs() <= 1e-12 * f_engine.abs().max(1e-12),
                "{law:?} u {u}: {f:e} vs {f_engine:e}"
            );
        }
    }
}

#[test]
fn pointwise_laws_reproduce_the_engine_contact_forces_in_time() {
    // The engine's own force series, evaluated in time along a branch point in contact, must
    // match the law applied to the engine's displacement series: same sign convention,
    // units, series layout and ω. Tolerance 5e-3 of the peak force: the force series is
    // truncated at H_nl = 100 harmonics around contact onsets smoothed over ~√(η/α) ≈ 3e-5 m
    // (measured 0.8e-3 to 2.1e-3). A sign or unit error gives O(1).
    let cases = [
        (ShockLaw::Plan, vec![1]),
        (ShockLaw::BiPlan, vec![1]),
        (
            ShockLaw::Cercle {
                origin: [0.001, 0.001],
                form: CercleForm::Secant,
            },
            vec![0, 1],
        ),
        (
            ShockLaw::Cercle {
                origin: [0.001, 0.001],
                form: CercleForm::Radial,
            },
            vec![0, 1],
        ),
    ];
    for (law, dofs) in cases {
        let p = pair(1.0, vec![shock(law, dofs.clone())]);
        let s = settings(5, 100, 25);
        let pts = branch(&p, &s, &[1.0, -1.0], 0.5, 12f64.sqrt());
        let last = pts.last().unwrap();
        let x = &last.x;
        let coefs = displacement_coefficients(&p, &s, x).unwrap();
        let lin = Linearised::new(
            &p,
            Orbit::new(coefs, s.harmonics.h_lin, last.omega).unwrap(),
        )
        .unwrap();
        let cc = contact_coefficients(&p, &s, x).unwrap();
        // Engine force series per component: PLAN/BI_PLAN f; CERCLE fx, fy (unknowns 0, 1).
        let series_idx: Vec<usize> = if dofs.len() == 2 { vec![0, 1] } else { vec![0] };
        let t_end = lin.orbit.period();
        let (mut peak, mut worst) = (0.0f64, 0.0f64);
        for j in 0..64 {
            let t = t_end * j as f64 / 64.0;
            let f_law = lin.forces(t).unwrap().remove(0);
            for (c, &v) in series_idx.iter().enumerate() {
                let f_eng = fourier::eval(&cc[0][v], s.harmonics.h_nonl, last.omega * t);
                peak = peak.max(f_eng.abs());
                worst = worst.max((f_law[c] - f_eng).abs());
            }
        }
        // In contact: the peak force is many times α·(regularisation width).
        assert!(
            peak > 0.05,
            "{law:?}: the orbit must reach the stop (peak force {peak:e})"
        );
        assert!(
            worst < 5e-3 * peak,
            "{law:?}: law vs engine {worst:e} (peak {peak:e})"
        );
    }
}

#[test]
fn law_jacobians_are_the_derivatives_of_the_forces() {
    // Centred differences with step 1e-8·JEU: truncation ~(1e-8)² relative plus round-off
    // ~1e-16/1e-8: 1e-5 relative (to the largest entry) covers both with a wide margin.
    let (g, alpha, eta) = (0.01, 50.0, 5e-5 * 10.0 * 1e-4);
    let laws = [
        PointLaw {
            law: ShockLaw::Plan,
            alpha,
            gap: g,
            eta,
        },
        PointLaw {
            law: ShockLaw::BiPlan,
            alpha,
            gap: g,
            eta,
        },
        PointLaw {
            law: ShockLaw::Cercle {
                origin: [0.001, -0.002],
                form: CercleForm::Secant,
            },
            alpha,
            gap: g,
            eta,
        },
    ];
    let samples = [
        -0.02, -0.0101, -0.005, 0.0, 0.003, 0.0099, 0.01, 0.0101, 0.013, 0.03,
    ];
    for law in laws {
        let nc = law.n_comp();
        for (i, &a) in samples.iter().enumerate() {
            let b = samples[(i * 7 + 3) % samples.len()];
            let u: Vec<f64> = [a, b][..nc].to_vec();
            let (_, j) = law.eval(&u).unwrap();
            let scale = j.iter().fold(1e-12f64, |m, v| m.max(v.abs()));
            for c in 0..nc {
                let d = 1e-8 * g;
                let mut up = u.clone();
                up[c] += d;
                let mut um = u.clone();
                um[c] -= d;
                let (fp, _) = law.eval(&up).unwrap();
                let (fm, _) = law.eval(&um).unwrap();
                for r in 0..nc {
                    let fd = (fp[r] - fm[r]) / (2.0 * d);
                    assert!(
                        (fd - j[r * nc + c]).abs() < 1e-5 * scale,
                        "{:?} at {u:?}: ∂F{r}/∂u{c} {} vs fd {fd}",
                        law.law,
                        j[r * nc + c]
                    );
                }
            }
        }
    }
    // CERCLE through its centre (origin (0.001, −0.002)): no force at the centre and the
    // Jacobian ε·I there (ε = η/JEU², BI_PLAN's slope at 0), continuous with the Jacobian
    // an instant away in any direction (r = 1e-9·JEU: φ/r and φ' differ from ε at order
    // (r/JEU)², so to round-off; 1e-9 relative covers it).
    let ring = laws[2];
    let eps = eta / (g * g);
    let (f, j) = ring.eval(&[0.001, -0.002]).unwrap();
    assert_eq!(f, vec![0.0, 0.0]);
    assert_eq!(j, vec![eps, 0.0, 0.0, eps]);
    for theta in [0.0f64, 1.0, 2.5, 4.0] {
        let r = 1e-9 * g;
        let u = [0.001 + r * theta.cos(), -0.002 + r * theta.sin()];
        let (f, jn) = ring.eval(&u).unwrap();
        assert!((f[0] - eps * (u[0] - 0.001)).abs() < 1e-9 * eps * r);
        for (a, b) in jn.iter().zip(&j) {
            assert!((a - b).abs() < 1e-9 * eps, "{jn:?} vs {j:?}");
        }
    }
}

#[test]
fn sdnd122_is_stable_and_newmark_converges_to_rk4_at_second_order() {
    let p = sdnd122();
    let s = settings(5, 50, 12);
    let pts = branch(&p, &s, &[1.0], 1.0, 10f64.sqrt());
    for q in pts.iter().step_by(3) {
        let coefs = displacement_coefficients(&p, &s, &q.x).unwrap();
        let lin =
            Linearised::new(&p, Orbit::new(coefs, s.harmonics.h_lin, q.omega).unwrap()).unwrap();
        // RK4 with 2000 steps is the reference: its own error, measured against 16000
        // steps, is below 3e-10 (fourth order), far under Newmark's.
        let reference = monodromy(&lin, 2000, Integrator::Rk4).unwrap();
        // Liouville: tr A = 0, so det Φ = 1 (RK4 error ~1e-12 here).
        let det = reference[(0, 0)] * reference[(1, 1)] - reference[(0, 1)] * reference[(1, 0)];
        assert!((det - 1.0).abs() < 1e-9, "E {:e}: det Φ {det}", q.energy);
        let diffs: Vec<f64> = [500, 1000, 2000]
            .iter()
            .map(|&nb| {
                rel_diff(
                    &monodromy(&lin, nb, Integrator::Newmark).unwrap(),
                    &reference,
                )
            })
            .collect();
        // Second order: ×4 per halving of the step (measured 3.9–4.0); 3 leaves room for
        // the contact onsets, resolved only from ~500 steps per period.
        assert!(
            diffs[0] > 3.0 * diffs[1] && diffs[1] > 3.0 * diffs[2],
            "E {:e}: {diffs:?}",
            q.energy
        );
        // At NB_INST = 1000 the two agree to 6e-5 (measured 3e-5 to 6e-5).
        assert!(diffs[1] < 1e-4, "E {:e}: {diffs:?}", q.energy);
        for integ in [Integrator::Newmark, Integrator::Rk4] {
            let f = floquet(&p, &s, &q.x, 1000, integ, 1e-2).unwrap();
            // One DOF: only the trivial pair, hence STABLE by definition; with det Φ = 1 and
            // tr Φ ≤ 2 it lies on the unit circle (|μ| = 1 to 2e-3, the Jordan block's √ of
            // Newmark's 3e-5 error on Φ), at the distance from +1 set by the H_l = 5 orbit.
            assert!(f.label() == "STABLE" && f.multipliers.len() == 2, "{f:?}");
            assert!(
                (f.max_modulus - 1.0).abs() < 5e-3,
                "E {:e} {integ:?}: {f:?}",
                q.energy
            );
        }
    }
}

fn rel_diff(a: &Mat<f64>, b: &Mat<f64>) -> f64 {
    let mut num = 0.0f64;
    let mut den = 0.0f64;
    for j in 0..a.ncols() {
        for i in 0..a.nrows() {
            num = num.max((a[(i, j)] - b[(i, j)]).abs());
            den = den.max(b[(i, j)].abs());
        }
    }
    num / den
}

#[test]
fn anti_phase_mode_is_unstable_between_its_energy_extrema_and_in_phase_mode_is_stable() {
    // Two unit masses grounded by k = 10, coupled by kc = 1, a stop on mass 2. For a family
    // of periodic orbits of a conservative system a nontrivial pair of multipliers passes
    // through +1 exactly where the energy along the family has an extremum (a fold of the
    // energy–frequency curve). The anti-phase NNM stiffens, its energy peaks, falls and rises
    // again: it must be unstable between the maximum and the minimum and stable elsewhere.
    // A fold is a regular point of the continuation: neither bifurcation test flags it, so
    // the energy extrema are the reference. Boundaries are checked to one branch point.
    let p = pair(1.0, vec![shock(ShockLaw::Plan, vec![1])]);
    let s = settings(10, 100, 25);
    let pts = branch(&p, &s, &[1.0, -1.0], 0.5, 12f64.sqrt());
    assert!(pts.iter().all(|q| !q.bifurcation));
    let e: Vec<f64> = pts.iter().map(|q| q.energy).collect();
    let imax = (1..e.len() - 1)
        .find(|&i| e[i] > e[i - 1] && e[i] >= e[i + 1])
        .expect("an energy maximum");
    let imin = (imax + 1..e.len() - 1)
        .find(|&i| e[i] < e[i - 1] && e[i] <= e[i + 1])
        .expect("an energy minimum");
    let verdicts: Vec<Floquet> = pts
        .iter()
        .map(|q| floquet(&p, &s, &q.x, 1000, Integrator::Rk4, 1e-2).unwrap())
        .collect();
    let unstable: Vec<usize> = (0..pts.len()).filter(|&i| !verdicts[i].stable).collect();
    let (a, b) = (unstable[0], unstable[unstable.len() - 1]);
    assert_eq!(
        unstable.len(),
        b - a + 1,
        "one unstable stretch: {unstable:?}"
    );
    assert!(
        a.abs_diff(imax) <= 1 && b.abs_diff(imin) <= 1,
        "unstable {a}..={b}, energy max {imax}, min {imin}"
    );
    // Far beyond TOLERANCE and beyond the trivial pair's own error (≤ 0.12 here).
    let worst = verdicts
        .iter()
        .map(|f| f.max_nontrivial_modulus)
        .fold(0.0, f64::max);
    assert!(worst > 1.4, "largest multiplier {worst}");
    assert_eq!(verdicts[a].label(), "INSTABLE");
    for (i, f) in verdicts.iter().enumerate() {
        if i + 1 < a || i > b + 1 {
            // Stable rows: every eigenvalue of Φ on the unit circle (RK4 error ~1e-8); the
            // nontrivial pair taken out of Φ by the reduction (reduce.rs) carries the orbit's
            // own error, first order in its defect (measured 1.2e-4 at a defect of 1e-3).
            assert!((f.max_modulus - 1.0).abs() < 1e-4, "row {i}: {f:?}");
            assert!(
                (f.max_nontrivial_modulus - 1.0).abs() < f.orbit_defect.max(1e-6),
                "row {i}: {f:?}"
            );
            // Newmark agrees away from the boundaries.
            assert!(
                floquet(&p, &s, &pts[i].x, 1000, Integrator::Newmark, 1e-2)
                    .unwrap()
                    .stable
            );
        } else if i > a && i < b {
            assert!(
                !floquet(&p, &s, &pts[i].x, 1000, Integrator::Newmark, 1e-2)
                    .unwrap()
                    .stable,
                "row {i}"
            );
        }
    }
    // The in-phase NNM of the same system stays stable over the same energy range.
    let s = settings(10, 100, 12);
    for q in branch(&p, &s, &[1.0, 1.0], 0.5, 10f64.sqrt()) {
        let f = floquet(&p, &s, &q.x, 1000, Integrator::Rk4, 1e-2).unwrap();
        // Every eigenvalue of Φ on the circle to 1e-4; the reduced pair to the orbit defect.
        assert!(
            f.stable
                && (f.max_modulus - 1.0).abs() < 1e-4
                && (f.max_nontrivial_modulus - 1.0).abs() < f.orbit_defect,
            "E {:e}: {f:?}",
            q.energy
        );
    }
}

#[test]
fn symmetric_pair_pitchfork_is_flagged_where_stability_switches() {
    // The same pair with the same stop on BOTH masses is symmetric under their exchange:
    // its anti-phase NNM meets a pitchfork (two localised modes branch off) and is unstable
    // beyond it. The determinant test of the continuation must flag the first branch end
    // past the pitchfork, and the Floquet multipliers (RK4, 1000 steps: error ~1e-8 on a
    // stable orbit) must leave the unit circle exactly there: every earlier row on the
    // circle to 1e-4, the flagged row and every later one off it by more than TOLERANCE.
    let p = pair(
        1.0,
        vec![
            shock(ShockLaw::Plan, vec![0]),
            shock(ShockLaw::Plan, vec![1]),
        ],
    );
    let s = settings(10, 100, 40);
    let pts = branch(&p, &s, &[1.0, -1.0], 0.9, 12f64.sqrt());
    let flagged: Vec<usize> = (0..pts.len()).filter(|&i| pts[i].bifurcation).collect();
    assert_eq!(flagged.len(), 1, "one flagged row: {flagged:?}");
    let f = flagged[0];
    assert!(
        f > 2 && f + 5 < pts.len(),
        "flag at row {f} of {}",
        pts.len()
    );
    let moduli: Vec<f64> = pts
        .iter()
        .map(|q| {
            floquet(&p, &s, &q.x, 1000, Integrator::Rk4, 1e-2)
                .unwrap()
                .max_nontrivial_modulus
        })
        .collect();
    for (i, m) in moduli.iter().enumerate() {
        if i < f {
            assert!((m - 1.0).abs() < 1e-4, "row {i} before the flag: |mu| {m}");
        } else {
            assert!(*m > 1.0 + 1e-2, "row {i} from the flag on: |mu| {m}");
        }
    }
}

#[test]
fn bad_input_gives_keyword_errors() {
    let p = sdnd122();
    let s = settings(5, 50, 1);
    let st = start_from_mode(&p, &s, &[1.0], 1.0, 10f64.sqrt()).unwrap();
    let x = &st.point.x;
    let kw = |r: Result<Floquet>| r.unwrap_err().setting;
    assert_eq!(
        kw(floquet(&p, &s, x, 0, Integrator::Newmark, 1e-2)),
        Some(crate::nnm::error::Setting::StabilityInstants)
    );
    assert_eq!(
        kw(floquet(&p, &s, x, 100, Integrator::Newmark, -1.0)),
        Some(crate::nnm::error::Setting::StabilityTolerance)
    );
    assert!(floquet(&p, &s, &x[1..], 100, Integrator::Rk4, 1e-2).is_err());
    // A DOF without mass: M is not positive definite, refused rather than inverted.
    let massless = Problem {
        forcing: None,
        m: sparse(2, &[(0, 0, 1.0)]),
        ..pair(1.0, vec![])
    };
    let coefs = vec![vec![0.0, 0.02, 0.0, 0.0, 0.0]; 2];
    let lin = Linearised::new(&massless, Orbit::new(coefs, 2, 3.0).unwrap()).unwrap();
    let err = monodromy(&lin, 100, Integrator::Newmark).unwrap_err();
    assert_eq!(err.setting, Some(crate::nnm::error::Setting::StabilityRows));
}

#[test]
fn trivial_pair_approaches_one_as_the_orbit_harmonics_grow() {
    // The trivial pair is exact only on an exact orbit: its distance to +1 and the orbit
    // defect measure the truncation of U(t) at NB_HARM_LINE. On sdnd122 at E ≈ 5.9e-4 J
    // (measured distance 0.13, 0.030, 0.0088 and defect 9e-3, 5e-4, 4e-5 for H_l = 5, 10,
    // 20) both must at least halve at each refinement.
    let p = sdnd122();
    let mut last = (f64::INFINITY, f64::INFINITY);
    for hl in [5, 10, 20] {
        let s = settings(hl, 100, 10);
        let q = branch(&p, &s, &[1.0], 1.0, 10f64.sqrt()).pop().unwrap();
        let f = floquet(&p, &s, &q.x, 2000, Integrator::Rk4, 1e-2).unwrap();
        assert!(
            f.trivial_distance < 0.5 * last.0 && f.orbit_defect < 0.5 * last.1,
            "H_l {hl}: {f:?} after {last:?}"
        );
        last = (f.trivial_distance, f.orbit_defect);
    }
}
