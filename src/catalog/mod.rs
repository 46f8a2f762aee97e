//! Operator catalogs: `commands/*.toml`, embedded at build time (see `build.rs`, which
//! also embeds each file converted to JSON, the form a run parses), parsed once, then used to validate calls ([`validate`]), print help ([`describe`],
//! [`summary`]) and generate the command reference ([`markdown_reference`]).

mod check;
pub mod def;
mod docs;
mod print;
mod suggest;
mod validate;
mod validate_args;

pub use check::check_consistency;
pub use def::{FactDef, OperatorDef, Reuse, Rule, RuleKind, SimpDef, Statut, When};
pub use docs::markdown_reference;
pub use print::{describe, summary};
pub use suggest::closest;
pub use validate::{validate, validate_with};
pub use validate_args::validate_args;

use crate::args::Args;
use std::sync::OnceLock;

mod embedded {
    include!(concat!(env!("OUT_DIR"), "/catalog_files.rs"));
}

/// All catalogs, sorted by operator name, plus the files that failed to parse (a bug of
/// ours that the tests catch; the binary keeps working with the other operators).
pub struct Catalog {
    pub ops: Vec<OperatorDef>,
    pub errors: Vec<String>,
}

/// Parses one catalog file.
pub fn parse(file: &str, text: &str) -> Result<OperatorDef, String> {
    toml::from_str::<OperatorDef>(text).map_err(|e| format!("commands/{file}: {e}"))
}

/// Parses embedded catalog `i` ([`files`]): from the JSON `build.rs` made of it, which
/// reads several times faster than the TOML; from the TOML itself when there is no JSON
/// (the file does not parse: its error is the TOML parser's, naming line and column).
fn parse_embedded(i: usize) -> Result<OperatorDef, String> {
    let (file, text) = embedded::FILES[i];
    match embedded::JSON.get(i).copied().flatten() {
        Some(json) => serde_json::from_str::<OperatorDef>(json)
            .or_else(|_| parse(file, text))
            .map_err(|e| e.to_string()),
        None => parse(file, text),
    }
}

/// The catalogs, parsed on first use.
pub fn catalog() -> &'static Catalog {
    static CATALOG: OnceLock<Catalog> = OnceLock::new();
    CATALOG.get_or_init(|| {
        let mut ops = Vec::new();
        let mut errors = Vec::new();
        for i in 0..embedded::FILES.len() {
            match parse_embedded(i) {
                Ok(op) => ops.push(op),
                Err(e) => errors.push(e),
            }
        }
        ops.sort_by(|a, b| a.name.cmp(&b.name));
        Catalog { ops, errors }
    })
}

/// The embedded catalog files: (file name, text).
pub fn files() -> &'static [(&'static str, &'static str)] {
    embedded::FILES
}

/// Names of all operators, sorted.
pub fn operator_names() -> Vec<&'static str> {
    catalog().ops.iter().map(|o| o.name.as_str()).collect()
}

/// Code_Aster operators that aster-nl does not implement, with what to do instead: a
/// file using one gets a clear error naming it, not "unknown operator".
const UNSUPPORTED: &[(&str, &str)] = &[
    (
        "DEFI_FICHIER",
        "map logical units with --unit N=FILE or the F lines of a .export",
    ),
    ("INFO_MODE", "CALC_MODES prints the frequencies it finds"),
    ("EXTR_MODE", "filter the modes with CALC_MODES's CALC_FREQ"),
    (
        "MACRO_MATR_ASSE",
        "use ASSEMBLAGE, or CALC_MATR_ELEM + NUME_DDL + ASSE_MATRICE",
    ),
    ("COMB_MATR_ASSE", "assemble the combined stiffness directly"),
    (
        "MODE_ITER_INV",
        "use CALC_MODES (OPTION='CENTRE' or 'BANDE')",
    ),
    ("CALC_MODAL", "use CALC_MODES"),
    (
        "DYNA_LINE_TRAN",
        "use DYNA_VIBRA(TYPE_CALCUL='TRAN', BASE_CALCUL='PHYS', ...)",
    ),
    ("DYNA_NON_LINE", "transient responses are not computed"),
    ("STAT_NON_LINE", "static analyses are not computed"),
    ("MECA_STATIQUE", "static analyses are not computed"),
    ("CALC_CHAMP", "fields are not post-processed"),
    ("POST_ELEM", "post-processing of fields is not available"),
    (
        "POST_RELEVE_T",
        "query the result tables of the database instead",
    ),
    (
        "CREA_RESU",
        "results come from CALC_MODES, MODE_NON_LINE and REST_MODE_NONL",
    ),
    ("PROJ_CHAMP", "fields are not projected"),
    ("DEFI_CONSTANTE", "use a Python variable"),
    (
        "DEFI_NAPPE",
        "functions of two parameters are not available",
    ),
    ("LIRE_TABLE", "build the table with CREA_TABLE"),
    ("INCLUDE", "put the included commands in the file"),
    ("IMPR_CO", "`aster-nl tables DB` lists the concepts"),
    (
        "TEST_FICHIER",
        "test values with TEST_TABLE, TEST_FONCTION or TEST_RESU",
    ),
    (
        "MACR_LIGN_COUPE",
        "post-processing of fields is not available",
    ),
];

/// What to do instead of `op`, if it is a Code_Aster operator that aster-nl does not
/// implement.
pub fn unsupported(op: &str) -> Option<&'static str> {
    UNSUPPORTED.iter().find(|(n, _)| *n == op).map(|(_, h)| *h)
}

/// Type of a concept `aster-nl check` cannot know (a name of a POURSUITE file checked
/// without its database): accepted wherever a concept is expected.
pub const UNKNOWN_CONCEPT_TYPE: &str = "?";

/// The catalog of one operator.
///
/// Only this operator's file is parsed (once): a run parses the catalogs of the operators
/// it calls, not all of them (the whole set took about 2 ms, a noticeable share of a
/// short run). Each file is named after its operator (`check_consistency`).
pub fn get(op: &str) -> Option<&'static OperatorDef> {
    static PARSED: OnceLock<Vec<OnceLock<Option<OperatorDef>>>> = OnceLock::new();
    let parsed = PARSED.get_or_init(|| embedded::FILES.iter().map(|_| OnceLock::new()).collect());
    let i = embedded::FILES
        .iter()
        .position(|(file, _)| file.strip_suffix(".toml") == Some(op))?;
    parsed[i]
        .get_or_init(|| parse_embedded(i).ok().filter(|def| def.name == op))
        .as_ref()
}

/// The type an operator call produces: a concept type (`table_sdaster`...), or `"R"`,
/// `"I"`, `"TXM"` when the interpreter binds a plain Python value (e.g.
/// `EXTR_TABLE(TYPE_RESU='R')`); `None` when the operator produces nothing.
pub fn result_type(op: &str, args: &Args) -> Option<String> {
    result_type_with(get(op)?, args)
}

/// [`result_type`] for a given catalog.
pub fn result_type_with(def: &OperatorDef, args: &Args) -> Option<String> {
    if let Some(c) = def.result_type_of.as_ref().and_then(|k| args.concept(k)) {
        if c.ty != UNKNOWN_CONCEPT_TYPE {
            return Some(c.ty.clone());
        }
    }
    if let Some(rf) = &def.result_from {
        if let Some(t) = args.text(&rf.keyword).and_then(|v| rf.map.get(v)) {
            return Some(t.clone());
        }
    }
    def.result.clone()
}

#[cfg(test)]
mod tests;
