//! DETRUIRE: remove concepts and all their data, including the SQL table of a table
//! concept, the CARA_CHOC sub-table of a MODE_NON_LINE result and the shocks' table of a
//! DYNA_VIBRA result (naming such a sub-table too is not an error). The concepts are named either by the newer syntax (NOM=(...)) or
//! by the classic one (CONCEPT=_F(NOM=(...)), repeatable); INFO=2 prints each name removed.

use super::OpContext;
use crate::args::Args;
use crate::error::{Error, Result};
use crate::value::Value;

pub fn run(ctx: &mut OpContext<'_>, args: &Args) -> Result<()> {
    // (names, keyword path for errors) of each place concepts are named, in file order.
    let mut groups: Vec<(Vec<String>, String)> = Vec::new();
    if args.has("NOM") {
        groups.push((names_at(args)?, args.key_path("NOM")));
    }
    for occ in args.facts_or_empty("CONCEPT") {
        groups.push((names_at(occ)?, occ.key_path("NOM")));
    }
    let verbose = args.int("INFO") == Some(2);
    let mut removed: Vec<String> = Vec::new();
    for (names, path) in groups {
        for n in names {
            if removed.contains(&n) {
                continue;
            }
            if ctx.store.concept_type(&n)?.is_none() {
                return Err(
                    Error::input(format!("{n} is not a concept of this study")).keyword(path)
                );
            }
            let mut gone = crate::store::mnl::owned_concepts(ctx.store, &n)?;
            gone.extend(crate::store::tran_gene::owned_concepts(ctx.store, &n)?);
            for sub in &gone {
                ctx.store.delete_concept(sub)?;
            }
            ctx.store.delete_concept(&n)?;
            gone.insert(0, n);
            if verbose {
                ctx.say(&format!("DETRUIRE: {} removed", gone.join(", ")))?;
            }
            removed.extend(gone);
        }
    }
    Ok(())
}

/// The concept names of one NOM keyword (a name or a sequence of names).
fn names_at(a: &Args) -> Result<Vec<String>> {
    match a.value("NOM") {
        Some(Value::Seq(v)) => v.iter().map(name_of).collect::<Option<_>>(),
        Some(v) => name_of(v).map(|n| vec![n]),
        None => None,
    }
    .ok_or_else(|| Error::validation("expected concepts").keyword(a.key_path("NOM")))
}

fn name_of(v: &Value) -> Option<String> {
    match v {
        Value::Concept(c) => Some(c.name.clone()),
        Value::Str(s) => Some(s.clone()),
        _ => None,
    }
}
