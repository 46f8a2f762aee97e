//! The adaptive loop of RUNGE_KUTTA_54 / RUNGE_KUTTA_32 on y = (q, v), y' = (v, a):
//! embedded error control, PAS_MINI / PAS_MAXI / NMAX_ITER_PAS / a step limit, listed
//! archive instants hit exactly, and event location at contact changes.
//!
//! Error: e = h Σ (b_i − b̂_i) k_i; the step is accepted when max_i |e_i| / (TOLERANCE · s_i)
//! ≤ 1, s_i the largest |q| (for a q component) or |v| (for a v component) met so far,
//! both ends of the step included: an error relative to the motion's amplitude, floored
//! near rest by |a|/ω²_max (resp. |a|/ω_max), a the new acceleration and ω_max the highest
//! pulsation of the structure with its shocks' stiffness (30 power steps towards
//! DIFF_CENTRE's stability estimate; in a contact |a|/ω²_max is then at most about the penetration, so the floor
//! does not loosen the test there): from rest under a force, |q| grows like the step's own
//! error and a purely relative test rejected every step (measured: the step fell to
//! PAS_MINI at t = 0 on a sliding pad driven by a sine force). The next
//! step is h · min(5, max(0.2, 0.9 err^(−1/(p̂+1)))), p̂ the lower order.
//!
//! Events: after a step passes the error test, each shock's contact status (normal
//! distance ≤ 0) is compared at both ends. If one changed, the crossing instant is found
//! by bisection on the distance along the cubic Hermite interpolant of the node
//! displacements (q' = v exactly, so it is O(h⁴) accurate) and the step is redone up to
//! that instant, so that contact onsets and releases fall on step boundaries (within
//! 1e-9 of the step, or within the interpolant's error, which the next step then meets
//! at its very start). The force law is discontinuous at those instants (AMOR_NOR,
//! friction); between them the right-hand side is smooth and the pair keeps its order.
//! Crossings in and out within one step (grazing) are not seen.

use super::archive::Recorder;
use super::dis_choc::Shock;
use super::error::{try_zeros, TransientError};
use super::problem::{Archive, ContactEvent, TimeGrid};
use super::scheme::runge_kutta::tableau;
use super::scheme::AdaptiveOptions;
use super::system::{commit, finite, Model, Work};

/// What the adaptive loop reports.
pub(crate) struct AdaptiveStats {
    pub taken: usize,
    pub rejected: usize,
    pub events: Vec<ContactEvent>,
}

/// Node displacements and velocities of a shock (u1, u2, u̇1, u̇2).
type Ends = [[f64; 3]; 4];

fn ends(shock: &Shock, t: f64, q: &[f64], v: &[f64]) -> Ends {
    let (u1, u2) = shock.node_displacements_at(t, q);
    let (w1, w2) = shock.node_velocities_at(t, v);
    [u1, u2, w1, w2]
}

/// The crossing fraction θ ∈ (0, 1) of the contact status along the Hermite interpolant.
fn locate(shock: &Shock, e0: &Ends, e1: &Ends, h: f64) -> f64 {
    let status = |s: f64| {
        let (s2, s3) = (s * s, s * s * s);
        let (h00, h10, h01, h11) = (
            2.0 * s3 - 3.0 * s2 + 1.0,
            s3 - 2.0 * s2 + s,
            -2.0 * s3 + 3.0 * s2,
            s3 - s2,
        );
        let mut u = [[0.0; 3]; 2];
        for (node, un) in u.iter_mut().enumerate() {
            for c in 0..3 {
                un[c] = h00 * e0[node][c]
                    + h10 * h * e0[node + 2][c]
                    + h01 * e1[node][c]
                    + h11 * h * e1[node + 2][c];
            }
        }
        shock.gap_from_displacements(u[0], u[1]).dnorm <= 0.0
    };
    let start = status(0.0);
    let (mut lo, mut hi) = (0.0, 1.0);
    for _ in 0..60 {
        let mid = 0.5 * (lo + hi);
        if status(mid) == start {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    hi
}

/// Runs from (q, v, a) at t0 (shock states committed, t0 archived) to t_end.
#[allow(clippy::too_many_arguments)]
pub(crate) fn run_adaptive(
    model: &Model,
    shocks: &mut [Shock],
    opts: &AdaptiveOptions,
    disp_per_accel: f64,
    q0: &[f64],
    v0: &[f64],
    a0: &[f64],
    grid: TimeGrid,
    archive: &Archive,
    rec: &mut Recorder,
    ws: &mut Work,
    progress: &mut dyn FnMut(f64),
) -> Result<AdaptiveStats, TransientError> {
    let tab = tableau(opts.pair);
    let n = q0.len();
    let m = 2 * n;
    let span = grid.t_end - grid.t0;
    let pas_maxi = opts.pas_maxi.unwrap_or(span);
    let pas_mini = opts.pas_mini.unwrap_or(1e-12 * span);
    let tol = opts.tolerance;
    let expo = 1.0 / (tab.low_order as f64 + 1.0);
    let mut y = try_zeros("the adaptive state", m)?;
    y[..n].copy_from_slice(q0);
    y[n..].copy_from_slice(v0);
    let mut k: Vec<Vec<f64>> = Vec::new();
    for _ in 0..tab.stages {
        k.push(try_zeros("the Runge-Kutta stages", m)?);
    }
    k[0][..n].copy_from_slice(v0);
    k[0][n..].copy_from_slice(a0);
    let mut ytmp = try_zeros("the adaptive state", m)?;
    let mut err = try_zeros("the adaptive state", m)?;
    let mut e_start: Vec<Ends> = shocks.iter().map(|s| ends(s, grid.t0, q0, v0)).collect();
    let mut e_end = e_start.clone();
    let mut gap_start: Vec<f64> = ws.evals.iter().map(|e| e.gap.dnorm).collect();
    let inf = |x: &[f64]| x.iter().fold(0.0f64, |a, b| a.max(b.abs()));
    let (mut qmax, mut vmax) = (inf(q0), inf(v0));
    let mut stats = AdaptiveStats {
        taken: 0,
        rejected: 0,
        events: Vec::new(),
    };
    let listed: &[f64] = archive.listed().unwrap_or(&[]);
    let every = archive.every().map_or(0, |k| k.max(1));
    let ttol = 1e-12 * span.max(grid.t_end.abs());
    let mut next = 0usize;
    // With PAS_ARCH the start is archived already (integrate.rs).
    if every == 0 && listed.first().is_some_and(|&t0| t0 <= grid.t0 + ttol) {
        rec.push(grid.t0, q0, v0, a0, &ws.evals)?;
    }
    while next < listed.len() && listed[next] <= grid.t0 + ttol {
        next += 1;
    }
    let mut t = grid.t0;
    let mut h_ctrl = grid.dt.min(pas_maxi);
    let mut in_row = 0usize;
    let mut redo: Option<f64> = None;
    let mut redos = 0usize;
    let mut last_report = 0.0;
    while t < grid.t_end - ttol {
        if stats.taken + stats.rejected >= opts.max_steps {
            return Err(TransientError::StepLimit {
                t,
                max_steps: opts.max_steps,
            });
        }
        let target = match listed.get(next) {
            Some(&ti) if ti < grid.t_end => ti,
            _ => grid.t_end,
        };
        let mut h = redo.take().unwrap_or(h_ctrl).min(pas_maxi);
        let shortened = h < h_ctrl;
        let hit = t + h >= target - ttol;
        if hit {
            h = target - t;
        }
        // Stages (the last one, FSAL, is the derivative at the new state).
        for i in 1..tab.stages {
            for j in 0..m {
                let s: f64 = (0..i).map(|l| tab.a[i][l] * k[l][j]).sum();
                ytmp[j] = y[j] + h * s;
            }
            let ki = &mut k[i];
            ki[..n].copy_from_slice(&ytmp[n..]);
            model.acceleration(
                shocks,
                t + tab.c[i] * h,
                &ytmp[..n],
                &ytmp[n..],
                &mut ki[n..],
                ws,
            )?;
        }
        // ytmp holds the new state (last row of a = b).
        for j in 0..m {
            err[j] = h * (0..tab.stages).map(|l| tab.e[l] * k[l][j]).sum::<f64>();
        }
        // Near rest (a start from zero under a force) |q| and |v| are no scale: the
        // error relative to them does not shrink with the step. Their floors are the
        // displacement and velocity the new acceleration gives the stiffest mode (shocks
        // included), |a|/ω²_max and |a|/ω_max.
        let a_new = inf(&k[tab.stages - 1][n..]);
        let sq = qmax.max(inf(&ytmp[..n])).max(a_new * disp_per_accel);
        let sv = vmax.max(inf(&ytmp[n..])).max(a_new * disp_per_accel.sqrt());
        let mut errn = 0.0f64;
        for (j, e) in err.iter().enumerate() {
            let sc = tol * if j < n { sq } else { sv };
            let r = if *e == 0.0 { 0.0 } else { e.abs() / sc };
            errn = errn.max(r);
        }
        if errn.is_nan() || errn > 1.0 || !finite(&ytmp) {
            stats.rejected += 1;
            in_row += 1;
            if in_row > opts.nmax_iter_pas {
                return Err(TransientError::TooManyRejections {
                    t,
                    rejections: in_row,
                    dt: h,
                });
            }
            let fac = if errn.is_finite() {
                (0.9 * errn.powf(-expo)).clamp(0.2, 1.0)
            } else {
                0.2
            };
            h_ctrl = h * fac;
            if h_ctrl < pas_mini {
                return Err(TransientError::StepTooSmall {
                    t,
                    dt: h_ctrl,
                    pas_mini,
                });
            }
            continue;
        }
        // Event location.
        let mut theta: Option<f64> = None;
        for (s, shock) in shocks.iter().enumerate() {
            let g1 = ws.evals[s].gap.dnorm;
            if (gap_start[s] <= 0.0) != (g1 <= 0.0) {
                e_end[s] = ends(shock, t + h, &ytmp[..n], &ytmp[n..]);
                let th = locate(shock, &e_start[s], &e_end[s], h);
                theta = Some(theta.map_or(th, |x: f64| x.min(th)));
            }
        }
        let ev_tol = 1e-9 * h_ctrl.max(h);
        if let Some(th) = theta {
            if th * h > ev_tol && (1.0 - th) * h > ev_tol && redos < 20 {
                redo = Some(th * h);
                redos += 1;
                continue;
            }
            let te = if th * h <= ev_tol { t } else { t + h };
            for (s, ev) in ws.evals.iter().enumerate() {
                let g1 = ev.gap.dnorm;
                if (gap_start[s] <= 0.0) != (g1 <= 0.0) {
                    stats.events.push(ContactEvent {
                        t: te,
                        shock: s,
                        onset: g1 <= 0.0,
                    });
                }
            }
        }
        // Accept.
        redos = 0;
        in_row = 0;
        t = if hit { target } else { t + h };
        y.copy_from_slice(&ytmp);
        let last = tab.stages - 1;
        let (first, rest) = k.split_at_mut(last);
        first[0].copy_from_slice(&rest[0]);
        commit(shocks, &ws.evals);
        for (s, shock) in shocks.iter().enumerate() {
            gap_start[s] = ws.evals[s].gap.dnorm;
            e_start[s] = ends(shock, t, &y[..n], &y[n..]);
        }
        qmax = sq;
        vmax = sv;
        stats.taken += 1;
        if !shortened && !hit {
            let fac = if errn > 0.0 {
                (0.9 * errn.powf(-expo)).clamp(0.2, 5.0)
            } else {
                5.0
            };
            h_ctrl = (h * fac).min(pas_maxi);
        }
        let done = t >= grid.t_end - ttol;
        let mut archive_now = every > 0 && (stats.taken.is_multiple_of(every) || done);
        while next < listed.len() && listed[next] <= t + ttol {
            archive_now = true;
            next += 1;
        }
        if archive_now {
            rec.push(t, &y[..n], &y[n..], &k[0][n..], &ws.evals)?;
        }
        let frac = (t - grid.t0) / span;
        if frac - last_report >= 0.01 || done {
            progress(frac.min(1.0));
            last_report = frac;
        }
    }
    Ok(stats)
}
