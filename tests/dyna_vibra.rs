//! DYNA_VIBRA's chain through the binary: the transient cases of `testcases/` (each checked
//! there against an exact reference) and the errors a user meets, each naming its keyword.

use std::path::{Path, PathBuf};
use std::process::Command;

fn case(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("testcases")
        .join(name)
}

/// `aster-nl run comm --db db`: (exit code, output).
fn run_file(comm: &Path, db: &Path) -> (Option<i32>, String) {
    let o = Command::new(env!("CARGO_BIN_EXE_aster-nl"))
        .arg("run")
        .arg(comm)
        .arg("--db")
        .arg(db)
        .output()
        .unwrap();
    let out = format!(
        "{}{}",
        String::from_utf8_lossy(&o.stdout),
        String::from_utf8_lossy(&o.stderr)
    );
    (o.status.code(), out)
}

fn run_case(name: &str, tests: usize) -> String {
    let dir = tempfile::tempdir().unwrap();
    let (code, out) = run_file(&case(name), &dir.path().join("case.db"));
    assert_eq!(code, Some(0), "{name}:\n{out}");
    assert!(
        out.contains(&format!("tests: {tests} OK, 0 NOOK")),
        "{name}:\n{out}"
    );
    out
}

#[test]
fn the_impact_oscillator_matches_its_exact_solution_with_every_scheme() {
    let out = run_case("dyna_vibra_impact.comm", 27);
    // RUNGE_KUTTA_54 located the 12 onsets and 11 releases of the 0.5 s.
    assert!(out.contains("23 contact change(s) located"), "{out}");
}

#[test]
fn the_coulomb_oscillator_loses_two_c_per_half_swing_then_sticks() {
    run_case("dyna_vibra_friction.comm", 8);
}

#[test]
fn a_transient_started_on_a_nonlinear_mode_comes_back_after_each_period() {
    run_case("dyna_vibra_nnm_check.comm", 6);
}

/// The impact case cut after its obstacle, with `call` as its DYNA_VIBRA: (code, output),
/// and the database's concepts after the run.
fn run_impact_with(call: &str) -> (Option<i32>, String, Vec<String>) {
    let dir = tempfile::tempdir().unwrap();
    let text = std::fs::read_to_string(case("dyna_vibra_impact.comm")).unwrap();
    let head = text.split("TI = (").next().unwrap();
    let comm = dir.path().join("impact.comm");
    std::fs::copy(
        case("dyna_vibra_impact.mail"),
        dir.path().join("impact.mail"),
    )
    .unwrap();
    std::fs::write(&comm, format!("{head}\n{call}\nFIN()\n")).unwrap();
    let db = dir.path().join("case.db");
    let (code, out) = run_file(&comm, &db);
    let conn = rusqlite::Connection::open(&db).unwrap();
    let mut stmt = conn
        .prepare("SELECT name FROM concepts ORDER BY name")
        .unwrap();
    let names = stmt
        .query_map([], |r| r.get(0))
        .unwrap()
        .collect::<Result<Vec<String>, _>>()
        .unwrap();
    (code, out, names)
}

const SHOCK: &str = "COMPORTEMENT=_F(RELATION='DIS_CHOC', GROUP_NO_1='NO1', OBSTACLE=PLAN, \
                     ORIG_OBST=(-1., 0., 0.), NORM_OBST=(0., 1., 0.), JEU=1. + G, RIGI_NOR=KN)";

#[test]
fn diff_centre_with_a_step_longer_than_the_contact_allows_is_refused_with_the_limit() {
    // omega of the contact: sqrt((k + KN)/m) = 1005 rad/s, limit 2/omega = 1.99e-3 s.
    let call = format!(
        "TR = DYNA_VIBRA(TYPE_CALCUL='TRAN', BASE_CALCUL='GENE', MATR_MASS=MGEN, \
         MATR_RIGI=KGEN, ETAT_INIT=_F(VITE=VGEN), INCREMENT=_F(INST_FIN=0.5, PAS=5.e-3), {SHOCK})"
    );
    let (code, out, names) = run_impact_with(&call);
    assert_ne!(code, Some(0), "{out}");
    assert!(out.contains("PAS") && out.contains("1.99"), "{out}");
    assert!(
        !names.iter().any(|n| n == "TR"),
        "a failed operator leaves nothing: {names:?}"
    );
}

#[test]
fn newmark_with_a_step_longer_than_a_contact_is_refused_and_a_coarse_step_warned() {
    // The contact: sqrt(KN/m) = 1000 rad/s, about pi/1000 = 3.1e-3 s long.
    let run = |scheme: &str, pas: &str| {
        run_impact_with(&format!(
            "TR = DYNA_VIBRA(TYPE_CALCUL='TRAN', BASE_CALCUL='GENE', MATR_MASS=MGEN, \
             MATR_RIGI=KGEN, SCHEMA_TEMPS=_F(SCHEMA='{scheme}'), ETAT_INIT=_F(VITE=VGEN), \
             INCREMENT=_F(INST_FIN=0.05, PAS={pas}), {SHOCK})"
        ))
    };
    let (code, out, names) = run("NEWMARK", "5.e-3");
    assert_ne!(code, Some(0), "{out}");
    assert!(out.contains("INCREMENT/PAS") && out.contains("1e-3"), "{out}");
    assert!(!names.iter().any(|n| n == "TR"), "{names:?}");
    // 6.3 steps per contact: accepted, with the alarm naming the step to take.
    for scheme in ["NEWMARK", "DIFF_CENTRE"] {
        let (code, out, _) = run(scheme, "5.e-4");
        assert_eq!(code, Some(0), "{out}");
        assert!(out.contains("<DYNA_VIBRA_1>") && out.contains("6.3 steps"), "{out}");
    }
    // 10 steps per contact or more: no alarm.
    let (code, out, _) = run("NEWMARK", "2.5e-4");
    assert_eq!(code, Some(0), "{out}");
    assert!(!out.contains("DYNA_VIBRA_1"), "{out}");
}

#[test]
fn a_shock_on_a_node_the_mesh_lacks_names_the_keyword() {
    let call = format!(
        "TR = DYNA_VIBRA(TYPE_CALCUL='TRAN', BASE_CALCUL='GENE', MATR_MASS=MGEN, \
         MATR_RIGI=KGEN, ETAT_INIT=_F(VITE=VGEN), INCREMENT=_F(INST_FIN=0.01, PAS=1.e-5), {})",
        SHOCK.replace("GROUP_NO_1='NO1'", "NOEUD_1='NO9'")
    );
    let (code, out, _) = run_impact_with(&call);
    assert_ne!(code, Some(0), "{out}");
    assert!(out.contains("NO9") && out.contains("NOEUD_1"), "{out}");
}

#[test]
fn assembled_matrices_on_a_modal_basis_are_refused_with_the_route() {
    let call = format!(
        "TR = DYNA_VIBRA(TYPE_CALCUL='TRAN', BASE_CALCUL='GENE', MATR_MASS=MASS, \
         MATR_RIGI=RIGI, INCREMENT=_F(INST_FIN=0.01, PAS=1.e-5), {SHOCK})"
    );
    let (code, out, _) = run_impact_with(&call);
    assert_ne!(code, Some(0), "{out}");
    assert!(
        out.contains("PROJ_MATR_BASE") && out.contains("MATR_MASS"),
        "{out}"
    );
}

#[test]
fn a_two_node_obstacle_without_its_second_node_is_refused() {
    let call = format!(
        "BI = DEFI_OBSTACLE(TYPE='BI_PLAN_Y')\n\
         TR = DYNA_VIBRA(TYPE_CALCUL='TRAN', BASE_CALCUL='GENE', MATR_MASS=MGEN, \
         MATR_RIGI=KGEN, INCREMENT=_F(INST_FIN=0.01, PAS=1.e-5), {})",
        SHOCK.replace("OBSTACLE=PLAN", "OBSTACLE=BI")
    );
    let (code, out, _) = run_impact_with(&call);
    assert_ne!(code, Some(0), "{out}");
    assert!(out.contains("NOEUD_2"), "{out}");
}

#[test]
fn rest_gene_phys_outside_the_archived_interval_is_refused() {
    let call = format!(
        "TR = DYNA_VIBRA(TYPE_CALCUL='TRAN', BASE_CALCUL='GENE', MATR_MASS=MGEN, \
         MATR_RIGI=KGEN, ETAT_INIT=_F(VITE=VGEN), INCREMENT=_F(INST_FIN=0.01, PAS=1.e-5), {SHOCK})\n\
         PH = REST_GENE_PHYS(RESU_GENE=TR, NOM_CHAM='DEPL', INST=0.02, INTERPOL='LIN')"
    );
    let (code, out, names) = run_impact_with(&call);
    assert_ne!(code, Some(0), "{out}");
    assert!(out.contains("INST") && out.contains("outside"), "{out}");
    assert!(names.iter().any(|n| n == "TR") && names.iter().any(|n| n == "TR_CHOC"));
}
