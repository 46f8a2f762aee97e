//! Tests of the catalogs and of validation. Calls are built by hand as the evaluator would
//! hand them over; every keyword sits on its own line so locations can be told apart.

use super::*;
use crate::error::Error;
use crate::value::{CommandCall, ConceptRef, Keyword, Span, Value};

const FILE: &str = "study.comm";

/// Span of a keyword written on line `line`.
fn at(line: usize) -> Span {
    Span {
        start: line * 100,
        end: line * 100 + 20,
        line,
        col: 5,
    }
}

fn call_span() -> Span {
    Span {
        start: 0,
        end: 5000,
        line: 1,
        col: 1,
    }
}

fn op_span() -> Span {
    Span {
        start: 4,
        end: 17,
        line: 1,
        col: 5,
    }
}

fn k(name: &str, value: Value, line: usize) -> Keyword {
    Keyword {
        name: name.into(),
        value,
        span: at(line),
    }
}

fn call(op: &str, args: Vec<Keyword>) -> CommandCall {
    CommandCall {
        op: op.into(),
        result: Some("RES".into()),
        reuse: None,
        args,
        span: call_span(),
        op_span: op_span(),
    }
}

fn co(name: &str, ty: &str) -> Value {
    Value::Concept(ConceptRef {
        name: name.into(),
        ty: ty.into(),
    })
}
fn r(x: f64) -> Value {
    Value::Real(x)
}
fn i(x: i64) -> Value {
    Value::Int(x)
}
fn s(x: &str) -> Value {
    Value::Str(x.into())
}
fn seq(v: Vec<Value>) -> Value {
    Value::Seq(v)
}
fn f(kws: Vec<Keyword>) -> Value {
    Value::Fact(kws)
}

fn errors(c: &CommandCall) -> Vec<Error> {
    match validate(c, FILE) {
        Ok(a) => panic!("expected errors, got {a:?}"),
        Err(e) => e,
    }
}

/// The single error of a call, checked for its keyword path and its line.
fn single_error(c: &CommandCall, keyword: &str, line: usize) -> Error {
    let errs = errors(c);
    assert_eq!(errs.len(), 1, "expected one error, got {errs:#?}");
    let e = errs.into_iter().next().expect("one error");
    assert_eq!(e.keyword.as_deref(), Some(keyword), "{e}");
    let loc = e.location.clone().expect("a location");
    assert_eq!(loc.file, FILE);
    assert_eq!(loc.span.line, line, "{e}");
    assert_eq!(e.kind, crate::error::ErrorKind::Validation);
    e
}

/// A complete MODE_NON_LINE call like sdnd122a's, lines 2..; `extra` is added at the top level.
fn mnl(extra: Vec<Keyword>) -> CommandCall {
    let mut args = vec![
        k("MATR_RIGI", co("RIGI", "matr_asse_depl_r"), 2),
        k("MATR_MASS", co("MASS", "matr_asse_depl_r"), 3),
        k(
            "ETAT_INIT",
            f(vec![
                k("MODE_LINE", co("MODES", "mode_meca"), 5),
                k("NUME_ORDRE", i(1), 6),
                k("DIR_EVOLUTION", i(1), 7),
            ]),
            4,
        ),
        k(
            "CHOC",
            f(vec![
                k("OBSTACLE", s("PLAN"), 9),
                k("NOEUD", s("N2"), 10),
                k("NOM_CMP", s("DX"), 11),
                k("JEU", r(0.01), 12),
                k("RIGI_NOR", i(50), 13),
                k("PARA_REGUL", r(5e-5), 14),
            ]),
            8,
        ),
        k(
            "RESOLUTION",
            f(vec![
                k("METHODE", s("EHMAN"), 16),
                k("NB_HARM_LINE", i(5), 17),
                k("NB_HARM_NONL", i(200), 18),
                k("NB_BRANCHE", i(105), 19),
                k("NB_PAS_MAN", i(1), 20),
                k("NB_ORDRE_MAN", i(20), 21),
                k("PREC_MAN", r(1e-14), 22),
                k("PREC_NEWTON", r(1e-9), 23),
                k("ITER_NEWTON_MAXI", i(15), 24),
            ]),
            15,
        ),
    ];
    args.extend(extra);
    call("MODE_NON_LINE", args)
}

/// `mnl` with keyword `key` of factor `fact` replaced (or removed when `value` is None).
fn mnl_with(fact: &str, key: &str, value: Option<Value>, line: usize) -> CommandCall {
    let mut c = mnl(vec![]);
    for kw in c.args.iter_mut().filter(|kw| kw.name == fact) {
        if let Value::Fact(items) = &mut kw.value {
            items.retain(|x| x.name != key);
            if let Some(v) = value.clone() {
                items.push(k(key, v, line));
            }
        }
    }
    c
}

// ---------------------------------------------------------------- catalogs themselves

#[test]
fn catalogs_parse_and_are_consistent() {
    let problems = check_consistency();
    assert!(
        problems.is_empty(),
        "catalog problems:\n{}",
        problems.join("\n")
    );
    let names = operator_names();
    for op in [
        "DEBUT",
        "POURSUITE",
        "FIN",
        "DETRUIRE",
        "CREA_TABLE",
        "IMPR_TABLE",
        "CALC_TABLE",
        "EXTR_TABLE",
        "DEFI_FONCTION",
        "RECU_FONCTION",
        "IMPR_FONCTION",
        "TEST_TABLE",
        "TEST_FONCTION",
        "TEST_RESU",
        "MODE_NON_LINE",
        "REST_MODE_NONL",
        "CALC_STABILITE",
    ] {
        assert!(names.contains(&op), "{op} missing from {names:?}");
    }
    assert_eq!(names.len(), files().len(), "one operator per file");
    let mut sorted = names.clone();
    sorted.sort();
    assert_eq!(names, sorted);
}

#[test]
fn embedded_json_reads_as_the_toml() {
    // A run reads the JSON build.rs made of each catalog: it must give exactly what the
    // TOML says (floats, integers, lists and defaults included), for every file.
    for (i, (file, text)) in files().iter().enumerate() {
        let json = super::embedded::JSON[i].unwrap_or_else(|| panic!("{file}: no JSON"));
        let from_json: OperatorDef = serde_json::from_str(json).unwrap();
        assert_eq!(from_json, parse(file, text).unwrap(), "{file}");
        assert_eq!(super::parse_embedded(i).unwrap(), from_json, "{file}");
    }
    assert_eq!(super::embedded::JSON.len(), files().len());
}

#[test]
fn consistency_check_catches_bad_catalogs() {
    // A broken catalog run through the same checks as the embedded ones.
    let text = r#"
name = "BAD"
rules = [{ kind = "UN_PARMI", keywords = ["A", "NOPE"] }]
[[simp]]
name = "A"
type = "I"
statut = "d"
default = "x"
[[simp]]
name = "A"
type = "R"
statut = "o"
[[simp]]
name = "B"
type = "TXM"
statut = "d"
default = "Z"
into = ["X", "Y"]
when = { keyword = "MISSING" }
[[simp]]
name = "C"
type = "matr_asse_typo"
statut = "f"
"#;
    let op = parse("BAD.toml", text).expect("parses");
    let mut out = Vec::new();
    check::check_op(&op, &mut out);
    let all = out.join("\n");
    assert!(all.contains("names unknown keyword NOPE"), "{all}");
    assert!(
        all.contains("BAD/A: default 'x': expected an integer"),
        "{all}"
    );
    assert!(all.contains("keyword A defined twice"), "{all}");
    assert!(
        all.contains("BAD/B: default 'Z': expected one of 'X', 'Y'"),
        "{all}"
    );
    assert!(
        all.contains("`when` names unknown keyword MISSING"),
        "{all}"
    );
    assert!(all.contains("unknown type matr_asse_typo"), "{all}");
    assert!(
        parse("X.toml", "name = \"X\"\nbogus = 1\n").is_err(),
        "unknown fields are refused"
    );
}

// ---------------------------------------------------------------- a real call

#[test]
fn validates_a_real_mode_non_line_call_with_defaults() {
    let a = validate(&mnl(vec![]), FILE).expect("valid call");
    assert_eq!(a.path, "MODE_NON_LINE");
    // Simple keywords in catalog order, INFO defaulted with the call's span.
    let names: Vec<&str> = a.simple.iter().map(|(n, _, _)| n.as_str()).collect();
    assert_eq!(names, ["MATR_RIGI", "MATR_MASS", "INFO"]);
    assert_eq!(a.int("INFO"), Some(1));
    assert_eq!(a.span("INFO"), Some(call_span()));
    assert_eq!(
        a.concept("MATR_RIGI").map(|c| c.name.as_str()),
        Some("RIGI")
    );

    let e = a.fact("ETAT_INIT").expect("ETAT_INIT");
    assert_eq!(e.path, "MODE_NON_LINE/ETAT_INIT");
    assert_eq!(e.int("DIR_EVOLUTION"), Some(1));
    assert_eq!(e.real("COEF_AMPL"), Some(1.0));

    let chocs = a.facts("CHOC").expect("CHOC");
    assert_eq!(chocs.len(), 1);
    let c = &chocs[0];
    assert_eq!(c.path, "MODE_NON_LINE/CHOC");
    assert_eq!(c.real("PARA_REGUL"), Some(5e-5));
    // NOM_CMP is a single component for a PLAN shock.
    assert_eq!(c.value("NOM_CMP"), Some(&s("DX")));
    // List default.
    assert_eq!(c.reals("ORIG_OBST"), Some(vec![0.0, 0.0, 0.0]));
    // An integer given to a real keyword is accepted.
    assert_eq!(c.real("RIGI_NOR"), Some(50.0));

    let res = a.fact("RESOLUTION").expect("RESOLUTION");
    assert_eq!(res.int("NB_HARM_NONL"), Some(200));
    assert_eq!(res.int("CRIT_ORDR_BIFURCATION"), Some(3));
    assert_eq!(res.real("RESI_RELA_BIFURCATION"), Some(1e-4));

    // SOLVEUR absent with statut "d": one occurrence made of its defaults, MUMPS branch.
    let solv = a.fact("SOLVEUR").expect("SOLVEUR by default");
    assert_eq!(solv.text("METHODE"), Some("MUMPS"));
    assert_eq!(solv.text("RENUM"), Some("AUTO"));
    assert_eq!(solv.int("PCENT_PIVOT"), Some(20));
    assert_eq!(a.span("SOLVEUR"), Some(call_span()));

    assert_eq!(
        result_type("MODE_NON_LINE", &a).as_deref(),
        Some("table_container")
    );
}

#[test]
fn defaults_of_the_resolution_block() {
    let c = mnl(vec![]);
    let mut c2 = c.clone();
    // Keep only the mandatory keywords of RESOLUTION.
    for kw in c2.args.iter_mut().filter(|kw| kw.name == "RESOLUTION") {
        kw.value = f(vec![
            k("NB_HARM_LINE", i(5), 17),
            k("NB_BRANCHE", i(10), 19),
            k("NB_PAS_MAN", i(1), 20),
        ]);
    }
    let a = validate(&c2, FILE).expect("valid");
    let res = a.fact("RESOLUTION").expect("RESOLUTION");
    assert_eq!(res.text("METHODE"), Some("EHMAN"));
    assert_eq!(res.int("NB_HARM_NONL"), Some(201));
    assert_eq!(res.int("NB_ORDRE_MAN"), Some(20));
    assert_eq!(res.real("PREC_MAN"), Some(1e-9));
    assert_eq!(res.real("PREC_NEWTON"), Some(1e-8));
    assert_eq!(res.int("ITER_NEWTON_MAXI"), Some(15));
    let e = a.fact("ETAT_INIT").expect("ETAT_INIT");
    assert_eq!(e.int("DIR_EVOLUTION"), Some(1));
}

#[test]
fn restart_from_a_table_and_reuse() {
    let mut c = mnl(vec![]);
    c.args.retain(|kw| kw.name != "CHOC");
    for kw in c.args.iter_mut().filter(|kw| kw.name == "ETAT_INIT") {
        kw.value = f(vec![
            k("MODE_NON_LINE", co("MNL", "table_container"), 5),
            k("NUME_ORDRE", i(5), 6),
        ]);
    }
    c.reuse = Some(ConceptRef {
        name: "MNL".into(),
        ty: "table_container".into(),
    });
    let a = validate(&c, FILE).expect("restart with reuse");
    assert_eq!(
        a.fact("ETAT_INIT").and_then(|e| e.int("DIR_EVOLUTION")),
        Some(-1)
    );
    assert!(a.facts("CHOC").is_none());

    // reuse of a concept of another type
    c.reuse = Some(ConceptRef {
        name: "MODES".into(),
        ty: "mode_meca".into(),
    });
    let e = single_error(&c, "MODE_NON_LINE/reuse", 1);
    assert_eq!(
        e.message,
        "expected reuse= a concept of type table_container, got MODES of type mode_meca"
    );

    // reuse= must be the table the restart starts from (reuse_of in the catalog)...
    c.reuse = Some(ConceptRef {
        name: "OTHER".into(),
        ty: "table_container".into(),
    });
    let e = single_error(&c, "MODE_NON_LINE/reuse", 1);
    assert!(
        e.message
            .starts_with("reuse=OTHER but ETAT_INIT/MODE_NON_LINE=MNL"),
        "{e}"
    );
    // ... and a first run (from a linear mode) cannot extend a table.
    let mut first = mnl(vec![]);
    first.reuse = Some(ConceptRef {
        name: "MNL".into(),
        ty: "table_container".into(),
    });
    let e = single_error(&first, "MODE_NON_LINE/reuse", 1);
    assert!(
        e.message
            .starts_with("reuse=MNL needs ETAT_INIT/MODE_NON_LINE=MNL"),
        "{e}"
    );
}

// ---------------------------------------------------------------- error kinds

#[test]
fn unknown_operator_suggests_close_names() {
    let c = call("MODE_NON_LINEE", vec![]);
    let errs = errors(&c);
    assert_eq!(errs.len(), 1);
    let e = &errs[0];
    assert_eq!(e.message, "unknown operator MODE_NON_LINEE");
    assert_eq!(e.location.as_ref().map(|l| l.span), Some(op_span()));
    assert_eq!(e.keyword.as_deref(), Some("MODE_NON_LINEE"));
    assert_eq!(e.hint.as_deref(), Some("did you mean MODE_NON_LINE?"));
}

#[test]
fn unknown_keyword_suggests_names_of_its_level() {
    let c = mnl(vec![k("MATR_RIGU", co("R", "matr_asse_depl_r"), 30)]);
    let e = single_error(&c, "MODE_NON_LINE/MATR_RIGU", 30);
    assert_eq!(e.message, "unknown keyword MATR_RIGU for MODE_NON_LINE");
    assert_eq!(e.hint.as_deref(), Some("did you mean MATR_RIGI?"));

    // Inside a factor keyword: the names of that factor keyword are suggested.
    let c = mnl_with("CHOC", "RIGI_NORM", Some(r(1.0)), 31);
    let errs = errors(&c);
    let e = errs
        .iter()
        .find(|e| e.keyword.as_deref() == Some("MODE_NON_LINE/CHOC/RIGI_NORM"))
        .expect("unknown keyword error");
    assert_eq!(e.location.as_ref().map(|l| l.span.line), Some(31));
    assert_eq!(e.hint.as_deref(), Some("did you mean RIGI_NOR?"));
}

#[test]
fn wrong_types() {
    // R refuses a text.
    let e = single_error(
        &mnl_with("CHOC", "JEU", Some(s("petit")), 40),
        "MODE_NON_LINE/CHOC/JEU",
        40,
    );
    assert_eq!(e.message, "expected a real, got a text 'petit'");
    // I refuses a real.
    let e = single_error(&mnl(vec![k("INFO", r(1.0), 41)]), "MODE_NON_LINE/INFO", 41);
    assert_eq!(e.message, "expected an integer, got a real 1.0");
    // TXM refuses a number.
    let e = single_error(
        &mnl_with("CHOC", "NOEUD", Some(i(2)), 42),
        "MODE_NON_LINE/CHOC/NOEUD",
        42,
    );
    assert_eq!(e.message, "expected a text, got an integer 2");
    // A concept of the wrong type.
    let mut c = mnl(vec![]);
    c.args[0].value = co("MODES", "mode_meca");
    let e = single_error(&c, "MODE_NON_LINE/MATR_RIGI", 2);
    assert_eq!(
        e.message,
        "expected a concept of type matr_asse_depl_r, got MODES of type mode_meca"
    );
    // A quoted concept name gets a hint.
    c.args[0].value = s("RIGI");
    let e = single_error(&c, "MODE_NON_LINE/MATR_RIGI", 2);
    assert_eq!(
        e.message,
        "expected a concept of type matr_asse_depl_r, got a text 'RIGI'"
    );
    assert!(e
        .hint
        .as_deref()
        .is_some_and(|h| h.contains("without quotes")));
}

#[test]
fn concept_types_with_alternatives_and_any() {
    let tab = |ty: &str| call("IMPR_TABLE", vec![k("TABLE", co("T", ty), 2)]);
    assert!(validate(&tab("table_sdaster"), FILE).is_ok());
    assert!(validate(&tab("table_container"), FILE).is_ok());
    let e = single_error(&tab("fonction_sdaster"), "IMPR_TABLE/TABLE", 2);
    assert_eq!(
        e.message,
        "expected a concept of type table_sdaster or table_container or dyna_trans or tran_gene, got T of type fonction_sdaster"
    );
    // DETRUIRE takes concepts of any type, as a list.
    let c = call(
        "DETRUIRE",
        vec![k(
            "CONCEPT",
            f(vec![k(
                "NOM",
                seq(vec![co("A", "mode_meca"), co("B", "table_sdaster")]),
                3,
            )]),
            2,
        )],
    );
    let a = validate(&c, FILE).expect("valid");
    let names: Vec<String> = a
        .fact("CONCEPT")
        .and_then(|o| o.concepts("NOM"))
        .unwrap_or_default()
        .into_iter()
        .map(|c| c.name)
        .collect();
    assert_eq!(names, ["A", "B"]);
    let e = single_error(
        &call("DETRUIRE", vec![k("NOM", r(1.0), 2)]),
        "DETRUIRE/NOM",
        2,
    );
    assert_eq!(e.message, "expected a concept, got a real 1.0");
}

#[test]
fn scalar_and_list_handling() {
    // A one-element list where a scalar is expected is accepted (and unwrapped).
    let a = validate(
        &mnl_with("ETAT_INIT", "NUME_ORDRE", Some(seq(vec![i(3)])), 6),
        FILE,
    )
    .expect("valid");
    assert_eq!(
        a.fact("ETAT_INIT").and_then(|e| e.value("NUME_ORDRE")),
        Some(&i(3))
    );
    // A longer list is not.
    let e = single_error(
        &mnl_with("ETAT_INIT", "NUME_ORDRE", Some(seq(vec![i(3), i(4)])), 6),
        "MODE_NON_LINE/ETAT_INIT/NUME_ORDRE",
        6,
    );
    assert_eq!(
        e.message,
        "expected a single value (an integer), got a list of 2 values"
    );
    // Length bounds of a list.
    let e = single_error(
        &mnl_with("CHOC", "ORIG_OBST", Some(seq(vec![r(0.0), r(1.0)])), 50),
        "MODE_NON_LINE/CHOC/ORIG_OBST",
        50,
    );
    assert_eq!(e.message, "expected 3 value(s) (a real), got 2");
    let e = single_error(
        &mnl_with(
            "CHOC",
            "NOM_CMP",
            Some(seq(vec![s("DX"), s("DY"), s("DZ")])),
            51,
        ),
        "MODE_NON_LINE/CHOC/NOM_CMP",
        51,
    );
    assert_eq!(
        e.message,
        "expected a single value (a text), got a list of 3 values"
    );
    // The hint says which definition of NOM_CMP applied, and why.
    assert_eq!(
        e.hint.as_deref(),
        Some("NOM_CMP takes this form when OBSTACLE is 'PLAN' or 'BI_PLAN'")
    );
    // A CERCLE shock takes two components (the definition of NOM_CMP follows OBSTACLE).
    let mut c = mnl_with("CHOC", "OBSTACLE", Some(s("CERCLE")), 53);
    let e = single_error(&c, "MODE_NON_LINE/CHOC/NOM_CMP", 11);
    assert_eq!(e.message, "expected 2 value(s) (a text), got 1");
    assert_eq!(
        e.hint.as_deref(),
        Some("NOM_CMP takes this form when OBSTACLE is 'CERCLE'")
    );
    // A misspelt OBSTACLE is the one error: NOM_CMP, whose form depends on it, is not
    // reported too (neither "only allowed when ..." nor a count).
    let e = single_error(
        &mnl_with("CHOC", "OBSTACLE", Some(s("CERCL")), 53),
        "MODE_NON_LINE/CHOC/OBSTACLE",
        53,
    );
    assert!(e.message.contains("'CERCL'"), "{}", e.message);
    for kw in c.args.iter_mut().filter(|kw| kw.name == "CHOC") {
        if let Value::Fact(items) = &mut kw.value {
            for it in items.iter_mut().filter(|it| it.name == "NOM_CMP") {
                it.value = seq(vec![s("DY"), s("DZ")]);
            }
        }
    }
    let a = validate(&c, FILE).expect("CERCLE with two components");
    assert_eq!(
        a.fact("CHOC").and_then(|o| o.texts("NOM_CMP")),
        Some(vec!["DY".to_string(), "DZ".to_string()])
    );
    // The wrong items of a list are one message: the first, and how many more (issue 35:
    // a million wrong items were a million messages).
    let c = mnl_with(
        "CHOC",
        "ORIG_OBST",
        Some(seq(vec![s("a"), r(0.0), s("b")])),
        52,
    );
    let errs = errors(&c);
    assert_eq!(errs.len(), 1, "{errs:#?}");
    assert!(errs[0].message.contains("'a'"), "{errs:#?}");
    assert!(
        errs[0].message.contains("and 1 more wrong item"),
        "{errs:#?}"
    );
    // A list default normalized: INTERPOL default of DEFI_FONCTION.
    let c = call(
        "DEFI_FONCTION",
        vec![
            k("NOM_PARA", s("X"), 2),
            k("VALE", seq(vec![r(0.0), r(1.0), r(1.0), r(2.0)]), 3),
        ],
    );
    let a = validate(&c, FILE).expect("valid");
    assert_eq!(
        a.texts("INTERPOL"),
        Some(vec!["LIN".to_string(), "LIN".to_string()])
    );
    // A scalar default of a list keyword becomes a one-element list.
    let c = call(
        "TEST_FONCTION",
        vec![k(
            "VALEUR",
            f(vec![
                k("FONCTION", co("F", "fonction_sdaster"), 3),
                k("VALE_PARA", r(0.5), 4),
                k("VALE_CALC", r(1.5), 5),
            ]),
            2,
        )],
    );
    let a = validate(&c, FILE).expect("valid");
    assert_eq!(
        a.fact("VALEUR").and_then(|v| v.value("CRITERE")),
        Some(&seq(vec![s("RELATIF")]))
    );
}

#[test]
fn missing_mandatory_keywords() {
    // A simple keyword of the operator: located at the call.
    let mut c = mnl(vec![]);
    c.args.retain(|kw| kw.name != "MATR_MASS");
    let e = single_error(&c, "MODE_NON_LINE/MATR_MASS", 1);
    assert_eq!(e.message, "missing mandatory keyword MATR_MASS");
    // A factor keyword.
    let mut c = mnl(vec![]);
    c.args.retain(|kw| kw.name != "RESOLUTION");
    let e = single_error(&c, "MODE_NON_LINE/RESOLUTION", 1);
    assert_eq!(e.message, "missing mandatory keyword RESOLUTION");
    // A keyword of a factor keyword: located at that factor keyword.
    let e = single_error(
        &mnl_with("CHOC", "JEU", None, 0),
        "MODE_NON_LINE/CHOC/JEU",
        8,
    );
    assert_eq!(e.message, "missing mandatory keyword JEU");
}

#[test]
fn values_outside_into_and_bounds() {
    let e = single_error(
        &mnl_with("CHOC", "OBSTACLE", Some(s("PLANE")), 60),
        "MODE_NON_LINE/CHOC/OBSTACLE",
        60,
    );
    assert_eq!(
        e.message,
        "expected one of 'PLAN', 'BI_PLAN', 'CERCLE', got 'PLANE'"
    );
    assert_eq!(
        e.hint.as_deref(),
        Some("allowed values: 'PLAN', 'BI_PLAN', 'CERCLE'")
    );
    let e = single_error(
        &mnl_with("ETAT_INIT", "DIR_EVOLUTION", Some(i(0)), 61),
        "MODE_NON_LINE/ETAT_INIT/DIR_EVOLUTION",
        61,
    );
    assert_eq!(e.message, "expected one of -1, 1, got 0");
    let e = single_error(
        &mnl_with("CHOC", "JEU", Some(r(-0.5)), 62),
        "MODE_NON_LINE/CHOC/JEU",
        62,
    );
    assert_eq!(e.message, "expected a value > 0.0, got -0.5");
    // The bound itself is refused when the catalog excludes it.
    let e = single_error(
        &mnl_with("CHOC", "JEU", Some(r(0.0)), 62),
        "MODE_NON_LINE/CHOC/JEU",
        62,
    );
    assert_eq!(e.message, "expected a value > 0.0, got 0.0");
    let e = single_error(
        &mnl_with("CHOC", "JEU", Some(r(f64::NAN)), 62),
        "MODE_NON_LINE/CHOC/JEU",
        62,
    );
    assert!(
        e.message.starts_with("expected a finite number"),
        "{}",
        e.message
    );
    let c = call(
        "DEBUT",
        vec![k("RESERVE_CPU", f(vec![k("POURCENTAGE", r(1.5), 3)]), 2)],
    );
    let e = single_error(&c, "DEBUT/RESERVE_CPU/POURCENTAGE", 3);
    assert_eq!(e.message, "expected a value <= 1.0, got 1.5");
}

#[test]
fn factor_occurrences() {
    let two = |line| {
        f(vec![
            k("MODE_LINE", co("M", "mode_meca"), line),
            k("NUME_ORDRE", i(1), line),
        ])
    };
    let mut c = mnl(vec![]);
    for kw in c.args.iter_mut().filter(|kw| kw.name == "ETAT_INIT") {
        kw.value = seq(vec![two(5), two(6)]);
    }
    let e = single_error(&c, "MODE_NON_LINE/ETAT_INIT", 4);
    assert_eq!(e.message, "expected 1 occurrence(s) of _F(...), got 2");
    // A tuple of several CHOC is fine; each occurrence its own Args.
    let choc = |node: &str| {
        f(vec![
            k("OBSTACLE", s("BI_PLAN"), 9),
            k("GROUP_NO", s(node), 10),
            k("NOM_CMP", s("DY"), 11),
            k("JEU", r(0.1), 12),
            k("RIGI_NOR", r(1e3), 13),
        ])
    };
    let mut c = mnl(vec![]);
    for kw in c.args.iter_mut().filter(|kw| kw.name == "CHOC") {
        kw.value = seq(vec![choc("G1"), choc("G2")]);
    }
    let a = validate(&c, FILE).expect("two shocks");
    let groups: Vec<&str> = a
        .facts_or_empty("CHOC")
        .iter()
        .filter_map(|o| o.text("GROUP_NO"))
        .collect();
    assert_eq!(groups, ["G1", "G2"]);
    // An empty tuple is below min.
    let mut c = mnl(vec![]);
    for kw in c.args.iter_mut().filter(|kw| kw.name == "CHOC") {
        kw.value = seq(vec![]);
    }
    let e = single_error(&c, "MODE_NON_LINE/CHOC", 8);
    assert_eq!(
        e.message,
        "expected at least 1 occurrence(s) of _F(...), got 0"
    );
    // Something else than _F.
    let mut c = mnl(vec![]);
    for kw in c.args.iter_mut().filter(|kw| kw.name == "CHOC") {
        kw.value = r(1.0);
    }
    let e = single_error(&c, "MODE_NON_LINE/CHOC", 8);
    assert_eq!(
        e.message,
        "expected a factor keyword _F(...) or a tuple of them, got a real 1.0"
    );
}

#[test]
fn rule_un_parmi() {
    // None given.
    let e = single_error(
        &mnl_with("ETAT_INIT", "MODE_LINE", None, 0),
        "MODE_NON_LINE/ETAT_INIT/MODE_LINE",
        4,
    );
    assert_eq!(
        e.message,
        "expected exactly one of MODE_LINE, MODE_NON_LINE, none given (rule UN_PARMI(MODE_LINE, MODE_NON_LINE))"
    );
    // Both given: located at the second one.
    let c = mnl_with(
        "ETAT_INIT",
        "MODE_NON_LINE",
        Some(co("T", "table_container")),
        70,
    );
    let e = single_error(&c, "MODE_NON_LINE/ETAT_INIT/MODE_NON_LINE", 70);
    assert_eq!(
        e.message,
        "expected exactly one of MODE_LINE, MODE_NON_LINE, got MODE_LINE and MODE_NON_LINE (rule UN_PARMI(MODE_LINE, MODE_NON_LINE))"
    );
}

#[test]
fn rule_ensemble_and_conditional_rule() {
    let stab = |filtre: Vec<Keyword>| {
        call(
            "CALC_STABILITE",
            vec![
                k("MODE_NON_LINE", co("MNL", "table_container"), 2),
                k("FILTRE", f(filtre), 3),
            ],
        )
    };
    let e = single_error(
        &stab(vec![k("FREQ_MIN", r(0.5), 4)]),
        "CALC_STABILITE/FILTRE/FREQ_MAX",
        3,
    );
    assert_eq!(
        e.message,
        "expected FREQ_MAX too: FREQ_MIN, FREQ_MAX go together, got only FREQ_MIN (rule ENSEMBLE(FREQ_MIN, FREQ_MAX))"
    );
    let a = validate(&stab(vec![k("NUME_ORDRE", i(1000), 4)]), FILE).expect("valid");
    let flt = a.fact("FILTRE").expect("FILTRE");
    // A scalar given to a list keyword becomes a one-element list.
    assert_eq!(flt.value("NUME_ORDRE"), Some(&seq(vec![i(1000)])));
    assert_eq!(flt.real("PRECISION"), Some(1e-3));
    assert_eq!(
        a.fact("SCHEMA_TEMPS").and_then(|s| s.int("NB_INST")),
        Some(1000)
    );
    assert_eq!(a.real("TOLERANCE"), Some(1e-2));

    // A rule applying under a condition: EQ (the default) needs a value, MAXI does not.
    let impr = |filtre: Vec<Keyword>| {
        call(
            "IMPR_TABLE",
            vec![
                k("TABLE", co("T", "table_sdaster"), 2),
                k("FILTRE", f(filtre), 3),
            ],
        )
    };
    let e = single_error(
        &impr(vec![k("NOM_PARA", s("FREQUENCE"), 4)]),
        "IMPR_TABLE/FILTRE/VALE",
        3,
    );
    assert!(
        e.message
            .ends_with("when CRIT_COMP is 'EQ' or 'NE' or 'GT' or 'LT' or 'GE' or 'LE')"),
        "{}",
        e.message
    );
    assert!(validate(
        &impr(vec![
            k("NOM_PARA", s("FREQUENCE"), 4),
            k("CRIT_COMP", s("MAXI"), 5)
        ]),
        FILE
    )
    .is_ok());
    let a = validate(
        &impr(vec![
            k("NOM_PARA", s("NUME_ORDRE"), 4),
            k("VALE_I", i(5), 5),
        ]),
        FILE,
    )
    .expect("valid");
    let flt = a.fact("FILTRE").expect("FILTRE");
    assert_eq!(flt.text("CRIT_COMP"), Some("EQ"));
    assert_eq!(flt.text("CRITERE"), Some("RELATIF"));
    // Pictures (FORMAT='PNG'/'SVG'): NOM_PARA is optional, a MODE_NON_LINE table without it
    // gives its frequency-energy plot (the operator picks the curve from the table).
    let plot = |format: &str, kws: Vec<Keyword>| {
        let mut v = vec![
            k("TABLE", co("MNL", "table_container"), 2),
            k("FORMAT", s(format), 3),
            k("UNITE", i(30), 4),
        ];
        v.extend(kws);
        call("IMPR_TABLE", v)
    };
    let a = validate(&plot("PNG", vec![]), FILE).expect("picture without NOM_PARA");
    assert_eq!(a.texts("NOM_PARA"), None);
    let a = validate(
        &plot(
            "SVG",
            vec![
                k("NOM_PARA", seq(vec![s("ENERGIE"), s("FREQUENCE")]), 5),
                k("COURBE", s("COLONNES"), 6),
            ],
        ),
        FILE,
    )
    .expect("valid plot");
    assert_eq!(
        a.texts("NOM_PARA"),
        Some(vec!["ENERGIE".to_string(), "FREQUENCE".to_string()])
    );
    assert_eq!(a.text("COURBE"), Some("COLONNES"));
    // The picture keywords belong to a picture format.
    let e = single_error(
        &plot("TABLEAU", vec![k("COURBE", s("FREQ_ENER"), 5)]),
        "IMPR_TABLE/COURBE",
        5,
    );
    assert_eq!(
        e.message,
        "keyword COURBE is only allowed when FORMAT is 'PNG' or 'SVG'"
    );
    // A misspelt FORMAT is the one error: the picture keywords depending on it are not
    // reported as "only allowed when ..." too.
    let e = single_error(
        &plot(
            "PNJ",
            vec![k("COURBE", s("FREQ_ENER"), 5), k("ECHELLE_X", s("LOG"), 6)],
        ),
        "IMPR_TABLE/FORMAT",
        3,
    );
    assert!(e.message.contains("'PNJ'"), "{}", e.message);
    // A complex value Code_Aster style is one value.
    assert!(validate(
        &impr(vec![
            k("NOM_PARA", s("Z"), 4),
            k("VALE_C", seq(vec![s("RI"), r(1.0), r(2.0)]), 5)
        ]),
        FILE
    )
    .is_ok());
}

/// A catalog exercising the rule kinds no embedded catalog uses at the top level, and CO.
const RULES_CATALOG: &str = r#"
name = "RULES"
result = "table_sdaster"
reuse = "required"
rules = [
  { kind = "AU_MOINS_UN", keywords = ["A", "B"] },
  { kind = "AU_PLUS_UN", keywords = ["B", "C"] },
  { kind = "EXCLUS", keywords = ["C", "D"] },
  { kind = "PRESENT_PRESENT", keywords = ["A", "E", "F"] },
  { kind = "PRESENT_ABSENT", keywords = ["D", "A", "B"] },
]
[[simp]]
name = "A"
type = "I"
statut = "f"
[[simp]]
name = "B"
type = "I"
statut = "f"
[[simp]]
name = "C"
type = "I"
statut = "f"
[[simp]]
name = "D"
type = "I"
statut = "f"
[[simp]]
name = "E"
type = "I"
statut = "f"
[[simp]]
name = "F"
type = "I"
statut = "f"
[[simp]]
name = "OUT"
type = "CO"
statut = "f"
"#;

fn rules_errors(kws: &[(&str, usize)]) -> Vec<Error> {
    let op = parse("RULES.toml", RULES_CATALOG).expect("parses");
    let mut c = call("RULES", kws.iter().map(|(n, l)| k(n, i(1), *l)).collect());
    c.reuse = Some(ConceptRef {
        name: "T".into(),
        ty: "table_sdaster".into(),
    });
    match validate_with(&op, &c, FILE) {
        Ok(_) => vec![],
        Err(e) => e,
    }
}

#[test]
fn rule_kinds() {
    let msgs = |e: Vec<Error>| -> Vec<(String, String, usize)> {
        e.into_iter()
            .map(|e| {
                (
                    e.keyword.unwrap_or_default(),
                    e.message,
                    e.location.map(|l| l.span.line).unwrap_or(0),
                )
            })
            .collect()
    };
    // AU_MOINS_UN
    let e = msgs(rules_errors(&[("C", 2)]));
    assert_eq!(e.len(), 1, "{e:?}");
    assert_eq!(e[0].0, "RULES/A");
    assert_eq!(
        e[0].1,
        "expected at least one of A, B, none given (rule AU_MOINS_UN(A, B))"
    );
    assert_eq!(e[0].2, 1);
    // AU_PLUS_UN
    let e = msgs(rules_errors(&[("B", 2), ("C", 3)]));
    assert_eq!(
        e,
        [(
            "RULES/C".to_string(),
            "expected at most one of B, C, got B and C (rule AU_PLUS_UN(B, C))".to_string(),
            3
        )]
    );
    // EXCLUS
    let e = msgs(rules_errors(&[("B", 2), ("D", 3), ("C", 4)]));
    assert!(
        e.contains(&(
            "RULES/D".to_string(),
            "expected at most one of C, D, got C and D (rule EXCLUS(C, D))".to_string(),
            3
        )),
        "{e:?}"
    );
    // PRESENT_PRESENT: A needs E and F.
    let e = msgs(rules_errors(&[("A", 2), ("E", 3)]));
    assert_eq!(
        e,
        [(
            "RULES/F".to_string(),
            "expected F since A is given (rule PRESENT_PRESENT(A, E, F))".to_string(),
            1
        )]
    );
    assert!(rules_errors(&[("A", 2), ("E", 3), ("F", 4)]).is_empty());
    // PRESENT_ABSENT: D excludes A and B (E/F only when A).
    let e = msgs(rules_errors(&[("D", 2), ("B", 3)]));
    assert_eq!(
        e,
        [(
            "RULES/B".to_string(),
            "B is not allowed together with D (rule PRESENT_ABSENT(D, A, B))".to_string(),
            3
        )]
    );
}

#[test]
fn co_type_and_required_reuse() {
    let op = parse("RULES.toml", RULES_CATALOG).expect("parses");
    let mut c = call(
        "RULES",
        vec![k("B", i(1), 2), k("OUT", Value::Co("TAB".into()), 3)],
    );
    assert!(validate_with(&op, &c, FILE).is_err(), "reuse is required");
    c.reuse = Some(ConceptRef {
        name: "T".into(),
        ty: "table_sdaster".into(),
    });
    let a = validate_with(&op, &c, FILE).expect("valid");
    assert_eq!(a.co("OUT"), Some("TAB"));
    c.args[1].value = s("TAB");
    let errs = validate_with(&op, &c, FILE).expect_err("CO refuses a text");
    assert_eq!(errs[0].message, "expected CO('NAME'), got a text 'TAB'");
    c.reuse = None;
    c.args[1].value = Value::Co("TAB".into());
    let errs = validate_with(&op, &c, FILE).expect_err("reuse missing");
    assert_eq!(errs[0].keyword.as_deref(), Some("RULES/reuse"));
    assert_eq!(errs[0].location.as_ref().map(|l| l.span), Some(call_span()));
    assert_eq!(
        errs[0].message,
        "RULES enriches an existing concept: expected reuse=<concept>"
    );
}

#[test]
fn reuse_not_allowed() {
    let mut c = call(
        "REST_MODE_NONL",
        vec![
            k("MODE_NON_LINE", co("MNL", "table_container"), 2),
            k("NUME_ORDRE", i(3), 3),
        ],
    );
    c.reuse = Some(ConceptRef {
        name: "MNL".into(),
        ty: "table_container".into(),
    });
    let e = single_error(&c, "REST_MODE_NONL/reuse", 1);
    assert_eq!(e.message, "REST_MODE_NONL does not accept reuse=");
}

#[test]
fn when_blocks() {
    let action = |kws: Vec<Keyword>| {
        call(
            "CALC_TABLE",
            vec![
                k("TABLE", co("MNL", "table_container"), 2),
                k("ACTION", f(kws), 3),
            ],
        )
    };
    // FILTRE block.
    let a = validate(
        &action(vec![
            k("OPERATION", s("FILTRE"), 4),
            k("NOM_PARA", s("NUME_ORDRE"), 5),
            k("VALE", i(80), 6),
        ]),
        FILE,
    )
    .expect("valid");
    let act = a.fact("ACTION").expect("ACTION");
    assert_eq!(act.value("NOM_PARA"), Some(&s("NUME_ORDRE")));
    assert_eq!(act.reals("VALE"), Some(vec![80.0]));
    assert_eq!(act.text("CRIT_COMP"), Some("EQ"));
    assert!(
        act.value("ORDRE").is_none(),
        "TRI keywords are not defaulted under FILTRE"
    );
    // TRI block: NOM_PARA is a list there, ORDRE defaulted.
    let a = validate(
        &action(vec![
            k("OPERATION", s("TRI"), 4),
            k("NOM_PARA", s("ENERGIE"), 5),
        ]),
        FILE,
    )
    .expect("valid");
    let act = a.fact("ACTION").expect("ACTION");
    assert_eq!(act.value("NOM_PARA"), Some(&seq(vec![s("ENERGIE")])));
    assert_eq!(act.text("ORDRE"), Some("CROISSANT"));
    assert!(act.value("CRIT_COMP").is_none());
    // A keyword of another block.
    let e = single_error(
        &action(vec![
            k("OPERATION", s("TRI"), 4),
            k("NOM_PARA", s("ENERGIE"), 5),
            k("CRIT_COMP", s("GT"), 6),
        ]),
        "CALC_TABLE/ACTION/CRIT_COMP",
        6,
    );
    assert_eq!(
        e.message,
        "keyword CRIT_COMP is only allowed when OPERATION is 'FILTRE'"
    );
    // Mandatory inside its block.
    let e = single_error(
        &action(vec![k("OPERATION", s("RENOMME"), 4)]),
        "CALC_TABLE/ACTION/NOM_PARA",
        3,
    );
    assert_eq!(
        e.message,
        "missing mandatory keyword NOM_PARA when OPERATION is 'RENOMME'"
    );
    // RENOMME takes exactly two names.
    let e = single_error(
        &action(vec![
            k("OPERATION", s("RENOMME"), 4),
            k("NOM_PARA", s("A"), 5),
        ]),
        "CALC_TABLE/ACTION/NOM_PARA",
        5,
    );
    assert_eq!(e.message, "expected 2 value(s) (a text), got 1");
    // A condition on a keyword being given: RECU_FONCTION.
    let e = single_error(
        &call(
            "RECU_FONCTION",
            vec![
                k("TABLE", co("MNL", "table_container"), 2),
                k("PARA_X", s("ENERGIE"), 3),
                k("NOM_CMP", s("DX"), 4),
                k("PARA_Y", s("FREQUENCE"), 5),
            ],
        ),
        "RECU_FONCTION/NOM_CMP",
        4,
    );
    assert_eq!(
        e.message,
        "keyword NOM_CMP is only allowed when RESU_GENE is given, or when RESULTAT is given"
    );
    // The solver branch follows METHODE, defaults included.
    let mut c = mnl(vec![k(
        "SOLVEUR",
        f(vec![k("METHODE", s("MULT_FRONT"), 31)]),
        30,
    )]);
    let a = validate(&c, FILE).expect("valid");
    assert_eq!(
        a.fact("SOLVEUR").and_then(|s| s.text("RENUM")),
        Some("METIS")
    );
    assert!(a
        .fact("SOLVEUR")
        .and_then(|s| s.value("PCENT_PIVOT"))
        .is_none());
    c.args.pop();
    c.args.push(k(
        "SOLVEUR",
        f(vec![k("METHODE", s("LDLT"), 31), k("RENUM", s("AMD"), 32)]),
        30,
    ));
    let e = single_error(&c, "MODE_NON_LINE/SOLVEUR/RENUM", 32);
    assert_eq!(e.message, "expected one of 'RCMK', 'SANS', got 'AMD'");
}

#[test]
fn none_duplicates_and_all_errors_collected() {
    // KEY=None is "not given".
    let a = validate(&mnl(vec![k("INFO", Value::None, 30)]), FILE).expect("valid");
    assert_eq!(a.int("INFO"), Some(1));
    // A keyword given twice.
    let c = mnl(vec![k("INFO", i(1), 30), k("INFO", i(2), 31)]);
    let e = single_error(&c, "MODE_NON_LINE/INFO", 31);
    assert_eq!(e.message, "keyword INFO is given twice");
    // Several problems at once: all reported.
    let mut c = mnl(vec![k("INFO", i(3), 30), k("BOGUS", i(1), 31)]);
    c.args.retain(|kw| kw.name != "MATR_MASS");
    let errs = errors(&c);
    let kws: Vec<&str> = errs.iter().filter_map(|e| e.keyword.as_deref()).collect();
    assert_eq!(kws.len(), 3, "{errs:#?}");
    for want in [
        "MODE_NON_LINE/INFO",
        "MODE_NON_LINE/BOGUS",
        "MODE_NON_LINE/MATR_MASS",
    ] {
        assert!(kws.contains(&want), "{want} not in {kws:?}");
    }
}

#[test]
fn result_types() {
    let extr = |t: &str| {
        call(
            "EXTR_TABLE",
            vec![
                k("TYPE_RESU", s(t), 2),
                k("TABLE", co("MNL", "table_container"), 3),
                k("NOM_PARA", s("CARA_CHOC"), 4),
                k(
                    "FILTRE",
                    f(vec![
                        k("NOM_PARA", s("NUME_ORDRE"), 6),
                        k("VALE_I", i(5), 7),
                    ]),
                    5,
                ),
            ],
        )
    };
    let ty = |c: &CommandCall| {
        let a = validate(c, FILE).expect("valid");
        result_type(&c.op, &a)
    };
    assert_eq!(ty(&extr("TABLE_SDASTER")).as_deref(), Some("table_sdaster"));
    assert_eq!(ty(&extr("R")).as_deref(), Some("R"));
    assert_eq!(ty(&extr("K")).as_deref(), Some("TXM"));
    let rest = |extra: Vec<Keyword>| {
        let mut v = vec![
            k("MODE_NON_LINE", co("MNL", "table_container"), 2),
            k("NUME_ORDRE", i(3), 3),
        ];
        v.extend(extra);
        call("REST_MODE_NONL", v)
    };
    assert_eq!(ty(&rest(vec![])).as_deref(), Some("dyna_trans"));
    assert_eq!(
        ty(&rest(vec![k("TYPE_RESU", s("MODE_MECA"), 4)])).as_deref(),
        Some("mode_meca")
    );
    assert_eq!(ty(&call("FIN", vec![])), None);
    assert_eq!(result_type("NOPE", &crate::args::Args::default()), None);
}

#[test]
fn real_file_keywords_accepted() {
    // DEBUT as Code_Aster's test cases write it.
    let c = call(
        "DEBUT",
        vec![
            k("CODE", f(vec![k("NIV_PUB_WEB", s("INTERNET"), 2)]), 2),
            k(
                "IGNORE_ALARM",
                seq(vec![s("SUPERVIS_1"), s("MODELISA4_9")]),
                3,
            ),
            k("ERREUR", f(vec![k("ERREUR_F", s("EXCEPTION"), 4)]), 4),
            k("PAR_LOT", s("NON"), 5),
            k("DEBUG", f(vec![k("SDVERI", s("OUI"), 6)]), 6),
        ],
    );
    let a = validate(&c, FILE).expect("valid");
    assert_eq!(
        a.texts("IGNORE_ALARM"),
        Some(vec!["SUPERVIS_1".to_string(), "MODELISA4_9".to_string()])
    );
    // Recent Code_Aster writes CODE='OUI' where older files have CODE=_F(...).
    let a = validate(&call("DEBUT", vec![k("CODE", s("OUI"), 2)]), FILE).expect("valid");
    assert_eq!(a.text("CODE"), Some("OUI"));
    assert!(a.has("CODE"));
    let e = single_error(
        &call("DEBUT", vec![k("CODE", s("NON"), 2)]),
        "DEBUT/CODE",
        2,
    );
    assert_eq!(
        e.message,
        "expected a factor keyword _F(...) or a text: expected one of 'OUI', got 'NON'"
    );
    let c = call(
        "FIN",
        vec![k("FORMAT_HDF", s("OUI"), 2), k("RETASSAGE", s("OUI"), 3)],
    );
    assert!(validate(&c, FILE).is_ok());
    let c = call("POURSUITE", vec![k("CODE", f(vec![]), 2)]);
    assert!(validate(&c, FILE).is_ok());
    // sdnd122's post-processing.
    let c = call(
        "RECU_FONCTION",
        vec![
            k("TABLE", co("MNL", "table_container"), 2),
            k("PARA_X", s("ENERGIE"), 3),
            k("PARA_Y", s("FREQUENCE"), 4),
            k("INTERPOL", seq(vec![s("LOG")]), 5),
        ],
    );
    let a = validate(&c, FILE).expect("valid");
    assert_eq!(a.texts("INTERPOL"), Some(vec!["LOG".to_string()]));
    assert_eq!(a.text("PROL_DROITE"), Some("EXCLU"));
    let c = call(
        "TEST_TABLE",
        vec![
            k("TABLE", co("T", "table_sdaster"), 2),
            k("NOM_PARA", s("FREQUENCE"), 3),
            k("VALE_CALC", r(0.6466), 4),
            k("REFERENCE", s("ANALYTIQUE"), 5),
            k("VALE_REFE", r(0.6465), 6),
            k("PRECISION", r(1e-3), 7),
            k(
                "FILTRE",
                f(vec![
                    k("NOM_PARA", s("NUME_ORDRE"), 9),
                    k("VALE_I", i(5), 10),
                ]),
                8,
            ),
        ],
    );
    let a = validate(&c, FILE).expect("valid");
    assert_eq!(a.reals("TOLE_MACHINE"), Some(vec![1e-6]));
    // VALE_REFE without REFERENCE is refused.
    let c = call(
        "TEST_TABLE",
        vec![
            k("TABLE", co("T", "table_sdaster"), 2),
            k("NOM_PARA", s("FREQUENCE"), 3),
            k("VALE_CALC", r(0.6466), 4),
            k("VALE_REFE", r(0.6465), 6),
        ],
    );
    let e = single_error(&c, "TEST_TABLE/VALE_REFE", 6);
    assert_eq!(
        e.message,
        "keyword VALE_REFE is only allowed when REFERENCE is given"
    );
    let c = call(
        "TEST_RESU",
        vec![k(
            "RESU",
            f(vec![
                k("RESULTAT", co("MODES", "mode_meca"), 3),
                k("NUME_ORDRE", i(1), 4),
                k("PARA", s("FREQ"), 5),
                k("VALE_CALC", r(0.503292), 6),
            ]),
            2,
        )],
    );
    assert!(validate(&c, FILE).is_ok());
    // A field value is read at one node: NOEUD or GROUP_NO.
    let field = |node: Vec<Keyword>| {
        let mut v = vec![
            k("RESULTAT", co("MODES", "mode_meca"), 3),
            k("NUME_ORDRE", i(1), 4),
            k("NOM_CHAM", s("DEPL"), 5),
            k("NOM_CMP", s("DX"), 6),
            k("VALE_CALC", r(1.0), 7),
        ];
        v.extend(node);
        call("TEST_RESU", vec![k("RESU", f(v), 2)])
    };
    let e = single_error(&field(vec![]), "TEST_RESU/RESU/NOEUD", 2);
    assert_eq!(
        e.message,
        "expected exactly one of NOEUD, GROUP_NO, none given (rule UN_PARMI(NOEUD, GROUP_NO) when NOM_CHAM is given)"
    );
    assert!(validate(&field(vec![k("NOEUD", s("N2"), 8)]), FILE).is_ok());
    assert!(validate(&field(vec![k("GROUP_NO", s("TIP"), 8)]), FILE).is_ok());
    let e = single_error(
        &field(vec![k("NOEUD", s("N2"), 8), k("GROUP_NO", s("TIP"), 9)]),
        "TEST_RESU/RESU/GROUP_NO",
        9,
    );
    assert_eq!(
        e.message,
        "expected exactly one of NOEUD, GROUP_NO, got NOEUD and GROUP_NO (rule UN_PARMI(NOEUD, GROUP_NO) when NOM_CHAM is given)"
    );
    let c = call(
        "CREA_TABLE",
        vec![k(
            "LISTE",
            seq(vec![
                f(vec![
                    k("PARA", s("X"), 3),
                    k("LISTE_R", seq(vec![r(1.0), r(2.0)]), 4),
                ]),
                f(vec![
                    k("PARA", s("N"), 5),
                    k("LISTE_K", seq(vec![s("A"), s("B")]), 6),
                ]),
            ]),
            2,
        )],
    );
    let a = validate(&c, FILE).expect("valid");
    assert_eq!(
        result_type("CREA_TABLE", &a).as_deref(),
        Some("table_sdaster")
    );
    assert_eq!(a.facts_or_empty("LISTE")[1].text("TYPE_K"), Some("K8"));
}

// ---------------------------------------------------------------- printer and docs

#[test]
fn describe_and_summary() {
    let d = describe("MODE_NON_LINE").expect("known operator");
    assert!(
        d.starts_with("MODE_NON_LINE -> table_container (reuse= allowed: the concept of ETAT_INIT/MODE_NON_LINE)"),
        "{d}"
    );
    for want in [
        "MATR_RIGI",
        "matr_asse_depl_r  [mandatory]",
        "ETAT_INIT = _F(...)  [mandatory]  occurrences: 1",
        "rule UN_PARMI(MODE_LINE, MODE_NON_LINE)",
        "PARA_REGUL",
        "default 0.005",
        "values: -1, 1",
        "ORIG_OBST              list of R (3)  [optional with default]  default (0.0, 0.0, 0.0)",
        "only when METHODE is 'MULT_FRONT'",
        "range: >= 0.0",
    ] {
        assert!(d.contains(want), "missing {want:?} in\n{d}");
    }
    let d = describe("REST_MODE_NONL").expect("known");
    assert!(
        d.contains("TYPE_RESU='DYNA_TRANS' -> dyna_trans; TYPE_RESU='MODE_MECA' -> mode_meca"),
        "{d}"
    );
    assert!(describe("NOPE").is_none());
    assert!(
        describe("MODE_NON_LINE")
            .unwrap_or_default()
            .lines()
            .all(|l| l.len() <= 100),
        "docs are wrapped"
    );
    // The one-line doc stops at the first sentence, not at an abbreviation.
    assert_eq!(
        print::first_line("Extracts a cell (e.g. a name). Then more."),
        "Extracts a cell (e.g. a name)."
    );
    let s = summary();
    assert_eq!(s.lines().count(), operator_names().len());
    assert!(s
        .lines()
        .any(|l| l.starts_with("MODE_NON_LINE ") && l.contains("Nonlinear normal modes")));
}

#[test]
fn markdown_reference_is_complete() {
    let md = markdown_reference();
    for op in operator_names() {
        assert!(md.contains(&format!("\n## {op}\n")), "{op} has no section");
    }
    assert!(md.contains("| `CHOC/PARA_REGUL` | R | optional with default | `0.005` |"));
    assert!(md.contains("| `ACTION/NOM_PARA` | list of TXM (2) | mandatory |"));
}

/// docs/commands.md must be what the catalogs generate. `UPDATE_DOCS=1 cargo test catalog`
/// rewrites it.
#[test]
fn docs_commands_md_is_up_to_date() {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("docs/commands.md");
    let want = markdown_reference();
    if std::env::var_os("UPDATE_DOCS").is_some() {
        std::fs::write(&path, &want).expect("write docs/commands.md");
        return;
    }
    let have = std::fs::read_to_string(&path).unwrap_or_default();
    assert!(
        have == want,
        "docs/commands.md is out of date with commands/*.toml: regenerate it with `UPDATE_DOCS=1 cargo test catalog`"
    );
}

// ---------------------------------------------------------------- robustness

mod fuzz {
    use super::*;
    use proptest::prelude::*;

    fn name() -> impl Strategy<Value = String> {
        let known: Vec<String> = crate::catalog::catalog()
            .ops
            .iter()
            .flat_map(|o| {
                o.simp
                    .iter()
                    .map(|s| s.name.clone())
                    .chain(o.fact.iter().flat_map(|f| {
                        std::iter::once(f.name.clone()).chain(f.simp.iter().map(|s| s.name.clone()))
                    }))
            })
            .collect();
        prop_oneof![
            3 => proptest::sample::select(known),
            1 => "[A-Z_]{1,8}",
        ]
    }

    fn value() -> impl Strategy<Value = Value> {
        let leaf = prop_oneof![
            Just(Value::None),
            any::<bool>().prop_map(Value::Bool),
            any::<i64>().prop_map(Value::Int),
            any::<f64>().prop_map(Value::Real),
            prop_oneof![
                Just("OUI".to_string()),
                Just("EQ".to_string()),
                Just("RI".to_string()),
                "[A-Z]{0,5}".prop_map(|s| s)
            ]
            .prop_map(Value::Str),
            (
                "[A-Z]{1,4}",
                proptest::sample::select(check::CONCEPT_TYPES.to_vec())
            )
                .prop_map(|(n, t)| Value::Concept(ConceptRef {
                    name: n,
                    ty: t.to_string()
                })),
            "[A-Z]{1,4}".prop_map(Value::Co),
        ];
        leaf.prop_recursive(3, 24, 4, |inner| {
            prop_oneof![
                proptest::collection::vec(inner.clone(), 0..4).prop_map(Value::Seq),
                proptest::collection::vec((name(), inner), 0..4).prop_map(|kws| {
                    Value::Fact(
                        kws.into_iter()
                            .enumerate()
                            .map(|(n, (nm, v))| k(&nm, v, n + 2))
                            .collect(),
                    )
                }),
            ]
        })
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(256))]
        #[test]
        fn validate_never_panics(
            op in proptest::sample::select(operator_names()),
            kws in proptest::collection::vec((name(), value()), 0..8),
            reuse in proptest::option::of(proptest::sample::select(check::CONCEPT_TYPES.to_vec())),
        ) {
            let mut c = call(op, kws.into_iter().enumerate().map(|(n, (nm, v))| k(&nm, v, n + 2)).collect());
            c.reuse = reuse.map(|t| ConceptRef { name: "R".into(), ty: t.to_string() });
            match validate(&c, FILE) {
                Ok(a) => {
                    prop_assert_eq!(a.path, op);
                    let _ = result_type(op, &validate(&c, FILE).unwrap_or_default());
                }
                Err(errs) => {
                    prop_assert!(!errs.is_empty());
                    for e in errs {
                        prop_assert!(e.location.is_some());
                        prop_assert!(e.keyword.as_deref().is_some_and(|k| k.starts_with(op)));
                    }
                }
            }
        }
    }
}

#[test]
fn a_co_keyword_declares_the_type_it_creates() {
    let op = |co_type: &str| {
        let text = format!(
            "name = \"MACRO\"\n[[simp]]\nname = \"OUT\"\ntype = \"CO\"\n{co_type}statut = \"o\"\n"
        );
        let def = super::parse("MACRO.toml", &text).expect("parses");
        let mut out = Vec::new();
        super::check::check_op(&def, &mut out);
        out
    };
    assert!(op("co_type = \"matr_asse_depl_r\"\n").is_empty());
    assert_eq!(
        op(""),
        vec!["MACRO/OUT: type \"CO\" needs co_type".to_string()]
    );
    assert_eq!(
        op("co_type = \"matr_asse_dpl_r\"\n"),
        vec!["MACRO/OUT: unknown type matr_asse_dpl_r".to_string()]
    );
    // check knows ASSEMBLAGE's outputs from the catalog, not from code.
    let asse = super::get("ASSEMBLAGE").expect("ASSEMBLAGE");
    let nume = asse.simp.iter().find(|s| s.name == "NUME_DDL").unwrap();
    assert_eq!(nume.co_type.as_deref(), Some("nume_ddl_sdaster"));
}

/// Bounds an operator used to check itself, now the catalog's only: an output unit of
/// IMPR_TABLE / IMPR_FONCTION is >= 1, ORDRE_GRANDEUR of the TEST_* operators >= 0 and
/// defaulted to 1.
#[test]
fn output_units_and_ordre_grandeur_are_bounded_in_the_catalog() {
    // (IMPR_FONCTION also misses its COURBE here: one error among others.)
    let impr_table = vec![k("TABLE", co("T", "table_sdaster"), 2), k("UNITE", i(0), 3)];
    for (op, args) in [
        ("IMPR_TABLE", impr_table),
        ("IMPR_FONCTION", vec![k("UNITE", i(0), 3)]),
    ] {
        let c = call(op, args);
        let unite = format!("{op}/UNITE");
        let errs = errors(&c);
        assert!(
            errs.iter()
                .any(|e| e.keyword.as_deref() == Some(unite.as_str())),
            "{op}: {errs:#?}"
        );
    }
    let test = |extra: Vec<Keyword>| {
        let mut args = vec![
            k("TABLE", co("T", "table_sdaster"), 2),
            k("NOM_PARA", s("FREQUENCE"), 3),
            k("VALE_CALC", r(0.0), 4),
        ];
        args.extend(extra);
        call("TEST_TABLE", args)
    };
    single_error(
        &test(vec![k("ORDRE_GRANDEUR", r(-1.0), 5)]),
        "TEST_TABLE/ORDRE_GRANDEUR",
        5,
    );
    let a = validate(&test(vec![]), FILE).expect("valid");
    assert_eq!(a.real("ORDRE_GRANDEUR"), Some(1.0));
}

/// Every INFO keyword says what 1 and 2 print, and an operator whose source never reads
/// its INFO level (`ctx.info`, `args.int("INFO")`) says it has no effect: the docs once
/// promised "verbosity" where both levels printed the same.
#[test]
fn info_keywords_say_what_each_level_prints() {
    let ops_dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("src/ops");
    let mut documented = 0;
    for op in operator_names() {
        let Some(info) = get(op).and_then(|d| d.simp.iter().find(|s| s.name == "INFO")) else {
            continue;
        };
        assert!(!info.doc.is_empty(), "{op}: INFO has no doc");
        // MODE_ITER_SIMULT is CALC_MODES with the older syntax.
        let file = if op == "MODE_ITER_SIMULT" {
            "CALC_MODES"
        } else {
            op
        };
        // An operator is one file, or one folder of files (ops/mode_non_line/).
        let stem = file.to_lowercase();
        let folder = ops_dir.join(&stem);
        let src = match std::fs::read_dir(&folder) {
            Ok(entries) => entries
                .filter_map(|e| std::fs::read_to_string(e.ok()?.path()).ok())
                .collect::<Vec<_>>()
                .join("\n"),
            Err(_) => {
                std::fs::read_to_string(ops_dir.join(format!("{stem}.rs"))).unwrap_or_default()
            }
        };
        let reads_info = src.contains("ctx.info") || src.contains("int(\"INFO\")");
        let no_effect = info.doc.starts_with("No effect");
        assert!(
            reads_info || no_effect,
            "{op}: its INFO doc promises output the operator never prints: {}",
            info.doc
        );
        assert!(
            !(reads_info && no_effect),
            "{op}: INFO changes what it prints, its doc says no effect"
        );
        documented += 1;
    }
    assert!(documented > 20, "only {documented} INFO keywords");
}
