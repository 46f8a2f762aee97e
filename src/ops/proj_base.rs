//! PROJ_BASE macro: a generalized numbering of the basis, then PROJ_MATR_BASE and
//! PROJ_VECT_BASE for each occurrence, every result a new concept named by CO('...').

use super::OpContext;
use crate::args::Args;
use crate::error::{Error, Result};
use crate::store::gene::{self, GeneNumbering};
use crate::store::modes as mode_store;

pub fn run(ctx: &mut OpContext<'_>, args: &Args) -> Result<()> {
    let base = args.req_concept("BASE")?.name.clone();
    for (key, what) in [
        ("RESU_GENE", "the projection of a transient result"),
        (
            "MATR_ASSE_GENE/MATR_ASSE_GENE",
            "a generalized matrix projected again",
        ),
        (
            "VECT_ASSE_GENE/VECT_ASSE_GENE",
            "a generalized vector projected again",
        ),
    ] {
        let given = match key.split_once('/') {
            Some((fact, simp)) => args.facts_or_empty(fact).iter().any(|o| o.has(simp)),
            None => args.has(key),
        };
        if given {
            return Err(Error::validation(format!("{what} is not supported"))
                .keyword(format!("PROJ_BASE/{key}"))
                .hint("project assembled matrices (MATR_ASSE) and nodal fields (VECT_ASSE)"));
        }
    }
    let outputs = outputs(args)?;
    let modes = mode_store::load_modes(ctx.store, &base)?;
    if let Some(n) = args.int("NB_VECT") {
        if usize::try_from(n).map_or(true, |n| n < modes.modes.len()) {
            return Err(Error::validation(format!(
                "NB_VECT={n} is below the {} vectors of {base}: aster-nl projects on the whole basis",
                modes.modes.len()
            ))
            .keyword("PROJ_BASE/NB_VECT")
            .hint("compute only the modes to project on (CALC_MODES), or drop NB_VECT"));
        }
    }
    let storage = args.req_text("STOCKAGE")?.to_string();
    let num_name = numbering(ctx, args, &base, modes.modes.len(), &storage)?;
    for occ in args.facts_or_empty("MATR_ASSE_GENE") {
        let co = co(occ, "MATRICE")?;
        let a = occ.req_concept("MATR_ASSE")?.name.clone();
        super::proj_matr_base::project(
            ctx,
            co,
            &num_name,
            &base,
            &a,
            "PROJ_BASE",
            &occ.key_path("MATR_ASSE"),
        )?;
    }
    for occ in args.facts_or_empty("VECT_ASSE_GENE") {
        let co = co(occ, "VECTEUR")?;
        let f = occ.req_concept("VECT_ASSE")?.name.clone();
        let kind = occ.req_text("TYPE_VECT")?.to_string();
        super::proj_vect_base::project(
            ctx,
            co,
            &num_name,
            &base,
            (&f, &occ.key_path("VECT_ASSE")),
            &kind,
            "PROJ_BASE",
        )?;
    }
    ctx.say(&format!(
        "PROJ_BASE: {} on the {} vectors of {base} (numbering {num_name}, STOCKAGE='{storage}')",
        outputs.join(", "),
        modes.modes.len()
    ))
}

/// The CO names of the results, each given once.
fn outputs(args: &Args) -> Result<Vec<String>> {
    let mut names: Vec<String> = Vec::new();
    if let Some(n) = args.co("NUME_DDL_GENE") {
        names.push(n.to_string());
    }
    for (fact, simp) in [("MATR_ASSE_GENE", "MATRICE"), ("VECT_ASSE_GENE", "VECTEUR")] {
        for occ in args.facts_or_empty(fact) {
            let c = co(occ, simp)?;
            if names.iter().any(|n| n == c) {
                return Err(Error::validation(format!(
                    "CO('{c}') is given twice: each result of PROJ_BASE needs its own name"
                ))
                .keyword(occ.key_path(simp)));
            }
            names.push(c.to_string());
        }
    }
    Ok(names)
}

fn co<'a>(occ: &'a Args, key: &str) -> Result<&'a str> {
    occ.co(key)
        .ok_or_else(|| Error::validation("expected CO('NAME')").keyword(occ.key_path(key)))
}

/// The generalized numbering: created under CO('...'), an existing one of the basis, or
/// (absent) PROJ_BASE's own for this basis and storage, created the first time.
fn numbering(
    ctx: &mut OpContext<'_>,
    args: &Args,
    base: &str,
    size: usize,
    storage: &str,
) -> Result<String> {
    let fresh = GeneNumbering {
        basis: base.to_string(),
        size,
        storage: storage.to_string(),
    };
    if let Some(c) = args.concept("NUME_DDL_GENE") {
        let num = gene::load_numbering(ctx.store, &c.name)?;
        if num.basis != base {
            return Err(Error::input(format!(
                "{} numbers the basis {}, not {base}",
                c.name, num.basis
            ))
            .keyword("PROJ_BASE/NUME_DDL_GENE"));
        }
        return Ok(c.name.clone());
    }
    let name = match args.co("NUME_DDL_GENE") {
        Some(co) => co.to_string(),
        None => {
            let own = format!("{base}.NUME_GENE.{storage}");
            if ctx.store.concept_type(&own)?.as_deref() == Some("nume_ddl_gene")
                && gene::load_numbering(ctx.store, &own)? == fresh
            {
                return Ok(own);
            }
            own
        }
    };
    ctx.create(&name, "nume_ddl_gene")?;
    ctx.store.record_dependency(&name, base)?;
    gene::save_numbering(ctx.store, &name, &fresh)?;
    Ok(name)
}
