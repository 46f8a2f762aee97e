//! EXTR_TABLE: one value of a table, after FILTRE (exactly one row must remain).
//! TYPE_RESU 'R', 'I', 'K' hands back a plain value
//! (`ctx.value`); 'TABLE_SDASTER' (or 'TABLE_CONTAINER', 'FONCTION_SDASTER') copies the
//! concept the cell names (a per-row object) into the result.

use super::common::table_args::{create_table, filters_for, load_table_arg};
use super::OpContext;
use crate::args::Args;
use crate::error::{Error, Result};
use crate::store::function::{load_function, save_function};
use crate::store::table::load_table;
use crate::table::filter::apply_all;
use crate::table::{Cell, Table};
use crate::value::Value;

/// The single remaining row's cell of `para`, or a clear error.
pub fn single_cell(t: &Table, para: &str, what: &str) -> Result<Cell> {
    let j = t.req_col(para)?;
    match t.rows.as_slice() {
        [row] => Ok(row.get(j).cloned().unwrap_or(Cell::Null)),
        rows => Err(Error::input(format!(
            "{what}: {} rows remain after FILTRE, exactly one is needed",
            rows.len()
        ))
        .hint("add or tighten FILTRE so that a single row is selected")),
    }
}

pub fn run(ctx: &mut OpContext<'_>, args: &Args) -> Result<()> {
    let (c, t) = load_table_arg(ctx, args, "TABLE")?;
    let t = apply_all(&t, &filters_for(ctx, &t, args, "FILTRE")?)?;
    let para = args.req_text("NOM_PARA")?;
    let cell = single_cell(&t, para, &format!("EXTR_TABLE on {}", c.name))
        .map_err(|e| e.keyword("EXTR_TABLE/FILTRE"))?;
    let type_resu = args.req_text("TYPE_RESU")?;
    let wrong = |want: &str| {
        Error::input(format!("the cell {para} holds {cell}, not {want}"))
            .keyword("EXTR_TABLE/TYPE_RESU")
    };
    match type_resu {
        "R" => ctx.value = Some(Value::Real(cell.as_f64().ok_or_else(|| wrong("a number"))?)),
        "I" => match cell {
            Cell::I(i) => ctx.value = Some(Value::Int(i)),
            _ => return Err(wrong("an integer")),
        },
        "K" => match &cell {
            Cell::K(s) => ctx.value = Some(Value::Str(s.clone())),
            _ => return Err(wrong("a text")),
        },
        other => {
            let target = cell
                .as_text()
                .ok_or_else(|| wrong("a concept name"))?
                .to_string();
            let ty = ctx.store.concept_type(&target)?.ok_or_else(|| {
                Error::input(format!(
                    "the cell {para} names {target}, which is not a concept of this study"
                ))
                .keyword("EXTR_TABLE/NOM_PARA")
            })?;
            if ty != other.to_ascii_lowercase() {
                return Err(Error::input(format!("{target} is a {ty}, not a {other}"))
                    .keyword("EXTR_TABLE/TYPE_RESU")
                    .hint(format!("use TYPE_RESU='{}'", ty.to_uppercase())));
            }
            let name = ctx.result_name()?.to_string();
            match ty.as_str() {
                "table_sdaster" | "table_container" => {
                    let sub = load_table(ctx.store, &target)?;
                    create_table(ctx, &name, &ty, &sub)?;
                }
                "fonction_sdaster" => {
                    let mut f = load_function(ctx.store, &target)?;
                    f.name = name.clone();
                    ctx.create(&name, &ty)?;
                    save_function(ctx.store, &name, &f)?;
                }
                _ => {
                    return Err(Error::input(format!("EXTR_TABLE cannot extract a {ty}"))
                        .keyword("EXTR_TABLE/TYPE_RESU")
                        .hint("tables and functions can be extracted; use the concept named in the table directly"))
                }
            }
        }
    }
    Ok(())
}
