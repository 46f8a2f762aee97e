//! FORMULE: a formula (`formule`) from its expression VALE, its parameters NOM_PARA and
//! its constants CONTEXTE (which the language fills from FORMULE's other keywords and the
//! command file's variables: `lang::formula`). Parsed and checked here
//! (`function::formula`), stored as its definition (`store::function`).

use super::OpContext;
use crate::args::Args;
use crate::error::{Error, Result};
use crate::function::formula::{Formula, FormulaDef};
use crate::store::function::save_formula;

pub fn run(ctx: &mut OpContext<'_>, args: &Args) -> Result<()> {
    let name = ctx.result_name()?.to_string();
    if args.has("VALE_C") {
        return Err(
            Error::validation("complex formulas (VALE_C) are not supported")
                .keyword(args.key_path("VALE_C"))
                .hint("write the real and the imaginary parts as two formulas with VALE"),
        );
    }
    let constants = args
        .facts_or_empty("CONTEXTE")
        .iter()
        .map(|c| Ok((c.req_text("NOM")?.to_string(), c.req_real("VALE")?)))
        .collect::<Result<Vec<_>>>()?;
    let def = FormulaDef {
        nom_para: args.req_texts("NOM_PARA")?,
        vale: args.req_text("VALE")?.to_string(),
        constants,
    };
    let f = Formula::new(&name, def)?;
    ctx.create(&name, "formule")?;
    save_formula(ctx.store, &name, f.def())
}
