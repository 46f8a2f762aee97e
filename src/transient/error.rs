//! The typed errors of the transient integrator, and their conversion into the crate's
//! [`crate::error::Error`] (kind, keyword, hint) in one place.

use crate::error::{Error, ErrorKind};
use std::fmt;

/// What can go wrong in a transient integration. Every variant names the numbers a user
/// needs to fix the input.
#[derive(Clone, Debug, PartialEq)]
pub enum TransientError {
    /// A vector or matrix has the wrong size.
    Dimension {
        what: String,
        expected: usize,
        got: usize,
    },
    /// A parameter is out of its domain (negative stiffness, zero NORM_OBST...).
    Invalid { keyword: String, message: String },
    /// DIFF_CENTRE with PAS above its stability limit 2/ω_max (ω_max of the structure with
    /// the shocks' stiffnesses engaged).
    Unstable { dt: f64, limit: f64, omega_max: f64 },
    /// The adaptive step fell below PAS_MINI.
    StepTooSmall { t: f64, dt: f64, pas_mini: f64 },
    /// One step was rejected NMAX_ITER_PAS times in a row.
    TooManyRejections { t: f64, rejections: usize, dt: f64 },
    /// More steps than allowed (runaway adaptive integration).
    StepLimit { t: f64, max_steps: usize },
    /// NEWMARK's iterations on the shock forces did not converge.
    NotConverged {
        t: f64,
        iterations: usize,
        increment: f64,
    },
    /// A matrix that must be factorised is not (mass not definite...).
    Singular { what: String },
    /// The state became NaN or infinite.
    NonFinite { t: f64 },
    /// The archive (or a workspace) does not fit in memory.
    OutOfMemory { what: String, bytes: u128 },
}

impl fmt::Display for TransientError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            TransientError::Dimension {
                what,
                expected,
                got,
            } => write!(f, "{what} has {got} entries, {expected} expected"),
            TransientError::Invalid { keyword, message } => write!(f, "{keyword}: {message}"),
            TransientError::Unstable {
                dt,
                limit,
                omega_max,
            } => write!(
                f,
                "DIFF_CENTRE is unstable with PAS = {dt:e}: the stability limit is \
                 2/ω_max = {limit:e} s (ω_max = {omega_max:e} rad/s, shocks' RIGI_NOR and \
                 RIGI_TAN included)"
            ),
            TransientError::StepTooSmall { t, dt, pas_mini } => write!(
                f,
                "the adaptive step fell to {dt:e} s at t = {t:e} s, below PAS_MINI = {pas_mini:e} s"
            ),
            TransientError::TooManyRejections { t, rejections, dt } => write!(
                f,
                "the step at t = {t:e} s was rejected {rejections} times in a row (last \
                 step {dt:e} s)"
            ),
            TransientError::StepLimit { t, max_steps } => write!(
                f,
                "more than {max_steps} steps were needed; stopped at t = {t:e} s"
            ),
            TransientError::NotConverged {
                t,
                iterations,
                increment,
            } => write!(
                f,
                "NEWMARK: the shock forces did not converge in {iterations} iterations at \
                 t = {t:e} s (last relative increment {increment:e})"
            ),
            TransientError::Singular { what } => write!(f, "{what} cannot be factorised"),
            TransientError::NonFinite { t } => {
                write!(f, "the solution became NaN or infinite at t = {t:e} s")
            }
            TransientError::OutOfMemory { what, bytes } => {
                write!(
                    f,
                    "{what} needs {bytes} bytes, which could not be allocated"
                )
            }
        }
    }
}

impl std::error::Error for TransientError {}

impl From<TransientError> for Error {
    fn from(e: TransientError) -> Error {
        let message = e.to_string();
        match e {
            TransientError::Dimension { .. } => Error::new(ErrorKind::Internal, message),
            TransientError::Invalid { keyword, .. } => {
                Error::new(ErrorKind::Input, message).keyword(keyword)
            }
            TransientError::Unstable { limit, .. } => Error::new(ErrorKind::Numerical, message)
                .keyword("INCREMENT/PAS")
                .hint(format!(
                    "take PAS below {limit:e}, or an unconditionally stable SCHEMA \
                     ('NEWMARK') or an adaptive one ('RUNGE_KUTTA_54')"
                )),
            TransientError::StepTooSmall { .. } => Error::new(ErrorKind::Numerical, message)
                .keyword("SCHEMA_TEMPS/PAS_MINI")
                .hint("lower PAS_MINI or loosen TOLERANCE"),
            TransientError::TooManyRejections { .. } => Error::new(ErrorKind::Numerical, message)
                .keyword("SCHEMA_TEMPS/NMAX_ITER_PAS")
                .hint("raise NMAX_ITER_PAS or loosen TOLERANCE"),
            TransientError::StepLimit { .. } => Error::new(ErrorKind::Numerical, message)
                .keyword("INCREMENT/NB_PAS_MAXI")
                .hint(
                    "loosen TOLERANCE, raise PAS_MINI, shorten the interval, or raise NB_PAS_MAXI",
                ),
            TransientError::NotConverged { .. } => Error::new(ErrorKind::Numerical, message)
                .keyword("INCREMENT/PAS")
                .hint("take a smaller PAS"),
            TransientError::Singular { .. } | TransientError::NonFinite { .. } => {
                Error::new(ErrorKind::Numerical, message)
            }
            TransientError::OutOfMemory { .. } => Error::new(ErrorKind::Numerical, message)
                .keyword("ARCHIVAGE")
                .hint("archive fewer instants (a larger PAS_ARCH)"),
        }
    }
}

/// `Invalid` for a keyword.
pub(crate) fn invalid(keyword: &str, message: impl Into<String>) -> TransientError {
    TransientError::Invalid {
        keyword: keyword.to_string(),
        message: message.into(),
    }
}

/// Checks a length.
pub(crate) fn check_len(what: &str, got: usize, expected: usize) -> Result<(), TransientError> {
    if got == expected {
        Ok(())
    } else {
        Err(TransientError::Dimension {
            what: what.to_string(),
            expected,
            got,
        })
    }
}

/// A zeroed vector of `len` f64, or `OutOfMemory` instead of an abort.
pub(crate) fn try_zeros(what: &str, len: usize) -> Result<Vec<f64>, TransientError> {
    let mut v = Vec::new();
    v.try_reserve_exact(len)
        .map_err(|_| TransientError::OutOfMemory {
            what: what.to_string(),
            bytes: len as u128 * 8,
        })?;
    v.resize(len, 0.0);
    Ok(v)
}
