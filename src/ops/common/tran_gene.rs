//! Time histories read from a DYNA_VIBRA result (RECU_FONCTION's RESU_GENE): a physical
//! component at a node (u = Φq over the archived instants), or a parameter of a shock found
//! by its node or INTITULE.

use crate::error::{Error, Result};
use crate::model::Cmp;
use crate::ops::common::gene::numbering_and_basis;
use crate::ops::common::supports::SupportShare;
use crate::store::tran_gene::{self, load_coordinates, Payload};
use crate::store::{table as table_store, Store};
use crate::table::{Cell, Table};
use crate::transient::ShockSample;

/// (INST, value) of NOM_CHAM `field` (DEPL, VITE, ACCE), component `cmp` of `node`; with
/// `absolute`, the supports' share of a multi-support run added (MULT_APPUI='OUI').
pub fn physical_history(
    store: &Store,
    result: &str,
    (field, node, cmp): (&str, &str, &str),
    absolute: bool,
    kw: &dyn Fn(&str) -> String,
) -> Result<(Vec<f64>, Vec<f64>)> {
    let payload = tran_gene::load_payload(store, result)?;
    if payload.base != "GENE" {
        return Err(Error::input(format!(
            "{result} is a result on the physical DOFs: give it as RESULTAT="
        ))
        .keyword(kw("RESU_GENE")));
    }
    let (_, modes) = numbering_and_basis(store, &payload.numbering, None, "RECU_FONCTION")?;
    let c = Cmp::parse(cmp).ok_or_else(|| {
        Error::validation(format!("NOM_CMP='{cmp}' is not a component")).keyword(kw("NOM_CMP"))
    })?;
    let dof = modes.numbering.index_of(node, c).ok_or_else(|| {
        Error::input(format!(
            "node {node} has no DOF {cmp} in the basis of {result}"
        ))
        .keyword(kw("NOM_CMP"))
    })?;
    let n = modes.modes.len();
    let coords = load_coordinates(store, result, n)?;
    let series = match field {
        "DEPL" => &coords.q,
        "VITE" => &coords.v,
        "ACCE" => &coords.a,
        other => {
            return Err(Error::validation(format!(
                "NOM_CHAM='{other}': a DYNA_VIBRA result gives DEPL, VITE or ACCE"
            ))
            .keyword(kw("NOM_CHAM")))
        }
    };
    let row: Vec<f64> = modes.modes.iter().map(|m| m.shape[dof]).collect();
    let mut values: Vec<f64> = (0..coords.t.len())
        .map(|i| {
            row.iter()
                .zip(&series[i * n..(i + 1) * n])
                .map(|(p, q)| p * q)
                .sum()
        })
        .collect();
    if absolute {
        let key = kw("MULT_APPUI");
        let share = SupportShare::load(store, result, &payload.supports, &key)?;
        for (v, &t) in values.iter_mut().zip(&coords.t) {
            let g = share.values(field, t).map_err(|e| e.keyword(key.clone()))?;
            *v += share.combine(&g, dof);
        }
    }
    Ok((coords.t, values))
}

/// (INST, value) of parameter `para` (FN, FT1, FT2, VN, VT1, VT2, DXLOC, DYLOC, DZLOC, or
/// an internal variable VINTi in Code_Aster's order) of the shock of `result` named by
/// `intitule`, or else acting on node `node`.
pub fn shock_history(
    store: &Store,
    result: &str,
    intitule: Option<&str>,
    node: Option<&str>,
    para: &str,
    kw: &dyn Fn(&str) -> String,
) -> Result<(Vec<f64>, Vec<f64>)> {
    let payload = tran_gene::load_payload(store, result)?;
    let which = find_shock(&payload, result, intitule, node, kw)?;
    let vint = para
        .strip_prefix("VINT")
        .and_then(|i| i.parse::<usize>().ok());
    if !ShockSample::NAMES.contains(&para) && vint.is_none() {
        return Err(Error::validation(format!(
            "PARA_Y='{para}' is not a parameter of a shock; give one of {} or VINTi",
            ShockSample::NAMES.join(", ")
        ))
        .keyword(kw("PARA_Y")));
    }
    let t = shock_table(store, result, &payload)?;
    if let Some(i) = vint {
        let shock = payload
            .shocks
            .iter()
            .find(|s| s.intitule == which)
            .ok_or_else(|| Error::store(format!("{result} has no shock '{which}'")))?;
        let (x, mut y) = super::shock_vint::history(&t, result, shock, Some(i))
            .map_err(|e| e.keyword(kw("PARA_Y")))?;
        return Ok((x, y.pop().unwrap_or_default()));
    }
    let (x, mut y) = shock_samples(&t, &which, &[para])?;
    Ok((x, y.pop().unwrap_or_default()))
}

/// The shocks' table `<result>_CHOC` of a result whose payload is `payload`.
pub fn shock_table(store: &Store, result: &str, payload: &Payload) -> Result<Table> {
    let table = payload
        .shock_table
        .as_deref()
        .ok_or_else(|| Error::store(format!("{result} has no shocks' table")))?;
    table_store::load_table(store, table)
}

/// The archived samples of shock `intitule` in its shocks' table `t`: the instants and
/// the columns `paras`, in row order. A missing or non-numeric cell reads NaN.
pub fn shock_samples(
    t: &Table,
    intitule: &str,
    paras: &[&str],
) -> Result<(Vec<f64>, Vec<Vec<f64>>)> {
    let (ji, jt) = (t.req_col("INTITULE")?, t.req_col("INST")?);
    let js = paras
        .iter()
        .map(|p| t.req_col(p))
        .collect::<Result<Vec<usize>>>()?;
    let num = |row: &[Cell], j: usize| row.get(j).and_then(Cell::as_f64).unwrap_or(f64::NAN);
    let mut x = Vec::new();
    let mut cols = vec![Vec::new(); paras.len()];
    for row in &t.rows {
        if row.get(ji).and_then(Cell::as_text) == Some(intitule) {
            x.push(num(row, jt));
            for (c, &j) in cols.iter_mut().zip(&js) {
                c.push(num(row, j));
            }
        }
    }
    Ok((x, cols))
}

fn find_shock(
    payload: &Payload,
    result: &str,
    intitule: Option<&str>,
    node: Option<&str>,
    kw: &dyn Fn(&str) -> String,
) -> Result<String> {
    let names = || {
        payload
            .shocks
            .iter()
            .map(|s| s.intitule.as_str())
            .collect::<Vec<_>>()
            .join(", ")
    };
    if payload.shocks.is_empty() {
        return Err(Error::input(format!("{result} has no shock")).keyword(kw("RESU_GENE")));
    }
    if let Some(i) = intitule {
        return payload
            .shocks
            .iter()
            .find(|s| s.intitule == i)
            .map(|s| s.intitule.clone())
            .ok_or_else(|| {
                Error::input(format!(
                    "{result} has no shock named '{i}'; its shocks are {}",
                    names()
                ))
                .keyword(kw("INTITULE"))
            });
    }
    let node = node.ok_or_else(|| {
        Error::validation("give INTITULE, NOEUD_CHOC or GROUP_NO_CHOC").keyword(kw("NOEUD_CHOC"))
    })?;
    let found: Vec<&str> = payload
        .shocks
        .iter()
        .filter(|s| s.node1 == node || s.node2.as_deref() == Some(node))
        .map(|s| s.intitule.as_str())
        .collect();
    match found.as_slice() {
        [one] => Ok(one.to_string()),
        [] => Err(Error::input(format!(
            "no shock of {result} acts on node {node}; its shocks are {}",
            names()
        ))
        .keyword(kw("NOEUD_CHOC"))),
        many => Err(Error::input(format!(
            "{} shocks of {result} act on node {node} ({}): name one with INTITULE",
            many.len(),
            many.join(", ")
        ))
        .keyword(kw("INTITULE"))),
    }
}
