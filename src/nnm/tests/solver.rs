//! The structured solver against the whole tangent factorised as one matrix (dense
//! references): solutions of the true bordered system, determinant signs.

use crate::nnm::model::contact_samples::init_contact;
use crate::nnm::model::fourier;
use crate::nnm::model::system::{Scaling, System};
use crate::nnm::solve::condensed_det;
use crate::nnm::solve::contact::Method;
use crate::nnm::solve::linear_solver::{ReferenceSolver, StructuredSolver, TangentSolver};
use crate::nnm::tests::{settings, sparse};
use crate::nnm::*;
use faer::prelude::Solve;
use faer::Mat;

/// Deterministic pseudo-random numbers in [−1, 1).
struct Lcg(u64);
impl Lcg {
    fn next(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        ((self.0 >> 11) as f64 / (1u64 << 53) as f64) * 2.0 - 1.0
    }
}

/// Four DOFs (a chain, DOF 3 without mass: a static condensation row) with one shock of
/// each law, two of them on the same DOF, and the CERCLE ring off-centre.
fn problem() -> Problem {
    let mut k = Vec::new();
    for i in 0..4 {
        k.push((i, i, 20.0));
        if i + 1 < 4 {
            k.push((i, i + 1, -10.0));
            k.push((i + 1, i, -10.0));
        }
    }
    Problem {
        forcing: None,
        k: sparse(4, &k),
        m: sparse(
            4,
            &[
                (0, 0, 1.0),
                (1, 1, 2.0),
                (2, 2, 1.5),
                (0, 1, 0.1),
                (1, 0, 0.1),
            ],
        ),
        shocks: vec![
            Shock {
                law: ShockLaw::Plan,
                dofs: vec![0],
                gap: 0.01,
                stiffness: 50.0,
                regul: 1e-3,
            },
            Shock {
                law: ShockLaw::BiPlan,
                dofs: vec![1],
                gap: 0.008,
                stiffness: 80.0,
                regul: 1e-3,
            },
            Shock {
                law: ShockLaw::Cercle {
                    origin: [0.002, -0.001],
                    form: CercleForm::Secant,
                },
                dofs: vec![1, 2],
                gap: 0.01,
                stiffness: 50.0,
                regul: 1e-3,
            },
        ],
    }
}

/// A point whose contact unknowns follow their laws (the physical roots, where the
/// pointwise Jacobians are invertible), with motion in every harmonic.
fn point(sys: &System, rng: &mut Lcg) -> Vec<f64> {
    let lay = sys.lay;
    let mut x = vec![0.0; lay.n_unk];
    for i in 0..lay.n {
        for j in 0..lay.n_coef_lin {
            let a = if j == fourier::ic(1) { 1.2 } else { 0.15 };
            x[lay.u(i) + j] = a * rng.next();
            x[lay.v(i) + j] = a * rng.next();
        }
    }
    x[lay.omega()] = 1.1;
    x[lay.gamma()] = 0.03;
    init_contact(sys, &mut x).unwrap();
    x
}

fn dense_full(sys: &System, x: &[f64], t: &[f64]) -> Mat<f64> {
    let n = sys.lay.n_unk;
    let mut a = Mat::<f64>::zeros(n, n);
    for tr in sys.tangent(x, t) {
        a[(tr.row, tr.col)] += tr.val;
    }
    a
}

fn max_rel(a: &[f64], b: &[f64]) -> f64 {
    let scale = b.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max)
        / scale
}

fn solvers(sys: &System) -> Vec<(Method, StructuredSolver)> {
    [Method::Dense, Method::Krylov, Method::Toeplitz]
        .into_iter()
        .map(|m| (m, StructuredSolver::new(sys, 24, Some(m)).unwrap()))
        .collect()
}

/// Solutions of [R_X; tᵀ] z = (r, ρ) for random r, ρ, t at random points equal the whole
/// tangent's sparse LU to 1e-11 relative (both direct or converged to 1e-14: what remains is
/// the conditioning of the bordered tangent times round-off), on both contact routes.
#[test]
fn structured_solves_equal_the_whole_tangents() {
    let p = problem();
    for (hl, hn) in [(2, 12), (3, 40)] {
        let s = settings(hl, hn, 1, 1);
        let sys = System::new(&p, &s, Scaling::new(&p, 1.0, 0).unwrap(), 0).unwrap();
        let n = sys.lay.n_unk;
        let mut rng = Lcg(7 + hn as u64);
        let mut reference = ReferenceSolver::default();
        let mut ours = solvers(&sys);
        for _ in 0..3 {
            let x = point(&sys, &mut rng);
            let t: Vec<f64> = (0..n).map(|_| rng.next()).collect();
            reference.factor(&sys, &x, &t).unwrap();
            for (_, s) in ours.iter_mut() {
                s.factor(&sys, &x, &t).unwrap();
            }
            for _ in 0..2 {
                let r: Vec<f64> = (0..n).map(|_| rng.next()).collect();
                let mut want = r.clone();
                reference.solve(&sys, &mut want).unwrap();
                // The residual of the dense system checks the reference itself.
                let a = dense_full(&sys, &x, &t);
                let mut ar = vec![0.0; n];
                for i in 0..n {
                    ar[i] = (0..n).map(|j| a[(i, j)] * want[j]).sum();
                }
                assert!(max_rel(&ar, &r) < 1e-10);
                for (m, s) in ours.iter_mut() {
                    let mut got = r.clone();
                    s.solve(&sys, &mut got).unwrap();
                    let e = max_rel(&got, &want);
                    assert!(e < 1e-11, "H {hl}/{hn} {m:?}: relative difference {e:e}");
                }
            }
        }
    }
}

/// The determinant sign of the structured solver differs from the whole tangent's (the
/// dense LU of J = [R_X; tᵀ] times the dense LUs of the contact blocks A_ff) and from the
/// reference test's (a minor of J⁻¹) by a factor fixed for the problem: at random points,
/// where those signs vary, the ratios stay constant.
#[test]
fn determinant_signs_change_together_with_the_dense_references() {
    let p = problem();
    let s = settings(2, 16, 1, 1);
    let sys = System::new(&p, &s, Scaling::new(&p, 1.0, 0).unwrap(), 0).unwrap();
    let n = sys.lay.n_unk;
    let mut rng = Lcg(99);
    let mut reference = ReferenceSolver::default();
    let mut ours = solvers(&sys);
    let mut ratios: Vec<(f64, f64, f64)> = Vec::new();
    let mut seen = (false, false);
    for _ in 0..12 {
        let x = point(&sys, &mut rng);
        let t: Vec<f64> = (0..n).map(|_| rng.next()).collect();
        let a = dense_full(&sys, &x, &t);
        let mut full = condensed_det::dense_det_sign(&a).unwrap();
        // Π sign det A_ff from the dense tangent's law blocks.
        for sh in &sys.shocks {
            let d = sh.eqs.n_own * sys.lay.n_coef_nonl;
            let blk = Mat::from_fn(d, d, |i, j| a[(sh.offset + i, sh.offset + j)]);
            full *= condensed_det::dense_det_sign(&blk).unwrap();
        }
        reference.factor(&sys, &x, &t).unwrap();
        let minor = reference.det_sign(&sys).unwrap();
        let mut got = Vec::new();
        for (_, s) in ours.iter_mut() {
            s.factor(&sys, &x, &t).unwrap();
            got.push(s.det_sign(&sys).unwrap());
        }
        assert_eq!(got[0], got[1], "the two contact routes give the same sign");
        ratios.push((got[0] * full, got[0] * minor, full));
        if full > 0.0 {
            seen.0 = true;
        } else {
            seen.1 = true;
        }
    }
    assert!(seen.0 && seen.1, "the sample must exercise both signs");
    assert!(
        ratios
            .windows(2)
            .all(|w| w[0].0 == w[1].0 && w[0].1 == w[1].1),
        "{ratios:?}"
    );
}

/// Whole runs: the structured solver (each route) and the reference give the same points
/// to 1e-10, and flag the same rows.
#[test]
fn runs_with_the_structured_solver_equal_the_reference_runs() {
    let p = problem();
    let mut s = settings(3, 30, 3, 2);
    s.continuation.prec_man = 1e-8;
    // The lowest linear mode by inverse iteration x ← K⁻¹ M x (M is singular: DOF 3 has
    // no mass; the iteration does not mind).
    let kd = p.k.to_dense();
    let md = p.m.to_dense();
    let lu = kd.partial_piv_lu();
    let mut mode = Mat::<f64>::from_fn(4, 1, |_, _| 1.0);
    for _ in 0..200 {
        mode = lu.solve(&md * &mode);
        let big = (0..4).map(|i| mode[(i, 0)].abs()).fold(0.0, f64::max);
        mode *= faer::Scale(1.0 / big);
    }
    let kx = &kd * &mode;
    let mx = &md * &mode;
    let omega = ((0..4).map(|i| mode[(i, 0)] * kx[(i, 0)]).sum::<f64>()
        / (0..4).map(|i| mode[(i, 0)] * mx[(i, 0)]).sum::<f64>())
    .sqrt();
    let mode: Vec<f64> = (0..4).map(|i| mode[(i, 0)]).collect();
    let run = |kind: SolverKind| {
        let st = start_from_mode_using(&p, &s, &mode, 0.5, omega, kind).unwrap();
        let out = continue_branches(&p, &s, st, &mut |_, _| {});
        assert!(out.error.is_none(), "{kind:?}: {:?}", out.error);
        out.points
    };
    let want = run(SolverKind::Reference);
    let (f0, f1) = (want[0].frequency, want[want.len() - 1].frequency);
    // The stops are reached: the frequency rises (by 1 % over these branches).
    assert!(f1 / f0 - 1.0 > 5e-3, "{f0} .. {f1}");
    for kind in [
        SolverKind::Structured,
        SolverKind::StructuredWith(Method::Dense),
        SolverKind::StructuredWith(Method::Krylov),
    ] {
        let got = run(kind);
        assert_eq!(got.len(), want.len());
        for (g, w) in got.iter().zip(&want) {
            assert!((g.frequency / w.frequency - 1.0).abs() < 1e-10, "{kind:?}");
            assert!((g.energy / w.energy - 1.0).abs() < 1e-10, "{kind:?}");
            assert!(
                max_rel(&g.x, &w.x) < 1e-10,
                "{kind:?}: {:e}",
                max_rel(&g.x, &w.x)
            );
            assert_eq!(g.bifurcation, w.bifurcation);
        }
    }
}
