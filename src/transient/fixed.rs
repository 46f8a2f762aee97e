//! The fixed-step loop of DIFF_CENTRE and NEWMARK: step, check, archive (every k-th step
//! or listed instants by interpolation), commit the shocks' states, report progress.

use super::archive::{Interp, Recorder, StepEnds};
use super::dis_choc::Shock;
use super::error::{try_zeros, TransientError};
use super::problem::{Archive, TimeGrid};
use super::scheme::diff_centre::DiffCentre;
use super::scheme::newmark::Newmark;
use super::system::{commit, finite, Model, Work};

pub(crate) enum Stepper<'s> {
    Diff(DiffCentre),
    Newmark(Box<Newmark<'s>>),
}

/// The state (q, v, a) at t0 with the shocks' states committed and t0 archived.
pub(crate) struct Start<'a> {
    pub q: &'a mut [f64],
    pub v: &'a mut [f64],
    pub a: &'a mut [f64],
}

#[allow(clippy::too_many_arguments)]
pub(crate) fn run_fixed(
    model: &Model,
    shocks: &mut [Shock],
    stepper: &mut Stepper,
    state: Start,
    grid: TimeGrid,
    archive: &Archive,
    rec: &mut Recorder,
    ws: &mut Work,
    progress: &mut dyn FnMut(f64),
) -> Result<usize, TransientError> {
    let Start { q, v, a } = state;
    let n = q.len();
    let (nsteps, h) = grid.fixed_steps();
    let listed = archive.listed();
    let every = archive.every();
    let keep_prev = listed.is_some();
    let len = if keep_prev { n } else { 0 };
    let (mut q0, mut v0, mut a0) = (
        try_zeros("the previous state", len)?,
        try_zeros("the previous state", len)?,
        try_zeros("the previous state", len)?,
    );
    let mut interp = Interp {
        q: try_zeros("the interpolation buffer", len)?,
        v: try_zeros("the interpolation buffer", len)?,
        a: try_zeros("the interpolation buffer", len)?,
        evals: ws.evals.clone(),
    };
    let tol = 1e-9 * h;
    let mut next = 0usize;
    if let Some(list) = listed {
        while next < list.len() && (list[next] - grid.t0).abs() <= tol {
            // With PAS_ARCH the start is archived already (integrate.rs).
            if every.is_none() {
                rec.push(grid.t0, q, v, a, &ws.evals)?;
            }
            next += 1;
        }
    }
    let report = (nsteps / 100).max(1);
    for k in 1..=nsteps {
        let t = grid.t0 + (k - 1) as f64 * h;
        let t1 = if k == nsteps {
            grid.t_end
        } else {
            grid.t0 + k as f64 * h
        };
        if keep_prev {
            q0.copy_from_slice(q);
            v0.copy_from_slice(v);
            a0.copy_from_slice(a);
        }
        match stepper {
            Stepper::Diff(s) => s.step(model, shocks, t, h, q, v, a, ws)?,
            Stepper::Newmark(s) => s.step(model, shocks, t, q, v, a, ws)?,
        }
        if !(finite(q) && finite(v) && finite(a)) {
            return Err(TransientError::NonFinite { t: t1 });
        }
        let at_step = every.is_some_and(|m| k.is_multiple_of(m.max(1)) || k == nsteps);
        if let Some(list) = listed {
            // The listed instants inside the step, then its end (once, if it is both).
            while next < list.len() && list[next] <= t1 + tol {
                let ti = list[next];
                if (ti - t1).abs() <= tol {
                    if !at_step {
                        rec.push(t1, q, v, a, &ws.evals)?;
                    }
                } else {
                    let ends = StepEnds {
                        t0: t,
                        h,
                        q0: &q0,
                        v0: &v0,
                        a0: &a0,
                        q1: q,
                        v1: v,
                        a1: a,
                    };
                    ends.interpolate(ti, shocks, &mut interp);
                    rec.push(ti, &interp.q, &interp.v, &interp.a, &interp.evals)?;
                }
                next += 1;
            }
        }
        if at_step {
            rec.push(t1, q, v, a, &ws.evals)?;
        }
        commit(shocks, &ws.evals);
        if k % report == 0 || k == nsteps {
            progress(k as f64 / nsteps as f64);
        }
    }
    Ok(nsteps)
}
