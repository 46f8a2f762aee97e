//! RUNGE_KUTTA_32 and RUNGE_KUTTA_54 as Code_Aster computes them (its routines `intruku32`,
//! `intruku54` and the driver `dtmcalc`), so that its files give its numbers. The
//! event-located pairs of `adaptive.rs` are aster-nl's extension
//! (SCHEMA_TEMPS/LOCALISATION_CHOC='OUI').
//!
//! The state is y = (q, v), y' = (v, a(t, q, v)). A step of length h from (q₁, v₁, a₁) at
//! t₁ runs the stages of the pair (Bogacki–Shampine 3(2): 4 stages; Dormand–Prince 5(4): 7;
//! tableaux in `scheme/runge_kutta.rs`): the first stage is (v₁, a₁), carried from the step
//! before; stage j + 1 evaluates the acceleration at t₁ + c_{j+1} h and
//! y₁ + h Σ_{l≤j} a_{j,l} k_l; the last row of the tableau is the propagated solution
//! (q₂, v₂) at t₁ + h, whose acceleration a₂ is the first stage of the next step.
//!
//! The shocks' internal variables (stick anchor, stick/slip flag, the buckling law's) run
//! through the stages in their order, as Code_Aster updates them in place: each evaluation
//! starts from the state the one before left, the first from the state committed with the
//! previous step; a try that is redone starts again from that committed state, and the
//! state of the step's last evaluation (at t₁ + h) is committed with it and archived.
//!
//! Error, when the step is free (|PAS_MAXI/PAS_MINI − 1| ≥ 100ε, ε the double precision;
//! with PAS_MINI = PAS_MAXI every step is the one the driver hands, PAS, unjudged): per
//! unknown i, the estimates without the factor h, e_q,i = Σ_j w_j k_j(q)_i and e_v,i =
//! Σ_j w_j k_j(v)_i (w Code_Aster's weights, the difference of the pair's two weight rows),
//! against the scales s_q,i = max(TOL·|q₁,i + α|, TOL·(|q₂,i − q₁,i| + α), 100ε) and s_v,i
//! the same with v (TOL = TOLERANCE, α = ALPHA; α inside the absolute value is Code_Aster's
//! form, kept); err = max(h·√((Σ_i (e_q,i/s_q,i)² + Σ_i (e_v,i/s_v,i)²)/(2n)), 100ε).
//!
//! Step rule, p = 4 for RUNGE_KUTTA_32 and 6 for RUNGE_KUTTA_54: f = 5 when err <
//! (0.9/5)^p, 0.2 when err > (0.9/0.2)^p, 0.9·err^(−1/p) between, and the next step
//! h' = min(PAS_MAXI, f·h). A try with err ≥ 1 is done again with h' as long as h' ≥
//! PAS_MINI; h' < PAS_MINI stops the run, whether the step was to be redone or accepted
//! (Code_Aster's fatal error ALGORITH5_23; here [`TransientError::StepTooSmall`], which
//! names SCHEMA_TEMPS/PAS_MINI). A retry whose error did not fall below 1/1.01 of the try
//! before it is accepted, its error taken as 0.99 (Code_Aster: shortening the step does not
//! help, the motion is taken as not in equilibrium and integrated on), so that the next
//! step is 0.9·0.99^(−1/p) times it. There is no limit on the tries (NMAX_ITER_PAS has no
//! effect, as in Code_Aster): each retry shortens the step by 0.9 at least until it is
//! accepted or falls below PAS_MINI. Defaults: PAS_MINI 1e-10 and PAS_MAXI 1e10 times the
//! first step, ALPHA 0; PAS_MAXI below PAS is refused (Code_Aster's DYNAMIQUE_15).
//!
//! Driver (Code_Aster's `dtmcalc`, as for DEVOGE and ADAPT): the first step is PAS. The
//! listed archive instants after t₀, then INST_FIN, are landed on: a step that would pass
//! the next one is cut to it; once it is reached, the next step is the part cut off
//! (the step rule's proposal is dropped there), then the rule's again; a fixed step (the
//! driver's own test, with its defaults 1e-6 and 1e6 × PAS) goes back to PAS after a
//! landing. With PAS_ARCH = k, step i is archived when i − (the number of cut steps that
//! reached an instant) is a multiple of k; a step redone short of an instant it was cut to
//! is not archived (the driver waits for the instant). Instants are compared with
//! Code_Aster's tolerance, i·10ε (i the step count). A landed instant is the listed one
//! exactly, where Code_Aster keeps t₁ + h, an ulp or so away.
//!
//! Workspaces are allocated once; nothing is allocated in the step loop.

use super::archive::Recorder;
use super::dis_choc::{Shock, ShockState};
use super::driver::{drive, DrivenScheme, DriverSettings, DriverStats, Taken as DriverTaken};
use super::error::{invalid, try_zeros, TransientError};
use super::problem::{Archive, TimeGrid};
use super::scheme::runge_kutta::{aster_control, tableau, Tableau};
use super::scheme::AdaptiveOptions;
use super::system::{commit, finite, Model, Work};

/// Code_Aster's machine precision (r8prem): the double epsilon.
const EPS: f64 = f64::EPSILON;
/// The floor of the scales and of the error, and the test of a free step (100ε).
const FLOOR: f64 = 100.0 * EPS;
/// Largest growth and shrink of the step, and the rule's safety factor.
const GROW: f64 = 5.0;
const SHRINK: f64 = 0.2;
const SAFETY: f64 = 0.9;
/// A retry is accepted unless its error fell below 1/RETRY_GAIN of the try before; it is
/// then taken as STALLED.
const RETRY_GAIN: f64 = 1.01;
const STALLED: f64 = 0.99;
/// Code_Aster's defaults of PAS_MINI and PAS_MAXI, times the first step.
const DEFAULT_MINI: f64 = 1e-10;
const DEFAULT_MAXI: f64 = 1e10;
/// One accepted step.
struct Taken {
    /// Its length.
    h: f64,
    /// The rule's next step (the step itself when the step is fixed).
    next: f64,
    /// Tries, the accepted one included.
    tries: usize,
}

/// The scheme's state between steps and its workspaces.
struct Rk {
    tab: &'static Tableau,
    weights: &'static [f64],
    p: f64,
    tol: f64,
    alpha: f64,
    /// (PAS_MINI, PAS_MAXI, free), set at the first step from its length.
    bounds: Option<(f64, f64, bool)>,
    /// The committed state at t₁.
    q1: Vec<f64>,
    v1: Vec<f64>,
    a1: Vec<f64>,
    /// The try's state (after the last stage: the new state).
    q2: Vec<f64>,
    v2: Vec<f64>,
    a2: Vec<f64>,
    /// The stages but the last: derivatives of q and of v.
    kq: Vec<Vec<f64>>,
    kv: Vec<Vec<f64>>,
    /// The shocks' states committed with the previous step.
    saved: Vec<ShockState>,
}

impl Rk {
    fn new(
        opts: &AdaptiveOptions,
        q0: &[f64],
        v0: &[f64],
        a0: &[f64],
        shocks: &[Shock],
    ) -> Result<Rk, TransientError> {
        let tab = tableau(opts.pair);
        let (weights, p) = aster_control(opts.pair);
        let n = q0.len();
        let z = || try_zeros("the Runge-Kutta state", n);
        let mut rk = Rk {
            tab,
            weights,
            p,
            tol: opts.tolerance,
            alpha: opts.alpha,
            bounds: None,
            q1: z()?,
            v1: z()?,
            a1: z()?,
            q2: z()?,
            v2: z()?,
            a2: z()?,
            kq: Vec::new(),
            kv: Vec::new(),
            saved: shocks.iter().map(|s| s.state).collect(),
        };
        for _ in 1..tab.stages {
            rk.kq.push(z()?);
            rk.kv.push(z()?);
        }
        rk.q1.copy_from_slice(q0);
        rk.v1.copy_from_slice(v0);
        rk.a1.copy_from_slice(a0);
        Ok(rk)
    }

    /// One try of length h from the committed state: the stages, the shocks' states
    /// running through them from the committed ones.
    fn attempt(
        &mut self,
        model: &Model,
        shocks: &mut [Shock],
        ws: &mut Work,
        t1: f64,
        h: f64,
    ) -> Result<(), TransientError> {
        for (shock, state) in shocks.iter_mut().zip(&self.saved) {
            shock.state = *state;
        }
        self.v2.copy_from_slice(&self.v1);
        self.a2.copy_from_slice(&self.a1);
        for j in 1..self.tab.stages {
            // The derivative just evaluated is stage j (the start's for j = 1).
            self.kq[j - 1].copy_from_slice(&self.v2);
            self.kv[j - 1].copy_from_slice(&self.a2);
            let row = self.tab.a[j];
            for i in 0..self.q1.len() {
                let (mut q, mut v) = (self.q1[i], self.v1[i]);
                for (l, &a) in row.iter().enumerate() {
                    q += h * a * self.kq[l][i];
                    v += h * a * self.kv[l][i];
                }
                self.q2[i] = q;
                self.v2[i] = v;
            }
            let t = t1 + h * self.tab.c[j];
            model.acceleration(shocks, t, &self.q2, &self.v2, &mut self.a2, ws)?;
            // Code_Aster updates the internal variables in place: the next stage starts
            // from this evaluation's.
            commit(shocks, &ws.evals);
        }
        if finite(&self.q2) && finite(&self.v2) && finite(&self.a2) {
            Ok(())
        } else {
            Err(TransientError::NonFinite { t: t1 + h })
        }
    }

    /// The error of the try just made (module doc).
    fn error(&self, h: f64) -> f64 {
        let last = self.weights.len() - 1;
        let (tol, alpha) = (self.tol, self.alpha);
        let (mut sum_q, mut sum_v) = (0.0, 0.0);
        for i in 0..self.q1.len() {
            let (mut eq, mut ev) = (0.0, 0.0);
            for (l, &w) in self.weights[..last].iter().enumerate() {
                eq += w * self.kq[l][i];
                ev += w * self.kv[l][i];
            }
            eq += self.weights[last] * self.v2[i];
            ev += self.weights[last] * self.a2[i];
            let dq = (self.q2[i] - self.q1[i]).abs();
            let dv = (self.v2[i] - self.v1[i]).abs();
            let sq = (tol * (self.q1[i] + alpha).abs())
                .max(tol * (dq + alpha))
                .max(FLOOR);
            let sv = (tol * (self.v1[i] + alpha).abs())
                .max(tol * (dv + alpha))
                .max(FLOOR);
            sum_q += (eq / sq).powi(2);
            sum_v += (ev / sv).powi(2);
        }
        let n2 = (2 * self.q1.len()) as f64;
        (h * ((sum_q + sum_v) / n2).sqrt()).max(FLOOR)
    }

    /// A step from t₁ of first try h, redone as the rule says; nothing is committed to the
    /// scheme's state (see [`Rk::accept`]); the shocks hold the last evaluation's states.
    fn step(
        &mut self,
        model: &Model,
        shocks: &mut [Shock],
        ws: &mut Work,
        opts: &AdaptiveOptions,
        t1: f64,
        first: f64,
    ) -> Result<Taken, TransientError> {
        let (mini, maxi, free) = *self.bounds.get_or_insert_with(|| {
            let mini = opts.pas_mini.unwrap_or(DEFAULT_MINI * first);
            let maxi = opts.pas_maxi.unwrap_or(DEFAULT_MAXI * first);
            (mini, maxi, (maxi / mini - 1.0).abs() >= FLOOR)
        });
        let seuil_grow = (SAFETY / GROW).powf(self.p);
        let seuil_shrink = (SAFETY / SHRINK).powf(self.p);
        let mut previous = f64::MAX;
        let mut h = first;
        let mut tries = 1usize;
        loop {
            self.attempt(model, shocks, ws, t1, h)?;
            if !free {
                return Ok(Taken { h, next: h, tries });
            }
            let mut err = self.error(h);
            if !err.is_finite() {
                return Err(TransientError::NonFinite { t: t1 + h });
            }
            if err * RETRY_GAIN > previous {
                err = STALLED;
            }
            let factor = if err < seuil_grow {
                GROW
            } else if err > seuil_shrink {
                SHRINK
            } else {
                SAFETY * err.powf(-1.0 / self.p)
            };
            let next = maxi.min(h * factor);
            if err >= 1.0 && next >= mini {
                h = next;
                previous = err;
                tries += 1;
                continue;
            }
            if next < mini {
                return Err(TransientError::StepTooSmall {
                    t: t1,
                    dt: next,
                    pas_mini: mini,
                });
            }
            return Ok(Taken { h, next, tries });
        }
    }

    /// The try just made becomes the committed state (the shocks' states with it).
    fn accept(&mut self, shocks: &[Shock]) {
        std::mem::swap(&mut self.q1, &mut self.q2);
        std::mem::swap(&mut self.v1, &mut self.v2);
        std::mem::swap(&mut self.a1, &mut self.a2);
        for (saved, shock) in self.saved.iter_mut().zip(shocks) {
            *saved = shock.state;
        }
    }
}

/// Checks what integrate.rs does not for every adaptive pair: ALPHA finite, PAS_MINI > 0,
/// and PAS_MAXI not below PAS (Code_Aster refuses it, DYNAMIQUE_15).
fn check(opts: &AdaptiveOptions, pas: f64) -> Result<(), TransientError> {
    if !opts.alpha.is_finite() {
        return Err(invalid("SCHEMA_TEMPS/ALPHA", "must be a finite number"));
    }
    if opts.pas_mini.is_some_and(|x| !(x.is_finite() && x > 0.0)) {
        return Err(invalid("SCHEMA_TEMPS/PAS_MINI", "must be > 0"));
    }
    if let Some(hi) = opts.pas_maxi {
        if hi < pas {
            return Err(invalid(
                "SCHEMA_TEMPS/PAS_MAXI",
                format!("PAS_MAXI = {hi:e} is below PAS = {pas:e}"),
            ));
        }
    }
    Ok(())
}

/// Rk under Code_Aster's driver.
struct Driven<'o> {
    rk: Rk,
    opts: &'o AdaptiveOptions,
}

impl DrivenScheme for Driven<'_> {
    fn step(
        &mut self,
        model: &Model,
        shocks: &mut [Shock],
        ws: &mut Work,
        t: f64,
        h: f64,
    ) -> Result<DriverTaken, TransientError> {
        let taken = self.rk.step(model, shocks, ws, self.opts, t, h)?;
        Ok(DriverTaken {
            h: taken.h,
            next: taken.next,
            tries: taken.tries,
        })
    }

    fn accept(&mut self, shocks: &mut [Shock], _ws: &mut Work, _h: f64) {
        self.rk.accept(shocks);
    }

    fn state(&self) -> (&[f64], &[f64], &[f64]) {
        (&self.rk.q1, &self.rk.v1, &self.rk.a1)
    }
}

/// Runs from (q, v, a) at t0 (shock states committed, t0 archived with PAS_ARCH) to t_end
/// under Code_Aster's driver (driver.rs).
#[allow(clippy::too_many_arguments)]
pub(crate) fn run_rk(
    model: &Model,
    shocks: &mut [Shock],
    opts: &AdaptiveOptions,
    q0: &[f64],
    v0: &[f64],
    a0: &[f64],
    grid: TimeGrid,
    archive: &Archive,
    rec: &mut Recorder,
    ws: &mut Work,
    progress: &mut dyn FnMut(f64),
) -> Result<DriverStats, TransientError> {
    check(opts, grid.dt)?;
    let mut scheme = Driven {
        rk: Rk::new(opts, q0, v0, a0, shocks)?,
        opts,
    };
    let settings = DriverSettings {
        pas_mini: opts.pas_mini,
        pas_maxi: opts.pas_maxi,
        max_steps: opts.max_steps,
    };
    drive(
        &mut scheme,
        &settings,
        model,
        shocks,
        (q0, v0, a0),
        grid,
        archive,
        rec,
        ws,
        progress,
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::transient::dense::DenseStructure;
    use crate::transient::scheme::RkPair;

    /// The accepted try of a step from (q0, v0), recomputed stage by stage from the
    /// tableau, each shock evaluation from the state the stage before left (`chained`)
    /// or each from `start`: the new q, v, a and the last evaluation's state.
    #[allow(clippy::too_many_arguments)]
    fn by_hand(
        shock: &Shock,
        k: f64,
        q0: f64,
        v0: f64,
        a0: f64,
        h: f64,
        start: ShockState,
        chained: bool,
    ) -> (f64, f64, f64, ShockState) {
        let tab = tableau(RkPair::BogackiShampine32);
        let (mut kq, mut kv) = (vec![v0], vec![a0]);
        let mut state = start;
        let (mut q, mut v) = (q0, v0);
        for j in 1..tab.stages {
            q = q0;
            v = v0;
            for (l, &a) in tab.a[j].iter().enumerate() {
                q += h * a * kq[l];
                v += h * a * kv[l];
            }
            let from = if chained { state } else { start };
            let ev = shock.evaluate_at(h * tab.c[j], &[q], &[v], &from);
            let mut r = [-(k * q)];
            shock.add_generalized(&ev, &mut r);
            state = ev.sample.state;
            kq.push(v);
            kv.push(r[0]);
        }
        (q, v, kv[tab.stages - 1], state)
    }

    /// One step of RUNGE_KUTTA_32 from (q0, v0) on m = 1, k = 1e4 with the friction shock,
    /// from the state the start's evaluation commits: the step, the loop's state after it
    /// and the shock's, and the committed state it started from.
    fn one_step(
        amor_tan: f64,
        q0: f64,
        v0: f64,
        opts: &AdaptiveOptions,
        first: f64,
    ) -> (Taken, Rk, ShockState, ShockState, f64) {
        let structure = DenseStructure::diagonal(vec![1.0], vec![1e4], None).unwrap();
        let model = Model {
            structure: &structure,
            forcing: &[],
        };
        let mut shocks = vec![crate::transient::tests::sdnd100a_friction_shock(amor_tan)];
        let mut ws = Work::new(1, &shocks).unwrap();
        let mut a0 = [0.0];
        model
            .acceleration(&shocks, 0.0, &[q0], &[v0], &mut a0, &mut ws)
            .unwrap();
        commit(&mut shocks, &ws.evals);
        let committed = shocks[0].state;
        let mut rk = Rk::new(opts, &[q0], &[v0], &a0, &shocks).unwrap();
        let taken = rk
            .step(&model, &mut shocks, &mut ws, opts, 0.0, first)
            .unwrap();
        (taken, rk, shocks[0].state, committed, a0[0])
    }

    /// A step whose first try is redone: the accepted try starts from the state committed
    /// before the step, not from the rejected try's, its stages run the shock's state from
    /// one to the next, and the last stage's state is the shock's after the step (and the
    /// one the next step starts from).
    #[test]
    fn a_retried_step_starts_from_the_committed_state() {
        let (q0, v0) = (1e-3, 5e-3);
        let mut opts = AdaptiveOptions::new(RkPair::BogackiShampine32);
        opts.tolerance = 1e-3;
        let (taken, mut rk, after, committed, a0) = one_step(1280.0, q0, v0, &opts, 4e-3);
        assert!(taken.tries >= 2, "{} tries", taken.tries);
        let shock = crate::transient::tests::sdnd100a_friction_shock(1280.0);
        let (q, v, a, state) = by_hand(&shock, 1e4, q0, v0, a0, taken.h, committed, true);
        assert_eq!((rk.q2[0], rk.v2[0], rk.a2[0]), (q, v, a));
        assert_eq!(after, state);
        // Accepted, the shock's state is the one the next step starts from.
        let mut held = shock;
        held.state = after;
        rk.accept(&[held]);
        assert_eq!(rk.saved[0], state);
    }

    /// Each stage's shock evaluation starts from the state the stage before left
    /// (Code_Aster updates the internal variables in place). A fixed step of 1 ms in which
    /// the slide reverses between the stages at h/2 and 3h/4: at 3h/4 the stick is judged
    /// from the anchor the slide at h/2 left (chained) and sticks; judged from the start's
    /// anchor it would slip, and the step would end elsewhere: the test bites.
    #[test]
    fn the_shock_state_runs_through_the_stages() {
        let h = 1e-3;
        let (q0, v0) = (1e-3, 6.6e-3);
        let mut opts = AdaptiveOptions::new(RkPair::BogackiShampine32);
        opts.pas_mini = Some(h);
        opts.pas_maxi = Some(h);
        let (taken, rk, after, committed, a0) = one_step(0.0, q0, v0, &opts, h);
        assert_eq!((taken.tries, taken.h), (1, h));
        let shock = crate::transient::tests::sdnd100a_friction_shock(0.0);
        let (q, v, a, state) = by_hand(&shock, 1e4, q0, v0, a0, h, committed, true);
        assert_eq!((rk.q2[0], rk.v2[0], rk.a2[0]), (q, v, a));
        assert_eq!(after, state);
        let (q_start, v_start, _, _) = by_hand(&shock, 1e4, q0, v0, a0, h, committed, false);
        eprintln!("chained ({q:e}, {v:e}), from the start's state ({q_start:e}, {v_start:e})");
        assert!((v - v_start).abs() > 1e-6, "{v:e} vs {v_start:e}");
    }
}
