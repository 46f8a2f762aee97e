//! Persistence of `mode_meca` concepts.
//!
//! - `modes(concept, NUME_ORDRE, FREQ, OMEGA2, MASS_GENE, RIGI_GENE, LABEL)`: one row per
//!   mode, queryable as `SELECT NUME_ORDRE, FREQ FROM modes WHERE concept='MODES'`.
//! - `mode_shapes(concept, NUME_ORDRE, dof, NOEUD, NOM_CMP, value)`: every shape value.
//! - `concept_data(concept, 'numbering')`: the DOF numbering (json);
//! - `concept_data(concept, 'matrices')`: the MATR_RIGI and MATR_MASS it was computed from.

use crate::error::{Error, Result};
use crate::model::modes::{Mode, ModeMeca, StaticTag};
use crate::model::numbering::DofNumbering;
use crate::store::{Schema, Store};
use rusqlite::params;
use rusqlite::types::ValueRef;

const SCHEMA: &str = "
CREATE TABLE IF NOT EXISTS modes (
    concept TEXT NOT NULL REFERENCES concepts(name) ON DELETE CASCADE,
    NUME_ORDRE INTEGER NOT NULL,
    FREQ REAL NOT NULL,
    OMEGA2 REAL NOT NULL,
    MASS_GENE REAL NOT NULL,
    RIGI_GENE REAL NOT NULL,
    LABEL TEXT NOT NULL,
    PRIMARY KEY (concept, NUME_ORDRE)
);
CREATE TABLE IF NOT EXISTS mode_shapes (
    concept TEXT NOT NULL REFERENCES concepts(name) ON DELETE CASCADE,
    NUME_ORDRE INTEGER NOT NULL,
    dof INTEGER NOT NULL,
    NOEUD TEXT NOT NULL,
    NOM_CMP TEXT NOT NULL,
    value REAL NOT NULL,
    PRIMARY KEY (concept, NUME_ORDRE, dof)
);
";

pub fn ensure_schema(store: &Store) -> Result<()> {
    store.ensure_schema(Schema::Modes, SCHEMA)
}

pub fn drop_data(store: &Store, name: &str) -> Result<()> {
    ensure_schema(store)?;
    store.exec("DELETE FROM modes WHERE concept = ?1", params![name])?;
    store.exec("DELETE FROM mode_shapes WHERE concept = ?1", params![name])?;
    Ok(())
}

pub fn save_modes(store: &Store, name: &str, modes: &ModeMeca) -> Result<()> {
    ensure_schema(store)?;
    drop_data(store, name)?;
    store.put_json(name, "numbering", &modes.numbering)?;
    store.put_json(name, "numbering_name", &modes.numbering_name)?;
    let conn = store.conn();
    let mut row = conn.prepare_cached(
        "INSERT INTO modes(concept, NUME_ORDRE, FREQ, OMEGA2, MASS_GENE, RIGI_GENE, LABEL)
         VALUES (?1, ?2, ?3, ?4, ?5, ?6, ?7)",
    )?;
    for m in &modes.modes {
        if m.shape.len() != modes.numbering.len() {
            return Err(Error::internal(format!(
                "mode {} has {} values for {} DOFs",
                m.nume_ordre,
                m.shape.len(),
                modes.numbering.len()
            )));
        }
        row.execute(params![
            name,
            m.nume_ordre as i64,
            m.freq,
            m.omega2,
            m.mass_gene,
            m.rigi_gene,
            m.label
        ])?;
        let order = m.nume_ordre as i64;
        crate::store::batch::insert_rows(
            conn,
            "mode_shapes",
            ["concept", "NUME_ORDRE", "dof", "NOEUD", "NOM_CMP", "value"],
            m.shape
                .iter()
                .zip(&modes.numbering.dofs)
                .enumerate()
                .map(|(i, (&v, dof))| {
                    [
                        ValueRef::Text(name.as_bytes()),
                        ValueRef::Integer(order),
                        ValueRef::Integer(i as i64),
                        ValueRef::Text(dof.node.as_bytes()),
                        ValueRef::Text(dof.cmp.name().as_bytes()),
                        ValueRef::Real(v),
                    ]
                }),
        )?;
    }
    Ok(())
}

/// What each vector of a MODE_STATIQUE result answers (`concept_data(concept,
/// 'static_modes')`).
pub fn save_static_tags(store: &Store, name: &str, tags: &[StaticTag]) -> Result<()> {
    store.put_json(name, "static_modes", &tags)
}

/// The static tags of `name`; empty for modes that are not static deformations.
pub fn load_static_tags(store: &Store, name: &str) -> Result<Vec<StaticTag>> {
    Ok(store.find_json(name, "static_modes")?.unwrap_or_default())
}

/// The matrices a basis was computed from (Code_Aster's reference of a mode_meca to its
/// MATR_RIGI and MATR_MASS): PROJ_VECT_BASE reads the mass as the metric of coordinates.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct ModeMatrices {
    pub rigi: String,
    pub mass: String,
}

pub fn save_matrices(store: &Store, name: &str, m: &ModeMatrices) -> Result<()> {
    store.put_json(name, "matrices", m)
}

/// The matrices of `name`, `None` for a basis stored without them (before aster-nl kept
/// them, or one REST_MODE_NONL wrote).
pub fn load_matrices(store: &Store, name: &str) -> Result<Option<ModeMatrices>> {
    store.find_json(name, "matrices")
}

pub fn load_modes(store: &Store, name: &str) -> Result<ModeMeca> {
    ensure_schema(store)?;
    let numbering: DofNumbering = store.get_json(name, "numbering")?;
    let numbering_name: String = store.get_json(name, "numbering_name")?;
    let conn = store.conn();
    let mut rows = conn.prepare_cached(
        "SELECT NUME_ORDRE, FREQ, OMEGA2, MASS_GENE, RIGI_GENE, LABEL FROM modes
         WHERE concept = ?1 ORDER BY NUME_ORDRE",
    )?;
    let mut modes: Vec<Mode> = rows
        .query_map(params![name], |r| {
            Ok(Mode {
                nume_ordre: r.get::<_, i64>(0)? as usize,
                freq: r.get(1)?,
                omega2: r.get(2)?,
                mass_gene: r.get(3)?,
                rigi_gene: r.get(4)?,
                label: r.get(5)?,
                shape: Vec::new(),
            })
        })?
        .collect::<rusqlite::Result<_>>()?;
    let mut vals = conn.prepare_cached(
        "SELECT dof, value FROM mode_shapes WHERE concept = ?1 AND NUME_ORDRE = ?2 ORDER BY dof",
    )?;
    for m in &mut modes {
        let mut shape = vec![0.0; numbering.len()];
        let entries = vals.query_map(params![name, m.nume_ordre as i64], |r| {
            Ok((r.get::<_, i64>(0)?, r.get::<_, f64>(1)?))
        })?;
        let mut found = 0;
        for e in entries {
            let (i, v) = e?;
            let slot = usize::try_from(i)
                .ok()
                .and_then(|i| shape.get_mut(i))
                .ok_or_else(|| {
                    Error::store(format!("mode_shapes of {name} names DOF {i} out of range"))
                })?;
            *slot = v;
            found += 1;
        }
        // Every DOF of every mode is stored: fewer rows mean the file was edited.
        if found != numbering.len() {
            return Err(Error::store(format!(
                "mode {} of {name} has {found} rows in mode_shapes for {} DOFs: the database was changed outside aster-nl",
                m.nume_ordre,
                numbering.len()
            ))
            .hint("recompute the modes (rerun the study from DEBUT)"));
        }
        m.shape = shape;
    }
    Ok(ModeMeca {
        numbering,
        numbering_name,
        modes,
    })
}
