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

#[allow(dead_code)]
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
