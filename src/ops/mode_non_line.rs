//! MODE_NON_LINE: branches of nonlinear normal modes with shocks (EHMAN).
//!
//! Glue only: reads the matrices, the start (a linear mode or a row of an earlier
//! MODE_NON_LINE table), the shocks and the settings, runs `nnm`, and stores the result
//! table (a real SQL table), the CARA_CHOC sub-table, every point's unknowns and the
//! displacement Fourier coefficients.

use crate::args::Args;
use crate::error::{Error, ErrorKind, Result};
use crate::nnm::{self, Point, Problem, Settings, StartState};
use crate::ops::common::mnl_end;
use crate::ops::common::mnl_exact_law;
use crate::ops::common::mnl_problem::{
    engine_shock, row_of, shocks_from_cara_choc, CARA_CHOC_COLUMNS,
};
use crate::ops::common::mnl_restart;
use crate::ops::common::mnl_start;
use crate::ops::common::nodes::{one_node_of_group, OneNode};
use crate::ops::{common::progress::Progress, OpContext};
use crate::store::mnl::{self as mnl_store, MnlSetup, StoredShock};
use crate::store::{matrix, table as table_store};
use crate::table::{Cell, ColKind, Table};

/// Columns of the result table: Code_Aster's, then ours (accuracy indicators).
const COLUMNS: &[(&str, ColKind)] = &[
    ("NUME_ORDRE", ColKind::I),
    ("FREQUENCE", ColKind::R),
    ("ENERGIE", ColKind::R),
    ("NB_COEF_FOURIER", ColKind::I),
    ("NOM_SD", ColKind::K),
    ("TYPE_OBJET", ColKind::K),
    ("NOM_OBJET", ColKind::K),
    ("CARA_CHOC", ColKind::K),
    ("HARM_MAX", ColKind::I),
    ("BIFURCATION", ColKind::K),
    ("STABILITE", ColKind::K),
    ("NUME_REPRISE", ColKind::I),
    // Beyond Code_Aster (docs/mode_non_line.md): residual norm after correction, |γ| (the
    // unfolding parameter, zero on an exact solution) and the relative spread of the total
    // energy over one period sampled in time.
    ("RESIDU", ColKind::R),
    ("AMOR_FICTIF", ColKind::R),
    ("ECART_ENERGIE", ColKind::R),
    // The contact laws checked in time: max |f_series − f_law(u)| / (RIGI_NOR·JEU); O(1)
    // when the branch has drifted onto a non-physical root of an implicit law.
    ("ECART_LOI_CHOC", ColKind::R),
    ("BRANCHE", ColKind::I),
    // Retries of the row's branch with a halved series step before its correction
    // converged (on the branch's corrected end row).
    ("NB_REPRISE_PAS", ColKind::I),
    // ENERGIE's formula averaged over the period instead of taken at one instant: closer
    // to the orbit's energy on a truncated harmonic balance (docs/mode_non_line.md).
    ("ENERGIE_MOYENNE", ColKind::R),
];

pub fn run(ctx: &mut OpContext<'_>, args: &Args) -> Result<()> {
    let name = match (ctx.reuse, ctx.result) {
        (Some(r), _) => r.to_string(),
        (None, Some(r)) => r.to_string(),
        (None, None) => ctx.result_name()?.to_string(),
    };
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
    if k.numbering.dofs != m.numbering.dofs || k.eliminated != m.eliminated {
        return Err(Error::input(format!(
            "{k_name} and {m_name} are not assembled on the same DOF numbering and boundary conditions"
        ))
        .keyword("MODE_NON_LINE/MATR_MASS"));
    }
    let free = k.free_dofs();
    let settings = settings(args)?;
    let exact_law = mnl_exact_law::settings(args, &settings)?;
    let mut control = step_control(args)?;
    let bounds = stop_bounds(args)?;
    let etat = args.req_fact("ETAT_INIT")?;

    // Shocks: from CHOC on a first run, from the stored CARA_CHOC on a restart.
    let restart_from = etat.concept("MODE_NON_LINE").map(|c| c.name.clone());
    let stored_shocks = match &restart_from {
        Some(src) => {
            if args.has("CHOC") {
                ctx.alarm(
                    "MODE_NON_LINE_2",
                    "CHOC is ignored on a restart: the shocks come from the CARA_CHOC of the start table",
                )?;
            }
            let setup = mnl_store::load_setup(ctx.store, src)?;
            check_restart_harmonics(&setup, &settings)?;
            // The contact data of the start row, as Code_Aster reads them: from the
            // sub-table named in its CARA_CHOC cell.
            let t = table_store::load_table(ctx.store, src)?;
            let order = etat.req_int("NUME_ORDRE")?;
            let sub = row_of(&t, order)
                .and_then(|r| t.cell(r, "CARA_CHOC"))
                .and_then(Cell::as_text)
                .map(str::to_string)
                .unwrap_or(setup.cara_choc);
            shocks_from_cara_choc(&table_store::load_table(ctx.store, &sub)?, &sub)?
        }
        None => shocks_from_args(ctx, args)?,
    };
    if ctx.info >= 1 {
        for line in orig_obst_notes(&stored_shocks) {
            ctx.say(&line)?;
        }
    }
    let shocks = stored_shocks
        .iter()
        .enumerate()
        .map(|(i, s)| engine_shock(s, i, &k))
        .collect::<Result<Vec<_>>>()?;
    let problem = Problem {
        k: k.reduced()?,
        m: m.reduced()?,
        shocks,
    };

    if let Some(x) = &exact_law {
        mnl_exact_law::check(&problem, x)?;
    }
    check_budget(ctx, &problem, &settings, &stored_shocks)?;

    // Start point.
    let nume_ordre = etat.req_int("NUME_ORDRE")?;
    let start: StartState = match &restart_from {
        Some(src) => {
            let x = mnl_store::load_point(ctx.store, src, nume_ordre)?.ok_or_else(|| {
                Error::input(format!("{src} has no row NUME_ORDRE={nume_ordre}"))
                    .keyword("MODE_NON_LINE/ETAT_INIT/NUME_ORDRE")
            })?;
            // A stored point that does not fit these settings is the start row's fault.
            let start_state = nnm::start_from_point(&problem, &settings, &x).map_err(|e| {
                if e.kind == ErrorKind::Input {
                    e.keyword("ETAT_INIT/NUME_ORDRE")
                } else {
                    e
                }
            })?;
            restart_direction(ctx, src, nume_ordre, settings.direction, start_state)?
        }
        None => mnl_start::from_linear_modes(ctx, etat, &problem, &settings, &k, &k_name)?,
    };

    // The linear modes (dense, small models only): the frequency floor of a family that
    // starts from a linear mode, and the internal-resonance alarm after the run.
    let linear_modes = nnm::linear_modes(&problem)?;
    if restart_from.is_none() {
        control.frequency_floor = nnm::FrequencyFloor::new(
            &problem,
            linear_modes.as_deref(),
            start.point.frequency,
            settings.h_lin,
            args.req_fact("RESOLUTION")?.req_real("BAISSE_FREQ_MAXI")?,
        );
    }
    // The rows kept after a wrong-branch end are judged by the same checks.
    let floor = control.frequency_floor.clone();
    let work_min = control.work_min.unwrap_or(f64::NEG_INFINITY);
    let gamma_max = control.gamma_max;

    // Continue, reporting each branch.
    let info = ctx.info;
    let mut lines = Vec::new();
    let progress = Progress::new(
        ctx.progress,
        settings.n_branches as u64,
        "MODE_NON_LINE",
        "branches",
    );
    let mut stopped_by: Option<String> = None;
    let mut bound_error: Option<Error> = None;
    // The rows of each branch, readable in a live file while the operator runs.
    let mut live = crate::ops::common::live::LiveView::start(ctx, &name)?;
    let outcome = nnm::continue_controlled(&problem, &settings, control, start, &mut |rep, pts| {
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
        match bounds.passed(&problem, &settings, pts) {
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

    // The result table: a new one, or the reused one extended.
    let (mut table, first_order, reprise) = match ctx.reuse {
        Some(r) => {
            let t = table_store::load_table(ctx.store, r)?;
            let last = max_int(&t, "NUME_ORDRE");
            let rep = max_int(&t, "NUME_REPRISE") + 1;
            (t, last + 1, rep)
        }
        None => (
            new_table(),
            1,
            i64::from(restart_from.is_some()) + restart_reprise(ctx, &restart_from)?,
        ),
    };
    // Built once: what every row's outputs share (layout, physical laws, FFT plan).
    let post = nnm::PostProcessor::new(&problem, &settings)?;
    // A branch that left the physical root of its law: its trailing suspect rows are not
    // stored (mnl_end::rows_kept; their defects computed only then, the rows' outputs are
    // not kept in memory); every other run stores every row.
    let kept = if mnl_end::cuts_rows(outcome.error.as_ref()) {
        let motions = outcome
            .points
            .iter()
            .map(|p| {
                let off_the_family = floor
                    .as_ref()
                    .is_some_and(|f| f.off_the_family(p.frequency, p.energy).is_some());
                let damped = gamma_max.is_some_and(|max| {
                    let ratio = nnm::relative_gamma(p);
                    ratio.is_nan() || ratio > max
                });
                Ok(!off_the_family && !damped && post.is_motion(&p.x, p.law_defect, work_min)?)
            })
            .collect::<Result<Vec<bool>>>()?;
        mnl_end::rows_kept(outcome.error.as_ref(), &motions)
    } else {
        outcome.points.len()
    };
    let points = &outcome.points[..kept];
    // RESOLUTION/CORR_LOI_EXACTE: the extra column, added to a reused table that lacks
    // it; a reused table that has it gets empty cells from a call without the correction.
    let exact_cells = match &exact_law {
        Some(x) => {
            if table.col(mnl_exact_law::COLUMN).is_none() {
                table.add_column(mnl_exact_law::COLUMN, ColKind::R)?;
            }
            mnl_exact_law::cells(ctx, &problem, x, points, first_order)?
        }
        None => Vec::new(),
    };
    let exact_col = table.col(mnl_exact_law::COLUMN);
    if ctx.reuse.is_none() {
        ctx.create(&name, "table_container")?;
        // The table names K and M and rebuilds the problem from them when it is used
        // again: it belongs to these K and M (checked at every use, store::deps).
        ctx.store.record_dependency(&name, &k_name)?;
        ctx.store.record_dependency(&name, &m_name)?;
        ctx.create(&cara_choc, "table_sdaster")?;
        table_store::save_table(ctx.store, &cara_choc, &cara_choc_table(&stored_shocks)?)?;
        mnl_store::save_setup(
            ctx.store,
            &name,
            &MnlSetup {
                h_lin: settings.h_lin,
                h_nonl: settings.h_nonl,
                matr_rigi: k_name.clone(),
                matr_mass: m_name.clone(),
                shocks: stored_shocks.clone(),
                cara_choc: cara_choc.clone(),
            },
        )?;
    }
    let dof_names: Vec<(String, String)> = free
        .iter()
        .map(|&i| {
            let d = &k.numbering.dofs[i];
            (d.node.clone(), d.cmp.name().to_string())
        })
        .collect();
    let ncoef = 2 * settings.h_lin as i64 + 1;
    let mut suspect: Vec<i64> = Vec::new();
    let mut worst_defect = 0.0f64;
    // Rows and how far their orbits reach into the obstacles, for the regularisation's
    // alarm (runs from a linear mode only: the floor knows its frequency).
    let mut clear_rows: Vec<nnm::ClearRow> = Vec::new();
    // The writer of the points (statements prepared once, Fourier rows batched).
    let mut writer = mnl_store::PointWriter::new(ctx.store, &name)?;
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
        if floor.is_some() {
            if let Ok(Some(penetration)) = post.largest_penetration(&p.x) {
                clear_rows.push(nnm::ClearRow {
                    order,
                    energy: p.energy,
                    frequency: p.frequency,
                    penetration,
                });
            }
        }
        let mut cells = row(&name, &cara_choc, order, ncoef, reprise, p, defect);
        if let Some(i) = exact_col {
            cells.insert(i, exact_cells.get(j).cloned().unwrap_or(Cell::Null));
        }
        table.push_row(cells)?;
        writer.point(order, p.omega, &p.x)?;
        writer.fourier(order, &dof_names, &out.displacement)?;
    }
    writer.finish()?;
    table_store::save_table(ctx.store, &name, &table)?;
    ctx.say(&format!(
        "  frequency against energy: SELECT NUME_ORDRE, ENERGIE, FREQUENCE FROM {name} ORDER BY NUME_ORDRE"
    ))?;
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
    // (nnm/below_contact.rs).
    if let Some(f) = &floor {
        if let Some(w) = nnm::regularisation_alarm(&problem, f.linear(), &clear_rows) {
            ctx.alarm("MODE_NON_LINE_9", &w)?;
        }
    }
    // The advice's estimate (a few small Newton solves) only when the alarm is shown.
    let advise = !ctx.ignored_alarms.iter().any(|a| a == "MODE_NON_LINE_1");
    for w in nnm::resolution_warnings(&problem, &settings, points, first_order, advise) {
        ctx.alarm("MODE_NON_LINE_1", &w)?;
    }
    // Internal resonances n:1 with a linear mode (nnm/resonance.rs).
    if let Some(w) = nnm::resonance_alarm(
        &problem,
        &settings,
        points,
        first_order,
        linear_modes.as_deref(),
    )? {
        ctx.alarm("MODE_NON_LINE_7", &w)?;
    }
    mnl_end::report(
        ctx,
        outcome.error,
        outcome.limit.as_deref(),
        points,
        outcome.points.len() - kept,
        settings.n_branches,
        first_order,
    )?;
    Ok(())
}

/// A restart goes on (DIR_EVOLUTION = −1) or back (+1) relative to the direction the
/// stored branch was travelling at the start row (mnl_restart.rs); said at INFO ≥ 1.
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
    match mnl_restart::travel_at_row(ctx.store, &t, src, order)? {
        Some(tr) => {
            if ctx.info >= 1 {
                ctx.say(&format!(
                    "  restart from {src} row {order}: DIR_EVOLUTION={direction} goes {way} the direction \
                     the stored branch travelled there (rows {} -> {})",
                    tr.from, tr.to
                ))?;
            }
            start_state.travelling(tr.direction)
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

/// One INFO line per CERCLE shock with a non-zero ORIG_OBST: aster-nl takes it in metres
/// (what the keyword means, and what Code_Aster's own energy routine assumes), while
/// Code_Aster's MODE_NON_LINE equations take it unscaled in units of the largest JEU, i.e.
/// put the ring centre at ORIG_OBST·JEU_max (docs/mode_non_line.md, "ORIG_OBST").
fn orig_obst_notes(shocks: &[StoredShock]) -> Vec<String> {
    let g = shocks.iter().map(|s| s.gap).fold(0.0f64, f64::max);
    // 12 significant digits: 3e-3 × 1e-2 prints as 3e-5, not 3.0000000000000004e-5.
    let num = |c: f64| match format!("{c:.11e}").parse::<f64>() {
        Ok(0.0) => "0".to_string(),
        Ok(r) => format!("{r:e}"),
        Err(_) => format!("{c:e}"),
    };
    let fmt = |v: [f64; 3]| format!("({}, {}, {})", num(v[0]), num(v[1]), num(v[2]));
    shocks
        .iter()
        .enumerate()
        .filter(|(_, s)| s.obstacle == "CERCLE" && s.origin.iter().any(|&c| c != 0.0))
        .map(|(i, s)| {
            let ca = s.origin.map(|c| c * g);
            format!(
                "  CHOC {}: ORIG_OBST={} is the ring centre in metres; Code_Aster would have put \
                 it at ORIG_OBST x JEU = {} m (it takes ORIG_OBST in units of the largest JEU, {:e} m); \
                 to reproduce a Code_Aster result give ORIG_OBST={}",
                i + 1,
                fmt(s.origin),
                fmt(ca),
                g,
                fmt(ca)
            )
        })
        .collect()
}

/// Refuse a call that cannot fit in memory, warn about one that will take very long: from
/// the sizes alone, before the engine allocates anything.
fn check_budget(
    ctx: &mut OpContext<'_>,
    problem: &Problem,
    s: &Settings,
    shocks: &[StoredShock],
) -> Result<()> {
    use crate::nnm::budget;
    use crate::ops::common::resources;
    // Own unknowns and displacement components per law (laws.rs).
    let shocks = shocks
        .iter()
        .map(|c| budget::ShockSizes {
            unknowns: match c.obstacle.as_str() {
                "CERCLE" => 4,
                "BI_PLAN" => 2,
                _ => 1,
            },
            components: c.cmps.len().max(1),
        })
        .collect::<Vec<_>>();
    let sizes = budget::MnlSizes {
        n_dofs: problem.k.nrows(),
        nnz: problem.k.compute_nnz() + problem.m.compute_nnz(),
        h_lin: s.h_lin,
        h_nonl: if shocks.is_empty() { s.h_lin } else { s.h_nonl },
        shocks,
        order: s.order,
        stored_points: s.n_branches as f64 * s.n_points_per_branch as f64,
    };
    resources::check_memory(
        "MODE_NON_LINE/RESOLUTION (NB_HARM_LINE, NB_HARM_NONL, NB_ORDRE_MAN, NB_BRANCHE, NB_PAS_MAN)",
        "the harmonic-balance continuation",
        budget::memory_estimate(&sizes),
    )?;
    resources::warn_long_work(
        ctx,
        "MODE_NON_LINE/RESOLUTION",
        "the continuation",
        budget::mnl_branch_flops(&sizes) * s.n_branches as f64,
    )
}

fn settings(args: &Args) -> Result<Settings> {
    let r = args.req_fact("RESOLUTION")?;
    // The bounds (at least 1, NB_ORDRE_MAN at least 2) are the catalog's.
    let usize_of = |key: &str| r.req_count(key);
    let h_lin = usize_of("NB_HARM_LINE")?;
    let h_nonl = usize_of("NB_HARM_NONL")?;
    if h_nonl < h_lin {
        return Err(Error::validation(format!(
            "NB_HARM_NONL ({h_nonl}) must be at least NB_HARM_LINE ({h_lin})"
        ))
        .keyword("MODE_NON_LINE/RESOLUTION/NB_HARM_NONL")
        .hint("the contact forces need at least as many harmonics as the displacements"));
    }
    let direction = args.req_fact("ETAT_INIT")?.req_int("DIR_EVOLUTION")?;
    Ok(Settings {
        h_lin,
        h_nonl,
        n_branches: usize_of("NB_BRANCHE")?,
        n_points_per_branch: usize_of("NB_PAS_MAN")?,
        order: usize_of("NB_ORDRE_MAN")?,
        prec_man: r.req_real("PREC_MAN")?,
        prec_newton: r.req_real("PREC_NEWTON")?,
        iter_newton_max: usize_of("ITER_NEWTON_MAXI")?,
        bif_terms: usize_of("CRIT_ORDR_BIFURCATION")?,
        bif_tol: r.req_real("RESI_RELA_BIFURCATION")?,
        det_test: r.req_text("TEST_BIFURCATION")? != "SERIE",
        direction: if direction >= 0 { 1 } else { -1 },
    })
}

/// RESOLUTION/NB_REPRISE_PAS_MAXI, NB_BRANCHE_SANS_PROGRES, ECART_LOI_CHOC_MAXI, SAUT_RACINE_MAXI,
/// RAPPORT_CORRECTION_MAXI, TRAVAIL_CHOC_MINI, AMOR_FICTIF_MAXI (BAISSE_FREQ_MAXI once the
/// start is known),
/// ECART_ENERGIE_MAXI and APPROX_MAN (aster-nl extensions; default and bounds in the
/// catalog).
fn step_control(args: &Args) -> Result<nnm::StepControl> {
    let r = args.req_fact("RESOLUTION")?;
    Ok(nnm::StepControl {
        retries_max: r.req_count("NB_REPRISE_PAS_MAXI")?,
        stall_branches: r.req_count("NB_BRANCHE_SANS_PROGRES")?,
        law_defect_max: Some(r.req_real("ECART_LOI_CHOC_MAXI")?),
        root_jump_max: Some(r.req_real("SAUT_RACINE_MAXI")?).filter(|&v| v > 0.0),
        correction_ratio_max: Some(r.req_real("RAPPORT_CORRECTION_MAXI")?).filter(|&v| v > 0.0),
        spread_max: r.real("ECART_ENERGIE_MAXI"),
        work_min: Some(r.req_real("TRAVAIL_CHOC_MINI")?),
        gamma_max: Some(r.req_real("AMOR_FICTIF_MAXI")?),
        // Set once the start is known (the mode the family starts from).
        frequency_floor: None,
        approximation: match r.req_text("APPROX_MAN")? {
            "PADE" => nnm::Approximation::Pade,
            _ => nnm::Approximation::Series,
        },
    })
}

/// RESOLUTION/ENER_MAX, FREQ_MAX, DEPL_MAX (aster-nl extensions): the run stops normally
/// after the first branch with a row past one of them.
struct StopBounds {
    energy: Option<f64>,
    frequency: Option<f64>,
    displacement: Option<f64>,
}

impl StopBounds {
    /// Which bound a row of `pts` has passed, said in words.
    fn passed(&self, problem: &Problem, s: &Settings, pts: &[Point]) -> Result<Option<String>> {
        for p in pts {
            if let Some(e) = self.energy.filter(|&e| p.energy >= e) {
                return Ok(Some(format!(
                    "ENERGIE = {:.6e} passed ENER_MAX = {e:.6e}",
                    p.energy
                )));
            }
            if let Some(f) = self.frequency.filter(|&f| p.frequency >= f) {
                return Ok(Some(format!(
                    "FREQUENCE = {:.6e} Hz passed FREQ_MAX = {f:.6e} Hz",
                    p.frequency
                )));
            }
            if let Some(d) = self.displacement {
                let u = nnm::largest_displacement(problem, s, &p.x)?;
                if u >= d {
                    return Ok(Some(format!(
                        "the largest displacement {u:.6e} passed DEPL_MAX = {d:.6e}"
                    )));
                }
            }
        }
        Ok(None)
    }
}

fn stop_bounds(args: &Args) -> Result<StopBounds> {
    let r = args.req_fact("RESOLUTION")?;
    Ok(StopBounds {
        energy: r.real("ENER_MAX"),
        frequency: r.real("FREQ_MAX"),
        displacement: r.real("DEPL_MAX"),
    })
}

fn check_restart_harmonics(setup: &MnlSetup, s: &Settings) -> Result<()> {
    if setup.h_lin != s.h_lin || setup.h_nonl != s.h_nonl {
        return Err(Error::validation(format!(
            "the start table was computed with NB_HARM_LINE={} and NB_HARM_NONL={}, this call asks for {} and {}",
            setup.h_lin, setup.h_nonl, s.h_lin, s.h_nonl
        ))
        .keyword("MODE_NON_LINE/RESOLUTION")
        .hint("a restart keeps the harmonics of the branch it continues"));
    }
    Ok(())
}

/// NUME_REPRISE of the start row's table, for a restart into a new concept.
fn restart_reprise(ctx: &OpContext<'_>, from: &Option<String>) -> Result<i64> {
    match from {
        None => Ok(0),
        Some(src) => {
            let t = table_store::load_table(ctx.store, src)?;
            Ok(max_int(&t, "NUME_REPRISE"))
        }
    }
}

fn shocks_from_args(ctx: &OpContext<'_>, args: &Args) -> Result<Vec<StoredShock>> {
    let mut out = Vec::new();
    for (i, c) in args.facts_or_empty("CHOC").iter().enumerate() {
        let kw = |k: &str| format!("MODE_NON_LINE/CHOC[{}]/{k}", i + 1);
        let obstacle = c.req_text("OBSTACLE")?.to_string();
        // One component (PLAN, BI_PLAN) or two (CERCLE): the catalog's bounds.
        let cmps = c.req_texts("NOM_CMP")?;
        // A ring lies in the plane of two different components: ('DX', 'DX') has no plane
        // (its tangent is singular, found only after a long failed start).
        if let [a, b] = cmps.as_slice() {
            if a == b {
                return Err(Error::validation(format!(
                    "NOM_CMP=('{a}', '{b}') names one component twice: OBSTACLE='{obstacle}' \
                     needs the two different components of the plane of its ring"
                ))
                .keyword(kw("NOM_CMP"))
                .hint("e.g. NOM_CMP=('DX', 'DY') for a ring in the XY plane"));
            }
        }
        let node = choc_node(ctx, args, c, &kw)?;
        // Finite and > 0: the catalog's bounds (val_min = 0, excluded).
        let positive = |key: &str| c.req_real(key);
        let gap = positive("JEU")?;
        let stiffness = positive("RIGI_NOR")?;
        let regul = positive("PARA_REGUL")?;
        // Three reals: the catalog's default and bounds (min = max = 3).
        let origin: [f64; 3] = c
            .req_reals("ORIG_OBST")?
            .try_into()
            .map_err(|o: Vec<f64>| {
                Error::internal(format!(
                    "ORIG_OBST has {} values: its catalog needs min = max = 3",
                    o.len()
                ))
                .keyword(kw("ORIG_OBST"))
            })?;
        // Text in the catalog's list (its `into`).
        let loi_cercle = c.req_text("LOI_CERCLE")?.to_string();
        // The same shock twice doubles its stiffness without a word: refuse it.
        if let Some(j) = out
            .iter()
            .position(|s: &StoredShock| s.node == node && s.cmps == cmps)
        {
            return Err(Error::validation(format!(
                "CHOC[{}] acts on the same node and components as CHOC[{}]",
                i + 1,
                j + 1
            ))
            .keyword(format!("MODE_NON_LINE/CHOC[{}]", i + 1))
            .hint("give each shock once; two obstacles on one DOF are one BI_PLAN"));
        }
        out.push(StoredShock {
            obstacle,
            node,
            cmps,
            gap,
            stiffness,
            regul,
            origin,
            loi_cercle,
        });
    }
    Ok(out)
}

/// The node of a CHOC: NOEUD, or a GROUP_NO holding exactly one node.
fn choc_node(
    ctx: &OpContext<'_>,
    args: &Args,
    c: &Args,
    kw: &dyn Fn(&str) -> String,
) -> Result<String> {
    if let Some(n) = c.text("NOEUD") {
        return Ok(n.to_string());
    }
    let group = c.req_text("GROUP_NO")?;
    let k_name = &args.req_concept("MATR_RIGI")?.name;
    let numbering = matrix::load_matrix(ctx.store, k_name)?.numbering;
    one_node_of_group(
        ctx.store,
        &numbering.mesh,
        group,
        OneNode {
            reason: "a shock acts on exactly one",
            hint: Some("give the node with NOEUD=, or a GROUP_NO of one node"),
        },
        kw("GROUP_NO"),
    )
}

fn new_table() -> Table {
    let mut t = Table::new("MODE_NON_LINE");
    for (name, kind) in COLUMNS {
        // Names are constants: add_column cannot fail on them.
        let _ = t.add_column(name, *kind);
    }
    t
}

fn row(
    name: &str,
    cara_choc: &str,
    order: i64,
    ncoef: i64,
    reprise: i64,
    p: &Point,
    law_defect: f64,
) -> Vec<Cell> {
    vec![
        Cell::I(order),
        Cell::R(p.frequency),
        Cell::R(p.energy),
        Cell::I(ncoef),
        Cell::K(format!("{name}.{order:04}")),
        Cell::K("MODE_MECA".into()),
        Cell::K(format!("FOURIER_{order:04}")),
        Cell::K(cara_choc.into()),
        Cell::I(p.harm_max as i64),
        Cell::K(if p.bifurcation { "OUI" } else { "NON" }.into()),
        Cell::K("NON_EVALUE".into()),
        Cell::I(reprise),
        Cell::R(p.residual),
        Cell::R(p.gamma.abs()),
        Cell::R(p.energy_spread),
        Cell::R(law_defect),
        Cell::I(p.branch as i64),
        Cell::I(p.step_retries as i64),
        Cell::R(p.energy_mean),
    ]
}

fn max_int(t: &Table, col: &str) -> i64 {
    t.column_cells(col)
        .map(|cells| {
            cells
                .iter()
                .filter_map(|c| match c {
                    Cell::I(i) => Some(*i),
                    _ => None,
                })
                .max()
                .unwrap_or(0)
        })
        .unwrap_or(0)
}

fn cara_choc_table(shocks: &[StoredShock]) -> Result<Table> {
    let mut t = Table::new("CARA_CHOC");
    for (n, k) in CARA_CHOC_COLUMNS {
        t.add_column(n, *k)?;
    }
    for (i, s) in shocks.iter().enumerate() {
        t.push_row(vec![
            Cell::I(i as i64 + 1),
            Cell::K(s.obstacle.clone()),
            Cell::K(s.node.clone()),
            Cell::K(s.cmps.first().cloned().unwrap_or_default()),
            s.cmps
                .get(1)
                .map(|c| Cell::K(c.clone()))
                .unwrap_or(Cell::Null),
            Cell::R(s.stiffness),
            Cell::R(s.regul),
            Cell::R(s.gap),
            Cell::R(s.origin[0]),
            Cell::R(s.origin[1]),
            Cell::R(s.origin[2]),
            Cell::K(s.loi_cercle.clone()),
        ])?;
    }
    Ok(t)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn shock(obstacle: &str, gap: f64, origin: [f64; 3]) -> StoredShock {
        StoredShock {
            obstacle: obstacle.into(),
            node: "N1".into(),
            cmps: vec!["DX".into(), "DY".into()],
            gap,
            stiffness: 50.0,
            regul: 1e-4,
            origin,
            loi_cercle: "RAYON".into(),
        }
    }

    /// A non-zero ORIG_OBST of a CERCLE is reported with the centre Code_Aster would have
    /// used: ORIG_OBST times the largest JEU (here 0.02, of the second shock).
    #[test]
    fn orig_obst_note_names_code_aster_centre() {
        let notes = orig_obst_notes(&[
            shock("CERCLE", 0.01, [0.0, 3e-3, 0.0]),
            shock("BI_PLAN", 0.02, [0.0; 3]),
            shock("CERCLE", 0.01, [0.0; 3]),
        ]);
        assert_eq!(notes.len(), 1, "{notes:?}");
        assert!(
            notes[0].starts_with("  CHOC 1: ORIG_OBST=(0, 3e-3, 0) is the ring centre in metres")
                && notes[0].contains("ORIG_OBST x JEU = (0, 6e-5, 0) m")
                && notes[0].contains("largest JEU, 2e-2 m"),
            "{}",
            notes[0]
        );
    }
}
