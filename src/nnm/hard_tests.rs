//! Hard cases: the engine must stay numerically stable (every corrected point within
//! PREC_NEWTON, nothing non-finite, physically monotone where physics says so) on stiff
//! contact, tiny regularisation, many harmonics, grazing, bifurcations, mixed laws, rings,
//! restarts and failed corrections. docs/hard_cases.md lists the measured figures.

use super::reference::Oscillator;
use super::tests::{freq_at, one_dof, settings, sparse, SDND};
use super::*;

/// Worst figures of a run, printed by every test (docs/hard_cases.md quotes them).
#[derive(Debug, Default)]
struct Stats {
    residual: f64,
    gamma: f64,
    spread: f64,
}

/// Every point corrected (NB_PAS_MAN = 1 in these tests): residual ≤ PREC_NEWTON, every
/// reported quantity finite. Returns the worst residual, |γ| and energy spread.
fn check_points(pts: &[Point], s: &Settings) -> Stats {
    assert!(!pts.is_empty());
    let mut st = Stats::default();
    for q in pts {
        assert!(
            q.x.iter().all(|v| v.is_finite())
                && q.frequency.is_finite()
                && q.energy.is_finite()
                && q.gamma.is_finite()
                && q.energy_spread.is_finite(),
            "non-finite point on branch {}",
            q.branch
        );
        assert!(
            q.residual <= s.prec_newton,
            "branch {}: residual {:.3e} > {:.1e}",
            q.branch,
            q.residual,
            s.prec_newton
        );
        st.residual = st.residual.max(q.residual);
        st.gamma = st.gamma.max(q.gamma.abs());
        st.spread = st.spread.max(q.energy_spread);
    }
    st
}

/// Energy strictly increasing along the run (direction +1) and, for a hardening stop,
/// frequency non-decreasing with it (1e-9 relative slack: below contact the frequency is
/// the linear one and only round-off moves it).
fn assert_hardening(pts: &[Point]) {
    for w in pts.windows(2) {
        assert!(w[1].energy > w[0].energy, "energy not increasing: {w:?}");
        assert!(
            w[1].frequency >= w[0].frequency * (1.0 - 1e-9),
            "frequency drops from {} to {} at E = {}",
            w[0].frequency,
            w[1].frequency,
            w[1].energy
        );
    }
}

fn run_all(p: &Problem, s: &Settings, mode: &[f64], coef: f64, omega: f64) -> Vec<Point> {
    let st = start_from_mode(p, s, mode, coef, omega).unwrap();
    let out = continue_branches(p, s, st, &mut |_, _| {});
    if let Some(e) = &out.error {
        panic!("run failed after {} points: {e}", out.points.len());
    }
    out.points
}

/// Chain of n unit masses, spring k between neighbours and to the ground at the first one
/// (fixed–free), stop on the free end.
fn chain_problem(n: usize, k: f64, law: ShockLaw, stiffness: f64, regul: f64) -> Problem {
    let mut ke = Vec::new();
    for i in 0..n {
        ke.push((i, i, if i + 1 < n { 2.0 * k } else { k }));
        if i + 1 < n {
            ke.push((i, i + 1, -k));
            ke.push((i + 1, i, -k));
        }
    }
    let me: Vec<(usize, usize, f64)> = (0..n).map(|i| (i, i, 1.0)).collect();
    Problem {
        k: sparse(n, &ke),
        m: sparse(n, &me),
        shocks: vec![Shock {
            law,
            dofs: vec![n - 1],
            gap: 0.01,
            stiffness,
            regul,
        }],
    }
}

/// Lowest mode of the fixed–free chain of unit masses, exact: ω = 2√k·sin(π/(2(2n+1))),
/// u_i ∝ sin((i+1)·π/(2n+1)) (i = 0..n−1, largest at the free end).
fn chain_mode(n: usize, k: f64) -> (Vec<f64>, f64) {
    let th = std::f64::consts::PI / (2 * n + 1) as f64;
    let v: Vec<f64> = (0..n).map(|i| ((i + 1) as f64 * th).sin()).collect();
    let big = v[n - 1];
    (
        v.iter().map(|a| a / big).collect(),
        2.0 * k.sqrt() * (th / 2.0).sin(),
    )
}

#[test]
fn hard_stiff_wall_one_dof_rigi_nor_1_to_1e8() {
    // RIGI_NOR/k = 1 … 1e8 on the sdnd122 oscillator (k = 10). The frequency at E = 1e-3
    // lies between the linear one and the rigid-impact limit (α → ∞), grows with α, and
    // for α = k it matches the exact period of ehman.md §8 (the contact is soft: H_nl = 60
    // resolves it; 1e-4 relative covers PARA_REGUL = 1e-5 and the truncation).
    let w0 = 10f64.sqrt();
    let e = 1e-3;
    let b = (2.0 * e / 10.0f64).sqrt();
    let rigid = w0 / (2.0 * (std::f64::consts::PI - (0.01 / b).acos()));
    let mut prev = w0 / (2.0 * std::f64::consts::PI);
    for ratio in [1.0, 1e2, 1e4, 1e6, 1e8] {
        let mut p = one_dof(ShockLaw::Plan, 1e-5);
        p.shocks[0].stiffness = 10.0 * ratio;
        let mut s = settings(5, 60, 20, 1);
        s.prec_man = 1e-8;
        let t0 = std::time::Instant::now();
        let pts = run_all(&p, &s, &[1.0], 1.0, w0);
        let st = check_points(&pts, &s);
        assert_hardening(&pts);
        let f = freq_at(&pts, e).unwrap();
        println!(
            "RIGI_NOR/k {ratio:e}: f(1e-3) {f:.8} rigid {rigid:.8} {st:?} {:?}",
            t0.elapsed()
        );
        assert!(f > prev && f < rigid, "{f} not in ({prev}, {rigid})");
        prev = f;
        if ratio == 1.0 {
            let osc = Oscillator {
                alpha: 10.0,
                ..SDND
            };
            let exact = 1.0 / osc.period_plan(e);
            assert!((f / exact - 1.0).abs() < 1e-4, "{f} vs exact {exact}");
        }
    }
}

#[test]
fn hard_stiff_stop_on_a_20_dof_chain() {
    // 20 unit masses, k = 10, PLAN on the free end, RIGI_NOR/k = 1 … 1e8. A uniform
    // fixed–free chain has ω₂/ω₁ = 2.997: the third harmonic of mode 1 (retained, H_l = 3)
    // is in 3:1 internal resonance with mode 2, and the frequency of that interacting branch
    // does dip below the linear one (measured). Physics gives no monotonicity here; the
    // checks are: every corrected point converged and nothing is NaN.
    let n = 20;
    let (mode, w) = chain_mode(n, 10.0);
    for ratio in [1.0, 1e4, 1e8] {
        let p = chain_problem(n, 10.0, ShockLaw::Plan, 10.0 * ratio, 1e-4);
        let mut s = settings(3, 40, 30, 1);
        s.prec_man = 1e-8;
        let t0 = std::time::Instant::now();
        let pts = run_all(&p, &s, &mode, 1.0, w);
        let st = check_points(&pts, &s);
        let last = pts.last().unwrap();
        println!(
            "chain RIGI_NOR/k {ratio:e}: {} pts, E {:.3e}..{:.3e}, f/f_lin {:.6}..{:.6} {st:?} {:?}",
            pts.len(),
            pts[0].energy,
            last.energy,
            pts[0].omega / w,
            last.omega / w,
            t0.elapsed()
        );
    }
}

#[test]
fn hard_tiny_regularisation_down_to_1e_7() {
    // PARA_REGUL = 1e-5, 1e-6, 1e-7 with NB_HARM_NONL raised as the force pulse sharpens.
    // The error against the exact nonsmooth period (ehman.md §8) over E ∈ [1e-3, 3e-3]
    // must stay small and the runs converge.
    for (eta, hn, hl, nb) in [(1e-5, 100, 7, 40), (1e-6, 200, 7, 60), (1e-7, 200, 7, 60)] {
        let p = one_dof(ShockLaw::Plan, eta);
        let mut s = settings(hl, hn, nb, 1);
        s.prec_man = 1e-8;
        let t0 = std::time::Instant::now();
        let pts = run_all(&p, &s, &[1.0], 1.0, 10f64.sqrt());
        let st = check_points(&pts, &s);
        assert_hardening(&pts);
        let err = pts
            .iter()
            .filter(|q| q.energy >= 1e-3 && q.energy <= 3e-3)
            .map(|q| (q.frequency * SDND.period_plan(q.energy) - 1.0).abs())
            .fold(0.0, f64::max);
        println!(
            "PARA_REGUL {eta:e} H_nl {hn}: {} pts, top E {:.3e}, max rel err {err:.3e} {st:?} {:?}",
            pts.len(),
            pts.last().unwrap().energy,
            t0.elapsed()
        );
        assert!(pts.last().unwrap().energy > 1.0e-3);
    }
}

#[test]
fn hard_many_harmonics() {
    // NB_HARM_LINE = 50, NB_HARM_NONL = 1000: few branches.
    let p = one_dof(ShockLaw::Plan, 1e-5);
    let mut s = settings(50, 1000, 1, 1);
    s.prec_man = 1e-8;
    let t0 = std::time::Instant::now();
    let pts = run_all(&p, &s, &[1.0], 1.0, 10f64.sqrt());
    let st = check_points(&pts, &s);
    assert_hardening(&pts);
    for q in &pts {
        let ex = 1.0 / SDND.period_plan(q.energy);
        println!("E {:.4e} f {:.8} exact {:.8}", q.energy, q.frequency, ex);
    }
    println!("many harmonics: {st:?} {:?}", t0.elapsed());
}

#[test]
fn hard_grazing_start_below_contact() {
    // COEF_AMPL = 0.5: the orbit starts at half the gap and crosses first contact
    // (E = ½kJEU² = 5e-4). Below it the frequency is the linear one up to the
    // regularisation's effect; above it, it rises.
    let p = one_dof(ShockLaw::Plan, 1e-7);
    let mut s = settings(5, 100, 30, 1);
    s.prec_man = 1e-8;
    let w0 = 10f64.sqrt();
    let f0 = w0 / (2.0 * std::f64::consts::PI);
    let t0 = std::time::Instant::now();
    let st0 = start_from_mode(&p, &s, &[1.0], 0.5, w0).unwrap();
    println!("start: E/Ec {:.4} f/f0-1 {:.3e}", st0.point.energy / 5e-4, st0.point.frequency / f0 - 1.0);
    let pts = continue_branches(&p, &s, st0, &mut |_, _| {}).points;
    let st = check_points(&pts, &s);
    assert_hardening(&pts);
    let e_c = 0.5 * 10.0 * 0.01 * 0.01;
    for q in &pts {
        println!(
            "E/Ec {:.4} f/f0-1 {:.3e} exact {:.3e}",
            q.energy / e_c,
            q.frequency / f0 - 1.0,
            SDND.period_plan(q.energy).recip() / f0 - 1.0
        );
    }
    println!("grazing {st:?} {:?}", t0.elapsed());
}

/// Two unit masses on springs k to the ground, coupled by kc; a PLAN stop on each (same
/// gap): the in-phase mode of this symmetric system is known to bifurcate toward localised
/// modes when the stops' stiffening outweighs the weak coupling.
fn two_mass(kc: f64, shocks: Vec<Shock>) -> Problem {
    Problem {
        k: sparse(
            2,
            &[(0, 0, 10.0 + kc), (0, 1, -kc), (1, 0, -kc), (1, 1, 10.0 + kc)],
        ),
        m: sparse(2, &[(0, 0, 1.0), (1, 1, 1.0)]),
        shocks,
    }
}

fn plan_on(dof: usize, law: ShockLaw) -> Shock {
    Shock {
        law,
        dofs: vec![dof],
        gap: 0.01,
        stiffness: 50.0,
        regul: 1e-4,
    }
}

#[test]
fn hard_bifurcation_on_a_symmetric_two_mass_system() {
    for (name, kc, shocks, mode, coef) in [
        ("antiphase PLAN on 0 kc .5", 0.5, vec![plan_on(0, ShockLaw::Plan)], [1.0, -1.0], 0.5),
        ("antiphase BI on 0 kc 2", 2.0, vec![plan_on(0, ShockLaw::BiPlan)], [1.0, -1.0], 1.0),
        ("antiphase BI on 0 kc .5", 0.5, vec![plan_on(0, ShockLaw::BiPlan)], [1.0, -1.0], 1.0),
    ] {
        let p = two_mass(kc, shocks);
        let mut s = settings(5, 60, 40, 1);
        s.prec_man = 1e-8;
        let w = if mode[1] > 0.0 { 10f64.sqrt() } else { (10.0 + 2.0 * kc).sqrt() };
        let t0 = std::time::Instant::now();
        let st0 = start_from_mode(&p, &s, &mode, coef, w).unwrap();
        let out = continue_branches(&p, &s, st0, &mut |_, _| {});
        let bifs: Vec<usize> = out.points.iter().filter(|q| q.bifurcation).map(|q| q.branch).collect();
        let nl = 2 * s.h_lin + 1;
        let last = out.points.last().unwrap();
        for q in &out.points {
            println!("  b {} E {:.4e} f {:.6} bif {} res {:.1e} u0 {:.3e} u1 {:.3e}", q.branch, q.energy, q.frequency, q.bifurcation, q.residual, q.x[1], q.x[nl + 1]);
        }
        println!(
            "{name}: {} pts err {:?} bif {bifs:?} E {:.3e} f {:.5} u0 {:.3e} u1 {:.3e} {:?}",
            out.points.len(), out.error.as_ref().map(|e| e.message.clone()), last.energy, last.frequency, last.x[1], last.x[nl + 1], t0.elapsed()
        );
    }
}

#[test]
fn hard_two_laws_on_one_model() {
    // PLAN on mass 1, BI_PLAN on mass 2 of a weakly coupled pair: both stops act on the
    // in-phase mode; hardening in both.
    let p = two_mass(
        2.0,
        vec![plan_on(0, ShockLaw::Plan), plan_on(1, ShockLaw::BiPlan)],
    );
    let mut s = settings(5, 60, 30, 1);
    s.prec_man = 1e-8;
    let t0 = std::time::Instant::now();
    let pts = run_all(&p, &s, &[1.0, 1.0], 1.0, 10f64.sqrt());
    let st = check_points(&pts, &s);
    assert_hardening(&pts);
    println!("two laws {st:?} {:?}", t0.elapsed());
}

#[test]
fn hard_restart_reproduces_the_single_run() {
    let p = one_dof(ShockLaw::Plan, 5e-5);
    let mut s = settings(5, 200, 10, 1);
    s.prec_man = 1e-12;
    let whole = run_all(&p, &s, &[1.0], 1.0, 10f64.sqrt());
    s.n_branches = 5;
    let first = run_all(&p, &s, &[1.0], 1.0, 10f64.sqrt());
    let st = start_from_point(&p, &s, &first[4].x).unwrap();
    println!("restart newton its {}", st.newton_iterations);
    let out = continue_branches(&p, &s, st, &mut |_, _| {});
    assert!(out.error.is_none());
    for (a, b) in whole[5..].iter().zip(&out.points) {
        println!(
            "df {:.3e} dE {:.3e}",
            b.frequency / a.frequency - 1.0,
            b.energy / a.energy - 1.0
        );
    }
    for (a, b) in whole[..5].iter().zip(&first) {
        println!(
            "first part df {:.3e} dE {:.3e}",
            b.frequency / a.frequency - 1.0,
            b.energy / a.energy - 1.0
        );
    }
}

#[test]
fn hard_failed_correction_keeps_the_points_before_it() {
    for (pm, it, coef) in [(1e-8, 1, 0.5), (1e-6, 1, 0.5), (1e-4, 1, 0.5), (1e-6, 1, 0.2), (1e-2, 1, 0.2)] {
        let p = one_dof(ShockLaw::Plan, 1e-4);
        let mut s = settings(3, 30, 20, 1);
        s.prec_man = pm;
        s.iter_newton_max = it;
        s.prec_newton = 1e-8;
        match start_from_mode(&p, &s, &[1.0], coef, 10f64.sqrt()) {
            Err(e) => println!("{pm} {it} {coef}: start failed {e}"),
            Ok(st) => {
                let out = continue_branches(&p, &s, st, &mut |_, _| {});
                println!("{pm} {it} {coef}: {} points, error {:?}", out.points.len(), out.error.map(|e| e.message));
            }
        }
    }
}

#[test]
fn hard_cercle_whirl_attempt() {
    // Isotropic node (k = 10 in x and y) in a centred ring: try a circular whirl of radius
    // A. Exact: constant radial force f, root of f² − αf(A − g) − αη = 0, and
    // ω² = (k + f/A)/m.
    let (g, alpha, k) = (0.01, 50.0, 10.0);
    let regul = 1e-4;
    let p = Problem {
        k: sparse(2, &[(0, 0, k), (1, 1, k)]),
        m: sparse(2, &[(0, 0, 1.0), (1, 1, 1.0)]),
        shocks: vec![Shock {
            law: ShockLaw::Cercle { origin: [0.0, 0.0] },
            dofs: vec![0, 1],
            gap: g,
            stiffness: alpha,
            regul,
        }],
    };
    let s = {
        let mut s = settings(3, 20, 10, 1);
        s.prec_man = 1e-8;
        s
    };
    let a = 0.012;
    let eta = regul * k * g * g;
    let f = (alpha * (a - g) + ((alpha * (a - g)).powi(2) + 4.0 * alpha * eta).sqrt()) / 2.0;
    let w = ((k + f / a) / 1.0f64).sqrt();
    let (hl, hn) = (s.h_lin, s.h_nonl);
    let (nl, nn) = (2 * hl + 1, 2 * hn + 1);
    let mut x = vec![0.0; unknown_count(&p, &s)];
    let ay = a * 0.9999;
    x[1] = a; // U_x c1
    x[nl + hl + 1] = ay; // U_y s1
    x[2 * nl + hl + 1] = -w * a; // V_x s1
    x[3 * nl + 1] = w * ay; // V_y c1
    let o = 4 * nl;
    x[o] = f;
    x[o + nn] = a;
    x[o + 2 * nn + 1] = f;
    x[o + 3 * nn + hn + 1] = f;
    let n = x.len();
    x[n - 2] = w;
    match start_from_point(&p, &s, &x) {
        Err(e) => println!("whirl start failed: {e}"),
        Ok(st) => {
            println!("whirl start: ω {} vs {} its {}", st.point.omega, w, st.newton_iterations);
            let out = continue_branches(&p, &s, st, &mut |_, _| {});
            println!("whirl: {} pts err {:?}", out.points.len(), out.error.map(|e| e.message));
            for q in &out.points {
                let r = q.x[o + nn];
                let fr = q.x[o];
                println!("E {:.4e} ω {:.8} r0 {:.5e} closed {:.8} ux {:.4e} uy {:.4e}", q.energy, q.omega, r, ((k + fr / r)).sqrt(), q.x[1], q.x[nl + hl + 1]);
            }
        }
    }
}
