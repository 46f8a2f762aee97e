//! The engine's errors: what failed, in the engine's words, and which setting of the
//! problem it is about, as a [`Setting`] rather than a keyword path. The operators name the
//! keyword (src/ops/engine_errors.rs), so that the numerics know nothing of the command
//! language: the same failure reads `RESOLUTION/PREC_MAN` in MODE_NON_LINE and
//! REPONSE_FORCEE_NL, and a new operator over the engine maps the settings its own way.
//!
//! An error of a layer below the engine (the sparse eigen-solver's, the shared linear
//! algebra's) keeps its keyword and location in [`Error::cause`], so nothing it said is lost
//! on the way through.

pub use crate::error::ErrorKind;

/// A setting of the problem or of its resolution that an error is about: what the user
/// changes to cure it. The engine's vocabulary; the operators' keywords are in
/// src/ops/engine_errors.rs.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Setting {
    /// The stiffness matrix (and the mass matrix beside it).
    Stiffness,
    /// The damping matrix of a forced response.
    Damping,
    /// The harmonic force of a forced response.
    Force,
    /// The shocks as a whole (their count, their DOFs).
    Shocks,
    /// The displacement components a shock acts on.
    ShockComponents,
    /// A shock's gap.
    ShockGap,
    /// A shock's normal stiffness.
    ShockStiffness,
    /// A shock's regularisation.
    ShockRegularisation,
    /// A cubic spring's stiffness.
    CubicStiffness,
    /// Harmonics of the displacements.
    HarmLine,
    /// Harmonics of the contact unknowns.
    HarmNonl,
    /// Order of the asymptotic series.
    SeriesOrder,
    /// Accuracy asked of the series, which sets the step length.
    SeriesPrecision,
    /// Series steps per branch.
    StepsPerBranch,
    /// Accuracy asked of Newton's correction.
    NewtonPrecision,
    /// Newton iterations allowed.
    NewtonIterations,
    /// Branches allowed without progress along the family.
    BranchesWithoutProgress,
    /// Largest contact-law defect allowed at a branch end.
    LawDefectMax,
    /// Largest energy spread allowed along a branch.
    EnergySpreadMax,
    /// Largest drop of the frequency below the linear one.
    FrequencyDropMax,
    /// Largest fictitious damping allowed at a branch end.
    FictitiousDampingMax,
    /// Smallest work of the contact forces allowed at a branch end.
    ContactWorkMin,
    /// The start as a whole.
    Start,
    /// The linear mode the start is taken from.
    StartMode,
    /// The second linear mode of a start in quadrature.
    StartQuadratureMode,
    /// The amplitude of a start from a linear mode.
    StartAmplitude,
    /// The frequency a forced response starts from.
    StartFrequency,
    /// Instants of a time history of an orbit.
    OrbitInstants,
    /// Time steps of the Floquet analysis over a period.
    StabilityInstants,
    /// Tolerance of the Floquet verdict.
    StabilityTolerance,
    /// The computed rows a Floquet analysis reads.
    StabilityRows,
}

impl Setting {
    /// The branch-end checks whose failure says the branch has left the motions of the
    /// system (its end breaks its contact law, does not conserve its energy, is held by its
    /// fictitious damping, its contact forces attract the structure, or its frequency is off
    /// the mode's family), rather than that it cannot go on.
    pub fn says_wrong_branch(self) -> bool {
        matches!(
            self,
            Setting::LawDefectMax
                | Setting::EnergySpreadMax
                | Setting::ContactWorkMin
                | Setting::FrequencyDropMax
                | Setting::FictitiousDampingMax
        )
    }
}

/// An error of the engine.
#[derive(Clone, Debug)]
pub struct Error {
    pub kind: ErrorKind,
    pub message: String,
    /// The setting the error is about, if one is.
    pub setting: Option<Setting>,
    /// What the user could do about it.
    pub hint: Option<String>,
    /// The error of a layer below the engine that this one carries, with its own keyword
    /// and location.
    pub cause: Option<Box<crate::error::Error>>,
}

pub type Result<T, E = Error> = std::result::Result<T, E>;

impl Error {
    pub fn new(kind: ErrorKind, message: impl Into<String>) -> Self {
        Error {
            kind,
            message: message.into(),
            setting: None,
            hint: None,
            cause: None,
        }
    }
    /// A setting that is not acceptable as given.
    pub fn input(message: impl Into<String>) -> Self {
        Self::new(ErrorKind::Input, message)
    }
    /// A setting or a size beyond what the engine can take.
    pub fn validation(message: impl Into<String>) -> Self {
        Self::new(ErrorKind::Validation, message)
    }
    /// A computation that failed (no convergence, a singular tangent...).
    pub fn numerical(message: impl Into<String>) -> Self {
        Self::new(ErrorKind::Numerical, message)
    }
    /// Stored data that does not fit the problem.
    pub fn store(message: impl Into<String>) -> Self {
        Self::new(ErrorKind::Store, message)
    }
    /// A bug of ours.
    pub fn internal(message: impl Into<String>) -> Self {
        Self::new(ErrorKind::Internal, message)
    }
    /// Name the setting the error is about, unless already named.
    pub fn setting(mut self, setting: Setting) -> Self {
        if self.setting.is_none() {
            self.setting = Some(setting);
        }
        self
    }
    pub fn hint(mut self, hint: impl Into<String>) -> Self {
        self.hint = Some(hint.into());
        self
    }
}

impl std::fmt::Display for Error {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        if let Some(s) = self.setting {
            write!(f, "{s:?}: ")?;
        }
        write!(f, "{}", self.message)?;
        if let Some(h) = &self.hint {
            write!(f, " (hint: {h})")?;
        }
        Ok(())
    }
}

impl std::error::Error for Error {}

/// An error of a lower layer, carried whole.
impl From<crate::error::Error> for Error {
    fn from(e: crate::error::Error) -> Self {
        Error {
            kind: e.kind,
            message: e.message.clone(),
            setting: None,
            hint: e.hint.clone(),
            cause: Some(Box::new(e)),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_first_setting_named_stays() {
        let e = Error::numerical("x")
            .setting(Setting::SeriesPrecision)
            .setting(Setting::HarmNonl);
        assert_eq!(e.setting, Some(Setting::SeriesPrecision));
    }

    #[test]
    fn a_lower_error_is_kept_whole() {
        let below = crate::error::Error::validation("too many modes")
            .keyword("CALC_FREQ/NMAX_FREQ")
            .hint("fewer");
        let e = Error::from(below);
        assert_eq!(e.kind, ErrorKind::Validation);
        assert_eq!(e.message, "too many modes");
        assert_eq!(e.hint.as_deref(), Some("fewer"));
        let cause = e.cause.expect("kept");
        assert_eq!(cause.keyword.as_deref(), Some("CALC_FREQ/NMAX_FREQ"));
    }
}
