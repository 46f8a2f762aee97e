//! DYNA_LINE (TYPE_CALCUL='TRAN'): Code_Aster's macro of a linear transient with shocks,
//! from the model. It chains the operators a user would call, each validated against its
//! own catalog: ASSEMBLAGE; with BASE_CALCUL='GENE' the basis (`basis`), PROJ_BASE,
//! DYNA_VIBRA and REST_GENE_PHYS; with 'PHYS' DYNA_VIBRA on the assembled matrices. The
//! concepts of the steps are named `<result>.DL.*`; RESU_GENE and BASE_RESU name two of
//! them with CO('...'). No numerics here.

mod basis;
mod chain;

use super::OpContext;
use crate::args::Args;
use crate::error::{Error, Result};
use crate::store::gene;
use crate::value::Value;
use chain::{concept, occurrence, passed_on, Call};

/// The assembled matrices and their numbering.
pub struct Assembled {
    pub nume: String,
    pub rigi: String,
    pub mass: String,
    pub amor: Option<String>,
}

/// One load of the transient: an assembled nodal field times a function or a constant.
struct Load {
    field: String,
    fonc: Option<Value>,
    coef: Option<f64>,
    /// An EXCIT with CHARGE: ENRI_STAT adds its static response to the basis.
    enriches: bool,
}

pub fn run(ctx: &mut OpContext<'_>, args: &Args) -> Result<()> {
    let name = ctx.result_name()?.to_string();
    refuse_unsupported(args)?;
    let gene = args.text("BASE_CALCUL") == Some("GENE");
    let outputs = co_outputs(args, &name)?;
    let prefix = format!("{name}.DL");
    let mats = assemble(ctx, args, &prefix)?;
    let loads = loads(ctx, args, &prefix, &mats)?;
    let pas = step(args)?;
    if gene {
        let base_name = outputs.base.clone().unwrap_or(format!("{prefix}.BASE"));
        let enriching: Vec<String> = loads
            .iter()
            .filter(|l| l.enriches)
            .map(|l| l.field.clone())
            .collect();
        let b = basis::build(ctx, args, &prefix, &mats, &enriching, &base_name)?;
        let projected = project(ctx, args, &prefix, &b, &mats, &loads)?;
        let tran = outputs.gene.clone().unwrap_or(format!("{prefix}.TRAN"));
        vibra(ctx, args, &projected, pas, "GENE", &tran)?;
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
        vibra(ctx, args, &physical, pas, "PHYS", &name)?;
        ctx.say(&format!(
            "DYNA_LINE {name}: on the {} physical matrices",
            mats.nume
        ))
    }
}

/// What is refused, by name, before anything is computed.
fn refuse_unsupported(args: &Args) -> Result<()> {
    if args.text("TYPE_CALCUL") == Some("HARM") {
        return Err(Error::validation("harmonic responses are not computed")
            .keyword("DYNA_LINE/TYPE_CALCUL")
            .hint("TYPE_CALCUL='TRAN' (a transient) is what DYNA_LINE runs here"));
    }
    if args.has("FREQ_COUP_STAT") {
        return Err(Error::validation(
            "a cutoff of the reduced modes is not applied: ORTHO='OUI' keeps every mode of the reduced problem",
        )
        .keyword("DYNA_LINE/FREQ_COUP_STAT")
        .hint("drop FREQ_COUP_STAT"));
    }
    let gene = args.text("BASE_CALCUL") == Some("GENE");
    if let Some(a) = args.fact("AMORTISSEMENT") {
        if a.text("TYPE_AMOR") == Some("MODAL") {
            if !gene {
                return Err(Error::validation("modal damping needs a modal basis")
                    .keyword("DYNA_LINE/AMORTISSEMENT/TYPE_AMOR")
                    .hint("BASE_CALCUL='GENE', or TYPE_AMOR='RAYLEIGH'"));
            }
            if !a.has("AMOR_REDUIT") {
                return Err(
                    Error::validation("TYPE_AMOR='MODAL' needs the damping ratios")
                        .keyword("DYNA_LINE/AMORTISSEMENT/AMOR_REDUIT"),
                );
            }
        }
    }
    for occ in args.facts_or_empty("EXCIT") {
        let key = |k: &str| occ.key_path(k);
        if occ.has("FREQ") {
            return Err(
                Error::validation("FREQ belongs to harmonic responses").keyword(key("FREQ"))
            );
        }
        match occ.text("TYPE_APPUI") {
            Some("MULTI") => {
                return Err(Error::validation(
                    "multi-support excitation is not run by DYNA_LINE",
                )
                .keyword(key("TYPE_APPUI"))
                .hint("run the chain yourself: MODE_STATIQUE (MODE_STAT), CALC_CHAR_SEISME, PROJ_BASE, DYNA_VIBRA with EXCIT MULT_APPUI='OUI' (docs/dyna_vibra.md, \"Moving supports\")"))
            }
            Some(_) => {
                for k in ["GROUP_NO", "NOEUD", "ACCE", "VITE", "DEPL", "CHARGE"] {
                    if occ.has(k) {
                        return Err(Error::validation(
                            "TYPE_APPUI='MONO' is run as every support accelerated together, by FONC_MULT along DIRECTION",
                        )
                        .keyword(key(k))
                        .hint("give the acceleration as FONC_MULT and drop this keyword"));
                    }
                }
                let d = occ.reals("DIRECTION").unwrap_or_default();
                if d.len() != 3 {
                    return Err(Error::validation(format!(
                        "expected the three translations of the direction, got {} value(s)",
                        d.len()
                    ))
                    .keyword(key("DIRECTION")));
                }
                if !occ.has("FONC_MULT") {
                    return Err(Error::validation("expected the support acceleration")
                        .keyword(key("FONC_MULT")));
                }
            }
            None => {
                for (k, what) in [("CHARGE", "the load"), ("FONC_MULT", "its function of time")] {
                    if !occ.has(k) {
                        return Err(Error::validation(format!(
                            "without TYPE_APPUI, EXCIT is a load times a function: expected {what}"
                        ))
                        .keyword(key(k)));
                    }
                }
                for k in ["DIRECTION", "GROUP_NO", "NOEUD", "ACCE", "VITE", "DEPL"] {
                    if occ.has(k) {
                        return Err(Error::validation("this keyword goes with TYPE_APPUI")
                            .keyword(key(k)));
                    }
                }
            }
        }
    }
    Ok(())
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

/// The loads as assembled nodal fields: the nodal forces of CHARGE (constant, when there
/// are any, as Code_Aster applies them), then each EXCIT (CHARGE's forces or the support
/// acceleration's −M·Δ).
fn loads(
    ctx: &mut OpContext<'_>,
    args: &Args,
    prefix: &str,
    mats: &Assembled,
) -> Result<Vec<Load>> {
    let mut out = Vec::new();
    let meca: Vec<Value> = args
        .concepts("CHARGE")
        .unwrap_or_default()
        .into_iter()
        .filter(|c| c.ty != "char_cine_meca")
        .map(Value::Concept)
        .collect();
    if !meca.is_empty() {
        let field = format!("{prefix}.F0");
        nodal_forces(
            ctx,
            args,
            Value::Seq(meca),
            &field,
            mats,
            "DYNA_LINE/CHARGE",
        )?;
        if gene::load_field(ctx.store, &field)?
            .values
            .iter()
            .any(|v| v.2 != 0.0)
        {
            out.push(Load {
                field,
                fonc: None,
                coef: Some(1.0),
                enriches: false,
            });
        }
    }
    for (i, occ) in args.facts_or_empty("EXCIT").iter().enumerate() {
        let field = format!("{prefix}.F{}", i + 1);
        let charge = occ.value("CHARGE").filter(|v| **v != Value::None);
        let enriches = charge.is_some();
        match charge {
            Some(charge) => nodal_forces(
                ctx,
                args,
                charge.clone(),
                &field,
                mats,
                &occ.key_path("CHARGE"),
            )?,
            None => {
                let direction = occ.value("DIRECTION").cloned().unwrap_or(Value::None);
                Call::new("CALC_CHAR_SEISME")
                    .concept(ctx, "MATR_MASS", &mats.mass)?
                    .set("DIRECTION", direction)
                    .text("MONO_APPUI", "OUI")
                    .run(ctx, Some(&field), &occ.key_path("DIRECTION"), &[])?
            }
        }
        out.push(Load {
            field,
            fonc: occ
                .value("FONC_MULT")
                .cloned()
                .filter(|v| *v != Value::None),
            coef: None,
            enriches,
        });
    }
    Ok(out)
}

/// CALC_VECT_ELEM and ASSE_VECTEUR: the nodal forces of `charge` on the numbering.
fn nodal_forces(
    ctx: &mut OpContext<'_>,
    args: &Args,
    charge: Value,
    field: &str,
    mats: &Assembled,
    blame: &str,
) -> Result<()> {
    let elem = format!("{field}.ELEM");
    let mut call = Call::new("CALC_VECT_ELEM")
        .text("OPTION", "CHAR_MECA")
        .set("CHARGE", charge);
    for key in ["CHAM_MATER", "CARA_ELEM"] {
        if let Some(v) = args.value(key).filter(|v| **v != Value::None) {
            call = call.set(key, v.clone());
        }
    }
    call.run(ctx, Some(&elem), blame, &[])?;
    Call::new("ASSE_VECTEUR")
        .concept(ctx, "VECT_ELEM", &elem)?
        .concept(ctx, "NUME_DDL", &mats.nume)?
        .run(ctx, Some(field), blame, &[])
}

/// The time step: INCREMENT/PAS, else 1/(5 F_max) of BANDE_ANALYSE (Code_Aster's).
fn step(args: &Args) -> Result<f64> {
    let inc = args.fact("INCREMENT");
    if let Some(p) = inc.and_then(|i| i.real("PAS")) {
        return Ok(p);
    }
    match args.reals("BANDE_ANALYSE").and_then(|b| b.last().copied()) {
        Some(f) if f > 0.0 => Ok(1.0 / (5.0 * f)),
        _ => Err(Error::validation(
            "no time step: without PAS it is 1/(5 F_max), F_max of BANDE_ANALYSE",
        )
        .keyword("DYNA_LINE/INCREMENT/PAS")
        .hint("give INCREMENT/PAS, or BANDE_ANALYSE")),
    }
}

/// The concepts DYNA_VIBRA runs on.
struct Chained {
    mass: String,
    rigi: String,
    amor: Option<String>,
    /// (field, FONC_MULT, COEF_MULT)
    loads: Vec<(String, Option<Value>, Option<f64>)>,
    depl: Option<String>,
    vite: Option<String>,
}

/// PROJ_BASE of the matrices, the loads and the initial state on the basis.
fn project(
    ctx: &mut OpContext<'_>,
    args: &Args,
    prefix: &str,
    b: &basis::Basis,
    mats: &Assembled,
    loads: &[Load],
) -> Result<Chained> {
    let gen = |s: &str| format!("{prefix}.{s}");
    let mut out = Chained {
        mass: gen("MGEN"),
        rigi: gen("KGEN"),
        amor: mats.amor.as_ref().map(|_| gen("CGEN")),
        loads: Vec::new(),
        depl: None,
        vite: None,
    };
    let mut matrices = vec![
        (out.mass.clone(), mats.mass.clone()),
        (out.rigi.clone(), mats.rigi.clone()),
    ];
    if let (Some(g), Some(a)) = (&out.amor, &mats.amor) {
        matrices.push((g.clone(), a.clone()));
    }
    let mut mocc = Vec::new();
    for (g, a) in &matrices {
        mocc.push(occurrence(
            "PROJ_BASE",
            "MATR_ASSE_GENE",
            vec![
                ("MATRICE", Value::Co(g.clone())),
                ("MATR_ASSE", concept(ctx, a)?),
            ],
        ));
    }
    let mut vectors: Vec<(String, String, &str)> = Vec::new();
    for (i, l) in loads.iter().enumerate() {
        let g = gen(&format!("FG{i}"));
        out.loads.push((g.clone(), l.fonc.clone(), l.coef));
        vectors.push((g, l.field.clone(), "FORC"));
    }
    if let Some(e) = args.fact("ETAT_INIT") {
        for (key, kind) in [("DEPL", "DEPL"), ("VITE", "VITE")] {
            if let Some(c) = e.concept(key) {
                let g = gen(&format!("{key}0"));
                vectors.push((g.clone(), c.name.clone(), kind));
                match key {
                    "DEPL" => out.depl = Some(g),
                    _ => out.vite = Some(g),
                }
            }
        }
    }
    let mut vocc = Vec::new();
    for (g, f, kind) in &vectors {
        vocc.push(occurrence(
            "PROJ_BASE",
            "VECT_ASSE_GENE",
            vec![
                ("VECTEUR", Value::Co(g.clone())),
                ("VECT_ASSE", concept(ctx, f)?),
                ("TYPE_VECT", Value::Str((*kind).to_string())),
            ],
        ));
    }
    let mut call = Call::new("PROJ_BASE")
        .concept(ctx, "BASE", &b.name)?
        .text("STOCKAGE", b.storage)
        .co("NUME_DDL_GENE", &gen("NUME_GENE"))
        .fact("MATR_ASSE_GENE", mocc);
    if !vocc.is_empty() {
        call = call.fact("VECT_ASSE_GENE", vocc);
    }
    call.run(ctx, None, "DYNA_LINE/BASE_CALCUL", &[])?;
    Ok(out)
}

/// DYNA_VIBRA on the chained concepts, its result named `result`.
fn vibra(
    ctx: &mut OpContext<'_>,
    args: &Args,
    c: &Chained,
    pas: f64,
    base: &str,
    result: &str,
) -> Result<()> {
    let vect_key = if base == "GENE" {
        "VECT_ASSE_GENE"
    } else {
        "VECT_ASSE"
    };
    let mut call = Call::new("DYNA_VIBRA")
        .text("TYPE_CALCUL", "TRAN")
        .text("BASE_CALCUL", base)
        .concept(ctx, "MATR_MASS", &c.mass)?
        .concept(ctx, "MATR_RIGI", &c.rigi)?;
    if let Some(a) = &c.amor {
        call = call.concept(ctx, "MATR_AMOR", a)?;
    }
    if let Some(level) = args.int("INFO") {
        // DYNA_VIBRA's: 2 lists the contact changes located.
        call = call.set("INFO", Value::Int(level));
    }
    if let Some(ratios) = args
        .fact("AMORTISSEMENT")
        .filter(|a| a.text("TYPE_AMOR") == Some("MODAL"))
        .and_then(|a| a.value("AMOR_REDUIT").cloned())
    {
        call = call.fact(
            "AMOR_MODAL",
            vec![occurrence(
                "DYNA_VIBRA",
                "AMOR_MODAL",
                vec![("AMOR_REDUIT", ratios)],
            )],
        );
    }
    let inc = args.fact("INCREMENT");
    let mut increment = vec![
        ("PAS", Value::Real(pas)),
        ("VERI_PAS", Value::Str("NON".into())),
    ];
    for key in ["INST_INIT", "INST_FIN"] {
        if let Some(v) = inc
            .and_then(|i| i.value(key))
            .filter(|v| **v != Value::None)
        {
            increment.push((key, v.clone()));
        }
    }
    call = call.fact(
        "INCREMENT",
        vec![occurrence("DYNA_VIBRA", "INCREMENT", increment)],
    );
    let mut passed = Vec::new();
    for fact in ["SCHEMA_TEMPS", "ARCHIVAGE", "COMPORTEMENT"] {
        if let Some(occ) = passed_on(args, fact, "DYNA_VIBRA") {
            call = call.fact(fact, occ);
            passed.push(fact);
        }
    }
    if c.depl.is_some() || c.vite.is_some() {
        let mut items = Vec::new();
        for (key, v) in [("DEPL", &c.depl), ("VITE", &c.vite)] {
            if let Some(n) = v {
                items.push((key, concept(ctx, n)?));
            }
        }
        call = call.fact(
            "ETAT_INIT",
            vec![occurrence("DYNA_VIBRA", "ETAT_INIT", items)],
        );
    }
    if !c.loads.is_empty() {
        let mut occ = Vec::new();
        for (field, fonc, coef) in &c.loads {
            let mut items = vec![(vect_key, concept(ctx, field)?)];
            if let Some(f) = fonc {
                items.push(("FONC_MULT", f.clone()));
            }
            if let Some(k) = coef {
                items.push(("COEF_MULT", Value::Real(*k)));
            }
            occ.push(occurrence("DYNA_VIBRA", "EXCIT", items));
        }
        call = call.fact("EXCIT", occ);
    }
    call.run(ctx, Some(result), "DYNA_LINE/INCREMENT", &passed)
}
