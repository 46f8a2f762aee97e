//! DYNA_LINE's transient: the time step, the projection on the basis (PROJ_BASE) and the
//! DYNA_VIBRA call on the chained concepts.

use super::basis;
use super::chain::{concept, occurrence, passed_on, Call};
use super::loads::Load;
use super::Assembled;
use crate::args::Args;
use crate::error::{Error, Result};
use crate::ops::OpContext;
use crate::value::Value;

/// The time step: INCREMENT/PAS, else 1/(5 F_max) of BANDE_ANALYSE (Code_Aster's).
pub(super) fn step(args: &Args) -> Result<f64> {
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
pub(super) struct Chained {
    pub(super) mass: String,
    pub(super) rigi: String,
    pub(super) amor: Option<String>,
    /// (field, FONC_MULT, COEF_MULT)
    pub(super) loads: Vec<(String, Option<Value>, Option<f64>)>,
    pub(super) depl: Option<String>,
    pub(super) vite: Option<String>,
}

/// PROJ_BASE of the matrices, the loads and the initial state on the basis.
pub(super) fn project(
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
pub(super) fn vibra(
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
