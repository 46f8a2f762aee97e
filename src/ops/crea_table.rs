//! CREA_TABLE: a table from lists, LISTE=_F(PARA, LISTE_R | LISTE_I | LISTE_K), TITRE.

use super::common::table_args::{create_table, titre};
use super::OpContext;
use crate::args::Args;
use crate::error::{Error, Result};
use crate::table::{Cell, ColKind, Column, Table};

pub fn run(ctx: &mut OpContext<'_>, args: &Args) -> Result<()> {
    let name = ctx.result_name()?.to_string();
    let mut cols = Vec::new();
    for l in args.facts_or_empty("LISTE") {
        let para = l.req_text("PARA")?.to_string();
        let given = ["LISTE_R", "LISTE_I", "LISTE_K"]
            .iter()
            .filter(|k| l.has(k))
            .count();
        if given != 1 {
            return Err(Error::validation(format!(
                "parameter {para}: give exactly one of LISTE_R, LISTE_I, LISTE_K"
            ))
            .keyword(l.path.clone()));
        }
        let (kind, cells) = if l.has("LISTE_R") {
            let v = l
                .reals("LISTE_R")
                .ok_or_else(|| bad(l, "LISTE_R", "reals"))?;
            (ColKind::R, v.into_iter().map(Cell::R).collect::<Vec<_>>())
        } else if l.has("LISTE_I") {
            let v = l
                .ints("LISTE_I")
                .ok_or_else(|| bad(l, "LISTE_I", "integers"))?;
            (ColKind::I, v.into_iter().map(Cell::I).collect())
        } else {
            let v = l
                .texts("LISTE_K")
                .ok_or_else(|| bad(l, "LISTE_K", "texts"))?;
            (ColKind::K, v.into_iter().map(Cell::K).collect())
        };
        cols.push((Column { name: para, kind }, cells));
    }
    if cols.is_empty() {
        return Err(
            Error::validation("CREA_TABLE needs at least one LISTE").keyword("CREA_TABLE/LISTE")
        );
    }
    let t = Table::from_columns(&titre(args).unwrap_or_default(), cols)
        .map_err(|e| e.keyword("CREA_TABLE/LISTE/PARA"))?;
    create_table(ctx, &name, "table_sdaster", &t)
}

fn bad(l: &Args, key: &str, what: &str) -> Error {
    Error::validation(format!("expected a list of {what}")).keyword(l.key_path(key))
}
