//! The live file of a running MODE_NON_LINE: a small SQLite file beside the study that
//! holds the rows reached so far, one transaction per branch, so that a reader can watch
//! the frequency–energy curve grow (docs/store.md, "Watching a running MODE_NON_LINE").
//!
//! Why a side file: the operator's rows go into the study in one transaction committed
//! when it ends (a failed operator leaves the study as it was), and while that
//! transaction is open no other connection may write to the study. The live file is
//! another database, in WAL mode so that a reader never waits for the writer.
//!
//! It is ours only: created exclusively (`create_new`), marked by a table
//! `aster_nl_live`; a file of that name without the mark is never touched, the next name
//! (`.live2.db`, ...) is tried instead. A live file of an earlier run (marked) is replaced.

use crate::error::{Error, Result};
use rusqlite::{params, Connection};
use std::path::{Path, PathBuf};

/// The mark of a live file, and what it is about.
const MARK: &str = "aster_nl_live";

/// How many names (`.live.db`, `.live2.db`, ...) are tried before giving up.
const NAMES: usize = 9;

/// One row of the live table.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LiveRow {
    pub branch: usize,
    pub frequency: f64,
    pub energy: f64,
    pub bifurcation: bool,
}

/// An open live file.
pub struct LiveFile {
    conn: Connection,
    path: PathBuf,
    table: String,
    rows: i64,
}

/// `<study stem>.<concept>.live.db` (then `.live2.db`...) beside `study`.
pub fn candidate(study: &Path, concept: &str, k: usize) -> PathBuf {
    let stem = study
        .file_stem()
        .map_or_else(|| "study".into(), |s| s.to_string_lossy().to_string());
    let suffix = if k == 1 { String::new() } else { k.to_string() };
    study.with_file_name(format!("{stem}.{concept}.live{suffix}.db"))
}

/// Whether `path` is a live file of ours (an SQLite file with our mark).
pub fn is_ours(path: &Path) -> bool {
    if !crate::store::study_file::has_sqlite_header(path) {
        return false;
    }
    let Ok(c) = Connection::open_with_flags(path, rusqlite::OpenFlags::SQLITE_OPEN_READ_ONLY)
    else {
        return false;
    };
    c.query_row(
        "SELECT COUNT(*) FROM sqlite_master WHERE type = 'table' AND name = ?1",
        params![MARK],
        |r| r.get::<_, i64>(0),
    )
    .is_ok_and(|n| n == 1)
}

/// Remove a live file of ours and its WAL companions.
fn remove_ours(path: &Path) {
    for suffix in ["", "-wal", "-shm"] {
        let mut p = path.as_os_str().to_os_string();
        p.push(suffix);
        let _ = std::fs::remove_file(PathBuf::from(p));
    }
}

impl LiveFile {
    /// Create the live file of `concept` beside the study `study`: the first free name,
    /// or one of our own live files (replaced); never a file that is not ours.
    pub fn create(study: &Path, concept: &str) -> Result<LiveFile> {
        let mut last_err = None;
        for k in 1..=NAMES {
            let path = candidate(study, concept, k);
            if path.exists() {
                if !is_ours(&path) {
                    continue;
                }
                remove_ours(&path);
            }
            match std::fs::OpenOptions::new()
                .write(true)
                .create_new(true)
                .open(&path)
            {
                Ok(_) => return LiveFile::init(path, concept),
                Err(e) => last_err = Some(e),
            }
        }
        Err(Error::input(format!(
            "no free name for the live file of {concept} beside {}{}",
            study.display(),
            last_err.map(|e| format!(": {e}")).unwrap_or_default()
        )))
    }

    fn init(path: PathBuf, concept: &str) -> Result<LiveFile> {
        let conn = Connection::open(&path)?;
        // journal_mode answers with a row: read it rather than execute it.
        conn.query_row("PRAGMA journal_mode = WAL", [], |_| Ok(()))?;
        conn.pragma_update(None, "synchronous", "OFF")?;
        let table = crate::store::table::quote_ident(concept);
        conn.execute_batch(&format!(
            "CREATE TABLE {MARK} (concept TEXT, pid INTEGER, branches INTEGER, rows INTEGER, \
             state TEXT);
             CREATE TABLE {table} (POINT INTEGER PRIMARY KEY, NUME_BRANCHE INTEGER, \
             FREQUENCE REAL, ENERGIE REAL, BIFURCATION TEXT);"
        ))?;
        conn.execute(
            &format!("INSERT INTO {MARK} VALUES (?1, ?2, 0, 0, 'RUNNING')"),
            params![concept, i64::from(std::process::id())],
        )?;
        Ok(LiveFile {
            conn,
            path,
            table,
            rows: 0,
        })
    }

    pub fn path(&self) -> &Path {
        &self.path
    }

    /// Append the rows of one branch, visible to readers once this returns.
    pub fn branch(&mut self, branch: usize, rows: &[LiveRow]) -> Result<()> {
        let tx = self.conn.transaction()?;
        {
            let mut st = tx.prepare_cached(&format!(
                "INSERT INTO {} VALUES (?1, ?2, ?3, ?4, ?5)",
                self.table
            ))?;
            for r in rows {
                self.rows += 1;
                st.execute(params![
                    self.rows,
                    r.branch as i64,
                    r.frequency,
                    r.energy,
                    if r.bifurcation { "OUI" } else { "NON" }
                ])?;
            }
        }
        tx.execute(
            &format!("UPDATE {MARK} SET branches = ?1, rows = ?2"),
            params![branch as i64, self.rows],
        )?;
        tx.commit()?;
        Ok(())
    }

    /// Record how the operator ended ('DONE': its rows are in the study; 'FAILED').
    pub fn finish(self, state: &str) -> Result<PathBuf> {
        self.conn
            .execute(&format!("UPDATE {MARK} SET state = ?1"), params![state])?;
        // Closing the last connection folds the WAL back into the file and removes it
        // (a reader still connected keeps it until it closes).
        Ok(self.path)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::store::Store;

    fn row(branch: usize, e: f64) -> LiveRow {
        LiveRow {
            branch,
            frequency: 0.5 + e,
            energy: e,
            bifurcation: false,
        }
    }

    /// A reader sees each branch's rows as soon as it is written, while the study is held
    /// by an open operator transaction that another connection could not write through,
    /// and the study gets nothing from the live file.
    #[test]
    fn a_reader_sees_the_rows_while_the_study_transaction_is_open() {
        let dir = tempfile::tempdir().unwrap();
        let study = dir.path().join("case.db");
        let store = Store::create(&study).unwrap();
        store.begin_op().unwrap();
        let mut live = LiveFile::create(&study, "MNL").unwrap();
        assert_eq!(live.path(), dir.path().join("case.MNL.live.db"));
        let reader = Connection::open(live.path()).unwrap();
        let count = |c: &Connection| -> i64 {
            c.query_row("SELECT COUNT(*) FROM MNL", [], |r| r.get(0))
                .unwrap()
        };
        assert_eq!(count(&reader), 0);
        live.branch(1, &[row(1, 0.1), row(1, 0.2)]).unwrap();
        assert_eq!(count(&reader), 2);
        live.branch(2, &[row(2, 0.3)]).unwrap();
        assert_eq!(count(&reader), 3);
        let (b, state): (i64, String) = reader
            .query_row("SELECT branches, state FROM aster_nl_live", [], |r| {
                Ok((r.get(0)?, r.get(1)?))
            })
            .unwrap();
        assert_eq!((b, state.as_str()), (2, "RUNNING"));
        // The study is held: a second connection cannot write to it meanwhile.
        let other = Connection::open(&study).unwrap();
        other
            .busy_timeout(std::time::Duration::from_millis(10))
            .unwrap();
        assert!(other.execute_batch("CREATE TABLE x (a)").is_err());
        store.rollback_op();
        let path = live.finish("FAILED").unwrap();
        assert!(is_ours(&path));
    }

    /// A file of that name that is not ours is left alone and the next name taken; a live
    /// file of ours from an earlier run is replaced.
    #[test]
    fn a_file_that_is_not_ours_is_never_touched() {
        let dir = tempfile::tempdir().unwrap();
        let study = dir.path().join("case.db");
        let first = candidate(&study, "MNL", 1);
        std::fs::write(&first, "my notes").unwrap();
        let live = LiveFile::create(&study, "MNL").unwrap();
        assert_eq!(live.path(), candidate(&study, "MNL", 2));
        assert_eq!(std::fs::read_to_string(&first).unwrap(), "my notes");
        let second = live.finish("DONE").unwrap();
        // Ours: the next run replaces it, starting empty.
        let mut again = LiveFile::create(&study, "MNL").unwrap();
        assert_eq!(again.path(), second);
        again.branch(1, &[row(1, 1.0)]).unwrap();
        let c = Connection::open(&second).unwrap();
        let n: i64 = c
            .query_row("SELECT COUNT(*) FROM MNL", [], |r| r.get(0))
            .unwrap();
        assert_eq!(n, 1);
        // Another program's SQLite file is not ours either.
        let foreign = candidate(&study, "T", 1);
        Connection::open(&foreign)
            .unwrap()
            .execute_batch("CREATE TABLE t (a)")
            .unwrap();
        assert!(!is_ours(&foreign));
        let live = LiveFile::create(&study, "T").unwrap();
        assert_eq!(live.path(), candidate(&study, "T", 2));
    }
}
