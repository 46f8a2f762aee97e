//! Reading the table keywords shared by several operators (FILTRE, TRI, TABLE) from
//! `Args`, and loading/saving the table concepts they name.

use crate::args::Args;
use crate::error::{Error, Result};
use crate::ops::OpContext;
use crate::store::mesh as mesh_store;
use crate::store::table::{load_table, save_table};
use crate::table::filter::{CritComp, Critere, Filter};
use crate::table::sort::{sort, Ordre};
use crate::table::{Cell, Table};
use crate::value::{ConceptRef, Value};

/// Concept types stored as a table (`store::table`): the tables, and the time history of
/// a `dyna_trans` (REST_MODE_NONL), whose rows are one table as well. Which of them an
/// operator takes is its catalog's business (IMPR_TABLE, TEST_TABLE and RECU_FONCTION
/// take a `dyna_trans`; CALC_TABLE and EXTR_TABLE do not), checked by the validation.
pub const TABLE_TYPES: &[&str] = &[
    "table_sdaster",
    "table_container",
    "dyna_trans",
    "tran_gene",
];

fn items(v: Option<&Value>) -> Vec<&Value> {
    match v {
        None | Some(Value::None) => Vec::new(),
        Some(Value::Seq(items)) => items.iter().collect(),
        Some(v) => vec![v],
    }
}

/// One FILTRE (or CALC_TABLE ACTION FILTRE) occurrence: NOM_PARA, CRIT_COMP (default EQ),
/// VALE | VALE_I | VALE_K, CRITERE (default RELATIF), PRECISION (default 1e-3).
pub fn filter_from(a: &Args) -> Result<Filter> {
    let nom_para = a.req_text("NOM_PARA")?;
    let crit_s = a.req_text("CRIT_COMP")?;
    let crit = CritComp::parse(crit_s).ok_or_else(|| {
        Error::validation(format!("unknown CRIT_COMP '{crit_s}'"))
            .keyword(a.key_path("CRIT_COMP"))
            .hint(format!("use one of {}", CritComp::NAMES.join(", ")))
    })?;
    let mut values = Vec::new();
    for key in ["VALE", "VALE_I", "VALE_K"] {
        for v in items(a.value(key)) {
            values.push(match v {
                Value::Int(i) => Cell::I(*i),
                Value::Real(r) => Cell::R(*r),
                Value::Str(s) => Cell::K(s.clone()),
                other => {
                    return Err(Error::validation(format!(
                        "expected a value to compare with, got {}",
                        other.kind_name()
                    ))
                    .keyword(a.key_path(key)))
                }
            });
        }
    }
    let s = a.req_text("CRITERE")?;
    let critere = Critere::parse(s).ok_or_else(|| {
        Error::validation(format!("unknown CRITERE '{s}'"))
            .keyword(a.key_path("CRITERE"))
            .hint("use 'RELATIF' or 'ABSOLU'")
    })?;
    let precision = a.req_real("PRECISION")?;
    Ok(Filter {
        nom_para: nom_para.to_string(),
        crit,
        values,
        critere,
        precision,
    })
}

/// All occurrences of the factor keyword `key` (usually FILTRE).
pub fn filters(args: &Args, key: &str) -> Result<Vec<Filter>> {
    args.facts_or_empty(key).iter().map(filter_from).collect()
}

/// The FILTRE occurrences `key` for table `t`, node numbers read as names
/// ([`node_numbers_as_names`]).
pub fn filters_for(ctx: &OpContext<'_>, t: &Table, args: &Args, key: &str) -> Result<Vec<Filter>> {
    let mut fl = filters(args, key)?;
    for f in &mut fl {
        node_numbers_as_names(ctx, t, f)?;
    }
    Ok(fl)
}

/// Code_Aster 17 keeps no node names: its tables name a node by its number, and its files
/// filter so (FILTRE=_F(NOM_PARA='NOEUD', VALE_K='1')). aster-nl's tables keep the names.
/// A filter on a node column (NOEUD, NOEUD_CHOC, ...) whose texts are all numbers and
/// match no cell of the table reads them as node numbers (1-based, in the mesh file's
/// order), when the study's meshes agree on the name of each; otherwise it is left as given.
pub fn node_numbers_as_names(ctx: &OpContext<'_>, t: &Table, f: &mut Filter) -> Result<()> {
    let numeric = |c: &Cell| matches!(c, Cell::K(s) if !s.is_empty() && s.bytes().all(|b| b.is_ascii_digit()));
    if !f.nom_para.starts_with("NOEUD") || f.values.is_empty() || !f.values.iter().all(numeric) {
        return Ok(());
    }
    let Ok(j) = t.req_col(&f.nom_para) else {
        return Ok(());
    };
    if t.rows
        .iter()
        .any(|r| r.get(j).is_some_and(|c| f.values.contains(c)))
    {
        return Ok(());
    }
    let mut names = Vec::with_capacity(f.values.len());
    for v in &f.values {
        let Cell::K(s) = v else { return Ok(()) };
        let Some(name) = s
            .parse::<usize>()
            .ok()
            .map(|k| mesh_store::node_name_by_number(ctx.store, k))
            .transpose()?
            .flatten()
        else {
            return Ok(());
        };
        names.push(Cell::K(name));
    }
    f.values = names;
    Ok(())
}

/// ORDRE (default CROISSANT).
pub fn ordre(a: &Args) -> Result<Ordre> {
    let s = a.req_text("ORDRE")?;
    Ordre::parse(s).ok_or_else(|| {
        Error::validation(format!("unknown ORDRE '{s}'"))
            .keyword(a.key_path("ORDRE"))
            .hint("use 'CROISSANT' or 'DECROISSANT'")
    })
}

/// Apply one TRI-like occurrence (NOM_PARA, ORDRE) to `t`.
pub fn apply_tri(t: &mut Table, a: &Args) -> Result<()> {
    let keys = a.texts("NOM_PARA").ok_or_else(|| {
        Error::validation("expected parameter names").keyword(a.key_path("NOM_PARA"))
    })?;
    sort(t, &keys, ordre(a)?).map_err(|e| e.keyword(a.key_path("NOM_PARA")))
}

/// The table concept given to `key` (usually TABLE), loaded.
pub fn load_table_arg(ctx: &OpContext<'_>, args: &Args, key: &str) -> Result<(ConceptRef, Table)> {
    let c = args.req_concept(key)?;
    if !TABLE_TYPES.contains(&c.ty.as_str()) {
        return Err(
            Error::validation(format!("{} is a {}, not a table", c.name, c.ty))
                .keyword(args.key_path(key)),
        );
    }
    let t = load_table(ctx.store, &c.name).map_err(|e| e.keyword(args.key_path(key)))?;
    Ok((c.clone(), t))
}

/// Register the concept `name` of type `ty` and save `t` under it.
pub fn create_table(ctx: &mut OpContext<'_>, name: &str, ty: &str, t: &Table) -> Result<()> {
    ctx.create(name, ty)?;
    save_table(ctx.store, name, t)
}

/// A title given as TITRE (a text or several lines).
pub fn titre(args: &Args) -> Option<String> {
    args.texts("TITRE").map(|l| l.join("\n"))
}
