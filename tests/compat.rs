//! Code_Aster command files as Code_Aster runs them (issue 10): the constructs real files
//! use, each in a small file written here, run with the `aster-nl` binary.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn bin() -> Command {
    Command::new(env!("CARGO_BIN_EXE_aster-nl"))
}

fn text(o: &Output) -> String {
    format!(
        "{}{}",
        String::from_utf8_lossy(&o.stdout),
        String::from_utf8_lossy(&o.stderr)
    )
}

/// Writes `comm` as `case.comm` in a new temporary directory and runs it there with
/// `extra` arguments; returns (exit code, output, directory).
fn run_text(comm: &str, extra: &[&str]) -> (Option<i32>, String, tempfile::TempDir) {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("case.comm");
    std::fs::write(&path, comm).unwrap();
    let o = bin().arg("run").arg(&path).args(extra).output().unwrap();
    (o.status.code(), text(&o), dir)
}

fn check_text(comm: &str, extra: &[&str]) -> (Option<i32>, String) {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("case.comm");
    std::fs::write(&path, comm).unwrap();
    let o = bin().arg("check").arg(&path).args(extra).output().unwrap();
    (o.status.code(), text(&o))
}

fn case(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("testcases")
        .join(name)
}

/// A table whose abscissa turns back (1, 3, 2) and repeats a point (3 twice), as a
/// MODE_NON_LINE table does after a `reuse=` restart; f = 10 E, so every interpolated
/// value is exact.
const TURNING_TABLE: &str = "\
T = CREA_TABLE(LISTE=(_F(PARA='E', LISTE_R=(1., 3., 2., 3., 4.)),
                      _F(PARA='F', LISTE_R=(10., 30., 20., 30., 40.)),))
F = RECU_FONCTION(TABLE=T, PARA_X='E', PARA_Y='F')
TEST_FONCTION(VALEUR=(_F(FONCTION=F, VALE_PARA=2.5, VALE_REFE=25., REFERENCE='ANALYTIQUE',
                         PRECISION=1.e-14),
                      _F(FONCTION=F, VALE_PARA=3.5, VALE_REFE=35., REFERENCE='ANALYTIQUE',
                         PRECISION=1.e-14),))
FIN()
";

#[test]
fn recu_fonction_sorts_a_turning_table_with_alarm_fonct0_62() {
    let (code, out, _d) = run_text(&format!("DEBUT()\n{TURNING_TABLE}"), &[]);
    assert_eq!(code, Some(0), "{out}");
    assert!(out.contains("<A> <FONCT0_62>"), "{out}");
    assert!(out.contains("sorted by increasing abscissa"), "{out}");
    assert!(
        out.contains("1 row(s) of table T repeat an abscissa (E) already taken"),
        "{out}"
    );
    assert!(out.contains("tests: 2 OK, 0 NOOK"), "{out}");

    // Silenced the way real files do after a reuse= restart.
    let (code, out, _d) = run_text(
        &format!("DEBUT(IGNORE_ALARM='FONCT0_62')\n{TURNING_TABLE}"),
        &[],
    );
    assert_eq!(code, Some(0), "{out}");
    assert!(!out.contains("FONCT0_62"), "{out}");
}

#[test]
fn erreur_alarme_exception_turns_alarms_into_errors() {
    let (code, out, _d) = run_text(
        &format!("DEBUT(ERREUR=_F(ALARME='EXCEPTION'))\n{TURNING_TABLE}"),
        &[],
    );
    assert_eq!(code, Some(2), "{out}");
    assert!(
        out.contains("alarm <FONCT0_62> raised as an error"),
        "{out}"
    );
    assert!(out.contains("IGNORE_ALARM='FONCT0_62'"), "{out}");
    assert!(
        out.contains("line 4") || out.contains("case.comm:4"),
        "{out}"
    );

    // An alarm the file silences is not raised; the other keywords are reported as
    // having no effect, in both spellings of CODE.
    for code_kw in ["CODE=_F(NIV_PUB_WEB='INTERNET')", "CODE='OUI'"] {
        let (code, out, _d) = run_text(
            &format!(
                "DEBUT({code_kw}, ERREUR=_F(ALARME='EXCEPTION', ERREUR_F='EXCEPTION'),\n      \
                 DEBUG=_F(SDVERI='OUI'), IGNORE_ALARM='FONCT0_62')\n{TURNING_TABLE}"
            ),
            &[],
        );
        assert_eq!(code, Some(0), "{out}");
        assert!(out.contains("ERREUR/ALARME='EXCEPTION'"), "{out}");
        let kw = if code_kw.starts_with("CODE=_F") {
            "CODE/NIV_PUB_WEB"
        } else {
            "CODE"
        };
        assert!(
            out.contains(&format!(
                "keyword(s) {kw}, ERREUR/ERREUR_F, DEBUG/SDVERI accepted for compatibility, no effect"
            )),
            "{out}"
        );
    }
}

#[test]
fn debut_keywords_are_validated() {
    let (code, out) = check_text("DEBUT(ERREUR=_F(ALARME='EXCEPTIONS'))\nFIN()\n", &[]);
    assert_eq!(code, Some(2), "{out}");
    assert!(out.contains("ALARME") && out.contains("EXCEPTION"), "{out}");
    let (code, out) = check_text("DEBUT(DEBUG=_F(SDVERI='PEUT-ETRE'))\nFIN()\n", &[]);
    assert_eq!(code, Some(2), "{out}");
    assert!(out.contains("SDVERI"), "{out}");
}

/// A value "computed by another code": 1 + 5e-5 against our exact 1.
const OTHER_CODE_VALUE: &str = "\
DEBUT()
T = CREA_TABLE(LISTE=(_F(PARA='A', LISTE_R=(1.,)), _F(PARA='N', LISTE_I=(3,)),))
TEST_TABLE(TABLE=T, NOM_PARA='A', TYPE_TEST='MAX', VALE_CALC=1.00005)
TEST_TABLE(TABLE=T, NOM_PARA='A', TYPE_TEST='MAX', VALE_CALC=1.00005, TOLE_MACHINE=1.e-3)
TEST_TABLE(TABLE=T, NOM_PARA='N', TYPE_TEST='MAX', VALE_CALC_I=3)
FIN()
";

#[test]
fn tole_machine_widens_non_regression_tolerances_only_when_asked() {
    // Code_Aster's semantics by default: 5e-5 is outside TOLE_MACHINE = 1e-6.
    let (code, out, _d) = run_text(OTHER_CODE_VALUE, &[]);
    assert_eq!(code, Some(1), "{out}");
    assert!(out.contains("tests: 2 OK, 1 NOOK"), "{out}");
    assert!(!out.contains("--tole-machine"), "{out}");

    let (code, out, _d) = run_text(OTHER_CODE_VALUE, &["--tole-machine", "1e-4"]);
    assert_eq!(code, Some(0), "{out}");
    assert!(out.contains("tests: 3 OK, 0 NOOK"), "{out}");
    // Said at the start, on the widened line only, and in the FIN summary.
    assert!(out.starts_with("--tole-machine 1e-4"), "{out}");
    assert_eq!(out.matches("(--tole-machine)").count(), 1, "{out}");
    let fin = &out[out.find("=== FIN ===").unwrap()..];
    assert!(
        fin.contains("--tole-machine 1e-4: every real non-regression"),
        "{out}"
    );

    let (code, out, _d) = run_text(OTHER_CODE_VALUE, &["--tole-machine=-1"]);
    assert_eq!(code, Some(2), "{out}");
    assert!(out.contains("not a positive real"), "{out}");
}

#[test]
fn check_takes_a_poursuite_file_with_its_database() {
    let dir = tempfile::tempdir().unwrap();
    let db = dir.path().join("study.db");
    let first = bin()
        .arg("run")
        .arg(case("poursuite_debut.comm"))
        .arg("--db")
        .arg(&db)
        .output()
        .unwrap();
    assert_eq!(first.status.code(), Some(0), "{}", text(&first));
    // Without the database: one clear error, not one per name.
    let o = bin()
        .arg("check")
        .arg(case("poursuite_suite.comm"))
        .output()
        .unwrap();
    let out = text(&o);
    assert_eq!(o.status.code(), Some(2), "{out}");
    assert!(out.contains("1 error(s)") && out.contains("--db"), "{out}");
    // With it: the concepts of the first run are known, and checked.
    let o = bin()
        .arg("check")
        .arg(case("poursuite_suite.comm"))
        .arg("--db")
        .arg(&db)
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(0), "{}", text(&o));
}

#[test]
fn check_reports_restart_and_mesh_misuse_statically() {
    // reuse= must name the table the restart starts from; a first run cannot reuse one.
    let (code, out) = check_text(
        "DEBUT()\nT = CREA_TABLE(LISTE=_F(PARA='A', LISTE_R=(1.,)))\n\
         T2 = CALC_TABLE(reuse=T, TABLE=T, ACTION=_F(OPERATION='FILTRE', NOM_PARA='A', VALE=1.))\n\
         U = CREA_TABLE(LISTE=_F(PARA='A', LISTE_R=(2.,)))\n\
         T = CALC_TABLE(reuse=T, TABLE=U, ACTION=_F(OPERATION='FILTRE', NOM_PARA='A', VALE=2.))\n\
         M = LIRE_MAILLAGE(FORMAT='MED')\nFIN()\n",
        &[],
    );
    assert_eq!(code, Some(2), "{out}");
    assert!(out.contains("reuse=T but TABLE=U"), "{out}");
    // No mesh beside the file, unit 20 not mapped.
    assert!(out.contains("no mesh file for unit 20"), "{out}");
    assert!(out.contains("2 error(s)"), "{out}");

    // A .mail file read as MED.
    let dir = tempfile::tempdir().unwrap();
    let comm = dir.path().join("m.comm");
    std::fs::write(
        &comm,
        "DEBUT()\nM = LIRE_MAILLAGE(FORMAT='MED', UNITE=20)\nFIN()\n",
    )
    .unwrap();
    let o = bin()
        .arg("check")
        .arg(&comm)
        .arg("--unit")
        .arg(format!("20={}", case("sdnd122a.mail").display()))
        .output()
        .unwrap();
    let out = text(&o);
    assert_eq!(o.status.code(), Some(2), "{out}");
    assert!(out.contains("is not a MED file"), "{out}");
}

#[test]
fn check_knows_the_rows_of_a_stored_table() {
    let dir = tempfile::tempdir().unwrap();
    let db = dir.path().join("r.db");
    let first = bin()
        .arg("run")
        .arg(case("hard/restart_part1.comm"))
        .arg("--db")
        .arg(&db)
        .output()
        .unwrap();
    assert_eq!(first.status.code(), Some(0), "{}", text(&first));
    let o = bin()
        .arg("check")
        .arg(case("hard/restart_part2.comm"))
        .arg("--db")
        .arg(&db)
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(0), "{}", text(&o));
    let src = std::fs::read_to_string(case("hard/restart_part2.comm")).unwrap();
    let bad = dir.path().join("bad.comm");
    std::fs::write(&bad, src.replace("NUME_ORDRE=5,", "NUME_ORDRE=500,")).unwrap();
    let o = bin()
        .arg("check")
        .arg(&bad)
        .arg("--db")
        .arg(&db)
        .output()
        .unwrap();
    let out = text(&o);
    assert_eq!(o.status.code(), Some(2), "{out}");
    assert!(
        out.contains("NUME_ORDRE 500 is not a row of table MNL"),
        "{out}"
    );
}

#[test]
fn code_aster_operators_we_do_not_implement_say_so() {
    let (code, out, _d) = run_text(
        "DEBUT()\nINFO_MODE(MATR_RIGI=K, MATR_MASS=M, FREQ=(0., 10.))\nFIN()\n",
        &[],
    );
    assert_eq!(code, Some(2), "{out}");
    assert!(
        out.contains("INFO_MODE is a Code_Aster operator that aster-nl does not support"),
        "{out}"
    );
    assert!(out.contains("CALC_MODES prints the frequencies"), "{out}");
    let (code, out) = check_text("DEBUT()\nDEFI_FICHIER(UNITE=38)\nFIN()\n", &[]);
    assert_eq!(code, Some(2), "{out}");
    assert!(
        out.contains("DEFI_FICHIER is a Code_Aster operator"),
        "{out}"
    );
}

/// Runs a testcase with its database in `dir`; asserts exit 0, no NOOK, `n_ok` tests OK.
fn run_case(name: &str, dir: &Path, n_ok: usize) -> PathBuf {
    let db = dir.join(format!("{}.db", name.replace('/', "_")));
    let o = bin()
        .arg("run")
        .arg(case(name))
        .arg("--db")
        .arg(&db)
        .output()
        .unwrap();
    let out = text(&o);
    assert_eq!(o.status.code(), Some(0), "{name}:\n{out}");
    assert!(
        out.contains(&format!("tests: {n_ok} OK, 0 NOOK")),
        "{name}:\n{out}"
    );
    db
}

fn energy_frequency(db: &Path) -> Vec<(i64, f64, f64)> {
    let c = rusqlite::Connection::open(db).unwrap();
    let mut st = c
        .prepare("SELECT NUME_ORDRE, ENERGIE, FREQUENCE FROM MNL ORDER BY NUME_ORDRE")
        .unwrap();
    st.query_map([], |r| Ok((r.get(0)?, r.get(1)?, r.get(2)?)))
        .unwrap()
        .map(Result::unwrap)
        .collect()
}

/// The same system written with the 13.x spellings (elements on nodes through the
/// model's own point cells, MODE_ITER_SIMULT, NOEUD=/MAILLE=) and with the 15-17.x ones
/// (CREA_POI1 groups sharing one cell per node, CALC_MODES, GROUP_NO=/GROUP_MA=) gives
/// the same branch, row for row.
#[test]
fn spellings_13x_and_17x_give_the_same_branch() {
    let dir = tempfile::tempdir().unwrap();
    let a = energy_frequency(&run_case("compat_2dof_13.comm", dir.path(), 7));
    let b = energy_frequency(&run_case("compat_2dof_17.comm", dir.path(), 7));
    assert_eq!(a.len(), 25);
    assert_eq!(a.len(), b.len());
    for ((n, e, f), (m, e2, f2)) in a.iter().zip(&b) {
        assert_eq!(n, m);
        assert!((e - e2).abs() <= 1e-12 * e.abs(), "row {n}: {e} {e2}");
        assert!((f - f2).abs() <= 1e-12 * f.abs(), "row {n}: {f} {f2}");
    }
}

#[test]
fn med_mesh_beam_against_the_closed_form() {
    let dir = tempfile::tempdir().unwrap();
    run_case("beam_med.comm", dir.path(), 6);
}

/// The sdnd122a system in a 13.x PAR_LOT='NON' file: CODE=_F(NOM=...), MODI_MAILLAGE
/// DEFORME/ALEA, MODE_ITER_SIMULT, and the reference computed in Python from
/// T.EXTR_TABLE() / tab.ENERGIE[0] / T['FREQUENCE', 1].
#[test]
fn par_lot_non_file_reads_its_table_back() {
    let dir = tempfile::tempdir().unwrap();
    let o = bin()
        .arg("run")
        .arg(case("compat_par_lot.comm"))
        .arg("--db")
        .arg(dir.path().join("c.db"))
        .output()
        .unwrap();
    let out = text(&o);
    assert_eq!(o.status.code(), Some(0), "{out}");
    assert!(out.contains("tests: 6 OK, 0 NOOK"), "{out}");
    assert!(
        out.contains("DEFORME/ALEA=1e-8: 2 node(s) moved at random"),
        "{out}"
    );
    assert!(out.contains("rows in the energy window:"), "{out}");
}

/// Under ERREUR=_F(ALARME='EXCEPTION') an alarm of aster-nl's own (here DEFI_GROUP's note
/// that a GROUP_NO exists, on the second TOUT_GROUP_MA) stays an alarm: Code_Aster would not stop the file there.
#[test]
fn own_alarms_do_not_stop_an_exception_file() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::copy(case("compat_par_lot.mail"), dir.path().join("case.mail")).unwrap();
    let path = dir.path().join("case.comm");
    std::fs::write(
        &path,
        "DEBUT(ERREUR=_F(ALARME='EXCEPTION'))\nMA = LIRE_MAILLAGE(FORMAT='ASTER')\n\
         MA = DEFI_GROUP(reuse=MA, MAILLAGE=MA, CREA_GROUP_NO=_F(TOUT_GROUP_MA='OUI'))\n\
         MA = DEFI_GROUP(reuse=MA, MAILLAGE=MA, CREA_GROUP_NO=_F(TOUT_GROUP_MA='OUI'))\nFIN()\n",
    )
    .unwrap();
    let o = bin().arg("run").arg(&path).output().unwrap();
    let out = text(&o);
    assert_eq!(o.status.code(), Some(0), "{out}");
    assert!(out.contains("<A> <DEFI_GROUP_EXISTS>"), "{out}");
    assert!(out.contains("applies to Code_Aster's alarms only"), "{out}");
}

/// Code_Aster's newer test files wrap the commands in its Python API: code_aster.init()
/// for DEBUT, `MA = code_aster.Mesh(); MA.readAsterMeshFile("file")` for LIRE_MAILLAGE,
/// `test = code_aster.TestCase()` and its assertions for TEST_*. testcases/compat_python_api
/// is nnm_wall written so (its mesh read by name, its rows checked against the exact
/// frequency of the nonsmooth wall by assertAlmostEqual, a function concept called at an
/// abscissa): all 8 assertions OK, and the
/// table equal to nnm_wall's to round-off (the same commands). A failing assertion is a
/// NOOK (exit 1); a mesh file that does not exist is an error naming it (exit 2).
#[test]
fn python_api_files_run_as_their_commands() {
    let dir = tempfile::tempdir().unwrap();
    let api = run_case("compat_python_api.comm", dir.path(), 8);
    let wall = run_case("nnm_wall.comm", dir.path(), 6);
    let (a, b) = (energy_frequency(&api), energy_frequency(&wall));
    assert_eq!(a.len(), b.len());
    for (x, y) in a.iter().zip(&b) {
        assert!((x.2 / y.2 - 1.0).abs() < 1e-12, "{x:?} {y:?}");
    }
    let base = std::fs::read_to_string(case("compat_python_api.comm")).unwrap();
    let failing = base.replacen("delta=1.e-4)", "delta=1.e-9)", 1);
    let failing_line = 1 + base
        .lines()
        .position(|l| l.contains("delta=1.e-4)"))
        .unwrap();
    let nook = format!(" NOOK test.assertAlmostEqual (line {failing_line})");
    assert_ne!(failing, base);
    let missing = base.replacen("\"nnm_wall.mail\"", "\"no_such_mesh.mail\"", 1);
    assert_ne!(missing, base);
    for (edited, code, want) in [
        (failing, 1, nook.as_str()),
        (missing, 2, "the file 'no_such_mesh.mail' does not exist"),
    ] {
        let sub = tempfile::tempdir().unwrap();
        std::fs::write(sub.path().join("api.comm"), edited).unwrap();
        std::fs::copy(case("nnm_wall.mail"), sub.path().join("nnm_wall.mail")).unwrap();
        let o = bin()
            .arg("run")
            .arg(sub.path().join("api.comm"))
            .output()
            .unwrap();
        let out = text(&o);
        assert_eq!(o.status.code(), Some(code), "{out}");
        assert!(out.contains(want), "{want}:\n{out}");
    }
}
