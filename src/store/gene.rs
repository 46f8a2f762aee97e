//! Persistence of the generalized (modal-basis) concepts and of nodal fields:
//! - `nume_ddl_gene` (NUME_DDL_GENE): in `concept_data` (key `gene`), the basis and its size;
//! - `matr_asse_gene_r` (PROJ_MATR_BASE) and `vect_asse_gene` (PROJ_VECT_BASE): their
//!   nonzero entries in `gene_entries(concept, row, col, value)` (a vector has col 0), and
//!   in `concept_data` (key `gene`) the numbering, the basis, the size and the kind;
//! - `cham_no_sdaster` (CREA_CHAMP): `field_values(concept, NOEUD, NOM_CMP, value)`, one
//!   row per node and component, and the mesh in `concept_data` (key `field`);
//! - an obstacle (DEFI_OBSTACLE, Code_Aster's `table_fonction`): its type in `concept_data`
//!   (key `obstacle`);
//! - `vect_elem_depl_r` (CALC_VECT_ELEM): the loads it names, in `concept_data` (key
//!   `vect_elem`).
//!
//! Queryable as, e.g., `SELECT row, value FROM gene_entries WHERE concept = 'VITINI'`.

use super::{Schema, Store};
use crate::error::{Error, Result};
use rusqlite::params;
use serde::{Deserialize, Serialize};

const SCHEMA: &str = "
CREATE TABLE IF NOT EXISTS gene_entries (
    concept TEXT NOT NULL REFERENCES concepts(name) ON DELETE CASCADE,
    row INTEGER NOT NULL,
    col INTEGER NOT NULL,
    value REAL NOT NULL,
    PRIMARY KEY (concept, row, col)
);
CREATE TABLE IF NOT EXISTS field_values (
    concept TEXT NOT NULL REFERENCES concepts(name) ON DELETE CASCADE,
    NOEUD TEXT NOT NULL,
    NOM_CMP TEXT NOT NULL,
    value REAL NOT NULL,
    PRIMARY KEY (concept, NOEUD, NOM_CMP)
);
";

const GENE: &str = "gene";
const FIELD: &str = "field";
const OBSTACLE: &str = "obstacle";
const VECT_ELEM: &str = "vect_elem";

pub fn ensure_schema(store: &Store) -> Result<()> {
    store.ensure_schema(Schema::Gene, SCHEMA)
}

/// Remove the rows a generalized concept or a field owns (called by `Store::delete_concept`).
pub fn drop_data(store: &Store, name: &str) -> Result<()> {
    ensure_schema(store)?;
    store.exec("DELETE FROM gene_entries WHERE concept = ?1", params![name])?;
    store.exec("DELETE FROM field_values WHERE concept = ?1", params![name])?;
    Ok(())
}

/// A generalized numbering: one unknown per vector of the basis, in its order.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct GeneNumbering {
    /// The `mode_meca` concept whose vectors are the unknowns.
    pub basis: String,
    pub size: usize,
    /// STOCKAGE as given ('DIAG', 'PLEIN' or 'LIGN_CIEL'); no effect on what is stored.
    pub storage: String,
}

/// What a generalized matrix or vector is attached to.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct GeneMeta {
    /// The NUME_DDL_GENE concept.
    pub numbering: String,
    pub basis: String,
    pub size: usize,
    /// A matrix: MASS, RIGI or AMOR (the kind of the projected matrix); a vector: its
    /// TYPE_VECT (FORC, DEPL, VITE, ACCE).
    pub kind: String,
}

/// A dense generalized matrix (row-major `size × size`) with what it is attached to.
#[derive(Clone, Debug, PartialEq)]
pub struct GeneMatrix {
    pub meta: GeneMeta,
    pub values: Vec<f64>,
}

/// A generalized vector with what it is attached to.
#[derive(Clone, Debug, PartialEq)]
pub struct GeneVector {
    pub meta: GeneMeta,
    pub values: Vec<f64>,
}

/// A nodal field: values by (node, component) on a mesh; components absent are zero.
#[derive(Clone, Debug, PartialEq, Default)]
pub struct NodalField {
    pub mesh: String,
    pub values: Vec<(String, String, f64)>,
}

/// Elementary load vectors (CALC_VECT_ELEM): the loads whose nodal forces ASSE_VECTEUR
/// sums.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct VectElem {
    pub charges: Vec<String>,
}

pub fn save_vect_elem(store: &Store, name: &str, v: &VectElem) -> Result<()> {
    store.put_json(name, VECT_ELEM, v)
}

pub fn load_vect_elem(store: &Store, name: &str) -> Result<VectElem> {
    store.get_json(name, VECT_ELEM)
}

/// The geometry of an obstacle as DEFI_OBSTACLE defines it.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct ObstacleDef {
    /// TYPE: PLAN_Y, PLAN_Z, BI_PLAN_Y, BI_PLAN_Z or CERCLE.
    pub kind: String,
}

pub fn save_numbering(store: &Store, name: &str, num: &GeneNumbering) -> Result<()> {
    store.put_json(name, GENE, num)
}

pub fn load_numbering(store: &Store, name: &str) -> Result<GeneNumbering> {
    store.get_json(name, GENE)
}

fn save_entries(
    store: &Store,
    name: &str,
    entries: impl Iterator<Item = (usize, usize, f64)>,
) -> Result<()> {
    ensure_schema(store)?;
    drop_data(store, name)?;
    let mut stmt = store.conn().prepare_cached(
        "INSERT INTO gene_entries(concept, row, col, value) VALUES (?1, ?2, ?3, ?4)",
    )?;
    for (i, j, v) in entries.filter(|e| e.2 != 0.0) {
        stmt.execute(params![name, i as i64, j as i64, v])?;
    }
    Ok(())
}

fn load_entries(store: &Store, name: &str, rows: usize, cols: usize) -> Result<Vec<f64>> {
    ensure_schema(store)?;
    let mut values = vec![0.0; rows * cols];
    let mut stmt = store
        .conn()
        .prepare_cached("SELECT row, col, value FROM gene_entries WHERE concept = ?1")?;
    let entries = stmt.query_map(params![name], |r| {
        Ok((
            r.get::<_, i64>(0)?,
            r.get::<_, i64>(1)?,
            r.get::<_, f64>(2)?,
        ))
    })?;
    for e in entries {
        let (i, j, v) = e?;
        let slot = usize::try_from(i)
            .ok()
            .zip(usize::try_from(j).ok())
            .filter(|&(i, j)| i < rows && j < cols)
            .map(|(i, j)| i * cols + j)
            .ok_or_else(|| {
                Error::store(format!(
                    "gene_entries of {name} has entry ({i}, {j}) outside its {rows} x {cols} size"
                ))
            })?;
        values[slot] = v;
    }
    Ok(values)
}

pub fn save_matrix(store: &Store, name: &str, m: &GeneMatrix) -> Result<()> {
    let n = m.meta.size;
    if m.values.len() != n * n {
        return Err(Error::internal(format!(
            "generalized matrix {name}: {} values for size {n}",
            m.values.len()
        )));
    }
    save_entries(
        store,
        name,
        m.values.iter().enumerate().map(|(k, &v)| (k / n, k % n, v)),
    )?;
    store.put_json(name, GENE, &m.meta)
}

pub fn load_matrix(store: &Store, name: &str) -> Result<GeneMatrix> {
    let meta: GeneMeta = store.get_json(name, GENE)?;
    let values = load_entries(store, name, meta.size, meta.size)?;
    Ok(GeneMatrix { meta, values })
}

pub fn save_vector(store: &Store, name: &str, v: &GeneVector) -> Result<()> {
    if v.values.len() != v.meta.size {
        return Err(Error::internal(format!(
            "generalized vector {name}: {} values for size {}",
            v.values.len(),
            v.meta.size
        )));
    }
    save_entries(
        store,
        name,
        v.values.iter().enumerate().map(|(i, &x)| (i, 0, x)),
    )?;
    store.put_json(name, GENE, &v.meta)
}

pub fn load_vector(store: &Store, name: &str) -> Result<GeneVector> {
    let meta: GeneMeta = store.get_json(name, GENE)?;
    let values = load_entries(store, name, meta.size, 1)?;
    Ok(GeneVector { meta, values })
}

pub fn save_field(store: &Store, name: &str, f: &NodalField) -> Result<()> {
    ensure_schema(store)?;
    drop_data(store, name)?;
    let mut stmt = store.conn().prepare_cached(
        "INSERT OR REPLACE INTO field_values(concept, NOEUD, NOM_CMP, value) VALUES (?1, ?2, ?3, ?4)",
    )?;
    for (node, cmp, v) in &f.values {
        stmt.execute(params![name, node, cmp, v])?;
    }
    store.put_json(name, FIELD, &f.mesh)
}

pub fn load_field(store: &Store, name: &str) -> Result<NodalField> {
    ensure_schema(store)?;
    let mesh: String = store.get_json(name, FIELD)?;
    let mut stmt = store.conn().prepare_cached(
        "SELECT NOEUD, NOM_CMP, value FROM field_values WHERE concept = ?1 ORDER BY rowid",
    )?;
    let values = stmt
        .query_map(params![name], |r| Ok((r.get(0)?, r.get(1)?, r.get(2)?)))?
        .collect::<rusqlite::Result<Vec<_>>>()?;
    Ok(NodalField { mesh, values })
}

pub fn save_obstacle(store: &Store, name: &str, o: &ObstacleDef) -> Result<()> {
    store.put_json(name, OBSTACLE, o)
}

pub fn load_obstacle(store: &Store, name: &str) -> Result<ObstacleDef> {
    store.get_json(name, OBSTACLE)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn store_with(name: &str, ty: &str) -> Store {
        let st = Store::in_memory().unwrap();
        st.register_concept(name, ty, "TEST", "t.comm", 1).unwrap();
        st
    }

    #[test]
    fn a_matrix_comes_back_with_its_zeros_and_meta() {
        let st = store_with("MG", "matr_asse_gene_r");
        let m = GeneMatrix {
            meta: GeneMeta {
                numbering: "NG".into(),
                basis: "MODES".into(),
                size: 2,
                kind: "RIGI".into(),
            },
            values: vec![4.0, 0.0, -1.5, 9.0],
        };
        save_matrix(&st, "MG", &m).unwrap();
        assert_eq!(load_matrix(&st, "MG").unwrap(), m);
        let stored: i64 = st
            .row(
                "SELECT COUNT(*) FROM gene_entries WHERE concept='MG'",
                [],
                |r| r.get(0),
            )
            .unwrap()
            .unwrap();
        assert_eq!(stored, 3, "the zero is not stored");
    }

    #[test]
    fn a_vector_and_a_field_come_back() {
        let st = store_with("V", "vect_asse_gene");
        st.register_concept("F", "cham_no_sdaster", "TEST", "t.comm", 2)
            .unwrap();
        let v = GeneVector {
            meta: GeneMeta {
                numbering: "NG".into(),
                basis: "MODES".into(),
                size: 3,
                kind: "DEPL".into(),
            },
            values: vec![0.0, 1.0, -2.0],
        };
        save_vector(&st, "V", &v).unwrap();
        assert_eq!(load_vector(&st, "V").unwrap(), v);
        let f = NodalField {
            mesh: "MA".into(),
            values: vec![
                ("N1".into(), "DX".into(), 1.5),
                ("N1".into(), "DY".into(), -1.0),
            ],
        };
        save_field(&st, "F", &f).unwrap();
        assert_eq!(load_field(&st, "F").unwrap(), f);
        st.delete_concept("F").unwrap();
        let left: i64 = st
            .row("SELECT COUNT(*) FROM field_values", [], |r| r.get(0))
            .unwrap()
            .unwrap();
        assert_eq!(left, 0);
    }
}
