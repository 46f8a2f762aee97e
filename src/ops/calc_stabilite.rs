//! CALC_STABILITE: stability of the rows of a MODE_NON_LINE table from the Floquet
//! multipliers of their periodic solutions (monodromy over one period of the regularised
//! system). Fills STABILITE ('STABLE'/'INSTABLE', or 'INDETERMINE' where a nontrivial
//! multiplier is within the accuracy band of the unit circle: `nnm::stability`) on the
//! filtered rows and stores every multiplier in the SQL table `mnl_floquet`.

use crate::args::Args;
use crate::error::{Error, Result};
use crate::nnm::stability::{FloquetAnalyser, Integrator, Verdict};
use crate::ops::mode_non_line::problem::{engine_problem, row_of};
use crate::ops::{common::progress::Progress, OpContext};
use crate::store::{matrix, mnl as mnl_store, table as table_store};
use crate::table::print::format_e;
use crate::table::{Cell, Table};

/// TOLERANCE and SCHEMA_TEMPS (SCHEMA, NB_INST): the Floquet analysis's settings, read the
/// same way by CALC_STABILITE and REPONSE_FORCEE_NL (defaults are each catalog's, filled by
/// the validation).
pub fn floquet_settings(args: &Args) -> Result<(f64, Integrator, usize)> {
    let tolerance = args.req_real("TOLERANCE")?;
    let schema = args.req_fact("SCHEMA_TEMPS")?;
    let integrator = match schema.req_text("SCHEMA")? {
        "RUNGE_KUTTA_4" => Integrator::Rk4,
        _ => Integrator::Newmark,
    };
    Ok((tolerance, integrator, schema.req_count("NB_INST")?))
}

pub fn run(ctx: &mut OpContext<'_>, args: &Args) -> Result<()> {
    let src = args.req_concept("MODE_NON_LINE")?.name.clone();
    let name = match (ctx.reuse, ctx.result) {
        (Some(r), _) | (None, Some(r)) => r.to_string(),
        (None, None) => ctx.result_name()?.to_string(),
    };
    let mut table = table_store::load_table(ctx.store, &src)?;
    let setup = mnl_store::load_setup(ctx.store, &src)?;
    let k = matrix::load_matrix(ctx.store, &setup.matr_rigi)?;
    let m = matrix::load_matrix(ctx.store, &setup.matr_mass)?;
    // A reduced run's stability is that of the reduced model its rows solve.
    let run = engine_problem(ctx.store, &src, &setup, &k, &m)?;
    let (problem, harmonics) = (&run.problem, run.harmonics);
    let (tolerance, integrator, n_inst) = floquet_settings(args)?;
    let rows = selected_rows(&table, args.req_fact("FILTRE")?)?;
    if rows.is_empty() {
        return Err(Error::validation("FILTRE selects no row of the table")
            .keyword("CALC_STABILITE/FILTRE")
            .hint("check NUME_ORDRE, or widen FREQ_MIN/FREQ_MAX"));
    }
    if ctx.reuse.is_none() && name != src {
        ctx.create(&name, "table_container")?;
        mnl_store::copy_data(ctx.store, &src, &name)?;
        ctx.store.copy_dependencies(&src, &name)?;
    }
    let stab_col = table.req_col("STABILITE")?;
    let order_col = table.req_col("NUME_ORDRE")?;
    // Built once: what every row's analysis shares (layout, dense K and M, laws).
    let n = problem.k.nrows();
    crate::ops::common::resources::check_memory(
        "CALC_STABILITE/SCHEMA_TEMPS/NB_INST",
        &format!("the monodromy matrix of {n} DOF(s)"),
        crate::nnm::budget::floquet_bytes(n),
    )?;
    crate::ops::common::resources::warn_long_work(
        ctx,
        "CALC_STABILITE/SCHEMA_TEMPS/NB_INST",
        &format!(
            "{n_inst} steps per period for each of {} row(s)",
            rows.len()
        ),
        crate::nnm::budget::floquet_flops(n, n_inst) * rows.len() as f64,
    )?;
    let analyser = FloquetAnalyser::new(problem, harmonics)?;
    let progress = Progress::new(ctx.progress, rows.len() as u64, "CALC_STABILITE", "rows");
    let (mut stable, mut unstable, mut undecided) = (0usize, 0usize, 0usize);
    // Rows whose monodromy does not map the orbit's own tangent onto itself within
    // TOLERANCE (orbit defect): their verdict cannot be trusted to TOLERANCE.
    let mut unreliable: Vec<(i64, f64)> = Vec::new();
    for r in rows {
        let order = match table.rows[r].get(order_col) {
            Some(Cell::I(i)) => *i,
            _ => continue,
        };
        let x = mnl_store::load_point(ctx.store, &src, order)?
            .ok_or_else(|| Error::store(format!("{src}: row {order} has no stored point")))?;
        let f = analyser
            .floquet(&x, n_inst, integrator, tolerance)
            .map_err(|e| {
                Error::from(e).keyword(format!("CALC_STABILITE (row NUME_ORDRE={order})"))
            })?;
        mnl_store::save_multipliers(ctx.store, &name, order, &f.multipliers)?;
        let verdict = f.label();
        match f.verdict {
            Verdict::Stable => stable += 1,
            Verdict::Unstable => unstable += 1,
            Verdict::Indeterminate => undecided += 1,
        }
        table.rows[r][stab_col] = Cell::K(verdict.to_string());
        // A NaN defect counts as unreliable too.
        if f.orbit_defect.is_nan() || f.orbit_defect > tolerance {
            unreliable.push((order, f.orbit_defect));
        }
        if ctx.info >= 2 {
            ctx.say(&format!(
                "  NUME_ORDRE {order:>5}: {verdict:<11} max |mu| (trivial pair excluded) {}  trivial pair at {} from +1  orbit defect {}  band {}",
                format_e(f.max_nontrivial_modulus, 6),
                format_e(f.trivial_distance, 2),
                format_e(f.orbit_defect, 2),
                format_e(f.band, 2)
            ))?;
        }
        progress.inc();
    }
    progress.finish();
    table_store::save_table(ctx.store, &name, &table)?;
    if !unreliable.is_empty() {
        ctx.alarm(
            "CALC_STABILITE_1",
            &unreliable_message(&unreliable, tolerance),
        )?;
    }
    ctx.say(&format!(
        "CALC_STABILITE {name}: {stable} STABLE, {unstable} INSTABLE{} (TOLERANCE={tolerance:e}); multipliers: SELECT * FROM mnl_floquet WHERE concept='{name}'",
        if undecided > 0 {
            format!(", {undecided} INDETERMINE")
        } else {
            String::new()
        }
    ))
}

/// The alarm for rows whose orbit defect ‖Φ(T)ẏ(0) − ẏ(0)‖/‖ẏ(0)‖ exceeds TOLERANCE. On a
/// well-resolved orbit it is the integrator's error (≤ 5e-3 with NEWMARK, NB_INST = 1000 on
/// the test cases); it reaches O(1) when NB_HARM_LINE is too low for the contact stiffness,
/// and the multipliers are then wrong by as much.
fn unreliable_message(rows: &[(i64, f64)], tolerance: f64) -> String {
    let worst = rows.iter().map(|r| r.1).fold(0.0, f64::max);
    let listed: Vec<String> = rows.iter().take(10).map(|r| r.0.to_string()).collect();
    let more = if rows.len() > 10 { ", ..." } else { "" };
    format!(
        "{} row(s) (NUME_ORDRE {}{more}): the monodromy matrix maps the orbit's own velocity \
         direction onto itself only to {} (> TOLERANCE = {tolerance:e}), so their multipliers \
         are known only to about that much: a row is STABLE only when its orbit is accurate to \
         TOLERANCE, INSTABLE when a multiplier lies beyond that band, INDETERMINE otherwise. \
         Raise SCHEMA_TEMPS/NB_INST (integration error) or compute the branch with a larger \
         NB_HARM_LINE (orbit not resolved in time); the multipliers are in mnl_floquet.",
        rows.len(),
        listed.join(", "),
        format_e(worst, 2)
    )
}

/// Rows chosen by FILTRE: NUME_ORDRE list, or a band FREQ_MIN..FREQ_MAX widened by
/// PRECISION (relative).
fn selected_rows(t: &Table, filtre: &Args) -> Result<Vec<usize>> {
    if let Some(orders) = filtre.ints("NUME_ORDRE") {
        return orders
            .iter()
            .map(|&o| {
                row_of(t, o).ok_or_else(|| {
                    Error::validation(format!("the table has no row NUME_ORDRE={o}"))
                        .keyword("CALC_STABILITE/FILTRE/NUME_ORDRE")
                })
            })
            .collect();
    }
    let (lo, hi) = (filtre.req_real("FREQ_MIN")?, filtre.req_real("FREQ_MAX")?);
    let prec = filtre.req_real("PRECISION")?;
    let (lo, hi) = (lo * (1.0 - prec), hi * (1.0 + prec));
    Ok((0..t.nrows())
        .filter(|&r| {
            t.cell(r, "FREQUENCE")
                .and_then(Cell::as_f64)
                .is_some_and(|f| f >= lo && f <= hi)
        })
        .collect())
}
