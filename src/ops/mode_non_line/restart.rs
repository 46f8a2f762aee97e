//! MODE_NON_LINE restarts: the direction in which the stored branch was travelling at the
//! start row, which DIR_EVOLUTION refers to (−1 goes on that way, +1 turns back).
//!
//! The rows of one run of MODE_NON_LINE (one NUME_REPRISE of a table: a `reuse=` restart
//! appends a new NUME_REPRISE, a restart into a new concept starts one) are numbered in
//! the order the branch was travelled. The direction at a row is the chord through its
//! neighbours in the same run: from the previous row to the next (the centred chord,
//! parallel to the tangent up to the curvature of the branch), or to/from the row itself
//! at either end of the run. Only its sign against the new tangent matters, so a chord
//! over one branch step is ample.

use crate::error::Result;
use crate::store::mnl as mnl_store;
use crate::store::Store;
use crate::table::{Cell, Table};

/// The direction of travel at a stored row, from row `from` to row `to` of the same run.
pub struct Travel {
    /// x(to) − x(from), physical units (the layout of the stored points).
    pub direction: Vec<f64>,
    pub from: i64,
    pub to: i64,
}

/// (NUME_ORDRE, NUME_REPRISE) of every row that has both.
fn orders(t: &Table) -> Vec<(i64, i64)> {
    let (Some(o), Some(r)) = (t.col("NUME_ORDRE"), t.col("NUME_REPRISE")) else {
        return Vec::new();
    };
    t.rows
        .iter()
        .filter_map(|row| match (row.get(o), row.get(r)) {
            (Some(Cell::I(o)), Some(Cell::I(r))) => Some((*o, *r)),
            _ => None,
        })
        .collect()
}

/// The direction in which the branch of table `name` (its result table `t`) was travelling
/// at row `order`, or None when that row is the only one of its run (nothing to compare
/// with) or a neighbour's point is not stored.
pub fn travel_at_row(store: &Store, t: &Table, name: &str, order: i64) -> Result<Option<Travel>> {
    let rows = orders(t);
    let Some(&(_, run)) = rows.iter().find(|(o, _)| *o == order) else {
        return Ok(None);
    };
    let same_run = rows.iter().filter(|(_, r)| *r == run).map(|(o, _)| *o);
    let prev = same_run.clone().filter(|&o| o < order).max();
    let next = same_run.filter(|&o| o > order).min();
    let (from, to) = match (prev, next) {
        (Some(p), Some(n)) => (p, n),
        (None, Some(n)) => (order, n),
        (Some(p), None) => (p, order),
        (None, None) => return Ok(None),
    };
    let (Some(a), Some(b)) = (
        mnl_store::load_point(store, name, from)?,
        mnl_store::load_point(store, name, to)?,
    ) else {
        return Ok(None);
    };
    if a.len() != b.len() {
        return Ok(None);
    }
    let direction = b.iter().zip(&a).map(|(y, x)| y - x).collect();
    Ok(Some(Travel {
        direction,
        from,
        to,
    }))
}
