//! Persistence of a `dyna_trans` (REST_MODE_NONL, TYPE_RESU='DYNA_TRANS').
//!
//! The time history is the table concept of the result (`store::table`): one row per
//! instant and free DOF, columns NUME_ORDRE, INST, NOEUD, NOM_CMP and one per stored field
//! (DEPL, VITE, ACCE). Beside it, `concept_data(concept, 'dyna_trans')` holds what a reader
//! needs to resolve and explain a node and a component: the mesh, and the DOFs of the
//! numbering that a boundary condition eliminated (they have no rows). Results written
//! before that payload existed have none: [`load_layout`] gives `None`.

use super::Store;
use crate::error::{Error, Result};
use rusqlite::params;
use serde::{Deserialize, Serialize};

/// The fields a time history may hold, as NOM_CHAM names them (and as its columns are named).
pub const FIELDS: [&str; 3] = ["DEPL", "VITE", "ACCE"];

const KEY: &str = "dyna_trans";

/// Where the DOFs of a time history come from.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Layout {
    pub mesh: String,
    /// (node, component) of every DOF of the numbering eliminated by a boundary condition.
    pub blocked: Vec<(String, String)>,
}

impl Layout {
    /// The layout of a time history on `numbering`'s DOFs, `eliminated` (one per DOF) the
    /// ones without rows.
    pub fn of(numbering: &crate::model::DofNumbering, eliminated: &[bool]) -> Layout {
        Layout {
            mesh: numbering.mesh.clone(),
            blocked: numbering
                .dofs
                .iter()
                .zip(eliminated)
                .filter(|(_, &e)| e)
                .map(|(dof, _)| (dof.node.clone(), dof.cmp.name().to_string()))
                .collect(),
        }
    }
}

pub fn save_layout(store: &Store, concept: &str, layout: &Layout) -> Result<()> {
    store.put_json(concept, KEY, layout)
}

/// The layout of `concept`, `None` for a result written without one.
pub fn load_layout(store: &Store, concept: &str) -> Result<Option<Layout>> {
    let n: i64 = store
        .row(
            "SELECT COUNT(*) FROM concept_data WHERE concept = ?1 AND key = ?2",
            params![concept, KEY],
            |r| r.get(0),
        )?
        .unwrap_or(0);
    if n == 0 {
        return Ok(None);
    }
    store.get_json(concept, KEY).map(Some)
}

/// The fields ([`FIELDS`]) stored in `concept`, in that order.
pub fn stored_fields(store: &Store, concept: &str) -> Result<Vec<&'static str>> {
    let mut stmt = store
        .conn()
        .prepare_cached("SELECT name FROM table_columns WHERE concept = ?1")?;
    let names: Vec<String> = stmt
        .query_map(params![concept], |r| r.get(0))?
        .collect::<rusqlite::Result<_>>()?;
    if names.is_empty() {
        return Err(Error::store(format!(
            "{concept} is not a time history stored in this database"
        )));
    }
    Ok(FIELDS
        .into_iter()
        .filter(|f| names.iter().any(|n| n == f))
        .collect())
}

/// One component's samples, by increasing NUME_ORDRE (= increasing INST).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Samples {
    pub nume_ordre: Vec<i64>,
    pub inst: Vec<f64>,
    pub values: Vec<f64>,
}

/// The samples of `field` (one of [`FIELDS`], checked by the caller against
/// [`stored_fields`]) at `node` `cmp`; empty when the table has no row of that DOF.
pub fn samples(
    store: &Store,
    concept: &str,
    field: &str,
    node: &str,
    cmp: &str,
) -> Result<Samples> {
    if !FIELDS.contains(&field) {
        return Err(Error::internal(format!(
            "{field} is not a time-history field"
        )));
    }
    let q = super::table::quote_ident;
    let mut stmt = store.conn().prepare(&format!(
        "SELECT NUME_ORDRE, INST, {} FROM {} WHERE NOEUD = ?1 AND NOM_CMP = ?2 \
         ORDER BY NUME_ORDRE",
        q(field),
        q(concept)
    ))?;
    let mut out = Samples::default();
    let mut rows = stmt.query(params![node, cmp])?;
    while let Some(r) = rows.next()? {
        let value: Option<f64> = r.get(2)?;
        let (n, t): (i64, f64) = (r.get(0)?, r.get(1)?);
        out.nume_ordre.push(n);
        out.inst.push(t);
        out.values.push(value.ok_or_else(|| {
            Error::store(format!(
                "{concept}: no {field} value of {node} {cmp} at NUME_ORDRE={n}"
            ))
        })?);
    }
    Ok(out)
}

/// The components stored at `node`, in table order.
pub fn components_at(store: &Store, concept: &str, node: &str) -> Result<Vec<String>> {
    let mut stmt = store.conn().prepare(&format!(
        "SELECT NOM_CMP FROM {} WHERE NOEUD = ?1 GROUP BY NOM_CMP ORDER BY MIN(rowid)",
        super::table::quote_ident(concept)
    ))?;
    let cmps = stmt
        .query_map(params![node], |r| r.get(0))?
        .collect::<rusqlite::Result<_>>()?;
    Ok(cmps)
}

/// The stored instants of `concept`, by increasing NUME_ORDRE.
pub fn instants(store: &Store, concept: &str) -> Result<Vec<f64>> {
    let mut stmt = store.conn().prepare(&format!(
        "SELECT INST FROM {} GROUP BY NUME_ORDRE ORDER BY NUME_ORDRE",
        super::table::quote_ident(concept)
    ))?;
    let t = stmt
        .query_map([], |r| r.get(0))?
        .collect::<rusqlite::Result<_>>()?;
    Ok(t)
}

/// (NOEUD, NOM_CMP, DEPL, VITE) of every row of instant `nume_ordre`, in one query (a start
/// from a result reads a whole instant; a query per DOF scans the table once per DOF).
pub fn displacements_and_velocities(
    store: &Store,
    concept: &str,
    nume_ordre: i64,
) -> Result<Vec<(String, String, f64, f64)>> {
    let mut stmt = store.conn().prepare(&format!(
        "SELECT NOEUD, NOM_CMP, DEPL, VITE FROM {} WHERE NUME_ORDRE = ?1",
        super::table::quote_ident(concept)
    ))?;
    let rows = stmt
        .query_map(params![nume_ordre], |r| {
            Ok((r.get(0)?, r.get(1)?, r.get(2)?, r.get(3)?))
        })?
        .collect::<rusqlite::Result<_>>()?;
    Ok(rows)
}
