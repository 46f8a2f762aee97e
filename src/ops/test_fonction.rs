//! TEST_FONCTION: VALEUR=_F(FONCTION, NOM_PARA, VALE_PARA, VALE_CALC / VALE_REFE...),
//! repeatable: the function evaluated at VALE_PARA, checked by `ops::common::testing`.

use super::common::testing::{checks_with_floor, header_line, TestValue};
use super::OpContext;
use crate::args::Args;
use crate::error::{Error, Result};
use crate::store::function::load_any_function;

pub fn run(ctx: &mut OpContext<'_>, args: &Args) -> Result<()> {
    for v in args.facts_or_empty("VALEUR") {
        let fc = v.req_concept("FONCTION")?;
        let f = load_any_function(ctx.store, &fc.name)
            .map_err(|e| e.keyword(v.key_path("FONCTION")))?;
        // NOM_PARA, when given, must name the function's parameter.
        if let Some(names) = v.texts("NOM_PARA") {
            if names.as_slice() != [f.nom_para().to_string()] {
                return Err(Error::validation(format!(
                    "function {} is a function of {}, not of {}",
                    f.name(),
                    f.nom_para(),
                    names.join(", ")
                ))
                .keyword(v.key_path("NOM_PARA")));
            }
        }
        let x = v.req_real("VALE_PARA")?;
        let y = f.eval(x).map_err(|e| e.keyword(v.key_path("VALE_PARA")))?;
        let outcomes = checks_with_floor(v, &TestValue::R(y), ctx.tole_machine)?;
        ctx.say(&format!(
            " ---- FONCTION {}  {}={x}",
            f.name(),
            f.nom_para()
        ))?;
        ctx.say(&header_line())?;
        for o in outcomes {
            ctx.say(&o.line)?;
            ctx.tests.push(o);
        }
    }
    Ok(())
}
