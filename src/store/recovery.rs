//! Reading a study that a killed run left with a hot journal, without writing to it.
//!
//! A run killed inside an operator leaves the operator's rollback journal beside the study
//! (`<db>-journal`, "hot"): the database pages hold part of the unfinished transaction, and
//! SQLite restores the last committed state by rolling the journal back the next time the
//! study is opened for writing. A read-only connection cannot do that, and refuses to read
//! (`SQLITE_READONLY_ROLLBACK`). So whoever only reads (`aster-nl tables`, DEBUT deciding
//! whether the file is a study it may replace) reads a private copy of the database and its
//! journal instead, rolled back in the copy: the user's files are not written, and a file
//! of another program is judged on its committed contents too.

use super::own_file;
use crate::error::{Error, Result};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};

/// Whether SQLite refused to read because a hot journal needs rolling back.
pub fn needs_rollback(e: &rusqlite::Error) -> bool {
    matches!(e, rusqlite::Error::SqliteFailure(f, _)
        if f.extended_code == rusqlite::ffi::SQLITE_READONLY_ROLLBACK)
}

/// Whether a read-only look at `db` hits a hot journal (`Ok(false)`: it reads).
pub fn has_hot_journal(db: &Path) -> bool {
    use rusqlite::OpenFlags;
    let Ok(conn) = rusqlite::Connection::open_with_flags(
        db,
        OpenFlags::SQLITE_OPEN_READ_ONLY | OpenFlags::SQLITE_OPEN_NO_MUTEX,
    ) else {
        return false;
    };
    let probe = conn.query_row("SELECT count(*) FROM sqlite_master", [], |r| {
        r.get::<_, i64>(0)
    });
    probe.as_ref().is_err_and(needs_rollback)
}

/// A private copy of a study and its journal, rolled back to the last committed state;
/// removed with everything in it when dropped.
#[derive(Debug)]
pub struct RecoveredCopy {
    dir: PathBuf,
    db: PathBuf,
}

impl RecoveredCopy {
    /// The copy of the database, to open read-only.
    pub fn db(&self) -> &Path {
        &self.db
    }
}

impl Drop for RecoveredCopy {
    fn drop(&mut self) {
        // The directory was created by us, exclusively, and holds only our copies.
        let _ = std::fs::remove_dir_all(&self.dir);
    }
}

/// Copy `db` and its rollback journal into a new private directory of the system's
/// temporary directory and let SQLite roll the journal back there.
pub fn recovered_copy(db: &Path) -> Result<RecoveredCopy> {
    static COUNTER: AtomicUsize = AtomicUsize::new(0);
    let dir = std::env::temp_dir().join(format!(
        "aster-nl-recovery-{}-{}",
        std::process::id(),
        COUNTER.fetch_add(1, Ordering::Relaxed)
    ));
    {
        use std::os::unix::fs::DirBuilderExt;
        std::fs::DirBuilder::new()
            .mode(0o700)
            .create(&dir)
            .map_err(|e| {
                Error::store(format!(
                    "{} was left by a killed run (its journal must be rolled back) and \
                     cannot be copied to read it: cannot create {}: {e}",
                    db.display(),
                    dir.display()
                ))
            })?;
    }
    let copy = RecoveredCopy {
        db: dir.join("study.db"),
        dir,
    };
    let journal = super::study_file::journal_paths(db)[0].clone();
    let mut copied_journal = copy.db.as_os_str().to_owned();
    copied_journal.push("-journal");
    copy_file(db, copy.db())?;
    copy_file(&journal, Path::new(&copied_journal))?;
    // Opened for writing, SQLite rolls the hot journal back (in the copy) on first read.
    let conn = rusqlite::Connection::open(copy.db())?;
    conn.query_row("SELECT count(*) FROM sqlite_master", [], |r| {
        r.get::<_, i64>(0)
    })?;
    drop(conn);
    Ok(copy)
}

/// Copy a regular file (never through a link, never blocking on a FIFO) to a new file.
fn copy_file(from: &Path, to: &Path) -> Result<()> {
    use std::os::unix::fs::OpenOptionsExt;
    let what = |e: std::io::Error| {
        Error::store(format!(
            "cannot copy {} to read the study it belongs to: {e}",
            from.display()
        ))
    };
    let mut src = std::fs::OpenOptions::new()
        .read(true)
        .custom_flags(libc::O_NOFOLLOW | libc::O_NONBLOCK | libc::O_CLOEXEC)
        .open(from)
        .map_err(what)?;
    if !own_file::is_regular(&src) {
        return Err(Error::store(format!(
            "{} is not a regular file",
            from.display()
        )));
    }
    let mut dst = own_file::create_new(to).map_err(what)?;
    std::io::copy(&mut src, &mut dst).map_err(what)?;
    Ok(())
}
