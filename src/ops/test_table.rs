//! TEST_TABLE: test one value of a table (exactly one row after FILTRE holding a value of
//! NOM_PARA, as Code_Aster counts them) or, with
//! TYPE_TEST, the SOMM_ABS / SOMM / MAX / MIN of a column.

use super::common::table_args::{filters_for, load_table_arg};
use super::common::testing::{checks_with_floor, header_line, TestValue};
use super::extr_table::single_cell;
use super::OpContext;
use crate::args::Args;
use crate::error::{Error, Result};
use crate::table::aggregate::{aggregate, Aggregate};
use crate::table::filter::apply_all;
use crate::table::{Cell, Table};

/// The value TYPE_TEST computes over the non-empty cells of `para`.
fn type_test(t: &Table, para: &str, kind: &str) -> Result<TestValue> {
    let agg = Aggregate::parse(kind).ok_or_else(|| {
        Error::validation(format!("unknown TYPE_TEST '{kind}'"))
            .keyword("TEST_TABLE/TYPE_TEST")
            .hint("use 'SOMM_ABS', 'SOMM', 'MAX' or 'MIN'")
    })?;
    match aggregate(t, para, agg).map_err(|e| e.keyword("TEST_TABLE/TYPE_TEST"))? {
        Cell::I(i) => Ok(TestValue::I(i)),
        Cell::R(x) => Ok(TestValue::R(x)),
        other => Err(Error::internal(format!("aggregate gave {other:?}"))),
    }
}

/// The rows whose cell of `para` holds a value, when some do: Code_Aster's TEST_TABLE
/// (tbliva) counts only those, so a filter leaving one row with the value and others
/// without it (POST_DYNA_MODA_T's USURE table, one row per statistic) selects that row.
fn valued(t: &Table, para: &str) -> Result<Table> {
    let j = t.req_col(para)?;
    let has = |row: &Vec<Cell>| !matches!(row.get(j), None | Some(Cell::Null));
    if !t.rows.iter().any(has) {
        return Ok(t.clone());
    }
    let mut out = t.clone();
    out.rows.retain(has);
    Ok(out)
}

pub fn run(ctx: &mut OpContext<'_>, args: &Args) -> Result<()> {
    let (c, t) = load_table_arg(ctx, args, "TABLE")?;
    let fl = filters_for(ctx, &t, args, "FILTRE")?;
    let t = apply_all(&t, &fl)?;
    let para = args.req_text("NOM_PARA")?;
    t.req_col(para)
        .map_err(|e| e.keyword("TEST_TABLE/NOM_PARA"))?;
    let computed = match args.text("TYPE_TEST") {
        Some(k) => type_test(&t, para, k)?,
        None => match single_cell(
            &valued(&t, para)?,
            para,
            &format!("TEST_TABLE on {}", c.name),
        )
        .map_err(|e| {
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
    let outcomes = checks_with_floor(args, &computed, ctx.tole_machine)?;
    let sel: Vec<String> = fl.iter().map(|f| f.describe()).collect();
    let what = args
        .text("TYPE_TEST")
        .map(|k| format!(" {k}"))
        .unwrap_or_default();
    ctx.say(format!(" ---- TABLE {}  {para}{what}  {}", c.name, sel.join(" ")).trim_end())?;
    ctx.say(&header_line())?;
    for o in outcomes {
        ctx.say(&o.line)?;
        ctx.tests.push(o);
    }
    Ok(())
}
