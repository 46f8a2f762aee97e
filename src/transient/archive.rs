//! Recording the archived instants into a [`Trajectory`]: sizes checked before any
//! allocation (an error, never an abort, when they do not fit), growth by `try_reserve`,
//! and the cubic Hermite interpolation of the fixed-step schemes at listed instants.

use super::dis_choc::{Shock, ShockEval, ShockSample};
use super::error::TransientError;
use super::problem::Trajectory;

pub(crate) struct Recorder {
    pub traj: Trajectory,
}

fn oom(what: &str, bytes: u128) -> TransientError {
    TransientError::OutOfMemory {
        what: what.to_string(),
        bytes,
    }
}

fn reserve<T>(v: &mut Vec<T>, more: usize, what: &str) -> Result<(), TransientError> {
    v.try_reserve(more)
        .map_err(|_| oom(what, (more as u128) * std::mem::size_of::<T>() as u128))
}

impl Recorder {
    /// Reserves `rows` archived instants for n unknowns and `n_shocks` shocks.
    pub fn new(n: usize, n_shocks: usize, rows: usize) -> Result<Recorder, TransientError> {
        let values = rows
            .checked_mul(n)
            .and_then(|x| x.checked_mul(3))
            .ok_or_else(|| oom("the archive (instants × unknowns overflows)", u128::MAX))?;
        let bytes = values as u128 * 8
            + (rows as u128) * (n_shocks as u128) * std::mem::size_of::<ShockSample>() as u128;
        let what = format!("the archive ({rows} instants × {n} unknowns, {n_shocks} shocks)");
        let mut traj = Trajectory {
            n,
            ..Trajectory::default()
        };
        let try_res =
            |v: &mut Vec<f64>, len: usize| v.try_reserve_exact(len).map_err(|_| oom(&what, bytes));
        try_res(&mut traj.t, rows)?;
        try_res(&mut traj.q, rows * n)?;
        try_res(&mut traj.v, rows * n)?;
        try_res(&mut traj.a, rows * n)?;
        for _ in 0..n_shocks {
            let mut s = Vec::new();
            s.try_reserve_exact(rows).map_err(|_| oom(&what, bytes))?;
            traj.shocks.push(s);
        }
        Ok(Recorder { traj })
    }

    /// Appends one instant.
    pub fn push(
        &mut self,
        t: f64,
        q: &[f64],
        v: &[f64],
        a: &[f64],
        evals: &[ShockEval],
    ) -> Result<(), TransientError> {
        let tr = &mut self.traj;
        let what = "the archive";
        reserve(&mut tr.t, 1, what)?;
        reserve(&mut tr.q, q.len(), what)?;
        reserve(&mut tr.v, v.len(), what)?;
        reserve(&mut tr.a, a.len(), what)?;
        for s in tr.shocks.iter_mut() {
            reserve(s, 1, what)?;
        }
        tr.t.push(t);
        tr.q.extend_from_slice(q);
        tr.v.extend_from_slice(v);
        tr.a.extend_from_slice(a);
        for (s, e) in tr.shocks.iter_mut().zip(evals) {
            s.push(e.sample);
        }
        Ok(())
    }
}

/// One step's two ends, for interpolation.
pub(crate) struct StepEnds<'a> {
    pub t0: f64,
    pub h: f64,
    pub q0: &'a [f64],
    pub v0: &'a [f64],
    pub a0: &'a [f64],
    pub q1: &'a [f64],
    pub v1: &'a [f64],
    pub a1: &'a [f64],
}

/// Interpolation buffers.
pub(crate) struct Interp {
    pub q: Vec<f64>,
    pub v: Vec<f64>,
    pub a: Vec<f64>,
    pub evals: Vec<ShockEval>,
}

impl StepEnds<'_> {
    /// Cubic Hermite in q (with v) and v (with a), linear in a, at t; the shocks
    /// evaluated there from their committed states.
    pub fn interpolate(&self, t: f64, shocks: &[Shock], out: &mut Interp) {
        let s = ((t - self.t0) / self.h).clamp(0.0, 1.0);
        let (s2, s3) = (s * s, s * s * s);
        let h00 = 2.0 * s3 - 3.0 * s2 + 1.0;
        let h10 = s3 - 2.0 * s2 + s;
        let h01 = -2.0 * s3 + 3.0 * s2;
        let h11 = s3 - s2;
        let h = self.h;
        for i in 0..self.q0.len() {
            out.q[i] =
                h00 * self.q0[i] + h10 * h * self.v0[i] + h01 * self.q1[i] + h11 * h * self.v1[i];
            out.v[i] =
                h00 * self.v0[i] + h10 * h * self.a0[i] + h01 * self.v1[i] + h11 * h * self.a1[i];
            out.a[i] = (1.0 - s) * self.a0[i] + s * self.a1[i];
        }
        for (e, sh) in out.evals.iter_mut().zip(shocks) {
            *e = sh.evaluate_at(t, &out.q, &out.v, &sh.state);
        }
    }
}
