//! The cubic spring (RESSORT_CUBIQUE, law/ressort_cubique.rs) against references written
//! here, independently of the engine: Duffing's exact period (the complete elliptic integral
//! by the arithmetic–geometric mean) and the exact Fourier series of its orbit, the
//! one-harmonic closed form, and shooting on a two-DOF chain (own RK4 and Newton).

use super::sparse;
use crate::nnm::*;
use std::f64::consts::PI;

/// K(m) = π / (2·AGM(1, √(1 − m))), the complete elliptic integral of the first kind of
/// parameter m = κ² (0 ≤ m < 1). The AGM converges quadratically: 30 steps are far more
/// than double precision needs for the m < 0.5 of a hardening Duffing spring.
fn elliptic_k(m: f64) -> f64 {
    let (mut a, mut b) = (1.0f64, (1.0 - m).sqrt());
    for _ in 0..30 {
        (a, b) = (0.5 * (a + b), (a * b).sqrt());
    }
    PI / (2.0 * a)
}

/// The exact orbit of m ẍ + k x + k₃ x³ = 0 from rest at amplitude A: x = A cn(ω̃t, κ²),
/// ω̃² = (k + k₃A²)/m, κ² = k₃A²/(2(k + k₃A²)), period T = 4K(κ²)/ω̃.
struct Duffing {
    m: f64,
    k: f64,
    k3: f64,
}

impl Duffing {
    fn kappa2(&self, a: f64) -> f64 {
        self.k3 * a * a / (2.0 * (self.k + self.k3 * a * a))
    }

    fn frequency(&self, a: f64) -> f64 {
        let w = ((self.k + self.k3 * a * a) / self.m).sqrt();
        w / (4.0 * elliptic_k(self.kappa2(a)))
    }

    /// The amplitude of the orbit of total energy E = ½kA² + ¼k₃A⁴.
    fn amplitude(&self, e: f64) -> f64 {
        ((-self.k + (self.k * self.k + 4.0 * self.k3 * e).sqrt()) / self.k3).sqrt()
    }

    /// The orbit's harmonic content beyond `h`, what a truncation to `h` harmonics leaves
    /// out, relative to the first harmonic: (Σ_{j > h} |a_j|, Σ_{j > h} j·|a_j|) / |a_1| over
    /// the cosine coefficients a_j of the displacement in the phase θ = 2πt/T (the second
    /// sum is the velocity's), a_{2n+1} ∝ q^{n+½}/(1 + q^{2n+1}) for cn, with the nome
    /// q = exp(−π K(1 − κ²)/K(κ²)).
    fn tails(&self, a: f64, h: usize) -> (f64, f64) {
        let m = self.kappa2(a);
        let q = (-PI * elliptic_k(1.0 - m) / elliptic_k(m)).exp();
        let c = |n: i32| q.powf(n as f64 + 0.5) / (1.0 + q.powi(2 * n + 1));
        let dropped = (0..60).filter(|&n| (2 * n + 1) as usize > h);
        let u: f64 = dropped.clone().map(c).sum();
        let v: f64 = dropped.map(|n| (2 * n + 1) as f64 * c(n)).sum();
        (u / c(0), v / c(0))
    }

    fn problem(&self) -> Problem {
        Problem {
            forcing: None,
            k: sparse(1, &[(0, 0, self.k)]),
            m: sparse(1, &[(0, 0, self.m)]),
            shocks: vec![spring(0, self.k3)],
        }
    }
}

fn spring(dof: usize, k3: f64) -> Shock {
    Shock {
        law: ShockLaw::RESSORT_CUBIQUE,
        dofs: vec![dof],
        gap: 0.0,
        stiffness: k3,
        regul: 0.0,
    }
}

const DUFFING: Duffing = Duffing {
    m: 1.0,
    k: 1.0,
    k3: 1.0,
};

/// The rows of the family of the first mode from amplitude `coef` (metres: no JEU) up to
/// ENERGIE `top`.
fn branch(
    problem: &Problem,
    s: &Settings,
    mode: &[f64],
    omega: f64,
    coef: f64,
    top: f64,
) -> Vec<Point> {
    let st = start_from_mode(problem, s, mode, coef, omega).unwrap();
    let out = continue_while(problem, s, st, &mut |r, _| r.energy_range.1 <= top);
    assert!(out.error.is_none(), "{:?}", out.error);
    out.points
}

/// u(0) of DOF `d` of a row: with the phase condition (zero velocity at t = 0) a turning
/// point, the amplitude of a brake orbit: the sum of its cosine coefficients.
fn start_displacement(x: &[f64], h: usize, d: usize) -> f64 {
    x[d * (2 * h + 1)..d * (2 * h + 1) + h + 1].iter().sum()
}

/// The continuation's own error, added to the truncation's: the rows inside a branch are
/// on the ANM series, whose residual is bounded by PREC_MAN (1e-9 here), the branch ends
/// Newton-corrected to PREC_NEWTON (1e-9); ten times that in relative frequency.
const FLOOR: f64 = 1e-8;

/// What one run of the Duffing family measures (`duffing_errors`).
struct Errors {
    /// Largest relative frequency error at the rows' amplitudes (their coefficients).
    amplitude: f64,
    /// The same at the rows' ENERGIE.
    energy: f64,
    /// The rows' largest ratio of the error at the amplitude to the displacement's tail
    /// (`Duffing::tails`) plus [`FLOOR`], and of the error at ENERGIE to the velocity's.
    amplitude_to_tail: f64,
    energy_to_tail: f64,
    /// The largest error beyond the tails (the continuation's own: PREC_MAN, PREC_NEWTON).
    beyond: f64,
    rows: usize,
}

/// The Duffing family with `h` harmonics (`hn` for the recast) up to k₃A²/k = `eps_top`,
/// each row against the exact frequency at its own amplitude and at its ENERGIE.
fn duffing_errors(h: usize, hn: usize, eps_top: f64) -> Errors {
    let d = DUFFING;
    let p = d.problem();
    let s = super::settings(h, hn, 60, 2);
    let a_top = (eps_top * d.k / d.k3).sqrt();
    let top = 0.5 * d.k * a_top * a_top + 0.25 * d.k3 * a_top.powi(4);
    let pts = branch(&p, &s, &[1.0], (d.k / d.m).sqrt(), 0.1, top);
    let mut e = Errors {
        amplitude: 0.0,
        energy: 0.0,
        amplitude_to_tail: 0.0,
        energy_to_tail: 0.0,
        beyond: 0.0,
        rows: 0,
    };
    for pt in pts.iter().filter(|pt| pt.energy <= top) {
        let a = start_displacement(&pt.x, h, 0).abs();
        let at_amp = (pt.frequency / d.frequency(a) - 1.0).abs();
        let ae = d.amplitude(pt.energy);
        let at_energy = (pt.frequency / d.frequency(ae) - 1.0).abs();
        let (tu, tv) = d.tails(ae, h);
        e.amplitude = e.amplitude.max(at_amp);
        e.energy = e.energy.max(at_energy);
        e.amplitude_to_tail = e.amplitude_to_tail.max(at_amp / (tu + FLOOR));
        e.energy_to_tail = e.energy_to_tail.max(at_energy / (tv + FLOOR));
        e.beyond = e.beyond.max(at_amp - tu).max(at_energy - tv);
        e.rows += 1;
    }
    e
}

/// The references themselves: K(0) = π/2, K(½) = Γ(¼)²/(4√π), and the exact frequency
/// against the Lindstedt series ω = ω₀(1 + ⅜ε − 21/256 ε²) at small ε = k₃A²/k.
#[test]
fn the_references_are_right() {
    assert!((elliptic_k(0.0) - PI / 2.0).abs() < 1e-15);
    // Γ(1/4) = 3.625609908221908...
    let gamma_quarter = 3.625_609_908_221_908_f64;
    let k_half = gamma_quarter * gamma_quarter / (4.0 * PI.sqrt());
    assert!(
        (elliptic_k(0.5) - k_half).abs() < 1e-14,
        "{}",
        elliptic_k(0.5)
    );
    let d = DUFFING;
    let eps: f64 = 1e-3;
    let w = 2.0 * PI * d.frequency(eps.sqrt());
    let lindstedt = 1.0 + 3.0 / 8.0 * eps - 21.0 / 256.0 * eps * eps;
    // The series' next term is O(ε³) = 1e-9.
    assert!((w / lindstedt - 1.0).abs() < 1e-8, "{w} {lindstedt}");
    // The tail of a one-harmonic orbit is the third harmonic ≈ ε/32 at small ε (Lindstedt).
    let (tu, tv) = d.tails(eps.sqrt(), 1);
    assert!((tu / (eps / 32.0) - 1.0).abs() < 1e-2 && (tv / tu - 3.0).abs() < 1e-2);
}

/// With one harmonic (NB_HARM_LINE = 1, NB_HARM_NONL ≥ 2) the harmonic balance of Duffing
/// IS the closed form ω² = k/m + ¾(k₃/m)A² at every amplitude (u = A cos θ, the first
/// harmonic of u³ is ¾A³): FREQUENCE matches it to the continuation's accuracy, from
/// ε = 0.015 past 14 (measured 2.9e-11 at most, `duffing_accuracy_table`). With too
/// few contact harmonics (NB_HARM_NONL = 1) w = u² loses its second harmonic and the
/// balance gives ω² = k/m + ½(k₃/m)A² instead: the recast's truncation, as documented.
#[test]
fn one_harmonic_is_the_closed_form() {
    let d = DUFFING;
    let p = d.problem();
    let closed = |a: f64, c: f64| ((d.k + c * d.k3 * a * a) / d.m).sqrt() / (2.0 * PI);
    for hn in [2, 3] {
        let s = super::settings(1, hn, 40, 2);
        let pts = branch(&p, &s, &[1.0], 1.0, 0.1, 60.0);
        assert!(pts.last().unwrap().energy > 30.0, "{}", pts.len());
        // The rows inside a branch are on the ANM series (residual within PREC_MAN = 1e-9):
        // measured 2.9e-11 at most.
        for pt in &pts {
            let a = start_displacement(&pt.x, 1, 0).abs();
            let e = (pt.frequency / closed(a, 0.75) - 1.0).abs();
            assert!(e < 1e-9, "H_nl {hn}, A {a}: {e:e}");
        }
    }
    let s = super::settings(1, 1, 10, 2);
    let pts = branch(&p, &s, &[1.0], 1.0, 0.1, 5.0);
    let pt = pts.last().unwrap();
    let a = start_displacement(&pt.x, 1, 0).abs();
    assert!((pt.frequency / closed(a, 0.5) - 1.0).abs() < 1e-9);
}

/// FREQUENCE against the exact period, at each row's amplitude (its Fourier coefficients)
/// and at its ENERGIE (½kA² + ¼k₃A⁴ for the brake orbit), from k₃A²/k = 0.01 to 10
/// (κ² up to 0.45). The truncation to NB_HARM_LINE harmonics drops the exact orbit's
/// harmonics beyond it (`Duffing::tails`); the rows' measures feel that at first order: the
/// amplitude u(0) = Σ a_j misses the displacement's tail, so the frequency read at it is off
/// by at most d ln f/d ln A ≤ 1 times that tail; ENERGIE = ½ m v(π/2)² misses twice the
/// velocity's tail Σ j·a_j, and d ln f/d ln E ≤ ½, so at most that tail. Those are the
/// bounds asserted, each plus [`FLOOR`] (measured: 0.86 and 0.49 of them at most; the rows
/// beyond their tails by 2.8e-11 at most). The errors then fall with the
/// tails, geometrically: at least 15 times per two harmonics (measured 27 to 37).
/// NB_HARM_NONL = 2·NB_HARM_LINE (the least for which the recast is exact on the
/// structure's harmonics) meets the same bounds as 3·NB_HARM_LINE.
#[test]
fn duffing_frequency_follows_the_exact_period() {
    for hn_per_h in [3, 2] {
        let mut last: Option<Errors> = None;
        for h in [3, 5, 7, 9] {
            let e = duffing_errors(h, hn_per_h * h, 10.0);
            assert!(e.rows > 20, "H {h}: {} rows", e.rows);
            assert!(
                e.amplitude_to_tail <= 1.0 && e.energy_to_tail <= 1.0,
                "H {h}, H_nl {}: {} {}",
                hn_per_h * h,
                e.amplitude_to_tail,
                e.energy_to_tail
            );
            if let Some(l) = &last {
                assert!(
                    e.amplitude * 15.0 <= l.amplitude && e.energy * 15.0 <= l.energy,
                    "H {h}: {:e} after {:e}, {:e} after {:e}",
                    e.amplitude,
                    l.amplitude,
                    e.energy,
                    l.energy
                );
            }
            last = Some(e);
        }
    }
}

/// The accuracy table of docs/mode_non_line.md ("Cubic springs"): `cargo test --release
/// --lib duffing_accuracy_table -- --ignored --nocapture`.
#[test]
#[ignore]
fn duffing_accuracy_table() {
    println!("| NB_HARM_LINE | rows | at the amplitude | / (tail + floor) | at ENERGIE | / (tail + floor) | beyond the tails |");
    // NB_HARM_LINE = 1 against the one-harmonic closed form (one_harmonic_is_the_closed_form).
    let d = DUFFING;
    let s = super::settings(1, 2, 40, 2);
    let pts = branch(&d.problem(), &s, &[1.0], 1.0, 0.1, 60.0);
    let closed = pts
        .iter()
        .map(|pt| {
            let a = start_displacement(&pt.x, 1, 0).abs();
            let f = ((d.k + 0.75 * d.k3 * a * a) / d.m).sqrt() / (2.0 * PI);
            (pt.frequency / f - 1.0).abs()
        })
        .fold(0.0f64, f64::max);
    println!(
        "NB_HARM_LINE 1 against the closed form: {closed:.1e} at most over {} rows",
        pts.len()
    );
    for h in [1, 3, 5, 7, 9, 11] {
        let e = duffing_errors(h, 3 * h, 10.0);
        println!(
            "| {h} | {} | {:.1e} | {:.2} | {:.1e} | {:.2} | {:.1e} |",
            e.rows, e.amplitude, e.amplitude_to_tail, e.energy, e.energy_to_tail, e.beyond
        );
    }
}

/// Two masses (1 and 2 kg) on ground springs (1 and 2 N/m) coupled by 0.5 N/m, a cubic
/// spring k₃ = 10 N/m³ on the first: linear frequencies 1 and √1.75 rad/s, the first mode
/// (1, 1).
struct Chain {
    k: [[f64; 2]; 2],
    m: [f64; 2],
    k3: f64,
}

const CHAIN: Chain = Chain {
    k: [[1.5, -0.5], [-0.5, 2.5]],
    m: [1.0, 2.0],
    k3: 10.0,
};

/// The chain's family is followed up to this frequency, 8 % above the linear one: the
/// cubic force is then about 7 times the linear at the first DOF, which the family
/// thereby holds nearly still. Beyond, the frequency saturates at that of the second mass
/// alone, √(2.5/2)/(2π) = 0.1779 Hz, and the energy grows without bound.
const CHAIN_TOP: f64 = 0.172;

impl Chain {
    fn problem(&self) -> Problem {
        let k = &self.k;
        Problem {
            forcing: None,
            k: sparse(
                2,
                &[
                    (0, 0, k[0][0]),
                    (0, 1, k[0][1]),
                    (1, 0, k[1][0]),
                    (1, 1, k[1][1]),
                ],
            ),
            m: sparse(2, &[(0, 0, self.m[0]), (1, 1, self.m[1])]),
            shocks: vec![spring(0, self.k3)],
        }
    }

    /// ẏ for y = (u₁, u₂, v₁, v₂): M v̇ = −K u − (k₃u₁³, 0).
    fn rhs(&self, y: [f64; 4]) -> [f64; 4] {
        let k = &self.k;
        let f0 = k[0][0] * y[0] + k[0][1] * y[1] + self.k3 * y[0].powi(3);
        let f1 = k[1][0] * y[0] + k[1][1] * y[1];
        [y[2], y[3], -f0 / self.m[0], -f1 / self.m[1]]
    }

    /// ENERGIE of a state at rest: ½uᵀKu + ¼k₃u₁⁴.
    fn energy_at_rest(&self, u: [f64; 2]) -> f64 {
        let k = &self.k;
        0.5 * (k[0][0] * u[0] * u[0] + 2.0 * k[0][1] * u[0] * u[1] + k[1][1] * u[1] * u[1])
            + 0.25 * self.k3 * u[0].powi(4)
    }

    /// RK4 from rest at `u0` over [0, τ] in `n` steps: the states at every step.
    fn integrate(&self, u0: [f64; 2], tau: f64, n: usize) -> Vec<[f64; 4]> {
        let h = tau / n as f64;
        let mut y = [u0[0], u0[1], 0.0, 0.0];
        let mut out = Vec::with_capacity(n + 1);
        out.push(y);
        let add = |a: [f64; 4], b: [f64; 4], c: f64| {
            [
                a[0] + c * b[0],
                a[1] + c * b[1],
                a[2] + c * b[2],
                a[3] + c * b[3],
            ]
        };
        for _ in 0..n {
            let k1 = self.rhs(y);
            let k2 = self.rhs(add(y, k1, 0.5 * h));
            let k3 = self.rhs(add(y, k2, 0.5 * h));
            let k4 = self.rhs(add(y, k3, h));
            for i in 0..4 {
                y[i] += h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
            }
            out.push(y);
        }
        out
    }

    /// The brake orbit of ENERGIE `e` (the orbit's total energy, at rest at t = 0) near
    /// rest state `u0` with half period near `tau`: Newton on (u₁(0), u₂(0), τ) for
    /// v(τ) = 0 and ENERGIE = e, finite-difference Jacobian. Returns (u(0), τ).
    fn shoot(&self, e: f64, mut u0: [f64; 2], mut tau: f64, n: usize) -> ([f64; 2], f64) {
        let res = |u0: [f64; 2], tau: f64| {
            let y = self.integrate(u0, tau, n)[n];
            [y[2], y[3], self.energy_at_rest(u0) / e - 1.0]
        };
        for _ in 0..30 {
            let r = res(u0, tau);
            if r.iter().all(|v| v.abs() < 1e-14) {
                break;
            }
            let scale = u0[0].abs().max(u0[1].abs());
            let mut jac = [[0.0; 3]; 3];
            for c in 0..3 {
                let (mut u, mut t) = (u0, tau);
                let d = if c < 2 { 1e-7 * scale } else { 1e-7 * tau };
                match c {
                    0 => u[0] += d,
                    1 => u[1] += d,
                    _ => t += d,
                }
                let rp = res(u, t);
                for (row, (p, q)) in jac.iter_mut().zip(rp.iter().zip(&r)) {
                    row[c] = (p - q) / d;
                }
            }
            let dx = solve3(jac, [-r[0], -r[1], -r[2]]);
            u0 = [u0[0] + dx[0], u0[1] + dx[1]];
            tau += dx[2];
        }
        (u0, tau)
    }
}

/// Cramer's rule for a 3×3 system.
fn solve3(a: [[f64; 3]; 3], b: [f64; 3]) -> [f64; 3] {
    let det = |m: [[f64; 3]; 3]| {
        m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1])
            - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
            + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0])
    };
    let d = det(a);
    let mut x = [0.0; 3];
    for (c, xc) in x.iter_mut().enumerate() {
        let mut m = a;
        for row in m.iter_mut().zip(b) {
            row.0[c] = row.1;
        }
        *xc = det(m) / d;
    }
    x
}

/// The relative velocity tail Σ_{j > h} j·|a_j| / |a_1| of the reference orbit's DOF
/// `d`: its cosine coefficients over the period 2τ by the trapezoidal rule on the RK4
/// states of the half period (the orbit is even in time: spectrally accurate).
fn velocity_tail(states: &[[f64; 4]], d: usize, h: usize) -> f64 {
    let n = states.len() - 1;
    let coef = |j: usize| {
        let w = |i: usize| if i == 0 || i == n { 0.5 } else { 1.0 };
        (0..=n)
            .map(|i| w(i) * states[i][d] * (j as f64 * PI * i as f64 / n as f64).cos())
            .sum::<f64>()
            * 2.0
            / n as f64
    };
    let a1 = coef(1).abs();
    (h + 1..40).map(|j| j as f64 * coef(j).abs()).sum::<f64>() / a1
}

/// What the chain's comparison measures at `NB_HARM_LINE` = h (`chain_errors`).
struct ChainErrors {
    /// The largest |FREQUENCE/f_ref − 1| over the rows compared.
    worst: f64,
    /// Its largest ratio to the bound.
    ratio: f64,
    /// The reference's own accuracy (RK4 with 4000 against 8000 steps), at worst.
    reference: f64,
    rows: usize,
}

/// The chain's rows against shooting at their ENERGIE, at 5 rows spread up to
/// [`CHAIN_TOP`]. The bound is the one-DOF argument's: ENERGIE = ½vᵀMv at ωt = π/2 misses
/// at most twice the largest velocity tail of the reference orbit beyond NB_HARM_LINE over
/// the DOFs (`velocity_tail`), and the frequency read at it is off by d ln f/d ln E (of the
/// reference, by shooting at E·(1 ± 1e-3)) times that, plus [`FLOOR`].
fn chain_errors(h: usize) -> ChainErrors {
    let c = CHAIN;
    let p = c.problem();
    let s = super::settings(h, 3 * h, 60, 2);
    let st = start_from_mode(&p, &s, &[1.0, 1.0], 0.05, 1.0).unwrap();
    let out = continue_while(&p, &s, st, &mut |r, _| r.freq_range.1 <= CHAIN_TOP);
    assert!(out.error.is_none(), "{:?}", out.error);
    let rows: Vec<&Point> = out
        .points
        .iter()
        .filter(|pt| pt.frequency <= CHAIN_TOP)
        .collect();
    let n = rows.len();
    let mut e = ChainErrors {
        worst: 0.0,
        ratio: 0.0,
        reference: 0.0,
        rows: n,
    };
    for i in [n / 5, 2 * n / 5, 3 * n / 5, 4 * n / 5, n - 1] {
        let pt = rows[i];
        let u0 = [
            start_displacement(&pt.x, h, 0),
            start_displacement(&pt.x, h, 1),
        ];
        let (u, tau) = c.shoot(pt.energy, u0, 0.5 / pt.frequency, 4000);
        let (u, tau_fine) = c.shoot(pt.energy, u, tau, 8000);
        e.reference = e.reference.max((tau_fine / tau - 1.0).abs());
        let f_ref = 0.5 / tau_fine;
        let (_, up) = c.shoot(pt.energy * 1.001, u, tau_fine, 4000);
        let (_, down) = c.shoot(pt.energy * 0.999, u, tau_fine, 4000);
        let slope = (down / up).ln() / (1.001f64 / 0.999).ln();
        let states = c.integrate(u, tau_fine, 4000);
        let tail = velocity_tail(&states, 0, h).max(velocity_tail(&states, 1, h));
        let bound = slope.abs() * 2.0 * tail + FLOOR;
        let err = (pt.frequency / f_ref - 1.0).abs();
        e.worst = e.worst.max(err);
        e.ratio = e.ratio.max(err / bound);
    }
    e
}

/// The chain against shooting: within the bound (measured 0.27 of it at most), the
/// reference far more accurate than the errors it measures (measured 5e-15), the errors
/// falling at least 8 times per two harmonics (the reference's tail at the top row falls
/// 16 to 18 times; the errors 11 to 18 times, the first step less because the error of
/// NB_HARM_LINE = 3 changes sign along the branch).
#[test]
fn two_dof_chain_matches_shooting() {
    let mut last = f64::INFINITY;
    for h in [3, 5, 7] {
        let e = chain_errors(h);
        assert!(e.rows > 10, "H {h}: {} rows", e.rows);
        assert!(e.reference < 1e-11, "H {h}: reference to {:e}", e.reference);
        assert!(
            e.ratio <= 1.0,
            "H {h}: error {:e}, {} of the bound",
            e.worst,
            e.ratio
        );
        assert!(e.worst * 8.0 <= last, "H {h}: {:e} after {last:e}", e.worst);
        last = e.worst;
    }
}

/// The two-DOF rows of the accuracy table: `cargo test --release --lib chain_accuracy_table
/// -- --ignored --nocapture`.
#[test]
#[ignore]
fn chain_accuracy_table() {
    println!("| NB_HARM_LINE | rows | largest error at ENERGIE (5 rows) | / bound | reference |");
    for h in [1, 3, 5, 7, 9] {
        let e = chain_errors(h);
        println!(
            "| {h} | {} | {:.1e} | {:.2} | {:.0e} |",
            e.rows, e.worst, e.ratio, e.reference
        );
    }
}
