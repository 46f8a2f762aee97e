//! Floquet analysis tests: closed forms on linear systems, consistency with the engine's
//! laws, Newmark against RK4, and an unstable orbit.

use super::super::{continue_branches, start_from_mode, Point, Problem, Settings, Shock, ShockLaw};
use super::*;
use faer::sparse::{SparseColMat, Triplet};

fn sparse(n: usize, e: &[(usize, usize, f64)]) -> SparseColMat<usize, f64> {
    let t: Vec<Triplet<usize, usize, f64>> = e.iter().map(|&(r, c, v)| Triplet::new(r, c, v)).collect();
    SparseColMat::try_new_from_triplets(n, n, &t).unwrap()
}

fn settings(hl: usize, hn: usize, branches: usize, points: usize) -> Settings {
    Settings {
        h_lin: hl,
        h_nonl: hn,
        n_branches: branches,
        n_points_per_branch: points,
        order: 20,
        prec_man: 1e-10,
        prec_newton: 1e-9,
        iter_newton_max: 15,
        bif_terms: 3,
        bif_tol: 1e-4,
        direction: 1,
    }
}

fn branch(problem: &Problem, s: &Settings, mode: &[f64], coef: f64, omega: f64) -> Vec<Point> {
    let st = match start_from_mode(problem, s, mode, coef, omega) { Ok(s) => s, Err(e) => { println!("start failed: {e}"); return vec![]; } };
    let mut pts = vec![st.point.clone()];
    let out = continue_branches(problem, s, st, &mut |_, _| {});
    if let Some(e) = &out.error {
        println!("run failed after {} points: {e}", out.points.len());
    }
    pts.extend(out.points);
    pts
}

fn sdnd122(law: ShockLaw) -> Problem {
    Problem {
        k: sparse(1, &[(0, 0, 10.0)]),
        m: sparse(1, &[(0, 0, 1.0)]),
        shocks: vec![Shock { law, dofs: vec![0], gap: 0.01, stiffness: 50.0, regul: 5e-5 }],
    }
}

#[test]
fn explore_sdnd122() {
    let p = sdnd122(ShockLaw::Plan);
    for hl in [5, 10, 20] {
    let s = settings(hl, 100, 30, 1);
    let pts = branch(&p, &s, &[1.0], 1.0, 10f64.sqrt());
    for q in pts.iter().step_by(6) {
        for nb in [1000, 4000] {
            let a = floquet(&p, &s, &q.x, nb, Integrator::Newmark, 1e-2).unwrap();
            let b = floquet(&p, &s, &q.x, nb, Integrator::Rk4, 1e-2).unwrap();
            println!(
                "E {:.3e} f {:.5} nb {nb} NM max {:.6} triv {:.2e} def {:.2e} | RK max {:.6} triv {:.2e} def {:.2e} {:?}",
                q.energy, q.frequency, a.max_modulus, a.trivial_distance, a.orbit_defect, b.max_modulus, b.trivial_distance, b.orbit_defect, b.multipliers
            );
        }
    }}
}

fn nontrivial_max(f: &Floquet) -> f64 {
    let mut v: Vec<(f64, f64)> = f.multipliers.iter().map(|m| ((m.0 - 1.0).hypot(m.1), m.0.hypot(m.1))).collect();
    v.sort_by(|a, b| a.0.total_cmp(&b.0));
    v.iter().skip(2).map(|x| x.1).fold(0.0, f64::max)
}

#[test]
fn explore_two_dof() {
    for (kc, hl) in [(1.0, 5), (1.0, 10), (1.0, 15)] {
        let k = 10.0;
        let p = Problem {
            k: sparse(2, &[(0, 0, k + kc), (0, 1, -kc), (1, 0, -kc), (1, 1, k + kc)]),
            m: sparse(2, &[(0, 0, 1.0), (1, 1, 1.0)]),
            shocks: vec![Shock { law: ShockLaw::Plan, dofs: vec![1], gap: 0.01, stiffness: 50.0, regul: 5e-5 }],
        };
        let s = settings(hl, 100, 40, 1);
        for (mode, w2) in [([1.0, -1.0], k + 2.0 * kc)] {
            println!("=== kc {kc} hl {hl} mode {mode:?}");
            let pts = branch(&p, &s, &mode, 0.5, w2.sqrt());
            for q in &pts {
                let b = floquet(&p, &s, &q.x, 1000, Integrator::Rk4, 1e-2).unwrap();
                println!(
                    "E {:.4e} f {:.5} bif {} max {:.5} nontriv {:.5} triv {:.2e} def {:.2e} {:.4?}",
                    q.energy, q.frequency, q.bifurcation, b.max_modulus, nontrivial_max(&b), b.trivial_distance, b.orbit_defect, b.multipliers
                );
            }
        }
    }
}
