//! DEVOGE: Code_Aster's adaptive Devogelaere–Fu scheme (SCHEMA_TEMPS SCHEMA='DEVOGE'), as
//! Code_Aster runs it (its routines `intdevo`, `intdevo_oper` and the driver `dtmcalc`),
//! so that its validation files give its numbers.
//!
//! Notation: h the step, t₁ its start; "g" is the acceleration without the damping term,
//! g = M⁻¹(f(t) + Σ shocks − K q), and C̃ = M⁻¹C. The scheme carries two states: level 1
//! (q₁, v₁, g₁ at t₁) and level 2 (q₂, v₂, g₂, the previous step's mid-point, nominally
//! at t₁ − h/2). A step:
//!   q₃ = q₁ + (h/2) v₁ + (h²/24) (4 g₁ − g₂ − C̃ (4 v₁ − v₂))                  (t₁ + h/2)
//!   g₃ from q₃ and the velocity of the chord, (q₃ − q₁)/(h/2)
//!   (4 + h C̃) v₃ = 4 v₁ + h (g₁ + g₃ − C̃ v₁)
//!   q₄ = q₁ + h v₁ + (h²/6) (g₁ + 2 g₃ − C̃ (v₁ + 2 v₃))                       (t₁ + h)
//!   g₄ from q₄ and the chord velocity (q₄ − q₃)/(h/2)
//!   (6 + h C̃) v₄ = 6 v₁ + h (g₁ + 4 g₃ + g₄ − C̃ (v₁ + 4 v₃))
//!   a₄ = g₄ − C̃ v₄,
//! then level 2 ← (q₃, v₃, g₃) and level 1 ← (q₄, v₄, g₄); the state left (and archived)
//! is (q₄, v₄, a₄). The shocks see the chord velocities, not v₃ and v₄, and their memory
//! (stick anchor, stick/slip flag) runs through the step as in Code_Aster: the mid-point
//! evaluation starts from the committed state, the end one from the mid-point's result;
//! the end's state is committed when the step is accepted, and a rejected try starts
//! again from the committed state.
//!
//! The very first step builds level 2 from the start state: q₂ = q₁ − (h/2) v₁ +
//! (h/8)(g₁ − C̃ v₁) (Code_Aster's factor is h/8, not h²/8: kept, its results come from
//! it), g₂ the start's forces with q₂ in the stiffness term, and
//! (4 − h C̃) v₂ = (4 + h C̃) v₁ − h (g₁ + g₂).
//!
//! Error (when PAS_MINI ≠ PAS_MAXI, i.e. always with the defaults): the mid-point q₃ is
//! estimated again by a Taylor expansion, from the step's end when the last steps had the
//! same length (ê₃ = q₄ − (h/2) v₄ + (h²/96)(7 g₄ + 6 g₃ − g₁)), from its start otherwise
//! (ê₃ = q₁ + (h/2) v₁ + (h²/96)(7 g₁ + 6 g₃ − g₄)); ê₂, the same estimate made at the
//! previous step, is its counterpart at level 2. The local error per component is
//! ((ê₃ − q₃) − α₁(ê₂ − q₂)) / β (times α₂ on the first term after two changes of step),
//! with α, β set by the ratios of the current and the two previous half steps: constant
//! step α₁ = 1, β = 45 h/8; one change (c₁ = h/h_prev) α₁ = c₁³(2 + c₁)/3, β = 5 (h_prev/2)
//! (12 + 7c₁ − c₁²)/(8 c₁); two changes, a longer formula (`estimate`). (Code_Aster also
//! has a case for "the second step after a change", but its test compares a step with
//! itself and never holds: such steps take the constant-step case, here too.) The error
//! is ‖e‖₂ (h/2) / n against TOLERANCE · (‖max(|q₃|, |h v₃|)‖₂ / n + ALPHA), n the
//! number of unknowns. (The estimates are written with g, without the damping term: with
//! damping the damping force counts as error and the steps come out short.) On the first retry of a step ê₂ is rebuilt from the previous step's
//! start state: ê₂ = q₁′ + (h′/2) v₁′ + (h′²/96)(7 g₁′ + 6 g₂ − g₁), primes for that step
//! (h′ its length), g₂ as moved for the retry. For the first step Code_Aster takes the
//! start itself there, with its raw generalized force f(t₀) in place of g₁′ (it saves
//! the start before turning its force into g): kept, as sdnd100b's values depend on it.
//!
//! Step control: with r the error over its allowance, the next step is h·f, f = 1.5 when
//! r < (0.9/1.5)⁴, 0.5 when r > (0.9/0.5)⁴, 0.9 r^(−1/4) between, clamped to
//! [PAS_MINI, PAS_MAXI] (defaults 1e-10 and 1e10 times the first step); an accepted step
//! keeps h when f is within 15 % of 1. A step with r > 1 is tried again with the new h (up
//! to 25 tries; the 25th is kept whatever its error: Code_Aster has no NMAX_ITER_PAS
//! here); on a retry level 2 is moved linearly towards level 1 to sit half the new step
//! back. A change of h between accepted steps does not move level 2 (Code_Aster's form:
//! the error estimate accounts for the change). A retry that cannot shorten the step (at
//! PAS_MINI) stops the run ([`TransientError::StepTooSmall`]).
//!
//! Driver (Code_Aster's `dtmcalc`): the first step is PAS. The archive instants (the
//! listed ones after t₀, then INST_FIN) are landed on exactly: a step that would pass the
//! next one is cut to it, and once it is reached the next step is the part cut off (the
//! controller's proposal is dropped there). With PAS_ARCH = k, step i is archived when
//! i − (number of cut steps that reached an instant) is a multiple of k. Instants are
//! compared with Code_Aster's tolerance, i·10·ε (i the step count, ε the double
//! precision).
//!
//! Workspaces are allocated once; with a damping matrix the two velocity matrices
//! 4M + hC and 6M + hC are factorised again when h changes (without damping they are
//! multiples of M and cost nothing).

// The step's formulas are component-wise over several vectors at once; indexing keeps them
// readable next to the module doc.
#![allow(clippy::needless_range_loop)]

use super::archive::Recorder;
use super::dis_choc::{Shock, ShockEval};
use super::driver::{drive, DrivenScheme, DriverSettings, DriverStats, Taken as DriverTaken};
use super::error::{invalid, try_zeros, TransientError};
use super::problem::{Archive, TimeGrid};
use super::structure::{LinearSolver, Structure};
use super::system::{commit, finite, Model, Work};

/// Code_Aster's machine precision (r8prem): the double epsilon.
const EPS: f64 = f64::EPSILON;
/// Tries of one step; the last is kept whatever its error.
const MAX_TRIES: usize = 25;
/// Largest growth and shrink factors of the step, and the controller's safety factor.
const GROW: f64 = 1.5;
const SHRINK: f64 = 0.5;
const SAFETY: f64 = 0.9;
/// An accepted step whose factor is within this of 1 keeps its length.
const DEAD_BAND: f64 = 0.15;

/// SCHEMA_TEMPS keywords of DEVOGE.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DevogeOptions {
    /// TOLERANCE (Code_Aster's default 1e-5), relative to the mean size of the
    /// mid-point displacement (module doc).
    pub tolerance: f64,
    /// ALPHA (default 0): added to that size (an absolute floor, in displacement units).
    pub alpha: f64,
    /// PAS_MINI (default: 1e-10 times the first step).
    pub pas_mini: Option<f64>,
    /// PAS_MAXI (default: 1e10 times the first step; must not be below PAS).
    pub pas_maxi: Option<f64>,
    /// The most steps (accepted and retried) before a runaway integration is stopped.
    pub max_steps: usize,
}

impl Default for DevogeOptions {
    fn default() -> Self {
        DevogeOptions {
            tolerance: 1e-5,
            alpha: 0.0,
            pas_mini: None,
            pas_maxi: None,
            max_steps: 50_000_000,
        }
    }
}

impl DevogeOptions {
    /// Checks the values (before the run).
    pub(crate) fn check(&self, pas: f64) -> Result<(), TransientError> {
        if !(self.tolerance.is_finite() && self.tolerance > 0.0) {
            return Err(invalid("SCHEMA_TEMPS/TOLERANCE", "must be > 0"));
        }
        if !(self.alpha.is_finite() && self.alpha >= 0.0) {
            return Err(invalid("SCHEMA_TEMPS/ALPHA", "must be ≥ 0"));
        }
        let positive = |x: f64| x.is_finite() && x > 0.0;
        if self.pas_mini.is_some_and(|x| !positive(x)) {
            return Err(invalid("SCHEMA_TEMPS/PAS_MINI", "must be > 0"));
        }
        if let Some(hi) = self.pas_maxi {
            if !positive(hi) {
                return Err(invalid("SCHEMA_TEMPS/PAS_MAXI", "must be > 0"));
            }
            if hi < pas {
                return Err(invalid(
                    "SCHEMA_TEMPS/PAS_MAXI",
                    format!("PAS_MAXI = {hi:e} is below PAS = {pas:e}"),
                ));
            }
            if self.pas_mini.is_some_and(|lo| hi < lo) {
                return Err(invalid(
                    "SCHEMA_TEMPS/PAS_MINI",
                    "PAS_MINI must be ≤ PAS_MAXI",
                ));
            }
        }
        Ok(())
    }
}

/// M⁻¹ products and the two velocity solves, (4M + hC)⁻¹M and (6M + hC)⁻¹M.
struct Operators<'s> {
    structure: &'s dyn Structure,
    damped: bool,
    /// The step of the factors below.
    h: f64,
    four: Option<Box<dyn LinearSolver + 's>>,
    six: Option<Box<dyn LinearSolver + 's>>,
    tmp: Vec<f64>,
}

impl<'s> Operators<'s> {
    fn new(structure: &'s dyn Structure) -> Result<Operators<'s>, TransientError> {
        Ok(Operators {
            structure,
            damped: structure.has_damping(),
            h: f64::NAN,
            four: None,
            six: None,
            tmp: try_zeros("DEVOGE's workspace", structure.n())?,
        })
    }

    /// out ← C̃ x = M⁻¹ C x (zero without damping).
    fn damp(&self, x: &[f64], out: &mut [f64]) -> Result<(), TransientError> {
        if self.damped {
            self.structure.apply_damping(x, out);
            self.structure.solve_mass(out)
        } else {
            out.iter_mut().for_each(|o| *o = 0.0);
            Ok(())
        }
    }

    /// out ← M⁻¹ K x.
    fn stiff(&self, x: &[f64], out: &mut [f64]) -> Result<(), TransientError> {
        self.structure.apply_stiffness(x, out);
        self.structure.solve_mass(out)
    }

    /// y ← (w I + h C̃)⁻¹ y, w = 4 or 6.
    fn velocity_solve(&mut self, w: f64, h: f64, y: &mut [f64]) -> Result<(), TransientError> {
        if !self.damped {
            y.iter_mut().for_each(|v| *v /= w);
            return Ok(());
        }
        if self.h != h || self.four.is_none() || self.six.is_none() {
            self.four = Some(self.structure.factor(4.0, h, 0.0)?);
            self.six = Some(self.structure.factor(6.0, h, 0.0)?);
            self.h = h;
        }
        let solver = if w == 4.0 {
            self.four.as_mut()
        } else {
            self.six.as_mut()
        };
        let Some(solver) = solver else {
            return Err(TransientError::Singular {
                what: "DEVOGE's velocity matrix".into(),
            });
        };
        self.structure.apply_mass(y, &mut self.tmp);
        solver.solve(&mut self.tmp)?;
        y.copy_from_slice(&self.tmp);
        Ok(())
    }
}

/// g ← M⁻¹(f(t) − K q + Σ shocks(q, v)), each shock evaluated from the state in `from`
/// (its committed state when `None`); the evaluations go to `evals`.
#[allow(clippy::too_many_arguments)]
fn load(
    model: &Model,
    shocks: &[Shock],
    from: Option<&[ShockEval]>,
    t: f64,
    q: &[f64],
    v: &[f64],
    g: &mut [f64],
    evals: &mut [ShockEval],
) -> Result<(), TransientError> {
    let s = model.structure;
    s.apply_stiffness(q, g);
    g.iter_mut().for_each(|x| *x = -*x);
    for f in model.forcing {
        let m = (f.multiplier)(t);
        if m != 0.0 {
            g.iter_mut()
                .zip(&f.generalized_force)
                .for_each(|(r, p)| *r += m * p);
        }
    }
    for (i, shock) in shocks.iter().enumerate() {
        let state = match from {
            Some(prev) => &prev[i].sample.state,
            None => &shock.state,
        };
        let ev = shock.evaluate_at(t, q, v, state);
        shock.add_generalized(&ev, g);
        evals[i] = ev;
    }
    s.solve_mass(g)
}

/// The history the step before gives the error estimate.
#[derive(Clone, Copy, PartialEq, Eq)]
enum History {
    /// The step and the two before it of the same length.
    Constant,
    /// The step differs from the last, which had the length of the one before.
    OneChange,
    /// The step differs from the last, which differed from the one before.
    TwoChanges,
}

/// The scheme's state between steps and its workspaces.
struct Devoge {
    n: usize,
    started: bool,
    adaptive: bool,
    tol: f64,
    alpha: f64,
    pas_mini: f64,
    pas_maxi: f64,
    /// The two last accepted steps (older first).
    pas: [f64; 2],
    /// The step the level-2 state and the operators were last set for.
    h_old: f64,
    q1: Vec<f64>,
    v1: Vec<f64>,
    a1: Vec<f64>,
    g1: Vec<f64>,
    q2: Vec<f64>,
    v2: Vec<f64>,
    g2: Vec<f64>,
    q3: Vec<f64>,
    v3: Vec<f64>,
    g3: Vec<f64>,
    q4: Vec<f64>,
    v4: Vec<f64>,
    a4: Vec<f64>,
    g4: Vec<f64>,
    x: Vec<f64>,
    cx: Vec<f64>,
    /// The estimates of q at level 2 and at the mid-point (module doc).
    e2: Vec<f64>,
    e3: Vec<f64>,
    /// Level 1 of the previous step.
    q1p: Vec<f64>,
    v1p: Vec<f64>,
    g1p: Vec<f64>,
    evals3: Vec<ShockEval>,
    evals4: Vec<ShockEval>,
}

/// One accepted step.
struct Taken {
    h: f64,
    next: f64,
    tries: usize,
}

impl Devoge {
    fn new(
        opts: &DevogeOptions,
        ops: &Operators,
        q0: &[f64],
        v0: &[f64],
        a0: &[f64],
        evals: &[ShockEval],
    ) -> Result<Devoge, TransientError> {
        let n = q0.len();
        let z = || try_zeros("DEVOGE's state", n);
        let mut d = Devoge {
            n,
            started: false,
            adaptive: true,
            tol: opts.tolerance,
            alpha: opts.alpha,
            pas_mini: 0.0,
            pas_maxi: 0.0,
            pas: [0.0; 2],
            h_old: 0.0,
            q1: z()?,
            v1: z()?,
            a1: z()?,
            g1: z()?,
            q2: z()?,
            v2: z()?,
            g2: z()?,
            q3: z()?,
            v3: z()?,
            g3: z()?,
            q4: z()?,
            v4: z()?,
            a4: z()?,
            g4: z()?,
            x: z()?,
            cx: z()?,
            e2: z()?,
            e3: z()?,
            q1p: z()?,
            v1p: z()?,
            g1p: z()?,
            evals3: evals.to_vec(),
            evals4: evals.to_vec(),
        };
        d.q1.copy_from_slice(q0);
        d.v1.copy_from_slice(v0);
        d.a1.copy_from_slice(a0);
        // g₁ = a₀ + C̃ v₀: the start's acceleration without its damping term.
        ops.damp(v0, &mut d.cx)?;
        for i in 0..n {
            d.g1[i] = a0[i] + d.cx[i];
        }
        Ok(d)
    }

    /// The first step's set-up, for its length h (module doc).
    fn start(
        &mut self,
        opts: &DevogeOptions,
        ops: &mut Operators,
        h: f64,
    ) -> Result<(), TransientError> {
        let n = self.n;
        self.pas_mini = opts.pas_mini.unwrap_or(1e-10 * h);
        self.pas_maxi = opts.pas_maxi.unwrap_or(1e10 * h);
        self.adaptive = (self.pas_maxi / self.pas_mini - 1.0).abs() >= EPS;
        let h1 = h / 2.0;
        // g2 first holds M⁻¹ f₁ (the start's forces), x holds M⁻¹K q₁.
        ops.stiff(&self.q1, &mut self.x)?;
        for i in 0..n {
            self.g2[i] = self.g1[i] + self.x[i];
        }
        // Code_Aster keeps the start's level 1 for the first retry's level-2 estimate
        // before it turns its force into g: that force is f₁ itself, M (M⁻¹ f₁).
        ops.structure.apply_mass(&self.g2, &mut self.g1p);
        ops.damp(&self.v1, &mut self.cx)?;
        let c8 = h1 / 4.0;
        for i in 0..n {
            self.q2[i] = self.q1[i] - h1 * self.v1[i] + c8 * (self.g1[i] - self.cx[i]);
        }
        ops.stiff(&self.q2, &mut self.x)?;
        for i in 0..n {
            self.g2[i] -= self.x[i];
        }
        if ops.damped {
            // (4M − hC) v₂ = M (4 v₁ − h (g₁ + g₂)) + h C v₁.
            let s = ops.structure;
            for i in 0..n {
                self.x[i] = 4.0 * self.v1[i] - h * (self.g1[i] + self.g2[i]);
            }
            s.apply_mass(&self.x, &mut self.v2);
            s.apply_damping(&self.v1, &mut self.cx);
            for i in 0..n {
                self.v2[i] += h * self.cx[i];
            }
            let mut h0 = s.factor(4.0, -h, 0.0)?;
            h0.solve(&mut self.v2)?;
        } else {
            for i in 0..n {
                self.v2[i] = (4.0 * self.v1[i] - h * (self.g1[i] + self.g2[i])) / 4.0;
            }
        }
        if self.adaptive {
            let w = h1.powf(2.0) / 24.0;
            for i in 0..n {
                self.e2[i] = (2.0 * self.q2[i] - self.q1[i])
                    + h1 * (2.0 * self.v2[i] - self.v1[i])
                    + w * (13.0 * self.g1[i]);
            }
        }
        self.pas = [h, h];
        self.q1p.copy_from_slice(&self.q1);
        self.v1p.copy_from_slice(&self.v1);
        self.h_old = h;
        self.started = true;
        Ok(())
    }

    /// One try of length h from level 1 at t1: levels 3 and 4.
    fn attempt(
        &mut self,
        model: &Model,
        shocks: &[Shock],
        ops: &mut Operators,
        t1: f64,
        h: f64,
    ) -> Result<(), TransientError> {
        let n = self.n;
        let (h1, h2, h3) = (h / 2.0, h / 4.0, h / 6.0);
        let (h4, h5) = (h * h / 24.0, h * h / 6.0);
        for i in 0..n {
            self.x[i] = 4.0 * self.v1[i] - self.v2[i];
        }
        ops.damp(&self.x, &mut self.cx)?;
        for i in 0..n {
            self.q3[i] =
                self.q1[i] + h1 * self.v1[i] + h4 * (4.0 * self.g1[i] - self.g2[i] - self.cx[i]);
            // The chord's velocity, which the shocks see.
            self.v3[i] = (self.q3[i] - self.q1[i]) / h1;
        }
        load(
            model,
            shocks,
            None,
            t1 + h1,
            &self.q3,
            &self.v3,
            &mut self.g3,
            &mut self.evals3,
        )?;
        ops.damp(&self.v1, &mut self.cx)?;
        for i in 0..n {
            self.v3[i] = 4.0 * (self.v1[i] + h2 * (self.g1[i] + self.g3[i] - self.cx[i]));
        }
        ops.velocity_solve(4.0, h, &mut self.v3)?;
        for i in 0..n {
            self.x[i] = self.v1[i] + 2.0 * self.v3[i];
        }
        ops.damp(&self.x, &mut self.cx)?;
        for i in 0..n {
            self.q4[i] =
                self.q1[i] + h * self.v1[i] + h5 * (self.g1[i] + 2.0 * self.g3[i] - self.cx[i]);
            self.v4[i] = (self.q4[i] - self.q3[i]) / h1;
        }
        load(
            model,
            shocks,
            Some(&self.evals3),
            t1 + h,
            &self.q4,
            &self.v4,
            &mut self.g4,
            &mut self.evals4,
        )?;
        for i in 0..n {
            self.x[i] = 4.0 * self.v3[i] + self.v1[i];
        }
        ops.damp(&self.x, &mut self.cx)?;
        for i in 0..n {
            self.v4[i] =
                6.0 * (self.v1[i] + h3 * (self.g4[i] + 4.0 * self.g3[i] + self.g1[i] - self.cx[i]));
        }
        ops.velocity_solve(6.0, h, &mut self.v4)?;
        ops.damp(&self.v4, &mut self.cx)?;
        for i in 0..n {
            self.a4[i] = self.g4[i] - self.cx[i];
        }
        Ok(())
    }

    /// The try's error over its allowance (module doc); `retry` is the number of tries
    /// of this step before this one.
    fn estimate(&mut self, h: f64, retry: usize) -> f64 {
        let n = self.n;
        let h1 = h / 2.0;
        let [old, last] = self.pas;
        let same_now = (h - last).abs() <= EPS;
        let same_before = (last - old).abs() <= EPS;
        let history = match (same_now, same_before) {
            (false, true) => History::OneChange,
            (false, false) => History::TwoChanges,
            _ => History::Constant,
        };
        let w = h1.powf(2.0) / 24.0;
        if history == History::Constant {
            for i in 0..n {
                self.e3[i] = self.q4[i] - h1 * self.v4[i]
                    + w * (7.0 * self.g4[i] + 6.0 * self.g3[i] - self.g1[i]);
            }
        } else {
            for i in 0..n {
                self.e3[i] = self.q1[i]
                    + h1 * self.v1[i]
                    + w * (7.0 * self.g1[i] + 6.0 * self.g3[i] - self.g4[i]);
            }
        }
        let (p0, p1) = (old / 2.0, last / 2.0);
        if retry == 1 {
            let wp = p1.powf(2.0) / 24.0;
            for i in 0..n {
                self.e2[i] = self.q1p[i]
                    + p1 * self.v1p[i]
                    + wp * (7.0 * self.g1p[i] + 6.0 * self.g2[i] - self.g1[i]);
            }
        }
        let (a2, a1, beta) = match history {
            History::Constant => (1.0, 1.0, 45.0 * h1 / 4.0),
            History::OneChange => {
                let c1 = h1 / p1;
                let a1 = c1.powf(3.0) * (2.0 + c1) / 3.0;
                let beta = 5.0 * p1 * (12.0 + 7.0 * c1 - c1.powf(2.0)) / (8.0 * c1);
                (1.0, a1, beta)
            }
            History::TwoChanges => {
                let c0 = p1 / p0;
                let c1 = h1 / p1;
                let a1 = c1.powf(3.0) * (2.0 + c1) / 3.0;
                let a2 = (1.0 + 2.0 / c0) / 3.0;
                let beta = 5.0
                    * h1
                    * (c0 * c0 * (12.0 + 7.0 * c1 - c1 * c1)
                        + c0 * (20.0 + 12.0 * c1 - 2.0 * (c1 * c1))
                        + 2.0 * c1
                        + 4.0)
                    / (24.0 * c0.powf(2.0) * c1.powf(2.0));
                (a2, a1, beta)
            }
        };
        let mut sum = 0.0;
        for i in 0..n {
            let d3 = self.e3[i] - self.q3[i];
            let d2 = self.e2[i] - self.q2[i];
            let e = if history == History::TwoChanges {
                (a2 * d3 - a1 * d2) / beta
            } else if history == History::OneChange {
                (d3 - a1 * d2) / beta
            } else {
                (d3 - d2) / beta
            };
            sum += e.powf(2.0);
        }
        let err = sum.sqrt() * h1 / n as f64;
        let mut size = 0.0;
        for i in 0..n {
            size += self.q3[i].abs().max((self.v3[i] * h).abs()).powf(2.0);
        }
        let size = size.sqrt() / n as f64;
        let allowed = self.tol * (size + self.alpha);
        if allowed <= EPS {
            // Nothing to measure against: the factor comes out as exactly 1.
            SAFETY.powf(4.0)
        } else {
            err / allowed
        }
    }

    /// Moves level 2 to sit half of the step h back, after a try of length h_old.
    fn shift_level2(&mut self, ratio: f64) {
        for i in 0..self.n {
            self.g2[i] = self.g1[i] + ratio * (self.g2[i] - self.g1[i]);
            self.q2[i] = self.q1[i] + ratio * (self.q2[i] - self.q1[i]);
            self.v2[i] = self.v1[i] + ratio * (self.v2[i] - self.v1[i]);
        }
    }

    /// One step from t1 starting with length h, retried shorter while its error is too
    /// large; leaves levels 3 and 4 and the end's shock evaluations for the caller to
    /// accept.
    fn step(
        &mut self,
        model: &Model,
        shocks: &[Shock],
        opts: &DevogeOptions,
        ops: &mut Operators,
        t1: f64,
        mut h: f64,
    ) -> Result<Taken, TransientError> {
        if !self.started {
            self.start(opts, ops, h)?;
        }
        let mut tries = 0usize;
        let mut next = h;
        loop {
            let ratio = h / self.h_old;
            if (ratio - 1.0).abs() >= EPS && tries > 0 {
                self.shift_level2(ratio);
            }
            self.attempt(model, shocks, ops, t1, h)?;
            if !(finite(&self.q4) && finite(&self.v4) && finite(&self.a4)) {
                return Err(TransientError::NonFinite { t: t1 + h });
            }
            self.h_old = h;
            if !self.adaptive {
                break;
            }
            let r = self.estimate(h, tries);
            let grow = if r < (SAFETY / GROW).powf(4.0) {
                GROW
            } else if r > (SAFETY / SHRINK).powf(4.0) {
                SHRINK
            } else {
                SAFETY * r.powf(-0.25)
            };
            tries += 1;
            next = (grow * h).max(self.pas_mini).min(self.pas_maxi);
            let factor = next / h;
            if r < 1.0 && (factor - 1.0).abs() < DEAD_BAND {
                next = h;
            }
            if r > 1.0 && tries < MAX_TRIES {
                if (factor - 1.0).abs() < EPS {
                    return Err(TransientError::StepTooSmall {
                        t: t1,
                        dt: h,
                        pas_mini: self.pas_mini,
                    });
                }
                h = next;
                continue;
            }
            break;
        }
        Ok(Taken {
            h,
            next,
            tries: tries.max(1),
        })
    }

    /// Makes the try just made the new level 1 (and its mid-point level 2).
    fn accept(&mut self, h: f64) {
        if self.adaptive {
            self.q1p.copy_from_slice(&self.q1);
            self.v1p.copy_from_slice(&self.v1);
            self.g1p.copy_from_slice(&self.g1);
            self.e2.copy_from_slice(&self.e3);
            self.pas = [self.pas[1], h];
        }
        self.q2.copy_from_slice(&self.q3);
        self.v2.copy_from_slice(&self.v3);
        self.g2.copy_from_slice(&self.g3);
        self.q1.copy_from_slice(&self.q4);
        self.v1.copy_from_slice(&self.v4);
        self.a1.copy_from_slice(&self.a4);
        self.g1.copy_from_slice(&self.g4);
    }
}

/// Devoge under Code_Aster's driver.
struct Driven<'o, 's> {
    dev: Devoge,
    opts: &'o DevogeOptions,
    ops: Operators<'s>,
}

impl DrivenScheme for Driven<'_, '_> {
    fn step(
        &mut self,
        model: &Model,
        shocks: &mut [Shock],
        _ws: &mut Work,
        t: f64,
        h: f64,
    ) -> Result<DriverTaken, TransientError> {
        let taken = self
            .dev
            .step(model, shocks, self.opts, &mut self.ops, t, h)?;
        Ok(DriverTaken {
            h: taken.h,
            next: taken.next,
            tries: taken.tries,
        })
    }

    fn accept(&mut self, shocks: &mut [Shock], ws: &mut Work, h: f64) {
        self.dev.accept(h);
        ws.evals.copy_from_slice(&self.dev.evals4);
        commit(shocks, &ws.evals);
    }

    fn state(&self) -> (&[f64], &[f64], &[f64]) {
        (&self.dev.q1, &self.dev.v1, &self.dev.a1)
    }
}

/// Runs from (q, v, a) at t0 (shock states committed, t0 archived with PAS_ARCH) to
/// t_end under Code_Aster's driver (driver.rs).
#[allow(clippy::too_many_arguments)]
pub(crate) fn run_devoge(
    model: &Model,
    shocks: &mut [Shock],
    opts: &DevogeOptions,
    q0: &[f64],
    v0: &[f64],
    a0: &[f64],
    grid: TimeGrid,
    archive: &Archive,
    rec: &mut Recorder,
    ws: &mut Work,
    progress: &mut dyn FnMut(f64),
) -> Result<DriverStats, TransientError> {
    opts.check(grid.dt)?;
    let ops = Operators::new(model.structure)?;
    let dev = Devoge::new(opts, &ops, q0, v0, a0, &ws.evals)?;
    let mut scheme = Driven { dev, opts, ops };
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

    /// A step whose first tries are rejected: the accepted try's mid-point evaluation
    /// starts from the committed state (not from a rejected try's end) and its end from
    /// the mid-point's result; nothing is committed by `step`.
    #[test]
    fn a_rejected_try_leaves_the_shock_state_as_committed() {
        // k x0 = 0.5 N < μ F_N = 1 N: the mass is held; a long try slides it and reverses.
        let structure = DenseStructure::diagonal(vec![1.0], vec![1e4], None).unwrap();
        let model = Model {
            structure: &structure,
            forcing: &[],
        };
        let mut shocks = vec![crate::transient::tests::sdnd100a_friction_shock(1280.0)];
        let mut ws = Work::new(1, &shocks).unwrap();
        let (q0, v0) = ([0.5e-4], [0.0]);
        let mut a0 = [0.0];
        model
            .acceleration(&shocks, 0.0, &q0, &v0, &mut a0, &mut ws)
            .unwrap();
        commit(&mut shocks, &ws.evals);
        let committed = shocks[0].state;
        let opts = DevogeOptions {
            tolerance: 1e-8,
            ..DevogeOptions::default()
        };
        let h0 = 2e-3;
        // The end state of the first try alone, as a leaking implementation would carry it.
        let mut ops = Operators::new(&structure).unwrap();
        let mut first = Devoge::new(&opts, &ops, &q0, &v0, &a0, &ws.evals).unwrap();
        first.start(&opts, &mut ops, h0).unwrap();
        first.attempt(&model, &shocks, &mut ops, 0.0, h0).unwrap();
        let leaked = first.evals4[0].sample.state;
        assert_ne!(leaked, committed);

        let mut ops = Operators::new(&structure).unwrap();
        let mut dev = Devoge::new(&opts, &ops, &q0, &v0, &a0, &ws.evals).unwrap();
        let taken = dev.step(&model, &shocks, &opts, &mut ops, 0.0, h0).unwrap();
        assert!(taken.tries >= 2, "{} tries", taken.tries);
        assert!(taken.h < h0);
        assert_eq!(shocks[0].state, committed);
        let h1 = taken.h / 2.0;
        let chord3 = [(dev.q3[0] - dev.q1[0]) / h1];
        let from_committed = shocks[0].evaluate_at(h1, &dev.q3, &chord3, &committed);
        assert_eq!(dev.evals3[0], from_committed);
        // With the rejected try's state the mid-point force would differ: the test bites.
        let from_leaked = shocks[0].evaluate_at(h1, &dev.q3, &chord3, &leaked);
        assert_ne!(from_leaked, from_committed);
        let chord4 = [(dev.q4[0] - dev.q3[0]) / h1];
        let end = shocks[0].evaluate_at(taken.h, &dev.q4, &chord4, &dev.evals3[0].sample.state);
        assert_eq!(dev.evals4[0], end);
    }

    /// The start's level 2 as Code_Aster builds it (module doc), on m = 2, k = 8 from x = 1
    /// at rest under f = 6: g₁ = (6 − 8)/2 = −1, q₂ = 1 + (h/8) g₁ (the factor h/8 kept),
    /// g₂ = 6/2 − 4 q₂, v₂ = −(h/4)(g₁ + g₂); the first retry's force there is f itself.
    #[test]
    fn the_start_follows_code_aster() {
        let structure = DenseStructure::diagonal(vec![2.0], vec![8.0], None).unwrap();
        let mut ops = Operators::new(&structure).unwrap();
        let opts = DevogeOptions::default();
        let mut dev = Devoge::new(&opts, &ops, &[1.0], &[0.0], &[-1.0], &[]).unwrap();
        let h = 0.1;
        dev.start(&opts, &mut ops, h).unwrap();
        let q2 = 1.0 - h / 8.0;
        let g2 = 3.0 - 4.0 * q2;
        assert!((dev.q2[0] - q2).abs() < 1e-15);
        assert!((dev.g2[0] - g2).abs() < 1e-14);
        assert!((dev.v2[0] + h / 4.0 * (-1.0 + g2)).abs() < 1e-15);
        assert_eq!(dev.g1p[0], 6.0);
        assert_eq!(dev.pas, [h, h]);
    }
}
