//! The data of a transient run besides the structure and the shocks: external forcing
//! (EXCIT), the time grid (INCREMENT), the archive request (ARCHIVAGE), the result
//! ([`Trajectory`]) and the located contact changes.

use super::dis_choc::ShockSample;

/// EXCIT: a generalized (or physical) force vector times a function of time (FONC_MULT,
/// or a constant COEF_MULT).
pub struct Forcing {
    pub generalized_force: Vec<f64>,
    pub multiplier: Box<dyn Fn(f64) -> f64>,
}

impl Forcing {
    /// COEF_MULT: a constant multiplier.
    pub fn constant(generalized_force: Vec<f64>, coef: f64) -> Forcing {
        Forcing {
            generalized_force,
            multiplier: Box::new(move |_| coef),
        }
    }
}

/// INCREMENT: INST_INIT, INST_FIN, PAS. Fixed-step schemes use the step that divides the
/// interval exactly nearest to PAS (⌈(t_end − t0)/PAS⌉ steps, PAS itself when it divides
/// the interval to 1e-9); the adaptive ones start from PAS.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TimeGrid {
    pub t0: f64,
    pub t_end: f64,
    pub dt: f64,
}

impl TimeGrid {
    /// The number of fixed steps and their length.
    pub fn fixed_steps(&self) -> (usize, f64) {
        let span = self.t_end - self.t0;
        let ratio = span / self.dt;
        let steps = if (ratio - ratio.round()).abs() <= 1e-9 * ratio.max(1.0) {
            ratio.round()
        } else {
            ratio.ceil()
        }
        .max(1.0);
        (steps as usize, span / steps)
    }
}

/// ARCHIVAGE: every k-th step (PAS_ARCH; the first and last instants are always kept), a
/// list of instants (INST/LIST_INST), or both (PAS_ARCH with INST, as Code_Aster allows:
/// the union, each instant once). Listed instants are hit exactly by the adaptive schemes
/// and interpolated (cubic Hermite in q, v) by the fixed-step ones.
#[derive(Clone, Debug, PartialEq)]
pub enum Archive {
    Every(usize),
    Instants(Vec<f64>),
    EveryAnd(usize, Vec<f64>),
}

impl Archive {
    /// PAS_ARCH, if the archive keeps every k-th step.
    pub fn every(&self) -> Option<usize> {
        match self {
            Archive::Every(k) | Archive::EveryAnd(k, _) => Some(*k),
            Archive::Instants(_) => None,
        }
    }

    /// The listed instants, if any.
    pub fn listed(&self) -> Option<&[f64]> {
        match self {
            Archive::Instants(l) | Archive::EveryAnd(_, l) => Some(l),
            Archive::Every(_) => None,
        }
    }
}

/// A located change of contact status of one shock.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ContactEvent {
    pub t: f64,
    pub shock: usize,
    /// true: contact begins (distance becomes ≤ 0); false: it ends.
    pub onset: bool,
}

/// The archived result: instants, q, v, a row-major (`n` values per instant), each shock's
/// samples per instant (`shocks[s][i]`), and counters.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Trajectory {
    pub n: usize,
    pub t: Vec<f64>,
    pub q: Vec<f64>,
    pub v: Vec<f64>,
    pub a: Vec<f64>,
    pub shocks: Vec<Vec<ShockSample>>,
    /// Contact changes the adaptive schemes located (step boundaries); empty for the
    /// fixed-step schemes.
    pub events: Vec<ContactEvent>,
    pub steps_taken: usize,
    pub steps_rejected: usize,
    /// ADAPT_ORDRE1/2: the instants whose step was kept after NMAX_ITER_PAS tries while
    /// still too long for the motion (Code_Aster goes on with an alarm there).
    pub steps_forced: Vec<f64>,
}

impl Trajectory {
    /// q at archived instant i.
    pub fn q_at(&self, i: usize) -> &[f64] {
        &self.q[i * self.n..(i + 1) * self.n]
    }

    pub fn v_at(&self, i: usize) -> &[f64] {
        &self.v[i * self.n..(i + 1) * self.n]
    }

    pub fn a_at(&self, i: usize) -> &[f64] {
        &self.a[i * self.n..(i + 1) * self.n]
    }
}
