//! RECU_FONCTION (from a table): the function PARA_Y(PARA_X) built from two columns of a
//! table after FILTRE, taking the rows in table order (abscissas must increase).

use super::defi_fonction::apply_options;
use super::table_args::{filters, load_table_arg};
use super::OpContext;
use crate::args::Args;
use crate::error::{Error, Result};
use crate::function::{Function, Interp, Prol};
use crate::store::function::save_function;
use crate::table::filter::apply_all;
use crate::table::Table;

fn column(t: &Table, table: &str, para: &str, key: &str) -> Result<Vec<f64>> {
    t.column_cells(para)
        .map_err(|e| e.keyword(format!("RECU_FONCTION/{key}")))?
        .into_iter()
        .enumerate()
        .map(|(i, c)| {
            if c.is_null() {
                return Err(Error::input(format!(
                    "table {table}: row {} has no value of {para}",
                    i + 1
                ))
                .keyword(format!("RECU_FONCTION/{key}"))
                .hint(format!(
                    "drop empty rows with FILTRE=_F(NOM_PARA='{para}', CRIT_COMP='NON_VIDE')"
                )));
            }
            c.as_f64().ok_or_else(|| {
                Error::input(format!(
                    "table {table}: {para} holds texts, a function needs numbers"
                ))
                .keyword(format!("RECU_FONCTION/{key}"))
            })
        })
        .collect()
}

pub fn run(ctx: &mut OpContext<'_>, args: &Args) -> Result<()> {
    let name = ctx.result_name()?.to_string();
    let (c, t) = load_table_arg(ctx, args, "TABLE")?;
    let t = apply_all(&t, &filters(args, "FILTRE")?)?;
    let px = args.req_text("PARA_X")?;
    let py = args.req_text("PARA_Y")?;
    let x = column(&t, &c.name, px, "PARA_X")?;
    let y = column(&t, &c.name, py, "PARA_Y")?;
    if let Some(k) = x.windows(2).position(|w| w[1] <= w[0]) {
        return Err(Error::input(format!(
            "table {}: {px} must increase strictly along the rows, but row {} does not exceed row {}",
            c.name,
            k + 2,
            k + 1
        ))
        .keyword("RECU_FONCTION/PARA_X")
        .hint(format!(
            "sort the table first: CALC_TABLE(TABLE={}, ACTION=_F(OPERATION='TRI', NOM_PARA='{px}'))",
            c.name
        )));
    }
    let mut f = Function {
        name: name.clone(),
        nom_para: args.text("NOM_PARA").unwrap_or(px).to_string(),
        nom_resu: args.text("NOM_RESU").unwrap_or(py).to_string(),
        x,
        y,
        interpol: (Interp::Lin, Interp::Lin),
        prol_gauche: Prol::Exclu,
        prol_droite: Prol::Exclu,
    };
    apply_options(&mut f, args)?;
    ctx.create(&name, "fonction_sdaster")?;
    save_function(ctx.store, &name, &f)
}
