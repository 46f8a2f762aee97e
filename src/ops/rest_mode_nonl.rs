//! REST_MODE_NONL: one row of a MODE_NON_LINE table back in physical form: the time
//! history over one period (TYPE_RESU='DYNA_TRANS') or the Fourier coefficient fields
//! (TYPE_RESU='MODE_MECA').

use crate::args::Args;
use crate::error::{Error, ErrorKind, Result};
use crate::model::modes::{Mode, ModeMeca};
use crate::nnm;
use crate::ops::mode_non_line::problem::{engine_problem, row_of};
use crate::ops::OpContext;
use crate::store::{
    dyna_trans as dyna_store, matrix, mnl as mnl_store, modes as mode_store, table as table_store,
};
use crate::table::{Cell, ColKind, Table};

pub fn run(ctx: &mut OpContext<'_>, args: &Args) -> Result<()> {
    let name = ctx.result_name()?.to_string();
    let src = args.req_concept("MODE_NON_LINE")?.name.clone();
    let order = args.req_int("NUME_ORDRE")?;
    let setup = mnl_store::load_setup(ctx.store, &src)?;
    let x = mnl_store::load_point(ctx.store, &src, order)?.ok_or_else(|| {
        Error::input(format!("{src} has no row NUME_ORDRE={order}"))
            .keyword("REST_MODE_NONL/NUME_ORDRE")
    })?;
    let table = table_store::load_table(ctx.store, &src)?;
    let freq = row_of(&table, order)
        .and_then(|r| table.cell(r, "FREQUENCE").and_then(Cell::as_f64))
        .unwrap_or(0.0);
    let k = matrix::load_matrix(ctx.store, &setup.matr_rigi)?;
    let m = matrix::load_matrix(ctx.store, &setup.matr_mass)?;
    let run = engine_problem(ctx.store, &src, &setup, &k, &m)?;
    let (problem, harmonics, free) = (&run.problem, run.harmonics, &run.free);
    // Defaults are the catalog's (commands/REST_MODE_NONL.toml), filled by the validation.
    match args.req_text("TYPE_RESU")? {
        "MODE_MECA" => {
            let coefs = run.on_free_dofs(
                nnm::displacement_coefficients(problem, harmonics, &x).map_err(stored_point)?,
            );
            let ncoef = 2 * harmonics.h_lin + 1;
            let modes = (0..ncoef)
                .map(|j| {
                    // Coefficient j of every free DOF (each has 2 h_lin + 1; not a keyword
                    // default: a missing coefficient is a zero one).
                    let reduced: Vec<f64> = coefs
                        .iter()
                        .map(|c| c.get(j).copied().unwrap_or(0.0))
                        .collect();
                    Ok(Mode {
                        nume_ordre: j + 1,
                        freq,
                        omega2: (2.0 * std::f64::consts::PI * freq).powi(2),
                        mass_gene: 0.0,
                        rigi_gene: 0.0,
                        label: coef_label(j, harmonics.h_lin),
                        shape: k.expand(&reduced)?,
                    })
                })
                .collect::<Result<Vec<_>>>()?;
            let numbering_name = matrix::matrix_numbering_name(ctx.store, &setup.matr_rigi)?;
            ctx.create(&name, "mode_meca")?;
            mode_store::save_modes(
                ctx.store,
                &name,
                &ModeMeca {
                    numbering: k.numbering.clone(),
                    numbering_name,
                    modes,
                },
            )
        }
        _ => {
            // At least 2 (the catalog's bound).
            let n_inst = args.req_count("NB_INST")?;
            let n = free.len();
            let force_components: usize = setup.shocks.iter().map(|s| s.cmps.len().max(1)).sum();
            crate::ops::common::resources::check_memory(
                "REST_MODE_NONL/NB_INST",
                &format!("the time history of {n} DOF(s) at {n_inst} instants"),
                nnm::budget::time_history_bytes(n, force_components, n_inst),
            )?;
            let mut th = nnm::time_history(problem, harmonics, &x, n_inst).map_err(stored_point)?;
            for series in [&mut th.displacement, &mut th.velocity, &mut th.acceleration] {
                *series = run.on_free_dofs(std::mem::take(series));
            }
            let mut t = Table::new(format!("REST_MODE_NONL {src} NUME_ORDRE={order}"));
            for (c, kind) in [
                ("NUME_ORDRE", ColKind::I),
                ("INST", ColKind::R),
                ("NOEUD", ColKind::K),
                ("NOM_CMP", ColKind::K),
                ("DEPL", ColKind::R),
                ("VITE", ColKind::R),
                ("ACCE", ColKind::R),
            ] {
                t.add_column(c, kind)?;
            }
            for (it, time) in th.t.iter().enumerate() {
                for (d, &full) in free.iter().enumerate() {
                    let dof = &k.numbering.dofs[full];
                    t.push_row(vec![
                        Cell::I(it as i64 + 1),
                        Cell::R(*time),
                        Cell::K(dof.node.clone()),
                        Cell::K(dof.cmp.name().to_string()),
                        Cell::R(th.displacement[d][it]),
                        Cell::R(th.velocity[d][it]),
                        Cell::R(th.acceleration[d][it]),
                    ])?;
                }
            }
            let mut f = Table::new(format!(
                "REST_MODE_NONL {src} NUME_ORDRE={order}: contact forces"
            ));
            for (c, kind) in [
                ("NUME_ORDRE", ColKind::I),
                ("INST", ColKind::R),
                ("NUME_CHOC", ColKind::I),
                ("NOEUD", ColKind::K),
                ("NOM_CMP", ColKind::K),
                ("FORCE", ColKind::R),
            ] {
                f.add_column(c, kind)?;
            }
            for (it, time) in th.t.iter().enumerate() {
                for (s, (shock, comps)) in setup.shocks.iter().zip(&th.contact_force).enumerate() {
                    for (c, values) in comps.iter().enumerate() {
                        f.push_row(vec![
                            Cell::I(it as i64 + 1),
                            Cell::R(*time),
                            Cell::I(s as i64 + 1),
                            Cell::K(shock.node.clone()),
                            Cell::K(shock.cmps.get(c).cloned().unwrap_or_default()),
                            Cell::R(values[it]),
                        ])?;
                    }
                }
            }
            let forces = format!("{name}_FORC");
            ctx.create(&name, "dyna_trans")?;
            table_store::save_table(ctx.store, &name, &t)?;
            // The DOFs without rows, for a reader to say why (the complement of `free`).
            dyna_store::save_layout(
                ctx.store,
                &name,
                &dyna_store::Layout::of(&k.numbering, &k.eliminated),
            )?;
            ctx.create(&forces, "table_sdaster")?;
            table_store::save_table(ctx.store, &forces, &f)?;
            ctx.say(&format!(
                "REST_MODE_NONL {name}: {n_inst} instants over one period {:.6e} s; displacements, velocities and accelerations in SQL table {name}, contact forces in {forces}",
                th.t.last().copied().unwrap_or(0.0)
            ))
        }
    }
}

/// Label of Fourier coefficient j in the order 0, C1..CH, S1..SH.
fn coef_label(j: usize, h: usize) -> String {
    match j {
        0 => "FOURIER_0".to_string(),
        j if j <= h => format!("FOURIER_C{j}"),
        j => format!("FOURIER_S{}", j - h),
    }
}

/// An input error of the engine about the point itself names the row that chose it.
fn stored_point(e: crate::nnm::error::Error) -> Error {
    let e = Error::from(e);
    if e.kind == ErrorKind::Input {
        e.keyword("NUME_ORDRE")
    } else {
        e
    }
}
