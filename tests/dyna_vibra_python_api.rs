//! The Python API of a DYNA_VIBRA result (R.LIST_ARCH(), R.FORCE_NORMALE(i),
//! R.VARI_INTERNE(i)), RECU_FONCTION's PARA_Y='VINTi', np.savetxt and IMPR_FONCTION's
//! FORMAT='XMGRACE' through the binary: `testcases/dyna_vibra_python_api.comm` checks
//! itself against the exact solution inside a contact; here, the files it writes hold
//! what the database holds, and a wrong call is an error naming its line.

use std::path::{Path, PathBuf};

mod support;
use support::{case, run_file};

const NAME: &str = "dyna_vibra_python_api";

/// The testcase copied into a fresh directory (it writes its files beside itself), with
/// `edit` applied to its text: (directory, command file).
fn copy_case(edit: &dyn Fn(&str) -> String) -> (tempfile::TempDir, PathBuf) {
    let dir = tempfile::tempdir().unwrap();
    let text = std::fs::read_to_string(case(&format!("{NAME}.comm"))).unwrap();
    let comm = dir.path().join(format!("{NAME}.comm"));
    std::fs::write(&comm, edit(&text)).unwrap();
    std::fs::copy(
        case(&format!("{NAME}.mail")),
        dir.path().join(format!("{NAME}.mail")),
    )
    .unwrap();
    (dir, comm)
}

/// The shock's columns `cols` at every archived instant, from the study `db`.
fn stored(db: &Path, cols: &str) -> Vec<Vec<f64>> {
    let conn = rusqlite::Connection::open(db).unwrap();
    let mut stmt = conn
        .prepare(&format!("SELECT {cols} FROM GE_CHOC ORDER BY NUME_ORDRE"))
        .unwrap();
    let n = cols.split(',').count();
    stmt.query_map([], |r| (0..n).map(|j| r.get::<_, f64>(j)).collect())
        .unwrap()
        .collect::<Result<Vec<Vec<f64>>, _>>()
        .unwrap()
}

#[test]
fn the_files_written_hold_the_stored_internal_variables_exactly() {
    let (dir, comm) = copy_case(&|t| t.to_string());
    let db = dir.path().join("case.db");
    let (code, out) = run_file(&comm, &db);
    assert_eq!(code, Some(0), "{out}");
    assert!(out.contains("tests: 24 OK, 0 NOOK"), "{out}");
    // VARI_INTERNE's description, as Code_Aster prints it with describe=True.
    assert!(
        out.contains("DIS_CHOC non linearity (index=1, AB)"),
        "{out}"
    );
    // np.savetxt: one line per archived instant, 20 numbers in %.18e, which read back
    // exactly the values of the shocks' table (FN, node 1's and node 2's local y, VN).
    let csv = std::fs::read_to_string(dir.path().join(format!("{NAME}.csv"))).unwrap();
    let rows: Vec<Vec<f64>> = csv
        .lines()
        .map(|l| l.split(',').map(|v| v.parse().unwrap()).collect())
        .collect();
    assert_eq!(rows.len(), 2);
    assert!(rows.iter().all(|r| r.len() == 20));
    assert!(csv
        .lines()
        .all(|l| l.split(',').all(|v| v.contains("e+") || v.contains("e-"))));
    let db_rows = stored(&db, "FN, DYLOC, DYLOC_N2, VN");
    for (r, s) in rows.iter().zip(&db_rows) {
        assert_eq!([r[0], r[4], r[7], r[9]], [s[0], s[1], s[2], s[3]]);
        assert!(r[0] > 70.0, "in contact: {r:?}");
    }
    // XMGRACE: FN against INST, the same numbers.
    let agr = std::fs::read_to_string(dir.path().join("fort.29")).unwrap();
    assert!(agr.contains("@    s0 legend \"FN\""), "{agr}");
    let points: Vec<Vec<f64>> = agr
        .lines()
        .filter(|l| !l.starts_with(['@', '#', '&']))
        .map(|l| l.split(' ').map(|v| v.parse().unwrap()).collect())
        .collect();
    let fn_rows = stored(&db, "INST, FN");
    assert_eq!(points, fn_rows);
}

/// Each wrong call stops the run with an error at its line that says what is expected.
#[test]
fn a_wrong_call_is_an_error_naming_its_line_and_what_is_expected() {
    let cases: [(&str, &str, &str, &[&str]); 5] = [
        (
            "FNOR = GE.FORCE_NORMALE(1)",
            "FNOR = GE.FORCE_NORMALE(2)",
            "FNOR = GE.FORCE_NORMALE(2)",
            &["between 1 and 1", "AB"],
        ),
        (
            "INST = GE.LIST_ARCH()",
            "INST = GE.LIST_INST()",
            "INST = GE.LIST_INST()",
            &["not supported", "VARI_INTERNE(i, describe=...)"],
        ),
        (
            "VI = GE.VARI_INTERNE(1)",
            "VI = GE.VARI_INTERNE(1, details=True)",
            "VI = GE.VARI_INTERNE(1, details=True)",
            &["no argument 'details'", "inoli, describe"],
        ),
        (
            "delimiter=',')",
            "delimiter=',', fmt='%s')",
            "np.savetxt(",
            &["fmt='%s'", "printf conversion"],
        ),
        (
            "np.savetxt('dyna_vibra_python_api.csv'",
            "np.savetxt('dyna_vibra_python_api.comm'",
            "np.savetxt(",
            &["will not write over"],
        ),
    ];
    for (from, to, line_text, expected) in cases {
        let (dir, comm) = copy_case(&|t| {
            assert!(t.contains(from), "{from}");
            t.replace(from, to)
        });
        let text = std::fs::read_to_string(&comm).unwrap();
        let line = text.lines().position(|l| l.contains(line_text)).unwrap() + 1;
        let (code, out) = run_file(&comm, &dir.path().join("case.db"));
        assert_ne!(code, Some(0), "{to}: {out}");
        assert!(
            out.contains(&format!("{NAME}.comm:{line}:")),
            "{to}: line {line}\n{out}"
        );
        for e in expected {
            assert!(out.contains(e), "{to}: {e}\n{out}");
        }
        // The command file itself is never written over.
        assert_eq!(std::fs::read_to_string(&comm).unwrap(), text);
    }
}

/// PARA_Y='VINT21' (DIS_CHOC has 20) is refused, naming PARA_Y and the value (a VINTi
/// beyond FLAMBAGE's 11: src/ops/common/shock_vint.rs's tests).
#[test]
fn a_vint_beyond_the_law_names_para_y() {
    let (dir, comm) = copy_case(&|t| t.replace("PARA_Y='VINT8'", "PARA_Y='VINT21'"));
    let (code, out) = run_file(&comm, &dir.path().join("case.db"));
    assert_ne!(code, Some(0), "{out}");
    assert!(out.contains("PARA_Y") && out.contains("VINT21"), "{out}");
}
