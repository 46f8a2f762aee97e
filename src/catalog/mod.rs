//! Operator catalogs: `commands/*.toml`, embedded at build time (see `build.rs`), parsed
//! once, then used to validate calls ([`validate`]), print help ([`describe`],
//! [`summary`]) and generate the command reference ([`markdown_reference`]).

mod check;
pub mod def;
mod docs;
mod print;
mod suggest;
mod validate;

pub use check::check_consistency;
pub use def::{FactDef, OperatorDef, Reuse, Rule, RuleKind, SimpDef, Statut, When};
pub use docs::markdown_reference;
pub use print::{describe, summary};
pub use suggest::closest;
pub use validate::{validate, validate_with};

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

/// The catalogs, parsed on first use.
pub fn catalog() -> &'static Catalog {
    static CATALOG: OnceLock<Catalog> = OnceLock::new();
    CATALOG.get_or_init(|| {
        let mut ops = Vec::new();
        let mut errors = Vec::new();
        for (file, text) in embedded::FILES {
            match parse(file, text) {
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

/// The catalog of one operator.
/// Type of a concept `aster-nl check` cannot know (a name of a POURSUITE file checked
/// without its database): accepted wherever a concept is expected.
pub const UNKNOWN_CONCEPT_TYPE: &str = "?";

pub fn get(op: &str) -> Option<&'static OperatorDef> {
    catalog().ops.iter().find(|o| o.name == op)
}

/// The type an operator call produces: a concept type (`table_sdaster`...), or `"R"`,
/// `"I"`, `"TXM"` when the interpreter binds a plain Python value (e.g.
/// `EXTR_TABLE(TYPE_RESU='R')`); `None` when the operator produces nothing.
pub fn result_type(op: &str, args: &Args) -> Option<String> {
    result_type_with(get(op)?, args)
}

/// [`result_type`] for a given catalog.
pub fn result_type_with(def: &OperatorDef, args: &Args) -> Option<String> {
    if let Some(rf) = &def.result_from {
        if let Some(t) = args.text(&rf.keyword).and_then(|v| rf.map.get(v)) {
            return Some(t.clone());
        }
    }
    def.result.clone()
}

#[cfg(test)]
mod tests;
