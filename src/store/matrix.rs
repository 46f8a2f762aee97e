//! DOF numberings and assembled matrices as SQL tables:
//! - `dof_numbering(numbering, idx, node, cmp, eliminated)`: one row per DOF;
//! - `matrix_entries(matrix, row, col, value)`: the consolidated entries (both triangles);
//! - in `concept_data`: the numbering's mesh/model (key `numbering`) and, for a matrix, its
//!   numbering name, kind and eliminated DOFs (key `matrix`).

use super::{Schema, Store};
use crate::error::{Error, Result};
use crate::model::numbering::NumberedDof;
use crate::model::relations::DofRelation;
use crate::model::{AssembledMatrix, Cmp, DofNumbering, MatrixKind};
use rusqlite::params;
use rusqlite::types::ValueRef;
use serde::{Deserialize, Serialize};

const SCHEMA: &str = "
CREATE TABLE IF NOT EXISTS dof_numbering (
    numbering TEXT NOT NULL REFERENCES concepts(name) ON DELETE CASCADE,
    idx INTEGER NOT NULL,
    node TEXT NOT NULL,
    cmp TEXT NOT NULL,
    eliminated INTEGER NOT NULL,
    PRIMARY KEY (numbering, idx)
);
CREATE TABLE IF NOT EXISTS matrix_entries (
    matrix TEXT NOT NULL REFERENCES concepts(name) ON DELETE CASCADE,
    row INTEGER NOT NULL,
    col INTEGER NOT NULL,
    value REAL NOT NULL,
    PRIMARY KEY (matrix, row, col)
) WITHOUT ROWID;
";

pub fn ensure_schema(store: &Store) -> Result<()> {
    store.ensure_schema(Schema::Matrix, SCHEMA)
}

#[derive(Serialize, Deserialize)]
struct NumberingMeta {
    mesh: String,
    model: String,
    /// LIAISON_DDL relations on the DOF indices; absent in studies written before.
    #[serde(default)]
    relations: Vec<DofRelation>,
}

#[derive(Serialize, Deserialize)]
struct MatrixMeta {
    numbering: String,
    kind: MatrixKind,
    /// Indices of the eliminated DOFs.
    eliminated: Vec<usize>,
    /// Rows written to `matrix_entries`: a load that finds another count refuses the
    /// matrix (rows removed or added outside aster-nl). Absent in studies written before.
    #[serde(default)]
    entries: Option<usize>,
}

/// Remove the rows a numbering or matrix concept owns (called by `Store::delete_concept`).
pub fn drop_data(store: &Store, name: &str) -> Result<()> {
    ensure_schema(store)?;
    store.exec(
        "DELETE FROM dof_numbering WHERE numbering = ?1",
        params![name],
    )?;
    store.exec(
        "DELETE FROM matrix_entries WHERE matrix = ?1",
        params![name],
    )?;
    Ok(())
}

pub fn save_numbering(store: &Store, name: &str, num: &DofNumbering) -> Result<()> {
    ensure_schema(store)?;
    drop_data(store, name)?;
    let mut stmt = store.conn().prepare_cached(
        "INSERT INTO dof_numbering(numbering, idx, node, cmp, eliminated) VALUES (?1, ?2, ?3, ?4, ?5)",
    )?;
    for (i, d) in num.dofs.iter().enumerate() {
        let e = num.eliminated.get(i).copied().unwrap_or(false);
        stmt.execute(params![name, i as i64, d.node, d.cmp.name(), e as i64])?;
    }
    store.put_json(
        name,
        "numbering",
        &NumberingMeta {
            mesh: num.mesh.clone(),
            model: num.model.clone(),
            relations: num.relations.clone(),
        },
    )
}

pub fn load_numbering(store: &Store, name: &str) -> Result<DofNumbering> {
    ensure_schema(store)?;
    let meta: NumberingMeta = store.get_json(name, "numbering")?;
    let mut stmt = store.conn().prepare_cached(
        "SELECT node, cmp, eliminated FROM dof_numbering WHERE numbering = ?1 ORDER BY idx",
    )?;
    let rows = stmt.query_map(params![name], |r| {
        Ok((
            r.get::<_, String>(0)?,
            r.get::<_, String>(1)?,
            r.get::<_, i64>(2)?,
        ))
    })?;
    let mut dofs = Vec::new();
    let mut eliminated = Vec::new();
    for row in rows {
        let (node, cmp, e) = row?;
        let cmp = Cmp::parse(&cmp).ok_or_else(|| {
            Error::store(format!("numbering {name} has an unknown component {cmp}"))
        })?;
        dofs.push(NumberedDof { node, cmp });
        eliminated.push(e != 0);
    }
    let n = dofs.len();
    if let Some(r) = meta
        .relations
        .iter()
        .find(|r| r.terms.iter().any(|&(i, _)| i >= n))
    {
        return Err(Error::store(format!(
            "numbering {name} has a relation on a DOF outside its {n} DOFs: {r:?}"
        )));
    }
    Ok(DofNumbering {
        mesh: meta.mesh,
        model: meta.model,
        dofs,
        eliminated,
        relations: meta.relations,
    })
}

/// Save an assembled matrix; `numbering` is the name of its (already saved) numbering.
pub fn save_matrix(store: &Store, name: &str, m: &AssembledMatrix, numbering: &str) -> Result<()> {
    ensure_schema(store)?;
    drop_data(store, name)?;
    super::batch::insert_rows(
        store.conn(),
        "matrix_entries",
        ["matrix", "row", "col", "value"],
        m.triplets.iter().map(|&(r, c, v)| {
            [
                ValueRef::Text(name.as_bytes()),
                ValueRef::Integer(r as i64),
                ValueRef::Integer(c as i64),
                ValueRef::Real(v),
            ]
        }),
    )?;
    store.put_json(
        name,
        "matrix",
        &MatrixMeta {
            numbering: numbering.to_string(),
            kind: m.kind,
            eliminated: m
                .eliminated
                .iter()
                .enumerate()
                .filter(|(_, e)| **e)
                .map(|(i, _)| i)
                .collect(),
            entries: Some(m.triplets.len()),
        },
    )
}

/// Name of the numbering an assembled matrix uses.
pub fn matrix_numbering_name(store: &Store, name: &str) -> Result<String> {
    let meta: MatrixMeta = store.get_json(name, "matrix")?;
    Ok(meta.numbering)
}

pub fn load_matrix(store: &Store, name: &str) -> Result<AssembledMatrix> {
    ensure_schema(store)?;
    let meta: MatrixMeta = store.get_json(name, "matrix")?;
    let numbering = load_numbering(store, &meta.numbering)?;
    let n = numbering.len();
    let mut stmt = store.conn().prepare_cached(
        "SELECT row, col, value FROM matrix_entries WHERE matrix = ?1 ORDER BY row, col",
    )?;
    let rows = stmt.query_map(params![name], |r| {
        Ok((
            r.get::<_, i64>(0)?,
            r.get::<_, i64>(1)?,
            r.get::<_, f64>(2)?,
        ))
    })?;
    let mut triplets = Vec::new();
    for row in rows {
        let (r, c, v) = row?;
        let (r, c) = (usize::try_from(r), usize::try_from(c));
        match (r, c) {
            (Ok(r), Ok(c)) if r < n && c < n => triplets.push((r, c, v)),
            _ => {
                return Err(Error::store(format!(
                    "matrix {name} has an entry outside its numbering of {n} DOFs"
                )))
            }
        }
    }
    if let Some(want) = meta.entries {
        if triplets.len() != want {
            return Err(Error::store(format!(
                "matrix {name} has {} rows in matrix_entries, {want} were stored: the database was changed outside aster-nl",
                triplets.len()
            ))
            .hint("recompute the matrix (rerun the study from DEBUT)"));
        }
    }
    let mut eliminated = vec![false; n];
    for i in meta.eliminated {
        match eliminated.get_mut(i) {
            Some(e) => *e = true,
            None => {
                return Err(Error::store(format!(
                    "matrix {name} eliminates DOF {i} outside its numbering"
                )))
            }
        }
    }
    Ok(AssembledMatrix::new(
        numbering, meta.kind, triplets, eliminated,
    ))
}
