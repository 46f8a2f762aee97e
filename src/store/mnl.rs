//! Persistence of what MODE_NON_LINE computes besides its result table.
//!
//! - `mnl_points(concept, NUME_ORDRE, omega, n, x)`: the full unknown vector of every row
//!   (little-endian f64 blob), enough to restart a branch or rebuild any quantity.
//! - `mnl_fourier(concept, NUME_ORDRE, NOEUD, NOM_CMP, HARM, COEF_C, COEF_S)`: the Fourier
//!   coefficients of every displacement, queryable in SQL (HARM 0 has COEF_S = 0).
//! - `mnl_basis(concept, NUME_VECT, omega2, residual, n, v)`: the columns of the
//!   Craig–Bampton basis of a run with REDUCTION (blobs over the free DOFs; omega2 and the
//!   mode's relative residual NULL for a constraint mode),
//!   what turns its stored points back into physical displacements.
//! - `concept_data(concept, 'mnl_setup')`: harmonics, numbering and shocks of the run.

use crate::error::{Error, Result};
use crate::linalg::craig_bampton::Reduction;
use crate::store::{Schema, Store};
use rusqlite::params;
use serde::{Deserialize, Serialize};

const SCHEMA: &str = "
CREATE TABLE IF NOT EXISTS mnl_points (
    concept TEXT NOT NULL REFERENCES concepts(name) ON DELETE CASCADE,
    NUME_ORDRE INTEGER NOT NULL,
    omega REAL NOT NULL,
    n INTEGER NOT NULL,
    x BLOB NOT NULL,
    PRIMARY KEY (concept, NUME_ORDRE)
);
CREATE TABLE IF NOT EXISTS mnl_fourier (
    concept TEXT NOT NULL REFERENCES concepts(name) ON DELETE CASCADE,
    NUME_ORDRE INTEGER NOT NULL,
    NOEUD TEXT NOT NULL,
    NOM_CMP TEXT NOT NULL,
    HARM INTEGER NOT NULL,
    COEF_C REAL NOT NULL,
    COEF_S REAL NOT NULL
);
CREATE INDEX IF NOT EXISTS mnl_fourier_row ON mnl_fourier(concept, NUME_ORDRE);
CREATE TABLE IF NOT EXISTS mnl_basis (
    concept TEXT NOT NULL REFERENCES concepts(name) ON DELETE CASCADE,
    NUME_VECT INTEGER NOT NULL,
    omega2 REAL,
    residual REAL,
    n INTEGER NOT NULL,
    v BLOB NOT NULL,
    PRIMARY KEY (concept, NUME_VECT)
);
CREATE TABLE IF NOT EXISTS mnl_floquet (
    concept TEXT NOT NULL REFERENCES concepts(name) ON DELETE CASCADE,
    NUME_ORDRE INTEGER NOT NULL,
    NUME_MULT INTEGER NOT NULL,
    PARTIE_REELLE REAL NOT NULL,
    PARTIE_IMAG REAL NOT NULL,
    MODULE REAL NOT NULL,
    PRIMARY KEY (concept, NUME_ORDRE, NUME_MULT)
);
";

/// One shock as stored (also written to the CARA_CHOC sub-table).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct StoredShock {
    pub obstacle: String,
    pub node: String,
    pub cmps: Vec<String>,
    pub gap: f64,
    pub stiffness: f64,
    pub regul: f64,
    pub origin: [f64; 3],
    /// LOI_CERCLE, the ring law's form ('RAYON' or 'SECANTE'; read by CERCLE only). Studies
    /// stored before the keyword existed were computed with 'SECANTE'.
    #[serde(default = "form_of_older_studies")]
    pub loi_cercle: String,
}

/// The ring law of studies stored before LOI_CERCLE existed.
pub fn form_of_older_studies() -> String {
    "SECANTE".to_string()
}

/// What a later REST_MODE_NONL or restart needs to interpret the stored points.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct MnlSetup {
    pub h_lin: usize,
    pub h_nonl: usize,
    pub matr_rigi: String,
    pub matr_mass: String,
    pub shocks: Vec<StoredShock>,
    /// Name of the CARA_CHOC sub-table concept.
    pub cara_choc: String,
    /// REDUCTION: the run's unknowns are reduced coordinates on the basis stored in
    /// `mnl_basis`. Absent for a run on the full model (and in studies written before).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub reduction: Option<StoredReduction>,
}

/// What a reduced run's basis is, beside its columns (`mnl_basis`).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct StoredReduction {
    /// The retained DOFs (indices into the free DOFs of MATR_RIGI), the first coordinates.
    pub retained: Vec<usize>,
    /// Fixed-interface modes kept.
    pub modes: usize,
}

pub fn ensure_schema(store: &Store) -> Result<()> {
    store.ensure_schema(Schema::Mnl, SCHEMA)
}

pub fn drop_data(store: &Store, name: &str) -> Result<()> {
    ensure_schema(store)?;
    for sql in [
        "DELETE FROM mnl_points WHERE concept = ?1",
        "DELETE FROM mnl_fourier WHERE concept = ?1",
        "DELETE FROM mnl_floquet WHERE concept = ?1",
        "DELETE FROM mnl_basis WHERE concept = ?1",
    ] {
        store.exec(sql, params![name])?;
    }
    Ok(())
}

/// The concepts a MODE_NON_LINE result owns beside its own rows: its CARA_CHOC sub-table
/// (`<name>_CHOC`), when that concept is still the one MODE_NON_LINE made. Empty for any
/// other concept. DETRUIRE removes them with their result, as Code_Aster's table_container
/// takes its sub-tables with it.
pub fn owned_concepts(store: &Store, name: &str) -> Result<Vec<String>> {
    if store.concept_operator(name)?.as_deref() != Some("MODE_NON_LINE") {
        return Ok(Vec::new());
    }
    let Ok(setup) = load_setup(store, name) else {
        return Ok(Vec::new());
    };
    let sub = setup.cara_choc;
    let made_here =
        sub != name && store.concept_operator(&sub)?.as_deref() == Some("MODE_NON_LINE");
    Ok(if made_here { vec![sub] } else { Vec::new() })
}

pub fn save_setup(store: &Store, name: &str, setup: &MnlSetup) -> Result<()> {
    store.put_json(name, "mnl_setup", setup)
}

pub fn load_setup(store: &Store, name: &str) -> Result<MnlSetup> {
    store.get_json(name, "mnl_setup")
}

fn to_blob(x: &[f64]) -> Vec<u8> {
    x.iter().flat_map(|v| v.to_le_bytes()).collect()
}

fn from_blob(b: &[u8]) -> Vec<f64> {
    b.chunks_exact(8)
        .map(|c| {
            let mut a = [0u8; 8];
            a.copy_from_slice(c);
            f64::from_le_bytes(a)
        })
        .collect()
}

pub fn save_point(store: &Store, name: &str, nume_ordre: i64, omega: f64, x: &[f64]) -> Result<()> {
    PointWriter::new(store, name)?.point(nume_ordre, omega, x)
}

const INSERT_POINT: &str =
    "INSERT OR REPLACE INTO mnl_points(concept, NUME_ORDRE, omega, n, x) VALUES (?1, ?2, ?3, ?4, ?5)";

/// Rows of the Fourier table written by one statement: fewer statement executions
/// (what dominates inserting small rows), a statement small enough to prepare once.
const FOURIER_ROWS_PER_INSERT: usize = 64;

fn fourier_insert_sql(rows: usize) -> String {
    let mut sql = String::from(
        "INSERT INTO mnl_fourier(concept, NUME_ORDRE, NOEUD, NOM_CMP, HARM, COEF_C, COEF_S) VALUES ",
    );
    for r in 0..rows {
        if r > 0 {
            sql.push(',');
        }
        sql.push_str("(?,?,?,?,?,?,?)");
    }
    sql
}

/// Writes the points of one MODE_NON_LINE concept and their Fourier coefficients: the
/// schema checked once, the statements prepared once (SQLite's statement cache), the
/// Fourier rows inserted FOURIER_ROWS_PER_INSERT at a time. Inside the operator's
/// transaction like every write.
pub struct PointWriter<'a> {
    store: &'a Store,
    name: &'a str,
    pending: Vec<(i64, usize, usize, f64, f64)>,
    dofs: Vec<(String, String)>,
}

impl<'a> PointWriter<'a> {
    pub fn new(store: &'a Store, name: &'a str) -> Result<PointWriter<'a>> {
        ensure_schema(store)?;
        Ok(PointWriter {
            store,
            name,
            pending: Vec::with_capacity(FOURIER_ROWS_PER_INSERT),
            dofs: Vec::new(),
        })
    }

    /// The full unknown vector of row `nume_ordre`.
    pub fn point(&mut self, nume_ordre: i64, omega: f64, x: &[f64]) -> Result<()> {
        let mut stmt = self.store.conn().prepare_cached(INSERT_POINT)?;
        stmt.execute(params![
            self.name,
            nume_ordre,
            omega,
            x.len() as i64,
            to_blob(x)
        ])?;
        Ok(())
    }

    /// The displacement coefficients of row `nume_ordre`: `coefs[d]` holds DOF `dofs[d]`'s
    /// 2H+1 coefficients ordered 0, C1..CH, S1..SH (HARM 0 gets COEF_S = 0).
    pub fn fourier(
        &mut self,
        nume_ordre: i64,
        dofs: &[(String, String)],
        coefs: &[Vec<f64>],
    ) -> Result<()> {
        if self.dofs.as_slice() != dofs {
            self.flush()?;
            self.dofs = dofs.to_vec();
        }
        for (d, c) in coefs.iter().enumerate().take(dofs.len()) {
            let h = c.len().saturating_sub(1) / 2;
            for k in 0..=h {
                let (cc, cs) = if k == 0 {
                    (c[0], 0.0)
                } else {
                    (c[k], c[h + k])
                };
                self.pending.push((nume_ordre, d, k, cc, cs));
                if self.pending.len() == FOURIER_ROWS_PER_INSERT {
                    self.flush()?;
                }
            }
        }
        Ok(())
    }

    /// Write the rows still pending (also done by `finish`).
    fn flush(&mut self) -> Result<()> {
        if self.pending.is_empty() {
            return Ok(());
        }
        let conn = self.store.conn();
        let mut stmt = conn.prepare_cached(&fourier_insert_sql(self.pending.len()))?;
        let mut values: Vec<&dyn rusqlite::ToSql> = Vec::with_capacity(7 * self.pending.len());
        let harm: Vec<i64> = self.pending.iter().map(|r| r.2 as i64).collect();
        for (r, h) in self.pending.iter().zip(&harm) {
            let (node, cmp) = &self.dofs[r.1];
            values.extend_from_slice(&[
                &self.name as &dyn rusqlite::ToSql,
                &r.0,
                node,
                cmp,
                h,
                &r.3,
                &r.4,
            ]);
        }
        stmt.execute(values.as_slice())?;
        drop(stmt);
        self.pending.clear();
        Ok(())
    }

    /// Write what is pending; the writer is done.
    pub fn finish(mut self) -> Result<()> {
        self.flush()
    }
}

/// The stored unknown vector of row `nume_ordre`, if any.
pub fn load_point(store: &Store, name: &str, nume_ordre: i64) -> Result<Option<Vec<f64>>> {
    ensure_schema(store)?;
    let row: Option<(i64, Vec<u8>)> = store.row(
        "SELECT n, x FROM mnl_points WHERE concept = ?1 AND NUME_ORDRE = ?2",
        params![name, nume_ordre],
        |r| Ok((r.get(0)?, r.get(1)?)),
    )?;
    match row {
        None => Ok(None),
        Some((n, blob)) => {
            let x = from_blob(&blob);
            if x.len() as i64 != n {
                return Err(Error::store(format!(
                    "row {nume_ordre} of {name}: stored point is damaged ({} values, {n} expected)",
                    x.len()
                )));
            }
            Ok(Some(x))
        }
    }
}

/// Write the displacement Fourier coefficients of one row: `coefs[d]` holds DOF `dofs[d]`'s
/// 2H+1 coefficients ordered 0, C1..CH, S1..SH.
pub fn save_fourier(
    store: &Store,
    name: &str,
    nume_ordre: i64,
    dofs: &[(String, String)],
    coefs: &[Vec<f64>],
) -> Result<()> {
    let mut w = PointWriter::new(store, name)?;
    w.fourier(nume_ordre, dofs, coefs)?;
    w.finish()
}

/// Replace the Floquet multipliers stored for row `nume_ordre`.
pub fn save_multipliers(
    store: &Store,
    name: &str,
    nume_ordre: i64,
    multipliers: &[(f64, f64)],
) -> Result<()> {
    ensure_schema(store)?;
    store.exec(
        "DELETE FROM mnl_floquet WHERE concept = ?1 AND NUME_ORDRE = ?2",
        params![name, nume_ordre],
    )?;
    let mut stmt = store.conn().prepare_cached(
        "INSERT INTO mnl_floquet(concept, NUME_ORDRE, NUME_MULT, PARTIE_REELLE, PARTIE_IMAG, MODULE)
         VALUES (?1, ?2, ?3, ?4, ?5, ?6)",
    )?;
    for (i, (re, im)) in multipliers.iter().enumerate() {
        stmt.execute(params![
            name,
            nume_ordre,
            i as i64 + 1,
            re,
            im,
            re.hypot(*im)
        ])?;
    }
    Ok(())
}

/// Store the columns of a reduced run's basis (replacing any stored before).
pub fn save_basis(store: &Store, name: &str, basis: &Reduction) -> Result<()> {
    ensure_schema(store)?;
    store.exec("DELETE FROM mnl_basis WHERE concept = ?1", params![name])?;
    let b = basis.retained.len();
    let mut stmt = store.conn().prepare_cached(
        "INSERT INTO mnl_basis(concept, NUME_VECT, omega2, residual, n, v)
         VALUES (?1, ?2, ?3, ?4, ?5, ?6)",
    )?;
    for (j, col) in basis.columns.iter().enumerate() {
        let mode = j.checked_sub(b);
        let omega2 = mode.and_then(|i| basis.omega2.get(i).copied());
        let residual = mode.and_then(|i| basis.residuals.get(i).copied());
        stmt.execute(params![
            name,
            j as i64 + 1,
            omega2,
            residual,
            col.len() as i64,
            to_blob(col)
        ])?;
    }
    Ok(())
}

/// The basis of a reduced run, as `save_basis` stored it.
pub fn load_basis(store: &Store, name: &str, red: &StoredReduction) -> Result<Reduction> {
    ensure_schema(store)?;
    let mut stmt = store.conn().prepare_cached(
        "SELECT NUME_VECT, omega2, residual, n, v FROM mnl_basis WHERE concept = ?1
         ORDER BY NUME_VECT",
    )?;
    let rows = stmt.query_map(params![name], |r| {
        Ok((
            r.get::<_, i64>(0)?,
            r.get::<_, Option<f64>>(1)?,
            r.get::<_, Option<f64>>(2)?,
            r.get::<_, i64>(3)?,
            r.get::<_, Vec<u8>>(4)?,
        ))
    })?;
    let damaged = |what: String| Error::store(format!("{name}: stored reduction basis {what}"));
    let (mut columns, mut omega2, mut residuals) = (Vec::new(), Vec::new(), Vec::new());
    for (j, row) in rows.enumerate() {
        let (order, w, residual, n, blob) = row?;
        let col = from_blob(&blob);
        if order != j as i64 + 1 || col.len() as i64 != n {
            return Err(damaged(format!("is damaged at vector {order}")));
        }
        if let Some(w) = w {
            omega2.push(w);
            // A mode without its residual is not known exact: its couplings are computed.
            residuals.push(residual.unwrap_or(f64::INFINITY));
        }
        columns.push(col);
    }
    let n = columns.first().map_or(0, Vec::len);
    if columns.len() != red.retained.len() + red.modes
        || omega2.len() != red.modes
        || columns.iter().any(|c| c.len() != n)
    {
        return Err(damaged(format!(
            "has {} vectors, {} expected",
            columns.len(),
            red.retained.len() + red.modes
        )));
    }
    Ok(Reduction {
        n,
        retained: red.retained.clone(),
        omega2,
        residuals,
        columns,
    })
}

/// Copy everything MODE_NON_LINE stored for `from` (setup, points, Fourier coefficients,
/// reduction basis, multipliers) to the new concept `to`.
pub fn copy_data(store: &Store, from: &str, to: &str) -> Result<()> {
    ensure_schema(store)?;
    save_setup(store, to, &load_setup(store, from)?)?;
    store.exec(
        "INSERT INTO mnl_points(concept, NUME_ORDRE, omega, n, x)
         SELECT ?2, NUME_ORDRE, omega, n, x FROM mnl_points WHERE concept = ?1",
        params![from, to],
    )?;
    store.exec(
        "INSERT INTO mnl_fourier(concept, NUME_ORDRE, NOEUD, NOM_CMP, HARM, COEF_C, COEF_S)
         SELECT ?2, NUME_ORDRE, NOEUD, NOM_CMP, HARM, COEF_C, COEF_S FROM mnl_fourier WHERE concept = ?1",
        params![from, to],
    )?;
    store.exec(
        "INSERT INTO mnl_basis(concept, NUME_VECT, omega2, residual, n, v)
         SELECT ?2, NUME_VECT, omega2, residual, n, v FROM mnl_basis WHERE concept = ?1",
        params![from, to],
    )?;
    store.exec(
        "INSERT INTO mnl_floquet(concept, NUME_ORDRE, NUME_MULT, PARTIE_REELLE, PARTIE_IMAG, MODULE)
         SELECT ?2, NUME_ORDRE, NUME_MULT, PARTIE_REELLE, PARTIE_IMAG, MODULE FROM mnl_floquet WHERE concept = ?1",
        params![from, to],
    )?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_reduction_basis_round_trips_is_copied_and_dropped() {
        let s = Store::in_memory().unwrap();
        for c in ["MNL", "COPY"] {
            s.register_concept(c, "table_container", "MODE_NON_LINE", "a.comm", 1)
                .unwrap();
        }
        let basis = Reduction {
            n: 3,
            retained: vec![1],
            omega2: vec![4.0, 9.5],
            residuals: vec![1e-14, 3e-6],
            columns: vec![
                vec![0.5, 1.0, -0.25],
                vec![0.1, 0.0, 0.7],
                vec![1e-300, 0.0, 3.0],
            ],
        };
        save_basis(&s, "MNL", &basis).unwrap();
        let stored = StoredReduction {
            retained: vec![1],
            modes: 2,
        };
        let back = load_basis(&s, "MNL", &stored).unwrap();
        assert_eq!((back.n, &back.retained), (3, &basis.retained));
        assert_eq!(
            (&back.omega2, &back.columns),
            (&basis.omega2, &basis.columns)
        );
        assert_eq!(back.residuals, basis.residuals);
        // A setup that expects another count is refused, not misread.
        let wrong = StoredReduction {
            retained: vec![1],
            modes: 3,
        };
        assert!(load_basis(&s, "MNL", &wrong).is_err());
        save_setup(
            &s,
            "MNL",
            &MnlSetup {
                h_lin: 1,
                h_nonl: 4,
                matr_rigi: "K".into(),
                matr_mass: "M".into(),
                shocks: vec![],
                cara_choc: "MNL_CHOC".into(),
                reduction: Some(stored.clone()),
            },
        )
        .unwrap();
        copy_data(&s, "MNL", "COPY").unwrap();
        assert_eq!(
            load_basis(&s, "COPY", &stored).unwrap().columns,
            basis.columns
        );
        drop_data(&s, "MNL").unwrap();
        assert!(load_basis(&s, "MNL", &stored).is_err());
    }

    #[test]
    fn point_round_trip_is_exact() {
        let s = Store::in_memory().unwrap();
        s.register_concept("MNL", "table_container", "MODE_NON_LINE", "a.comm", 1)
            .unwrap();
        let x = vec![1.0, -2.5e-300, f64::MAX, 0.1 + 0.2];
        save_point(&s, "MNL", 3, 2.5, &x).unwrap();
        assert_eq!(load_point(&s, "MNL", 3).unwrap(), Some(x));
        assert_eq!(load_point(&s, "MNL", 4).unwrap(), None);
    }

    #[test]
    fn batched_fourier_rows_are_the_coefficients_in_order() {
        let s = Store::in_memory().unwrap();
        s.register_concept("MNL", "table_container", "MODE_NON_LINE", "a.comm", 1)
            .unwrap();
        // 3 DOFs × 2 rows × (H + 1 = 40) harmonics: flushes at 64 and a remainder.
        let dofs: Vec<(String, String)> = (0..3)
            .map(|i| (format!("N{i}"), "DX".to_string()))
            .collect();
        let h = 39;
        let coefs = |row: i64| -> Vec<Vec<f64>> {
            (0..3)
                .map(|d| {
                    (0..2 * h + 1)
                        .map(|j| row as f64 * 1000.0 + d as f64 * 100.0 + j as f64)
                        .collect()
                })
                .collect()
        };
        let mut w = PointWriter::new(&s, "MNL").unwrap();
        for row in 1..=2 {
            w.fourier(row, &dofs, &coefs(row)).unwrap();
        }
        w.finish().unwrap();
        let n: i64 = s
            .conn()
            .query_row("SELECT count(*) FROM mnl_fourier", [], |r| r.get(0))
            .unwrap();
        assert_eq!(n, 2 * 3 * (h as i64 + 1));
        let (c, sn): (f64, f64) = s
            .conn()
            .query_row(
                "SELECT COEF_C, COEF_S FROM mnl_fourier WHERE NUME_ORDRE = 2 AND NOEUD = 'N1' AND HARM = 7",
                [],
                |r| Ok((r.get(0)?, r.get(1)?)),
            )
            .unwrap();
        assert_eq!((c, sn), (2107.0, 2000.0 + 100.0 + (h + 7) as f64));
        let s0: f64 = s
            .conn()
            .query_row(
                "SELECT COEF_S FROM mnl_fourier WHERE NUME_ORDRE = 1 AND NOEUD = 'N2' AND HARM = 0",
                [],
                |r| r.get(0),
            )
            .unwrap();
        assert_eq!(s0, 0.0);
    }
}
