//! Forced responses (`Problem::forcing`, REPONSE_FORCEE_NL) against references written
//! here without the engine: the linear frequency response in closed form (one DOF) and by a
//! complex 2×2 solve (two DOFs), and the periodic steady state of the same regularised
//! impact oscillator found by shooting (own RK4, own Newton) at points of the curve.

use super::{settings, sparse};
use crate::nnm::{
    continue_while, peak_amplitude, start_forced, Forcing, Point, Problem, Settings, Shock,
    ShockLaw,
};
use std::f64::consts::PI;

/// m, k, c, F of the one-DOF oscillator (sdnd122's mass and spring, 1.6 % damping).
pub(crate) const M: f64 = 1.0;
pub(crate) const K: f64 = 10.0;
pub(crate) const C: f64 = 0.1;
pub(crate) const F: f64 = 0.01;

pub(crate) fn forced(
    k: &[(usize, usize, f64)],
    m: &[(usize, usize, f64)],
    c: &[(usize, usize, f64)],
    f: Vec<f64>,
    shocks: Vec<Shock>,
) -> Problem {
    let n = f.len();
    Problem {
        k: sparse(n, k),
        m: sparse(n, m),
        shocks,
        forcing: Some(Forcing {
            damping: sparse(n, c),
            force: f,
        }),
    }
}

pub(crate) fn plan(gap: f64, stiffness: f64, regul: f64) -> Shock {
    Shock {
        law: ShockLaw::Plan,
        dofs: vec![0],
        gap,
        stiffness,
        regul,
    }
}

/// The curve from `f_min` Hz until it passes `f_max` (the start point first).
pub(crate) fn curve(p: &Problem, s: &Settings, f_min: f64, f_max: f64) -> Vec<Point> {
    let start = start_forced(p, s, 2.0 * PI * f_min).unwrap();
    let mut points = vec![start.point.clone()];
    let out = continue_while(p, s, start, &mut |_, pts| {
        pts.last().is_none_or(|q| q.frequency <= f_max)
    });
    assert!(out.error.is_none(), "{:?}", out.error);
    points.extend(out.points);
    assert!(
        points.last().unwrap().frequency > f_max,
        "the curve did not cross the band"
    );
    points
}

/// (C1, S1) of DOF `i` and the largest |coefficient| of its harmonics 0 and 2..H.
fn first_harmonic(p: &Point, i: usize, h: usize) -> ((f64, f64), f64) {
    let nl = 2 * h + 1;
    let u = &p.x[i * nl..(i + 1) * nl];
    let others = (0..nl)
        .filter(|&j| j != 1 && j != h + 1)
        .fold(0.0f64, |a, j| a.max(u[j].abs()));
    ((u[1], u[h + 1]), others)
}

/// Without shocks the curve is the linear frequency response x = Re(X e^{iωt}),
/// X = F/(k − mω² + icω), at every row, to round-off (1e-10 relative: the rows are
/// Newton-corrected or series points to PREC_MAN 1e-12 on a linear problem whose
/// series is exact from order 2 on), through the resonance at 0.503 Hz; no harmonic
/// other than the first.
#[test]
fn one_dof_linear_is_the_closed_form_response() {
    let p = forced(&[(0, 0, K)], &[(0, 0, M)], &[(0, 0, C)], vec![F], vec![]);
    let mut s = settings(3, 3, 400, 3);
    s.continuation.prec_man = 1e-12;
    s.continuation.prec_newton = 1e-12;
    let points = curve(&p, &s, 0.2, 1.0);
    assert!(points.len() > 10);
    let mut passed_peak = false;
    for q in &points {
        let w = q.omega;
        let (re, im) = (K - M * w * w, C * w);
        let d = re * re + im * im;
        // X = F (re − i im)/d; x = Re(X e^{iωt}) = Re X cos − Im X sin.
        let (c1, s1) = (F * re / d, F * im / d);
        let ((a, b), others) = first_harmonic(q, 0, 3);
        let amp = F / d.sqrt();
        assert!(
            (a - c1).abs() <= 1e-10 * amp,
            "{} Hz: C1 {a} against {c1}",
            q.frequency
        );
        assert!(
            (b - s1).abs() <= 1e-10 * amp,
            "{} Hz: S1 {b} against {s1}",
            q.frequency
        );
        assert!(others <= 1e-12 * amp);
        let peak = peak_amplitude(&q.x[..7], 3);
        assert!((peak - amp).abs() <= 1e-10 * amp);
        passed_peak |= (w - (K / M).sqrt()).abs() < 0.01;
    }
    assert!(passed_peak, "no row within 0.01 rad/s of the resonance");
}

/// Two DOFs (a chain with a full damping matrix): the first harmonic against the complex
/// solve of (K − ω²M + iωC) X = F written here (Cramer's rule), 1e-10 relative.
#[test]
fn two_dof_linear_is_the_complex_solve() {
    let k = [(0, 0, 20.0), (0, 1, -10.0), (1, 0, -10.0), (1, 1, 10.0)];
    let m = [(0, 0, 1.0), (1, 1, 0.5)];
    let c = [(0, 0, 0.08), (0, 1, -0.03), (1, 0, -0.03), (1, 1, 0.05)];
    let f = vec![0.0, 0.02];
    let p = forced(&k, &m, &c, f.clone(), vec![]);
    let mut s = settings(2, 2, 600, 2);
    s.continuation.prec_man = 1e-12;
    s.continuation.prec_newton = 1e-12;
    let points = curve(&p, &s, 0.1, 1.2);
    type Cx = (f64, f64);
    let mul = |a: Cx, b: Cx| (a.0 * b.0 - a.1 * b.1, a.0 * b.1 + a.1 * b.0);
    let sub = |a: Cx, b: Cx| (a.0 - b.0, a.1 - b.1);
    let div = |a: Cx, b: Cx| {
        let d = b.0 * b.0 + b.1 * b.1;
        ((a.0 * b.0 + a.1 * b.1) / d, (a.1 * b.0 - a.0 * b.1) / d)
    };
    for q in &points {
        let w = q.omega;
        let entry = |i: usize, j: usize| -> Cx {
            let get = |e: &[(usize, usize, f64)]| {
                e.iter()
                    .filter(|t| t.0 == i && t.1 == j)
                    .map(|t| t.2)
                    .sum::<f64>()
            };
            (get(&k) - w * w * get(&m), w * get(&c))
        };
        let (a, b, cc, d) = (entry(0, 0), entry(0, 1), entry(1, 0), entry(1, 1));
        let det = sub(mul(a, d), mul(b, cc));
        let (f0, f1) = ((f[0], 0.0), (f[1], 0.0));
        let x = [
            div(sub(mul(f0, d), mul(b, f1)), det),
            div(sub(mul(a, f1), mul(cc, f0)), det),
        ];
        let scale = x.iter().map(|z| z.0.hypot(z.1)).fold(0.0, f64::max);
        for (i, xi) in x.iter().enumerate() {
            let ((c1, s1), others) = first_harmonic(q, i, 2);
            assert!(
                (c1 - xi.0).abs() <= 1e-10 * scale,
                "{} Hz DOF {i}",
                q.frequency
            );
            assert!(
                (s1 + xi.1).abs() <= 1e-10 * scale,
                "{} Hz DOF {i}",
                q.frequency
            );
            assert!(others <= 1e-12 * scale);
        }
    }
}

/// A PLAN stop never reached (JEU 10 times the largest linear amplitude): the curve is
/// the linear response up to the regularised law's force in the gap, f ≈ η/(g − u) with
/// η = PARA_REGUL·k·g² (k_ref = k on one DOF, g = JEU), which is η/g (1 + u/g + ...): a
/// constant push −η/g, hence a mean displacement −PARA_REGUL·g, and a stiffness
/// PARA_REGUL·k. At PARA_REGUL 1e-13 the stiffness moves the first harmonic by about 1e-13
/// relative (3e-12 at the peak, 1/(2ζ) times more): it must equal the linear response to
/// 1e-10. The lengths of the engine are in units of JEU, and PREC_MAN bounds the series'
/// error in those units: PREC_MAN 1e-14 is 1e-14·JEU, below 3e-12 of the smallest
/// amplitude of the band (JEU/A ≤ 270 at 0.2 Hz). The mean must be −PARA_REGUL·g to 1e-2
/// (its next term is the mean of (u/g)², A²/(2g²) ≤ 5e-3 of it).
#[test]
fn a_stop_never_reached_leaves_the_linear_response() {
    let peak = F / (C * (K / M).sqrt());
    let (gap, regul) = (10.0 * peak, 1e-13);
    let p = forced(
        &[(0, 0, K)],
        &[(0, 0, M)],
        &[(0, 0, C)],
        vec![F],
        vec![plan(gap, 50.0, regul)],
    );
    let mut s = settings(3, 6, 600, 3);
    s.continuation.prec_man = 1e-14;
    s.continuation.prec_newton = 1e-13;
    let points = curve(&p, &s, 0.2, 1.0);
    for q in &points {
        let w = q.omega;
        let amp = F / ((K - M * w * w).powi(2) + (C * w).powi(2)).sqrt();
        let ((c1, s1), _) = first_harmonic(q, 0, 3);
        let got = c1.hypot(s1);
        assert!(
            (got - amp).abs() <= 1e-10 * amp,
            "{} Hz: {got} against {amp}",
            q.frequency
        );
        let mean = q.x[0];
        assert!(
            (mean + regul * gap).abs() <= 1e-2 * regul * gap,
            "{} Hz: mean {mean}",
            q.frequency
        );
    }
}

/// The regularised PLAN force of the engine's law (docs/ehman.md §2) in physical units,
/// its positive root written here: f² − α f (u − g) − α η = 0, η = PARA_REGUL·k·g².
pub(crate) fn plan_force(u: f64, g: f64, alpha: f64, eta: f64) -> f64 {
    let b = alpha * (u - g);
    // The root without cancellation on either side of the stop.
    if b >= 0.0 {
        0.5 * (b + (b * b + 4.0 * alpha * eta).sqrt())
    } else {
        2.0 * alpha * eta / ((b * b + 4.0 * alpha * eta).sqrt() - b)
    }
}

/// m ẍ + c ẋ + k x + f(x) = F cos ωt, one RK4 step of `dt` from (x, v) at time t.
pub(crate) fn rk4(x: f64, v: f64, t: f64, dt: f64, w: f64, law: &dyn Fn(f64) -> f64) -> (f64, f64) {
    let acc = |x: f64, v: f64, t: f64| (F * (w * t).cos() - C * v - K * x - law(x)) / M;
    let (k1x, k1v) = (v, acc(x, v, t));
    let (k2x, k2v) = (
        v + 0.5 * dt * k1v,
        acc(x + 0.5 * dt * k1x, v + 0.5 * dt * k1v, t + 0.5 * dt),
    );
    let (k3x, k3v) = (
        v + 0.5 * dt * k2v,
        acc(x + 0.5 * dt * k2x, v + 0.5 * dt * k2v, t + 0.5 * dt),
    );
    let (k4x, k4v) = (v + dt * k3v, acc(x + dt * k3x, v + dt * k3v, t + dt));
    (
        x + dt / 6.0 * (k1x + 2.0 * k2x + 2.0 * k3x + k4x),
        v + dt / 6.0 * (k1v + 2.0 * k2v + 2.0 * k3v + k4v),
    )
}

/// One forcing period from (x0, v0) at t = 0 in `steps` RK4 steps: the end state and the
/// largest |x| met (at the steps: (ωdt)²/8 relative at most below the true one, 1e-10
/// at 20 000 steps).
pub(crate) fn period(
    x0: f64,
    v0: f64,
    w: f64,
    steps: usize,
    law: &dyn Fn(f64) -> f64,
) -> ((f64, f64), f64) {
    let dt = 2.0 * PI / w / steps as f64;
    let (mut x, mut v, mut big) = (x0, v0, x0.abs());
    for i in 0..steps {
        (x, v) = rk4(x, v, i as f64 * dt, dt, w, law);
        big = big.max(x.abs());
    }
    ((x, v), big)
}

/// The periodic steady state at ω by shooting: Newton on (x(T) − x0, v(T) − v0) with a
/// finite-difference Jacobian, from the guess (x0, v0); its state at t = 0.
pub(crate) fn shooting_state(x0: f64, v0: f64, w: f64, law: &dyn Fn(f64) -> f64) -> (f64, f64) {
    let steps = 20_000;
    let (mut x, mut v) = (x0, v0);
    for _ in 0..20 {
        let ((xe, ve), _) = period(x, v, w, steps, law);
        let (rx, rv) = (xe - x, ve - v);
        if rx.hypot(rv) < 1e-14 {
            break;
        }
        let h = 1e-7;
        let ((xa, va), _) = period(x + h, v, w, steps, law);
        let ((xb, vb), _) = period(x, v + h, w, steps, law);
        let j = [
            [(xa - xe) / h - 1.0, (xb - xe) / h],
            [(va - ve) / h, (vb - ve) / h - 1.0],
        ];
        let det = j[0][0] * j[1][1] - j[0][1] * j[1][0];
        x -= (j[1][1] * rx - j[0][1] * rv) / det;
        v -= (-j[1][0] * rx + j[0][0] * rv) / det;
    }
    (x, v)
}

/// The largest |x| of the periodic steady state found by shooting from (x0, v0).
fn shooting_amplitude(x0: f64, v0: f64, w: f64, law: &dyn Fn(f64) -> f64) -> f64 {
    let (x, v) = shooting_state(x0, v0, w, law);
    period(x, v, w, 20_000, law).1
}

/// The one-DOF impact oscillator (sdnd122's wall: JEU 0.01, RIGI_NOR 50, PARA_REGUL
/// 1e-4; 1.6 % damping, F = 0.01 N, whose linear peak is three times the gap): the
/// curve bends right and folds twice. At rows on its two stable branches (the upper one
/// before the first fold, in contact at 1.5 and 2.5 gaps, and the lower one after the
/// second, clear of the stop below 0.8 gap: the lower fold is at grazing) the amplitude equals the periodic steady state
/// of the same regularised law found by shooting (written above, started from the row's
/// state at t = 0). The difference is the harmonic-balance truncation, measured at the
/// three rows: 7.8e-5, 2.6e-5, 1.2e-8 with NB_HARM_LINE 10 (NB_HARM_NONL 100), 2.7e-6,
/// 2.0e-6, 1e-10 with 20 (200); the bounds are five times the worst (4e-4, 1.5e-5), and
/// the finer balance must be closer at every level. The shooting's own error (RK4 at
/// 20 000 steps a period, the maximum taken at the steps: (ωΔt)²/8 = 1.2e-8 relative at
/// most) is far below both.
#[test]
fn impact_oscillator_matches_shooting_on_its_stable_branches() {
    let (g, alpha, regul) = (0.01, 50.0, 1e-4);
    let eta = regul * K * g * g;
    let law = move |x: f64| plan_force(x, g, alpha, eta);
    let p = forced(
        &[(0, 0, K)],
        &[(0, 0, M)],
        &[(0, 0, C)],
        vec![F],
        vec![plan(g, alpha, regul)],
    );
    let errors = |h: usize| -> Vec<f64> {
        let mut s = settings(h, 10 * h, 300, 4);
        s.continuation.det_test = false;
        let rows = curve(&p, &s, 0.3, 0.8);
        let amp = |q: &Point| peak_amplitude(&q.x[..2 * h + 1], h);
        // The folds: where the frequency steps change sign.
        let turns: Vec<usize> = (1..rows.len() - 1)
            .filter(|&i| {
                (rows[i].frequency - rows[i - 1].frequency)
                    * (rows[i + 1].frequency - rows[i].frequency)
                    < 0.0
            })
            .collect();
        assert_eq!(
            turns.len(),
            2,
            "H {h}: two folds expected, at rows {turns:?}"
        );
        let upper = &rows[..turns[0]];
        let lower = &rows[turns[1] + 1..];
        let picked = [
            upper.iter().find(|q| amp(q) > 1.5 * g),
            upper.iter().find(|q| amp(q) > 2.5 * g),
            lower.iter().find(|q| amp(q) < 0.8 * g),
        ];
        picked
            .iter()
            .map(|q| {
                let q = q.expect("a row at that level");
                let (w, u) = (q.omega, &q.x[..2 * h + 1]);
                let x0: f64 = u[..h + 1].iter().sum();
                let v0: f64 = (1..=h).map(|k| k as f64 * w * u[h + k]).sum();
                let reference = shooting_amplitude(x0, v0, w, &law);
                let e = (amp(q) - reference).abs() / reference;
                eprintln!(
                    "H {h}: ω {w:.6} rad/s, amplitude {:.9e}, shooting {reference:.9e}, {e:.2e}",
                    amp(q)
                );
                e
            })
            .collect()
    };
    let (coarse, fine) = (errors(10), errors(20));
    for (c, f) in coarse.iter().zip(&fine) {
        assert!(*c < 4e-4, "H 10: {c:e}");
        assert!(*f < 1.5e-5, "H 20: {f:e}");
        assert!(f < c, "H 20 ({f:e}) not closer than H 10 ({c:e})");
    }
}

/// As damping and force shrink together (c = 0.4, 0.2, 0.1 with F/c fixed, so the linear
/// peak stays at F/(c ω₀) ≈ 3 gaps), the resonance of the one-DOF wall hangs on the backbone: the
/// autonomous family of the same regularised problem and harmonics (the engine's
/// MODE_NON_LINE continuation from the linear mode). The peak is taken at phase
/// resonance, where the first cosine harmonic of x changes sign along the curve (the
/// force then balances the damping of the first harmonic), interpolated linearly between
/// the two rows around it; the backbone's frequency at that amplitude is interpolated
/// between its rows. The gap between the two frequencies must shrink at least like the
/// damping: halving c at least halves it (ratio ≤ 0.55, 10 % for the interpolations,
/// whose errors do not scale with c). Measured: 9.98e-5, 2.50e-5, 6.16e-6 Hz, ratios
/// 0.250 and 0.247: the gap falls like c², the peak at 2.974e-2 m (three gaps) every time.
#[test]
fn resonance_peak_follows_the_backbone_as_damping_vanishes() {
    let (g, alpha, regul) = (0.01, 50.0, 1e-4);
    let h = 6;
    let mut s = settings(h, 10 * h, 400, 8);
    s.continuation.det_test = false;
    let amp = |q: &Point| peak_amplitude(&q.x[..2 * h + 1], h);
    // The backbone, up to 4.5 gaps.
    let free = Problem {
        forcing: None,
        ..forced(
            &[(0, 0, K)],
            &[(0, 0, M)],
            &[(0, 0, C)],
            vec![F],
            vec![plan(g, alpha, regul)],
        )
    };
    let st = crate::nnm::start_from_mode(&free, &s, &[1.0], 0.5, (K / M).sqrt()).unwrap();
    let mut backbone = vec![st.point.clone()];
    let out = continue_while(&free, &s, st, &mut |_, pts| {
        pts.last()
            .is_none_or(|q| peak_amplitude(&q.x[..2 * h + 1], h) < 4.5 * g)
    });
    assert!(out.error.is_none(), "{:?}", out.error);
    backbone.extend(out.points);
    let bb: Vec<(f64, f64)> = backbone.iter().map(|q| (amp(q), q.frequency)).collect();
    assert!(
        bb.windows(2).all(|w| w[1].0 > w[0].0),
        "backbone amplitude not increasing"
    );
    // Quadratic (three-row Lagrange) interpolation: its error, O(Δa³), stays below 1e-6 Hz
    // (the gaps at c = 0.1 and 0.05 fell to 1e-6 and 4e-6 with linear interpolation, its
    // floor; hence damping from 0.4 down to 0.1 here, gaps well above it).
    let f_backbone = |a: f64| -> f64 {
        let i = bb
            .iter()
            .position(|p| p.0 >= a)
            .expect("backbone reaches the amplitude");
        let i = i.clamp(1, bb.len() - 2);
        let (p, q, r) = (bb[i - 1], bb[i], bb[i + 1]);
        let l = |x0: f64, x1: f64, x2: f64| (a - x1) * (a - x2) / ((x0 - x1) * (x0 - x2));
        p.1 * l(p.0, q.0, r.0) + q.1 * l(q.0, p.0, r.0) + r.1 * l(r.0, p.0, q.0)
    };
    let mut gaps = Vec::new();
    for c in [0.4, 0.2, 0.1] {
        let p = forced(
            &[(0, 0, K)],
            &[(0, 0, M)],
            &[(0, 0, c)],
            vec![0.1 * c],
            vec![plan(g, alpha, regul)],
        );
        let rows = curve(&p, &s, 0.3, 0.8);
        // Phase resonance: the first cosine coefficient C1 = x[1] changes sign.
        let i = (1..rows.len())
            .find(|&i| rows[i - 1].x[1] * rows[i].x[1] <= 0.0)
            .expect("a phase resonance in the band");
        let (a, b) = (&rows[i - 1], &rows[i]);
        let t = a.x[1] / (a.x[1] - b.x[1]);
        let f_peak = a.frequency + t * (b.frequency - a.frequency);
        let a_peak = amp(a) + t * (amp(b) - amp(a));
        let gap = (f_peak - f_backbone(a_peak)).abs();
        eprintln!(
            "c {c}: peak {f_peak:.6} Hz at {a_peak:.5e} m, backbone {:.6} Hz, gap {gap:.3e}",
            f_backbone(a_peak)
        );
        gaps.push(gap);
    }
    for w in gaps.windows(2) {
        eprintln!("ratio {:.3}", w[1] / w[0]);
        assert!(w[1] <= 0.55 * w[0], "gaps {gaps:?}");
    }
}
