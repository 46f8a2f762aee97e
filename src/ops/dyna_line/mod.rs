//! DYNA_LINE (TYPE_CALCUL='TRAN'): Code_Aster's macro of a linear transient with shocks,
//! from the model. It chains the operators a user would call, each validated against its
//! own catalog: ASSEMBLAGE here, the loads (`loads`); with BASE_CALCUL='GENE' the basis
//! (`basis`), PROJ_BASE and DYNA_VIBRA (`transient`) and REST_GENE_PHYS; with 'PHYS'
//! DYNA_VIBRA on the assembled matrices. What is refused is in `checks`. The
//! concepts of the steps are named `<result>.DL.*`; RESU_GENE and BASE_RESU name two of
//! them with CO('...'). No numerics here.

mod basis;
mod chain;
mod checks;
mod loads;
mod transient;

use super::OpContext;
use crate::args::Args;
use crate::error::{Error, Result};
use crate::value::Value;
use chain::{occurrence, Call};
use transient::Chained;

/// The assembled matrices and their numbering.
pub struct Assembled {
    pub nume: String,
    pub rigi: String,
    pub mass: String,
    pub amor: Option<String>,
}

pub fn run(ctx: &mut OpContext<'_>, args: &Args) -> Result<()> {
    let name = ctx.result_name()?.to_string();
    checks::refuse_unsupported(args)?;
    let gene = args.text("BASE_CALCUL") == Some("GENE");
    let outputs = co_outputs(args, &name)?;
    let prefix = format!("{name}.DL");
    let mats = assemble(ctx, args, &prefix)?;
    let loads = loads::loads(ctx, args, &prefix, &mats)?;
    let pas = transient::step(args)?;
    if gene {
        let base_name = outputs.base.clone().unwrap_or(format!("{prefix}.BASE"));
        let enriching: Vec<String> = loads
            .iter()
            .filter(|l| l.enriches)
            .map(|l| l.field.clone())
            .collect();
        let b = basis::build(ctx, args, &prefix, &mats, &enriching, &base_name)?;
        let projected = transient::project(ctx, args, &prefix, &b, &mats, &loads)?;
        let tran = outputs.gene.clone().unwrap_or(format!("{prefix}.TRAN"));
        transient::vibra(ctx, args, &projected, pas, "GENE", &tran)?;
        Call::new("REST_GENE_PHYS")
            .concept(ctx, "RESU_GENE", &tran)?
            .text("TOUT_CHAM", "OUI")
            .run(ctx, Some(&name), "DYNA_LINE/RESU_GENE", &[])?;
        let modes = crate::store::modes::load_modes(ctx.store, &b.name)?
            .modes
            .len();
        ctx.say(&format!(
            "DYNA_LINE {name}: {modes} vector(s) in the basis {} (STOCKAGE='{}'), transient {tran}, physical fields restored",
            b.name, b.storage
        ))
    } else {
        let physical = Chained {
            mass: mats.mass.clone(),
            rigi: mats.rigi.clone(),
            amor: mats.amor.clone(),
            loads: loads
                .iter()
                .map(|l| (l.field.clone(), l.fonc.clone(), l.coef))
                .collect(),
            depl: args
                .fact("ETAT_INIT")
                .and_then(|e| e.concept("DEPL"))
                .map(|c| c.name.clone()),
            vite: args
                .fact("ETAT_INIT")
                .and_then(|e| e.concept("VITE"))
                .map(|c| c.name.clone()),
        };
        transient::vibra(ctx, args, &physical, pas, "PHYS", &name)?;
        ctx.say(&format!(
            "DYNA_LINE {name}: on the {} physical matrices",
            mats.nume
        ))
    }
}

/// The CO names of RESU_GENE and BASE_RESU, checked distinct from each other and the
/// result.
struct Outputs {
    gene: Option<String>,
    base: Option<String>,
}

fn co_outputs(args: &Args, result: &str) -> Result<Outputs> {
    let gene = args.co("RESU_GENE").map(str::to_string);
    let base = args.co("BASE_RESU").map(str::to_string);
    for (key, co) in [("RESU_GENE", &gene), ("BASE_RESU", &base)] {
        if co.as_deref() == Some(result) {
            return Err(Error::validation(format!(
                "CO('{result}') is the name of DYNA_LINE's result itself"
            ))
            .keyword(format!("DYNA_LINE/{key}"))
            .hint("give each output its own name"));
        }
    }
    if gene.is_some() && gene == base {
        return Err(
            Error::validation("RESU_GENE and BASE_RESU are given the same name")
                .keyword("DYNA_LINE/BASE_RESU")
                .hint("give each output its own name"),
        );
    }
    for (key, given) in [
        ("RESU_GENE", args.has("RESU_GENE")),
        ("BASE_RESU", args.has("BASE_RESU")),
    ] {
        if given && args.co(key).is_none() {
            return Err(
                Error::validation("expected CO('NAME'), the name of a new concept")
                    .keyword(format!("DYNA_LINE/{key}")),
            );
        }
    }
    Ok(Outputs { gene, base })
}

/// ASSEMBLAGE of the stiffness, the mass and (AMORTISSEMENT RAYLEIGH) the damping.
fn assemble(ctx: &mut OpContext<'_>, args: &Args, prefix: &str) -> Result<Assembled> {
    let out = Assembled {
        nume: format!("{prefix}.NUME"),
        rigi: format!("{prefix}.RIGI"),
        mass: format!("{prefix}.MASS"),
        amor: (args.fact("AMORTISSEMENT").and_then(|a| a.text("TYPE_AMOR")) == Some("RAYLEIGH"))
            .then(|| format!("{prefix}.AMOR")),
    };
    let charges = args.concepts("CHARGE").unwrap_or_default();
    let (cine, meca): (Vec<_>, Vec<_>) =
        charges.into_iter().partition(|c| c.ty == "char_cine_meca");
    let mut matrices = vec![("RIGI_MECA", &out.rigi), ("MASS_MECA", &out.mass)];
    if let Some(a) = &out.amor {
        matrices.push(("AMOR_MECA", a));
    }
    let mut call = Call::new("ASSEMBLAGE")
        .set(
            "MODELE",
            args.value("MODELE").cloned().unwrap_or(Value::None),
        )
        .co("NUME_DDL", &out.nume)
        .fact(
            "MATR_ASSE",
            matrices
                .iter()
                .map(|(option, name)| {
                    occurrence(
                        "ASSEMBLAGE",
                        "MATR_ASSE",
                        vec![
                            ("MATRICE", Value::Co((*name).clone())),
                            ("OPTION", Value::Str((*option).to_string())),
                        ],
                    )
                })
                .collect(),
        );
    for key in ["CHAM_MATER", "CARA_ELEM"] {
        if let Some(v) = args.value(key).filter(|v| **v != Value::None) {
            call = call.set(key, v.clone());
        }
    }
    if !meca.is_empty() {
        call = call.set(
            "CHARGE",
            Value::Seq(meca.into_iter().map(Value::Concept).collect()),
        );
    }
    if !cine.is_empty() {
        call = call.set(
            "CHAR_CINE",
            Value::Seq(cine.into_iter().map(Value::Concept).collect()),
        );
    }
    call.run(ctx, None, "DYNA_LINE/MODELE", &[])?;
    Ok(out)
}
