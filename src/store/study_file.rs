//! The study file on disk: what DEBUT may replace, the lock a run holds on its study, and
//! the check that the study can be written before any operator runs.
//!
//! - **Replacing** ([`check_replaceable`]): DEBUT only ever removes a regular file that is an
//!   aster-nl database (SQLite header and our `meta` schema marker). A command file, a mesh,
//!   a directory, a device, a symbolic link or any other file is refused, named, and left
//!   untouched.
//!   A study a killed run left with a hot journal is judged on its rolled-back copy
//!   (`store::recovery`), so it is recognised and replaced.
//! - **Journals** ([`check_journals`]): SQLite deletes, truncates or writes through the
//!   files `<db>-journal`, `-wal` and `-shm`; beside a new study any such file is not ours
//!   and is refused, and a link or special file there is refused always.
//! - **Locking** (`store::study_lock`, re-exported here): a run holds an exclusive lock on
//!   `<db>.lock` from before DEBUT/POURSUITE touches the database until the run ends.
//! - **Writability** ([`check_writable`]): the file and its directory (where SQLite writes
//!   its journal) must be writable; a file or directory without any write permission bit is
//!   refused even for root, because that is how a user marks a study read-only.

use crate::error::{Error, Result};
use std::fs::{File, OpenOptions};
use std::io::Read;
use std::path::{Path, PathBuf};

/// The first 16 bytes of every SQLite 3 database file.
const SQLITE_HEADER: &[u8; 16] = b"SQLite format 3\0";

/// What a path on disk holds, as far as the store cares.
#[derive(Debug, PartialEq, Eq)]
pub enum FileKind {
    Absent,
    /// A regular file starting with the SQLite header.
    Sqlite,
    /// A regular file that is not an SQLite database (empty files included).
    OtherFile,
    /// A directory, device, FIFO, socket, or a symbolic link.
    NotRegular(&'static str),
}

/// Classify `path` without following a symbolic link and without modifying anything.
pub fn file_kind(path: &Path) -> Result<FileKind> {
    let meta = match std::fs::symlink_metadata(path) {
        Ok(m) => m,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(FileKind::Absent),
        Err(e) => {
            return Err(Error::store(format!(
                "cannot inspect {}: {e}",
                path.display()
            )));
        }
    };
    let ft = meta.file_type();
    if ft.is_symlink() {
        return Ok(FileKind::NotRegular("a symbolic link"));
    }
    if ft.is_dir() {
        return Ok(FileKind::NotRegular("a directory"));
    }
    if !ft.is_file() {
        return Ok(FileKind::NotRegular(
            "a device, FIFO or socket, not a regular file",
        ));
    }
    Ok(if has_sqlite_header(path) {
        FileKind::Sqlite
    } else {
        FileKind::OtherFile
    })
}

/// Whether the regular file at `path` starts with the SQLite header (false if unreadable).
pub fn has_sqlite_header(path: &Path) -> bool {
    let mut head = [0u8; 16];
    match File::open(path) {
        Ok(mut f) => f.read_exact(&mut head).is_ok() && &head == SQLITE_HEADER,
        Err(_) => false,
    }
}

/// Whether the SQLite file at `path` carries the aster-nl schema marker (a `meta` table with
/// a `schema_version` row, any version). Opened read-only: nothing is written.
/// A file a killed process left with a hot journal is judged on its committed contents, in
/// a private copy (an error if the copy cannot be made).
fn has_schema_marker(path: &Path) -> Result<bool> {
    if super::recovery::has_hot_journal(path) {
        let copy = super::recovery::recovered_copy(path)?;
        return Ok(marker_in(copy.db()));
    }
    Ok(marker_in(path))
}

/// [`has_schema_marker`] of a file SQLite can read as it is.
fn marker_in(path: &Path) -> bool {
    use rusqlite::OpenFlags;
    let Ok(conn) = rusqlite::Connection::open_with_flags(
        path,
        OpenFlags::SQLITE_OPEN_READ_ONLY | OpenFlags::SQLITE_OPEN_NO_MUTEX,
    ) else {
        return false;
    };
    conn.query_row(
        "SELECT count(*) FROM meta WHERE key = 'schema_version'",
        [],
        |r| r.get::<_, i64>(0),
    )
    .map(|n| n > 0)
    .unwrap_or(false)
}

/// Refuse unless DEBUT may create the study at `path`: absent, or an aster-nl database.
/// Returns whether a file is there to be replaced.
pub fn check_replaceable(path: &Path) -> Result<bool> {
    let shown = path.display();
    let proceed = "DEBUT only replaces an aster-nl database; \
                   pass another file with --db, or move this one away";
    match file_kind(path)? {
        FileKind::Absent => Ok(false),
        FileKind::NotRegular(what) => Err(Error::store(format!(
            "the database path {shown} is {what}: DEBUT will not replace it"
        ))
        .hint(proceed)),
        FileKind::OtherFile => Err(Error::store(format!(
            "{shown} exists and is not an aster-nl database: DEBUT will not replace it"
        ))
        .hint(proceed)),
        FileKind::Sqlite if has_schema_marker(path)? => Ok(true),
        FileKind::Sqlite => Err(Error::store(format!(
            "{shown} is an SQLite database but not an aster-nl study (no schema marker): \
             DEBUT will not replace it"
        ))
        .hint(proceed)),
    }
}

/// Refuse, before SQLite opens `path` for writing, an SQLite file that a killed process
/// left with a hot journal and that is not an aster-nl study: opening it would roll back
/// another program's journal. (A file without a hot journal is judged by the store's own
/// schema check, which names the version.)
pub fn check_marker(path: &Path) -> Result<()> {
    if super::recovery::has_hot_journal(path) && !has_schema_marker(path)? {
        return Err(Error::store(format!(
            "{} is an SQLite database but not an aster-nl study (no schema marker), and \
             another program left its journal beside it: aster-nl will not open it",
            path.display()
        ))
        .hint("pass the study's .db file with --db"));
    }
    Ok(())
}

/// Refuse unless POURSUITE may open `path`: a regular file.
pub fn check_openable(path: &Path) -> Result<()> {
    match file_kind(path)? {
        FileKind::Absent => Err(Error::store(format!(
            "no database to continue at {}",
            path.display()
        ))
        .hint("POURSUITE continues a study started by DEBUT; run that one first or pass --db")),
        FileKind::NotRegular(what) => Err(Error::store(format!(
            "the database path {} is {what}, not a study",
            path.display()
        ))
        .hint("pass the study's .db file with --db")),
        FileKind::OtherFile => Err(Error::store(format!(
            "{} is not an aster-nl database (not an SQLite file)",
            path.display()
        ))
        .hint("pass the study's .db file with --db")),
        FileKind::Sqlite => Ok(()),
    }
}

/// The directory holding `path` ("." for a bare file name).
fn parent_dir(path: &Path) -> PathBuf {
    match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
        _ => PathBuf::from("."),
    }
}

/// Refuse a study that cannot be written: the file (when it exists) and its directory need a
/// write permission bit, and the directory must accept a new file (SQLite's journal).
pub fn check_writable(path: &Path) -> Result<()> {
    use std::os::unix::fs::PermissionsExt;
    let dir = parent_dir(path);
    let dir_meta = std::fs::metadata(&dir).map_err(|e| {
        Error::store(format!(
            "the directory {} of the database cannot be read: {e}",
            dir.display()
        ))
    })?;
    if !dir_meta.is_dir() {
        return Err(Error::store(format!(
            "{} is not a directory",
            dir.display()
        )));
    }
    if dir_meta.permissions().mode() & 0o222 == 0 {
        return Err(Error::store(format!(
            "the directory {} of the database is read-only: SQLite needs to write its journal there",
            dir.display()
        ))
        .hint("make it writable (chmod u+w) or pass a database elsewhere with --db"));
    }
    if let Ok(meta) = std::fs::metadata(path) {
        if meta.permissions().mode() & 0o222 == 0 {
            return Err(
                Error::store(format!("the database {} is read-only", path.display())).hint(
                    "make it writable (chmod u+w), or copy it and continue the copy with --db",
                ),
            );
        }
    }
    // The permission bits are not the whole story (read-only mounts, ACLs, another owner):
    // try what SQLite will do, create a file in the directory.
    let probe = dir.join(format!(
        ".{}.aster-nl-probe-{}",
        path.file_name()
            .map(|n| n.to_string_lossy().into_owned())
            .unwrap_or_default(),
        std::process::id()
    ));
    match super::own_file::create_new(&probe) {
        Ok(f) => super::own_file::remove_if_ours(&f, &probe),
        Err(e) => {
            return Err(Error::store(format!(
                "cannot create files in {}, where the database and its journal live: {e}",
                dir.display()
            ))
            .hint("pass a database in a writable directory with --db"));
        }
    }
    if path.exists() {
        OpenOptions::new().write(true).open(path).map_err(|e| {
            Error::store(format!(
                "the database {} cannot be written: {e}",
                path.display()
            ))
            .hint("make it writable, or copy it and continue the copy with --db")
        })?;
    }
    Ok(())
}

/// The journal files SQLite may keep beside a database (rollback journal, WAL, shared memory).
pub fn journal_paths(path: &Path) -> [PathBuf; 3] {
    let with = |suffix: &str| {
        let mut s = path.as_os_str().to_owned();
        s.push(suffix);
        PathBuf::from(s)
    };
    [with("-journal"), with("-wal"), with("-shm")]
}

/// The first bytes of a rollback journal SQLite is using.
const JOURNAL_MAGIC: [u8; 8] = [0xd9, 0xd5, 0x05, 0xf9, 0x20, 0xa1, 0x63, 0xd7];

/// Whether the regular file at `journal` is what SQLite leaves at a rollback journal's
/// path: empty (truncated), starting with the journal magic (a transaction's), or with a
/// zeroed 28-byte header (a journal kept between transactions, `journal_mode = PERSIST`).
fn looks_like_a_journal(journal: &Path) -> bool {
    let mut head = Vec::with_capacity(28);
    let Ok(f) = File::open(journal) else {
        return false;
    };
    if f.take(28).read_to_end(&mut head).is_err() {
        return false;
    }
    head.is_empty()
        || head.starts_with(&JOURNAL_MAGIC)
        || (head.len() == 28 && head.iter().all(|&b| b == 0))
}

/// Refuse the files at the journal paths of `path` that SQLite would delete, truncate or
/// write through and that are not provably the journal of our study: any of them beside a
/// study that does not exist yet (`study_exists` false: DEBUT creating one); a write-ahead
/// log or its shared memory (`-wal`, `-shm`: our studies never use one); a rollback
/// journal that does not look like one; a link, a directory or a special file always.
pub fn check_journals(path: &Path, study_exists: bool) -> Result<()> {
    let hint = "move that file away, or pass another database with --db";
    for (k, j) in journal_paths(path).into_iter().enumerate() {
        let shown = j.display();
        let refuse = |why: String| {
            Err(Error::store(format!(
                "{shown} {why}: SQLite would delete, overwrite or write through it, so the \
                 study {} is not opened",
                path.display()
            ))
            .hint(hint))
        };
        match file_kind(&j)? {
            FileKind::Absent => {}
            FileKind::NotRegular(what) => return refuse(format!("is {what}")),
            _ if !study_exists => {
                return refuse("exists but there is no study beside it: it is not ours".into())
            }
            _ if k > 0 => {
                return refuse("exists, and aster-nl studies never use a write-ahead log".into())
            }
            _ if !looks_like_a_journal(&j) => {
                return refuse("is not a journal SQLite wrote".into())
            }
            _ => {}
        }
    }
    Ok(())
}

pub use super::study_lock::{lock_path, StudyLock};

/// Whether two paths name the same existing file (same device and inode).
pub fn same_path(a: &Path, b: &Path) -> bool {
    use std::os::unix::fs::MetadataExt;
    match (std::fs::metadata(a), std::fs::metadata(b)) {
        (Ok(a), Ok(b)) => a.dev() == b.dev() && a.ino() == b.ino(),
        _ => false,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn only_aster_databases_are_replaceable() {
        let dir = tempfile::tempdir().unwrap();
        let comm = dir.path().join("case.comm");
        std::fs::write(&comm, "DEBUT()\nFIN()\n").unwrap();
        assert!(check_replaceable(&comm).is_err());
        let empty = dir.path().join("empty.db");
        std::fs::write(&empty, "").unwrap();
        assert!(check_replaceable(&empty).is_err());
        let other = dir.path().join("other.db");
        rusqlite::Connection::open(&other)
            .unwrap()
            .execute_batch("CREATE TABLE t(x)")
            .unwrap();
        let err = check_replaceable(&other).unwrap_err();
        assert!(err.message.contains("not an aster-nl study"), "{err}");
        assert!(check_replaceable(dir.path()).is_err());
        assert!(check_replaceable(Path::new("/dev/null")).is_err());
        assert!(!check_replaceable(&dir.path().join("new.db")).unwrap());
        let ours = dir.path().join("ours.db");
        drop(crate::store::Store::create(&ours).unwrap());
        assert!(check_replaceable(&ours).unwrap());
    }

    #[test]
    fn read_only_study_is_refused() {
        use std::os::unix::fs::PermissionsExt;
        let dir = tempfile::tempdir().unwrap();
        let db = dir.path().join("s.db");
        std::fs::write(&db, "x").unwrap();
        check_writable(&db).unwrap();
        std::fs::set_permissions(&db, std::fs::Permissions::from_mode(0o444)).unwrap();
        let err = check_writable(&db).unwrap_err();
        assert!(err.message.contains("read-only"), "{err}");
        std::fs::set_permissions(&db, std::fs::Permissions::from_mode(0o644)).unwrap();
        std::fs::set_permissions(dir.path(), std::fs::Permissions::from_mode(0o555)).unwrap();
        let err = check_writable(&db).unwrap_err();
        std::fs::set_permissions(dir.path(), std::fs::Permissions::from_mode(0o755)).unwrap();
        assert!(err.message.contains("directory"), "{err}");
    }
}
