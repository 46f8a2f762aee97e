//! How DYNA_LINE runs the operators it chains: a call built as `Args`, validated against
//! that operator's catalog (its defaults and bounds, as if the user had written it), run
//! in the same transaction with its own result name, and its errors told as DYNA_LINE's.

use super::super::{lookup, OpContext};
use crate::args::Args;
use crate::error::{Error, Result};
use crate::value::{ConceptRef, Span, Value};

/// A call of `op` being built.
pub struct Call {
    op: &'static str,
    args: Args,
}

impl Call {
    pub fn new(op: &'static str) -> Self {
        Call {
            op,
            args: Args::new(op),
        }
    }

    /// KEY=value.
    pub fn set(mut self, key: &str, value: Value) -> Self {
        self.args
            .simple
            .push((key.to_string(), value, Span::default()));
        self
    }

    pub fn text(self, key: &str, v: &str) -> Self {
        self.set(key, Value::Str(v.to_string()))
    }

    pub fn co(self, key: &str, name: &str) -> Self {
        self.set(key, Value::Co(name.to_string()))
    }

    /// KEY=<the stored concept `name`>, with its type as the store knows it.
    pub fn concept(self, ctx: &OpContext<'_>, key: &str, name: &str) -> Result<Self> {
        Ok(self.set(key, concept(ctx, name)?))
    }

    /// A factor keyword with these occurrences.
    pub fn fact(mut self, key: &str, occurrences: Vec<Args>) -> Self {
        self.args
            .factor
            .push((key.to_string(), occurrences, Span::default()));
        self
    }

    /// Run it: `result` names its result (None for a macro whose results are CO names).
    /// Its errors name `blame`, the keyword of DYNA_LINE that asked for this step, unless
    /// they are about a keyword DYNA_LINE passed on as the user wrote it (`passed`: the
    /// factor keywords copied, whose paths then read DYNA_LINE/...).
    pub fn run(
        self,
        ctx: &mut OpContext<'_>,
        result: Option<&str>,
        blame: &str,
        passed: &[&str],
    ) -> Result<()> {
        let op = self.op;
        let told = |e: Error| as_dyna_line(e, op, blame, passed);
        let f = lookup(op).ok_or_else(|| Error::internal(format!("{op} is not an operator")))?;
        let args = crate::catalog::validate_args(op, &self.args, None, ctx.file).map_err(told)?;
        let mut sub = OpContext::new(ctx.store, op, &mut *ctx.out, ctx.units, &mut *ctx.tests);
        sub.result = result;
        sub.file = ctx.file;
        sub.line = ctx.line;
        sub.ignored_alarms = ctx.ignored_alarms;
        sub.alarms_are_errors = ctx.alarms_are_errors;
        sub.tole_machine = ctx.tole_machine;
        let outcome = f(&mut sub, &args);
        let created = std::mem::take(&mut sub.created);
        drop(sub);
        ctx.created.extend(created);
        outcome.map_err(told)
    }
}

/// The stored concept `name` as a keyword value.
pub fn concept(ctx: &OpContext<'_>, name: &str) -> Result<Value> {
    let ty = ctx
        .store
        .concept_type(name)?
        .ok_or_else(|| Error::internal(format!("DYNA_LINE: {name} was not created")))?;
    Ok(Value::Concept(ConceptRef {
        name: name.to_string(),
        ty,
    }))
}

/// One occurrence of a factor keyword of the call of `op`.
pub fn occurrence(op: &str, fact: &str, items: Vec<(&str, Value)>) -> Args {
    let mut a = Args::new(format!("{op}/{fact}"));
    for (k, v) in items {
        a.simple.push((k.to_string(), v, Span::default()));
    }
    a
}

/// The user's occurrences of a factor keyword of DYNA_LINE, for the same factor keyword of
/// `op` (their absent keywords left out, the catalog of `op` filling its own defaults).
pub fn passed_on(args: &Args, fact: &str, op: &str) -> Option<Vec<Args>> {
    let occurrences = args.facts(fact)?;
    Some(
        occurrences
            .iter()
            .map(|occ| {
                let mut copy = Args::new(format!("{op}/{fact}"));
                copy.simple = occ
                    .simple
                    .iter()
                    .filter(|(_, v, _)| *v != Value::None)
                    .cloned()
                    .collect();
                copy.factor = occ.factor.clone();
                copy
            })
            .collect(),
    )
}

/// An error of a chained operator, told as DYNA_LINE's: about a factor keyword passed on
/// as written, it names that keyword under DYNA_LINE; otherwise it says which step failed
/// and names the keyword of DYNA_LINE behind that step.
fn as_dyna_line(mut e: Error, op: &str, blame: &str, passed: &[&str]) -> Error {
    let on_passed = e.keyword.as_deref().and_then(|k| {
        let rest = k.strip_prefix(op)?.strip_prefix('/')?;
        passed
            .iter()
            .any(|p| {
                rest == *p
                    || rest.starts_with(&format!("{p}/"))
                    || rest.starts_with(&format!("{p}["))
            })
            .then(|| format!("DYNA_LINE/{rest}"))
    });
    match on_passed {
        Some(k) => e.keyword = Some(k),
        None => {
            let inner = e.keyword.take();
            e.message = match inner {
                Some(k) => format!("{op} (run by DYNA_LINE), {k}: {}", e.message),
                None => format!("{op} (run by DYNA_LINE): {}", e.message),
            };
            e.keyword = Some(blame.to_string());
        }
    }
    e
}
