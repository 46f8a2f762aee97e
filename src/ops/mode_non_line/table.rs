//! MODE_NON_LINE's result table as Code_Aster lays it out (then aster-nl's accuracy
//! columns): its columns, one row per point, the CARA_CHOC sub-table, the restart count
//! NUME_REPRISE.

use super::problem::CARA_CHOC_COLUMNS;
use crate::error::Result;
use crate::nnm::Point;
use crate::ops::OpContext;
use crate::store::mnl::StoredShock;
use crate::store::table as table_store;
use crate::table::{Cell, ColKind, Table};

/// Columns of the result table: Code_Aster's, then ours (accuracy indicators).
pub(super) const COLUMNS: &[(&str, ColKind)] = &[
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
    // The contact laws checked in time: max |f_series − f_law(u)| / (RIGI_NOR·JEU) (a cubic
    // spring's over its largest force); O(1) when the branch has drifted onto a
    // non-physical root of an implicit law.
    ("ECART_LOI_CHOC", ColKind::R),
    ("BRANCHE", ColKind::I),
    // Retries of the row's branch with a halved series step before its correction
    // converged (on the branch's corrected end row).
    ("NB_REPRISE_PAS", ColKind::I),
    // ENERGIE's formula averaged over the period instead of taken at one instant: closer
    // to the orbit's energy on a truncated harmonic balance (docs/mode_non_line.md).
    ("ENERGIE_MOYENNE", ColKind::R),
];

/// NUME_REPRISE of the start row's table, for a restart into a new concept.
pub(super) fn restart_reprise(ctx: &OpContext<'_>, from: &Option<String>) -> Result<i64> {
    match from {
        None => Ok(0),
        Some(src) => {
            let t = table_store::load_table(ctx.store, src)?;
            Ok(max_int(&t, "NUME_REPRISE"))
        }
    }
}

pub(super) fn new_table() -> Table {
    let mut t = Table::new("MODE_NON_LINE");
    for (name, kind) in COLUMNS {
        // Names are constants: add_column cannot fail on them.
        let _ = t.add_column(name, *kind);
    }
    t
}

pub(super) fn row(
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

pub(super) fn max_int(t: &Table, col: &str) -> i64 {
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

pub(super) fn cara_choc_table(shocks: &[StoredShock]) -> Result<Table> {
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
            // A cubic spring has no ring law: an empty cell.
            if s.loi_cercle.is_empty() {
                Cell::Null
            } else {
                Cell::K(s.loi_cercle.clone())
            },
        ])?;
    }
    Ok(t)
}
