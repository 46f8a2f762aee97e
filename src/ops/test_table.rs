//! TEST_TABLE: test one value of a table (exactly one row after FILTRE) or, with
//! TYPE_TEST, the SOMM_ABS / SOMM / MAX / MIN of a column.

use super::extr_table::single_cell;
use super::table_args::{filters, load_table_arg};
use super::testing::{checks_from_args, TestValue};
use super::OpContext;
use crate::args::Args;
use crate::error::{Error, Result};
use crate::table::filter::apply_all;
use crate::table::{Cell, ColKind, Table};

/// The value TYPE_TEST computes over the non-empty cells of `para`.
pub fn type_test(t: &Table, para: &str, kind: &str) -> Result<TestValue> {
    let col = t.column(para).ok_or_else(|| {
        t.req_col(para)
            .err()
            .unwrap_or_else(|| Error::internal("column"))
    })?;
    let cells: Vec<&Cell> = t
        .column_cells(para)?
        .into_iter()
        .filter(|c| !c.is_null())
        .collect();
    if col.kind == ColKind::K {
        return Err(
            Error::input(format!("TYPE_TEST needs numbers, {para} holds texts"))
                .keyword("TEST_TABLE/TYPE_TEST"),
        );
    }
    if cells.is_empty() && matches!(kind, "MAX" | "MIN") {
        return Err(
            Error::input(format!("{para} has no value to take the {kind} of"))
                .keyword("TEST_TABLE/FILTRE"),
        );
    }
    if col.kind == ColKind::I {
        let v: Vec<i64> = cells
            .iter()
            .filter_map(|c| if let Cell::I(i) = c { Some(*i) } else { None })
            .collect();
        let r = match kind {
            "SOMM_ABS" => v.iter().map(|x| x.abs()).sum(),
            "SOMM" => v.iter().sum(),
            "MAX" => v.iter().copied().max().unwrap_or(0),
            "MIN" => v.iter().copied().min().unwrap_or(0),
            other => return Err(unknown(other)),
        };
        return Ok(TestValue::I(r));
    }
    let v: Vec<f64> = cells.iter().filter_map(|c| c.as_f64()).collect();
    let r = match kind {
        "SOMM_ABS" => v.iter().map(|x| x.abs()).sum(),
        "SOMM" => v.iter().sum(),
        "MAX" => v.iter().copied().fold(f64::NEG_INFINITY, f64::max),
        "MIN" => v.iter().copied().fold(f64::INFINITY, f64::min),
        other => return Err(unknown(other)),
    };
    Ok(TestValue::R(r))
}

fn unknown(k: &str) -> Error {
    Error::validation(format!("unknown TYPE_TEST '{k}'"))
        .keyword("TEST_TABLE/TYPE_TEST")
        .hint("use 'SOMM_ABS', 'SOMM', 'MAX' or 'MIN'")
}

pub fn run(ctx: &mut OpContext<'_>, args: &Args) -> Result<()> {
    let (c, t) = load_table_arg(ctx, args, "TABLE")?;
    let fl = filters(args, "FILTRE")?;
    let t = apply_all(&t, &fl)?;
    let para = args.req_text("NOM_PARA")?;
    t.req_col(para)
        .map_err(|e| e.keyword("TEST_TABLE/NOM_PARA"))?;
    let computed = match args.text("TYPE_TEST") {
        Some(k) => type_test(&t, para, k)?,
        None => match single_cell(&t, para, &format!("TEST_TABLE on {}", c.name)).map_err(|e| {
            e.keyword("TEST_TABLE/FILTRE")
                .hint("add FILTRE to select one row, or give TYPE_TEST")
        })? {
            Cell::R(x) => TestValue::R(x),
            Cell::I(i) => TestValue::I(i),
            Cell::K(s) => TestValue::K(s),
            Cell::Null => {
                return Err(
                    Error::input(format!("the selected cell of {para} is empty"))
                        .keyword("TEST_TABLE/NOM_PARA"),
                )
            }
        },
    };
    let outcomes = checks_from_args(args, &computed)?;
    let sel: Vec<String> = fl.iter().map(|f| f.describe()).collect();
    let what = args
        .text("TYPE_TEST")
        .map(|k| format!(" {k}"))
        .unwrap_or_default();
    ctx.say(format!(" ---- TABLE {}  {para}{what}  {}", c.name, sel.join(" ")).trim_end())?;
    for o in outcomes {
        ctx.say(&o.line)?;
        ctx.tests.push(o);
    }
    Ok(())
}
