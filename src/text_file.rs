//! Reading the text files a user names (command files, `.export` files, sweep study files
//! and templates): each must be a regular file of at most [`MAX_TEXT_BYTES`], both checked
//! before a byte is read, so that a FIFO (which would block), `/dev/zero` (which never
//! ends) or a huge file is refused at once with a message naming it.

use crate::error::{Error, ErrorKind, Result};
use std::io::Read;
use std::os::unix::fs::OpenOptionsExt;
use std::path::Path;

/// The largest text file read: real command files are kilobytes; a template with a long
/// table literal stays far below this.
pub const MAX_TEXT_BYTES: u64 = 64 * 1024 * 1024;

/// The text of the regular file `path`; `what` names it in messages ("the command file").
pub fn read(path: &Path, what: &str) -> Result<String> {
    read_bounded(path, what, MAX_TEXT_BYTES)
}

/// [`read`] with a given size limit.
pub fn read_bounded(path: &Path, what: &str, max_bytes: u64) -> Result<String> {
    let bytes = read_bytes_bounded(path, what, max_bytes)?;
    String::from_utf8(bytes).map_err(|e| {
        Error::new(
            ErrorKind::Io,
            format!(
                "cannot read {what} {}: not UTF-8 text ({e})",
                path.display()
            ),
        )
    })
}

/// The bytes of the regular file `path` (at most [`MAX_TEXT_BYTES`]), for a reader that
/// decodes them itself (the command file: UTF-8 or Latin-1, lang::encoding).
pub fn read_bytes(path: &Path, what: &str) -> Result<Vec<u8>> {
    read_bytes_bounded(path, what, MAX_TEXT_BYTES)
}

/// [`read_bytes`] with a given size limit.
pub fn read_bytes_bounded(path: &Path, what: &str, max_bytes: u64) -> Result<Vec<u8>> {
    let shown = path.display();
    let io = |msg: String| Error::new(ErrorKind::Io, msg);
    let meta =
        std::fs::metadata(path).map_err(|e| io(format!("cannot read {what} {shown}: {e}")))?;
    if !meta.is_file() {
        let kind = if meta.is_dir() {
            "a directory"
        } else {
            "a FIFO, a device or a socket"
        };
        return Err(io(format!("{what} {shown} is {kind}, not a regular file"))
            .hint("give the path of a file saved on disk"));
    }
    if meta.len() > max_bytes {
        return Err(io(format!(
            "{what} {shown} has {} bytes, more than the {max_bytes} a text file may have",
            meta.len()
        )));
    }
    // Opened without blocking (the path may have become a FIFO since) and read up to the
    // limit (it may have grown).
    let file = std::fs::OpenOptions::new()
        .read(true)
        .custom_flags(libc::O_NONBLOCK | libc::O_CLOEXEC)
        .open(path)
        .map_err(|e| io(format!("cannot read {what} {shown}: {e}")))?;
    if !file.metadata().is_ok_and(|m| m.is_file()) {
        return Err(io(format!("{what} {shown} is not a regular file")));
    }
    let mut bytes = Vec::new();
    file.take(max_bytes + 1)
        .read_to_end(&mut bytes)
        .map_err(|e| io(format!("cannot read {what} {shown}: {e}")))?;
    if bytes.len() as u64 > max_bytes {
        return Err(io(format!(
            "{what} {shown} has more than the {max_bytes} bytes a text file may have"
        )));
    }
    Ok(bytes)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn special_files_and_large_files_are_refused_before_reading() {
        let e = read(Path::new("/dev/zero"), "the command file").unwrap_err();
        assert!(e.message.contains("not a regular file"), "{e}");
        let dir = tempfile::tempdir().unwrap();
        let fifo = dir.path().join("f.comm");
        let c = std::ffi::CString::new(fifo.to_str().unwrap()).unwrap();
        // SAFETY: mkfifo on a NUL-terminated path we own.
        assert_eq!(unsafe { libc::mkfifo(c.as_ptr(), 0o600) }, 0);
        let e = read(&fifo, "the command file").unwrap_err();
        assert!(e.message.contains("FIFO"), "{e}");
        let e = read(dir.path(), "the command file").unwrap_err();
        assert!(e.message.contains("directory"), "{e}");
        let big = dir.path().join("big.comm");
        std::fs::write(&big, "x".repeat(101)).unwrap();
        let e = read_bounded(&big, "the command file", 100).unwrap_err();
        assert!(e.message.contains("101 bytes"), "{e}");
        assert_eq!(read_bounded(&big, "f", 101).unwrap().len(), 101);
    }
}
