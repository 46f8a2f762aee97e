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
//!
//! Durability ([`Durability`], docs/store.md "Durability"): a study that DEBUT creates is
//! synced to disk once, when its run ends; a study that POURSUITE continues, at every
//! commit.

pub mod batch;
mod conversions;
pub mod deps;
pub mod dyna_trans;
pub mod function;
pub mod gene;
pub mod live;
pub mod matrix;
pub mod mesh;
pub mod mnl;
pub mod model;
pub mod modes;
pub(crate) mod own_file;
pub mod recovery;
pub mod study_file;
pub mod study_lock;
pub mod table;
pub mod tran_gene;

use crate::error::{Error, Result};
use rusqlite::{params, Connection, OptionalExtension, Params};
use serde::{de::DeserializeOwned, Serialize};
use std::cell::Cell;
use std::path::{Path, PathBuf};

/// Version of the schema written by this build. Bump it when the layout changes.
pub const SCHEMA_VERSION: i64 = 1;

pub struct Store {
    conn: Connection,
    path: Option<PathBuf>,
    /// The typed-table schemas ([`Schema`]) known to exist on this connection, one bit each.
    schemas: Cell<u32>,
    /// When the file reaches the disk; `RunEnd` until [`Store::close`] has synced it.
    durability: Durability,
    /// The run's exclusive lock on the study (none for in-memory and read-only stores).
    /// Declared after `conn` so that the connection closes before the lock is released.
    _lock: Option<study_file::StudyLock>,
    /// The rolled-back copy a read-only store reads when a killed run left the study with a
    /// hot journal (removed when the store is dropped, after the connection closes).
    _recovered: Option<recovery::RecoveredCopy>,
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

/// The schemas of the typed submodules. Each is a batch of `CREATE ... IF NOT EXISTS`
/// statements run on first use ([`Store::ensure_schema`]): a study only gets the tables it
/// uses, and a study written by an older aster-nl gets the ones it lacks when POURSUITE
/// first needs them.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Schema {
    Table = 1,
    Mesh = 2,
    Matrix = 4,
    Modes = 8,
    Mnl = 16,
    Gene = 32,
}

/// When a study's writes are forced to the disk (`fsync`). Either way each operator is one
/// transaction of SQLite's rollback journal: an operator that fails, and a run that is
/// killed, leave the file as the last committed operator left it (the kernel has every
/// write a killed process made). What the two differ in is an operating-system crash or a
/// power cut during a run.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Durability {
    /// A new study (DEBUT): no sync per commit and the journal file kept between commits
    /// (`synchronous = OFF`, `journal_mode = PERSIST`), one sync of the file and its
    /// directory when the run ends ([`Store::close`]), the journal then removed. A crash
    /// of the system during the run may leave the study unreadable; nothing older is at
    /// stake (DEBUT has replaced it), and rerunning the command file rebuilds it. Measured
    /// on sdnd122a: the per-commit syncs and the journal's creation and removal are 7 %
    /// (quiet machine) to 16 % (loaded) of a run's CPU time (docs/performance_history.md, seventh
    /// round).
    RunEnd,
    /// A continued study (POURSUITE): SQLite's defaults (`synchronous = FULL`, the journal
    /// deleted at each commit), so that a system crash during the run cannot take the
    /// results of earlier runs with it.
    EveryCommit,
    /// Nothing to sync (in memory, read-only, or already closed).
    None,
}

/// The pragmas of [`Durability::RunEnd`], set before the first transaction.
const RUN_END_PRAGMAS: &str = "PRAGMA journal_mode = PERSIST; PRAGMA synchronous = OFF;";

/// Statements kept prepared per connection. Every fixed statement of the store fits (a run
/// uses about sixty), so none is parsed twice; the SQL of a table concept (its name is in
/// the text) passes through once per save and evicts the least recently used.
const STATEMENT_CACHE: usize = 128;

/// Where DEBUT prepares a new study before renaming it to `path`: `.<name>.new-<pid>`
/// beside it.
fn fresh_study_path(path: &Path) -> PathBuf {
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    path.with_file_name(format!(".{name}.new-{}", std::process::id()))
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
        // Beside a new study, a journal is not ours; beside our study, it is its journal.
        study_file::check_journals(path, replace)?;
        study_file::check_writable(path)?;
        // The new study is made whole beside its place, schema marker committed, then
        // renamed into it: a run killed during DEBUT never leaves a file without the
        // marker at the study's path (only, at worst, that temporary).
        let fresh = fresh_study_path(path);
        let made = own_file::create_new(&fresh).map_err(|e| {
            Error::store(format!(
                "cannot create {}, where the new study is prepared: {e}",
                fresh.display()
            ))
            .hint("the directory of the database must be writable")
        })?;
        let prepared = (|| -> Result<()> {
            let new = Store::with(Connection::open(&fresh)?, None, None);
            new.init_schema()
        })();
        if let Err(e) = prepared {
            own_file::remove_if_ours(&made, &fresh);
            return Err(e);
        }
        if replace {
            // Our lock is held, so no aster-nl run uses these: a journal left by a killed
            // run of the old study must not be applied to the new one.
            for j in study_file::journal_paths(path) {
                if study_file::file_kind(&j)? != study_file::FileKind::Absent {
                    let _ = std::fs::remove_file(&j);
                }
            }
        }
        std::fs::rename(&fresh, path).map_err(|e| {
            own_file::remove_if_ours(&made, &fresh);
            Error::store(format!(
                "cannot create the database {}: {e}",
                path.display()
            ))
        })?;
        let mut store = Store::with(Connection::open(path)?, Some(path), Some(lock));
        store.conn.execute_batch(RUN_END_PRAGMAS)?;
        store.durability = Durability::RunEnd;
        store.conn.execute_batch("PRAGMA foreign_keys = ON;")?;
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
        study_file::check_journals(path, true)?;
        // Judged before SQLite opens it for writing, which would roll back the hot journal
        // of another program's database.
        study_file::check_marker(path)?;
        study_file::check_writable(path)?;
        let store = Store::with(Connection::open(path)?, Some(path), Some(lock));
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
        // A study a killed run left with a hot journal is read in a rolled-back copy: the
        // study itself is not written (the next run that writes rolls it back).
        let copy = if recovery::has_hot_journal(path) {
            Some(recovery::recovered_copy(path)?)
        } else {
            None
        };
        let read = copy.as_ref().map_or(path, |c| c.db());
        let conn = Connection::open_with_flags(read, OpenFlags::SQLITE_OPEN_READ_ONLY)?;
        let mut store = Store::with(conn, Some(path), None);
        store._recovered = copy;
        store.check_schema()?;
        Ok(store)
    }

    /// A store that lives in memory (tests, `check`).
    pub fn in_memory() -> Result<Store> {
        let store = Store::with(Connection::open_in_memory()?, None, None);
        store.init_schema()?;
        Ok(store)
    }

    fn with(conn: Connection, path: Option<&Path>, lock: Option<study_file::StudyLock>) -> Store {
        conn.set_prepared_statement_cache_capacity(STATEMENT_CACHE);
        let durability = match (path, &lock) {
            (Some(_), Some(_)) => Durability::EveryCommit,
            _ => Durability::None,
        };
        Store {
            conn,
            path: path.map(Path::to_path_buf),
            schemas: Cell::new(0),
            durability,
            _lock: lock,
            _recovered: None,
        }
    }

    /// How this store's writes reach the disk.
    pub fn durability(&self) -> Durability {
        self.durability
    }

    /// End the run's use of the study: a [`Durability::RunEnd`] study is synced (the
    /// database file and its directory) and its journal removed. Called when the run ends
    /// (FIN, or the store dropped after an error); further calls do nothing.
    pub fn close(&mut self) -> Result<()> {
        if self.durability != Durability::RunEnd {
            return Ok(());
        }
        self.durability = Durability::None;
        let Some(path) = self.path.clone() else {
            return Ok(());
        };
        if self.conn.is_autocommit() {
            // Back to SQLite's defaults: the kept journal file is deleted, and anything
            // written after this (nothing, in a run) is synced at its commit.
            self.conn
                .execute_batch("PRAGMA journal_mode = DELETE; PRAGMA synchronous = FULL;")?;
        }
        let sync = |p: &Path| std::fs::File::open(p).and_then(|f| f.sync_all());
        sync(&path).map_err(|e| {
            Error::store(format!("cannot sync the database {}: {e}", path.display()))
        })?;
        let dir = match path.parent() {
            Some(d) if !d.as_os_str().is_empty() => d.to_path_buf(),
            _ => PathBuf::from("."),
        };
        // The directory's entry of the new file (not every system lets one sync a
        // directory: an error there is not the study's).
        let _ = sync(&dir);
        Ok(())
    }

    pub fn path(&self) -> Option<&Path> {
        self.path.as_deref()
    }

    /// The underlying connection, for the typed submodules of `store`.
    pub fn conn(&self) -> &Connection {
        &self.conn
    }

    /// Run `sql` (a batch of `CREATE ... IF NOT EXISTS`) unless this connection already
    /// did for `which`: running it again per call would parse every statement of the batch
    /// each time. [`Store::rollback_op`] forgets them all, since a rollback may have
    /// undone the creation.
    pub(crate) fn ensure_schema(&self, which: Schema, sql: &str) -> Result<()> {
        let bit = which as u32;
        if self.schemas.get() & bit == 0 {
            self.conn.execute_batch(sql)?;
            self.schemas.set(self.schemas.get() | bit);
        }
        Ok(())
    }

    /// Execute one statement of fixed text, prepared once per connection (SQLite's
    /// statement cache) instead of per call. Not for SQL that names a table concept: each
    /// such text is used once and would only evict the fixed statements.
    pub(crate) fn exec<P: Params>(&self, sql: &str, params: P) -> Result<usize> {
        Ok(self.conn.prepare_cached(sql)?.execute(params)?)
    }

    /// The first row of a cached statement of fixed text (see [`Store::exec`]), if any.
    pub(crate) fn row<T, P: Params>(
        &self,
        sql: &str,
        params: P,
        f: impl FnOnce(&rusqlite::Row<'_>) -> rusqlite::Result<T>,
    ) -> Result<Option<T>> {
        Ok(self
            .conn
            .prepare_cached(sql)?
            .query_row(params, f)
            .optional()?)
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
        self.exec("BEGIN IMMEDIATE", [])?;
        Ok(())
    }
    pub fn commit_op(&self) -> Result<()> {
        self.exec("COMMIT", [])?;
        Ok(())
    }
    /// Undo everything the failed operator wrote. Errors here are ignored on purpose: the
    /// rollback is already the error path, and SQLite rolls back on its own if it can't.
    pub fn rollback_op(&self) {
        let _ = self.conn.execute_batch("ROLLBACK");
        // The operator may have created typed tables: they are gone with the rest.
        self.schemas.set(0);
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
        self.exec(
            "INSERT INTO concepts(name, type, operator, file, line) VALUES (?1, ?2, ?3, ?4, ?5)",
            params![name, ty, operator, file, line as i64],
        )?;
        self.new_generation(name)?;
        Ok(())
    }

    pub fn concept_type(&self, name: &str) -> Result<Option<String>> {
        self.row(
            "SELECT type FROM concepts WHERE name = ?1",
            params![name],
            |r| r.get(0),
        )
    }

    /// The operator that created concept `name`, if it exists.
    pub fn concept_operator(&self, name: &str) -> Result<Option<String>> {
        self.row(
            "SELECT operator FROM concepts WHERE name = ?1",
            params![name],
            |r| r.get(0),
        )
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
        self.exec("DELETE FROM concept_data WHERE concept = ?1", params![name])?;
        self.exec("DELETE FROM concepts WHERE name = ?1", params![name])?;
        Ok(())
    }

    /// Delete the rows a concept owns in the typed tables. Each typed submodule adds its
    /// own cleanup here.
    fn drop_typed_data(&self, name: &str) -> Result<()> {
        table::drop_table_data(self, name)?;
        matrix::drop_data(self, name)?;
        mesh::delete_mesh(self, name)?;
        modes::drop_data(self, name)?;
        mnl::drop_data(self, name)?;
        gene::drop_data(self, name)?;
        Ok(())
    }

    /// Store a serde payload under (concept, key).
    pub fn put_json<T: Serialize>(&self, concept: &str, key: &str, value: &T) -> Result<()> {
        let json = serde_json::to_string(value)?;
        self.exec(
            "INSERT OR REPLACE INTO concept_data(concept, key, json) VALUES (?1, ?2, ?3)",
            params![concept, key, json],
        )?;
        Ok(())
    }

    /// Read a serde payload stored under (concept, key), `None` when there is none.
    pub fn find_json<T: DeserializeOwned>(&self, concept: &str, key: &str) -> Result<Option<T>> {
        let json: Option<String> = self.row(
            "SELECT json FROM concept_data WHERE concept = ?1 AND key = ?2",
            params![concept, key],
            |r| r.get(0),
        )?;
        match json {
            Some(j) => Ok(Some(serde_json::from_str(&j)?)),
            None => Ok(None),
        }
    }

    /// Read a serde payload stored under (concept, key).
    pub fn get_json<T: DeserializeOwned>(&self, concept: &str, key: &str) -> Result<T> {
        let json: Option<String> = self.row(
            "SELECT json FROM concept_data WHERE concept = ?1 AND key = ?2",
            params![concept, key],
            |r| r.get(0),
        )?;
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

impl Drop for Store {
    /// A run that ends without FIN, or on an error, still syncs what it committed (errors
    /// are not reported here: the run's own error, if any, is the one to read).
    fn drop(&mut self) {
        let _ = self.close();
    }
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

    fn has_table(s: &Store, name: &str) -> bool {
        s.conn()
            .query_row(
                "SELECT count(*) FROM sqlite_master WHERE type='table' AND name=?1",
                params![name],
                |r| r.get::<_, i64>(0),
            )
            .unwrap()
            > 0
    }

    fn pragma(s: &Store, name: &str) -> String {
        s.conn()
            .query_row(&format!("PRAGMA {name}"), [], |r| {
                r.get::<_, rusqlite::types::Value>(0)
            })
            .map(|v| match v {
                rusqlite::types::Value::Text(t) => t,
                rusqlite::types::Value::Integer(i) => i.to_string(),
                other => format!("{other:?}"),
            })
            .unwrap()
    }

    fn journal_of(p: &Path) -> PathBuf {
        study_file::journal_paths(p)[0].clone()
    }

    /// One operator that creates table concept `name`, committed.
    fn commit_one_concept(s: &Store, name: &str) {
        s.begin_op().unwrap();
        s.register_concept(name, "table_sdaster", "CREA_TABLE", "x.comm", 1)
            .unwrap();
        s.commit_op().unwrap();
    }

    #[test]
    fn a_new_study_is_synced_at_the_end_and_leaves_no_journal() {
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("s.db");
        let mut s = Store::create(&p).unwrap();
        assert_eq!(s.durability(), Durability::RunEnd);
        assert_eq!(pragma(&s, "journal_mode"), "persist");
        assert_eq!(pragma(&s, "synchronous"), "0");
        commit_one_concept(&s, "A");
        // The journal is kept between commits (not created and deleted at each one).
        assert!(journal_of(&p).exists());
        s.close().unwrap();
        assert!(
            !journal_of(&p).exists(),
            "the run's end removes the journal"
        );
        assert_eq!(s.durability(), Durability::None);
        assert_eq!(pragma(&s, "journal_mode"), "delete");
        assert_eq!(pragma(&s, "synchronous"), "2");
        s.close().unwrap();
        drop(s);
        let again = Store::open(&p).unwrap();
        let names: Vec<String> = again
            .concepts()
            .unwrap()
            .into_iter()
            .map(|c| c.name)
            .collect();
        assert_eq!(names, vec!["A".to_string()]);
    }

    #[test]
    fn a_store_dropped_without_close_is_synced_too() {
        // A run that stops on an error never reaches FIN: dropping the store does the same.
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("s.db");
        {
            let s = Store::create(&p).unwrap();
            commit_one_concept(&s, "A");
            assert!(journal_of(&p).exists());
        }
        assert!(!journal_of(&p).exists());
    }

    #[test]
    fn a_continued_study_keeps_every_commit_synced() {
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("s.db");
        drop(Store::create(&p).unwrap());
        let mut s = Store::open(&p).unwrap();
        assert_eq!(s.durability(), Durability::EveryCommit);
        assert_eq!(pragma(&s, "journal_mode"), "delete");
        assert_eq!(pragma(&s, "synchronous"), "2");
        commit_one_concept(&s, "B");
        assert!(!journal_of(&p).exists());
        s.close().unwrap();
        assert_eq!(s.durability(), Durability::EveryCommit);
        assert_eq!(Store::in_memory().unwrap().durability(), Durability::None);
    }

    #[test]
    fn a_rolled_back_schema_is_created_again() {
        // The first operator to use the MODE_NON_LINE tables fails: its rollback removes
        // them, and the next operator must not take them as created.
        let s = Store::in_memory().unwrap();
        s.begin_op().unwrap();
        s.register_concept("MNL", "table_container", "MODE_NON_LINE", "x.comm", 1)
            .unwrap();
        mnl::save_point(&s, "MNL", 1, 2.0, &[1.0]).unwrap();
        assert!(has_table(&s, "mnl_points"));
        s.rollback_op();
        assert!(!has_table(&s, "mnl_points"));
        s.begin_op().unwrap();
        s.register_concept("MNL", "table_container", "MODE_NON_LINE", "x.comm", 2)
            .unwrap();
        mnl::save_point(&s, "MNL", 1, 2.0, &[1.0]).unwrap();
        s.commit_op().unwrap();
        assert_eq!(mnl::load_point(&s, "MNL", 1).unwrap(), Some(vec![1.0]));
    }

    #[test]
    fn poursuite_of_a_study_without_typed_tables_creates_them() {
        // A study whose runs never used the table and MODE_NON_LINE tables (or was written
        // before they existed): a POURSUITE store creates them on first use, once.
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("s.db");
        {
            let s = Store::create(&p).unwrap();
            s.begin_op().unwrap();
            s.register_concept("A", "fonction_sdaster", "DEFI_FONCTION", "x.comm", 1)
                .unwrap();
            s.commit_op().unwrap();
            assert!(!has_table(&s, "table_meta") && !has_table(&s, "mnl_points"));
        }
        let s = Store::open(&p).unwrap();
        s.begin_op().unwrap();
        s.register_concept("T", "table_sdaster", "CREA_TABLE", "y.comm", 1)
            .unwrap();
        let mut t = crate::table::Table::new("t");
        t.add_column("X", crate::table::ColKind::R).unwrap();
        t.push_row(vec![crate::table::Cell::R(1.5)]).unwrap();
        table::save_table(&s, "T", &t).unwrap();
        s.register_concept("MNL", "table_container", "MODE_NON_LINE", "y.comm", 2)
            .unwrap();
        mnl::save_point(&s, "MNL", 1, 2.0, &[3.0]).unwrap();
        mnl::save_point(&s, "MNL", 2, 2.0, &[4.0]).unwrap();
        s.commit_op().unwrap();
        assert_eq!(table::load_table(&s, "T").unwrap(), t);
        assert_eq!(mnl::load_point(&s, "MNL", 2).unwrap(), Some(vec![4.0]));
        drop(s);
        // And the next run reads them without creating anything.
        let s = Store::open(&p).unwrap();
        assert_eq!(mnl::load_point(&s, "MNL", 1).unwrap(), Some(vec![3.0]));
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
