//! EHMAN stage 3, the correction: the points of one branch from its series, the branch end
//! Newton-corrected (newton.rs), checked against its contact law in time, and retried from
//! the same series with a shorter step when it fails (docs/nnm.md, "Failed corrections").

use crate::nnm::continuation::anm;
use crate::nnm::continuation::end_check::EndCheck;
use crate::nnm::continuation::frequency_floor::OffTheFamily;
use crate::nnm::continuation::newton;
use crate::nnm::continuation::report::in_branch;
use crate::nnm::continuation::step_control::ROOT_JUMP_RATIO;
use crate::nnm::error::{Error, Result, Setting};
use crate::nnm::model::energy::energy_ca_joules;
use crate::nnm::model::point::{finite, make_point};
use crate::nnm::model::root_defect::frequency_defect;
use crate::nnm::model::system::System;
use crate::nnm::model::workspace::Workspace;
use crate::nnm::solve::linear_solver::TangentSolver;
use crate::nnm::{Continuation, Point, Settings, StepControl};

/// Why a corrected branch end is not a point of the physical family although its residual
/// converged, if it is not (StepControl::law_defect_max, work_min, frequency_floor,
/// spread_max): the error a retry with a shorter step may cure, else the one that stops the
/// run. The law check's absolute defect is kept on the point (`Point::law_defect`) for its
/// row.
///
/// `start_energy`: the ENERGIE of the branch's start (J), which tells a descending branch.
pub(in crate::nnm) fn off_the_law(
    control: &StepControl,
    law_check: Option<&dyn EndCheck>,
    end: &mut Point,
    start_energy: f64,
) -> Result<Option<Error>> {
    if let (Some(max), Some(check)) = (control.law_defect_max, law_check) {
        let (absolute, defect) = check.law_defects(&end.x)?;
        end.law_defect = Some((absolute, defect));
        if defect.is_nan() || defect > max {
            return Ok(Some(
                Error::numerical(format!(
                    "the branch end satisfies its contact law in time only to {defect:.3e} x \
                     max(RIGI_NOR*JEU, largest contact force) > ECART_LOI_CHOC_MAXI = {max:.3e} \
                     (ENERGIE = {:.6e}, FREQUENCE = {:.6e} Hz): the branch has left the physical \
                     root of the regularised law (a converged solution of the harmonic balance \
                     that is not a motion of the system)",
                    end.energy, end.frequency
                ))
                .setting(Setting::LawDefectMax)
                .hint(
                    "lower PREC_MAN (1e-9 or below: shorter series steps do not jump across to \
                     the other root of the law), raise PARA_REGUL, or raise NB_HARM_NONL",
                ),
            ));
        }
    }
    if let (Some(min), Some(check)) = (control.work_min, law_check) {
        if let Some(ratio) = check.not_a_motion(&end.x, min)? {
            return Ok(Some(
                Error::numerical(format!(
                    "the contact forces of the branch end attract the structure on average: \
                     their work on the displacement over the period is {ratio:.3e} x its elastic \
                     virial < TRAVAIL_CHOC_MINI = {min:.3e} (ENERGIE = {:.6e}, FREQUENCE = \
                     {:.6e} Hz): a root of the truncated harmonic balance, not a motion of the \
                     system (its force series is too short for the contact it carries)",
                    end.energy, end.frequency
                ))
                .setting(Setting::ContactWorkMin)
                .hint(
                    "raise NB_HARM_NONL and NB_HARM_LINE (a stiff stop needs both), or raise \
                     PARA_REGUL or lower RIGI_NOR",
                ),
            ));
        }
    }
    if let Some(max) = control.gamma_max {
        let ratio = relative_gamma(end);
        if ratio.is_nan() || ratio > max {
            return Ok(Some(
                Error::numerical(format!(
                    "the branch end balances its equations only with a fictitious damping \
                     AMOR_FICTIF = {:.3e}, {ratio:.3e} x its pulsation > AMOR_FICTIF_MAXI = \
                     {max:.3e} (ENERGIE = {:.6e}, FREQUENCE = {:.6e} Hz): over a period that \
                     damping does work of about {:.1e} x the energy, so the point is not a \
                     periodic orbit of the conservative structure (a root of the truncated \
                     harmonic balance)",
                    end.gamma.abs(),
                    end.energy,
                    end.frequency,
                    2.0 * std::f64::consts::PI * ratio
                ))
                .setting(Setting::FictitiousDampingMax)
                .hint(
                    "raise NB_HARM_NONL and NB_HARM_LINE (the truncated contact force is not \
                     conservative enough), or lower PREC_MAN",
                ),
            ));
        }
    }
    if let Some(floor) = &control.frequency_floor {
        let descending = end.energy < start_energy;
        let why = match floor.off_the_family(end.frequency, end.energy, descending) {
            Some(OffTheFamily::Below(dip)) => Some((
                format!(
                    "the branch end is {dip:.3e} x the linear frequency {:.6e} Hz of its mode \
                     below it > BAISSE_FREQ_MAXI = {:.3e}, with no internal resonance near to \
                     explain it (ENERGIE = {:.6e}, FREQUENCE = {:.6e} Hz): the contact laws \
                     only stiffen the structure, so this is a root of the truncated harmonic \
                     balance, not a motion of the system (its frequency is wrong by at least \
                     that much)",
                    floor.linear(),
                    floor.tolerance(),
                    end.energy,
                    end.frequency
                ),
                "raise NB_HARM_NONL (the contact force of a stiff or weakly regularised stop \
                 needs many harmonics near first contact), or raise PARA_REGUL or lower \
                 RIGI_NOR",
            )),
            Some(OffTheFamily::Linear(distance)) => Some((
                format!(
                    "the branch end is far below first contact (ENERGIE = {:.6e}) yet \
                     {distance:.3e} x the linear frequency {:.6e} Hz of its mode away from it \
                     (FREQUENCE = {:.6e} Hz): a motion that reaches no stop is the linear mode, \
                     so the branch has folded back onto the equilibrium, which solves the \
                     harmonic balance at any frequency",
                    end.energy,
                    floor.linear(),
                    end.frequency
                ),
                "the rows before are the family down to that energy; to go further up, \
                 restart from a row in contact with ETAT_INIT=_F(MODE_NON_LINE=..., \
                 NUME_ORDRE=...) and the other DIR_EVOLUTION, or lower PREC_MAN",
            )),
            Some(OffTheFamily::Cone(above)) => Some((
                format!(
                    "the branch goes down far below first contact (ENERGIE = {:.6e}) and its \
                     end is {above:.3e} x the linear frequency {:.6e} Hz of its mode above it \
                     (FREQUENCE = {:.6e} Hz): no obstacle is reached, so with the nonsmooth \
                     law the motion is the linear mode at that frequency; what lifts it is the \
                     regularised ring's force at its centre (about η/JEU whatever the \
                     amplitude), which stiffens a small motion through the centre without \
                     bound as the amplitude falls. Further down the regularisation alone sets \
                     the frequency, and the truncated force series, which flips across the \
                     centre, resolves it poorly",
                    end.energy,
                    floor.linear(),
                    end.frequency
                ),
                "the rows before are the family down to that energy; to follow the linear \
                 mode further down, lower PARA_REGUL or give LOI_CERCLE='SECANTE' (no force \
                 at the centre); to go up into contact, use the other DIR_EVOLUTION",
            )),
            None => None,
        };
        if let Some((why, hint)) = why {
            return Ok(Some(
                Error::numerical(why)
                    .setting(Setting::FrequencyDropMax)
                    .hint(hint),
            ));
        }
    }
    if let Some(max) = control.spread_max {
        let spread = end.energy_spread;
        if spread.is_nan() || spread > max {
            return Ok(Some(
                Error::numerical(format!(
                    "the energy of the branch end varies over the period by ECART_ENERGIE = \
                     {spread:.3e} > ECART_ENERGIE_MAXI = {max:.3e} (ENERGIE = {:.6e}, FREQUENCE \
                     = {:.6e} Hz): the point is not a periodic orbit of the system to that \
                     accuracy",
                    end.energy, end.frequency
                ))
                .setting(Setting::EnergySpreadMax)
                .hint(
                    "raise NB_HARM_LINE (a stiff stop needs many harmonics of the displacement), \
                     lower PREC_MAN, or raise PARA_REGUL",
                ),
            ));
        }
    }
    Ok(None)
}

/// The points of one branch: the series evaluated at a_max·i/np, the last one corrected.
/// Ok(Err(e)): the correction failed (retryable with a shorter step); Err: anything else.
struct BranchPoints {
    points: Vec<Point>,
    /// The corrected end (scaled).
    x_end: Vec<f64>,
    newton_iterations: usize,
    /// The unit tangent of the series at the end.
    tangent: Vec<f64>,
    /// How far the Newton correction moved the end, relative to the step: ‖x_end − x̂‖ /
    /// ‖x̂ − x0‖, x̂ the series' prediction (0 when the prediction needed no correction).
    correction_ratio: f64,
    /// The end's frequency defect (model/root_defect.rs), once `jumped_off` has computed it.
    end_defect: Option<f64>,
}

fn branch_points_of(
    sys: &System,
    ws: &mut Workspace,
    solver: &mut dyn TangentSolver,
    cont: &Continuation,
    series: &anm::Series,
    x0: &[f64],
    b: usize,
) -> Result<std::result::Result<BranchPoints, Error>> {
    let np = cont.n_points_per_branch;
    let mut branch_points = Vec::with_capacity(np);
    let mut newton_iterations = 0;
    let tangent = series.unit_tangent(series.a_max);
    if !finite(&tangent) {
        return Err(in_branch(
            Error::numerical("the branch tangent is not finite"),
            b,
        ));
    }
    let series_bif = series
        .bifurcation
        .map(|ab| (((ab / series.a_max) * np as f64).round() as usize).clamp(1, np));
    let mut x_end = Vec::new();
    let mut correction_ratio = 0.0;
    for i in 1..=np {
        let a = series.a_max * i as f64 / np as f64;
        let mut x = series.eval(x0, a);
        if !finite(&x) {
            return Err(in_branch(
                Error::numerical(format!("the series diverged at a = {a:.3e} (point {i})")),
                b,
            ));
        }
        // The end's residual is the Newton correction's first evaluation (not twice).
        let mut res = if i == np {
            f64::NAN
        } else {
            newton::relative(&sys.residual(&x, ws), &x)
        };
        let mut at_floor = false;
        if i == np {
            let predicted = x.clone();
            let corr = match newton::correct(
                sys,
                ws,
                solver,
                &mut x,
                &tangent,
                cont.prec_newton,
                cont.iter_newton_max,
            ) {
                Ok(c) => c,
                Err(e) => return Ok(Err(e)),
            };
            newton_iterations = corr.iterations;
            res = corr.residual;
            at_floor = corr.at_floor;
            x_end = x.clone();
            correction_ratio = distance(&x, &predicted) / distance(&predicted, x0);
        }
        let mut p = make_point(sys, &x, res, b, series_bif == Some(i));
        p.at_floor = at_floor;
        if !(p.energy.is_finite() && p.omega.is_finite() && p.energy_spread.is_finite()) {
            return Err(in_branch(
                Error::numerical(format!("energy or frequency not finite at point {i}")),
                b,
            ));
        }
        if p.frequency <= 0.0 {
            // Not a periodic orbit: the series has jumped off the family (a shorter step
            // stays closer to its origin).
            return Ok(Err(Error::numerical(format!(
                "the frequency is not positive at point {i} ({:.6e} Hz): the branch has left the \
                 family of periodic orbits",
                p.frequency
            ))
            .setting(Setting::SeriesPrecision)
            .hint(
                "lower PREC_MAN (shorter, more accurate branches) or raise PARA_REGUL",
            )));
        }
        branch_points.push(p);
    }
    Ok(Ok(BranchPoints {
        end_defect: None,
        points: branch_points,
        x_end,
        newton_iterations,
        tangent,
        correction_ratio,
    }))
}

/// Euclidean distance of two vectors of unknowns.
fn distance(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(p, q)| (p - q) * (p - q))
        .sum::<f64>()
        .sqrt()
}

/// One branch, corrected: its points (the last one the corrected end), the corrected end in
/// scaled units, the Newton iterations of its correction, the end tangent, and how many
/// times the step was halved before the correction held.
pub(in crate::nnm) struct CorrectedBranch {
    pub points: Vec<Point>,
    pub x_end: Vec<f64>,
    pub newton_iterations: usize,
    pub tangent: Vec<f64>,
    pub step_retries: usize,
    /// The end's frequency defect when the root check computed it: the next branch's
    /// `start_defect`.
    pub end_defect: Option<f64>,
}

/// The points of branch `b` from `series` at `x0`. A failed correction, or a corrected end off
/// its contact law ([`off_the_law`]), is retried from the same series with a_max halved (the
/// series is more accurate closer to its origin), at most `control.retries_max` times; then
/// the last failure stops the run, naming the retries.
///
/// A branch whose end jumped off its family ([`Jump`]: the correction moved it as far as
/// the step, or its contact forces jumped to the other root of their law) is retried
/// likewise. The jump is taken for the branch's own, and the first, full-length attempt
/// kept (as without the check), when every shorter step jumps too or a shorter step fails
/// its correction. (Keeping the full step as soon as a shorter one carried a defect within
/// [`ROOT_JUMP_RATIO`] of it, to spare steep physical branches the shorter steps, let one
/// run of the wall grid end with exit 0 on the wrong family: near grazing the two families
/// are too close for that test.)
#[allow(clippy::too_many_arguments)]
pub(in crate::nnm) fn correct_branch(
    sys: &System,
    ws: &mut Workspace,
    solver: &mut dyn TangentSolver,
    settings: &Settings,
    control: &StepControl,
    law_check: Option<&dyn EndCheck>,
    series: &mut anm::Series,
    x0: &[f64],
    start_defect: Option<f64>,
    b: usize,
) -> Result<CorrectedBranch> {
    let defect_at_start = match control.root_jump_max {
        Some(_) if !sys.shocks.is_empty() => match start_defect {
            Some(d) => Some(d),
            None => Some(frequency_defect(sys, x0)?),
        },
        _ => None,
    };
    // Only the frequency floor's cone check reads it (a descending branch).
    let start_energy = if control.frequency_floor.is_some() {
        energy_ca_joules(sys, x0)
    } else {
        f64::NAN
    };
    let mut step_retries = 0;
    // The first attempt whose end jumped off the family, its step and the retries before
    // it: what is kept when no shorter step stays on the family (the discarded attempts
    // then count no retry, the row is as without the check).
    let mut jumped: Option<(BranchPoints, f64, usize)> = None;
    let BranchPoints {
        mut points,
        x_end,
        newton_iterations,
        tangent,
        end_defect,
        ..
    } = loop {
        let attempt = branch_points_of(sys, ws, solver, &settings.continuation, series, x0, b)?
            .and_then(|mut done| {
                match done.points.last_mut() {
                    Some(end) => off_the_law(control, law_check, end, start_energy)?,
                    None => None,
                }
                .map_or(Ok(done), Err)
            });
        match attempt {
            Ok(mut done) => {
                let jump = jumped_off(sys, control, defect_at_start, &mut done)?;
                if jump.is_some() && step_retries < control.retries_max {
                    if jumped.is_none() {
                        jumped = Some((done, series.a_max, step_retries));
                    }
                    step_retries += 1;
                    series.a_max *= 0.5;
                    continue;
                }
                match jumped.take() {
                    Some((first, a_max, retries)) if jump.is_some() => {
                        series.a_max = a_max;
                        step_retries = retries;
                        break first;
                    }
                    _ => break done,
                }
            }
            Err(_) if step_retries < control.retries_max => {
                step_retries += 1;
                series.a_max *= 0.5;
            }
            Err(e) => {
                if let Some((first, a_max, retries)) = jumped.take() {
                    series.a_max = a_max;
                    step_retries = retries;
                    break first;
                }
                if step_retries == 0 {
                    return Err(in_branch(e, b));
                }
                let e = Error {
                    message: format!(
                        "{} (also with the series step halved {step_retries} times, a_max = {:.3e})",
                        e.message, series.a_max
                    ),
                    ..e
                };
                return Err(in_branch(e, b));
            }
        }
    };
    if let Some(p) = points.last_mut() {
        p.step_retries = step_retries;
    }
    Ok(CorrectedBranch {
        points,
        x_end,
        newton_iterations,
        tangent,
        step_retries,
        end_defect,
    })
}

/// Why a corrected branch end is taken to have left the family its branch started on.
#[derive(Clone, Copy, Debug)]
enum Jump {
    /// The Newton correction moved it by more than `control.correction_ratio_max` times the
    /// step: a prediction that accurate lands next to its own family, a correction of the
    /// order of the step has reached another one (e.g. where two families cross at grazing).
    Correction,
    /// Its contact forces sit on another root of their law than at the branch start: the
    /// frequency defect they carry (model/root_defect.rs) grew past both
    /// `control.root_jump_max` and [`ROOT_JUMP_RATIO`] times its value at the start. On one
    /// family the defect grows smoothly (by a factor of about 100 over the branch that
    /// reaches first contact, measured on sdnd122's wall); a step that crosses grazing onto
    /// the family whose forces vanish in contact raises it from round-off to the whole
    /// frequency shift of the contact (1e-8 to 7e-3 there) at once.
    Root,
}

fn jumped_off(
    sys: &System,
    control: &StepControl,
    defect_at_start: Option<f64>,
    done: &mut BranchPoints,
) -> Result<Option<Jump>> {
    if control
        .correction_ratio_max
        .is_some_and(|max| done.correction_ratio > max)
    {
        return Ok(Some(Jump::Correction));
    }
    let (Some(max), Some(start)) = (control.root_jump_max, defect_at_start) else {
        return Ok(None);
    };
    let end = frequency_defect(sys, &done.x_end)?;
    done.end_defect = Some(end);
    Ok((end > max.max(ROOT_JUMP_RATIO * start)).then_some(Jump::Root))
}

/// AMOR_FICTIF relative to the pulsation, |γ|/ω: the work of the fictitious damping over a
/// period is about 2π times this fraction of the energy (StepControl::gamma_max).
pub fn relative_gamma(p: &Point) -> f64 {
    p.gamma.abs() / (2.0 * std::f64::consts::PI * p.frequency.abs())
}
