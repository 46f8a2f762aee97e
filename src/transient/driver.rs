//! Code_Aster's driver of its adaptive schemes (its `dtmcalc`), shared by DEVOGE and
//! RUNGE_KUTTA_32/54: the step that would pass the next listed archive instant (then
//! INST_FIN) is cut to land on it, and the step after a cut is the remainder of the cut
//! one; with no instants listed every PAS_ARCH-th step is archived, the steps that ended
//! at a cut not counted. When the scheme's step is fixed (PAS_MINI = PAS_MAXI, judged with
//! the driver's own defaults 1e-6·PAS and 1e6·PAS), the step after a landing is PAS again.
//! Landings are judged within i·10ε, i the step's number, as Code_Aster does.

use super::archive::Recorder;
use super::dis_choc::Shock;
use super::error::TransientError;
use super::problem::{Archive, TimeGrid};
use super::system::{Model, Work};

const EPS: f64 = f64::EPSILON;

/// The driver's own defaults of PAS_MINI and PAS_MAXI, relative to PAS (whether it sets
/// the step back to PAS after a landing).
const DRIVER_MINI: f64 = 1e-6;
const DRIVER_MAXI: f64 = 1e6;

/// One step a scheme took.
pub(crate) struct Taken {
    /// Its length.
    pub h: f64,
    /// The length the scheme proposes next (the step itself when the step is fixed).
    pub next: f64,
    /// Tries, the accepted one included.
    pub tries: usize,
}

/// One of Code_Aster's adaptive schemes, as its driver runs it.
pub(crate) trait DrivenScheme {
    /// A step from t of first length h, retried as the scheme's error control says;
    /// nothing committed yet.
    fn step(
        &mut self,
        model: &Model,
        shocks: &mut [Shock],
        ws: &mut Work,
        t: f64,
        h: f64,
    ) -> Result<Taken, TransientError>;

    /// The step just taken (of length h) becomes the committed state, the shocks' states
    /// and the evaluations archived with it (`ws.evals`) included.
    fn accept(&mut self, shocks: &mut [Shock], ws: &mut Work, h: f64);

    /// (q, v, a) of the committed state.
    fn state(&self) -> (&[f64], &[f64], &[f64]);
}

/// The driver's settings: the scheme's PAS_MINI and PAS_MAXI as given, and the step limit.
pub(crate) struct DriverSettings {
    pub pas_mini: Option<f64>,
    pub pas_maxi: Option<f64>,
    pub max_steps: usize,
}

/// Steps taken and tries redone with a shorter step.
pub(crate) struct DriverStats {
    pub taken: usize,
    pub rejected: usize,
}

/// Runs `scheme` from (q0, v0, a0) at t0 (shock states committed, t0 archived with
/// PAS_ARCH by the caller) to t_end.
#[allow(clippy::too_many_arguments)]
pub(crate) fn drive(
    scheme: &mut dyn DrivenScheme,
    settings: &DriverSettings,
    model: &Model,
    shocks: &mut [Shock],
    (q0, v0, a0): (&[f64], &[f64], &[f64]),
    grid: TimeGrid,
    archive: &Archive,
    rec: &mut Recorder,
    ws: &mut Work,
    progress: &mut dyn FnMut(f64),
) -> Result<DriverStats, TransientError> {
    let span = grid.t_end - grid.t0;
    let lo = settings.pas_mini.unwrap_or(DRIVER_MINI * grid.dt);
    let hi = settings.pas_maxi.unwrap_or(DRIVER_MAXI * grid.dt);
    let driver_adapts = (hi / lo - 1.0).abs() > EPS;
    let every = archive.every().map_or(0, |k| k.max(1));
    // The instants to land on: the listed ones after t0 (an instant at t0 is the start,
    // archived below), then t_end.
    let listed: &[f64] = archive.listed().unwrap_or(&[]);
    let first = listed.partition_point(|&x| x <= grid.t0 + EPS);
    let inner = &listed[first..];
    let kept = inner.partition_point(|&x| x < grid.t_end - EPS);
    let final_listed = kept < inner.len();
    let landing = |k: usize| -> (f64, bool) {
        if k < kept {
            (inner[k], true)
        } else {
            (grid.t_end, final_listed || every > 0)
        }
    };
    if every == 0 && first > 0 {
        rec.push(grid.t0, q0, v0, a0, &ws.evals)?;
    }
    let mut stats = DriverStats {
        taken: 0,
        rejected: 0,
    };
    let tol_unit = 10.0 * EPS;
    let mut t = grid.t0;
    let mut step = grid.dt;
    let mut i: usize = 1;
    let mut cut_landings: usize = 0;
    let mut next_landing = 0usize;
    // 0: free step; 1: a landing is pending; 2: the step after a landing's leftover.
    let mut mode = 0u8;
    let mut cut = step;
    let mut last_report = 0.0;
    while grid.t_end - t > i as f64 * tol_unit {
        if stats.taken + stats.rejected >= settings.max_steps {
            return Err(TransientError::StepLimit {
                t,
                max_steps: settings.max_steps,
            });
        }
        let tol_i = i as f64 * tol_unit;
        let (target, record_target) = landing(next_landing);
        let proposed = step;
        let mut h = proposed;
        if t + proposed - target > tol_i {
            cut = target - t;
            h = cut;
            mode = 1;
        } else if (t + proposed - target).abs() < tol_i {
            cut = proposed;
            mode = 1;
        }
        let taken = scheme.step(model, shocks, ws, t, h)?;
        stats.rejected += taken.tries - 1;
        stats.taken += 1;
        scheme.accept(shocks, ws, taken.h);
        let mut t_new = t + taken.h;
        step = taken.next;
        if mode == 2 {
            mode = 0;
            if !driver_adapts {
                step = grid.dt;
            }
        }
        let mut archive_now = false;
        if mode == 1 {
            if (t_new - target).abs() <= tol_i {
                t_new = target;
                archive_now = record_target;
                next_landing += 1;
                mode = 0;
                if (proposed - cut).abs() > tol_i {
                    cut_landings += 1;
                    step = proposed - cut;
                    mode = 2;
                } else if !driver_adapts {
                    step = grid.dt;
                }
            }
        } else if every > 0 && (i - cut_landings).is_multiple_of(every) {
            archive_now = true;
        }
        t = t_new;
        if archive_now {
            let (q, v, a) = scheme.state();
            rec.push(t, q, v, a, &ws.evals)?;
        }
        i += 1;
        let frac = (t - grid.t0) / span;
        let done = grid.t_end - t <= i as f64 * tol_unit;
        if frac - last_report >= 0.01 || done {
            progress(frac.min(1.0));
            last_report = frac;
        }
    }
    Ok(stats)
}
