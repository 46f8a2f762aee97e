//! The model operators end to end on the sdnd122 system (one mass m = 1 on a spring
//! k = 10 along X): AFFE_CHAR_CINE + ASSEMBLAGE and AFFE_CHAR_MECA + CALC_MATR_ELEM +
//! NUME_DDL + ASSE_MATRICE must give the same reduced matrices [[10]] and [[1]].
use crate::args::Args;
use crate::error::Result;
use crate::mesh::{Cell, CellKind, Mesh, Node};
use crate::model::tests::{fact, r, reals, s, seq, with_facts};
use crate::ops::{lookup, OpContext, Units};
use crate::store::matrix::load_matrix;
use crate::store::Store;
use crate::value::{ConceptRef, Value};

fn c(name: &str, ty: &str) -> Value {
    Value::Concept(ConceptRef {
        name: name.into(),
        ty: ty.into(),
    })
}

fn run(
    store: &Store,
    op: &str,
    result: Option<&str>,
    args: &Args,
) -> Result<(Vec<(String, String)>, String)> {
    let units = Units::default();
    let mut out: Vec<u8> = Vec::new();
    let mut tests = Vec::new();
    let f = lookup(op).expect("operator registered");
    let args = &crate::ops::common::harness::validated(op, args, None)?;
    let created = {
        let mut ctx = OpContext::new(store, op, &mut out, &units, &mut tests);
        ctx.result = result;
        ctx.file = "t.comm";
        ctx.line = 1;
        crate::ops::run_in_transaction(f, &mut ctx, args)?;
        ctx.created
    };
    Ok((created, String::from_utf8(out).unwrap()))
}

fn setup() -> Store {
    let store = Store::in_memory().unwrap();
    let mesh = Mesh {
        dim: 3,
        nodes: vec![
            Node {
                name: "N1".into(),
                coords: [0.0; 3],
            },
            Node {
                name: "N2".into(),
                coords: [1.0, 0.0, 0.0],
            },
        ],
        cells: vec![
            Cell {
                name: "M1".into(),
                kind: CellKind::Seg2,
                nodes: vec![0, 1],
            },
            Cell {
                name: "P2".into(),
                kind: CellKind::Poi1,
                nodes: vec![1],
            },
        ],
        node_groups: vec![],
        cell_groups: vec![],
    };
    store
        .register_concept("MA", "maillage_sdaster", "LIRE_MAILLAGE", "t.comm", 1)
        .unwrap();
    crate::store::mesh::save_mesh(&store, "MA", &mesh).unwrap();
    let mo = with_facts(
        fact(
            "AFFE_MODELE",
            vec![("MAILLAGE", c("MA", "maillage_sdaster"))],
        ),
        "AFFE",
        vec![fact(
            "AFFE_MODELE/AFFE",
            vec![
                ("MAILLE", seq(vec![s("M1"), s("P2")])),
                ("PHENOMENE", s("MECANIQUE")),
                ("MODELISATION", s("DIS_T")),
            ],
        )],
    );
    run(&store, "AFFE_MODELE", Some("MO"), &mo).unwrap();
    let d = |m: &str, cara: &str, v: &[f64]| {
        fact(
            "AFFE_CARA_ELEM/DISCRET",
            vec![
                ("MAILLE", s(m)),
                ("CARA", s(cara)),
                ("VALE", reals(v)),
                ("REPERE", s("GLOBAL")),
            ],
        )
    };
    let ca = with_facts(
        fact(
            "AFFE_CARA_ELEM",
            vec![("MODELE", c("MO", "modele_sdaster"))],
        ),
        "DISCRET",
        vec![
            d("M1", "K_T_D_L", &[10.0, 0.0, 0.0]),
            d("P2", "K_T_D_N", &[0.0, 0.0, 0.0]),
            d("P2", "M_T_D_N", &[1.0]),
        ],
    );
    run(&store, "AFFE_CARA_ELEM", Some("CARA"), &ca).unwrap();
    store
}

fn bcs(op: &str, key: &str, dx2: f64) -> Args {
    with_facts(
        fact(op, vec![("MODELE", c("MO", "modele_sdaster"))]),
        key,
        vec![
            fact(
                key,
                vec![
                    ("NOEUD", s("N1")),
                    ("DX", r(0.0)),
                    ("DY", r(0.0)),
                    ("DZ", r(0.0)),
                ],
            ),
            fact(
                key,
                vec![("NOEUD", s("N2")), ("DY", r(0.0)), ("DZ", r(dx2))],
            ),
        ],
    )
}

#[test]
fn cine_and_meca_paths_give_the_same_matrices() {
    let store = setup();
    run(
        &store,
        "AFFE_CHAR_CINE",
        Some("CINE"),
        &bcs("AFFE_CHAR_CINE", "MECA_IMPO", 0.0),
    )
    .unwrap();
    let mut asse = fact(
        "ASSEMBLAGE",
        vec![
            ("MODELE", c("MO", "modele_sdaster")),
            ("CARA_ELEM", c("CARA", "cara_elem")),
            ("CHAR_CINE", c("CINE", "char_cine_meca")),
            ("NUME_DDL", Value::Co("NUME".into())),
        ],
    );
    asse = with_facts(
        asse,
        "MATR_ASSE",
        vec![
            fact(
                "ASSEMBLAGE/MATR_ASSE",
                vec![
                    ("MATRICE", Value::Co("RIGI".into())),
                    ("OPTION", s("RIGI_MECA")),
                ],
            ),
            fact(
                "ASSEMBLAGE/MATR_ASSE",
                vec![
                    ("MATRICE", Value::Co("MASS".into())),
                    ("OPTION", s("MASS_MECA")),
                ],
            ),
        ],
    );
    let (created, _) = run(&store, "ASSEMBLAGE", None, &asse).unwrap();
    let names: Vec<&str> = created.iter().map(|(n, _)| n.as_str()).collect();
    assert_eq!(names, ["NUME", "RIGI", "MASS"]);
    assert_eq!(
        store.concept_type("RIGI").unwrap().as_deref(),
        Some("matr_asse_depl_r")
    );
    let k = load_matrix(&store, "RIGI").unwrap();
    let m = load_matrix(&store, "MASS").unwrap();
    assert_eq!(k.reduced().unwrap().to_dense()[(0, 0)], 10.0);
    assert_eq!(m.reduced().unwrap().to_dense()[(0, 0)], 1.0);
    assert_eq!(k.free_dofs().len(), 1);

    // The AFFE_CHAR_MECA path.
    run(
        &store,
        "AFFE_CHAR_MECA",
        Some("CH"),
        &bcs("AFFE_CHAR_MECA", "DDL_IMPO", 0.0),
    )
    .unwrap();
    for (name, opt) in [("KEL", "RIGI_MECA"), ("MEL", "MASS_MECA")] {
        let a = fact(
            "CALC_MATR_ELEM",
            vec![
                ("OPTION", s(opt)),
                ("MODELE", c("MO", "modele_sdaster")),
                ("CARA_ELEM", c("CARA", "cara_elem")),
                ("CHARGE", seq(vec![c("CH", "char_meca")])),
            ],
        );
        run(&store, "CALC_MATR_ELEM", Some(name), &a).unwrap();
    }
    run(
        &store,
        "NUME_DDL",
        Some("NU"),
        &fact(
            "NUME_DDL",
            vec![("MATR_RIGI", c("KEL", "matr_elem_depl_r"))],
        ),
    )
    .unwrap();
    for (name, el) in [("K2", "KEL"), ("M2", "MEL")] {
        let a = fact(
            "ASSE_MATRICE",
            vec![
                ("MATR_ELEM", c(el, "matr_elem_depl_r")),
                ("NUME_DDL", c("NU", "nume_ddl_sdaster")),
            ],
        );
        run(&store, "ASSE_MATRICE", Some(name), &a).unwrap();
    }
    let k2 = load_matrix(&store, "K2").unwrap();
    let m2 = load_matrix(&store, "M2").unwrap();
    assert_eq!(
        k2.reduced().unwrap().to_dense(),
        k.reduced().unwrap().to_dense()
    );
    assert_eq!(
        m2.reduced().unwrap().to_dense(),
        m.reduced().unwrap().to_dense()
    );
    assert_eq!(k2.eliminated, k.eliminated);
    assert_eq!(k2.triplets, k.triplets);

    // Storage round trip is exact, and deleting a matrix removes its rows.
    let again =
        crate::ops::asse_matrice::assemble_named(&store, &["KEL".into()], "NU", &[]).unwrap();
    assert_eq!(again, k2);
    store.delete_concept("K2").unwrap();
    let n: i64 = store
        .conn()
        .query_row(
            "SELECT count(*) FROM matrix_entries WHERE matrix='K2'",
            [],
            |r| r.get(0),
        )
        .unwrap();
    assert_eq!(n, 0);
}

#[test]
fn nonzero_imposed_value_raises_an_alarm() {
    let store = setup();
    let (_, out) = run(
        &store,
        "AFFE_CHAR_MECA",
        Some("CH"),
        &bcs("AFFE_CHAR_MECA", "DDL_IMPO", 0.5),
    )
    .unwrap();
    assert!(
        out.contains("<A> <MODEL_NONZERO_IMPO> 1 nonzero imposed value(s) (e.g. DZ = 0.5 on N2)"),
        "{out}"
    );
}

#[test]
fn wrong_cara_for_cell_is_an_error() {
    let store = setup();
    let ca = with_facts(
        fact(
            "AFFE_CARA_ELEM",
            vec![("MODELE", c("MO", "modele_sdaster"))],
        ),
        "DISCRET",
        vec![fact(
            "AFFE_CARA_ELEM/DISCRET",
            vec![
                ("MAILLE", s("P2")),
                ("CARA", s("K_T_D_L")),
                ("VALE", reals(&[1.0, 1.0, 1.0])),
            ],
        )],
    );
    let e = run(&store, "AFFE_CARA_ELEM", Some("C2"), &ca).unwrap_err();
    assert_eq!(e.keyword.as_deref(), Some("AFFE_CARA_ELEM/DISCRET/CARA"));
    assert!(store.concept_type("C2").unwrap().is_none());
}

#[test]
fn catalogs_parse_and_cover_the_operators() {
    let ops = [
        "AFFE_MODELE",
        "DEFI_MATERIAU",
        "AFFE_MATERIAU",
        "AFFE_CARA_ELEM",
        "AFFE_CHAR_CINE",
        "AFFE_CHAR_MECA",
        "CALC_MATR_ELEM",
        "NUME_DDL",
        "ASSE_MATRICE",
        "ASSEMBLAGE",
    ];
    for op in ops {
        let path = format!("{}/commands/{op}.toml", env!("CARGO_MANIFEST_DIR"));
        let text = std::fs::read_to_string(&path).unwrap();
        let v: toml::Value = toml::from_str(&text).unwrap_or_else(|e| panic!("{path}: {e}"));
        assert_eq!(v.get("name").and_then(|n| n.as_str()), Some(op));
        assert!(lookup(op).is_some(), "{op} not registered");
    }
}

#[test]
fn the_catalog_names_exactly_the_registered_operators() {
    use crate::ops::{INTERPRETER_COMMANDS, OPERATORS};
    use std::collections::BTreeSet;
    let catalog: BTreeSet<&str> = crate::catalog::operator_names().into_iter().collect();
    let registered: BTreeSet<&str> = OPERATORS.iter().map(|(n, _)| *n).collect();
    assert_eq!(
        registered.len(),
        OPERATORS.len(),
        "an operator is registered twice"
    );
    let interpreter: BTreeSet<&str> = INTERPRETER_COMMANDS.iter().copied().collect();
    assert!(registered.is_disjoint(&interpreter));
    let all: BTreeSet<&str> = registered.union(&interpreter).copied().collect();
    let missing: Vec<&str> = catalog.difference(&all).copied().collect();
    assert!(
        missing.is_empty(),
        "in commands/ but not registered: {missing:?}"
    );
    let extra: Vec<&str> = all.difference(&catalog).copied().collect();
    assert!(
        extra.is_empty(),
        "registered but without a catalog: {extra:?}"
    );
}
