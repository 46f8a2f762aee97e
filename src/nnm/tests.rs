//! Engine tests against closed forms (reference.rs) and internal consistency.

use super::reference::Oscillator;
use super::system::{Scaling, System};
use super::*;
use faer::sparse::Triplet;

pub fn sparse(n: usize, e: &[(usize, usize, f64)]) -> SparseColMat<usize, f64> {
    let t: Vec<Triplet<usize, usize, f64>> = e.iter().map(|&(r, c, v)| Triplet::new(r, c, v)).collect();
    SparseColMat::try_new_from_triplets(n, n, &t).unwrap()
}

pub fn settings(hl: usize, hn: usize, branches: usize, points: usize) -> Settings {
    Settings {
        h_lin: hl,
        h_nonl: hn,
        n_branches: branches,
        n_points_per_branch: points,
        order: 20,
        prec_man: 1e-9,
        prec_newton: 1e-9,
        iter_newton_max: 15,
        bif_terms: 3,
        bif_tol: 1e-4,
        direction: 1,
    }
}

/// The sdnd122 oscillator: m = 1, k = 10, stop at JEU = 0.01 with RIGI_NOR = 50.
pub fn one_dof(law: ShockLaw, regul: f64) -> Problem {
    Problem {
        k: sparse(1, &[(0, 0, 10.0)]),
        m: sparse(1, &[(0, 0, 1.0)]),
        shocks: vec![Shock { law, dofs: vec![0], gap: 0.01, stiffness: 50.0, regul }],
    }
}

pub const SDND: Oscillator = Oscillator { m: 1.0, k: 10.0, g: 0.01, alpha: 50.0 };

/// Frequency at energy `e` by log-log interpolation between the bracketing points (as
/// RECU_FONCTION(INTERPOL='LOG') then TEST_FONCTION do).
pub fn freq_at(points: &[Point], e: f64) -> Option<f64> {
    let mut v: Vec<(f64, f64)> = points.iter().map(|p| (p.energy, p.frequency)).collect();
    v.sort_by(|a, b| a.0.total_cmp(&b.0));
    v.windows(2).find(|w| w[0].0 <= e && e <= w[1].0).map(|w| {
        let t = (e.ln() - w[0].0.ln()) / (w[1].0.ln() - w[0].0.ln());
        (w[0].1.ln() + t * (w[1].1.ln() - w[0].1.ln())).exp()
    })
}

fn run(problem: &Problem, s: &Settings, mode: &[f64], coef: f64, omega: f64) -> Vec<Point> {
    let st = start_from_mode(problem, s, mode, coef, omega).unwrap();
    let out = continue_branches(problem, s, st, &mut |_, _| {});
    if let Some(e) = &out.error {
        panic!("run failed after {} points: {e}", out.points.len());
    }
    out.points
}

/// Dense copy of the first n_eq rows of the bordered tangent.
fn dense_tangent(sys: &System, x: &[f64]) -> Vec<Vec<f64>> {
    let n = sys.lay.n_unk;
    let mut a = vec![vec![0.0; n]; n];
    for t in sys.tangent(x, &vec![0.0; n]) {
        a[t.row][t.col] += t.val;
    }
    a
}

#[test]
fn tangent_is_the_derivative_of_the_residual() {
    // R is quadratic, so the centred difference is exact up to round-off: 1e-8 absolute on
    // O(1) entries.
    for law in [ShockLaw::Plan, ShockLaw::BiPlan, ShockLaw::Cercle { origin: [0.002, -0.001] }] {
        let dofs = if matches!(law, ShockLaw::Cercle { .. }) { vec![0, 1] } else { vec![1] };
        let p = Problem {
            k: sparse(2, &[(0, 0, 20.0), (0, 1, -10.0), (1, 0, -10.0), (1, 1, 10.0)]),
            m: sparse(2, &[(0, 0, 1.0), (1, 1, 2.0)]),
            shocks: vec![Shock { law, dofs, gap: 0.01, stiffness: 50.0, regul: 1e-3 }],
        };
        let s = settings(2, 4, 1, 1);
        let sc = Scaling::new(&p, 1.0, 0).unwrap();
        let sys = System::new(&p, &s, sc, 0).unwrap();
        let n = sys.lay.n_unk;
        let x: Vec<f64> = (0..n).map(|i| ((i * 37 % 11) as f64 / 11.0 - 0.4) * 1.3 + 0.5).collect();
        let a = dense_tangent(&sys, &x);
        for c in 0..n {
            let h = 1e-3;
            let mut xp = x.clone();
            xp[c] += h;
            let mut xm = x.clone();
            xm[c] -= h;
            let (rp, rm) = (sys.residual(&xp), sys.residual(&xm));
            for r in 0..n - 1 {
                let fd = (rp[r] - rm[r]) / (2.0 * h);
                assert!((fd - a[r][c]).abs() < 1e-8, "{law:?} row {r} col {c}: fd {fd} vs {}", a[r][c]);
            }
        }
    }
}

#[test]
fn explore_sdnd122_small() {
    let p = one_dof(ShockLaw::Plan, 5e-5);
    let mut s = settings(5, 50, 40, 1);
    s.prec_man = 1e-10;
    let pts = run(&p, &s, &[1.0], 1.0, 10f64.sqrt());
    for q in &pts {
        let exact = 1.0 / SDND.period_plan(q.energy);
        println!(
            "E {:.6e} f {:.8} exact {:.8} rel {:.2e} res {:.1e} spread {:.1e} gamma {:.1e}",
            q.energy,
            q.frequency,
            exact,
            q.frequency / exact - 1.0,
            q.residual,
            q.energy_spread,
            q.gamma
        );
    }
}
