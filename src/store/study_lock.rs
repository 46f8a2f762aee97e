//! The lock a run holds on its study: an exclusive advisory lock (`flock`) on `<db>.lock`,
//! a file that records the process id and the command file of the run holding it, so that
//! a second run on the same study is refused at once with a message naming the first. The
//! kernel releases the lock when the process dies, however it dies (`kill -9` included): a
//! lock file left behind never blocks a later run.
//!
//! The lock file is ours only if we made it: it is created exclusively, with its text, by
//! linking a fully written temporary into place (never through a symbolic link), and an
//! existing `<db>.lock` is used only if it is a regular file starting with [`MARKER`]. A
//! file of the user's at that path (or a link) is refused, named, and left untouched; the
//! lock file is removed at the end of the run only while the path still names it.

use super::own_file;
use crate::error::{Error, Result};
use std::fs::File;
use std::os::unix::fs::FileExt;
use std::path::{Path, PathBuf};

/// How every lock file aster-nl writes begins.
pub const MARKER: &str = "aster-nl process ";

/// The most of a lock file read to recognise it (ours are one short line).
const MAX_LOCK_TEXT: usize = 4096;

/// The lock file of a study: `<db>.lock`.
pub fn lock_path(path: &Path) -> PathBuf {
    let mut s = path.as_os_str().to_owned();
    s.push(".lock");
    PathBuf::from(s)
}

/// An exclusive lock on a study, held for as long as this value lives.
#[derive(Debug)]
pub struct StudyLock {
    file: File,
    path: PathBuf,
}

impl StudyLock {
    /// Take the lock of the study at `db` without waiting; `purpose` (the command file, say)
    /// is recorded for the message another run would print.
    pub fn acquire(db: &Path, purpose: &str) -> Result<StudyLock> {
        let path = lock_path(db);
        let text = format!("{MARKER}{} running {purpose}\n", std::process::id());
        // A run that ended removes its lock file; another one may be removing it just as we
        // open it, so retry until the file we locked is the one at the path.
        for _ in 0..16 {
            let file = match create_with_text(&path, &text)? {
                Some(f) => f,
                None => match open_ours(db, &path)? {
                    Some(f) => f,
                    None => continue,
                },
            };
            match file.try_lock() {
                Ok(()) => {}
                Err(std::fs::TryLockError::WouldBlock) => {
                    let holder = read_text(&file);
                    let holder = holder.trim();
                    return Err(Error::store(format!(
                        "the study {} is in use by {holder}",
                        db.display()
                    ))
                    .hint(
                        "wait for that run to end, or give this one another database with --db",
                    ));
                }
                Err(std::fs::TryLockError::Error(e)) => {
                    return Err(Error::store(format!(
                        "cannot lock the study {} ({}): {e}",
                        db.display(),
                        path.display()
                    )));
                }
            }
            if own_file::is_at(&file, &path) {
                record(&file, &text)?;
                return Ok(StudyLock { file, path });
            }
        }
        Err(Error::store(format!(
            "cannot lock the study {}: its lock file keeps changing",
            db.display()
        )))
    }
}

impl Drop for StudyLock {
    fn drop(&mut self) {
        // Removed while still locked: a run waiting on this inode then sees that the path
        // names another file and retries (see `acquire`).
        own_file::remove_if_ours(&self.file, &self.path);
    }
}

/// Make the lock file with `text` in it, all at once: a temporary beside it is created
/// exclusively and written, then hard-linked to `path` (`link` fails if anything, a link
/// included, is there). `None` when `path` exists.
fn create_with_text(path: &Path, text: &str) -> Result<Option<File>> {
    let cannot = |e: std::io::Error| {
        Error::store(format!(
            "cannot create the lock file {} of the study: {e}",
            path.display()
        ))
        .hint("the directory of the database must be writable")
    };
    let mut tmp = path.as_os_str().to_owned();
    tmp.push(format!(".{}.new", std::process::id()));
    let tmp = PathBuf::from(tmp);
    let file = own_file::create_new(&tmp).map_err(cannot)?;
    let linked = file
        .write_all_at(text.as_bytes(), 0)
        .and_then(|()| std::fs::hard_link(&tmp, path));
    own_file::remove_if_ours(&file, &tmp);
    match linked {
        Ok(()) => Ok(Some(file)),
        Err(e) if e.kind() == std::io::ErrorKind::AlreadyExists => Ok(None),
        Err(e) => Err(cannot(e)),
    }
}

/// Open the existing lock file at `path` if it is one of ours: a regular file (not a link)
/// whose text starts with [`MARKER`]. `None` when it vanished meanwhile.
fn open_ours(db: &Path, path: &Path) -> Result<Option<File>> {
    let shown = path.display();
    let hint = format!(
        "aster-nl keeps the lock of the study {} in {shown}: move that file away, or give \
         this run another database with --db",
        db.display()
    );
    let file = match own_file::open_existing(path) {
        Ok(f) => f,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(None),
        Err(e) if own_file::is_link_refusal(&e) => {
            return Err(Error::store(format!(
                "{shown} is a symbolic link, not a lock file of aster-nl: the run will not \
                 write through it"
            ))
            .hint(hint));
        }
        Err(e) => {
            return Err(Error::store(format!("cannot open the lock file {shown}: {e}")).hint(hint))
        }
    };
    if !own_file::is_regular(&file) {
        return Err(Error::store(format!(
            "{shown} is not a regular file, not a lock file of aster-nl: the run will not touch it"
        ))
        .hint(hint));
    }
    if !read_text(&file).starts_with(MARKER) {
        return Err(Error::store(format!(
            "{shown} exists and is not a lock file of aster-nl: the run will not overwrite \
             or delete it"
        ))
        .hint(hint));
    }
    Ok(Some(file))
}

/// The start of an open lock file's text (empty if unreadable).
fn read_text(file: &File) -> String {
    let mut buf = vec![0u8; MAX_LOCK_TEXT];
    let n = file.read_at(&mut buf, 0).unwrap_or(0);
    buf.truncate(n);
    String::from_utf8_lossy(&buf).into_owned()
}

/// Write this run's line over the lock file's text without ever leaving it empty (the
/// marker comes first and stays, so the file is recognised whenever the run is killed).
fn record(file: &File, text: &str) -> Result<()> {
    file.write_all_at(text.as_bytes(), 0)?;
    file.set_len(text.len() as u64)?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_second_lock_is_refused_and_names_the_first() {
        let dir = tempfile::tempdir().unwrap();
        let db = dir.path().join("s.db");
        let first = StudyLock::acquire(&db, "a.comm").unwrap();
        let err = StudyLock::acquire(&db, "b.comm").unwrap_err();
        assert!(err.message.contains("in use by"), "{err}");
        assert!(err.message.contains("a.comm"), "{err}");
        assert!(
            err.message
                .contains(&format!("process {}", std::process::id())),
            "{err}"
        );
        drop(first);
        assert!(!lock_path(&db).exists());
        let _again = StudyLock::acquire(&db, "b.comm").unwrap();
        // No temporary is left beside the lock.
        let names: Vec<_> = std::fs::read_dir(dir.path())
            .unwrap()
            .map(|e| e.unwrap().file_name())
            .collect();
        assert_eq!(names, vec![std::ffi::OsString::from("s.db.lock")]);
    }

    #[test]
    fn a_lock_left_by_a_killed_run_is_taken_over() {
        let dir = tempfile::tempdir().unwrap();
        let db = dir.path().join("s.db");
        std::fs::write(
            lock_path(&db),
            "aster-nl process 1 running an old run.comm and a much longer line\n",
        )
        .unwrap();
        let lock = StudyLock::acquire(&db, "b.comm").unwrap();
        let text = std::fs::read_to_string(lock_path(&db)).unwrap();
        assert_eq!(
            text,
            format!("{MARKER}{} running b.comm\n", std::process::id())
        );
        drop(lock);
        assert!(!lock_path(&db).exists());
    }

    #[test]
    fn a_file_of_the_users_at_the_lock_path_is_refused_and_kept() {
        let dir = tempfile::tempdir().unwrap();
        let db = dir.path().join("s.db");
        for content in ["my notes\n", ""] {
            std::fs::write(lock_path(&db), content).unwrap();
            let err = StudyLock::acquire(&db, "b.comm").unwrap_err();
            assert!(err.message.contains("not a lock file of aster-nl"), "{err}");
            assert!(err.message.contains("s.db.lock"), "{err}");
            assert_eq!(std::fs::read_to_string(lock_path(&db)).unwrap(), content);
        }
    }

    #[test]
    fn a_link_at_the_lock_path_is_never_followed() {
        let dir = tempfile::tempdir().unwrap();
        let db = dir.path().join("s.db");
        let target = dir.path().join("precious.txt");
        std::fs::write(&target, "precious").unwrap();
        std::os::unix::fs::symlink(&target, lock_path(&db)).unwrap();
        let err = StudyLock::acquire(&db, "b.comm").unwrap_err();
        assert!(err.message.contains("symbolic link"), "{err}");
        assert_eq!(std::fs::read_to_string(&target).unwrap(), "precious");
        assert!(std::fs::symlink_metadata(lock_path(&db))
            .unwrap()
            .file_type()
            .is_symlink());
        // A dangling link: nothing is created at its target.
        std::fs::remove_file(lock_path(&db)).unwrap();
        let nowhere = dir.path().join("nowhere");
        std::os::unix::fs::symlink(&nowhere, lock_path(&db)).unwrap();
        assert!(StudyLock::acquire(&db, "b.comm").is_err());
        assert!(!nowhere.exists());
    }
}
