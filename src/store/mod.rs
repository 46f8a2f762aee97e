//! The concept store: one SQLite file per study.
//!
//! Layout:
//! - `meta(key, value)`: schema version and creation info.
//! - `concepts(name, type, operator, file, line, created_at)`: one row per concept.
//! - `concept_data(concept, key, json)`: serde-encoded payloads of concepts that users do
//!   not query row by row (models, materials, element characteristics, loads...).
//! - typed tables, one family per kind of data, written by the submodules
//!   (`store::table`, `store::mesh`, `store::matrix`, ...). Every table concept `T` is also a
//!   real SQL table named `T` (see `store::table`).
//!
//! Each operator runs inside one transaction ([`Store::begin_op`] / [`Store::commit_op`] /
//! [`Store::rollback_op`]): an operator that fails leaves the file exactly as before.

pub mod deps;
pub mod dyna_trans;
pub mod function;
pub mod matrix;
pub mod mesh;
pub mod mnl;
pub mod model;
pub mod modes;
pub mod study_file;
pub mod table;

use crate::error::{Error, Result};
use rusqlite::{params, Connection, OptionalExtension};
use serde::{de::DeserializeOwned, Serialize};
use std::path::{Path, PathBuf};

/// Version of the schema written by this build. Bump it when the layout changes.
pub const SCHEMA_VERSION: i64 = 1;

pub struct Store {
    conn: Connection,
    path: Option<PathBuf>,
    /// The run's exclusive lock on the study (none for in-memory and read-only stores).
    /// Declared after `conn` so that the connection closes before the lock is released.
    _lock: Option<study_file::StudyLock>,
}

/// One row of the `concepts` table.
#[derive(Clone, Debug, PartialEq)]
pub struct ConceptInfo {
    pub name: String,
    pub ty: String,
    pub operator: String,
    pub file: String,
    pub line: i64,
    pub created_at: String,
}

const CORE_SCHEMA: &str = "
CREATE TABLE IF NOT EXISTS meta (key TEXT PRIMARY KEY, value TEXT NOT NULL);
CREATE TABLE IF NOT EXISTS concepts (
    name TEXT PRIMARY KEY,
    type TEXT NOT NULL,
    operator TEXT NOT NULL,
    file TEXT NOT NULL,
    line INTEGER NOT NULL,
    created_at TEXT NOT NULL DEFAULT (strftime('%Y-%m-%dT%H:%M:%fZ','now'))
);
CREATE TABLE IF NOT EXISTS concept_data (
    concept TEXT NOT NULL REFERENCES concepts(name) ON DELETE CASCADE,
    key TEXT NOT NULL,
    json TEXT NOT NULL,
    PRIMARY KEY (concept, key)
);
";

impl Store {
    /// Start a new study (DEBUT). The study is locked first (a second run on it is refused);
    /// an existing file at `path` is replaced only if it is an aster-nl database
    /// (see [`study_file`]); `purpose` names the run in the lock file.
    pub fn create(path: &Path) -> Result<Store> {
        Self::create_for(path, "a study")
    }

    /// [`Store::create`] recording `purpose` (e.g. the command file) in the lock.
    pub fn create_for(path: &Path, purpose: &str) -> Result<Store> {
        let lock = study_file::StudyLock::acquire(path, purpose)?;
        let replace = study_file::check_replaceable(path)?;
        study_file::check_writable(path)?;
        if replace {
            // Our lock is held, so no aster-nl run uses these: a journal left by a killed
            // run of the old study must not be applied to the new one.
            for j in study_file::journal_paths(path) {
                if matches!(
                    study_file::file_kind(&j)?,
                    study_file::FileKind::OtherFile | study_file::FileKind::Sqlite
                ) {
                    let _ = std::fs::remove_file(&j);
                }
            }
            std::fs::remove_file(path).map_err(|e| {
                Error::store(format!(
                    "cannot replace the database {}: {e}",
                    path.display()
                ))
            })?;
        }
        let conn = Connection::open(path)?;
        let store = Store {
            conn,
            path: Some(path.to_path_buf()),
            _lock: Some(lock),
        };
        store.init_schema()?;
        Ok(store)
    }

    /// Continue a study (POURSUITE): the file must exist, carry a schema we know and be
    /// writable; the study is locked for as long as the store lives.
    pub fn open(path: &Path) -> Result<Store> {
        Self::open_for(path, "a study")
    }

    /// [`Store::open`] recording `purpose` (e.g. the command file) in the lock.
    pub fn open_for(path: &Path, purpose: &str) -> Result<Store> {
        let lock = study_file::StudyLock::acquire(path, purpose)?;
        study_file::check_openable(path)?;
        study_file::check_writable(path)?;
        let conn = Connection::open(path)?;
        let store = Store {
            conn,
            path: Some(path.to_path_buf()),
            _lock: Some(lock),
        };
        store.check_schema()?;
        // A study written before dependencies were recorded gets the tables now.
        store.conn.execute_batch(deps::SCHEMA)?;
        Ok(store)
    }

    /// Open a study to read it (`aster-nl tables`): no lock, nothing written, so it works
    /// while a run holds the study.
    pub fn open_read_only(path: &Path) -> Result<Store> {
        use rusqlite::OpenFlags;
        study_file::check_openable(path)?;
        let conn = Connection::open_with_flags(path, OpenFlags::SQLITE_OPEN_READ_ONLY)?;
        let store = Store {
            conn,
            path: Some(path.to_path_buf()),
            _lock: None,
        };
        store.check_schema()?;
        Ok(store)
    }

    /// A store that lives in memory (tests, `check`).
    pub fn in_memory() -> Result<Store> {
        let store = Store {
            conn: Connection::open_in_memory()?,
            path: None,
            _lock: None,
        };
        store.init_schema()?;
        Ok(store)
    }

    pub fn path(&self) -> Option<&Path> {
        self.path.as_deref()
    }

    /// The underlying connection, for the typed submodules of `store`.
    pub fn conn(&self) -> &Connection {
        &self.conn
    }

    fn init_schema(&self) -> Result<()> {
        // Outside any transaction (SQLite ignores it inside one).
        self.conn.execute_batch("PRAGMA foreign_keys = ON;")?;
        // One transaction for the whole schema: each statement on its own would commit (and
        // sync the file) once per table.
        self.conn.execute_batch("BEGIN IMMEDIATE")?;
        let done = (|| -> Result<()> {
            self.conn.execute_batch(CORE_SCHEMA)?;
            self.conn.execute_batch(deps::SCHEMA)?;
            self.conn.execute(
                "INSERT OR REPLACE INTO meta(key, value) VALUES ('schema_version', ?1)",
                params![SCHEMA_VERSION.to_string()],
            )?;
            self.conn.execute(
                "INSERT OR REPLACE INTO meta(key, value) VALUES ('producer', ?1)",
                params![format!("aster-nl {}", env!("CARGO_PKG_VERSION"))],
            )?;
            Ok(())
        })();
        match done {
            Ok(()) => self.conn.execute_batch("COMMIT")?,
            Err(e) => {
                let _ = self.conn.execute_batch("ROLLBACK");
                return Err(e);
            }
        }
        Ok(())
    }

    fn check_schema(&self) -> Result<()> {
        let where_ = self
            .path
            .as_ref()
            .map(|p| p.display().to_string())
            .unwrap_or_default();
        let has_meta: bool = self
            .conn
            .query_row(
                "SELECT count(*) FROM sqlite_master WHERE type='table' AND name='meta'",
                [],
                |r| r.get::<_, i64>(0),
            )
            .map_err(|e| Error::store(format!("{where_} is not an aster-nl database: {e}")))?
            > 0;
        if !has_meta {
            return Err(Error::store(format!(
                "{where_} is not an aster-nl database (no meta table)"
            )));
        }
        let version: Option<String> = self
            .conn
            .query_row(
                "SELECT value FROM meta WHERE key='schema_version'",
                [],
                |r| r.get(0),
            )
            .optional()?;
        let version = version
            .and_then(|v| v.parse::<i64>().ok())
            .ok_or_else(|| Error::store(format!("{where_} has no readable schema version")))?;
        if version != SCHEMA_VERSION {
            return Err(Error::store(format!(
                "{where_} has schema version {version}, this aster-nl reads version {SCHEMA_VERSION}"
            ))
            .hint(if version > SCHEMA_VERSION {
                "the file was written by a newer aster-nl; use that version"
            } else {
                "the file was written by an older aster-nl; rerun the study from DEBUT"
            }));
        }
        self.conn.execute_batch("PRAGMA foreign_keys = ON;")?;
        Ok(())
    }

    /// Start the transaction of one operator.
    pub fn begin_op(&self) -> Result<()> {
        self.conn.execute_batch("BEGIN IMMEDIATE")?;
        Ok(())
    }
    pub fn commit_op(&self) -> Result<()> {
        self.conn.execute_batch("COMMIT")?;
        Ok(())
    }
    /// Undo everything the failed operator wrote. Errors here are ignored on purpose: the
    /// rollback is already the error path, and SQLite rolls back on its own if it can't.
    pub fn rollback_op(&self) {
        let _ = self.conn.execute_batch("ROLLBACK");
    }

    /// Record a new concept (or replace the record of a concept with the same name, as
    /// Code_Aster does when a name is reassigned: its old data is removed first).
    pub fn register_concept(
        &self,
        name: &str,
        ty: &str,
        operator: &str,
        file: &str,
        line: usize,
    ) -> Result<()> {
        if self.concept_type(name)?.is_some() {
            // A name given again drops what went with its old concept (a MODE_NON_LINE
            // result's shock table), as DETRUIRE does: else that table would outlive the
            // result it describes.
            for owned in mnl::owned_concepts(self, name)? {
                self.delete_concept(&owned)?;
            }
            self.delete_concept(name)?;
        }
        self.conn.execute(
            "INSERT INTO concepts(name, type, operator, file, line) VALUES (?1, ?2, ?3, ?4, ?5)",
            params![name, ty, operator, file, line as i64],
        )?;
        self.new_generation(name)?;
        Ok(())
    }

    pub fn concept_type(&self, name: &str) -> Result<Option<String>> {
        // Cached: tables look up every text cell of every row (save_table), and a statement
        // prepared per call costs more than the lookup.
        Ok(self
            .conn
            .prepare_cached("SELECT type FROM concepts WHERE name = ?1")?
            .query_row(params![name], |r| r.get(0))
            .optional()?)
    }

    /// The operator that created concept `name`, if it exists.
    pub fn concept_operator(&self, name: &str) -> Result<Option<String>> {
        Ok(self
            .conn
            .prepare_cached("SELECT operator FROM concepts WHERE name = ?1")?
            .query_row(params![name], |r| r.get(0))
            .optional()?)
    }

    pub fn concepts(&self) -> Result<Vec<ConceptInfo>> {
        let mut stmt = self.conn.prepare(
            "SELECT name, type, operator, file, line, created_at FROM concepts ORDER BY rowid",
        )?;
        let rows = stmt.query_map([], |r| {
            Ok(ConceptInfo {
                name: r.get(0)?,
                ty: r.get(1)?,
                operator: r.get(2)?,
                file: r.get(3)?,
                line: r.get(4)?,
                created_at: r.get(5)?,
            })
        })?;
        Ok(rows.collect::<rusqlite::Result<Vec<_>>>()?)
    }

    /// Remove a concept and everything stored for it. Typed submodules register their
    /// cleanup in [`Store::drop_typed_data`].
    pub fn delete_concept(&self, name: &str) -> Result<()> {
        self.drop_typed_data(name)?;
        self.drop_dependency_data(name)?;
        self.conn
            .execute("DELETE FROM concept_data WHERE concept = ?1", params![name])?;
        self.conn
            .execute("DELETE FROM concepts WHERE name = ?1", params![name])?;
        Ok(())
    }

    /// Delete the rows a concept owns in the typed tables. Each typed submodule adds its
    /// own cleanup here.
    fn drop_typed_data(&self, name: &str) -> Result<()> {
        table::drop_table_data(self, name)?;
        matrix::drop_data(self, name)?;
        mesh::delete_mesh(&self.conn, name)?;
        modes::drop_data(self, name)?;
        mnl::drop_data(self, name)?;
        Ok(())
    }

    /// Store a serde payload under (concept, key).
    pub fn put_json<T: Serialize>(&self, concept: &str, key: &str, value: &T) -> Result<()> {
        let json = serde_json::to_string(value)?;
        self.conn.execute(
            "INSERT OR REPLACE INTO concept_data(concept, key, json) VALUES (?1, ?2, ?3)",
            params![concept, key, json],
        )?;
        Ok(())
    }

    /// Read a serde payload stored under (concept, key).
    pub fn get_json<T: DeserializeOwned>(&self, concept: &str, key: &str) -> Result<T> {
        let json: Option<String> = self
            .conn
            .query_row(
                "SELECT json FROM concept_data WHERE concept = ?1 AND key = ?2",
                params![concept, key],
                |r| r.get(0),
            )
            .optional()?;
        let json = json
            .ok_or_else(|| Error::store(format!("concept {concept} has no stored '{key}' data")))?;
        Ok(serde_json::from_str(&json)?)
    }
}

/// Text listing of a database for `aster-nl tables`: concepts, then every SQL table with
/// its row count.
pub fn listing(store: &Store) -> Result<String> {
    let mut text = String::from("concepts:\n");
    for c in store.concepts()? {
        text.push_str(&format!(
            "  {:<16} {:<20} {:<16} {}:{}  {}\n",
            c.name, c.ty, c.operator, c.file, c.line, c.created_at
        ));
    }
    text.push_str("SQL tables:\n");
    let names: Vec<String> = {
        let mut stmt = store
            .conn()
            .prepare("SELECT name FROM sqlite_master WHERE type='table' ORDER BY name")?;
        let rows = stmt.query_map([], |r| r.get(0))?;
        rows.collect::<rusqlite::Result<Vec<String>>>()?
    };
    for name in names {
        let quoted = name.replace('"', "\"\"");
        let n: i64 =
            store
                .conn()
                .query_row(&format!("SELECT count(*) FROM \"{quoted}\""), [], |r| {
                    r.get(0)
                })?;
        text.push_str(&format!("  {name:<24} {n:>8} rows\n"));
    }
    Ok(text)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn failed_operator_rolls_back() {
        let s = Store::in_memory().unwrap();
        s.begin_op().unwrap();
        s.register_concept("A", "table_sdaster", "CREA_TABLE", "x.comm", 1)
            .unwrap();
        s.commit_op().unwrap();
        s.begin_op().unwrap();
        s.register_concept("B", "table_sdaster", "CREA_TABLE", "x.comm", 2)
            .unwrap();
        s.delete_concept("A").unwrap();
        s.rollback_op();
        let names: Vec<String> = s.concepts().unwrap().into_iter().map(|c| c.name).collect();
        assert_eq!(names, vec!["A".to_string()]);
    }

    #[test]
    fn newer_schema_is_refused() {
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("s.db");
        {
            let s = Store::create(&p).unwrap();
            s.conn()
                .execute("UPDATE meta SET value='99' WHERE key='schema_version'", [])
                .unwrap();
        }
        let err = Store::open(&p).err().unwrap();
        assert!(err.message.contains("schema version 99"), "{err}");
    }
}
