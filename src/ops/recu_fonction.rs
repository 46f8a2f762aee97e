//! RECU_FONCTION from a table: the function PARA_Y(PARA_X) built from two columns of a
//! table after FILTRE. As in Code_Aster, rows whose abscissa is not increasing (a branch
//! that turns back, a table extended by a `reuse=` restart) are sorted by abscissa with
//! alarm FONCT0_62; rows repeating an abscissa already taken are dropped, with a note.
//!
//! RECU_FONCTION from a DYNA_VIBRA result (RESU_GENE=): a physical component restored from
//! the generalized coordinates, or a shock's FN, FT1, ... by INTITULE or node.
//!
//! RECU_FONCTION from a `dyna_trans` (RESULTAT=, NOM_CHAM=, NOEUD= | GROUP_NO=, NOM_CMP=):
//! the time history of one component, NOM_PARA='INST' and NOM_RESU the component's name,
//! as in Code_Aster.

use super::common::table_args::{filters_for, load_table_arg};
use super::common::{dyna_trans, tran_gene};
use super::defi_fonction::function_with_options;
use super::OpContext;
use crate::args::Args;
use crate::error::{Error, Result};
use crate::function::{order_points, Reorder};
use crate::store::function::save_function;
use crate::table::filter::apply_all;
use crate::table::{Cell, Table};

/// The points (PARA_X, PARA_Y) of the rows, in table order. As in Code_Aster, where the
/// two-column extract of a table loses its all-empty rows, rows empty in both parameters
/// are skipped; a row with only one of them is an error.
fn points(t: &Table, table: &str, px: &str, py: &str) -> Result<(Vec<f64>, Vec<f64>)> {
    let jx = t
        .req_col(px)
        .map_err(|e| e.keyword("RECU_FONCTION/PARA_X"))?;
    let jy = t
        .req_col(py)
        .map_err(|e| e.keyword("RECU_FONCTION/PARA_Y"))?;
    let (mut x, mut y) = (Vec::new(), Vec::new());
    for (i, row) in t.rows.iter().enumerate() {
        let (cx, cy) = (
            row.get(jx).unwrap_or(&Cell::Null),
            row.get(jy).unwrap_or(&Cell::Null),
        );
        if cx.is_null() && cy.is_null() {
            continue;
        }
        for (c, para, key) in [(cx, px, "PARA_X"), (cy, py, "PARA_Y")] {
            if c.is_null() {
                return Err(Error::input(format!(
                    "table {table}: row {} has no value of {para}",
                    i + 1
                ))
                .keyword(format!("RECU_FONCTION/{key}"))
                .hint(format!(
                    "drop such rows with FILTRE=_F(NOM_PARA='{para}', CRIT_COMP='NON_VIDE')"
                )));
            }
        }
        match (cx.as_f64(), cy.as_f64()) {
            (Some(a), Some(b)) => {
                x.push(a);
                y.push(b);
            }
            _ => {
                let (para, key) = if cx.as_f64().is_none() {
                    (px, "PARA_X")
                } else {
                    (py, "PARA_Y")
                };
                return Err(Error::input(format!(
                    "table {table}: {para} holds texts, a function needs numbers"
                ))
                .keyword(format!("RECU_FONCTION/{key}")));
            }
        }
    }
    Ok((x, y))
}

/// The keywords choosing instants of a transient result (INTERP_NUME, CRITERE and
/// PRECISION have defaults: always present, they only matter with these).
const INSTANT_KEYS: [&str; 5] = ["TOUT_INST", "TOUT_ORDRE", "NUME_ORDRE", "INST", "LIST_INST"];

pub fn run(ctx: &mut OpContext<'_>, args: &Args) -> Result<()> {
    if args.text("MULT_APPUI") == Some("OUI") && args.concept("RESU_GENE").is_none() {
        return Err(Error::validation(
            "MULT_APPUI='OUI' restores the absolute motion of a DYNA_VIBRA result on a modal basis",
        )
        .keyword(args.key_path("MULT_APPUI"))
        .hint("give the result as RESU_GENE (REST_GENE_PHYS with MULT_APPUI='OUI' writes absolute fields)"));
    }
    // The catalog's UN_PARMI(TABLE, RESULTAT, RESU_GENE) leaves one of them.
    if args.concept("RESULTAT").is_some() {
        from_result(ctx, args)
    } else if args.concept("RESU_GENE").is_some() {
        from_resu_gene(ctx, args)
    } else {
        if let Some(k) = INSTANT_KEYS.iter().find(|k| args.has(k)) {
            return Err(Error::validation(format!(
                "{k} chooses instants of a transient result (RESULTAT or RESU_GENE), not rows of a table"
            ))
            .keyword(args.key_path(k))
            .hint("select rows of a table with FILTRE"));
        }
        from_table(ctx, args)
    }
}

/// The history (x the archived instants, increasing) at the instants the call asks for
/// (TOUT_INST, NUME_ORDRE, INST or LIST_INST; INTERP_NUME='LIN' interpolates between
/// archived instants).
fn at_instants(args: &Args, x: Vec<f64>, y: Vec<f64>) -> Result<(Vec<f64>, Vec<f64>)> {
    let chosen = super::common::instants::picks(args, &x, "INTERP_NUME")?;
    let at = |i: usize| y.get(i).copied().unwrap_or(f64::NAN);
    let ys = chosen
        .iter()
        .map(|p| super::common::instants::value(p, at))
        .collect();
    Ok((chosen.iter().map(|p| p.t).collect(), ys))
}

/// From a DYNA_VIBRA result: a physical component (NOM_CHAM, NOEUD | GROUP_NO, NOM_CMP)
/// restored at the archived instants, or a shock's parameter (PARA_Y) by INTITULE,
/// NOEUD_CHOC or GROUP_NO_CHOC. The instants increase.
fn from_resu_gene(ctx: &mut OpContext<'_>, args: &Args) -> Result<()> {
    let name = ctx.result_name()?.to_string();
    let result = args.req_concept("RESU_GENE")?.name.clone();
    let kw = |k: &str| args.key_path(k);
    let payload = crate::store::tran_gene::load_payload(ctx.store, &result)?;
    let node_of = |key: &str, group_key: &str| -> Result<Option<String>> {
        if let Some(n) = args.text(key) {
            return Ok(Some(n.to_string()));
        }
        let Some(group) = args.text(group_key) else {
            return Ok(None);
        };
        let (_, modes) = super::common::gene::numbering_and_basis(
            ctx.store,
            &payload.numbering,
            None,
            "RECU_FONCTION",
        )?;
        super::common::nodes::one_node_of_group(
            ctx.store,
            &modes.numbering.mesh,
            group,
            super::common::nodes::OneNode {
                reason: "RECU_FONCTION extracts the history of one node",
                hint: None,
            },
            kw(group_key),
        )
        .map(Some)
    };
    let (x, y, para, resu) = if let Some(field) = args.text("NOM_CHAM") {
        let node = node_of("NOEUD", "GROUP_NO")?
            .ok_or_else(|| Error::validation("give NOEUD or GROUP_NO").keyword(kw("NOEUD")))?;
        let cmp = args.req_text("NOM_CMP")?.to_string();
        let absolute = args.text("MULT_APPUI") == Some("OUI");
        let (x, y) =
            tran_gene::physical_history(ctx.store, &result, (field, &node, &cmp), absolute, &kw)?;
        (x, y, "INST".to_string(), cmp)
    } else {
        let node = node_of("NOEUD_CHOC", "GROUP_NO_CHOC")?;
        let para_y = args.req_text("PARA_Y")?.to_string();
        let (x, y) = tran_gene::shock_history(
            ctx.store,
            &result,
            args.text("INTITULE"),
            node.as_deref(),
            &para_y,
            &kw,
        )?;
        (x, y, args.req_text("PARA_X")?.to_string(), para_y)
    };
    let (x, y) = at_instants(args, x, y)?;
    let f = function_with_options(args, &name, &para, &resu, x, y)?;
    ctx.create(&name, "fonction_sdaster")?;
    save_function(ctx.store, &name, &f)
}

/// The time history of one component of a `dyna_trans`: its instants are increasing (one
/// period sampled from 0), so no reordering is needed.
fn from_result(ctx: &mut OpContext<'_>, args: &Args) -> Result<()> {
    let name = ctx.result_name()?.to_string();
    let result = args.req_concept("RESULTAT")?.name.clone();
    let c = dyna_trans::component(
        ctx.store,
        args,
        &result,
        &|k| args.key_path(k),
        "RECU_FONCTION extracts the history of one node",
    )?;
    let (x, y) = at_instants(args, c.samples.inst, c.samples.values)?;
    let f = function_with_options(args, &name, "INST", &c.cmp, x, y)?;
    ctx.create(&name, "fonction_sdaster")?;
    save_function(ctx.store, &name, &f)?;
    if ctx.info >= 2 {
        ctx.say(&format!(
            "RECU_FONCTION {name}: {} of {} at node {}, component {}: {} instants",
            c.field,
            result,
            c.node,
            c.cmp,
            f.x.len()
        ))?;
    }
    Ok(())
}

fn from_table(ctx: &mut OpContext<'_>, args: &Args) -> Result<()> {
    let name = ctx.result_name()?.to_string();
    let (c, t) = load_table_arg(ctx, args, "TABLE")?;
    let t = apply_all(&t, &filters_for(ctx, &t, args, "FILTRE")?)?;
    let px = args.req_text("PARA_X")?;
    let py = args.req_text("PARA_Y")?;
    let (mut x, mut y) = points(&t, &c.name, px, py)?;
    let order = order_points(&mut x, &mut y);
    if order.reorder != Reorder::None {
        let how = match order.reorder {
            Reorder::Reversed => "decrease along the rows: the points were reversed",
            _ => "do not increase along the rows: the points were sorted by increasing abscissa",
        };
        ctx.alarm(
            "FONCT0_62",
            &format!(
                "function {name}: the abscissas ({px} of table {}) {how}",
                c.name
            ),
        )?;
    }
    if order.dropped > 0 {
        let values = if order.max_dropped_dy == 0.0 {
            "exact copies of kept points".to_string()
        } else {
            format!(
                "their {py} differs from the kept one by up to {:e}",
                order.max_dropped_dy
            )
        };
        ctx.say(&format!(
            "RECU_FONCTION: function {name}: {} row(s) of table {} repeat an abscissa ({px}) already taken and were dropped, keeping the first row of each ({values})",
            order.dropped, c.name
        ))?;
    }
    // RECU_FONCTION has no NOM_PARA / NOM_RESU keywords: the function is named after the
    // table's columns.
    let f = function_with_options(args, &name, px, py, x, y)?;
    ctx.create(&name, "fonction_sdaster")?;
    save_function(ctx.store, &name, &f)
}
