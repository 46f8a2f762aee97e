//! The files aster-nl makes for itself beside a study (its lock, temporaries, private
//! copies): created exclusively and never through a symbolic link, and removed only while
//! the path still names the very file we made. A file a user put at such a path is never
//! opened for writing, truncated or deleted.

use std::fs::{File, OpenOptions};
use std::io;
use std::os::unix::fs::{MetadataExt, OpenOptionsExt};
use std::path::Path;

/// Create `path` for reading and writing, failing if anything is there already (a file, a
/// symbolic link, even a dangling one: `O_CREAT | O_EXCL` never follows a link) .
pub fn create_new(path: &Path) -> io::Result<File> {
    OpenOptions::new()
        .read(true)
        .write(true)
        .create_new(true)
        .custom_flags(libc::O_NOFOLLOW | libc::O_CLOEXEC)
        .mode(0o644)
        .open(path)
}

/// Open an existing `path` for reading and writing without following a symbolic link
/// (`ELOOP` then) and without blocking on a FIFO; the caller checks what it opened with
/// [`is_regular`].
pub fn open_existing(path: &Path) -> io::Result<File> {
    OpenOptions::new()
        .read(true)
        .write(true)
        .custom_flags(libc::O_NOFOLLOW | libc::O_NONBLOCK | libc::O_CLOEXEC)
        .open(path)
}

/// Whether an open file is a regular file (not a FIFO, device, socket or directory).
pub fn is_regular(file: &File) -> bool {
    file.metadata().is_ok_and(|m| m.file_type().is_file())
}

/// Whether the open `file` is the file at `path` now (same device and inode; the path is
/// not followed if it is a link, so a link to our file is not our file).
pub fn is_at(file: &File, path: &Path) -> bool {
    match (file.metadata(), std::fs::symlink_metadata(path)) {
        (Ok(a), Ok(b)) => a.dev() == b.dev() && a.ino() == b.ino(),
        _ => false,
    }
}

/// Remove `path` if, and only if, it still names the open `file`.
pub fn remove_if_ours(file: &File, path: &Path) {
    if is_at(file, path) {
        let _ = std::fs::remove_file(path);
    }
}

/// Whether an I/O error says the path is a symbolic link that `O_NOFOLLOW` refused.
pub fn is_link_refusal(e: &io::Error) -> bool {
    e.raw_os_error() == Some(libc::ELOOP)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_link_or_an_existing_file_is_never_created_through() {
        let dir = tempfile::tempdir().unwrap();
        let target = dir.path().join("target.txt");
        std::fs::write(&target, "the user's text").unwrap();
        let link = dir.path().join("link");
        std::os::unix::fs::symlink(&target, &link).unwrap();
        assert!(create_new(&link).is_err());
        assert!(create_new(&target).is_err());
        let e = open_existing(&link).unwrap_err();
        assert!(is_link_refusal(&e), "{e}");
        // A dangling link is not followed either.
        let dangling = dir.path().join("dangling");
        std::os::unix::fs::symlink(dir.path().join("nowhere"), &dangling).unwrap();
        assert!(create_new(&dangling).is_err());
        assert!(!dir.path().join("nowhere").exists());
        assert_eq!(std::fs::read_to_string(&target).unwrap(), "the user's text");
    }

    #[test]
    fn only_the_file_we_made_is_removed() {
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("ours");
        let f = create_new(&p).unwrap();
        assert!(is_regular(&f));
        // Someone replaces it: the new file is not ours and stays.
        std::fs::remove_file(&p).unwrap();
        std::fs::write(&p, "theirs").unwrap();
        remove_if_ours(&f, &p);
        assert_eq!(std::fs::read_to_string(&p).unwrap(), "theirs");
        let g = open_existing(&p).unwrap();
        remove_if_ours(&g, &p);
        assert!(!p.exists());
    }
}
