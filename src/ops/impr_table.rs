//! IMPR_TABLE: print a table (FORMAT 'TABLEAU' or 'CSV') after FILTRE, TRI and NOM_PARA;
//! TITRE replaces the table's title in the TABLEAU header.

use super::output::write_unit;
use super::table_args::{apply_tri, filters, load_table_arg, titre};
use super::OpContext;
use crate::args::Args;
use crate::error::{Error, Result};
use crate::table::filter::apply_all;
use crate::table::print::{csv, tableau, FormatR};

pub fn run(ctx: &mut OpContext<'_>, args: &Args) -> Result<()> {
    let (c, t) = load_table_arg(ctx, args, "TABLE")?;
    let mut t = apply_all(&t, &filters(args, "FILTRE")?)?;
    if let Some(tri) = args.fact("TRI") {
        apply_tri(&mut t, tri)?;
    }
    if let Some(names) = args.texts("NOM_PARA") {
        t = t
            .extract(&names)
            .map_err(|e| e.keyword("IMPR_TABLE/NOM_PARA"))?;
    }
    let fmt = FormatR::parse(args.text("FORMAT_R").unwrap_or("E12.5"))?;
    let format = args.text("FORMAT").unwrap_or("TABLEAU");
    let text = match format {
        "TABLEAU" => {
            let title = if let Some(titre) = titre(args) {
                titre
            } else if t.title.is_empty() {
                format!("ASTER CONCEPT {} DE TYPE {}", c.name, c.ty.to_uppercase())
            } else {
                t.title.clone()
            };
            tableau(&t, &title, fmt, args.text("SEPARATEUR").unwrap_or(" "))
        }
        "CSV" => csv(&t, fmt, args.text("SEPARATEUR").unwrap_or(",")),
        other => {
            return Err(
                Error::validation(format!("FORMAT '{other}' is not supported"))
                    .keyword("IMPR_TABLE/FORMAT")
                    .hint("use 'TABLEAU' or 'CSV'"),
            )
        }
    };
    let unite = args.int("UNITE").unwrap_or(8);
    write_unit(ctx, unite, &text)
}
