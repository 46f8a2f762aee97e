//! DYNA_VIBRA's buckling shocks (COMPORTEMENT RELATION='FLAMBAGE') and its continuation of
//! a result (reuse= with ETAT_INIT=_F(RESULTAT=...)) through the binary:
//! `testcases/dyna_vibra_flambage.comm` against the exact motion, a run continued with
//! reuse= equal to the run in one call, what a continued result keeps, and the errors a
//! user meets, each naming its keyword (and leaving the database as it was).

use std::path::Path;

mod support;
use support::{case, run_file};

#[test]
fn a_mass_thrown_on_a_buckling_support_matches_its_exact_motion() {
    let dir = tempfile::tempdir().unwrap();
    let (code, out) = run_file(
        &case("dyna_vibra_flambage.comm"),
        &dir.path().join("case.db"),
    );
    assert_eq!(code, Some(0), "{out}");
    assert!(out.contains("tests: 7 OK, 0 NOOK"), "{out}");
    assert!(
        out.contains("its first 1001 instants kept, up to 1e-2 s"),
        "{out}"
    );
}

/// The testcase up to its shock's definition (SUPPORT), then `tail`: (code, output,
/// database directory).
fn run_with(tail: &str) -> (Option<i32>, String, tempfile::TempDir) {
    let dir = tempfile::tempdir().unwrap();
    let text = std::fs::read_to_string(case("dyna_vibra_flambage.comm")).unwrap();
    let head = text.split("TR = DYNA_VIBRA(").next().unwrap();
    std::fs::copy(case("dyna_vibra_flambage.mail"), dir.path().join("f.mail")).unwrap();
    let comm = dir.path().join("f.comm");
    std::fs::write(&comm, format!("{head}\n{tail}\nFIN()\n")).unwrap();
    let (code, out) = run_file(&comm, &dir.path().join("f.db"));
    (code, out, dir)
}

/// A DYNA_VIBRA call of the testcase's system: `name` with `scheme`, from `init` to
/// `fin`, and `more` keywords.
fn call(name: &str, more: &str, scheme: &str, init: &str, fin: f64) -> String {
    format!(
        "{name} = DYNA_VIBRA({more}TYPE_CALCUL='TRAN', BASE_CALCUL='GENE', MATR_MASS=MGEN, \
         MATR_RIGI=KGEN, SCHEMA_TEMPS=_F(SCHEMA='{scheme}'), ETAT_INIT={init}, \
         INCREMENT=_F(INST_FIN={fin}, PAS=1.e-5), COMPORTEMENT=SUPPORT)\n"
    )
}

/// A table concept's rows as text cells and numbers, in its order.
fn table(db: &Path, name: &str, cols: &str, order: &str) -> Vec<Vec<f64>> {
    let conn = rusqlite::Connection::open(db).unwrap();
    let n = cols.split(',').count();
    let mut stmt = conn
        .prepare(&format!("SELECT {cols} FROM \"{name}\" ORDER BY {order}"))
        .unwrap();
    stmt.query_map([], |r| (0..n).map(|i| r.get(i)).collect())
        .unwrap()
        .collect::<Result<Vec<Vec<f64>>, _>>()
        .unwrap()
}

const COORDS: &str = "INST, DEPL, VITE, ACCE";
const SHOCK: &str = "INST, FN, VN, DXLOC, ECRAS_RESI, RIGI_FL, ENFO_MAX, AMOR_FL";

/// DIFF_CENTRE over [0, 0.04] in one call, and the same in two calls split at 0.02 (during
/// the plateau, where the support is buckled and crushing) with reuse=: the same result,
/// every coordinate, force and internal variable to the last bit (the same operations on
/// the same numbers: the restart takes the stored displacement, velocity, acceleration and
/// internal variables and re-evaluates nothing), the instants to round-off of t0 + k·PAS.
#[test]
fn a_run_continued_with_reuse_is_the_run_in_one_call() {
    let one = call("ONE", "", "DIFF_CENTRE", "_F(VITE=VGEN)", 0.04);
    let two = call("TWO", "", "DIFF_CENTRE", "_F(VITE=VGEN)", 0.02)
        + &call(
            "TWO",
            "reuse=TWO, ",
            "DIFF_CENTRE",
            "_F(RESULTAT=TWO)",
            0.04,
        );
    let (code, out, dir) = run_with(&format!("{one}{two}"));
    assert_eq!(code, Some(0), "{out}");
    let db = dir.path().join("f.db");
    let a = table(&db, "ONE", COORDS, "NUME_ORDRE");
    let b = table(&db, "TWO", COORDS, "NUME_ORDRE");
    assert_eq!(a.len(), 4001);
    assert_eq!(a.len(), b.len());
    for (x, y) in a.iter().zip(&b) {
        assert!((x[0] - y[0]).abs() <= 1e-15, "{x:?} {y:?}");
        assert_eq!(x[1..], y[1..], "at {}", x[0]);
    }
    let a = table(&db, "ONE_CHOC", SHOCK, "NUME_ORDRE");
    let b = table(&db, "TWO_CHOC", SHOCK, "NUME_ORDRE");
    assert_eq!(a.len(), b.len());
    for (x, y) in a.iter().zip(&b) {
        assert_eq!(x[1..], y[1..], "at {}", x[0]);
    }
    // The split fell on a buckled support: without its crush the second half would differ.
    let at_split = &b[2000];
    assert!(at_split[4] > 0.0 && at_split[1] > 0.0, "{at_split:?}");
}

/// ETAT_INIT/INST_INIT before the last instant: reuse= keeps the instants up to it, drops
/// the later ones (Code_Aster's), and goes on from there with the state stored there; a
/// new name instead of reuse= holds the new instants only, from that one.
#[test]
fn a_continued_result_keeps_its_instants_up_to_the_restart() {
    let first = call("TR", "", "DIFF_CENTRE", "_F(VITE=VGEN)", 0.02);
    let again = call(
        "TR",
        "reuse=TR, ",
        "ADAPT_ORDRE2",
        "_F(RESULTAT=TR, INST_INIT=0.01)",
        0.03,
    );
    let copy = call(
        "NEW",
        "",
        "DIFF_CENTRE",
        "_F(RESULTAT=TR, NUME_ORDRE=501)",
        0.01,
    );
    let (code, out, dir) = run_with(&format!("{first}{copy}{again}"));
    assert_eq!(code, Some(0), "{out}");
    let db = dir.path().join("f.db");
    let tr = table(&db, "TR", COORDS, "NUME_ORDRE");
    // 0..0.01 at 1e-5: 1001 instants, then ADAPT_ORDRE2's after 0.01.
    assert!((tr[1000][0] - 0.01).abs() < 1e-15);
    assert!(tr[1001][0] > 0.01 && tr[1001][0] < 0.0101);
    assert!((tr.last().unwrap()[0] - 0.03).abs() < 1e-12);
    let shocks = table(&db, "TR_CHOC", "INST, ECRAS_RESI", "NUME_ORDRE");
    assert_eq!(shocks.len(), tr.len());
    // NEW: from instant 501 (t = 0.005, buckled at 3.77e-3) to 0.01, crush carried over.
    let new = table(&db, "NEW", COORDS, "NUME_ORDRE");
    assert_eq!(new.len(), 501);
    assert!((new[0][0] - 0.005).abs() < 1e-15);
    let crush = table(&db, "NEW_CHOC", "INST, ECRAS_RESI", "NUME_ORDRE");
    assert!(crush[0][1] > 0.0, "{:?}", crush[0]);
}

/// FNOR_POST_FL above FNOR_CRIT, FNOR_CRIT missing or not positive, a post-buckling line
/// starting before the stop, friction on a buckling shock: each refused naming its keyword.
#[test]
fn bad_buckling_parameters_are_refused_naming_their_keyword() {
    let shock = |extra: &str| {
        format!(
            "TR = DYNA_VIBRA(TYPE_CALCUL='TRAN', BASE_CALCUL='GENE', MATR_MASS=MGEN, \
             MATR_RIGI=KGEN, ETAT_INIT=_F(VITE=VGEN), INCREMENT=_F(INST_FIN=0.01, PAS=1.e-5), \
             COMPORTEMENT=_F(RELATION='FLAMBAGE', GROUP_NO_1='N2', OBSTACLE=PLAN, \
             NORM_OBST=(0., 1., 0.), RIGI_NOR=KN, {extra}))"
        )
    };
    for (extra, keyword, says) in [
        (
            "FNOR_CRIT=1000., FNOR_POST_FL=1500.",
            "COMPORTEMENT/FNOR_POST_FL",
            "above FNOR_CRIT",
        ),
        ("FNOR_POST_FL=300.", "FNOR_CRIT", "FNOR_CRIT"),
        ("FNOR_CRIT=0., FNOR_POST_FL=300.", "FNOR_CRIT", "FNOR_CRIT"),
        (
            "FNOR_CRIT=1000., FNOR_POST_FL=300., RIGI_NOR_POST_FL=1.e4",
            "COMPORTEMENT/RIGI_NOR_POST_FL",
            "before the stop",
        ),
        (
            "FNOR_CRIT=1000., FNOR_POST_FL=300., FROTTEMENT='COULOMB', COULOMB=0.1",
            "FROTTEMENT",
            "FROTTEMENT",
        ),
        (
            "FNOR_CRIT=1000., FNOR_POST_FL=300., DEPL_POST_FL=(0.1,)",
            "COMPORTEMENT/RIGI_POST_FL",
            "one stiffness per crush",
        ),
    ] {
        let (code, out, _dir) = run_with(&shock(extra));
        assert_eq!(code, Some(2), "{extra}: {out}");
        assert!(
            out.contains(keyword) && out.contains(says),
            "{extra}: {out}"
        );
    }
}

/// A continuation that does not fit its result is refused naming ETAT_INIT's RESULTAT,
/// and the failed call leaves the result as it was (one transaction per operator).
#[test]
fn a_continuation_with_other_shocks_is_refused_and_changes_nothing() {
    let first = call("TR", "", "DIFF_CENTRE", "_F(VITE=VGEN)", 0.01);
    let chocs = "COMPORTEMENT=_F(RELATION='DIS_CHOC', GROUP_NO_1='N2', OBSTACLE=PLAN, \
                 NORM_OBST=(0., 1., 0.), RIGI_NOR=KN)";
    let other = call("TR", "reuse=TR, ", "DIFF_CENTRE", "_F(RESULTAT=TR)", 0.02)
        .replace("COMPORTEMENT=SUPPORT", chocs);
    let (code, out, dir) = run_with(&format!("{first}{other}"));
    assert_eq!(code, Some(2), "{out}");
    assert!(
        out.contains("ETAT_INIT/RESULTAT") && out.contains("is a FLAMBAGE on N2"),
        "{out}"
    );
    let db = dir.path().join("f.db");
    assert_eq!(table(&db, "TR", COORDS, "NUME_ORDRE").len(), 1001);
    assert_eq!(table(&db, "TR_CHOC", SHOCK, "NUME_ORDRE").len(), 1001);
    // reuse= of another result than the one it starts from: refused before it runs.
    let wrong = call("TR", "", "DIFF_CENTRE", "_F(VITE=VGEN)", 0.01)
        + &call("B", "", "DIFF_CENTRE", "_F(VITE=VGEN)", 0.01)
        + &call("TR", "reuse=TR, ", "DIFF_CENTRE", "_F(RESULTAT=B)", 0.02);
    let (code, out, _dir) = run_with(&wrong);
    assert_eq!(code, Some(2), "{out}");
    assert!(out.contains("reuse=TR but ETAT_INIT/RESULTAT=B"), "{out}");
}

/// POST_DYNA_MODA_T (OPTION='IMPACT') on a result with a DIS_CHOC shock and a FLAMBAGE one
/// between two nodes, given in that order reversed: Code_Aster's table lists the DIS_CHOC
/// shocks first, then the FLAMBAGE ones; the buckled one gets its CALCUL='FLAMBAGE' rows
/// after its PROBA rows, CHOC its rank (2), FLAMBAGE='OUI', INST_FLAMB its first instant
/// with a positive crush, and between two nodes the crush shared: ECRAS_RESI/2 on a row for
/// each node. The columns are Code_Aster's, FLAMBAGE, ECRAS_RESI, INST_FLAMB after PROBA.
#[test]
fn post_dyna_moda_t_writes_the_buckled_shocks_rows() {
    // The mass thrown toward N1 (clamped) through a BI_PLAN_Y between N1 and N2 whose
    // DIST_1 + DIST_2 is their distance: in contact as soon as DX < 0.
    let tail = "NUMG = NUME_DDL_GENE(BASE=MODES, STOCKAGE='DIAG')\n\
        VNEG = CREA_CHAMP(OPERATION='AFFE', TYPE_CHAM='NOEU_DEPL_R', MAILLAGE=MAIL, NUME_DDL=NUME,\n\
                          PROL_ZERO='OUI', AFFE=_F(GROUP_NO='N2', NOM_CMP='DX', VALE=-V0))\n\
        VGNEG = PROJ_VECT_BASE(BASE=MODES, NUME_DDL_GENE=NUMG, VECT_ASSE=VNEG, TYPE_VECT='VITE')\n\
        BIPLAN = DEFI_OBSTACLE(TYPE='BI_PLAN_Y')\n\
        TR = DYNA_VIBRA(TYPE_CALCUL='TRAN', BASE_CALCUL='GENE', MATR_MASS=MGEN, MATR_RIGI=KGEN,\n\
                        ETAT_INIT=_F(VITE=VGNEG), INCREMENT=_F(INST_FIN=0.05, PAS=1.e-5),\n\
                        COMPORTEMENT=(_F(RELATION='FLAMBAGE', INTITULE='BI', GROUP_NO_1='N1',\n\
                                         GROUP_NO_2='N2', OBSTACLE=BIPLAN, NORM_OBST=(0., 1., 0.),\n\
                                         DIST_1=0.5, DIST_2=0.5, RIGI_NOR=KN, FNOR_CRIT=FCRIT,\n\
                                         FNOR_POST_FL=FPOST),\n\
                                      _F(RELATION='DIS_CHOC', INTITULE='FAR', GROUP_NO_1='N2',\n\
                                         OBSTACLE=PLAN, NORM_OBST=(0., 1., 0.), JEU=5., RIGI_NOR=KN)))\n\
        TAB = POST_DYNA_MODA_T(RESU_GENE=TR, CHOC=_F(OPTION='IMPACT'))\n";
    let (code, out, dir) = run_with(tail);
    assert_eq!(code, Some(0), "{out}");
    let db = dir.path().join("f.db");
    let conn = rusqlite::Connection::open(&db).unwrap();
    let mut stmt = conn
        .prepare("SELECT name FROM pragma_table_info('TAB')")
        .unwrap();
    let cols: Vec<String> = stmt
        .query_map([], |r| r.get(0))
        .unwrap()
        .collect::<Result<_, _>>()
        .unwrap();
    let tail_cols = &cols[cols.len() - 4..];
    assert_eq!(tail_cols, ["PROBA", "FLAMBAGE", "ECRAS_RESI", "INST_FLAMB"]);
    let mut stmt = conn
        .prepare("SELECT INTITULE, NOEUD, CALCUL, CHOC, FLAMBAGE, ECRAS_RESI, INST_FLAMB FROM TAB")
        .unwrap();
    type Row = (
        String,
        String,
        String,
        Option<i64>,
        Option<String>,
        Option<f64>,
        Option<f64>,
    );
    let rows: Vec<Row> = stmt
        .query_map([], |r| {
            Ok((
                r.get(0)?,
                r.get(1)?,
                r.get(2)?,
                r.get(3)?,
                r.get(4)?,
                r.get(5)?,
                r.get(6)?,
            ))
        })
        .unwrap()
        .collect::<Result<_, _>>()
        .unwrap();
    // FAR's rows come first (no impact: one row CHOC = 0), then BI's.
    let first_bi = rows.iter().position(|r| r.0 == "BI").unwrap();
    assert!(rows[..first_bi].iter().all(|r| r.0 == "FAR"), "{rows:?}");
    assert_eq!((rows[0].2.as_str(), rows[0].3), ("IMPACT", Some(0)));
    let flambage: Vec<&Row> = rows.iter().filter(|r| r.2 == "FLAMBAGE").collect();
    assert_eq!(flambage.len(), 2, "{rows:?}");
    assert_eq!(
        rows.len() - 2,
        rows.iter().rposition(|r| r.2 == "PROBA").unwrap() + 1
    );
    let crush = table(&db, "TR_CHOC", "INST, ECRAS_RESI", "NUME_ORDRE, INTITULE")
        .iter()
        .map(|r| r[1])
        .fold(0.0, f64::max);
    assert!(crush > 0.0);
    for (row, node) in flambage.iter().zip(["N1", "N2"]) {
        assert_eq!(row.1, node);
        assert_eq!(row.3, Some(2));
        assert_eq!(row.4.as_deref(), Some("OUI"));
        assert_eq!(row.5, Some(crush / 2.0));
        // Buckled at the step after 3.77e-3 s (the same dynamics as the testcase, mirrored).
        let t = row.6.unwrap();
        assert!((t - 3.77e-3).abs() < 1e-5, "{t}");
    }
}

/// Code_Aster 13's spelling: DYNA_TRAN_MODAL with a FLAMBAGE factor (RIGI_NOR_POST_FL) and
/// reuse= with ETAT_INIT=_F(RESU_GENE=...), as the older sdnd105a writes it; its reuse= of
/// a result it does not start from is refused naming RESU_GENE. The crush within 1e-2:
/// the buckling's first-order bound (3.7e-3, the testcase's) plus ADAPT_ORDRE2's own
/// first-order error while its step grows from PAS to 1e6·PAS on the plateau (measured
/// 5.0e-3 in all, 3.0e-3 with DIFF_CENTRE alone).
#[test]
fn dyna_tran_modal_continues_a_buckling_run_in_code_aster_13s_spelling() {
    let flambage = "FLAMBAGE=_F(NOEUD_1='N2', OBSTACLE=PLAN, ORIG_OBST=(0., 0., 0.), \
                    NORM_OBST=(0., 1., 0.), JEU=1., RIGI_NOR=KN, FNOR_CRIT=FCRIT, \
                    FNOR_POST_FL=FPOST, RIGI_NOR_POST_FL=KP)";
    let run = |name: &str, reuse: &str, method: &str, init: &str, fin: f64| {
        format!(
            "{name} = DYNA_TRAN_MODAL({reuse}MASS_GENE=MGEN, RIGI_GENE=KGEN, METHODE='{method}', \
             ETAT_INIT={init}, INCREMENT=_F(INST_FIN={fin}, PAS=1.e-5), {flambage})\n"
        )
    };
    let ok = run("T", "", "EULER", "_F(VITE_INIT_GENE=VGEN)", 0.01)
        + &run(
            "T",
            "reuse=T, ",
            "ADAPT",
            "_F(RESU_GENE=T, INST_INIT=0.01)",
            0.05,
        )
        + "TAB = POST_DYNA_MODA_T(RESU_GENE=T, CHOC=_F(OPTION='IMPACT'))\n\
           TEST_TABLE(TABLE=TAB, FILTRE=_F(NOM_PARA='CALCUL', VALE_K='FLAMBAGE'), \
           NOM_PARA='ECRAS_RESI', VALE_REFE=CRUSH, REFERENCE='ANALYTIQUE', PRECISION=1.e-2)\n";
    let (code, out, _dir) = run_with(&ok);
    assert_eq!(code, Some(0), "{out}");
    assert!(
        out.contains("T (reuse): its first 1001 instants kept"),
        "{out}"
    );
    assert!(out.contains("tests: 1 OK, 0 NOOK"), "{out}");
    let wrong = run("T", "", "EULER", "_F(VITE_INIT_GENE=VGEN)", 0.01)
        + &run("U", "", "EULER", "_F(VITE_INIT_GENE=VGEN)", 0.01)
        + &run("U", "reuse=U, ", "ADAPT", "_F(RESU_GENE=T)", 0.05);
    let (code, out, _dir) = run_with(&wrong);
    assert_eq!(code, Some(2), "{out}");
    assert!(
        out.contains("DYNA_TRAN_MODAL/ETAT_INIT/RESU_GENE") && out.contains("reuse=U needs"),
        "{out}"
    );
}
