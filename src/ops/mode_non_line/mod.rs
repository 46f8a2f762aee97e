//! MODE_NON_LINE: branches of nonlinear normal modes with shocks (EHMAN).
//!
//! Glue only: reads the matrices, the start (a linear mode or a row of an earlier
//! MODE_NON_LINE table), the shocks and the settings, reduces the problem on a
//! Craig–Bampton basis when REDUCTION asks (reduction.rs), runs `nnm`, and stores the
//! result table (a real SQL table), the CARA_CHOC sub-table, every point's unknowns, the
//! displacement Fourier coefficients of every DOF and the basis.

mod end;
mod exact_law;
pub(crate) mod inputs;
pub(crate) mod problem;
mod reduction;
mod restart;
mod start;
mod table;

use crate::args::Args;
use crate::error::{Error, ErrorKind, Result};
use crate::model::assembly::AssembledMatrix;
use crate::nnm::exact_law::ExactLawSettings;
use crate::nnm::Settings;
use crate::nnm::{self, Problem, StartState};
use crate::ops::{common::progress::Progress, OpContext};
use crate::store::mnl::StoredShock;
use crate::store::mnl::{self as mnl_store, MnlSetup};
use crate::store::{matrix, table as table_store};
use crate::table::{Cell, ColKind, Table};
use inputs::StopBounds;
use inputs::{
    check_budget, check_restart_harmonics, orig_obst_notes, settings, shocks_from_args,
    step_control, stop_bounds,
};
use problem::{engine_shocks, row_of, shocks_from_cara_choc};
use table::{cara_choc_table, max_int, new_table, restart_reprise, row};

pub fn run(ctx: &mut OpContext<'_>, args: &Args) -> Result<()> {
    let name = match (ctx.reuse, ctx.result) {
        (Some(r), _) => r.to_string(),
        (None, Some(r)) => r.to_string(),
        (None, None) => ctx.result_name()?.to_string(),
    };
    let (call, mut control) = read_call(ctx, args, &name)?;
    let start = start_state(ctx, args, &call)?;
    let (problem, settings, restart_from) = (&call.problem, &call.settings, &call.restart_from);

    // The linear modes (dense, small models only): the frequency floor of a family that
    // starts from a linear mode, and the internal-resonance alarm after the run.
    let linear_modes = nnm::linear_modes(problem)?;
    if restart_from.is_none() {
        control.frequency_floor = nnm::FrequencyFloor::new(
            problem,
            linear_modes.as_deref(),
            start.point.frequency,
            settings.harmonics.h_lin,
            args.req_fact("RESOLUTION")?.req_real("BAISSE_FREQ_MAXI")?,
        );
    }
    // The rows kept after a wrong-branch end are judged by the same checks.
    let floor = control.frequency_floor.clone();
    let work_min = control.work_min.unwrap_or(f64::NEG_INFINITY);
    let gamma_max = control.gamma_max;

    let outcome = follow(ctx, &name, &call, control, start)?;

    let (table, first_order, reprise) = result_table(ctx, restart_from)?;
    // Built once: what every row's outputs share (layout, physical laws, FFT plan).
    let post = nnm::PostProcessor::new(problem, settings)?;
    // A branch that left the physical root of its law: its trailing suspect rows are not
    // stored; every other run stores every row.
    let kept = rows_kept(&post, &outcome, floor.as_ref(), work_min, gamma_max)?;
    let points = &outcome.points[..kept];
    // Rows and how far their orbits reach into the obstacles, for the regularisation's
    // alarm (runs from a linear mode only: the floor knows its frequency).
    let clearance = floor.is_some();
    let checks = store_rows(
        ctx,
        &name,
        &call,
        &post,
        points,
        table,
        first_order,
        reprise,
        clearance,
    )?;
    row_alarms(
        ctx,
        &call,
        points,
        first_order,
        &checks,
        floor.as_ref(),
        linear_modes.as_deref(),
    )?;

    end::report(
        ctx,
        outcome.error.map(Error::from),
        outcome.limit.as_deref(),
        points,
        outcome.points.len() - kept,
        settings.continuation.n_branches,
        first_order,
    )?;
    Ok(())
}

/// The result table: a new one, or the reused one extended; with the NUME_ORDRE of its first
/// new row and the NUME_REPRISE of this call.
fn result_table(ctx: &OpContext<'_>, restart_from: &Option<String>) -> Result<(Table, i64, i64)> {
    Ok(match ctx.reuse {
        Some(r) => {
            let t = table_store::load_table(ctx.store, r)?;
            let last = max_int(&t, "NUME_ORDRE");
            let rep = max_int(&t, "NUME_REPRISE") + 1;
            (t, last + 1, rep)
        }
        None => (
            new_table(),
            1,
            i64::from(restart_from.is_some()) + restart_reprise(ctx, restart_from)?,
        ),
    })
}

/// How many of the run's rows are stored: all, or, after an end on a wrong branch, those
/// before its trailing rows that are not motions by the run's own checks (end::rows_kept;
/// the defects are computed only then, the rows' outputs are not kept in memory).
fn rows_kept(
    post: &nnm::PostProcessor,
    outcome: &nnm::Outcome,
    floor: Option<&nnm::FrequencyFloor>,
    work_min: f64,
    gamma_max: Option<f64>,
) -> Result<usize> {
    Ok(if end::cuts_rows(outcome.error.as_ref()) {
        let motions = outcome
            .points
            .iter()
            .enumerate()
            .map(|(i, p)| {
                // Descending: below the row before (the cone is judged going down only).
                let descending = i > 0 && p.energy < outcome.points[i - 1].energy;
                let off_the_family = floor.is_some_and(|f| {
                    f.off_the_family(p.frequency, p.energy, descending)
                        .is_some()
                });
                let damped = gamma_max.is_some_and(|max| {
                    let ratio = nnm::relative_gamma(p);
                    ratio.is_nan() || ratio > max
                });
                Ok(!off_the_family && !damped && post.is_motion(&p.x, p.law_defect, work_min)?)
            })
            .collect::<Result<Vec<bool>>>()?;
        end::rows_kept(outcome.error.as_ref(), &motions)
    } else {
        outcome.points.len()
    })
}

/// What the call asks for, read once: the matrices, the settings, the shocks (from CHOC, or
/// from the start table's CARA_CHOC on a restart) and the engine's problem, checked (the
/// shock table's name, the exact-law settings, the cost) before anything is computed.
struct Call {
    k_name: String,
    m_name: String,
    cara_choc: String,
    k: AssembledMatrix,
    free: Vec<usize>,
    settings: Settings,
    exact_settings: Option<ExactLawSettings>,
    bounds: StopBounds,
    restart_from: Option<String>,
    stored_shocks: Vec<StoredShock>,
    /// The problem the engine solves: on the free DOFs, or on the reduction basis.
    problem: Problem,
    /// REDUCTION (or a restart from a reduced run): the basis of `problem`'s coordinates.
    reduction: Option<nnm::Reduced>,
}

fn read_call(ctx: &mut OpContext<'_>, args: &Args, name: &str) -> Result<(Call, nnm::StepControl)> {
    let k_name = args.req_concept("MATR_RIGI")?.name.clone();
    let m_name = args.req_concept("MATR_MASS")?.name.clone();
    let cara_choc = format!("{name}_CHOC");
    // The shock table's name is derived from the result's: a concept of that name made
    // by another operator is the user's, never silently replaced.
    if let Some(op) = ctx
        .store
        .concept_operator(&cara_choc)?
        .filter(|_| ctx.reuse.is_none())
    {
        if op != "MODE_NON_LINE" {
            return Err(Error::validation(format!(
                "MODE_NON_LINE stores its shocks in the table {cara_choc}, but a concept of \
                 that name already exists (made by {op}) and would be overwritten"
            ))
            .hint(format!(
                "name the result of MODE_NON_LINE otherwise, or rename the concept {cara_choc}"
            )));
        }
    }
    let k = matrix::load_matrix(ctx.store, &k_name)?;
    let m = matrix::load_matrix(ctx.store, &m_name)?;
    k.refuse_damping(&k_name, "MODE_NON_LINE/MATR_RIGI")?;
    m.refuse_damping(&m_name, "MODE_NON_LINE/MATR_MASS")?;
    if !k.same_dofs(&m) {
        return Err(Error::input(format!(
            "{k_name} and {m_name} are not assembled on the same DOF numbering and boundary conditions"
        ))
        .keyword("MODE_NON_LINE/MATR_MASS"));
    }
    k.refuse_relations("MODE_NON_LINE")
        .map_err(|e| e.keyword("MODE_NON_LINE/MATR_RIGI"))?;
    let free = k.free_dofs();
    let settings = settings(args)?;
    let exact_settings = exact_law::settings(args, &settings)?;
    let control = step_control(args)?;
    let bounds = stop_bounds(args)?;
    let etat = args.req_fact("ETAT_INIT")?;

    // Shocks: from CHOC on a first run, from the stored CARA_CHOC on a restart.
    let restart_from = etat.concept("MODE_NON_LINE").map(|c| c.name.clone());
    let restart_setup = match &restart_from {
        Some(src) => Some(mnl_store::load_setup(ctx.store, src)?),
        None => None,
    };
    let stored_shocks = match (&restart_from, &restart_setup) {
        (Some(src), Some(setup)) => {
            if args.has("CHOC") {
                ctx.alarm(
                    "MODE_NON_LINE_2",
                    "CHOC is ignored on a restart: the shocks come from the CARA_CHOC of the start table",
                )?;
            }
            if args.has("RESSORT_CUBIQUE") {
                ctx.alarm(
                    "MODE_NON_LINE_2",
                    "RESSORT_CUBIQUE is ignored on a restart: the cubic springs come from the CARA_CHOC of the start table",
                )?;
            }
            check_restart_harmonics(setup, &settings.harmonics)?;
            // The contact data of the start row, as Code_Aster reads them: from the
            // sub-table named in its CARA_CHOC cell.
            let t = table_store::load_table(ctx.store, src)?;
            let order = etat.req_int("NUME_ORDRE")?;
            let sub = row_of(&t, order)
                .and_then(|r| t.cell(r, "CARA_CHOC"))
                .and_then(Cell::as_text)
                .map(str::to_string)
                .unwrap_or_else(|| setup.cara_choc.clone());
            shocks_from_cara_choc(&table_store::load_table(ctx.store, &sub)?, &sub)?
        }
        _ => shocks_from_args(ctx, args)?,
    };
    if ctx.info >= 1 {
        for line in orig_obst_notes(&stored_shocks) {
            ctx.say(&line)?;
        }
    }
    let shocks = engine_shocks(&stored_shocks, &k)?;
    let full = Problem {
        forcing: None,
        k: k.reduced()?,
        m: m.reduced()?,
        shocks,
    };
    let (problem, reduction) = reduce_if_asked(
        ctx,
        args,
        full,
        (&restart_from, restart_setup.as_ref()),
        &settings,
        (&k, &k_name),
    )?;

    if let Some(x) = &exact_settings {
        exact_law::check(&problem, x)?;
    }
    check_budget(ctx, &problem, &settings)?;
    let call = Call {
        k_name,
        m_name,
        cara_choc,
        k,
        free,
        settings,
        exact_settings,
        bounds,
        restart_from,
        stored_shocks,
        problem,
        reduction,
    };
    Ok((call, control))
}

/// The problem the engine solves: the full one, or its reduction (REDUCTION on a first run;
/// a restart goes on with the basis of the run it starts from).
fn reduce_if_asked(
    ctx: &mut OpContext<'_>,
    args: &Args,
    full: Problem,
    (restart_from, restart_setup): (&Option<String>, Option<&MnlSetup>),
    settings: &Settings,
    (k, k_name): (&AssembledMatrix, &str),
) -> Result<(Problem, Option<nnm::Reduced>)> {
    let asked = reduction::ask(args)?;
    let basis = match (restart_from, restart_setup) {
        (Some(src), Some(setup)) => {
            if asked.is_some() {
                ctx.alarm(
                    "MODE_NON_LINE_2",
                    "REDUCTION is ignored on a restart: the run goes on with the model of the start table's run (its basis, if it had one)",
                )?;
            }
            match &setup.reduction {
                Some(r) => Some(mnl_store::load_basis(ctx.store, src, r)?),
                None => None,
            }
        }
        _ => match asked {
            Some(ask) => {
                let etat = args.req_fact("ETAT_INIT")?;
                let f_start = start::linear_frequency(ctx, etat, k, k_name)?;
                Some(reduction::basis(
                    &full,
                    ask.cut(settings.harmonics.h_lin, f_start),
                )?)
            }
            None => None,
        },
    };
    let Some(basis) = basis else {
        return Ok((full, None));
    };
    let problem = nnm::reduced_problem(&full, &basis)?;
    if ctx.info >= 1 {
        ctx.say(&format!(
            "  REDUCTION: {} free DOF(s) -> {} coordinate(s): {} shock DOF(s) and {} fixed-interface mode(s){}",
            basis.n,
            basis.size(),
            basis.retained.len(),
            basis.omega2.len(),
            match crate::linalg::craig_bampton::highest_frequency(&basis) {
                Some(f) => format!(", the highest at {f:.6e} Hz"),
                None => String::new(),
            }
        ))?;
    }
    Ok((problem, Some(nnm::Reduced::new(basis, &full)?)))
}

/// The first point: a stored row (a restart, in the direction DIR_EVOLUTION asks relative to
/// the stored travel) or a linear mode scaled by COEF_AMPL.
fn start_state(ctx: &mut OpContext<'_>, args: &Args, call: &Call) -> Result<StartState> {
    let Call {
        restart_from,
        problem,
        settings,
        k,
        k_name,
        ..
    } = call;
    let etat = args.req_fact("ETAT_INIT")?;

    let nume_ordre = etat.req_int("NUME_ORDRE")?;
    let start: StartState = match &restart_from {
        Some(src) => {
            let x = mnl_store::load_point(ctx.store, src, nume_ordre)?.ok_or_else(|| {
                Error::input(format!("{src} has no row NUME_ORDRE={nume_ordre}"))
                    .keyword("MODE_NON_LINE/ETAT_INIT/NUME_ORDRE")
            })?;
            // A stored point that does not fit these settings is the start row's fault.
            let start_state = nnm::start_from_point(problem, settings, &x).map_err(|e| {
                let e = Error::from(e);
                if e.kind == ErrorKind::Input {
                    e.keyword("ETAT_INIT/NUME_ORDRE")
                } else {
                    e
                }
            })?;
            restart_direction(
                ctx,
                src,
                nume_ordre,
                settings.continuation.direction,
                start_state,
            )?
        }
        None => {
            let start = start::from_linear_modes(
                ctx,
                etat,
                (problem, call.reduction.as_ref()),
                settings,
                k,
                k_name,
            )?;
            if let Some((fraction, why)) = &start.approached {
                let coef = etat.req_real("COEF_AMPL")?;
                ctx.alarm(
                    "MODE_NON_LINE_11",
                    &start::approached_alarm(coef, *fraction, why),
                )?;
            }
            start
        }
    };
    Ok(start)
}

/// The continuation, its progress, its live view and its report of each branch; stops at the
/// first branch past a bound of RESOLUTION (ENER_MAX, FREQ_MAX, DEPL_MAX).
fn follow(
    ctx: &mut OpContext<'_>,
    name: &str,
    call: &Call,
    control: nnm::StepControl,
    start: StartState,
) -> Result<nnm::Outcome> {
    let (problem, settings, bounds) = (&call.problem, &call.settings, &call.bounds);

    let info = ctx.info;
    let mut lines = Vec::new();
    let progress = Progress::new(
        ctx.progress,
        settings.continuation.n_branches as u64,
        "MODE_NON_LINE",
        "branches",
    );
    let mut stopped_by: Option<String> = None;
    let mut bound_error: Option<Error> = None;
    // The rows of each branch, readable in a live file while the operator runs.
    let mut live = crate::ops::common::live::LiveView::start(ctx, name)?;
    let outcome = nnm::continue_controlled(problem, settings, control, start, &mut |rep, pts| {
        progress.inc();
        live.branch(rep.branch, pts);
        if info >= 1 {
            lines.push(format!(
                "  branch {:>4}: {:>3} pts  freq {:.6e} .. {:.6e} Hz  energy {:.6e} .. {:.6e}  a_max {:.3e}  newton {:>2}  bifurcation {}{}{}",
                rep.branch,
                rep.points,
                rep.freq_range.0,
                rep.freq_range.1,
                rep.energy_range.0,
                rep.energy_range.1,
                rep.a_max,
                rep.newton_iterations,
                if rep.bifurcation { "yes" } else { "no" },
                if rep.step_retries > 0 {
                    format!("  step halved {} time(s) (a failed correction, a law check or a jump off the family)", rep.step_retries)
                } else {
                    String::new()
                },
                if rep.at_floor { "  residual accepted at its round-off floor" } else { "" }
            ));
        }
        match bounds.passed(problem, settings, pts) {
            Ok(Some(why)) => {
                stopped_by = Some(format!("branch {}: {why}", rep.branch));
                false
            }
            Ok(None) => true,
            Err(e) => {
                bound_error = Some(e);
                false
            }
        }
    });
    progress.finish();
    live.finish(ctx, outcome.error.is_none() && bound_error.is_none())?;
    if let Some(e) = bound_error {
        return Err(e);
    }
    ctx.say(&format!(
        "MODE_NON_LINE {name}: {} point(s)",
        outcome.points.len()
    ))?;
    for l in &lines {
        ctx.say(l)?;
    }
    if let Some(why) = &stopped_by {
        ctx.say(&format!(
            "MODE_NON_LINE {name}: stopped at the bound asked for in RESOLUTION: {why}"
        ))?;
    }
    Ok(outcome)
}

/// The rows of the run stored in the result table (`first_order` on), with their Fourier
/// coefficients and unknowns; what the row alarms need is returned.
#[allow(clippy::too_many_arguments)]
fn store_rows(
    ctx: &mut OpContext<'_>,
    name: &str,
    call: &Call,
    post: &nnm::PostProcessor,
    points: &[nnm::Point],
    mut table: Table,
    first_order: i64,
    reprise: i64,
    clearance: bool,
) -> Result<RowChecks> {
    let Call {
        k_name,
        m_name,
        cara_choc,
        k,
        free,
        settings,
        exact_settings,
        stored_shocks,
        problem,
        reduction,
        ..
    } = call;

    // RESOLUTION/CORR_LOI_EXACTE: the extra column, added to a reused table that lacks
    // it; a reused table that has it gets empty cells from a call without the correction.
    let exact_cells = match &exact_settings {
        Some(x) => {
            if table.col(exact_law::COLUMN).is_none() {
                table.add_column(exact_law::COLUMN, ColKind::R)?;
            }
            exact_law::cells(ctx, problem, x, points, first_order)?
        }
        None => Vec::new(),
    };
    let exact_col = table.col(exact_law::COLUMN);
    if ctx.reuse.is_none() {
        ctx.create(name, "table_container")?;
        // The table names K and M and rebuilds the problem from them when it is used
        // again: it belongs to these K and M (checked at every use, store::deps).
        ctx.store.record_dependency(name, k_name)?;
        ctx.store.record_dependency(name, m_name)?;
        ctx.create(cara_choc, "table_sdaster")?;
        table_store::save_table(ctx.store, cara_choc, &cara_choc_table(stored_shocks)?)?;
        mnl_store::save_setup(
            ctx.store,
            name,
            &MnlSetup {
                h_lin: settings.harmonics.h_lin,
                h_nonl: settings.harmonics.h_nonl,
                matr_rigi: k_name.clone(),
                matr_mass: m_name.clone(),
                shocks: stored_shocks.clone(),
                cara_choc: cara_choc.clone(),
                reduction: reduction.as_ref().map(|r| reduction::stored(&r.basis)),
            },
        )?;
        if let Some(r) = reduction {
            mnl_store::save_basis(ctx.store, name, &r.basis)?;
        }
    }
    let dof_names: Vec<(String, String)> = free
        .iter()
        .map(|&i| {
            let d = &k.numbering.dofs[i];
            (d.node.clone(), d.cmp.name().to_string())
        })
        .collect();
    let ncoef = 2 * settings.harmonics.h_lin as i64 + 1;
    let mut suspect: Vec<i64> = Vec::new();
    let mut worst_defect = 0.0f64;
    // Rows and how far their orbits reach into the obstacles, for the regularisation's
    // alarm (runs from a linear mode only: the floor knows its frequency).
    let mut clear_rows: Vec<nnm::ClearRow> = Vec::new();
    // The writer of the points (statements prepared once, Fourier rows batched).
    let mut writer = mnl_store::PointWriter::new(ctx.store, name)?;
    for (j, p) in points.iter().enumerate() {
        let order = first_order + j as i64;
        let out = post.row_with_defect(&p.x, p.law_defect)?;
        let defect = out.law_defect;
        // Judged relative to the force the law carries (as ECART_LOI_CHOC_MAXI): far into
        // a stop the force is many RIGI_NOR*JEU and so is a well-resolved defect.
        if out.law_defect_relative > nnm::LAW_DEFECT_ALARM {
            suspect.push(order);
        }
        worst_defect = worst_defect.max(out.law_defect_relative);
        // An alarm's input: a row it cannot read is left out, never an error.
        if clearance {
            if let Ok(Some(penetration)) = post.largest_penetration(&p.x) {
                clear_rows.push(nnm::ClearRow {
                    order,
                    energy: p.energy,
                    frequency: p.frequency,
                    penetration,
                });
            }
        }
        let mut cells = row(name, cara_choc, order, ncoef, reprise, p, defect);
        if let Some(i) = exact_col {
            cells.insert(i, exact_cells.get(j).cloned().unwrap_or(Cell::Null));
        }
        table.push_row(cells)?;
        writer.point(order, p.omega, &p.x)?;
        match reduction {
            // Every DOF's coefficients, expanded from the reduced coordinates'.
            Some(r) => {
                writer.fourier(order, &dof_names, &r.basis.expand_series(&out.displacement))?
            }
            None => writer.fourier(order, &dof_names, &out.displacement)?,
        }
    }
    writer.finish()?;
    table_store::save_table(ctx.store, name, &table)?;
    ctx.say(&format!(
        "  frequency against energy: SELECT NUME_ORDRE, ENERGIE, FREQUENCE FROM {name} ORDER BY NUME_ORDRE"
    ))?;
    Ok(RowChecks {
        suspect,
        worst_defect,
        clear_rows,
    })
}

/// What the stored rows tell the alarms: the rows whose law defect is suspect and the worst
/// one, and the rows with how far their orbits reach into the obstacles.
struct RowChecks {
    suspect: Vec<i64>,
    worst_defect: f64,
    clear_rows: Vec<nnm::ClearRow>,
}

/// The alarms on the stored rows: suspect law defects (MODE_NON_LINE_3), rows at the
/// round-off floor (5), the regularisation's shift clear of every obstacle (9), poorly
/// resolved force series (1) and internal resonances (7).
fn row_alarms(
    ctx: &mut OpContext<'_>,
    call: &Call,
    points: &[nnm::Point],
    first_order: i64,
    checks: &RowChecks,
    floor: Option<&nnm::FrequencyFloor>,
    linear_modes: Option<&[nnm::LinearMode]>,
) -> Result<()> {
    let (problem, settings) = (&call.problem, &call.settings);
    let RowChecks {
        suspect,
        worst_defect,
        clear_rows,
    } = checks;

    if let (Some(first), Some(last)) = (suspect.first(), suspect.last()) {
        ctx.alarm(
            "MODE_NON_LINE_3",
            &format!(
                "{} row(s) between NUME_ORDRE {first} and {last} satisfy their contact law in time only \
                 to {:.3e} x max(RIGI_NOR*JEU, largest contact force) (column ECART_LOI_CHOC, divided \
                 by that force in units of RIGI_NOR*JEU when it is larger): either the force series is too poorly \
                 resolved there (raise NB_HARM_NONL, and NB_HARM_LINE at high energy) or the branch has \
                 left the physical root of the regularised law; treat those rows as suspect",
                suspect.len(),
                worst_defect
            ),
        )?;
    }
    let floor_rows: Vec<i64> = points
        .iter()
        .enumerate()
        .filter(|(_, p)| p.at_floor)
        .map(|(j, _)| first_order + j as i64)
        .collect();
    if let (Some(first), Some(last)) = (floor_rows.first(), floor_rows.last()) {
        ctx.alarm(
            "MODE_NON_LINE_5",
            &format!(
                "{} row(s) between NUME_ORDRE {first} and {last} were accepted with RESIDU above \
                 PREC_NEWTON: the correction had stopped decreasing at the round-off level of the \
                 equations there (docs/nnm.md, `Point::residual`); that level \
                 grows with the amplitude far up a branch (the quadratic law terms) and with a \
                 stiff regularised law: a larger PARA_REGUL or a smaller RIGI_NOR lowers it, or \
                 NB_BRANCHE can stop the branch lower",
                floor_rows.len()
            ),
        )?;
    }
    // Rows clear of every obstacle, off the linear frequency: the regularisation's shift
    // (nnm/analysis/below_contact.rs).
    if let Some(f) = &floor {
        if let Some(w) = nnm::regularisation_alarm(problem, f.linear(), clear_rows) {
            ctx.alarm("MODE_NON_LINE_9", &w)?;
        }
    }
    // The advice's estimate (a few small Newton solves) only when the alarm is shown.
    let advise = !ctx.ignored_alarms.iter().any(|a| a == "MODE_NON_LINE_1");
    let tails = nnm::resolution_warnings(problem, settings, points, first_order, advise);
    // Resolved force series say nothing of the displacement's truncation: the estimate
    // itself then decides (nnm/analysis/resolution.rs, ANNOUNCED_ERROR).
    let estimated = if tails.is_empty() && advise {
        nnm::accuracy_warning(problem, settings, points, first_order)
    } else {
        None
    };
    for w in tails.iter().chain(&estimated) {
        ctx.alarm("MODE_NON_LINE_1", w)?;
    }
    // A reduction basis whose cut-off is below the harmonics the rows carry.
    if let Some(r) = &call.reduction {
        let rows: Vec<(i64, f64)> = points
            .iter()
            .enumerate()
            .map(|(j, p)| (first_order + j as i64, p.frequency))
            .collect();
        if let Some(w) = reduction::cut_off_alarm(&r.basis, settings.harmonics.h_lin, &rows) {
            ctx.alarm("MODE_NON_LINE_10", &w)?;
        }
    }
    // Internal resonances n:1 with a linear mode (nnm/analysis/resonance.rs).
    if let Some(w) = nnm::resonance_alarm(
        problem,
        &settings.harmonics,
        points,
        first_order,
        linear_modes,
    )? {
        ctx.alarm("MODE_NON_LINE_7", &w)?;
    }
    Ok(())
}

/// A restart goes on (DIR_EVOLUTION = −1) or back (+1) relative to the direction the
/// stored branch was travelling at the start row (restart.rs); said at INFO ≥ 1.
fn restart_direction(
    ctx: &mut OpContext<'_>,
    src: &str,
    order: i64,
    direction: i32,
    start_state: StartState,
) -> Result<StartState> {
    let t = table_store::load_table(ctx.store, src)?;
    let way = if direction < 0 {
        "on in"
    } else {
        "back against"
    };
    match restart::travel_at_row(ctx.store, &t, src, order)? {
        Some(tr) => {
            if ctx.info >= 1 {
                ctx.say(&format!(
                    "  restart from {src} row {order}: DIR_EVOLUTION={direction} goes {way} the direction \
                     the stored branch travelled there (rows {} -> {})",
                    tr.from, tr.to
                ))?;
            }
            Ok(start_state.travelling(tr.direction)?)
        }
        None => {
            ctx.alarm(
                "MODE_NON_LINE_4",
                &format!(
                    "row {order} of {src} is the only stored row of its run: the direction the branch \
                     travelled there is unknown, so DIR_EVOLUTION={direction} goes toward {} \
                     amplitude, as from a linear mode",
                    if direction < 0 { "increasing" } else { "decreasing" }
                ),
            )?;
            Ok(start_state)
        }
    }
}
