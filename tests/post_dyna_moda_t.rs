//! POST_DYNA_MODA_T through the binary: the impact and wear statistics of
//! `testcases/dyna_vibra_impact_stats.comm` (each checked there against its closed form),
//! the table's Code_Aster columns, and the errors a user meets, each naming its keyword.

use std::path::Path;

mod support;
use support::{case, run_file};

/// The impact case up to its first POST_DYNA_MODA_T (the transient TRAN of the impact
/// oscillator, archived 0..0.2 s), then `tail`: (code, output, database).
fn run_impact_with(tail: &str) -> (Option<i32>, String, tempfile::TempDir) {
    let dir = tempfile::tempdir().unwrap();
    let text = std::fs::read_to_string(case("dyna_vibra_impact_stats.comm")).unwrap();
    let head = text.split("TT = POST_DYNA_MODA_T").next().unwrap();
    let comm = dir.path().join("stats.comm");
    std::fs::write(&comm, format!("{head}\n{tail}\nFIN()\n")).unwrap();
    std::fs::copy(
        case("dyna_vibra_impact_stats.mail"),
        dir.path().join("stats.mail"),
    )
    .unwrap();
    let (code, out) = run_file(&comm, &dir.path().join("stats.db"));
    (code, out, dir)
}

/// The columns of table concept `name`, in order.
fn columns(db: &Path, name: &str) -> Vec<String> {
    let conn = rusqlite::Connection::open(db).unwrap();
    let mut stmt = conn
        .prepare(&format!("SELECT name FROM pragma_table_info('{name}')"))
        .unwrap();
    stmt.query_map([], |r| r.get(0))
        .unwrap()
        .collect::<Result<Vec<String>, _>>()
        .unwrap()
}

/// (CALCUL, CHOC, F_MAX) of the rows of table `name`.
fn impact_rows(db: &Path, name: &str) -> Vec<(String, Option<i64>, Option<f64>)> {
    let conn = rusqlite::Connection::open(db).unwrap();
    let mut stmt = conn
        .prepare(&format!("SELECT CALCUL, CHOC, F_MAX FROM \"{name}\""))
        .unwrap();
    stmt.query_map([], |r| Ok((r.get(0)?, r.get(1)?, r.get(2)?)))
        .unwrap()
        .collect::<Result<Vec<_>, _>>()
        .unwrap()
}

#[test]
fn impact_and_wear_statistics_match_their_closed_forms() {
    let dir = tempfile::tempdir().unwrap();
    let db = dir.path().join("case.db");
    let (code, out) = run_file(&case("dyna_vibra_impact_stats.comm"), &db);
    assert_eq!(code, Some(0), "{out}");
    assert!(out.contains("tests: 26 OK, 0 NOOK"), "{out}");
    // Code_Aster's columns, in its order.
    let impact = [
        "INTITULE",
        "NOEUD",
        "CALCUL",
        "CHOC",
        "INSTANT",
        "F_MAX",
        "IMPULSION",
        "T_CHOC",
        "V_IMPACT",
        "NB_IMPACT",
        "F_MAX_ABS",
        "F_MAX_MOY",
        "F_MAX_ETYPE",
        "CLASSE",
        "DEBUT",
        "FIN",
        "PROBA",
    ];
    assert_eq!(columns(&db, "TT"), impact);
    let wear = [
        "INTITULE",
        "NOEUD",
        "CALCUL",
        "MOYEN",
        "ECART_TYPE",
        "RMS",
        "MAXI",
        "MINI",
        "MOYEN_T_TOTAL",
        "MOYEN_T_CHOC",
        "RMS_T_TOTAL",
        "RMS_T_CHOC",
        "NB_CHOC_S",
        "NB_REBON_CHOC",
        "T_CHOC_MOYEN",
        "T_CHOC_MAXI",
        "T_CHOC_MINI",
        "T_REBON_MOYEN",
        "%_T_CHOC",
        "PUIS_USURE",
    ];
    assert_eq!(columns(&db, "TW"), wear);
    // Five impacts, then the GLOBAL row and NB_CLASSE = 4 PROBA rows.
    let rows = impact_rows(&db, "TT");
    let kinds: Vec<&str> = rows.iter().map(|r| r.0.as_str()).collect();
    assert_eq!(
        kinds,
        [
            "IMPACT", "IMPACT", "IMPACT", "IMPACT", "IMPACT", "GLOBAL", "PROBA", "PROBA", "PROBA",
            "PROBA"
        ]
    );
    let chocs: Vec<Option<i64>> = rows.iter().take(5).map(|r| r.1).collect();
    assert_eq!(chocs, [Some(1), Some(2), Some(3), Some(4), Some(5)]);
}

#[test]
fn both_options_in_one_call_and_a_result_on_the_physical_dofs() {
    // The same impacts on the physical DOF (DYNA_VIBRA BASE_CALCUL='PHYS' keeps its shocks'
    // samples as the GENE run does): the same peak forces; IMPACT and USURE occurrences of
    // one call write into one table, each with its columns.
    let tail = "\
PH = DYNA_VIBRA(TYPE_CALCUL='TRAN', BASE_CALCUL='PHYS', MATR_MASS=MASS, MATR_RIGI=RIGI,
                SCHEMA_TEMPS=_F(SCHEMA='RUNGE_KUTTA_54', TOLERANCE=1.e-10),
                ETAT_INIT=_F(VITE=VPHYS), INCREMENT=_F(INST_FIN=TF, PAS=1.e-4),
                ARCHIVAGE=_F(LIST_INST=LI),
                COMPORTEMENT=_F(RELATION='DIS_CHOC', INTITULE='STOP', GROUP_NO_1='NO1',
                                OBSTACLE=PLAN, ORIG_OBST=(-1., 0., 0.), NORM_OBST=(0., 1., 0.),
                                JEU=1., RIGI_NOR=KN))
TP = POST_DYNA_MODA_T(RESU_GENE=PH, CHOC=(_F(OPTION='IMPACT', SEUIL_FORCE=1., NB_CLASSE=2),
                                        _F(OPTION='USURE', SEUIL_FORCE=1.)), INFO=2)
TEST_TABLE(TABLE=TP, NOM_PARA='F_MAX', FILTRE=(_F(NOM_PARA='CALCUL', VALE_K='IMPACT'),
                                             _F(NOM_PARA='CHOC', VALE_I=4)),
           VALE_REFE=KN*V0/WC, REFERENCE='ANALYTIQUE', PRECISION=1.e-8)
TEST_TABLE(TABLE=TP, NOM_PARA='T_CHOC_MOYEN', FILTRE=_F(NOM_PARA='CALCUL', VALE_K='STAT_CHOC'),
           VALE_REFE=49*H, REFERENCE='ANALYTIQUE', PRECISION=1.e-10)
TEST_TABLE(TABLE=TP, NOM_PARA='NB_REBON_CHOC', FILTRE=_F(NOM_PARA='CALCUL', VALE_K='STAT_CHOC'),
           VALE_CALC_I=1)
";
    let (code, out, dir) = run_impact_with(tail);
    assert_eq!(code, Some(0), "{out}");
    assert!(out.contains("tests: 3 OK, 0 NOOK"), "{out}");
    // INFO=2: one line per shock and occurrence.
    assert!(
        out.contains("shock 'STOP' (node NO1): 3184 archived instants"),
        "{out}"
    );
    assert!(out.contains("5 impact(s)"), "{out}");
    let cols = columns(&dir.path().join("stats.db"), "TP");
    assert!(cols.contains(&"F_MAX".to_string()) && cols.contains(&"PUIS_USURE".to_string()));
    let rows = impact_rows(&dir.path().join("stats.db"), "TP");
    // 5 IMPACT + GLOBAL + 2 PROBA, then the 10 rows of USURE.
    assert_eq!(rows.len(), 5 + 1 + 2 + 10, "{rows:?}");
    assert_eq!(rows[8].0, "DEPL_X");
    assert_eq!(rows[17].0, "PUIS_USURE");
}

#[test]
fn a_result_without_shocks_is_refused_naming_resu_gene() {
    let tail = "\
FREE = DYNA_VIBRA(TYPE_CALCUL='TRAN', BASE_CALCUL='GENE', MATR_MASS=MGEN, MATR_RIGI=KGEN,
                  ETAT_INIT=_F(VITE=VGEN), INCREMENT=_F(INST_FIN=0.01, PAS=1.e-5))
T = POST_DYNA_MODA_T(RESU_GENE=FREE, CHOC=_F(OPTION='IMPACT'))
";
    let (code, out, _dir) = run_impact_with(tail);
    assert_eq!(code, Some(2), "{out}");
    assert!(
        out.contains("POST_DYNA_MODA_T/RESU_GENE") && out.contains("FREE holds no shock"),
        "{out}"
    );
}

#[test]
fn an_analysed_time_outside_the_archive_is_refused_naming_inst_init() {
    let tail = "T = POST_DYNA_MODA_T(RESU_GENE=TRAN, CHOC=_F(OPTION='IMPACT', INST_INIT=0.3, INST_FIN=0.4))\n";
    let (code, out, _dir) = run_impact_with(tail);
    assert_eq!(code, Some(2), "{out}");
    assert!(
        out.contains("POST_DYNA_MODA_T/CHOC/INST_INIT") && out.contains("fewer than two"),
        "{out}"
    );
}

#[test]
fn more_blocks_than_samples_is_refused_naming_nb_bloc() {
    let tail = "T = POST_DYNA_MODA_T(RESU_GENE=TRAN, CHOC=_F(OPTION='USURE', NB_BLOC=2000))\n";
    let (code, out, _dir) = run_impact_with(tail);
    assert_eq!(code, Some(2), "{out}");
    assert!(
        out.contains("POST_DYNA_MODA_T/CHOC/NB_BLOC") && out.contains("fewer than 2 per block"),
        "{out}"
    );
}

#[test]
fn keywords_out_of_the_catalog_are_refused_before_the_run() {
    for (call, kw) in [
        (
            "T = POST_DYNA_MODA_T(RESU_GENE=TRAN, RELA_EFFO_DEPL=_F(NOEUD='NO1', NOM_CMP='DX'))",
            "RELA_EFFO_DEPL",
        ),
        (
            "T = POST_DYNA_MODA_T(RESU_GENE=TRAN, CHOC=_F(OPTION='FLAMBAGE'))",
            "OPTION",
        ),
        (
            "T = POST_DYNA_MODA_T(RESU_GENE=TRAN, CHOC=_F(SEUIL_FORCE=-1.))",
            "SEUIL_FORCE",
        ),
    ] {
        let (code, out, _dir) = run_impact_with(call);
        assert_eq!(code, Some(2), "{call}\n{out}");
        assert!(out.contains(kw), "{call}\n{out}");
    }
}

/// Code_Aster 17 names nodes by their number in its tables and its files filter so
/// (NOEUD='1'): the number reads as the mesh's node of that number (NO1, the first node),
/// giving the same row as NOEUD='NO1'; a number the mesh does not have selects nothing.
#[test]
fn a_node_given_by_its_number_filters_as_its_name() {
    let head = "TT = POST_DYNA_MODA_T(RESU_GENE=TRAN, CHOC=_F(OPTION='IMPACT', SEUIL_FORCE=1.))
IMP = _F(NOM_PARA='CALCUL', VALE_K='IMPACT') ; FIRST = _F(NOM_PARA='CHOC', VALE_I=1)
F1 = EXTR_TABLE(TYPE_RESU='R', TABLE=TT, NOM_PARA='F_MAX',
                FILTRE=(IMP, FIRST, _F(NOM_PARA='NOEUD', VALE_K='NO1')))
";
    let by_number = "TEST_TABLE(TABLE=TT, NOM_PARA='F_MAX', VALE_REFE=F1, REFERENCE='ANALYTIQUE',
           PRECISION=1.e-15, FILTRE=(IMP, FIRST, _F(NOM_PARA='NOEUD', VALE_K='1')))";
    let (code, out, _dir) = run_impact_with(&format!("{head}{by_number}"));
    assert_eq!(code, Some(0), "{out}");
    assert!(out.contains("tests: 1 OK, 0 NOOK"), "{out}");
    let absent = by_number.replace("VALE_K='1'", "VALE_K='2'");
    let (code, out, _dir) = run_impact_with(&format!("{head}{absent}"));
    assert_eq!(
        code,
        Some(2),
        "node 2 does not exist: its filter selects no row\n{out}"
    );
    assert!(out.contains("TEST_TABLE/FILTRE"), "{out}");
}

/// The wear power of the Coulomb oscillator (testcases/dyna_vibra_friction.comm: four half
/// swings, then held by friction from 2T = 0.126 s): Code_Aster's `pusure` leaves out the
/// intervals that start from a sticking sample (the stick flag VINT13 of the shocks'
/// table), so the held part wears exactly nothing, where the creep of the stick spring
/// RIGI_TAN would count. Over the whole run it is F_N times the distance slid, 8 U0 − 32 C,
/// over the time: 0.525 W (measured 2.3e-7 off; asserted 1e-5). TEST_TABLE filtered on the node alone selects the one row that holds
/// PUIS_USURE, as Code_Aster's does (its other rows hold other statistics).
#[test]
fn the_wear_power_leaves_out_the_sticking_samples() {
    let dir = tempfile::tempdir().unwrap();
    let text = std::fs::read_to_string(case("dyna_vibra_friction.comm")).unwrap();
    let head = text.split("W0 = sqrt(K/M)").next().unwrap();
    let tail = "\
HELD = POST_DYNA_MODA_T(RESU_GENE=TRAN, CHOC=_F(OPTION='USURE', INST_INIT=0.13, INST_FIN=0.16))
ALL = POST_DYNA_MODA_T(RESU_GENE=TRAN, CHOC=_F(OPTION='USURE'))
TEST_TABLE(TABLE=HELD, NOM_PARA='PUIS_USURE', FILTRE=_F(NOM_PARA='NOEUD', VALE_K='NO1'),
           VALE_REFE=0., REFERENCE='ANALYTIQUE', CRITERE='ABSOLU', PRECISION=0.)
TEST_TABLE(TABLE=ALL, NOM_PARA='PUIS_USURE', FILTRE=_F(NOM_PARA='NOEUD', VALE_K='NO1'),
           VALE_REFE=KN*PEN*(8*U0 - 32*MU*KN*PEN/K)/0.16, REFERENCE='ANALYTIQUE',
           PRECISION=1.e-5)
";
    let comm = dir.path().join("friction.comm");
    std::fs::write(&comm, format!("{head}\n{tail}\nFIN()\n")).unwrap();
    std::fs::copy(
        case("dyna_vibra_friction.mail"),
        dir.path().join("friction.mail"),
    )
    .unwrap();
    let (code, out) = run_file(&comm, &dir.path().join("friction.db"));
    assert_eq!(code, Some(0), "{out}");
    assert!(out.contains("tests: 2 OK, 0 NOOK"), "{out}");
    // Filtered on the node, the column holding several values is still refused.
    let many = format!(
        "{head}\nALL = POST_DYNA_MODA_T(RESU_GENE=TRAN, CHOC=_F(OPTION='USURE'))\n\
         TEST_TABLE(TABLE=ALL, NOM_PARA='MAXI', FILTRE=_F(NOM_PARA='NOEUD', VALE_K='NO1'),\n\
         VALE_REFE=0., REFERENCE='ANALYTIQUE')\nFIN()\n"
    );
    std::fs::write(&comm, many).unwrap();
    let (code, out) = run_file(&comm, &dir.path().join("many.db"));
    assert_eq!(code, Some(2), "{out}");
    assert!(out.contains("TEST_TABLE/FILTRE"), "{out}");
}
