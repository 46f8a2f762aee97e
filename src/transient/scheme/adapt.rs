//! ADAPT_ORDRE1 and ADAPT_ORDRE2: Code_Aster's adaptive explicit schemes, in its own form
//! so that a file gives the same numbers here and there. The step is not controlled by an
//! error estimate but by an *apparent frequency*: the step must resolve the fastest motion
//! the last step showed with NB_POIN_PERIODE points per period.
//!
//! One step of length h from (q₁, v₁, a₁), v₁ being what the previous step carried:
//! - order 2 (a central difference with a half-step velocity):
//!   w = v₁ + c·a₁ (the half-step velocity), q₂ = q₁ + h·w, v₂ = w + (h/2)·a₁,
//!   a₂ = a(t + h, q₂, v₂); the step carries w as its velocity, and archives (q₂, v₂, a₂);
//! - order 1 (the kick-drift of DIFF_CENTRE): v₂ = v₁ + c·a₁, q₂ = q₁ + h·v₂,
//!   a₂ = a(t + h, q₂, v₂); it carries and archives v₂.
//!
//! c is half the sum of the step proposed and the step tried, as Code_Aster writes it: h
//! itself on a step tried at its proposed length, between h and the proposal on a step
//! retried shorter; on the very first step of order 2 the proposal counts as zero (c = h/2:
//! the half step from the initial velocity), order 1 takes a full kick there.
//!
//! The apparent frequency of a step is f = √(max_i |a₂ᵢ − a₁ᵢ| / max(vmin_i·h, |q₂ᵢ − q₁ᵢ|)) / 2π
//! (the curvature of the motion over its travel; a floor of the machine epsilon under
//! the maximum), vmin a reference velocity: 1 % of the last half-step velocity's norm
//! (VITE_MIN='NORM'), or per component the largest 1 % of it met so far ('MAXI'); 1e-15
//! before the first step. The error is e = max(NB_POIN_PERIODE·f·h, 100·ε). A step with
//! e ≥ 1 is retried with h/COEF_DIVI_PAS (at most NMAX_ITER_PAS tries: the last one is
//! kept, with an alarm); once a step passes, the next one is proposed
//! min(PAS_MAXI, h·COEF_MULT_PAS) when e < 0.75 after more than four steps that kept their
//! length, else h. ADAPT_ORDRE1 does not judge its first five steps (e = 0 there).
//!
//! Defaults as Code_Aster's: PAS_MAXI = 10⁶·PAS, PAS_MINI = PAS_LIMI_RELA·PAS; a step
//! below PAS_MINI stops the run. When PAS_MINI equals PAS_MAXI the step is fixed.

/// Which of Code_Aster's two schemes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum AdaptOrder {
    One,
    Two,
}

/// VITE_MIN: the reference velocity of the apparent frequency.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum VelocityFloor {
    /// 'NORM': 1 % of the norm of the last half-step velocity, for every component.
    Norm,
    /// 'MAXI': per component, the largest 1 % of |velocity| met so far.
    Maxi,
}

/// SCHEMA_TEMPS of ADAPT_ORDRE1/ADAPT_ORDRE2, with Code_Aster's defaults.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AdaptOptions {
    pub order: AdaptOrder,
    /// NB_POIN_PERIODE (50).
    pub points_per_period: f64,
    /// NMAX_ITER_PAS (16): tries of one step.
    pub nmax_iter_pas: usize,
    /// COEF_MULT_PAS (1.1).
    pub coef_mult: f64,
    /// COEF_DIVI_PAS (1.3333334).
    pub coef_divi: f64,
    /// PAS_MAXI (default 10⁶·PAS).
    pub pas_maxi: Option<f64>,
    /// PAS_MINI (default PAS_LIMI_RELA·PAS).
    pub pas_mini: Option<f64>,
    /// PAS_LIMI_RELA (1e-6).
    pub pas_limi_rela: f64,
    /// VITE_MIN ('NORM').
    pub velocity_floor: VelocityFloor,
    /// The most steps (accepted and retried) before a runaway integration is stopped.
    pub max_steps: usize,
}

impl AdaptOptions {
    pub fn new(order: AdaptOrder) -> AdaptOptions {
        AdaptOptions {
            order,
            points_per_period: 50.0,
            nmax_iter_pas: 16,
            coef_mult: 1.1,
            coef_divi: 1.333_333_4,
            pas_maxi: None,
            pas_mini: None,
            pas_limi_rela: 1e-6,
            velocity_floor: VelocityFloor::Norm,
            max_steps: 50_000_000,
        }
    }

    /// (PAS_MINI, PAS_MAXI) for the initial step `pas`.
    pub fn bounds(&self, pas: f64) -> (f64, f64) {
        (
            self.pas_mini.unwrap_or(self.pas_limi_rela * pas),
            self.pas_maxi.unwrap_or(1e6 * pas),
        )
    }
}

/// Code_Aster's small numbers: its relative precision (the double's epsilon) and the
/// smallest normal double.
const EPS: f64 = f64::EPSILON;
const TINY: f64 = f64::MIN_POSITIVE;

/// The apparent frequency (Hz) of a step of length `h` from (q1, a1) to (q2, a2).
pub(crate) fn apparent_frequency(
    h: f64,
    q1: &[f64],
    q2: &[f64],
    a1: &[f64],
    a2: &[f64],
    vmin: &[f64],
) -> f64 {
    let mut worst = EPS;
    for i in 0..q1.len() {
        let travel = (q2[i] - q1[i]).abs();
        let mut b = (vmin[i] * h).max(travel);
        if b <= TINY {
            b = EPS;
        }
        worst = worst.max(((a2[i] - a1[i]) / b).abs());
    }
    worst.sqrt() / std::f64::consts::TAU
}

/// The step controller's memory between steps (Code_Aster's "stable steps" counter).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Controller {
    steps_kept: f64,
}

/// What the controller says about a tried step.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Verdict {
    /// The step is too long (e ≥ 1).
    pub too_long: bool,
    /// The next length: a retry's if `too_long`, else the next step's proposal.
    pub next: f64,
}

impl Controller {
    pub fn new() -> Controller {
        Controller { steps_kept: 1.0 }
    }

    /// The verdict on a step of length `h` with error `err`, `pas_maxi` the longest step.
    pub fn judge(&mut self, opts: &AdaptOptions, h: f64, err: f64, pas_maxi: f64) -> Verdict {
        let mut coef = 1.0;
        if err >= 1.0 {
            coef = 1.0 / opts.coef_divi;
        } else if self.steps_kept > 4.5 {
            if err < 0.75 {
                coef = opts.coef_mult;
                self.steps_kept = 1.0;
            }
        } else {
            self.steps_kept += 1.0;
        }
        Verdict {
            too_long: err >= 1.0,
            next: pas_maxi.min(h * coef),
        }
    }
}

/// The error of a step: NB_POIN_PERIODE times its apparent frequency times `h`.
pub(crate) fn step_error(opts: &AdaptOptions, freq: f64, h: f64) -> f64 {
    (opts.points_per_period * freq * h).max(100.0 * EPS)
}

/// The reference velocity for the next step's apparent frequency, from the velocity `w`
/// the step carries (VITE_MIN).
pub(crate) fn update_vmin(rule: VelocityFloor, w: &[f64], vmin: &mut [f64]) {
    match rule {
        VelocityFloor::Norm => {
            let norm = w.iter().map(|x| x * x).sum::<f64>().sqrt() * 0.01;
            vmin.iter_mut().for_each(|v| *v = norm);
        }
        VelocityFloor::Maxi => {
            for (v, x) in vmin.iter_mut().zip(w) {
                *v = (x * 0.01).abs().max(*v);
            }
        }
    }
}

/// The new state of a step of length `h` with kick coefficient `c` (module doc): fills
/// q2, v2 (the velocity the forces see at the end) and `carried` (the velocity the next
/// step starts from: the half-step one for order 2, v2 for order 1).
#[allow(clippy::too_many_arguments)]
pub(crate) fn advance(
    order: AdaptOrder,
    h: f64,
    c: f64,
    q1: &[f64],
    v1: &[f64],
    a1: &[f64],
    q2: &mut [f64],
    v2: &mut [f64],
    carried: &mut [f64],
) {
    for i in 0..q1.len() {
        let w = v1[i] + a1[i] * c;
        q2[i] = q1[i] + w * h;
        carried[i] = w;
        v2[i] = match order {
            AdaptOrder::Two => w + 0.5 * h * a1[i],
            AdaptOrder::One => w,
        };
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn apparent_frequency_of_a_harmonic_step_is_its_own() {
        // q = cos ωt over a short step from t = 0.3: |Δa|/|Δq| = ω², whatever the step.
        let w = 7.0f64;
        let h = 1e-3;
        let q = |t: f64| (w * t).cos();
        let a = |t: f64| -w * w * (w * t).cos();
        let f = apparent_frequency(
            h,
            &[q(0.3)],
            &[q(0.3 + h)],
            &[a(0.3)],
            &[a(0.3 + h)],
            &[0.0],
        );
        assert!((f - w / std::f64::consts::TAU).abs() < 1e-9 * f, "{f}");
    }

    #[test]
    fn velocity_floor_bounds_the_frequency_of_a_step_at_rest() {
        // No travel: the floor vmin·h stands in for it.
        let f = apparent_frequency(0.1, &[1.0], &[1.0], &[0.0], &[4.0], &[10.0]);
        let expect = (4.0f64 / 1.0).sqrt() / std::f64::consts::TAU;
        assert!((f - expect).abs() < 1e-12, "{f}");
    }

    #[test]
    fn controller_shrinks_at_once_and_grows_after_five_steps() {
        let o = AdaptOptions::new(AdaptOrder::Two);
        let mut c = Controller::new();
        let v = c.judge(&o, 1.0, 1.2, 10.0);
        assert!(v.too_long && (v.next - 1.0 / 1.333_333_4).abs() < 1e-15);
        // Four quiet steps keep the length, the fifth grows it by COEF_MULT_PAS.
        for _ in 0..4 {
            let v = c.judge(&o, 1.0, 0.5, 10.0);
            assert!(!v.too_long && v.next == 1.0);
        }
        let v = c.judge(&o, 1.0, 0.5, 10.0);
        assert!((v.next - 1.1).abs() < 1e-15);
        // Growth is capped by PAS_MAXI.
        let mut c = Controller { steps_kept: 5.0 };
        assert_eq!(c.judge(&o, 1.0, 0.1, 1.05).next, 1.05);
        // An error between 0.75 and 1 neither grows nor resets the count.
        let mut c = Controller { steps_kept: 5.0 };
        assert_eq!(c.judge(&o, 1.0, 0.8, 10.0).next, 1.0);
        assert_eq!(c.steps_kept, 5.0);
    }

    #[test]
    fn order_two_is_the_central_difference() {
        // q'' = −q from q = 1, v = 0: after the half-step start, the positions follow
        // q_{n+1} − 2q_n + q_{n−1} = h² a_n.
        let h = 0.01;
        let (mut q, mut v, mut a) = (vec![1.0], vec![0.0], vec![-1.0]);
        let (mut q2, mut v2, mut w) = (vec![0.0], vec![0.0], vec![0.0]);
        let mut hist = vec![q[0]];
        for k in 0..3 {
            let c = if k == 0 { 0.5 * h } else { h };
            advance(AdaptOrder::Two, h, c, &q, &v, &a, &mut q2, &mut v2, &mut w);
            q.copy_from_slice(&q2);
            v.copy_from_slice(&w);
            a[0] = -q[0];
            hist.push(q[0]);
        }
        for n in 1..3 {
            let lhs = hist[n + 1] - 2.0 * hist[n] + hist[n - 1];
            assert!((lhs - h * h * (-hist[n])).abs() < 1e-15, "{n}");
        }
        // The first step is the Taylor step q0 + h v0 + h²/2 a0.
        assert!((hist[1] - (1.0 - 0.5 * h * h)).abs() < 1e-16);
    }
}
