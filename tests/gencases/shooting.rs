//! Periodic orbits of the generated cases by shooting, independent of the engine: the
//! equations of motion M ü + K u + Pᵀ F(u) = 0 with the law of `law/`, integrated by
//! `ode.rs`, and a Newton on the initial displacement and the half period at a given
//! ENERGIE.
//!
//! The orbits of a nonlinear normal mode of a conservative, time-reversible system are
//! brake orbits: every velocity vanishes at t = 0 and again at T/2, and u(−t) = u(t). So the
//! unknowns are u(0) (n values) and τ = T/2, the equations v(τ) = 0 (n) and ENERGIE = E (1).
//! ENERGIE is Code_Aster's quantity, the one the table reports: ½uᵀKu + ½vᵀMv plus the
//! penalty energy ½α(penetration)² at ωt = π/2, a quarter period after the zero-velocity
//! instant the engine's phase condition puts at t = 0 (the same state, up to the sign of v,
//! whichever turning point that is). For an exact orbit of the nonsmooth law it is the total
//! energy; for the regularised law it differs from the total energy by the regularised
//! potential at that instant, and the reference uses ENERGIE's definition so that row and
//! reference are compared at the same quantity.
//!
//! Accuracy: the Newton is run at rtol 1e-8, then 1e-10, then 1e-12 of the integrator, each
//! from the previous solution; the change of the frequency between the last two is the
//! reference's own error estimate (`Reference::accuracy`).

use super::eigen;
use super::laws::Shock;
use super::model::Model;
use realfft::RealFftPlanner;

pub struct Dynamics {
    pub n: usize,
    pub k: Vec<f64>,
    pub m: Vec<f64>,
    minv: Vec<f64>,
    pub shock: Shock,
}

impl Dynamics {
    pub fn new(model: &Model, shock: Shock) -> Result<Dynamics, String> {
        let minv = eigen::inverse(&model.m, model.n).ok_or("singular mass matrix")?;
        Ok(Dynamics {
            n: model.n,
            k: model.k.clone(),
            m: model.m.clone(),
            minv,
            shock,
        })
    }

    pub fn rhs(&self, y: &[f64], dy: &mut [f64]) {
        let n = self.n;
        let (u, v) = y.split_at(n);
        dy[..n].copy_from_slice(v);
        let mut g = eigen::mul(&self.k, u);
        let (fx, fy) = self.shock.force(u);
        g[self.shock.px] += fx;
        if fy != 0.0 {
            g[self.shock.py] += fy;
        }
        for i in 0..n {
            dy[n + i] = -(0..n).map(|j| self.minv[i * n + j] * g[j]).sum::<f64>();
        }
    }

    /// Code_Aster's ENERGIE formula at state y.
    pub fn energy_ca(&self, y: &[f64]) -> f64 {
        let (u, v) = y.split_at(self.n);
        eigen::half_quad(&self.k, u) + eigen::half_quad(&self.m, v) + self.shock.penalty_energy(u)
    }

    /// The length on which the shooting residual changes its form near rest at `u0`: the
    /// penetration into the stop when it is smaller than the amplitude, else the amplitude.
    /// A finite-difference step is a small fraction of it. With a stiff stop the orbit
    /// starts a few 1e-4 of the amplitude past contact, ENERGIE and v(τ) turn over on that
    /// length, and a step relative to the amplitude alone spans it: the Jacobian is then
    /// wrong by O(1) and the Newton stalls (measured on generated case 290 of seed 1: three
    /// rows near first contact whose references failed at |r| ≈ 1e-3 converge with the
    /// step on the penetration). Not below 1e-4 of the amplitude, where the integrator's
    /// noise would swamp the difference. A second try only ([`solve`]): with this step
    /// alone, three of the first 300 generated cases lost references the step on the
    /// amplitude computes.
    pub fn difference_length(&self, u0: &[f64]) -> f64 {
        let amp = norm(u0).max(1e-300);
        let depth = self.shock.penetration(u0);
        if depth > 0.0 {
            depth.clamp(1e-4 * amp, amp)
        } else {
            amp
        }
    }

    /// Whether [`Dynamics::difference_length`] is shorter than the amplitude at `u0` (a
    /// second Newton with that step is then worth trying).
    pub fn penetration_differs(&self, u0: &[f64]) -> bool {
        self.difference_length(u0) < norm(u0)
    }

    /// States at the given instants from rest at u0.
    pub fn shoot(&self, u0: &[f64], stops: &[f64], rtol: f64) -> Result<Vec<Vec<f64>>, String> {
        let n = self.n;
        let amp = u0.iter().fold(0.0f64, |a, &b| a.max(b.abs())).max(1e-300);
        let omega = std::f64::consts::PI / stops.last().copied().unwrap_or(1.0);
        let mut scale = vec![amp; 2 * n];
        for s in &mut scale[n..] {
            *s = amp * omega;
        }
        let mut y0 = u0.to_vec();
        y0.extend(std::iter::repeat_n(0.0, n));
        let f = |y: &[f64], dy: &mut [f64]| self.rhs(y, dy);
        super::ode::integrate(&f, &y0, stops, rtol, &scale, 20_000_000).map(|r| r.0)
    }
}

/// A brake orbit: rest at u0 at t = 0, period 2τ.
#[derive(Debug, Clone)]
pub struct Orbit {
    pub u0: Vec<f64>,
    pub tau: f64,
}

impl Orbit {
    pub fn freq(&self) -> f64 {
        0.5 / self.tau
    }
}

/// v(τ) in units of the guess's velocity scale (fixed, so that a shrinking τ cannot make the
/// residual small: τ → 0 is a spurious root, rest at t = 0 and almost at rest just after),
/// and the relative ENERGIE defect.
fn residual(
    d: &Dynamics,
    o: &Orbit,
    energy: f64,
    rtol: f64,
    tau_g: f64,
) -> Result<Vec<f64>, String> {
    let n = d.n;
    let s = d.shoot(&o.u0, &[0.5 * o.tau, o.tau], rtol)?;
    let amp = o.u0.iter().fold(0.0f64, |a, &b| a.max(b.abs())).max(1e-300);
    let w = std::f64::consts::PI / tau_g;
    let mut r: Vec<f64> = s[1][n..].iter().map(|v| v / (amp * w)).collect();
    r.push((d.energy_ca(&s[0]) - energy) / energy);
    Ok(r)
}

fn norm(v: &[f64]) -> f64 {
    v.iter().fold(0.0f64, |a, &b| a.max(b.abs()))
}

/// Newton on (u0, τ) at ENERGIE `energy`, finite-difference Jacobian, from `guess`
/// (environment GEN_DEBUG: print every iteration, for a case whose reference fails).
pub fn solve(d: &Dynamics, guess: &Orbit, energy: f64, rtol: f64) -> Result<Orbit, String> {
    newton_at_energy(d, guess, energy, rtol, Step::OnAmplitude).or_else(|first| {
        match d.penetration_differs(&guess.u0) {
            true => {
                newton_at_energy(d, guess, energy, rtol, Step::OnPenetration).map_err(|_| first)
            }
            false => Err(first),
        }
    })
}

/// What a finite-difference step of the displacement is a fraction of.
#[derive(Clone, Copy)]
enum Step {
    /// The largest displacement.
    OnAmplitude,
    /// [`Dynamics::difference_length`]: the penetration when it is the shorter length.
    OnPenetration,
}

impl Step {
    fn length(self, d: &Dynamics, u0: &[f64]) -> f64 {
        match self {
            Step::OnAmplitude => norm(u0).max(1e-300),
            Step::OnPenetration => d.difference_length(u0),
        }
    }
}

/// [`solve`]'s Newton with one choice of the difference step.
fn newton_at_energy(
    d: &Dynamics,
    guess: &Orbit,
    energy: f64,
    rtol: f64,
    on: Step,
) -> Result<Orbit, String> {
    let n = d.n;
    let mut o = guess.clone();
    let tau_g = guess.tau;
    let mut r = residual(d, &o, energy, rtol, tau_g)?;
    let h = (rtol.sqrt() * 10.0).min(1e-4);
    for _it in 0..30 {
        let amp = norm(&o.u0).max(1e-300);
        let length = on.length(d, &o.u0);
        let mut jac = vec![0.0; (n + 1) * (n + 1)];
        for c in 0..=n {
            let mut p = o.clone();
            let step = if c < n { h * length } else { h * o.tau };
            if c < n {
                p.u0[c] += step;
            } else {
                p.tau += step;
            }
            let rp = residual(d, &p, energy, rtol, tau_g)?;
            for i in 0..=n {
                jac[i * (n + 1) + c] = (rp[i] - r[i]) / step;
            }
        }
        if std::env::var_os("GEN_DEBUG").is_some() {
            eprintln!(
                "newton rtol {rtol:e}: u0 {:?} tau {:e} r {:?} jac {:?}",
                o.u0, o.tau, r, jac
            );
        }
        let neg: Vec<f64> = r.iter().map(|x| -x).collect();
        let dx = eigen::solve(&jac, &neg).ok_or("singular shooting Jacobian")?;
        let size = norm(&dx[..n]) / amp + (dx[n] / o.tau).abs();
        let mut lambda = 1.0;
        let r0 = norm(&r);
        loop {
            let mut p = o.clone();
            for (u, d) in p.u0.iter_mut().zip(&dx[..n]) {
                *u += lambda * d;
            }
            p.tau += lambda * dx[n];
            // The orbit sought is the row's: its period within a factor 1.5 of the row's
            // (2τ is a brake orbit too: the same orbit twice).
            if p.tau > tau_g / 1.5 && p.tau < 1.5 * tau_g {
                if let Ok(rp) = residual(d, &p, energy, rtol, tau_g) {
                    if norm(&rp) < r0 || size * lambda < 100.0 * rtol || lambda < 1e-3 {
                        o = p;
                        r = rp;
                        break;
                    }
                }
            }
            lambda *= 0.5;
            if lambda < 1e-3 {
                // No decrease left: converged if the residual is at the integrator's noise.
                if r0 <= 1e3 * rtol {
                    return Ok(o);
                }
                return Err(format!("shooting Newton stalled at |r| = {r0:.2e}"));
            }
        }
        if size * lambda <= 100.0 * rtol {
            return Ok(o);
        }
    }
    if norm(&r) <= (1e3 * rtol).max(1e-5) {
        return Ok(o);
    }
    Err(format!(
        "shooting Newton did not converge (|r| = {:.2e})",
        norm(&r)
    ))
}

/// The rest state along `u0` whose ENERGIE (½uᵀKu + penalty, v = 0) is `energy`: u0 scaled
/// by bisection (the potential grows along a ray). The row's displacement at t = 0 is the
/// truncated series' value; with a stiff stop a few 1e-4 of the gap past contact can hold a
/// large share of the energy, so the shape is kept and the size is set by the energy before
/// the Newton starts.
pub fn at_energy(d: &Dynamics, u0: &[f64], energy: f64) -> Vec<f64> {
    let pot = |s: f64| {
        let u: Vec<f64> = u0.iter().map(|x| s * x).collect();
        eigen::half_quad(&d.k, &u) + d.shock.penalty_energy(&u)
    };
    let (mut lo, mut hi) = (0.0, 1.0);
    while pot(hi) < energy && hi < 1e30 {
        hi *= 2.0;
    }
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if pot(mid) < energy {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    u0.iter().map(|x| 0.5 * (lo + hi) * x).collect()
}

/// The half period of the motion from rest at u0 nearest to `tau`: the zero of the velocity
/// of the DOF that moves most, among 400 instants in [0.7τ, 1.3τ]. With a stiff stop the
/// row's period can be off by more than the contact lasts, and v(τ) then changes by a jump
/// that a Newton cannot cross; this puts τ on the right side first.
pub fn half_period_near(d: &Dynamics, u0: &[f64], tau: f64) -> f64 {
    let i = (0..d.n)
        .max_by(|&a, &b| u0[a].abs().total_cmp(&u0[b].abs()))
        .unwrap_or(0);
    let stops: Vec<f64> = (0..=400)
        .map(|j| tau * (0.7 + 0.6 * j as f64 / 400.0))
        .collect();
    let Ok(states) = d.shoot(u0, &stops, 1e-9) else {
        return tau;
    };
    let v: Vec<f64> = states.iter().map(|y| y[d.n + i]).collect();
    (0..400)
        .filter(|&j| v[j] == 0.0 || (v[j] > 0.0) != (v[j + 1] > 0.0))
        .map(|j| stops[j] + (stops[j + 1] - stops[j]) * v[j] / (v[j] - v[j + 1]))
        .min_by(|a, b| (a - tau).abs().total_cmp(&(b - tau).abs()))
        .unwrap_or(tau)
}

/// The whole solve from a rough guess (a row's state, a linear orbit): the guess put at the
/// energy (`at_energy`), its half period on the right side of any contact
/// (`half_period_near`), then `solve_refined`.
pub fn solve_from(d: &Dynamics, guess: &Orbit, energy: f64) -> Result<(Orbit, f64), String> {
    let u0 = at_energy(d, &guess.u0, energy);
    let start = Orbit {
        tau: half_period_near(d, &u0, guess.tau),
        u0,
    };
    solve_refined(d, &start, energy)
}

/// Solves at the three accuracies; returns the orbit and the frequency change between the
/// last two (the reference's error estimate).
pub fn solve_refined(d: &Dynamics, guess: &Orbit, energy: f64) -> Result<(Orbit, f64), String> {
    let o1 = solve(d, guess, energy, 1e-8)?;
    let o2 = solve(d, &o1, energy, 1e-10)?;
    let o3 = solve(d, &o2, energy, 1e-12)?;
    let acc = (o3.freq() / o2.freq() - 1.0).abs();
    Ok((o3, acc))
}

/// Newton on u0 at the half period `tau` held fixed (the frequency given, the energy free),
/// finite-difference Jacobian, from `u0`: the brake orbit of that period next to the guess.
/// Where ENERGIE folds or barely changes along a family (a stiff stop at grazing: the
/// frequency rises at almost constant energy), the orbit at a row's ENERGIE may sit on
/// another part of the curve than the row; at the row's frequency it is on the row's part.
/// Ill-posed where the frequency does not change with the energy (the linear regime): the
/// caller then keeps the comparison at equal ENERGIE. Refuses an orbit whose ENERGIE is below
/// half the guess's (the rest state is a root too).
pub fn solve_at_period(d: &Dynamics, u0: &[f64], tau: f64, rtol: f64) -> Result<Orbit, String> {
    newton_at_period(d, u0, tau, rtol, Step::OnAmplitude).or_else(|first| {
        match d.penetration_differs(u0) {
            true => newton_at_period(d, u0, tau, rtol, Step::OnPenetration).map_err(|_| first),
            false => Err(first),
        }
    })
}

/// [`solve_at_period`]'s Newton with one choice of the difference step.
fn newton_at_period(
    d: &Dynamics,
    u0: &[f64],
    tau: f64,
    rtol: f64,
    on: Step,
) -> Result<Orbit, String> {
    let n = d.n;
    let w = std::f64::consts::PI / tau;
    let scale = norm(u0).max(1e-300);
    let res = |u: &[f64]| -> Result<Vec<f64>, String> {
        let s = d.shoot(u, &[tau], rtol)?;
        Ok(s[0][n..].iter().map(|v| v / (scale * w)).collect())
    };
    let energy =
        |u: &[f64]| -> Result<f64, String> { Ok(d.energy_ca(&d.shoot(u, &[0.5 * tau], rtol)?[0])) };
    let e_guess = energy(u0)?;
    let mut u = u0.to_vec();
    let mut r = res(&u)?;
    let h = (rtol.sqrt() * 10.0).min(1e-4);
    for _ in 0..30 {
        let mut jac = vec![0.0; n * n];
        let length = on.length(d, &u);
        for c in 0..n {
            let mut p = u.clone();
            let step = h * length;
            p[c] += step;
            let rp = res(&p)?;
            for i in 0..n {
                jac[i * n + c] = (rp[i] - r[i]) / step;
            }
        }
        let neg: Vec<f64> = r.iter().map(|x| -x).collect();
        let dx = eigen::solve(&jac, &neg).ok_or("singular shooting Jacobian at fixed period")?;
        let size = norm(&dx) / scale;
        let r0 = norm(&r);
        let mut lambda = 1.0;
        loop {
            let p: Vec<f64> = u.iter().zip(&dx).map(|(a, b)| a + lambda * b).collect();
            if let Ok(rp) = res(&p) {
                if norm(&rp) < r0 || size * lambda < 100.0 * rtol {
                    u = p;
                    r = rp;
                    break;
                }
            }
            lambda *= 0.5;
            if lambda < 1e-3 {
                // No decrease left: converged if the residual is at the integrator's noise.
                if r0 <= 1e3 * rtol {
                    break;
                }
                return Err(format!("fixed-period Newton stalled at |r| = {r0:.2e}"));
            }
        }
        if size * lambda <= 100.0 * rtol || lambda < 1e-3 {
            break;
        }
    }
    if norm(&r) > (1e3 * rtol).max(1e-5) {
        return Err(format!(
            "fixed-period Newton did not converge (|r| = {:.2e})",
            norm(&r)
        ));
    }
    if energy(&u)? < 0.5 * e_guess {
        return Err("fixed-period Newton went to another orbit (ENERGIE halved)".into());
    }
    Ok(Orbit { u0: u, tau })
}

/// ENERGIE of a brake orbit (at the quarter period, as the rows read it).
pub fn energy_of(d: &Dynamics, o: &Orbit, rtol: f64) -> Result<f64, String> {
    Ok(d.energy_ca(&d.shoot(&o.u0, &[0.5 * o.tau], rtol)?[0]))
}

/// What the truncation to `h_lin` and `h_nonl` harmonics leaves out of the orbit, from its
/// own spectrum over one period (N uniform samples, N ≥ 16 NB_HARM_NONL and ≥ 64 samples per
/// contact pulse, up to 2²⁰):
/// - `tail_v`: the share of the mean kinetic energy above harmonic h_lin;
/// - `tail_f`: the share of the contact force's mean square above harmonic h_nonl;
/// - `tail_r`: for a ring, the same share of its radial distance |u − c| (an unknown of
///   eq. (12) whose truncation limits the engine's force even where the force is smooth:
///   through the centre |u − c| has a kink); 0 for the planes;
/// - `ripple`: |ENERGIE of the orbit truncated to h_lin harmonics − ENERGIE| / ENERGIE, the
///   error that ENERGIE, read at one instant, carries on a truncated series.
pub struct Tails {
    pub tail_v: f64,
    pub tail_f: f64,
    pub tail_r: f64,
    pub ripple: f64,
    pub samples: usize,
}

/// Sample j of a half period: the start (rest at u0) or the integrator's stop j.
fn state_at<'a>(y0: &'a [f64], states: &'a [Vec<f64>], j: usize) -> &'a [f64] {
    if j == 0 {
        y0
    } else {
        &states[j - 1]
    }
}

pub fn tails(d: &Dynamics, o: &Orbit, h_lin: usize, h_nonl: usize) -> Result<Tails, String> {
    let n = d.n;
    let px = d.shock.px;
    let mp = 1.0 / d.minv[px * n + px];
    let pulse = std::f64::consts::PI * (mp / d.shock.alpha).sqrt();
    let per_pulse = 64.0 * 2.0 * o.tau / pulse;
    let want = (16 * h_nonl).max(4096).max(per_pulse.min(1e7) as usize);
    let big_n = want.next_power_of_two().min(1 << 20);
    let half = big_n / 2;
    let stops: Vec<f64> = (1..=half).map(|j| o.tau * j as f64 / half as f64).collect();
    let states = d.shoot(&o.u0, &stops, 1e-11)?;
    let mut y0 = o.u0.clone();
    y0.extend(std::iter::repeat_n(0.0, n));
    let state = |j: usize| state_at(&y0, &states, j);
    let mut planner = RealFftPlanner::<f64>::new();
    let fft = planner.plan_fft_forward(big_n);
    let spectrum = |x: Vec<f64>| -> Result<Vec<realfft::num_complex::Complex<f64>>, String> {
        let mut x = x;
        let mut out = fft.make_output_vec();
        fft.process(&mut x, &mut out).map_err(|e| e.to_string())?;
        Ok(out.into_iter().map(|c| c / big_n as f64).collect())
    };
    // Full period by the symmetry of a brake orbit: u(T − t) = u(t), v(T − t) = −v(t).
    let full = |i: usize, vel: bool| -> Vec<f64> {
        (0..big_n)
            .map(|j| {
                if j <= half {
                    state(j)[i + if vel { n } else { 0 }]
                } else {
                    let s = state(big_n - j)[i + if vel { n } else { 0 }];
                    if vel {
                        -s
                    } else {
                        s
                    }
                }
            })
            .collect()
    };
    let mut us = Vec::with_capacity(n);
    let mut vs = Vec::with_capacity(n);
    for i in 0..n {
        us.push(spectrum(full(i, false))?);
        vs.push(spectrum(full(i, true))?);
    }
    let nh = half + 1;
    let mut ke = vec![0.0; nh];
    for (h, e) in ke.iter_mut().enumerate() {
        let w = if h == 0 || h == half { 1.0 } else { 2.0 };
        let mut s = 0.0;
        for i in 0..n {
            for j in 0..n {
                let mij = d.m[i * n + j];
                if mij != 0.0 {
                    s += mij * (vs[i][h] * vs[j][h].conj()).re;
                }
            }
        }
        *e = w * s;
    }
    let share = |p: &[f64], h: usize| -> f64 {
        let tot: f64 = p.iter().sum();
        if tot <= 0.0 || h + 1 >= p.len() {
            0.0
        } else {
            p[h + 1..].iter().sum::<f64>() / tot
        }
    };
    let tail_v = share(&ke, h_lin);
    let force: Vec<f64> = (0..big_n)
        .map(|j| {
            let jj = if j <= half { j } else { big_n - j };
            d.shock.force_magnitude(&state(jj)[..n])
        })
        .collect();
    let fs = spectrum(force)?;
    let fp: Vec<f64> = fs
        .iter()
        .enumerate()
        .map(|(h, c)| if h == 0 || h == half { 1.0 } else { 2.0 } * c.norm_sqr())
        .collect();
    let tail_f = share(&fp, h_nonl);
    let tail_r = if d.shock.radial_distance(&o.u0).is_some() {
        let radial: Vec<f64> = (0..big_n)
            .map(|j| {
                let jj = if j <= half { j } else { big_n - j };
                d.shock.radial_distance(&state(jj)[..n]).unwrap_or(0.0)
            })
            .collect();
        let rs = spectrum(radial)?;
        let rp: Vec<f64> = rs
            .iter()
            .enumerate()
            .map(|(h, c)| if h == 0 || h == half { 1.0 } else { 2.0 } * c.norm_sqr())
            .collect();
        share(&rp, h_nonl)
    } else {
        0.0
    };
    // ENERGIE of the orbit truncated to h_lin harmonics, at the quarter period.
    let w = std::f64::consts::PI / o.tau;
    let mut y = vec![0.0; 2 * n];
    for i in 0..n {
        let c = |h: usize| {
            if h == 0 {
                us[i][0].re
            } else {
                2.0 * us[i][h].re
            }
        };
        let q =
            (0..=h_lin.min(half)).map(|h| c(h) * (h as f64 * std::f64::consts::FRAC_PI_2).cos());
        y[i] = q.sum();
        y[n + i] = -(1..=h_lin.min(half))
            .map(|h| w * h as f64 * c(h) * (h as f64 * std::f64::consts::FRAC_PI_2).sin())
            .sum::<f64>();
    }
    let e_true = d.energy_ca(state(half / 2));
    let ripple = (d.energy_ca(&y) / e_true - 1.0).abs();
    Ok(Tails {
        tail_v,
        tail_f,
        tail_r,
        ripple,
        samples: big_n,
    })
}
