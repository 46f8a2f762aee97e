//! The loop of ADAPT_ORDRE1 / ADAPT_ORDRE2 (the step itself in `scheme/adapt.rs`), with
//! Code_Aster's way of meeting the archive: the listed instants and INST_FIN are
//! reached exactly by cutting the step that would pass them; after a cut step the next
//! one is the remainder of the step that was cut (the controller's proposal is set aside
//! for that one step); otherwise every PAS_ARCH-th step is archived (steps that ended
//! short of a listed instant after a retry are not: their end is neither). Instants are
//! compared with a tolerance of 10ε per step taken, as Code_Aster's driver does.

use super::archive::Recorder;
use super::dis_choc::Shock;
use super::error::{try_zeros, TransientError};
use super::problem::{Archive, TimeGrid};
use super::scheme::adapt::{
    advance, apparent_frequency, step_error, update_vmin, AdaptOptions, AdaptOrder, Controller,
};
use super::system::{commit, finite, Model, Work};

/// What the loop reports.
pub(crate) struct AdaptStats {
    pub taken: usize,
    pub retried: usize,
    /// Instants whose step was kept after NMAX_ITER_PAS tries although still too long.
    pub forced: Vec<f64>,
}

/// Driver tolerance per step (Code_Aster's 10ε).
const DRIVER_EPS: f64 = 10.0 * f64::EPSILON;
/// Below this length ADAPT_ORDRE1 kicks with the whole step (Code_Aster's 1e-13 s).
const ORDER1_FULL_KICK: f64 = 1e-13;
/// ADAPT_ORDRE1 does not judge its first steps.
const ORDER1_UNJUDGED: usize = 5;

/// The instants the steps are cut at: the listed ones after t0, then INST_FIN.
fn cut_instants(archive: &Archive, grid: &TimeGrid) -> Vec<f64> {
    let tol = 1e-12 * (grid.t_end - grid.t0).max(grid.t_end.abs());
    let mut cuts: Vec<f64> = archive
        .listed()
        .unwrap_or(&[])
        .iter()
        .copied()
        .filter(|&x| x > grid.t0 + tol && x < grid.t_end - tol)
        .collect();
    cuts.push(grid.t_end);
    cuts
}

/// Runs from (q, v, a) at t0 (shock states committed, t0 archived when PAS_ARCH is given)
/// to t_end.
#[allow(clippy::too_many_arguments)]
pub(crate) fn run_adapt(
    model: &Model,
    shocks: &mut [Shock],
    opts: &AdaptOptions,
    q0: &[f64],
    v0: &[f64],
    a0: &[f64],
    grid: TimeGrid,
    archive: &Archive,
    rec: &mut Recorder,
    ws: &mut Work,
    progress: &mut dyn FnMut(f64),
) -> Result<AdaptStats, TransientError> {
    let n = q0.len();
    let alloc = |len| try_zeros("the ADAPT state", len);
    let (mut q, mut v, mut a) = (alloc(n)?, alloc(n)?, alloc(n)?);
    q.copy_from_slice(q0);
    v.copy_from_slice(v0);
    a.copy_from_slice(a0);
    let (mut q2, mut v2, mut a2, mut carried) = (alloc(n)?, alloc(n)?, alloc(n)?, alloc(n)?);
    let mut vmin = alloc(n)?;
    vmin.iter_mut().for_each(|x| *x = 1e-15);

    let (pas_mini, pas_maxi) = opts.bounds(grid.dt);
    let adaptive = (pas_maxi / pas_mini - 1.0).abs() >= 100.0 * f64::EPSILON;
    let listed: &[f64] = archive.listed().unwrap_or(&[]);
    let every = archive.every().map(|k| k.max(1));
    let cuts = cut_instants(archive, &grid);
    let span = grid.t_end - grid.t0;
    let snap = 1e-12 * span.max(grid.t_end.abs());
    if every.is_none() && listed.first().is_some_and(|&t| t <= grid.t0 + snap) {
        rec.push(grid.t0, &q, &v, &a, &ws.evals)?;
    }
    let is_listed = |t: f64| listed.iter().any(|&x| (x - t).abs() <= snap);

    let mut ctrl = Controller::new();
    let mut stats = AdaptStats {
        taken: 0,
        retried: 0,
        forced: Vec::new(),
    };
    let mut time = grid.t0;
    let mut step = grid.dt;
    let mut first = true;
    // Code_Aster's counters: i the steps taken (from 1), the cut instant to reach next,
    // the archive cuts that shortened a step, and whether the step now is cut (1) or the
    // remainder of one (2).
    let mut i = 1usize;
    let mut next_cut = 0usize;
    let mut cut_archives = 0usize;
    let mut cut_state = 0u8;
    let mut last_report = 0.0;
    while grid.t_end - time > i as f64 * DRIVER_EPS {
        if stats.taken + stats.retried >= opts.max_steps {
            return Err(TransientError::StepLimit {
                t: time,
                max_steps: opts.max_steps,
            });
        }
        let tol = i as f64 * DRIVER_EPS;
        let proposed = step;
        let mut cut_len = proposed;
        if let Some(&tc) = cuts.get(next_cut) {
            if time + proposed - tc > tol {
                cut_len = tc - time;
                step = cut_len;
                cut_state = 1;
            } else if (time + proposed - tc).abs() < tol {
                cut_state = 1;
            }
        }

        // The step, retried shorter while too long (scheme/adapt.rs).
        let start = if first && opts.order == AdaptOrder::Two {
            0.0
        } else {
            step
        };
        let mut h = step;
        let mut tries = 1usize;
        let next = loop {
            let c = if opts.order == AdaptOrder::One && h <= ORDER1_FULL_KICK {
                h
            } else {
                0.5 * (start + h)
            };
            advance(opts.order, h, c, &q, &v, &a, &mut q2, &mut v2, &mut carried);
            model.acceleration(shocks, time + h, &q2, &v2, &mut a2, ws)?;
            if !(finite(&q2) && finite(&v2) && finite(&a2)) {
                return Err(TransientError::NonFinite { t: time + h });
            }
            if !adaptive {
                // A fixed step (PAS_MINI = PAS_MAXI): back to it after a cut. Code_Aster
                // leaves the next step undefined there (ADAPT_ORDRE2) or at the cut's
                // remainder (ADAPT_ORDRE1).
                break pas_maxi;
            }
            let err = if opts.order == AdaptOrder::One && stats.taken < ORDER1_UNJUDGED {
                0.0
            } else {
                let f = apparent_frequency(h, &q, &q2, &a, &a2, &vmin);
                step_error(opts, f, h)
            };
            let verdict = ctrl.judge(opts, h, err, pas_maxi);
            if verdict.too_long && verdict.next >= pas_mini && tries < opts.nmax_iter_pas {
                tries += 1;
                stats.retried += 1;
                h = verdict.next;
                continue;
            }
            if verdict.next < pas_mini {
                return Err(TransientError::StepTooSmall {
                    t: time,
                    dt: verdict.next,
                    pas_mini,
                });
            }
            if verdict.too_long {
                stats.forced.push(time);
            }
            update_vmin(opts.velocity_floor, &carried, &mut vmin);
            break verdict.next;
        };

        // Accept.
        q.copy_from_slice(&q2);
        v.copy_from_slice(&carried);
        a.copy_from_slice(&a2);
        commit(shocks, &ws.evals);
        time += h;
        step = next;
        first = false;
        stats.taken += 1;

        if cut_state == 2 {
            cut_state = 0;
        }
        let mut archive_now = false;
        if cut_state == 1 {
            if let Some(&tc) = cuts.get(next_cut) {
                if (time - tc).abs() <= tol {
                    time = tc;
                    archive_now = is_listed(tc) || every.is_some();
                    next_cut += 1;
                    cut_state = 0;
                    if (proposed - cut_len).abs() > tol {
                        cut_archives += 1;
                        step = proposed - cut_len;
                        cut_state = 2;
                    }
                }
            }
        } else if let Some(k) = every {
            archive_now = (i - cut_archives).is_multiple_of(k);
        }
        if archive_now {
            // The state at the end of the step: the velocity the forces saw there.
            rec.push(time, &q, &v2, &a, &ws.evals)?;
        }
        i += 1;
        let frac = (time - grid.t0) / span;
        if frac - last_report >= 0.01 || grid.t_end - time <= tol {
            progress(frac.min(1.0));
            last_report = frac;
        }
    }
    Ok(stats)
}
