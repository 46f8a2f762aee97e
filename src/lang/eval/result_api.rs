//! The methods of Code_Aster's Python API on a DYNA_VIBRA result (`tran_gene`) that its test
//! files call (docs/mode_non_line.md, "Files written with Code_Aster's Python API"):
//! `R.LIST_ARCH()`, `R.FORCE_NORMALE(i)` and `R.VARI_INTERNE(i, describe=True)`. Their
//! arguments are checked here (so that `aster-nl check` reports a wrong one); the host reads
//! the result. numpy arrays are lists here: a 2-D array is a list of rows.

use super::Evaluator;
use crate::error::Result;
use crate::lang::ast::{Arg, Name};
use crate::value::{ConceptRef, ResultMethod, Span, Value};

/// The methods offered, for messages.
pub(super) const METHODS: &str = "LIST_ARCH(), FORCE_NORMALE(i), VARI_INTERNE(i, describe=...)";

/// Whether `ty` is a concept type these methods apply to (`?`: one `check` could not type).
pub(super) fn has_result_methods(ty: &str) -> bool {
    ty == "tran_gene" || ty == crate::catalog::UNKNOWN_CONCEPT_TYPE
}

impl Evaluator<'_> {
    /// `R.method(...)` on the DYNA_VIBRA result `r`; `None` when `method` is not one of
    /// them (the caller reports it).
    pub(super) fn result_method(
        &mut self,
        r: &ConceptRef,
        attr: &Name,
        args: &[Arg],
        span: Span,
    ) -> Result<Option<Value>> {
        let name = attr.text.as_str();
        if !matches!(name, "LIST_ARCH" | "FORCE_NORMALE" | "VARI_INTERNE") {
            return Ok(None);
        }
        let (pos, kws) = self.args(args)?;
        let allowed: &[&str] = match name {
            "LIST_ARCH" => &[],
            "FORCE_NORMALE" => &["inoli"],
            _ => &["inoli", "describe"],
        };
        if pos.len() > allowed.len() {
            return Err(self.syntax(
                format!(
                    "{}.{name}() takes {} argument(s): {}",
                    r.name,
                    allowed.len(),
                    if allowed.is_empty() {
                        "none".to_string()
                    } else {
                        allowed.join(", ")
                    }
                ),
                pos[allowed.len()].1,
            ));
        }
        let mut given: Vec<(&str, Value, Span)> = allowed
            .iter()
            .zip(pos)
            .map(|(n, (v, s))| (*n, v, s))
            .collect();
        for k in kws {
            let Some(n) = allowed.iter().find(|n| **n == k.name) else {
                return Err(self.syntax(
                    format!(
                        "{}.{name}() has no argument '{}'{}",
                        r.name,
                        k.name,
                        if allowed.is_empty() {
                            String::new()
                        } else {
                            format!(" (it takes {})", allowed.join(", "))
                        }
                    ),
                    k.span,
                ));
            };
            if given.iter().any(|g| g.0 == *n) {
                return Err(self.syntax(format!("argument '{n}' is given twice"), k.span));
            }
            given.push((n, k.value, k.span));
        }
        let get = |n: &str| given.iter().find(|g| g.0 == n);
        let index = match get("inoli") {
            None => None,
            Some((_, Value::Unknown, _)) => return Ok(Some(Value::Unknown)),
            // Code_Aster's -1 is "not given": the first nonlinearity, with a note.
            Some((_, Value::Int(-1), _)) => None,
            Some((_, Value::Int(i), _)) => Some(*i),
            Some((_, v, s)) => {
                return Err(self.input(
                    format!(
                        "{}.{name}(inoli): the nonlinearity's index is an integer (1 for the \
                         first COMPORTEMENT occurrence), not {}",
                        r.name,
                        v.kind_name()
                    ),
                    *s,
                ))
            }
        };
        let describe = match get("describe") {
            None => true,
            Some((_, Value::Bool(b), _)) => *b,
            Some((_, Value::Int(i), _)) => *i != 0,
            Some((_, Value::Unknown, _)) => true,
            Some((_, v, s)) => {
                return Err(self.input(
                    format!("describe= is True or False, not {}", v.kind_name()),
                    *s,
                ))
            }
        };
        let method = match name {
            "LIST_ARCH" => ResultMethod::ListArch,
            "FORCE_NORMALE" => ResultMethod::NormalForce(index),
            _ => ResultMethod::InternalVariables { index, describe },
        };
        let v = self
            .host
            .result_method(r, method)
            .map_err(|e| e.at(self.file, span))?;
        Ok(Some(v))
    }
}
