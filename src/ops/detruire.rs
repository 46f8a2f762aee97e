//! DETRUIRE: remove concepts (CONCEPT=_F(NOM=(...)), repeatable) and all their data,
//! including the SQL table of a table concept.

use super::OpContext;
use crate::args::Args;
use crate::error::{Error, Result};
use crate::value::Value;

pub fn run(ctx: &mut OpContext<'_>, args: &Args) -> Result<()> {
    for occ in args.facts_or_empty("CONCEPT") {
        let names: Vec<String> = match occ.value("NOM") {
            Some(Value::Seq(v)) => v.iter().map(name_of).collect::<Option<_>>(),
            Some(v) => name_of(v).map(|n| vec![n]),
            None => None,
        }
        .ok_or_else(|| Error::validation("expected concepts").keyword(occ.key_path("NOM")))?;
        for n in names {
            if ctx.store.concept_type(&n)?.is_none() {
                return Err(Error::input(format!("{n} is not a concept of this study"))
                    .keyword(occ.key_path("NOM")));
            }
            ctx.store.delete_concept(&n)?;
        }
    }
    Ok(())
}

fn name_of(v: &Value) -> Option<String> {
    match v {
        Value::Concept(c) => Some(c.name.clone()),
        Value::Str(s) => Some(s.clone()),
        _ => None,
    }
}
