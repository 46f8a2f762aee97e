//! The verdict against independent Floquet multipliers: shooting on the same regularised
//! law, written here without the engine (own law, own RK4 of the equations of motion and of
//! the variational equations, own Newton), on two masses with a stop; and the reduction of
//! the trivial pair on a monodromy matrix built by hand.

// The 4 × 4 algebra of the reference is written index-wise, as on paper.
#![allow(clippy::needless_range_loop)]

use super::tests::{branch, pair, settings, shock};
use super::*;
use crate::nnm::{displacement_coefficients, ShockLaw};

/// PLAN with α = RIGI_NOR, g = JEU, η: the positive root of f² − α f (u − g) − α η = 0
/// (docs/ehman.md), written without cancellation on either side, and df/du.
fn plan_law(u: f64, alpha: f64, g: f64, eta: f64) -> (f64, f64) {
    let d = u - g;
    let q = (alpha * alpha * d * d + 4.0 * alpha * eta).sqrt();
    let f = if d >= 0.0 {
        0.5 * (alpha * d + q)
    } else {
        2.0 * alpha * eta / (q - alpha * d)
    };
    (f, alpha * f / q)
}

/// Two unit masses, ground springs `k`, coupling `kc`, PLAN stop on mass 2.
struct Pair {
    k: f64,
    kc: f64,
    alpha: f64,
    gap: f64,
    eta: f64,
}

impl Pair {
    /// η = PARA_REGUL·k_ref·JEU² with k_ref = 1/(K⁻¹)₂₂ (the engine's reference stiffness
    /// at the stop, `nnm::point_law::eta_phys`), computed here from the 2 × 2 inverse.
    fn new(k: f64, kc: f64, alpha: f64, gap: f64, regul: f64) -> Pair {
        let (a, b) = (k + kc, -kc);
        let k_ref = (a * a - b * b) / a;
        Pair {
            k,
            kc,
            alpha,
            gap,
            eta: regul * k_ref * gap * gap,
        }
    }

    /// (ẏ, the tangent stiffness K + J) at y = (u₁, u₂, v₁, v₂).
    fn rhs(&self, y: &[f64; 4]) -> ([f64; 4], [[f64; 2]; 2]) {
        let (f, df) = plan_law(y[1], self.alpha, self.gap, self.eta);
        let (a, c) = (self.k + self.kc, -self.kc);
        let acc = [-(a * y[0] + c * y[1]), -(c * y[0] + a * y[1] + f)];
        ([y[2], y[3], acc[0], acc[1]], [[a, c], [c, a + df]])
    }

    /// y(T) and Φ(T) from y0 by RK4 with `steps` steps (state and variational equations
    /// advanced together, the Jacobian taken at each stage's state).
    fn flow(&self, y0: [f64; 4], t: f64, steps: usize) -> ([f64; 4], [[f64; 4]; 4]) {
        type S = ([f64; 4], [[f64; 4]; 4]);
        let deriv = |s: &S| -> S {
            let (dy, kt) = self.rhs(&s.0);
            let p = &s.1;
            let dphi: [[f64; 4]; 4] = [
                p[2],
                p[3],
                std::array::from_fn(|c| -(kt[0][0] * p[0][c] + kt[0][1] * p[1][c])),
                std::array::from_fn(|c| -(kt[1][0] * p[0][c] + kt[1][1] * p[1][c])),
            ];
            (dy, dphi)
        };
        let axpy = |s: &S, h: f64, d: &S| -> S {
            let mut o = *s;
            for i in 0..4 {
                o.0[i] += h * d.0[i];
                for j in 0..4 {
                    o.1[i][j] += h * d.1[i][j];
                }
            }
            o
        };
        let mut id = [[0.0; 4]; 4];
        for (i, row) in id.iter_mut().enumerate() {
            row[i] = 1.0;
        }
        let mut s: S = (y0, id);
        let h = t / steps as f64;
        for _ in 0..steps {
            let k1 = deriv(&s);
            let k2 = deriv(&axpy(&s, 0.5 * h, &k1));
            let k3 = deriv(&axpy(&s, 0.5 * h, &k2));
            let k4 = deriv(&axpy(&s, h, &k3));
            let mut sum = k1;
            for (kk, w) in [(&k2, 2.0), (&k3, 2.0), (&k4, 1.0)] {
                sum = axpy(&sum, w, kk);
            }
            s = axpy(&s, h / 6.0, &sum);
        }
        s
    }

    /// The periodic orbit of period `t` through a start near `y0` with v₁(0) = 0, by
    /// Gauss–Newton on y(T) − y(0) = 0 over (u₁, u₂, v₂) (4 equations, one redundant by
    /// energy conservation); then its nontrivial multiplier's modulus: Φ is symplectic with
    /// the trivial pair at +1, so the other pair satisfies μ + 1/μ = tr Φ − 2.
    fn shooting_modulus(&self, mut y0: [f64; 4], t: f64, steps: usize) -> (f64, f64) {
        y0[2] = 0.0;
        let free = [0usize, 1, 3];
        let mut gap = f64::INFINITY;
        for _ in 0..20 {
            let (yt, phi) = self.flow(y0, t, steps);
            let r: Vec<f64> = (0..4).map(|i| yt[i] - y0[i]).collect();
            gap = r.iter().map(|x| x * x).sum::<f64>().sqrt();
            if gap < 1e-13 {
                break;
            }
            // J = (Φ − I) on the free columns; normal equations JᵀJ δ = −Jᵀ r (3 × 3).
            let jac = |i: usize, c: usize| phi[i][free[c]] - if i == free[c] { 1.0 } else { 0.0 };
            let mut a = [[0.0; 4]; 3];
            for p in 0..3 {
                for q in 0..3 {
                    a[p][q] = (0..4).map(|i| jac(i, p) * jac(i, q)).sum();
                }
                a[p][3] = -(0..4).map(|i| jac(i, p) * r[i]).sum::<f64>();
            }
            for col in 0..3 {
                let piv = (col..3)
                    .max_by(|&x, &y| a[x][col].abs().total_cmp(&a[y][col].abs()))
                    .unwrap();
                a.swap(col, piv);
                for row in 0..3 {
                    if row != col {
                        let m = a[row][col] / a[col][col];
                        for c in col..4 {
                            a[row][c] -= m * a[col][c];
                        }
                    }
                }
            }
            for (c, &k) in free.iter().enumerate() {
                y0[k] += a[c][3] / a[c][c];
            }
        }
        let (_, phi) = self.flow(y0, t, steps);
        let s = phi[0][0] + phi[1][1] + phi[2][2] + phi[3][3] - 2.0;
        let modulus = if s.abs() <= 2.0 {
            1.0
        } else {
            0.5 * (s.abs() + (s * s - 4.0).sqrt())
        };
        (modulus, gap)
    }
}

/// The engine's orbit of a stored point at the instant its first DOF's velocity vanishes
/// with the displacement at its maximum: a start for the shooting.
fn start_state(coefs: &[Vec<f64>], h: usize, omega: f64) -> [f64; 4] {
    let at = |c: &[f64], th: f64, order: usize| {
        let mut d1 = vec![0.0; c.len()];
        fourier::deriv(c, h, &mut d1);
        match order {
            0 => fourier::eval(c, h, th),
            _ => omega * fourier::eval(&d1, h, th),
        }
    };
    let th = (0..4096)
        .map(|i| 2.0 * std::f64::consts::PI * i as f64 / 4096.0)
        .max_by(|a, b| at(&coefs[0], *a, 0).total_cmp(&at(&coefs[0], *b, 0)))
        .unwrap_or(0.0);
    [
        at(&coefs[0], th, 0),
        at(&coefs[1], th, 0),
        0.0,
        at(&coefs[1], th, 1),
    ]
}

#[test]
fn verdict_matches_shooting_multipliers_outside_the_band() {
    // testcases/stability_2dof.comm's system (k = 10, kc = 1, stop on mass 2, JEU 0.01,
    // RIGI_NOR 50, PARA_REGUL 5e-5), anti-phase family over its fold in energy, computed with
    // a coarse NB_HARM_LINE = 5 so that the orbit carries a visible truncation error (orbit
    // defect up to 1.4e-2 > TOLERANCE). CALC_STABILITE's defaults: NEWMARK, NB_INST 1000,
    // TOLERANCE 1e-2. Reference: shooting on the same law at the row's period, RK4 with
    // 20000 steps (40000 agree to 4e-13 on |μ|; measured).
    let tol = 1e-2;
    let p = pair(1.0, vec![shock(ShockLaw::Plan, vec![1])]);
    let s = settings(5, 100, 25);
    let pts = branch(&p, &s, &[1.0, -1.0], 0.5, 12f64.sqrt());
    let reference = Pair::new(10.0, 1.0, 50.0, 0.01, 5e-5);
    let analyser = FloquetAnalyser::new(&p, &s).unwrap();
    let (mut labels, mut old_false_unstable, mut worst_ratio) = (Vec::new(), 0, 0.0f64);
    for (i, q) in pts.iter().enumerate() {
        let f = analyser
            .floquet(&q.x, 1000, Integrator::Newmark, tol)
            .unwrap();
        let coefs = displacement_coefficients(&p, &s, &q.x).unwrap();
        let y0 = start_state(&coefs, s.harmonics.h_lin, q.omega);
        let t = 2.0 * std::f64::consts::PI / q.omega;
        let (mu, gap) = reference.shooting_modulus(y0, t, 20000);
        assert!(gap < 1e-12, "row {i}: shooting did not close ({gap:e})");
        let got = f.max_nontrivial_modulus;
        // The former rule: the two eigenvalues of Φ closest to +1 taken as the trivial pair.
        let mut by_dist: Vec<(f64, f64)> = f
            .multipliers
            .iter()
            .map(|m| ((m.0 - 1.0).hypot(m.1), m.0.hypot(m.1)))
            .collect();
        by_dist.sort_by(|a, b| a.0.total_cmp(&b.0));
        let old = by_dist.iter().skip(2).map(|d| d.1).fold(0.0, f64::max);
        if old > 1.0 + tol && mu == 1.0 {
            old_false_unstable += 1;
        }
        if mu > 1.0 {
            // The error of μ + 1/μ per unit of orbit defect: what the band is built on.
            let ratio = ((got + 1.0 / got) - (mu + 1.0 / mu)).abs() / f.orbit_defect;
            worst_ratio = worst_ratio.max(ratio);
        }
        eprintln!(
            "row {i:>2} E {:.5e} f {:.6}: shooting {mu:.5} reduced {got:.5} former {old:.5} \
             defect {:.2e} band {:.3} {}",
            q.energy,
            q.frequency,
            f.orbit_defect,
            f.band,
            f.label()
        );
        // Never wrong: INSTABLE only beyond 1 + TOLERANCE, STABLE only on the unit circle
        // (here every stable reference is on it: |s| ≤ 2).
        match f.verdict {
            Verdict::Unstable => assert!(mu > 1.0 + tol, "row {i}: INSTABLE, shooting {mu}"),
            Verdict::Stable => assert!(mu <= 1.0 + tol, "row {i}: STABLE, shooting {mu}"),
            Verdict::Indeterminate => assert!(
                mu <= 1.0 + 1.5 * f.band,
                "row {i}: INDETERMINE, shooting {mu}, band {}",
                f.band
            ),
        }
        labels.push(f.verdict);
    }
    assert!(worst_ratio <= DEFECT_TO_TRACE, "ratio {worst_ratio}");
    // The former rule called stable rows INSTABLE past the fold (its "trivial pair" was the
    // nontrivial one): measured on 2 rows.
    assert!(
        old_false_unstable >= 1,
        "the former rule was right everywhere"
    );
    // One unstable stretch, no flicker: STABLE, INSTABLE, at most one INDETERMINE
    // stretch at its end, STABLE.
    let flips = labels.windows(2).filter(|w| w[0] != w[1]).count();
    assert!(flips <= 3, "{labels:?}");
    let unstable: Vec<usize> = (0..labels.len())
        .filter(|&i| labels[i] == Verdict::Unstable)
        .collect();
    assert!(!unstable.is_empty());
    assert_eq!(
        unstable.len(),
        unstable[unstable.len() - 1] - unstable[0] + 1
    );
}

#[test]
fn the_reduction_takes_out_a_split_trivial_pair_that_the_closest_to_one_rule_keeps() {
    // A hand-built monodromy of 2 DOFs, state (u₁, u₂, v₁, v₂), M = I, ω = 1: the trivial
    // Jordan block in (u₁, v₁) (orbit tangent a = e_u₁, Φ e_v₁ = e_v₁ + e_u₁) and a
    // hyperbolic nontrivial pair μ = 1.02, 1/μ in (u₂, v₂). An error ε = −1e-3 on Φ[v₁, u₁]
    // splits the trivial pair to 1 ± i·√1e-3 = 1 ± 0.0316i, farther from +1 than the
    // nontrivial 1.02 and 0.98: "the two closest to +1" then takes the nontrivial pair for
    // the trivial one and keeps |1 ± 0.0316i| = 1.0005 (STABLE at TOLERANCE 1e-2, wrong).
    // The reduction keeps exactly {1.02, 1/1.02}: the error sits in the trivial block only.
    let mu = 1.02;
    let mut phi = Mat::<f64>::identity(4, 4);
    phi[(0, 2)] = 1.0;
    phi[(1, 1)] = mu;
    phi[(3, 3)] = 1.0 / mu;
    phi[(2, 0)] = -1e-3;
    let m = Mat::<f64>::identity(2, 2);
    let a = [1.0, 0.0, 0.0, 0.0];
    let eig = phi.eigenvalues().unwrap();
    let mut by_dist: Vec<(f64, f64)> = eig
        .iter()
        .map(|z| ((z.re - 1.0).hypot(z.im), z.re.hypot(z.im)))
        .collect();
    by_dist.sort_by(|x, y| x.0.total_cmp(&y.0));
    let old = by_dist.iter().skip(2).map(|d| d.1).fold(0.0, f64::max);
    assert!((old - 1.0).abs() < 1e-3, "the former rule keeps {old}");
    let got = reduce::nontrivial_multipliers(&phi, &m, &a, 1.0).unwrap();
    assert_eq!(got.len(), 2);
    assert!((got[0].0 - mu).abs() < 1e-14 && got[0].1 == 0.0, "{got:?}");
    assert!(
        (got[1].0 - 1.0 / mu).abs() < 1e-14 && got[1].1 == 0.0,
        "{got:?}"
    );
    // The verdict at TOLERANCE 1e-2 with the orbit defect ‖Φa − a‖ = 1e-3 (band
    // √(2e-3) = 0.045): 1.02 is inside the band, INDETERMINE, not the former STABLE.
    assert_eq!(verdict(got[0].0, 1e-3, 1e-2).0, Verdict::Indeterminate);
    assert_eq!(verdict(got[0].0, 1e-5, 1e-2).0, Verdict::Unstable);
}

#[test]
fn the_verdict_has_an_explicit_band() {
    // Band b = max(TOLERANCE, √(2·defect)): STABLE up to 1 + TOLERANCE, INSTABLE beyond
    // 1 + b, INDETERMINE between; a NaN defect never supports INSTABLE.
    assert_eq!(verdict(1.005, 1e-5, 1e-2), (Verdict::Stable, 1e-2));
    assert_eq!(verdict(1.02, 1e-5, 1e-2).0, Verdict::Unstable);
    let (v, b) = verdict(1.05, 2e-3, 1e-2);
    assert!(
        (b - 0.0632455532).abs() < 1e-9 && v == Verdict::Indeterminate,
        "{v:?} {b}"
    );
    assert_eq!(verdict(1.07, 2e-3, 1e-2).0, Verdict::Unstable);
    assert_eq!(verdict(1.005, 2e-3, 1e-2).0, Verdict::Stable);
    assert_eq!(verdict(1.0, f64::NAN, 1e-2).0, Verdict::Stable);
    assert_eq!(verdict(2.0, f64::NAN, 1e-2).0, Verdict::Indeterminate);
}
