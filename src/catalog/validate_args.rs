//! Validation of `Args` built in code (tests, the study, other front ends) against the
//! catalog, exactly as the interpreter validates a user's call: the hand-built keywords go
//! back to a [`CommandCall`], then through [`super::validate`]. Operators only ever see
//! `Args` with the catalog's defaults filled, whoever built the call.

use crate::args::Args;
use crate::error::Error;
use crate::value::{CommandCall, ConceptRef, Keyword, Value};

/// The call `args` of `op` (with `reuse=` of the concept named, if any) validated against
/// the embedded catalog: defaults filled, bounds and rules checked. Errors name `file`;
/// the first one is returned as the call's error.
pub fn validate_args(
    op: &str,
    args: &Args,
    reuse: Option<&str>,
    file: &str,
) -> Result<Args, Error> {
    let call = CommandCall {
        op: op.to_string(),
        result: None,
        reuse: reuse.map(|name| ConceptRef {
            name: name.to_string(),
            ty: super::UNKNOWN_CONCEPT_TYPE.to_string(),
        }),
        args: keywords(args),
        span: Default::default(),
        op_span: Default::default(),
    };
    super::validate(&call, file).map_err(|mut errors| errors.remove(0))
}

/// Hand-built `Args` back to the keywords of a call (a factor keyword becomes a tuple of
/// `_F(...)`).
fn keywords(args: &Args) -> Vec<Keyword> {
    let simple = args.simple.iter().map(|(name, value, span)| Keyword {
        name: name.clone(),
        value: value.clone(),
        span: *span,
    });
    let factor = args.factor.iter().map(|(name, occs, span)| Keyword {
        name: name.clone(),
        value: Value::Seq(occs.iter().map(|o| Value::Fact(keywords(o))).collect()),
        span: *span,
    });
    simple.chain(factor).collect()
}
