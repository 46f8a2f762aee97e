//! Tests of the table and function operators, run through `lookup` on an in-memory store.

use crate::args::Args;
use crate::ops::common::harness::*;
use crate::store::table::{links, load_table};
use crate::value::Value;

/// TAB: NUME_ORDRE 1..3, FREQ 1.5 2.5 3.5, NOM 'a' 'b' 'c'.
fn crea(h: &mut Harness) {
    let a = args(
        "CREA_TABLE",
        vec![("TITRE", k("three modes"))],
        vec![(
            "LISTE",
            vec![
                fact(
                    "CREA_TABLE/LISTE",
                    vec![
                        ("PARA", k("NUME_ORDRE")),
                        ("LISTE_I", seq(vec![i(1), i(2), i(3)])),
                    ],
                ),
                fact(
                    "CREA_TABLE/LISTE",
                    vec![
                        ("PARA", k("FREQ")),
                        ("LISTE_R", seq(vec![r(1.5), r(2.5), r(3.5)])),
                    ],
                ),
                fact(
                    "CREA_TABLE/LISTE",
                    vec![
                        ("PARA", k("NOM")),
                        ("LISTE_K", seq(vec![k("a"), k("b"), k("c")])),
                    ],
                ),
            ],
        )],
    );
    h.run("CREA_TABLE", Some("TAB"), None, &a).unwrap();
}

fn filtre(para: &str, v: Value) -> Args {
    fact("FILTRE", vec![("NOM_PARA", k(para)), ("VALE_I", v)])
}

#[test]
fn crea_table_is_a_queryable_sql_table() {
    let mut h = Harness::new();
    crea(&mut h);
    let mut q = h
        .store
        .conn()
        .prepare("SELECT NUME_ORDRE, FREQ FROM TAB")
        .unwrap();
    let got: Vec<(i64, f64)> = q
        .query_map([], |row| Ok((row.get(0)?, row.get(1)?)))
        .unwrap()
        .collect::<rusqlite::Result<_>>()
        .unwrap();
    assert_eq!(got, vec![(1, 1.5), (2, 2.5), (3, 3.5)]);
    assert_eq!(load_table(&h.store, "TAB").unwrap().title, "three modes");
}

#[test]
fn test_table_ok_and_nook() {
    let mut h = Harness::new();
    crea(&mut h);
    let a = args(
        "TEST_TABLE",
        vec![
            ("TABLE", table("TAB")),
            ("NOM_PARA", k("FREQ")),
            ("VALE_CALC", r(2.5)),
            ("VALE_REFE", r(2.6)),
            ("REFERENCE", k("ANALYTIQUE")),
        ],
        vec![("FILTRE", vec![filtre("NUME_ORDRE", i(2))])],
    );
    h.run("TEST_TABLE", None, None, &a).unwrap();
    // Non-regression 2.5 vs 2.5: OK. Reference 2.6: |2.5-2.6|/2.6 = 3.85e-2 > 1e-3: NOOK.
    assert_eq!(
        h.tests.iter().map(|t| t.ok).collect::<Vec<_>>(),
        vec![true, false]
    );
    assert!(h.tests[1].line.contains("3.85E+00%"), "{}", h.tests[1].line);
    let out = h.output();
    assert!(out.contains("---- TABLE TAB  FREQ  NUME_ORDRE=2"), "{out}");
    assert!(out.contains(" NOOK ANALYTIQUE"), "{out}");

    // TYPE_TEST SOMM over the whole column: 1.5 + 2.5 + 3.5 = 7.5; MAX of NUME_ORDRE = 3.
    let a = args(
        "TEST_TABLE",
        vec![
            ("TABLE", table("TAB")),
            ("NOM_PARA", k("FREQ")),
            ("TYPE_TEST", k("SOMM")),
            ("VALE_CALC", r(7.5)),
        ],
        vec![],
    );
    h.run("TEST_TABLE", None, None, &a).unwrap();
    let a = args(
        "TEST_TABLE",
        vec![
            ("TABLE", table("TAB")),
            ("NOM_PARA", k("NUME_ORDRE")),
            ("TYPE_TEST", k("MAX")),
            ("VALE_CALC_I", i(3)),
        ],
        vec![],
    );
    h.run("TEST_TABLE", None, None, &a).unwrap();
    let a = args(
        "TEST_TABLE",
        vec![
            ("TABLE", table("TAB")),
            ("NOM_PARA", k("NOM")),
            ("VALE_CALC_K", k("c")),
        ],
        vec![(
            "FILTRE",
            vec![fact(
                "FILTRE",
                vec![("NOM_PARA", k("FREQ")), ("CRIT_COMP", k("MAXI"))],
            )],
        )],
    );
    h.run("TEST_TABLE", None, None, &a).unwrap();
    assert_eq!(h.tests.len(), 5);
    assert!(h.tests[2..].iter().all(|t| t.ok));

    // Without FILTRE, three rows remain: a clear error.
    let a = args(
        "TEST_TABLE",
        vec![
            ("TABLE", table("TAB")),
            ("NOM_PARA", k("FREQ")),
            ("VALE_CALC", r(2.5)),
        ],
        vec![],
    );
    let err = h.run("TEST_TABLE", None, None, &a).unwrap_err();
    assert!(err.message.contains("3 rows remain"), "{err}");
}

#[test]
fn impr_table_to_stdout_and_to_a_unit() {
    let mut h = Harness::new();
    crea(&mut h);
    let a = args(
        "IMPR_TABLE",
        vec![
            ("TABLE", table("TAB")),
            ("NOM_PARA", seq(vec![k("NUME_ORDRE"), k("FREQ")])),
        ],
        vec![(
            "TRI",
            vec![fact(
                "TRI",
                vec![("NOM_PARA", k("FREQ")), ("ORDRE", k("DECROISSANT"))],
            )],
        )],
    );
    h.run("IMPR_TABLE", None, None, &a).unwrap();
    let expected = concat!(
        "#\n#--------------------------------------------------------------------------------\n#\n",
        "#three modes\n",
        "NUME_ORDRE   FREQ\n",
        "           3  3.50000E+00\n",
        "           2  2.50000E+00\n",
        "           1  1.50000E+00\n",
        "\n",
    );
    assert_eq!(h.output(), expected);

    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("tab.csv");
    h.units.map.insert(29, path.clone());
    let a = args(
        "IMPR_TABLE",
        vec![
            ("TABLE", table("TAB")),
            ("UNITE", i(29)),
            ("FORMAT", k("CSV")),
            ("SEPARATEUR", k(";")),
        ],
        vec![(
            "FILTRE",
            vec![fact(
                "FILTRE",
                vec![
                    ("NOM_PARA", k("FREQ")),
                    ("CRIT_COMP", k("GT")),
                    ("VALE", r(2.0)),
                ],
            )],
        )],
    );
    h.run("IMPR_TABLE", None, None, &a).unwrap();
    let text = std::fs::read_to_string(&path).unwrap();
    assert_eq!(
        text,
        "NUME_ORDRE;FREQ;NOM\n2;2.50000E+00;b\n3;3.50000E+00;c\n"
    );
    // Without SEPARATEUR a CSV is comma-separated (the catalog's default for CSV; it was
    // TABLEAU's space), while TABLEAU keeps Code_Aster's space.
    let path = dir.path().join("tab2.csv");
    h.units.map.insert(30, path.clone());
    let a = args(
        "IMPR_TABLE",
        vec![
            ("TABLE", table("TAB")),
            ("UNITE", i(30)),
            ("FORMAT", k("CSV")),
        ],
        vec![],
    );
    h.run("IMPR_TABLE", None, None, &a).unwrap();
    let text = std::fs::read_to_string(&path).unwrap();
    assert!(
        text.starts_with("NUME_ORDRE,FREQ,NOM\n") && text.contains("\n2,2.50000E+00,b\n"),
        "{text}"
    );
}

/// FORMAT='ASTER' is the TABLEAU block between Code_Aster's markers with a line of types;
/// TABLEAU_CROISE turns three parameters into a cross table; XMGRACE writes two columns as
/// a Grace file; a format aster-nl does not write (NUMPY) is an alarm that loses nothing,
/// not a stop of the study.
#[test]
fn impr_table_aster_cross_grace_and_unwritten_formats() {
    let mut h = Harness::new();
    crea(&mut h);
    let print = |h: &mut Harness, format: &str, names: &[&str]| {
        let mut simple = vec![("TABLE", table("TAB")), ("FORMAT", k(format))];
        if !names.is_empty() {
            simple.push(("NOM_PARA", seq(names.iter().map(|n| k(n)).collect())));
        }
        let before = h.output().len();
        h.run(
            "IMPR_TABLE",
            None,
            None,
            &args("IMPR_TABLE", simple, vec![]),
        )
        .unwrap();
        h.output()[before..].to_string()
    };
    let expected = concat!(
        "#\n#--------------------------------------------------------------------------------\n#\n",
        "#DEBUT_TABLE\n",
        "#TITRE three modes\n",
        " NUME_ORDRE   FREQ         NOM\n",
        " I            R            K8\n",
        "            1  1.50000E+00 a\n",
        "            2  2.50000E+00 b\n",
        "            3  3.50000E+00 c\n",
        "#FIN_TABLE\n",
        "\n",
    );
    assert_eq!(print(&mut h, "ASTER", &[]), expected);

    // NOM as a function of FREQ (rows) and NUME_ORDRE (columns): the diagonal is filled.
    let crossed = print(&mut h, "TABLEAU_CROISE", &[]);
    let lines: Vec<&str> = crossed.lines().collect();
    assert_eq!(lines[3], "#three modes");
    assert_eq!(lines[4], "#NOM FONCTION DE FREQ ET NUME_ORDRE");
    assert_eq!(lines[5], "FREQ/NUME_ORDRE 1 2 3");
    assert_eq!(lines[6], "    1.50000E+00 a - -");
    assert_eq!(lines[7], "    2.50000E+00 - b -");
    assert_eq!(lines[8], "    3.50000E+00 - - c");
    // Two parameters cannot be crossed: an alarm, nothing printed.
    let out = print(&mut h, "TABLEAU_CROISE", &["NUME_ORDRE", "FREQ"]);
    assert!(out.contains("TABLE0_36") && !out.contains("#---"), "{out}");

    let grace = print(&mut h, "XMGRACE", &["NUME_ORDRE", "FREQ"]);
    assert!(grace.contains("@xaxis label \"NUME_ORDRE\""), "{grace}");
    assert!(
        grace.ends_with("@type xy\n@s0 legend \"FREQ\"\n 1.00000E+00  1.50000E+00\n 2.00000E+00  2.50000E+00\n 3.00000E+00  3.50000E+00\n&\n"),
        "{grace}"
    );
    let out = print(&mut h, "XMGRACE", &[]);
    assert!(out.contains("TABLE0_21"), "{out}");
    let err = h
        .run(
            "IMPR_TABLE",
            None,
            None,
            &args(
                "IMPR_TABLE",
                vec![
                    ("TABLE", table("TAB")),
                    ("FORMAT", k("XMGRACE")),
                    ("NOM_PARA", seq(vec![k("FREQ"), k("NOM")])),
                ],
                vec![],
            ),
        )
        .unwrap_err();
    assert!(err.message.contains("column NOM holds texts"), "{err}");

    let out = print(&mut h, "NUMPY", &[]);
    assert!(
        out.contains("IMPR_TABLE_1") && out.contains("FORMAT='NUMPY' is not written"),
        "{out}"
    );
}

#[test]
fn calc_table_applies_actions_in_order() {
    let mut h = Harness::new();
    crea(&mut h);
    let act = |simple: Vec<(&str, Value)>| fact("CALC_TABLE/ACTION", simple);
    let a = args(
        "CALC_TABLE",
        vec![("TABLE", table("TAB"))],
        vec![(
            "ACTION",
            vec![
                act(vec![
                    ("OPERATION", k("FILTRE")),
                    ("NOM_PARA", k("NUME_ORDRE")),
                    ("CRIT_COMP", k("GE")),
                    ("VALE_I", i(2)),
                ]),
                act(vec![
                    ("OPERATION", k("TRI")),
                    ("NOM_PARA", k("FREQ")),
                    ("ORDRE", k("DECROISSANT")),
                ]),
                act(vec![
                    ("OPERATION", k("EXTR")),
                    ("NOM_PARA", seq(vec![k("NOM"), k("FREQ")])),
                ]),
                act(vec![
                    ("OPERATION", k("RENOMME")),
                    ("NOM_PARA", seq(vec![k("FREQ"), k("FREQ_HZ")])),
                ]),
            ],
        )],
    );
    h.run("CALC_TABLE", Some("T2"), None, &a).unwrap();
    let t = load_table(&h.store, "T2").unwrap();
    assert_eq!(t.names(), vec!["NOM", "FREQ_HZ"]);
    use crate::table::Cell;
    assert_eq!(
        t.rows,
        vec![
            vec![Cell::K("c".into()), Cell::R(3.5)],
            vec![Cell::K("b".into()), Cell::R(2.5)]
        ]
    );
    // reuse: TAB enriched in place.
    let a = args(
        "CALC_TABLE",
        vec![("TABLE", table("TAB"))],
        vec![(
            "ACTION",
            vec![act(vec![
                ("OPERATION", k("FILTRE")),
                ("NOM_PARA", k("NOM")),
                ("VALE_K", k("a")),
            ])],
        )],
    );
    h.run("CALC_TABLE", Some("TAB"), Some("TAB"), &a).unwrap();
    assert_eq!(load_table(&h.store, "TAB").unwrap().nrows(), 1);
}

#[test]
fn extr_table_sub_table_and_values() {
    let mut h = Harness::new();
    crea(&mut h);
    // A container whose rows name per-row objects: row 1 names TAB.
    let a = args(
        "CREA_TABLE",
        vec![],
        vec![(
            "LISTE",
            vec![
                fact(
                    "CREA_TABLE/LISTE",
                    vec![
                        ("PARA", k("NUME_ORDRE")),
                        ("LISTE_I", seq(vec![i(1), i(2)])),
                    ],
                ),
                fact(
                    "CREA_TABLE/LISTE",
                    vec![
                        ("PARA", k("NOM_SD")),
                        ("LISTE_K", seq(vec![k("TAB"), k("NOPE")])),
                    ],
                ),
            ],
        )],
    );
    h.run("CREA_TABLE", Some("CONT"), None, &a).unwrap();
    assert_eq!(links(&h.store, "CONT").unwrap().len(), 1);
    let a = args(
        "EXTR_TABLE",
        vec![
            ("TABLE", table("CONT")),
            ("TYPE_RESU", k("TABLE_SDASTER")),
            ("NOM_PARA", k("NOM_SD")),
        ],
        vec![("FILTRE", vec![filtre("NUME_ORDRE", i(1))])],
    );
    h.run("EXTR_TABLE", Some("SUB"), None, &a).unwrap();
    assert_eq!(
        load_table(&h.store, "SUB").unwrap(),
        load_table(&h.store, "TAB").unwrap()
    );

    let a = args(
        "EXTR_TABLE",
        vec![
            ("TABLE", table("TAB")),
            ("TYPE_RESU", k("R")),
            ("NOM_PARA", k("FREQ")),
        ],
        vec![("FILTRE", vec![filtre("NUME_ORDRE", i(3))])],
    );
    assert_eq!(
        h.run("EXTR_TABLE", Some("x"), None, &a).unwrap(),
        Some(Value::Real(3.5))
    );
    let a = args(
        "EXTR_TABLE",
        vec![
            ("TABLE", table("TAB")),
            ("TYPE_RESU", k("K")),
            ("NOM_PARA", k("NOM")),
        ],
        vec![("FILTRE", vec![filtre("NUME_ORDRE", i(3))])],
    );
    assert_eq!(
        h.run("EXTR_TABLE", Some("x"), None, &a).unwrap(),
        Some(Value::Str("c".into()))
    );
    let a = args(
        "EXTR_TABLE",
        vec![
            ("TABLE", table("TAB")),
            ("TYPE_RESU", k("I")),
            ("NOM_PARA", k("NUME_ORDRE")),
        ],
        vec![("FILTRE", vec![filtre("NUME_ORDRE", i(2))])],
    );
    assert_eq!(
        h.run("EXTR_TABLE", Some("x"), None, &a).unwrap(),
        Some(Value::Int(2))
    );
    // Two rows left: refused.
    let a = args(
        "EXTR_TABLE",
        vec![
            ("TABLE", table("TAB")),
            ("TYPE_RESU", k("R")),
            ("NOM_PARA", k("FREQ")),
        ],
        vec![(
            "FILTRE",
            vec![fact(
                "FILTRE",
                vec![
                    ("NOM_PARA", k("FREQ")),
                    ("CRIT_COMP", k("GT")),
                    ("VALE", r(2.0)),
                ],
            )],
        )],
    );
    let err = h.run("EXTR_TABLE", Some("x"), None, &a).unwrap_err();
    assert!(err.message.contains("2 rows remain"), "{err}");
    // A cell naming no concept.
    let a = args(
        "EXTR_TABLE",
        vec![
            ("TABLE", table("CONT")),
            ("TYPE_RESU", k("TABLE_SDASTER")),
            ("NOM_PARA", k("NOM_SD")),
        ],
        vec![("FILTRE", vec![filtre("NUME_ORDRE", i(2))])],
    );
    assert!(h
        .run("EXTR_TABLE", Some("S2"), None, &a)
        .unwrap_err()
        .message
        .contains("NOPE"));
    assert!(h.store.concept_type("S2").unwrap().is_none());
}

/// H: INST 0 2 1, DEPL 0 8 2 (unsorted on purpose).
fn history(h: &mut Harness) {
    let a = args(
        "CREA_TABLE",
        vec![],
        vec![(
            "LISTE",
            vec![
                fact(
                    "CREA_TABLE/LISTE",
                    vec![
                        ("PARA", k("INST")),
                        ("LISTE_R", seq(vec![r(0.0), r(2.0), r(1.0)])),
                    ],
                ),
                fact(
                    "CREA_TABLE/LISTE",
                    vec![
                        ("PARA", k("DEPL")),
                        ("LISTE_R", seq(vec![r(0.0), r(8.0), r(2.0)])),
                    ],
                ),
            ],
        )],
    );
    h.run("CREA_TABLE", Some("H"), None, &a).unwrap();
}

#[test]
fn recu_fonction_then_test_fonction() {
    let mut h = Harness::new();
    history(&mut h);
    let recu = args(
        "RECU_FONCTION",
        vec![
            ("TABLE", table("H")),
            ("PARA_X", k("INST")),
            ("PARA_Y", k("DEPL")),
        ],
        vec![],
    );
    // INST 0, 2, 1 is not increasing: sorted, with Code_Aster's alarm.
    h.run("RECU_FONCTION", Some("F"), None, &recu).unwrap();
    assert!(h.output().contains("FONCT0_62"), "{}", h.output());
    let tri = args(
        "CALC_TABLE",
        vec![("TABLE", table("H"))],
        vec![(
            "ACTION",
            vec![fact(
                "ACTION",
                vec![("OPERATION", k("TRI")), ("NOM_PARA", k("INST"))],
            )],
        )],
    );
    h.run("CALC_TABLE", Some("H"), Some("H"), &tri).unwrap();
    h.run("RECU_FONCTION", Some("F"), None, &recu).unwrap();
    // Linear between (1, 2) and (2, 8): at 1.5, 5.
    let a = args(
        "TEST_FONCTION",
        vec![],
        vec![(
            "VALEUR",
            vec![fact(
                "TEST_FONCTION/VALEUR",
                vec![
                    (
                        "FONCTION",
                        crate::ops::common::harness::concept("F", "fonction_sdaster"),
                    ),
                    ("VALE_PARA", r(1.5)),
                    ("VALE_CALC", r(5.0)),
                    ("VALE_REFE", r(5.0)),
                    ("REFERENCE", k("ANALYTIQUE")),
                ],
            )],
        )],
    );
    h.run("TEST_FONCTION", None, None, &a).unwrap();
    assert_eq!(h.tests.len(), 2);
    assert!(h.tests.iter().all(|t| t.ok), "{:?}", h.tests);
    assert!(h.output().contains("---- FONCTION F  INST=1.5"));
    // NOM_PARA must be the function's parameter.
    let bad = args(
        "TEST_FONCTION",
        vec![],
        vec![(
            "VALEUR",
            vec![fact(
                "TEST_FONCTION/VALEUR",
                vec![
                    (
                        "FONCTION",
                        crate::ops::common::harness::concept("F", "fonction_sdaster"),
                    ),
                    ("NOM_PARA", k("FREQ")),
                    ("VALE_PARA", r(1.5)),
                    ("VALE_CALC", r(5.0)),
                ],
            )],
        )],
    );
    let err = h.run("TEST_FONCTION", None, None, &bad).unwrap_err();
    assert!(
        err.message.contains("function of INST, not of FREQ"),
        "{err}"
    );
}

/// INTERPOL: one value applies to both axes, two are (abscissa, ordinate), none is the
/// catalog's default (LIN, LIN); PROL_* default to EXCLU; an unknown value is refused.
#[test]
fn defi_fonction_interpol_and_prolongation_defaults() {
    use crate::function::{Interp, Prol};
    use crate::store::function::load_function;
    let mut h = Harness::new();
    let cases = [
        ("F1", Some(seq(vec![k("LOG")])), (Interp::Log, Interp::Log)),
        ("F2", None, (Interp::Lin, Interp::Lin)),
        (
            "F3",
            Some(seq(vec![k("LIN"), k("LOG")])),
            (Interp::Lin, Interp::Log),
        ),
    ];
    for (name, interpol, want) in cases {
        let mut simple = vec![
            ("NOM_PARA", k("FREQ")),
            ("VALE", seq(vec![r(1.0), r(1.0), r(2.0), r(4.0)])),
        ];
        simple.extend(interpol.map(|v| ("INTERPOL", v)));
        h.run(
            "DEFI_FONCTION",
            Some(name),
            None,
            &args("DEFI_FONCTION", simple, vec![]),
        )
        .unwrap();
        let f = load_function(&h.store, name).unwrap();
        assert_eq!(f.interpol, want, "{name}");
        assert_eq!((f.prol_gauche, f.prol_droite), (Prol::Exclu, Prol::Exclu));
    }
    let bad = args(
        "DEFI_FONCTION",
        vec![
            ("NOM_PARA", k("FREQ")),
            ("VALE", seq(vec![r(1.0), r(1.0), r(2.0), r(4.0)])),
            ("INTERPOL", k("CUBIC")),
        ],
        vec![],
    );
    assert!(h.run("DEFI_FONCTION", Some("F4"), None, &bad).is_err());
}

#[test]
fn defi_fonction_log_and_impr() {
    let mut h = Harness::new();
    // y = x² at 1, 2, 4 with LOG/LOG: exact for the power law, so F(3) = 9 to rounding
    // (1e-12 relative, the f64 rounding of ln/exp), checked with ABSOLU 1e-10.
    let a = args(
        "DEFI_FONCTION",
        vec![
            ("NOM_PARA", k("FREQ")),
            (
                "VALE",
                seq(vec![r(1.0), r(1.0), r(2.0), r(4.0), r(4.0), r(16.0)]),
            ),
            ("INTERPOL", seq(vec![k("LOG")])),
            ("PROL_DROITE", k("LINEAIRE")),
        ],
        vec![],
    );
    h.run("DEFI_FONCTION", Some("F"), None, &a).unwrap();
    let f = crate::ops::common::harness::concept("F", "fonction_sdaster");
    let val = |x: f64, y: f64| {
        fact(
            "TEST_FONCTION/VALEUR",
            vec![
                ("FONCTION", f.clone()),
                ("VALE_PARA", r(x)),
                ("VALE_REFE", r(y)),
                ("REFERENCE", k("ANALYTIQUE")),
                ("CRITERE", k("ABSOLU")),
                ("PRECISION", r(1e-10)),
            ],
        )
    };
    // 3 → 9 inside; 8 → 64 by LINEAIRE prolongation of the power law; 3 → 9.5 must fail.
    let t = args(
        "TEST_FONCTION",
        vec![],
        vec![("VALEUR", vec![val(3.0, 9.0), val(8.0, 64.0), val(3.0, 9.5)])],
    );
    h.run("TEST_FONCTION", None, None, &t).unwrap();
    assert_eq!(
        h.tests.iter().map(|t| t.ok).collect::<Vec<_>>(),
        vec![true, true, false]
    );
    // Left of the range with EXCLU: an error naming the function and its range.
    let t = args(
        "TEST_FONCTION",
        vec![],
        vec![("VALEUR", vec![val(0.5, 0.25)])],
    );
    let err = h.run("TEST_FONCTION", None, None, &t).unwrap_err();
    assert!(
        err.message.contains("function F") && err.message.contains("[1, 4]"),
        "{err}"
    );

    h.out.clear();
    let p = args(
        "IMPR_FONCTION",
        vec![],
        vec![(
            "COURBE",
            vec![fact("IMPR_FONCTION/COURBE", vec![("FONCTION", f.clone())])],
        )],
    );
    h.run("IMPR_FONCTION", None, None, &p).unwrap();
    let expected = concat!(
        "#\n#--------------------------------------------------------------------------------\n#\n",
        "#FONCTION F\n",
        "FREQ         TOUTRESU\n",
        " 1.00000E+00  1.00000E+00\n",
        " 2.00000E+00  4.00000E+00\n",
        " 4.00000E+00  1.60000E+01\n",
        "\n",
    );
    assert_eq!(h.output(), expected);

    let bad = args(
        "DEFI_FONCTION",
        vec![
            ("NOM_PARA", k("X")),
            ("VALE", seq(vec![r(1.0), r(2.0), r(3.0)])),
        ],
        vec![],
    );
    assert!(h
        .run("DEFI_FONCTION", Some("G"), None, &bad)
        .unwrap_err()
        .message
        .contains("pairs"));
    let bad = args(
        "DEFI_FONCTION",
        vec![
            ("NOM_PARA", k("X")),
            ("VALE", seq(vec![r(1.0), r(2.0), r(0.0), r(3.0)])),
        ],
        vec![],
    );
    assert!(h
        .run("DEFI_FONCTION", Some("G"), None, &bad)
        .unwrap_err()
        .message
        .contains("strictly increasing"));
    assert!(h.store.concept_type("G").unwrap().is_none());
    // VERIF='NON' sorts the points: (0, 3), (1, 2) → G(0.5) = 2.5.
    let ok = args(
        "DEFI_FONCTION",
        vec![
            ("NOM_PARA", k("X")),
            ("VALE_PARA", seq(vec![r(1.0), r(0.0)])),
            ("VALE_FONC", seq(vec![r(2.0), r(3.0)])),
            ("VERIF", k("NON")),
        ],
        vec![],
    );
    h.run("DEFI_FONCTION", Some("G"), None, &ok).unwrap();
    let g = crate::store::function::load_function(&h.store, "G").unwrap();
    assert_eq!((g.x.clone(), g.y.clone()), (vec![0.0, 1.0], vec![3.0, 2.0]));
    assert_eq!(g.eval(0.5).unwrap(), 2.5);
}

#[test]
fn detruire_drops_the_sql_table() {
    let mut h = Harness::new();
    crea(&mut h);
    let count = |h: &Harness| -> i64 {
        h.store
            .conn()
            .query_row(
                "SELECT count(*) FROM sqlite_master WHERE name = 'TAB'",
                [],
                |r| r.get(0),
            )
            .unwrap()
    };
    assert_eq!(count(&h), 1);
    let a = args(
        "DETRUIRE",
        vec![],
        vec![(
            "CONCEPT",
            vec![fact(
                "DETRUIRE/CONCEPT",
                vec![("NOM", seq(vec![table("TAB")]))],
            )],
        )],
    );
    h.run("DETRUIRE", None, None, &a).unwrap();
    assert_eq!(count(&h), 0);
    assert!(h.store.concept_type("TAB").unwrap().is_none());
    assert!(h.run("DETRUIRE", None, None, &a).is_err());
}

/// The newer syntax, DETRUIRE(NOM=...), removes the concept as CONCEPT=_F(NOM=...) does.
#[test]
fn detruire_by_the_top_level_nom() {
    let mut h = Harness::new();
    crea(&mut h);
    let a = args("DETRUIRE", vec![("NOM", seq(vec![table("TAB")]))], vec![]);
    h.run("DETRUIRE", None, None, &a).unwrap();
    assert!(h.store.concept_type("TAB").unwrap().is_none());
    let err = h.run("DETRUIRE", None, None, &a).unwrap_err();
    assert!(err.message.contains("TAB is not a concept"), "{err:?}");
}

#[test]
fn a_table_named_like_an_internal_table_is_refused_and_rolled_back() {
    let mut h = Harness::new();
    let a = args(
        "CREA_TABLE",
        vec![],
        vec![(
            "LISTE",
            vec![fact(
                "CREA_TABLE/LISTE",
                vec![("PARA", k("A")), ("LISTE_I", seq(vec![i(1)]))],
            )],
        )],
    );
    let err = h.run("CREA_TABLE", Some("CONCEPTS"), None, &a).unwrap_err();
    assert!(err.message.contains("cannot be named CONCEPTS"), "{err}");
    assert!(h.store.concepts().unwrap().is_empty());
}

#[test]
fn recu_fonction_skips_rows_empty_in_both_parameters() {
    let mut h = Harness::new();
    let liste = |para: &str, key: &str, v: Value| {
        fact("CREA_TABLE/LISTE", vec![("PARA", k(para)), (key, v)])
    };
    // Row 3 has only a TAG: skipped. Row 3 of T2 has INST but no DEPL: refused.
    let a = args(
        "CREA_TABLE",
        vec![],
        vec![(
            "LISTE",
            vec![
                liste("INST", "LISTE_R", seq(vec![r(0.0), r(1.0)])),
                liste("DEPL", "LISTE_R", seq(vec![r(0.0), r(3.0)])),
                liste("TAG", "LISTE_K", seq(vec![k("a"), k("b"), k("c")])),
            ],
        )],
    );
    h.run("CREA_TABLE", Some("T1"), None, &a).unwrap();
    let recu = |t: &str| {
        args(
            "RECU_FONCTION",
            vec![
                ("TABLE", table(t)),
                ("PARA_X", k("INST")),
                ("PARA_Y", k("DEPL")),
            ],
            vec![],
        )
    };
    h.run("RECU_FONCTION", Some("F"), None, &recu("T1"))
        .unwrap();
    let f = crate::store::function::load_function(&h.store, "F").unwrap();
    assert_eq!((f.x, f.y), (vec![0.0, 1.0], vec![0.0, 3.0]));

    let a = args(
        "CREA_TABLE",
        vec![],
        vec![(
            "LISTE",
            vec![
                liste("INST", "LISTE_R", seq(vec![r(0.0), r(1.0), r(2.0)])),
                liste("DEPL", "LISTE_R", seq(vec![r(0.0), r(3.0)])),
            ],
        )],
    );
    h.run("CREA_TABLE", Some("T2"), None, &a).unwrap();
    let err = h
        .run("RECU_FONCTION", Some("G"), None, &recu("T2"))
        .unwrap_err();
    assert!(err.message.contains("row 3 has no value of DEPL"), "{err}");
    assert!(err.hint.unwrap().contains("NON_VIDE"));
}
