//! IMPR_FONCTION: print functions (COURBE=_F(FONCTION=...)) as tables, FORMAT='TABLEAU'.

use super::output::write_unit;
use super::OpContext;
use crate::args::Args;
use crate::error::{Error, Result};
use crate::function::Function;
use crate::store::function::load_function;
use crate::table::print::{tableau, FormatR};
use crate::table::{Cell, ColKind, Column, Table};

/// The points of `f` as a two-column table (NOM_PARA, NOM_RESU).
pub fn as_table(f: &Function) -> Result<Table> {
    let col = |name: &str, v: &[f64]| {
        (
            Column {
                name: name.to_string(),
                kind: ColKind::R,
            },
            v.iter().map(|&x| Cell::R(x)).collect::<Vec<_>>(),
        )
    };
    // A function whose parameter and result share a name still prints both columns.
    let resu = if f.nom_resu == f.nom_para {
        format!("{}_", f.nom_resu)
    } else {
        f.nom_resu.clone()
    };
    Table::from_columns(
        &format!("FONCTION {}", f.name),
        vec![col(&f.nom_para, &f.x), col(&resu, &f.y)],
    )
}

pub fn run(ctx: &mut OpContext<'_>, args: &Args) -> Result<()> {
    let format = args.text("FORMAT").unwrap_or("TABLEAU");
    if format != "TABLEAU" {
        return Err(
            Error::validation(format!("FORMAT '{format}' is not supported"))
                .keyword("IMPR_FONCTION/FORMAT")
                .hint("use 'TABLEAU'"),
        );
    }
    let fmt = FormatR::parse(args.text("FORMAT_R").unwrap_or("E12.5"))?;
    let mut text = String::new();
    for c in args.facts_or_empty("COURBE") {
        let fc = c.req_concept("FONCTION")?;
        let f =
            load_function(ctx.store, &fc.name).map_err(|e| e.keyword(c.key_path("FONCTION")))?;
        let t = as_table(&f)?;
        text.push_str(&tableau(&t, &t.title, fmt, " "));
    }
    let unite = args.int("UNITE").unwrap_or(8);
    write_unit(ctx, unite, &text)
}
