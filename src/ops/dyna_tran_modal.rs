//! DYNA_TRAN_MODAL: Code_Aster's transient on a modal basis before DYNA_VIBRA, run as
//! DYNA_VIBRA(TYPE_CALCUL='TRAN', BASE_CALCUL='GENE'). Its keywords (both the version-10
//! spellings and the later ones) are renamed into DYNA_VIBRA's, validated against
//! DYNA_VIBRA's catalog (its defaults and bounds), and the errors name the keyword as the
//! user wrote it.

use super::OpContext;
use crate::args::Args;
use crate::error::{Error, Result};
use crate::value::{Span, Value};

/// Top-level renames: DYNA_TRAN_MODAL's name, DYNA_VIBRA's.
const TOP: [(&str, &str); 7] = [
    ("MASS_GENE", "MATR_MASS"),
    ("MATR_MASS", "MATR_MASS"),
    ("RIGI_GENE", "MATR_RIGI"),
    ("MATR_RIGI", "MATR_RIGI"),
    ("AMOR_GENE", "MATR_AMOR"),
    ("MATR_AMOR", "MATR_AMOR"),
    ("MODE_STAT", "MODE_STAT"),
];

/// Renames inside a factor keyword (DYNA_VIBRA's factor, then the inner renames).
const ETAT_INIT: [(&str, &str); 8] = [
    ("DEPL_INIT_GENE", "DEPL"),
    ("DEPL", "DEPL"),
    ("VITE_INIT_GENE", "VITE"),
    ("VITE", "VITE"),
    ("RESU_GENE", "RESULTAT"),
    ("RESULTAT", "RESULTAT"),
    ("NUME_ORDRE", "NUME_ORDRE"),
    ("INST_INIT", "INST_INIT"),
];
const EXCIT: [(&str, &str); 4] = [
    ("VECT_GENE", "VECT_ASSE_GENE"),
    ("VECT_ASSE_GENE", "VECT_ASSE_GENE"),
    ("FONC_MULT", "FONC_MULT"),
    ("COEF_MULT", "COEF_MULT"),
];

/// METHODE (or SCHEMA) as DYNA_VIBRA's SCHEMA (docs/dyna_vibra.md: the departures).
fn scheme(name: &str) -> &str {
    match name {
        "EULER" => "DIFF_CENTRE",
        "ADAPT" => "ADAPT_ORDRE2",
        other => other,
    }
}

pub fn run(ctx: &mut OpContext<'_>, args: &Args) -> Result<()> {
    let (vibra, renamed) = translate(args);
    let vibra = crate::catalog::validate_args("DYNA_VIBRA", &vibra, None, ctx.file)
        .map_err(|e| spelled_as_written(e, &renamed))?;
    super::dyna_vibra::run(ctx, &vibra).map_err(|e| spelled_as_written(e, &renamed))
}

/// DYNA_VIBRA's keywords for the call, and the (DYNA_VIBRA path, user's path) of every
/// keyword renamed.
fn translate(args: &Args) -> (Args, Vec<(String, String)>) {
    let mut out = Args::new("DYNA_VIBRA");
    let mut renamed = Vec::new();
    let span = |k: &str| args.span(k).unwrap_or_default();
    out.simple.push((
        "TYPE_CALCUL".into(),
        Value::Str("TRAN".into()),
        Span::default(),
    ));
    out.simple.push((
        "BASE_CALCUL".into(),
        Value::Str("GENE".into()),
        Span::default(),
    ));
    for (from, to) in TOP {
        if let Some(v) = args.value(from).filter(|v| **v != Value::None) {
            out.simple.push((to.into(), v.clone(), span(from)));
            renamed.push((format!("DYNA_VIBRA/{to}"), args.key_path(from)));
        }
    }
    // INFO is DYNA_VIBRA's: 2 lists the contact changes located.
    if let Some(level) = args.int("INFO") {
        out.simple
            .push(("INFO".into(), Value::Int(level), span("INFO")));
    }
    if let Some(ratios) = args.value("AMOR_REDUIT").filter(|v| **v != Value::None) {
        let mut amor = Args::new("DYNA_VIBRA/AMOR_MODAL");
        amor.simple
            .push(("AMOR_REDUIT".into(), ratios.clone(), span("AMOR_REDUIT")));
        out.factor
            .push(("AMOR_MODAL".into(), vec![amor], span("AMOR_REDUIT")));
        renamed.push((
            "DYNA_VIBRA/AMOR_MODAL/AMOR_REDUIT".into(),
            args.key_path("AMOR_REDUIT"),
        ));
    }
    if let Some(m) = args.text("METHODE") {
        let mut st = Args::new("DYNA_VIBRA/SCHEMA_TEMPS");
        st.simple.push((
            "SCHEMA".into(),
            Value::Str(scheme(m).into()),
            span("METHODE"),
        ));
        out.factor
            .push(("SCHEMA_TEMPS".into(), vec![st], span("METHODE")));
        renamed.push((
            "DYNA_VIBRA/SCHEMA_TEMPS/SCHEMA".into(),
            args.key_path("METHODE"),
        ));
    }
    for (fact, inner) in [
        ("AMOR_MODAL", &[][..]),
        ("SCHEMA_TEMPS", &[][..]),
        ("INCREMENT", &[][..]),
        ("ARCHIVAGE", &[][..]),
        ("VERI_CHOC", &[][..]),
        ("ETAT_INIT", &ETAT_INIT[..]),
        ("EXCIT", &EXCIT[..]),
        ("CHOC", &[][..]),
        ("FLAMBAGE", &[][..]),
    ] {
        let Some(occurrences) = args.facts(fact) else {
            continue;
        };
        let copies = occurrences
            .iter()
            .enumerate()
            .map(|(i, occ)| {
                let path = if occurrences.len() > 1 {
                    format!("DYNA_VIBRA/{fact}[{}]", i + 1)
                } else {
                    format!("DYNA_VIBRA/{fact}")
                };
                let mut copy = Args::new(path.clone());
                for (key, value, s) in &occ.simple {
                    if *value == Value::None {
                        continue;
                    }
                    let to = inner
                        .iter()
                        .find(|(f, _)| f == key)
                        .map_or(key.as_str(), |(_, t)| t);
                    let value = match value {
                        Value::Str(n) if fact == "SCHEMA_TEMPS" && key == "SCHEMA" => {
                            Value::Str(scheme(n).into())
                        }
                        v => v.clone(),
                    };
                    copy.simple.push((to.to_string(), value, *s));
                    if to != key {
                        renamed.push((format!("{path}/{to}"), occ.key_path(key)));
                    }
                }
                copy.factor = occ.factor.clone();
                copy
            })
            .collect();
        out.factor.push((fact.to_string(), copies, span(fact)));
    }
    (out, renamed)
}

/// An error about a DYNA_VIBRA keyword, named as the user wrote it in DYNA_TRAN_MODAL.
fn spelled_as_written(mut e: Error, renamed: &[(String, String)]) -> Error {
    if let Some(k) = e.keyword.clone() {
        let user = renamed
            .iter()
            .find(|(vibra, _)| k == *vibra || k.starts_with(&format!("{vibra}/")))
            .map(|(vibra, user)| format!("{user}{}", &k[vibra.len()..]))
            .unwrap_or_else(|| k.replacen("DYNA_VIBRA", "DYNA_TRAN_MODAL", 1));
        e.keyword = Some(user);
    }
    e
}
