//! Floquet analysis of forced, damped points (`forced.rs`): the linear damped oscillator's
//! multipliers in closed form, the one-DOF wall's curve (unstable between its two folds,
//! stable outside), and the verdict against the growth of a perturbation of the true
//! periodic orbit integrated in time here (RK4 of the nonlinear ODE, not the engine).

use super::*;
use crate::nnm::tests::forced::{
    curve, forced, period, plan, plan_force, shooting_state, C, F, K, M,
};
use crate::nnm::{peak_amplitude, start_forced, Point};
use std::f64::consts::PI;

/// The forced linear point at ω (the start of a curve: exact for a linear system).
fn linear_point(p: &Problem, h: usize, omega: f64) -> Vec<f64> {
    let s = crate::nnm::tests::settings(h, h, 1, 1);
    start_forced(p, &s, omega).unwrap().point.x
}

/// Each expected multiplier has a computed one within `tol` (absolute), one to one.
fn assert_close(got: &[(f64, f64)], want: &[(f64, f64)], tol: f64, what: &str) {
    assert_eq!(got.len(), want.len(), "{what}");
    let mut left = got.to_vec();
    for w in want {
        let (i, d) = left
            .iter()
            .enumerate()
            .map(|(i, g)| (i, (g.0 - w.0).hypot(g.1 - w.1)))
            .min_by(|a, b| a.1.total_cmp(&b.1))
            .unwrap();
        assert!(d <= tol, "{what}: {w:?} missed by {d:e} in {got:?}");
        left.remove(i);
    }
}

/// m ẍ + c ẋ + k x = F cos ωt: the multipliers are exp(λT), λ = −ζωₙ ± iω_d, T = 2π/ω,
/// whatever the orbit. RK4 at 2000 steps has a global error of about
/// N(ωₙh)⁵/120 ≈ 6e-12 per period here, so 1e-8 leaves a wide margin. Newmark's average
/// acceleration is the trapezoidal rule on (u, v): its multipliers are exactly
/// ((1 + hλ/2)/(1 − hλ/2))^N, to round-off (1e-11 over 1000 steps), and differ from
/// exp(λT) by about T|λ|(|λ|h)²/12 (2e-5 here). The exact orbit leaves only the
/// integrator's error in the orbit defect, and the verdict is STABLE.
#[test]
fn linear_damped_oscillator_multipliers_are_exact() {
    let p = forced(&[(0, 0, K)], &[(0, 0, M)], &[(0, 0, C)], vec![F], vec![]);
    let wn = (K / M).sqrt();
    let zeta = C / (2.0 * (K * M).sqrt());
    let wd = wn * (1.0 - zeta * zeta).sqrt();
    for omega in [0.6 * wn, wn, 1.7 * wn] {
        let x = linear_point(&p, 3, omega);
        let t = 2.0 * PI / omega;
        let (re, im) = (-zeta * wn, wd);
        let exact: Vec<(f64, f64)> = [im, -im]
            .iter()
            .map(|&b| {
                let r = (re * t).exp();
                (r * (b * t).cos(), r * (b * t).sin())
            })
            .collect();
        let a =
            FloquetAnalyser::new(&p, crate::nnm::tests::settings(3, 3, 1, 1).harmonics).unwrap();
        let rk = a.floquet(&x, 2000, Integrator::Rk4, 1e-3).unwrap();
        assert_close(&rk.multipliers, &exact, 1e-8, "RK4 against exp(λT)");
        assert!(
            rk.orbit_defect < 1e-9,
            "RK4 orbit defect {:e}",
            rk.orbit_defect
        );
        assert_eq!(rk.verdict, Verdict::Stable);
        let n = 1000;
        let h = t / n as f64;
        // (1 + hλ/2)/(1 − hλ/2) as a complex number, raised to the N-th power.
        let cayley: Vec<(f64, f64)> = [im, -im]
            .iter()
            .map(|&b| {
                let (nr, ni) = (1.0 + 0.5 * h * re, 0.5 * h * b);
                let (dr, di) = (1.0 - 0.5 * h * re, -0.5 * h * b);
                let d = dr * dr + di * di;
                let (qr, qi) = ((nr * dr + ni * di) / d, (ni * dr - nr * di) / d);
                let (r, arg) = (qr.hypot(qi).powi(n as i32), qi.atan2(qr) * n as f64);
                (r * arg.cos(), r * arg.sin())
            })
            .collect();
        let nm = a.floquet(&x, n, Integrator::Newmark, 1e-3).unwrap();
        assert_close(
            &nm.multipliers,
            &cayley,
            1e-11,
            "Newmark against its discrete map",
        );
        assert_close(&nm.multipliers, &exact, 1e-4, "Newmark against exp(λT)");
        assert!(
            nm.orbit_defect < 1e-4,
            "Newmark orbit defect {:e}",
            nm.orbit_defect
        );
    }
}

/// Two DOFs with a full damping matrix: the multipliers are exp(λᵢT), λᵢ the eigenvalues
/// of the first-order matrix [[0, I], [−M⁻¹K, −M⁻¹C]] (a dense eigensolve here, not the
/// integrator), RK4 at 2000 steps within 1e-8.
#[test]
fn two_dof_linear_multipliers_are_the_state_matrix_exponentials() {
    let k = [(0, 0, 20.0), (0, 1, -10.0), (1, 0, -10.0), (1, 1, 10.0)];
    let m = [(0, 0, 1.0), (1, 1, 0.5)];
    let c = [(0, 0, 0.08), (0, 1, -0.03), (1, 0, -0.03), (1, 1, 0.05)];
    let p = forced(&k, &m, &c, vec![0.0, 0.02], vec![]);
    let omega = 3.0;
    let x = linear_point(&p, 2, omega);
    let (kd, md, cd) = (p.k.to_dense(), p.m.to_dense(), p.forcing.as_ref().unwrap());
    let cd = cd.damping.to_dense();
    let a = Mat::from_fn(4, 4, |i, j| match (i < 2, j < 2) {
        (true, true) => 0.0,
        (true, false) => f64::from(u8::from(j - 2 == i)),
        (false, true) => -kd[(i - 2, j)] / md[(i - 2, i - 2)],
        (false, false) => -cd[(i - 2, j - 2)] / md[(i - 2, i - 2)],
    });
    let t = 2.0 * PI / omega;
    let exact: Vec<(f64, f64)> = a
        .eigenvalues()
        .unwrap()
        .iter()
        .map(|l| {
            let r = (l.re * t).exp();
            (r * (l.im * t).cos(), r * (l.im * t).sin())
        })
        .collect();
    let f = floquet(
        &p,
        crate::nnm::tests::settings(2, 2, 1, 1).harmonics,
        &x,
        2000,
        Integrator::Rk4,
        1e-3,
    )
    .unwrap();
    assert_close(
        &f.multipliers,
        &exact,
        1e-8,
        "two DOFs, RK4 against exp(λT)",
    );
    assert!(f.orbit_defect < 1e-9, "{:e}", f.orbit_defect);
}

/// The one-DOF wall of testcases/forced_plan.comm (JEU 0.01, RIGI_NOR 50, PARA_REGUL 1e-4,
/// 1.6 % damping, F = 0.01 N; NB_HARM_LINE 10): its curve, its fold rows, and every row's
/// Floquet analysis (Newmark, 1000 steps a period, TOLERANCE 1e-3).
struct Wall {
    h: usize,
    rows: Vec<Point>,
    folds: Vec<usize>,
    floquet: Vec<Floquet>,
}

fn wall() -> Wall {
    let h = 10;
    let problem = forced(
        &[(0, 0, K)],
        &[(0, 0, M)],
        &[(0, 0, C)],
        vec![F],
        vec![plan(0.01, 50.0, 1e-4)],
    );
    let mut s = crate::nnm::tests::settings(h, 10 * h, 300, 4);
    s.continuation.det_test = false;
    let rows = curve(&problem, &s, 0.3, 0.8);
    let folds: Vec<usize> = (1..rows.len() - 1)
        .filter(|&i| {
            (rows[i].frequency - rows[i - 1].frequency)
                * (rows[i + 1].frequency - rows[i].frequency)
                < 0.0
        })
        .collect();
    assert_eq!(folds.len(), 2, "two folds expected: {folds:?}");
    let a = FloquetAnalyser::new(&problem, s.harmonics).unwrap();
    let floquet = rows
        .iter()
        .map(|q| a.floquet(&q.x, 1000, Integrator::Newmark, 1e-3).unwrap())
        .collect();
    Wall {
        h,
        rows,
        folds,
        floquet,
    }
}

/// Between the two folds of the bent resonance the rows are INSTABLE, outside they are
/// STABLE, and the switch happens at the fold rows: there the largest multiplier is real
/// and 1 − μ changes sign within one row of the PLI row (saddle-node: one real multiplier
/// crosses +1). The rows next to a fold may be INDETERMINE (their μ within the band of 1).
#[test]
fn wall_curve_is_unstable_between_its_folds() {
    let w = wall();
    let (a, b) = (w.folds[0], w.folds[1]);
    let mut undecided = Vec::new();
    for (j, f) in w.floquet.iter().enumerate() {
        let near_fold = j.abs_diff(a) <= 1 || j.abs_diff(b) <= 1;
        let want = if j > a && j < b {
            Verdict::Unstable
        } else {
            Verdict::Stable
        };
        // INDETERMINE: μ within the band above 1 (CALC_STABILITE's rule), said so.
        if f.verdict == Verdict::Indeterminate {
            undecided.push(j);
        } else if !near_fold {
            assert_eq!(
                f.verdict, want,
                "row {j} at {} Hz: max |μ| {} defect {:e}",
                w.rows[j].frequency, f.max_modulus, f.orbit_defect
            );
        }
    }
    eprintln!(
        "folds at rows {a}, {b} of {}; INDETERMINE rows {undecided:?}",
        w.rows.len()
    );
    for &j in &undecided {
        let f = &w.floquet[j];
        eprintln!(
            "  row {j}: max |μ| {:.6} band {:.4} defect {:.2e}",
            f.max_modulus, f.band, f.orbit_defect
        );
    }
    // Saddle-node: the largest multiplier is real at the fold row and on its unstable
    // side, and max |μ| − 1 changes sign within two rows of the fold. (At the lower fold,
    // at grazing, the real pair meets and turns complex one row past +1: measured.)
    for (fold, inside) in [(a, a + 1), (b, b - 1)] {
        for j in [fold, inside] {
            let top = w.floquet[j].multipliers[0];
            assert!(top.0 > 0.0 && top.1.abs() < 1e-9, "row {j}: {top:?}");
        }
        let signs: Vec<f64> = (fold - 2..=fold + 2)
            .map(|j| w.floquet[j].max_modulus - 1.0)
            .collect();
        eprintln!("fold row {fold}: max |μ| − 1 around it {signs:?}");
        assert!(
            signs[0] * signs[4] < 0.0,
            "no crossing of +1 around row {fold}: {signs:?}"
        );
    }
    // Liouville: Π μ = det Φ(T) = exp(−cT/m) on every row, whatever the orbit (the
    // nonlinearity is in the stiffness only). Newmark's step (the trapezoidal rule on
    // (u, v)) has determinant (1 − hc/2m + h²k_t(t)/4m)/(1 + hc/2m + h²k_t(t+h)/4m), which
    // is exp(−hc/m) only to O(h³) a step, O(h²) over the period: measured 9.3e-6 at 1000
    // steps, bound 3e-5.
    let mut worst = 0.0f64;
    for (q, f) in w.rows.iter().zip(&w.floquet) {
        let (p0, p1) = (f.multipliers[0], f.multipliers[1]);
        let prod = p0.0 * p1.0 - p0.1 * p1.1;
        let want = (-C / M * 2.0 * PI / q.omega).exp();
        worst = worst.max((prod - want).abs() / want);
    }
    eprintln!("largest relative gap of Π μ to exp(−cT/m): {worst:e}");
    assert!(worst < 3e-5, "{worst:e}");
    // INDETERMINE only on the unstable stretch, where the multiplier is above 1 but
    // within the band √(2·defect) of it (defect ≈ 2e-3 at NB_HARM_LINE 10).
    for &j in &undecided {
        assert!(j > a && j < b && w.floquet[j].max_modulus > 1.0, "row {j}");
    }
}

/// The verdict against the time integration of the nonlinear ODE: at rows of each
/// branch, the true periodic orbit of the same regularised law (shooting, RK4 at 20 000
/// steps a period) is perturbed by 1e-8 in (x, v/ω) and both trajectories are integrated
/// for 24 periods (fewer on an unstable row, until 1e-4 JEU apart); the growth of their
/// distance per period from the third period on is the
/// largest multiplier modulus of the true orbit (the other multiplier is det Φ/μ, det Φ =
/// exp(−cT/m)). It must be on the same side of 1 as the HB row's verdict and within 2 %
/// of its largest modulus (measured: the HB multipliers with NB_HARM_LINE 10 and Newmark
/// at 1000 steps against the growth rate; see the printed values).
#[test]
fn verdict_matches_the_growth_of_a_perturbation() {
    let w = wall();
    let (g, alpha) = (0.01, 50.0);
    let eta = 1e-4 * K * g * g;
    let law = move |x: f64| plan_force(x, g, alpha, eta);
    let (a, b) = (w.folds[0], w.folds[1]);
    let picks = [
        a / 2,
        a + (b - a) / 3,
        a + 2 * (b - a) / 3,
        (b + w.rows.len()) / 2,
    ];
    for j in picks {
        let q = &w.rows[j];
        let (om, u) = (q.omega, &q.x[..2 * w.h + 1]);
        let x0: f64 = u[..w.h + 1].iter().sum();
        let v0: f64 = (1..=w.h).map(|k| k as f64 * om * u[w.h + k]).sum();
        let (xs, vs) = shooting_state(x0, v0, om, &law);
        let d0 = 1e-8;
        let (mut base, mut pert) = ((xs, vs), (xs + d0 * 0.6, vs + d0 * 0.8 * om));
        let dist = |p: (f64, f64), q: (f64, f64)| (p.0 - q.0).hypot((p.1 - q.1) / om);
        let mut d = Vec::new();
        // Until 24 periods, or the distance 1e-6 (1e-4 JEU: still linear) on an unstable row.
        while d.len() < 24 && d.last().is_none_or(|&x: &f64| x < 1e-6) {
            base = period(base.0, base.1, om, 4000, &law).0;
            pert = period(pert.0, pert.1, om, 4000, &law).0;
            d.push(dist(base, pert));
        }
        assert!(d.len() >= 8, "row {j}: {d:?}");
        let last = d.len() - 1;
        let growth = (d[last] / d[2]).powf(1.0 / (last - 2) as f64);
        let f = &w.floquet[j];
        eprintln!(
            "row {j} ({} Hz, amplitude {:.4e}): growth {growth:.6} per period, HB max |μ| {:.6}, {}",
            q.frequency,
            peak_amplitude(u, w.h),
            f.max_modulus,
            f.label()
        );
        assert_eq!(growth > 1.0, f.verdict == Verdict::Unstable, "row {j}");
        assert!(
            (growth - f.max_modulus).abs() <= 0.02 * f.max_modulus,
            "row {j}: growth {growth} against {}",
            f.max_modulus
        );
    }
}
