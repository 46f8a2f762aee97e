//! The engine's errors in the user's words: the keyword of each setting an engine error is
//! about (`nnm::error::Setting`), for the operators over the engine (MODE_NON_LINE,
//! REPONSE_FORCEE_NL, CALC_STABILITE, REST_MODE_NONL). The paths are relative to the
//! operator, as every operator's errors are (the interpreter puts the operator in front).
//!
//! One mapping serves them all because they share their keywords' names (RESOLUTION's, CHOC's,
//! ETAT_INIT's); an operator that names a setting otherwise maps it before converting.

use crate::error::Error;
use crate::nnm::error::{Error as EngineError, Setting};

/// The keyword path a user changes for `setting`.
pub fn keyword(setting: Setting) -> &'static str {
    match setting {
        Setting::Stiffness => "MATR_RIGI",
        Setting::Damping => "MATR_AMOR",
        Setting::Force => "EXCIT",
        Setting::Shocks => "CHOC",
        Setting::ShockComponents => "CHOC/NOM_CMP",
        Setting::ShockGap => "CHOC/JEU",
        Setting::ShockStiffness => "CHOC/RIGI_NOR",
        Setting::ShockRegularisation => "CHOC/PARA_REGUL",
        Setting::CubicStiffness => "RESSORT_CUBIQUE/RAIDEUR",
        Setting::HarmLine => "RESOLUTION/NB_HARM_LINE",
        Setting::HarmNonl => "RESOLUTION/NB_HARM_NONL",
        Setting::SeriesOrder => "RESOLUTION/NB_ORDRE_MAN",
        Setting::SeriesPrecision => "RESOLUTION/PREC_MAN",
        Setting::StepsPerBranch => "RESOLUTION/NB_PAS_MAN",
        Setting::NewtonPrecision => "RESOLUTION/PREC_NEWTON",
        Setting::NewtonIterations => "RESOLUTION/ITER_NEWTON_MAXI",
        Setting::BranchesWithoutProgress => "RESOLUTION/NB_BRANCHE_SANS_PROGRES",
        Setting::LawDefectMax => "RESOLUTION/ECART_LOI_CHOC_MAXI",
        Setting::EnergySpreadMax => "RESOLUTION/ECART_ENERGIE_MAXI",
        Setting::FrequencyDropMax => "RESOLUTION/BAISSE_FREQ_MAXI",
        Setting::FictitiousDampingMax => "RESOLUTION/AMOR_FICTIF_MAXI",
        Setting::ContactWorkMin => "RESOLUTION/TRAVAIL_CHOC_MINI",
        Setting::Start => "ETAT_INIT",
        Setting::StartMode => "ETAT_INIT/NUME_ORDRE",
        Setting::StartQuadratureMode => "ETAT_INIT/NUME_ORDRE_QUAD",
        Setting::StartAmplitude => "ETAT_INIT/COEF_AMPL",
        Setting::StartFrequency => "FREQ_MIN",
        Setting::OrbitInstants => "NB_INST",
        Setting::StabilityInstants => "SCHEMA_TEMPS/NB_INST",
        Setting::StabilityTolerance => "TOLERANCE",
        Setting::StabilityRows => "MODE_NON_LINE",
    }
}

/// The engine's error as the user reads it: its setting's keyword, or the keyword and
/// location of the lower layer's error it carries.
impl From<EngineError> for Error {
    fn from(e: EngineError) -> Self {
        let (location, below) = match e.cause {
            Some(c) => (c.location, c.keyword),
            None => (None, None),
        };
        Error {
            kind: e.kind,
            message: e.message,
            location,
            keyword: e.setting.map(|s| keyword(s).to_string()).or(below),
            hint: e.hint,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_setting_becomes_its_keyword_and_a_lower_error_keeps_its_own() {
        let e: Error = EngineError::numerical("no convergence")
            .setting(Setting::SeriesPrecision)
            .hint("lower it")
            .into();
        assert_eq!(e.keyword.as_deref(), Some("RESOLUTION/PREC_MAN"));
        assert_eq!(e.hint.as_deref(), Some("lower it"));
        let below = Error::validation("too many").keyword("CALC_FREQ/NMAX_FREQ");
        let e: Error = EngineError::from(below).into();
        assert_eq!(e.keyword.as_deref(), Some("CALC_FREQ/NMAX_FREQ"));
        assert_eq!(e.message, "too many");
    }
}
