//! The errors of the store's libraries (SQLite, and the JSON that some stored columns hold)
//! as the crate's [`Error`]: kept here, beside the store, so that the shared error type
//! (error.rs), which the numerics use, names no database library.

use crate::error::Error;

impl From<rusqlite::Error> for Error {
    fn from(e: rusqlite::Error) -> Self {
        Error::store(e.to_string())
    }
}

impl From<serde_json::Error> for Error {
    fn from(e: serde_json::Error) -> Self {
        Error::store(format!("stored data could not be decoded: {e}"))
    }
}
