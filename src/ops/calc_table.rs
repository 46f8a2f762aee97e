//! CALC_TABLE: apply ACTION occurrences in order (FILTRE, TRI, EXTR, RENOMME) to a table.

use super::common::table_args::{
    apply_tri, create_table, filter_from, load_table_arg, node_numbers_as_names, titre,
};
use super::OpContext;
use crate::args::Args;
use crate::error::{Error, Result};
use crate::store::table::save_table;
use crate::table::Table;

fn action(ctx: &OpContext<'_>, t: Table, a: &Args) -> Result<Table> {
    let op = a.req_text("OPERATION")?;
    match op {
        "FILTRE" => {
            let mut f = filter_from(a)?;
            node_numbers_as_names(ctx, &t, &mut f)?;
            f.apply(&t)
        }
        "TRI" => {
            let mut t = t;
            apply_tri(&mut t, a)?;
            Ok(t)
        }
        "EXTR" => {
            let names = a.texts("NOM_PARA").ok_or_else(|| {
                Error::validation("expected parameter names").keyword(a.key_path("NOM_PARA"))
            })?;
            t.extract(&names)
                .map_err(|e| e.keyword(a.key_path("NOM_PARA")))
        }
        "RENOMME" => match a.texts("NOM_PARA").as_deref() {
            Some([old, new]) => {
                let mut t = t;
                t.rename(old, new)
                    .map_err(|e| e.keyword(a.key_path("NOM_PARA")))?;
                Ok(t)
            }
            _ => Err(
                Error::validation("RENOMME needs NOM_PARA=(old name, new name)")
                    .keyword(a.key_path("NOM_PARA")),
            ),
        },
        other => Err(
            Error::validation(format!("OPERATION '{other}' is not supported"))
                .keyword(a.key_path("OPERATION"))
                .hint("use 'FILTRE', 'TRI', 'EXTR' or 'RENOMME'"),
        ),
    }
}

pub fn run(ctx: &mut OpContext<'_>, args: &Args) -> Result<()> {
    let (c, mut t) = load_table_arg(ctx, args, "TABLE")?;
    for a in args.facts_or_empty("ACTION") {
        t = action(ctx, t, a)?;
    }
    if let Some(title) = titre(args) {
        t.title = title;
    }
    match ctx.reuse {
        Some(reuse) => {
            if reuse != c.name {
                return Err(Error::validation(format!(
                    "reuse={reuse} but TABLE={}: CALC_TABLE can only enrich the table it reads",
                    c.name
                ))
                .keyword("CALC_TABLE/TABLE"));
            }
            save_table(ctx.store, reuse, &t)
        }
        None => {
            let name = ctx.result_name()?.to_string();
            create_table(ctx, &name, &c.ty, &t)
        }
    }
}
