//! The driver: checks the inputs, computes the initial acceleration, sizes the archive,
//! checks DIFF_CENTRE's stability limit, and runs the fixed-step or the adaptive loop.

use super::adapt_loop::run_adapt;
use super::adaptive::run_adaptive;
use super::archive::Recorder;
use super::devoge::run_devoge;
use super::dis_choc::Shock;
use super::error::{check_len, invalid, try_zeros, TransientError};
use super::fixed::{run_fixed, Start, Stepper};
use super::problem::{Archive, Forcing, TimeGrid, Trajectory};
use super::rk_loop::run_rk;
use super::scheme::diff_centre::{max_pulsation, stability_limit, DiffCentre};
use super::scheme::newmark::Newmark;
use super::scheme::{AdaptOptions, Scheme};
use super::structure::Structure;
use super::system::{commit, finite, Model, Work};

/// Power steps of the ω_max estimate that floors the adaptive error scale.
const FLOOR_POWER_STEPS: usize = 30;

/// Most rows reserved up front for an archive whose size is not known in advance (the
/// adaptive schemes with PAS_ARCH); it grows beyond by `try_reserve`.
const INITIAL_ROWS_CAP: usize = 1 << 16;

fn check_inputs(
    n: usize,
    shocks: &[Shock],
    forcing: &[Forcing],
    init: (&[f64], &[f64]),
    times: &TimeGrid,
    archive: &Archive,
) -> Result<(), TransientError> {
    check_len("ETAT_INIT/DEPL", init.0.len(), n)?;
    check_len("ETAT_INIT/VITE", init.1.len(), n)?;
    if !(finite(init.0) && finite(init.1)) {
        return Err(invalid("ETAT_INIT", "the initial state is not finite"));
    }
    for f in forcing {
        check_len("EXCIT/VECT_ASSE_GENE", f.generalized_force.len(), n)?;
    }
    for s in shocks {
        if let Some(i) = s.max_index() {
            if i >= n {
                return Err(TransientError::Dimension {
                    what: "a shock's rows".into(),
                    expected: n,
                    got: i + 1,
                });
            }
        }
    }
    let TimeGrid { t0, t_end, dt } = *times;
    if !(t0.is_finite() && t_end.is_finite() && t_end > t0) {
        return Err(invalid(
            "INCREMENT/INST_FIN",
            format!("INST_FIN = {t_end:e} must be after INST_INIT = {t0:e}"),
        ));
    }
    if !(dt.is_finite() && dt > 0.0) {
        return Err(invalid(
            "INCREMENT/PAS",
            format!("PAS = {dt:e} must be > 0"),
        ));
    }
    match archive {
        Archive::Every(0) | Archive::EveryAnd(0, _) => {
            Err(invalid("ARCHIVAGE/PAS_ARCH", "must be ≥ 1"))
        }
        Archive::Every(_) => Ok(()),
        Archive::Instants(list) | Archive::EveryAnd(_, list) => {
            let tol = 1e-9 * (t_end - t0);
            let sorted = list.windows(2).all(|w| w[1] > w[0]);
            let inside = list.iter().all(|&x| x >= t0 - tol && x <= t_end + tol);
            if list.is_empty() || !sorted || !inside {
                Err(invalid(
                    "ARCHIVAGE/INST",
                    "the instants must be increasing and within [INST_INIT, INST_FIN]",
                ))
            } else {
                Ok(())
            }
        }
    }
}

fn check_scheme(scheme: &Scheme) -> Result<(), TransientError> {
    match scheme {
        Scheme::DiffCentre => Ok(()),
        Scheme::Newmark { beta, gamma } => {
            if beta.is_finite() && *beta > 0.0 && gamma.is_finite() && *gamma >= 0.0 {
                Ok(())
            } else {
                Err(invalid(
                    "SCHEMA_TEMPS/BETA",
                    format!("BETA = {beta:e} must be > 0 and GAMMA = {gamma:e} ≥ 0"),
                ))
            }
        }
        Scheme::Adaptive(o) => {
            if !(o.tolerance.is_finite() && o.tolerance > 0.0) {
                return Err(invalid("SCHEMA_TEMPS/TOLERANCE", "must be > 0"));
            }
            if let (Some(lo), Some(hi)) = (o.pas_mini, o.pas_maxi) {
                if !(lo > 0.0 && hi >= lo) {
                    return Err(invalid(
                        "SCHEMA_TEMPS/PAS_MINI",
                        "PAS_MINI must be > 0 and ≤ PAS_MAXI",
                    ));
                }
            }
            if o.pas_maxi.is_some_and(|h| h.is_nan() || h <= 0.0) {
                return Err(invalid("SCHEMA_TEMPS/PAS_MAXI", "must be > 0"));
            }
            Ok(())
        }
        Scheme::Adapt(o) => check_adapt(o),
        // Checked against PAS when the run starts (devoge.rs).
        Scheme::Devoge(_) => Ok(()),
    }
}

fn check_adapt(o: &AdaptOptions) -> Result<(), TransientError> {
    let positive = |x: f64| x.is_finite() && x > 0.0;
    if !(positive(o.points_per_period)) {
        return Err(invalid("SCHEMA_TEMPS/NB_POIN_PERIODE", "must be > 0"));
    }
    if !(o.coef_mult.is_finite() && o.coef_mult >= 1.0) {
        return Err(invalid("SCHEMA_TEMPS/COEF_MULT_PAS", "must be ≥ 1"));
    }
    // 1 is allowed for both: Code_Aster's files use it for a constant step.
    if !(o.coef_divi.is_finite() && o.coef_divi >= 1.0) {
        return Err(invalid("SCHEMA_TEMPS/COEF_DIVI_PAS", "must be ≥ 1"));
    }
    if o.nmax_iter_pas == 0 {
        return Err(invalid("SCHEMA_TEMPS/NMAX_ITER_PAS", "must be ≥ 1"));
    }
    let bounds = [
        ("SCHEMA_TEMPS/PAS_MINI", o.pas_mini),
        ("SCHEMA_TEMPS/PAS_MAXI", o.pas_maxi),
        ("SCHEMA_TEMPS/PAS_LIMI_RELA", Some(o.pas_limi_rela)),
    ];
    for (key, value) in bounds {
        if value.is_some_and(|x| !positive(x)) {
            return Err(invalid(key, "must be > 0"));
        }
    }
    if let (Some(lo), Some(hi)) = (o.pas_mini, o.pas_maxi) {
        if hi < lo {
            return Err(invalid(
                "SCHEMA_TEMPS/PAS_MINI",
                "PAS_MINI must be ≤ PAS_MAXI",
            ));
        }
    }
    Ok(())
}

/// Integrates M q̈ + C q̇ + K q = Σ f_i·g_i(t) + Σ_s Φ_sᵀ F_s from `init` = (q0, v0) over
/// `times` with `scheme`, archiving as `archive` asks; `progress` receives the fraction
/// of the interval done. The shocks' states are advanced (they hold the final state).
// The operator's signature: each argument is one keyword group of DYNA_VIBRA.
#[allow(clippy::too_many_arguments)]
pub fn integrate(
    structure: &dyn Structure,
    shocks: &mut [Shock],
    forcing: &[Forcing],
    init: (&[f64], &[f64]),
    scheme: Scheme,
    times: TimeGrid,
    archive: &Archive,
    progress: &mut dyn FnMut(f64),
) -> Result<Trajectory, TransientError> {
    integrate_from(
        structure, shocks, forcing, init, None, scheme, times, archive, progress,
    )
}

/// [`integrate`] from a stored instant (ETAT_INIT=_F(RESULTAT=...), Code_Aster's restart):
/// with `acceleration`, the start's acceleration is that one and the shocks' states are
/// those the caller set on them (their internal variables at that instant): nothing is
/// re-evaluated at t0 before the first step, as Code_Aster goes on from a stored state.
/// The row archived at t0 holds the shocks evaluated there from those states.
#[allow(clippy::too_many_arguments)]
pub fn integrate_from(
    structure: &dyn Structure,
    shocks: &mut [Shock],
    forcing: &[Forcing],
    init: (&[f64], &[f64]),
    acceleration: Option<&[f64]>,
    scheme: Scheme,
    times: TimeGrid,
    archive: &Archive,
    progress: &mut dyn FnMut(f64),
) -> Result<Trajectory, TransientError> {
    let n = structure.n();
    check_inputs(n, shocks, forcing, init, &times, archive)?;
    if let Some(a0) = acceleration {
        check_len("ETAT_INIT/RESULTAT (ACCE)", a0.len(), n)?;
        if !finite(a0) {
            return Err(invalid(
                "ETAT_INIT",
                "the initial acceleration is not finite",
            ));
        }
    }
    check_scheme(&scheme)?;
    let model = Model { structure, forcing };
    let mut ws = Work::new(n, shocks)?;
    let mut q = try_zeros("the state", n)?;
    let mut v = try_zeros("the state", n)?;
    let mut a = try_zeros("the state", n)?;
    q.copy_from_slice(init.0);
    v.copy_from_slice(init.1);
    match acceleration {
        Some(a0) => {
            a.copy_from_slice(a0);
            // The shocks at t0 for the archive, their committed states left as given.
            model.force(shocks, times.t0, &q, &v, &mut ws);
        }
        None => {
            model.acceleration(shocks, times.t0, &q, &v, &mut a, &mut ws)?;
            if !finite(&a) {
                return Err(TransientError::NonFinite { t: times.t0 });
            }
            commit(shocks, &ws.evals);
        }
    }
    let (nsteps, h) = times.fixed_steps();
    let listed = archive.listed().map_or(0, <[f64]>::len);
    let rows = match (archive.every(), &scheme) {
        (None, _) => listed,
        (Some(k), Scheme::Adaptive(_) | Scheme::Adapt(_) | Scheme::Devoge(_)) => {
            ((times.t_end - times.t0) / times.dt / k as f64 + 2.0 + listed as f64)
                .min(INITIAL_ROWS_CAP as f64) as usize
        }
        (Some(k), _) => nsteps / k.max(1) + 2 + listed,
    };
    let mut rec = Recorder::new(n, shocks.len(), rows)?;
    if archive.every().is_some() {
        rec.push(times.t0, &q, &v, &a, &ws.evals)?;
    }
    let mut forced = Vec::new();
    let (taken, rejected, events) = match scheme {
        Scheme::Devoge(opts) => {
            let st = run_devoge(
                &model, shocks, &opts, &q, &v, &a, times, archive, &mut rec, &mut ws, progress,
            )?;
            (st.taken, st.rejected, Vec::new())
        }
        Scheme::Adapt(opts) => {
            let st = run_adapt(
                &model, shocks, &opts, &q, &v, &a, times, archive, &mut rec, &mut ws, progress,
            )?;
            forced = st.forced;
            (st.taken, st.retried, Vec::new())
        }
        // Code_Aster's RUNGE_KUTTA_32/54 (rk_loop.rs).
        Scheme::Adaptive(opts) if !opts.locate_contacts => {
            let st = run_rk(
                &model, shocks, &opts, &q, &v, &a, times, archive, &mut rec, &mut ws, progress,
            )?;
            (st.taken, st.rejected, Vec::new())
        }
        // LOCALISATION_CHOC='OUI': aster-nl's event-located pairs.
        Scheme::Adaptive(opts) => {
            // The error scale's floor near rest (adaptive.rs): 1/ω²_max of the structure
            // with its shocks' stiffness (without it, the large accelerations of a contact
            // would loosen the test there), none for a structure without stiffness. A
            // scale needs no converged eigenvalue: 30 power steps (an estimate from below
            // makes the floor that much larger; the converged one cost 0.2 s on 3000 DOFs).
            let omega_max = max_pulsation(structure, shocks, Some(FLOOR_POWER_STEPS))?;
            let floor = if omega_max > 0.0 && omega_max.is_finite() {
                1.0 / (omega_max * omega_max)
            } else {
                0.0
            };
            let st = run_adaptive(
                &model, shocks, &opts, floor, &q, &v, &a, times, archive, &mut rec, &mut ws,
                progress,
            )?;
            (st.taken, st.rejected, st.events)
        }
        Scheme::DiffCentre | Scheme::Newmark { .. } => {
            let mut stepper = match scheme {
                Scheme::Newmark { beta, gamma } => {
                    Stepper::Newmark(Box::new(Newmark::new(structure, shocks, beta, gamma, h)?))
                }
                _ => {
                    let (limit, omega_max) = stability_limit(structure, shocks)?;
                    if h > limit {
                        return Err(TransientError::Unstable {
                            dt: h,
                            limit,
                            omega_max,
                        });
                    }
                    Stepper::Diff(DiffCentre)
                }
            };
            let start = Start {
                q: &mut q,
                v: &mut v,
                a: &mut a,
            };
            // t0's listed instants are archived inside, before the commit.
            let taken = run_fixed(
                &model,
                shocks,
                &mut stepper,
                start,
                times,
                archive,
                &mut rec,
                &mut ws,
                progress,
            )?;
            (taken, 0, Vec::new())
        }
    };
    let mut traj = rec.traj;
    traj.steps_taken = taken;
    traj.steps_rejected = rejected;
    traj.events = events;
    traj.steps_forced = forced;
    Ok(traj)
}
