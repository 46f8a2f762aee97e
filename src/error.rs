//! Errors as values. Every failure a user can cause is an [`Error`] that says what was
//! wrong, where (file, line, column, keyword) and, when we can, what to do about it.

use crate::value::Span;
use std::fmt;

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ErrorKind {
    /// The text is not in the supported Python subset.
    Syntax,
    /// A call does not match its operator's catalog.
    Validation,
    /// Bad user data found while running (mesh file, missing characteristic...).
    Input,
    /// A computation failed (no convergence, singular matrix...).
    Numerical,
    /// The SQLite concept store.
    Store,
    /// Files.
    Io,
    /// A bug of ours: should never reach a user.
    Internal,
}

/// Where an error happened in a source file (a `.comm`, a mesh file...).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Location {
    pub file: String,
    pub span: Span,
}

#[derive(Clone, Debug)]
pub struct Error {
    pub kind: ErrorKind,
    pub message: String,
    pub location: Option<Location>,
    /// The keyword the error is about, e.g. `CHOC/JEU`.
    pub keyword: Option<String>,
    /// What the user could do about it.
    pub hint: Option<String>,
}

pub type Result<T, E = Error> = std::result::Result<T, E>;

impl Error {
    pub fn new(kind: ErrorKind, message: impl Into<String>) -> Self {
        Error {
            kind,
            message: message.into(),
            location: None,
            keyword: None,
            hint: None,
        }
    }
    pub fn syntax(message: impl Into<String>) -> Self {
        Self::new(ErrorKind::Syntax, message)
    }
    pub fn validation(message: impl Into<String>) -> Self {
        Self::new(ErrorKind::Validation, message)
    }
    pub fn input(message: impl Into<String>) -> Self {
        Self::new(ErrorKind::Input, message)
    }
    pub fn numerical(message: impl Into<String>) -> Self {
        Self::new(ErrorKind::Numerical, message)
    }
    pub fn store(message: impl Into<String>) -> Self {
        Self::new(ErrorKind::Store, message)
    }
    pub fn internal(message: impl Into<String>) -> Self {
        Self::new(ErrorKind::Internal, message)
    }

    /// Attach a location unless one is already set (the innermost location wins).
    pub fn at(mut self, file: impl Into<String>, span: Span) -> Self {
        if self.location.is_none() {
            self.location = Some(Location {
                file: file.into(),
                span,
            });
        }
        self
    }
    /// Attach a file and a 1-based line (for data files such as meshes).
    pub fn at_line(self, file: impl Into<String>, line: usize) -> Self {
        self.at(
            file,
            Span {
                line,
                col: 1,
                ..Span::default()
            },
        )
    }
    /// Name the keyword the error is about, unless already named.
    pub fn keyword(mut self, kw: impl Into<String>) -> Self {
        if self.keyword.is_none() {
            self.keyword = Some(kw.into());
        }
        self
    }
    pub fn hint(mut self, hint: impl Into<String>) -> Self {
        self.hint = Some(hint.into());
        self
    }
}

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if let Some(loc) = &self.location {
            write!(f, "{}:{}:{}: ", loc.file, loc.span.line, loc.span.col)?;
        }
        if let Some(kw) = &self.keyword {
            write!(f, "{kw}: ")?;
        }
        write!(f, "{}", self.message)?;
        if let Some(h) = &self.hint {
            write!(f, " (hint: {h})")?;
        }
        Ok(())
    }
}

impl std::error::Error for Error {}

impl From<std::io::Error> for Error {
    fn from(e: std::io::Error) -> Self {
        Error::new(ErrorKind::Io, e.to_string())
    }
}
