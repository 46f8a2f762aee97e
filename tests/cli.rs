//! The `aster-nl` binary on the command files of `testcases/`, as a user runs them.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn bin() -> Command {
    Command::new(env!("CARGO_BIN_EXE_aster-nl"))
}

fn case(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("testcases")
        .join(name)
}

fn text(o: &Output) -> String {
    format!(
        "{}{}",
        String::from_utf8_lossy(&o.stdout),
        String::from_utf8_lossy(&o.stderr)
    )
}

/// `aster-nl run COMM --db DB`, its output.
fn run_with_db(comm: impl AsRef<std::ffi::OsStr>, db: impl AsRef<std::ffi::OsStr>) -> Output {
    bin()
        .arg("run")
        .arg(comm)
        .arg("--db")
        .arg(db)
        .output()
        .unwrap()
}

/// Runs a self-checking case with its database in a temporary directory; returns the
/// output after asserting exit code 0, no NOOK and at least one OK.
fn run_ok(name: &str) -> String {
    let dir = tempfile::tempdir().unwrap();
    let o = run_with_db(case(name), dir.path().join("case.db"));
    let out = text(&o);
    assert_eq!(o.status.code(), Some(0), "{name}:\n{out}");
    assert!(!out.contains("NOOK "), "{name}:\n{out}");
    assert!(out.contains(" OK "), "{name} ran no test:\n{out}");
    out
}

#[test]
fn spring_chain_fixed_fixed() {
    let out = run_ok("chain_fixed_fixed.comm");
    assert!(out.contains("tests: 11 OK, 0 NOOK"), "{out}");
}

#[test]
fn spring_chain_fixed_free_with_ddl_impo() {
    run_ok("chain_fixed_free.comm");
}

#[test]
fn spring_chain_free_free_has_a_rigid_body_mode() {
    run_ok("chain_free_free.comm");
}

#[test]
fn cantilever_beam() {
    let out = run_ok("beam_cantilever.comm");
    assert!(out.contains("tests: 5 OK, 0 NOOK"), "{out}");
}

/// The FIN summary gives each operator's CPU and elapsed time, as Code_Aster's per-command
/// lines do: one line per operator that ran, with both figures as non-negative numbers.
#[test]
fn fin_summary_gives_cpu_and_elapsed_per_operator() {
    let out = run_ok("beam_cantilever.comm");
    assert!(
        out.contains("time per operator (CPU: user + system; elapsed):"),
        "{out}"
    );
    let line = out
        .lines()
        .find(|l| l.trim_start().starts_with("CALC_MODES ") && l.contains("call(s)"))
        .unwrap_or_else(|| panic!("no CALC_MODES timing line:\n{out}"));
    let words: Vec<&str> = line.split_whitespace().collect();
    let after = |key: &str| -> f64 {
        let i = words.iter().position(|w| *w == key).unwrap();
        words[i + 1].parse().unwrap()
    };
    assert!(after("CPU") >= 0.0 && after("elapsed") >= 0.0, "{line}");
}

#[test]
fn simply_supported_beam() {
    run_ok("beam_simply_supported.comm");
}

#[test]
fn tables_and_functions() {
    let out = run_ok("tables_functions.comm");
    assert!(out.contains("tests: 12 OK, 0 NOOK"), "{out}");
}

#[test]
fn poursuite_sees_the_concepts_of_the_first_run() {
    let dir = tempfile::tempdir().unwrap();
    let db = dir.path().join("study.db");
    let first = bin()
        .args(["run"])
        .arg(case("poursuite_debut.comm"))
        .arg("--db")
        .arg(&db)
        .output()
        .unwrap();
    assert_eq!(first.status.code(), Some(0), "{}", text(&first));
    let second = bin()
        .args(["run"])
        .arg(case("poursuite_suite.comm"))
        .arg("--db")
        .arg(&db)
        .output()
        .unwrap();
    let out = text(&second);
    assert_eq!(second.status.code(), Some(0), "{out}");
    assert!(out.contains("continuing"), "{out}");
    assert!(out.contains("tests: 2 OK, 0 NOOK"), "{out}");
}

#[test]
fn poursuite_without_a_database_is_a_clear_error() {
    let dir = tempfile::tempdir().unwrap();
    let o = run_with_db(case("poursuite_suite.comm"), dir.path().join("missing.db"));
    let out = text(&o);
    assert_eq!(o.status.code(), Some(2), "{out}");
    assert!(out.contains("no database to continue"), "{out}");
}

#[test]
fn syntax_error_names_file_line_and_column() {
    let dir = tempfile::tempdir().unwrap();
    let o = run_with_db(case("errors/syntax.comm"), dir.path().join("x.db"));
    let out = text(&o);
    assert_eq!(o.status.code(), Some(2), "{out}");
    assert!(out.contains("syntax.comm:2:15"), "{out}");
    assert!(out.contains("was never closed"), "{out}");
}

#[test]
fn check_reports_every_catalog_error_of_a_file() {
    let o = bin()
        .arg("check")
        .arg(case("errors/catalog.comm"))
        .output()
        .unwrap();
    let out = text(&o);
    assert_eq!(o.status.code(), Some(2), "{out}");
    assert!(out.contains("3 error(s)"), "{out}");
    assert!(out.contains("did you mean TITRE?"), "{out}");
    assert!(out.contains("catalog.comm:4:22"), "{out}");
    assert!(out.contains("expected a real"), "{out}");
}

#[test]
fn check_accepts_every_runnable_case() {
    // Every command file of testcases/ and testcases/hard/ but the deliberate errors and the
    // two POURSUITE continuations (their concepts come from an earlier run's database).
    let mut checked = 0;
    for dir in [case(""), case("hard")] {
        for entry in std::fs::read_dir(&dir).unwrap() {
            let path = entry.unwrap().path();
            let name = path.file_name().unwrap().to_string_lossy().to_string();
            if !name.ends_with(".comm")
                || name == "poursuite_suite.comm"
                || name == "restart_part2.comm"
            {
                continue;
            }
            let o = bin().arg("check").arg(&path).output().unwrap();
            assert_eq!(o.status.code(), Some(0), "{name}: {}", text(&o));
            checked += 1;
        }
    }
    assert!(checked > 20, "only {checked} files checked");
}

#[test]
fn check_carries_values_only_a_run_knows() {
    // EXTR_TABLE returns a value only a run computes: `check` must follow it through
    // arithmetic, math functions, indexing and loops without inventing an error, and still
    // report a real one after it.
    let dir = tempfile::tempdir().unwrap();
    let comm = dir.path().join("unknown.comm");
    std::fs::write(
        &comm,
        "DEBUT()\nfrom math import *\n\
         T = CREA_TABLE(LISTE=_F(PARA='A', LISTE_R=(4., 9.)))\n\
         X = EXTR_TABLE(TABLE=T, TYPE_RESU='R', NOM_PARA='A', FILTRE=_F(NOM_PARA='A', VALE=4.))\n\
         Y = sqrt(-X - 1.)\n\
         L = (X, 2.*X)\n\
         for v in range(int(X)):\n    Z = L[v] + Y\n\
         TEST_TABLE(TABLE=T, NOM_PARA='A', TYPE_TEST='MAX', VALE_CALC=Z)\n\
         TEST_TABLE(TABLE=T, NOM_PARA='A', TYPE_TEST='MAXI', VALE_CALC=Z)\n\
         FIN()\n",
    )
    .unwrap();
    let o = bin().arg("check").arg(&comm).output().unwrap();
    let out = text(&o);
    assert_ne!(o.status.code(), Some(0), "{out}");
    assert!(out.contains("1 error(s)"), "{out}");
    assert!(out.contains("TYPE_TEST") && out.contains("MAXI"), "{out}");
}

/// sdnd122a's one-DOF model as a port from Code_Aster might start: `(comm, mesh)` written
/// into `dir`, the mesh beside the command file (read by `check` and by the run).
fn port_of_sdnd122a(dir: &Path, body: &str) -> PathBuf {
    let comm = dir.join("port.comm");
    std::fs::copy(case("sdnd122a.mail"), dir.join("port.mail")).unwrap();
    std::fs::write(&comm, body).unwrap();
    comm
}

const PORT_HEAD: &str = "DEBUT()\n\
     MAIL = LIRE_MAILLAGE(FORMAT='ASTER', UNITE=20)\n\
     MODELE = AFFE_MODELE(MAILLAGE=MAIL, AFFE=_F(GROUP_MA=('M1', 'P2'), PHENOMENE='MECANIQUE', \
     MODELISATION='DIS_T'))\n";

const PORT_MATRICES: &str = "ASSEMBLAGE(MODELE=MODELE, CARA_ELEM=CARA, CHAR_CINE=CL, \
     NUME_DDL=CO('NUMEDDL'), MATR_ASSE=(_F(MATRICE=CO('RIGIDITE'), OPTION='RIGI_MECA'), \
     _F(MATRICE=CO('MASSE'), OPTION='MASS_MECA')))\n\
     MODES = CALC_MODES(MATR_RIGI=RIGIDITE, MATR_MASS=MASSE, OPTION='BANDE', \
     CALC_FREQ=_F(FREQ=(0.01, 10.)))\n";

#[test]
fn check_goes_past_unsupported_operators_and_unknown_names() {
    // Before, `check` stopped at the first unknown (here MODEL, line 4): one error per try.
    let dir = tempfile::tempdir().unwrap();
    let body = format!(
        "{PORT_HEAD}\
         CARA = AFFE_CARA_ELEM(MODELE=MODEL, DISCRET=(_F(CARA='M_T_D_N', GROUP_MA='P2', VALE=1.0), \
         _F(CARA='K_T_D_L', GROUP_MA='M1', VALE=(10., 0., 0.), REPERE='GLOBAL')))\n\
         CL = AFFE_CHAR_CINE(MODELE=MODELE, MECA_IMPO=(_F(GROUP_NO='N1', DX=0., DY=0., DZ=0.), \
         _F(GROUP_NO='NO2', DY=0., DZ=0.)))\n\
         F = DEFI_NAPPE(NOM_PARA='X')\n\
         {PORT_MATRICES}\
         DYN = DYNA_NON_LINE(MODELE=MODELE, FONC=F)\n\
         MNL = MODE_NON_LINE(MATR_RIGI=RIGIDITE, MATR_MASS=MASSE, \
         ETAT_INIT=_F(MODE_LINE=MODES, NUME_ORDRE=1), \
         CHOC=_F(OBSTACLE='PLAN', GROUP_NO='N2', NOM_CMP='DX', JEU=-0.01, RIGI_NOR=50.), \
         RESOLUTION=_F(METHODE='EHMAN', NB_HARM_LINE=5, NB_HARM_NONL=100, NB_PAS_MAN=1, \
         NB_BRANCH=10))\n\
         INFO_MODE(MATR_RIGI=RIGIDITE, MATR_MASS=MASSE)\n\
         FIN()\n"
    );
    let comm = port_of_sdnd122a(dir.path(), &body);
    let o = bin().arg("check").arg(&comm).output().unwrap();
    let out = text(&o);
    assert_eq!(o.status.code(), Some(2), "{out}");
    // The misspelt NB_BRANCH also leaves NB_BRANCHE missing: 8 errors in all.
    assert!(out.contains("8 error(s)"), "{out}");
    for expected in [
        "port.comm:4:",
        "name 'MODEL' is not defined",
        "did you mean 'MODELE'?",
        "port.comm:5:",
        "GROUP_NO 'NO2' is not in the mesh",
        "did you mean 'N2'? the mesh has 2 GROUP_NO(s): N1, N2",
        "DEFI_NAPPE is a Code_Aster operator that aster-nl does not support",
        "DYNA_NON_LINE is a Code_Aster operator that aster-nl does not support",
        "MODE_NON_LINE/CHOC/JEU: expected a value > 0.0, got -0.01",
        "unknown keyword NB_BRANCH",
        "did you mean NB_BRANCHE?",
        "missing mandatory keyword NB_BRANCHE",
        "INFO_MODE is a Code_Aster operator that aster-nl does not support",
    ] {
        assert!(out.contains(expected), "{expected}:\n{out}");
    }
}

#[test]
fn a_misspelt_group_is_found_by_check_and_by_the_run_with_the_groups_listed() {
    let dir = tempfile::tempdir().unwrap();
    let body = format!(
        "{PORT_HEAD}\
         CARA = AFFE_CARA_ELEM(MODELE=MODELE, DISCRET=(_F(CARA='M_T_D_N', GROUP_MA='P2', VALE=1.0), \
         _F(CARA='K_T_D_L', GROUP_MA='M1', VALE=(10., 0., 0.), REPERE='GLOBAL')))\n\
         CL = AFFE_CHAR_CINE(MODELE=MODELE, MECA_IMPO=(_F(GROUP_NO='N1', DX=0., DY=0., DZ=0.), \
         _F(GROUP_NO='N2', DY=0., DZ=0.)))\n\
         {PORT_MATRICES}\
         MNL = MODE_NON_LINE(MATR_RIGI=RIGIDITE, MATR_MASS=MASSE, \
         ETAT_INIT=_F(MODE_LINE=MODES, NUME_ORDRE=1), \
         CHOC=_F(OBSTACLE='PLAN', GROUP_NO='NO2', NOM_CMP='DX', JEU=0.01, RIGI_NOR=50.), \
         RESOLUTION=_F(METHODE='EHMAN', NB_HARM_LINE=5, NB_HARM_NONL=20, NB_PAS_MAN=1, \
         NB_BRANCHE=2))\n\
         FIN()\n"
    );
    let comm = port_of_sdnd122a(dir.path(), &body);
    // `check` reads the mesh beside the file (before: OK, the name was invisible to it).
    let o = bin().arg("check").arg(&comm).output().unwrap();
    let out = text(&o);
    assert_eq!(o.status.code(), Some(2), "{out}");
    assert!(out.contains("1 error(s)"), "{out}");
    assert!(out.contains("GROUP_NO 'NO2' is not in the mesh"), "{out}");
    assert!(out.contains("MODE_NON_LINE/CHOC/GROUP_NO"), "{out}");
    assert!(
        out.contains("did you mean 'N2'? the mesh has 2 GROUP_NO(s): N1, N2"),
        "{out}"
    );
    // The run's own error lists the groups and suggests (before: the message alone).
    let o = run_with_db(&comm, dir.path().join("port.db"));
    let out = text(&o);
    assert_eq!(o.status.code(), Some(2), "{out}");
    assert!(out.contains("mesh MAIL has no GROUP_NO 'NO2'"), "{out}");
    assert!(
        out.contains("did you mean 'N2'? the mesh has 2 GROUP_NO(s): N1, N2"),
        "{out}"
    );
}

#[test]
fn failed_operator_keeps_earlier_concepts() {
    let dir = tempfile::tempdir().unwrap();
    let db = dir.path().join("r.db");
    let o = run_with_db(case("errors/runtime.comm"), &db);
    let out = text(&o);
    assert_eq!(o.status.code(), Some(2), "{out}");
    assert!(out.contains("no mesh file for unit 33"), "{out}");
    let t = bin().arg("tables").arg(&db).output().unwrap();
    let listing = text(&t);
    assert_eq!(t.status.code(), Some(0), "{listing}");
    assert!(listing.contains("table_sdaster"), "{listing}");
    assert!(!listing.contains("MAIL "), "{listing}");
}

#[test]
fn nook_test_gives_exit_code_1() {
    let dir = tempfile::tempdir().unwrap();
    let o = run_with_db(case("errors/nook.comm"), dir.path().join("n.db"));
    let out = text(&o);
    assert_eq!(o.status.code(), Some(1), "{out}");
    assert!(out.contains("NOOK"), "{out}");
}

#[test]
fn export_file_maps_the_mesh_unit() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::copy(
        case("chain_fixed_fixed.comm"),
        dir.path().join("study.comm"),
    )
    .unwrap();
    std::fs::copy(
        case("chain_fixed_fixed.mail"),
        dir.path().join("other_name.mail"),
    )
    .unwrap();
    std::fs::write(
        dir.path().join("study.export"),
        "P actions make_etude\nF comm study.comm D 1\nF mail other_name.mail D 20\nF mess study.mess R 6\n",
    )
    .unwrap();
    let o = bin()
        .arg("run")
        .arg(dir.path().join("study.export"))
        .output()
        .unwrap();
    let out = text(&o);
    assert_eq!(o.status.code(), Some(0), "{out}");
    assert!(out.contains("tests: 11 OK, 0 NOOK"), "{out}");
    assert!(dir.path().join("study.db").exists());
}

#[test]
fn catalog_prints_an_operator() {
    let o = bin().args(["catalog", "MODE_NON_LINE"]).output().unwrap();
    let out = text(&o);
    assert_eq!(o.status.code(), Some(0), "{out}");
    for word in ["NB_HARM_NONL", "201", "PARA_REGUL", "CHOC", "EHMAN"] {
        assert!(out.contains(word), "{word} missing:\n{out}");
    }
    let o = bin().args(["catalog", "NOT_AN_OPERATOR"]).output().unwrap();
    assert_eq!(o.status.code(), Some(2));
}

#[test]
fn sdnd122a_nonlinear_mode_end_to_end() {
    let out = run_ok("sdnd122a.comm");
    assert!(out.contains("tests: 6 OK, 0 NOOK"), "{out}");
    assert!(out.contains("MODE_NON_LINE MNL: 105 point(s)"), "{out}");
    assert!(
        out.contains("SELECT NUME_ORDRE, ENERGIE, FREQUENCE FROM MNL"),
        "{out}"
    );
}

#[test]
fn sdnd122c_restart_into_a_new_concept() {
    let out = run_ok("sdnd122c.comm");
    assert!(out.contains("tests: 6 OK, 0 NOOK"), "{out}");
}

#[test]
fn sdnd122b_ddl_impo_and_row_1000_is_stable() {
    let out = run_ok("sdnd122b.comm");
    assert!(out.contains("MODE_NON_LINE MNL: 1050 point(s)"), "{out}");
    assert!(
        out.contains("CALC_STABILITE MNL: 1 STABLE, 0 INSTABLE"),
        "{out}"
    );
}

#[test]
fn symmetric_pitchfork_flagged_by_mode_non_line_where_calc_stabilite_switches() {
    let out = run_ok("bifurcation_2dof.comm");
    assert!(out.contains("tests: 11 OK, 0 NOOK"), "{out}");
}

#[test]
fn two_dof_anti_phase_mode_loses_stability_between_its_energy_extrema() {
    let out = run_ok("stability_2dof.comm");
    assert!(out.contains("tests: 5 OK, 0 NOOK"), "{out}");
    assert!(!out.contains("CALC_STABILITE_1"), "{out}");
}

#[test]
fn calc_stabilite_warns_when_the_monodromy_is_too_coarse_to_judge() {
    // stability_2dof's first branches, but 20 Newmark steps per period instead of 1000:
    // the monodromy no longer maps the orbit's velocity onto itself within TOLERANCE.
    let dir = tempfile::tempdir().unwrap();
    let src = std::fs::read_to_string(case("stability_2dof.comm")).unwrap();
    let cut = src.find("IMPR_TABLE(").unwrap();
    let comm = src[..cut]
        .replace("NB_BRANCHE=40", "NB_BRANCHE=4")
        .replace("NB_INST=1000", "NB_INST=20")
        + "FIN()\n";
    std::fs::write(dir.path().join("coarse.comm"), comm).unwrap();
    std::fs::copy(case("stability_2dof.mail"), dir.path().join("coarse.mail")).unwrap();
    let o = bin()
        .arg("run")
        .arg(dir.path().join("coarse.comm"))
        .output()
        .unwrap();
    let out = text(&o);
    assert_eq!(o.status.code(), Some(0), "{out}");
    assert!(out.contains("<A> <CALC_STABILITE_1>"), "{out}");
    assert!(out.contains("NB_INST"), "{out}");
}

/// A CERCLE shock with one component: the catalog (NOM_CMP's form follows OBSTACLE) stops
/// the call with one message naming the keyword, the line and the rule; the operator's own
/// count check never adds a second one.
#[test]
fn cercle_shock_with_one_component_is_one_clear_error() {
    let dir = tempfile::tempdir().unwrap();
    let hard = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("testcases")
        .join("hard");
    let src = std::fs::read_to_string(hard.join("cercle_centre.comm")).unwrap();
    assert!(src.contains("NOM_CMP=('DX', 'DY')"));
    let comm = dir.path().join("cercle_one.comm");
    std::fs::write(&comm, src.replace("NOM_CMP=('DX', 'DY')", "NOM_CMP='DX'")).unwrap();
    std::fs::copy(
        hard.join("cercle_centre.mail"),
        dir.path().join("cercle_one.mail"),
    )
    .unwrap();
    let o = run_with_db(&comm, dir.path().join("case.db"));
    let out = text(&o);
    assert_eq!(o.status.code(), Some(2), "{out}");
    // One error, reported once: the keyword path starts its message.
    assert_eq!(
        out.matches("MODE_NON_LINE/CHOC/NOM_CMP:").count(),
        1,
        "{out}"
    );
    assert!(
        out.contains("MODE_NON_LINE/CHOC/NOM_CMP: expected 2 value(s) (a text), got 1"),
        "{out}"
    );
    assert!(out.contains("cercle_one.comm:39:"), "{out}");
    assert!(
        out.contains("NOM_CMP takes this form when OBSTACLE is 'CERCLE'"),
        "{out}"
    );
    // Not the operator's message on top of it.
    assert!(!out.contains("component(s) in NOM_CMP"), "{out}");
}

/// DIR_EVOLUTION (testcases/dir_evolution.comm): +1 from the linear mode goes down in
/// energy; a restart with +1 turns back against the stored direction of travel (up) and
/// retraces the same orbits; a restart with -1 goes on (up).
#[test]
fn dir_evolution_backward_then_restarts_against_and_along_the_travel() {
    let dir = tempfile::tempdir().unwrap();
    let db = dir.path().join("case.db");
    let o = run_with_db(case("dir_evolution.comm"), &db);
    let out = text(&o);
    assert_eq!(o.status.code(), Some(0), "{out}");
    assert!(out.contains("tests: 4 OK, 0 NOOK"), "{out}");
    assert!(
        out.contains("restart from MNL row 80: DIR_EVOLUTION=1 goes back against")
            && out.contains("restart from MNL2 row 20: DIR_EVOLUTION=-1 goes on in"),
        "{out}"
    );
    let c = rusqlite::Connection::open(&db).unwrap();
    let rows = |t: &str| -> Vec<(f64, f64)> {
        let mut st = c
            .prepare(&format!(
                "SELECT ENERGIE, FREQUENCE FROM {t} ORDER BY NUME_ORDRE"
            ))
            .unwrap();
        st.query_map([], |r| Ok((r.get(0)?, r.get(1)?)))
            .unwrap()
            .map(|r| r.unwrap())
            .collect()
    };
    let (down, up, on) = (rows("MNL"), rows("MNL2"), rows("MNL3"));
    let falls = |v: &[(f64, f64)]| v.windows(2).all(|w| w[1].0 < w[0].0);
    let rises = |v: &[(f64, f64)]| v.windows(2).all(|w| w[1].0 > w[0].0);
    // The start (COEF_AMPL=1: amplitude JEU) has the linear energy ½·k·JEU² = 5e-4.
    assert!(falls(&down) && down[0].0 < 5e-4, "{down:?}");
    assert!(rises(&up) && up[0].0 > down[79].0, "{up:?}");
    assert!(rises(&on) && on[0].0 > up[19].0, "{on:?}");
    // MNL2 climbs back through the energies MNL came down: the same orbits, so the same
    // frequency at equal energy, to the LIN interpolation error of MNL's 80 rows (measured
    // at most 1.8e-7; 8.7e-6 with 8 rows: it shrinks as the row spacing squared; a different
    // orbit family would differ at first order).
    let mut compared = 0;
    for &(e, f) in up.iter().filter(|r| r.0 < down[0].0) {
        let w = down
            .windows(2)
            .find(|w| w[1].0 <= e && e <= w[0].0)
            .unwrap();
        let fl = w[1].1 + (e - w[1].0) / (w[0].0 - w[1].0) * (w[0].1 - w[1].1);
        assert!((f / fl - 1.0).abs() < 1e-6, "E {e}: {f} vs {fl}");
        compared += 1;
    }
    assert!(compared >= 3, "{compared}");
}

/// The U-tube of testcases/utube.comm (10 POU_D_E elements, two centred CERCLE rings, H_l 1,
/// H_nl 201, 10 branches): the .comm checks CALC_MODES, the residuals and the low-amplitude
/// end against independent eigen-solutions (5 tests). Here: the tube vibrates out of the
/// plane of the U, through the ring centres (DX of the ring nodes zero), and the CERCLE
/// table is the BI_PLAN one at equal ENERGIE. The two laws are the same function pointwise;
/// their harmonic balances truncate it differently (the ring's force series is λ·d, a
/// product with the one-harmonic displacement): measured up to 3.0e-5 apart in FREQUENCE
/// (log-log interpolation between BI_PLAN rows), growing with the depth of contact
/// (1.5e-5 at row 80, 2.0e-5 at row 90, 3.0e-5 at row 100), asserted 5e-5. Into contact: FREQUENCE
/// rises 2.0 % above the linear 3.7763 Hz (asserted > 1.5 %).
#[test]
fn utube_rings_through_their_centres_match_the_planes() {
    let dir = tempfile::tempdir().unwrap();
    let db = dir.path().join("case.db");
    let o = run_with_db(case("utube.comm"), &db);
    let out = text(&o);
    assert_eq!(o.status.code(), Some(0), "{out}");
    assert!(out.contains("tests: 5 OK, 0 NOOK"), "{out}");
    let c = rusqlite::Connection::open(&db).unwrap();
    let rows = |t: &str| -> Vec<(f64, f64)> {
        let mut st = c
            .prepare(&format!(
                "SELECT ENERGIE, FREQUENCE FROM {t} ORDER BY NUME_ORDRE"
            ))
            .unwrap();
        st.query_map([], |r| Ok((r.get(0)?, r.get(1)?)))
            .unwrap()
            .map(|r| r.unwrap())
            .collect()
    };
    let (ring, planes) = (rows("MNL"), rows("BIP"));
    assert_eq!((ring.len(), planes.len()), (100, 100));
    let at = |v: &[(f64, f64)], e: f64| {
        v.windows(2).find(|w| w[0].0 <= e && e <= w[1].0).map(|w| {
            let t = (e.ln() - w[0].0.ln()) / (w[1].0.ln() - w[0].0.ln());
            (w[0].1.ln() + t * (w[1].1.ln() - w[0].1.ln())).exp()
        })
    };
    let (mut compared, mut worst) = (0, 0.0f64);
    for &(e, f) in &ring {
        if let Some(fp) = at(&planes, e) {
            worst = worst.max((f / fp - 1.0).abs());
            compared += 1;
        }
    }
    println!("U-tube: rings vs planes over {compared} rows: worst {worst:.2e}");
    assert!(compared > 90 && worst < 5e-5, "{compared} {worst:e}");
    let top = ring.iter().map(|r| r.1).fold(0.0, f64::max);
    assert!(top > 3.7763268220 * 1.015, "{top}");
    let dx: f64 = c
        .query_row(
            "SELECT max(abs(COEF_C) + abs(COEF_S)) FROM mnl_fourier WHERE concept = 'MNL' \
             AND NOEUD IN ('N4', 'N8') AND NOM_CMP = 'DX'",
            [],
            |r| r.get(0),
        )
        .unwrap();
    assert!(dx < 1e-20, "{dx}");
}

/// TEST_RESU by INST finds its instant as Code_Aster does: to the second TOLE_MACHINE value
/// with the second CRITERE (one value: both), while the first values make the test.
/// sdnd122a's HIST has 256 instants over a period of 1.711203 s, both ends included:
/// instant 2 is at 6.71060e-3 s, and INST=6.7103e-3 is 4.5e-5 relative (3.0e-7 s) away.
#[test]
fn test_resu_finds_inst_with_the_second_tole_machine_and_critere() {
    let dir = tempfile::tempdir().unwrap();
    let src = std::fs::read_to_string(case("sdnd122a.comm")).unwrap();
    std::fs::copy(case("sdnd122a.mail"), dir.path().join("inst.mail")).unwrap();
    // |VITE| < 1 m/s on this orbit (amplitude about 0.02 m at 0.65 Hz): VALE_CALC=0 passes
    // at the tolerance 1 (a zero reference is compared absolutely).
    let test = |extra: &str| {
        format!(
            "TEST_RESU(RESU=_F(RESULTAT=HIST, INST=6.7103e-3, NOM_CHAM='VITE', NOEUD='N2', \
             NOM_CMP='DX', VALE_CALC=0.0, {extra}))\n"
        )
    };
    let run = |tests: &[String]| {
        let comm = dir.path().join("inst.comm");
        std::fs::write(
            &comm,
            src.replace("\nFIN()", &format!("\n{}FIN()", tests.concat())),
        )
        .unwrap();
        let _ = std::fs::remove_file(dir.path().join("case.db"));
        let o = run_with_db(&comm, dir.path().join("case.db"));
        (o.status.code(), text(&o))
    };
    let (code, out) = run(&[
        test("CRITERE=('ABSOLU', 'RELATIF'), TOLE_MACHINE=(1.0, 1.e-4)"),
        test("CRITERE=('ABSOLU', 'ABSOLU'), TOLE_MACHINE=(1.0, 1.e-6)"),
    ]);
    assert_eq!(code, Some(0), "{out}");
    assert!(out.contains("tests: 8 OK, 0 NOOK"), "{out}");
    // The instant is not within the default 1e-6 relative, nor 1e-7 s (one value: the
    // test's tolerance is the extraction's too).
    for extra in [
        "TOLE_MACHINE=1.e-6",
        "CRITERE='ABSOLU', TOLE_MACHINE=1.e-7",
        "CRITERE=('ABSOLU', 'ABSOLU'), TOLE_MACHINE=(1.0, 1.e-7)",
    ] {
        let (code, out) = run(&[test(extra)]);
        assert_eq!(code, Some(2), "{extra}:\n{out}");
        assert!(out.contains("at the requested instant"), "{extra}:\n{out}");
    }
}

/// sdnd122a's wall (m = 1, k = 10, JEU 0.01, RIGI_NOR 50), 20 rows, and what one test of
/// RECU_FONCTION on a dyna_trans needs: `extra` is appended before FIN. The mesh has a
/// group TOUS of both nodes. Returns the run's exit code, output and database.
fn recu_resultat_run(dir: &Path, extra: &str) -> (Option<i32>, String, PathBuf) {
    let src = std::fs::read_to_string(case("sdnd122a.comm")).unwrap();
    let cut = src.find("FREQ = RECU_FONCTION").unwrap();
    assert!(src.contains("NB_BRANCHE=105") && src.contains("COEF_AMPL=1."));
    // A second branch, started inside the gap (COEF_AMPL 0.5) with a regularisation of
    // 1e-10: its row 1 is before any contact.
    let mnl = &src[src.find("MNL = MODE_NON_LINE(").unwrap()..cut];
    let before_contact = mnl
        .replace("MNL = ", "MNL0 = ")
        .replace("COEF_AMPL=1.", "COEF_AMPL=0.5")
        .replace("PARA_REGUL=5.e-5", "PARA_REGUL=1.e-10")
        .replace("NB_BRANCHE=105", "NB_BRANCHE=1");
    let comm = format!(
        "{}{before_contact}{extra}\nFIN()\n",
        src[..cut].replace("NB_BRANCHE=105", "NB_BRANCHE=20")
    );
    std::fs::write(dir.join("recu.comm"), comm).unwrap();
    let mail = std::fs::read_to_string(case("sdnd122a.mail")).unwrap();
    let mail = mail.replacen(
        "GROUP_NO\n",
        "GROUP_NO\n TOUS\n N1 N2\nFINSF\nGROUP_NO\n",
        1,
    );
    std::fs::write(dir.join("recu.mail"), mail).unwrap();
    let db = dir.join("recu.db");
    let _ = std::fs::remove_file(&db);
    let o = run_with_db(dir.join("recu.comm"), &db);
    (o.status.code(), text(&o), db)
}

/// (INST, DEPL, VITE, ACCE) of N2 DX in the dyna_trans table `h`, by NUME_ORDRE.
fn history_rows(c: &rusqlite::Connection, h: &str) -> Vec<[f64; 4]> {
    let mut st = c
        .prepare(&format!(
            "SELECT INST, DEPL, VITE, ACCE FROM {h} WHERE NOEUD='N2' AND NOM_CMP='DX' \
             ORDER BY NUME_ORDRE"
        ))
        .unwrap();
    st.query_map([], |r| Ok([r.get(0)?, r.get(1)?, r.get(2)?, r.get(3)?]))
        .unwrap()
        .collect::<rusqlite::Result<_>>()
        .unwrap()
}

fn max_abs(v: impl Iterator<Item = f64>) -> f64 {
    v.fold(0.0, |m, x| m.max(x.abs()))
}

/// RECU_FONCTION(RESULTAT=H, NOM_CHAM=DEPL|VITE|ACCE, NOEUD|GROUP_NO, NOM_CMP) gives the
/// stored time history, INST against the component; ACCE is the second derivative of the
/// displacement, checked against ω²·DEPL where the motion is harmonic and against the
/// centred difference of VITE where it is not.
#[test]
fn recu_fonction_reads_depl_vite_acce_of_a_dyna_trans() {
    let dir = tempfile::tempdir().unwrap();
    let calls = "
H = REST_MODE_NONL(MODE_NON_LINE=MNL, NUME_ORDRE=20, NB_INST=1025)
H0 = REST_MODE_NONL(MODE_NON_LINE=MNL0, NUME_ORDRE=1, NB_INST=65)
FD = RECU_FONCTION(RESULTAT=H, NOM_CHAM='DEPL', NOEUD='N2', NOM_CMP='DX')
FV = RECU_FONCTION(RESULTAT=H, NOM_CHAM='VITE', GROUP_NO='N2', NOM_CMP='DX')
FA = RECU_FONCTION(RESULTAT=H, NOM_CHAM='ACCE', NOEUD='N2', NOM_CMP='DX',
                   INTERPOL='LIN', PROL_DROITE='CONSTANT')
";
    let (code, out, db) = recu_resultat_run(dir.path(), calls);
    assert_eq!(code, Some(0), "{out}");
    let c = rusqlite::Connection::open(&db).unwrap();
    let rows = history_rows(&c, "H");
    assert_eq!(rows.len(), 1025);

    // (a) Each function is its column of the table, instant by instant, named as in
    // Code_Aster (NOM_PARA='INST', NOM_RESU the component), with the catalog's defaults.
    for (f, col, prol_droite) in [
        ("FD", 1, "Exclu"),
        ("FV", 2, "Exclu"),
        ("FA", 3, "Constant"),
    ] {
        let json: String = c
            .query_row(
                "SELECT json FROM concept_data WHERE concept=?1 AND key='function'",
                [f],
                |r| r.get(0),
            )
            .unwrap();
        let v: serde_json::Value = serde_json::from_str(&json).unwrap();
        assert_eq!(
            (v["nom_para"].as_str(), v["nom_resu"].as_str()),
            (Some("INST"), Some("DX"))
        );
        assert_eq!(v["prol_gauche"], "Exclu");
        assert_eq!(v["prol_droite"], prol_droite, "{f}");
        let xs: Vec<f64> = serde_json::from_value(v["x"].clone()).unwrap();
        let ys: Vec<f64> = serde_json::from_value(v["y"].clone()).unwrap();
        assert_eq!(xs, rows.iter().map(|r| r[0]).collect::<Vec<_>>(), "{f}");
        assert_eq!(ys, rows.iter().map(|r| r[col]).collect::<Vec<_>>(), "{f}");
    }
    // ... and TEST_RESU (by NOEUD and by GROUP_NO) and TEST_FONCTION read the same values.
    let k = 300;
    let [t, d, v, a] = rows[k - 1];
    let tests = format!(
        "{calls}
TEST_RESU(RESU=(_F(RESULTAT=H, NUME_ORDRE={k}, NOM_CHAM='DEPL', NOEUD='N2', NOM_CMP='DX', VALE_CALC={d:e}, TOLE_MACHINE=1.e-12),
                _F(RESULTAT=H, NUME_ORDRE={k}, NOM_CHAM='VITE', GROUP_NO='N2', NOM_CMP='DX', VALE_CALC={v:e}, TOLE_MACHINE=1.e-12),
                _F(RESULTAT=H, NUME_ORDRE={k}, NOM_CHAM='ACCE', GROUP_NO='N2', NOM_CMP='DX', VALE_CALC={a:e}, TOLE_MACHINE=1.e-12)))
TEST_FONCTION(VALEUR=(_F(FONCTION=FD, VALE_PARA={t:e}, VALE_CALC={d:e}, TOLE_MACHINE=1.e-12),
                      _F(FONCTION=FV, VALE_PARA={t:e}, VALE_CALC={v:e}, TOLE_MACHINE=1.e-12),
                      _F(FONCTION=FA, VALE_PARA={t:e}, VALE_CALC={a:e}, TOLE_MACHINE=1.e-12)))
"
    );
    let (code, out, _) = recu_resultat_run(dir.path(), &tests);
    assert_eq!(code, Some(0), "{out}");
    assert!(out.contains("tests: 8 OK, 0 NOOK"), "{out}");

    // (b) Before contact (MNL0 row 1) the motion is harmonic: ACCE = −ω²·DEPL, ω from the
    // table's FREQUENCE. Not to round-off: inside the gap the regularised PLAN law still
    // pushes with f ≈ η/(g − u), η = PARA_REGUL·k·g² = 1e-13 here, about 3e-9·k·A at this
    // amplitude (A = 0.0084, g − A = 0.0016); its effect on ü + ω²u is below that, so
    // 1e-8·max|ACCE| bounds it while any error in the derivative or in its scale (ω², the
    // units) is of order 1.
    let c = rusqlite::Connection::open(&db).unwrap();
    let f0: f64 = c
        .query_row("SELECT FREQUENCE FROM MNL0 WHERE NUME_ORDRE=1", [], |r| {
            r.get(0)
        })
        .unwrap();
    let w2 = (2.0 * std::f64::consts::PI * f0).powi(2);
    let h0 = history_rows(&c, "H0");
    let amax0 = max_abs(h0.iter().map(|r| r[3]));
    assert!(
        max_abs(h0.iter().map(|r| r[1])) < 0.009,
        "row 1 of MNL0 touches the wall"
    );
    for r in &h0 {
        assert!((r[3] + w2 * r[1]).abs() <= 1e-8 * amax0, "{r:?}, ω² = {w2}");
    }
    // In contact (MNL row 20, harmonics 0..5): the centred difference of VITE over
    // h = T/1024 differs from v' = ü by at most h²/6·max|v'''| (Taylor), and
    // max|v'''| = max|u''''| ≤ Σ_k (kω)⁴·|C_k| from the stored Fourier coefficients of u
    // (mnl_fourier); VITE is the velocity series, equal to u' to round-off at a converged
    // point, hence the 1e-9·max|ACCE| added for that.
    let f20: f64 = c
        .query_row("SELECT FREQUENCE FROM MNL WHERE NUME_ORDRE=20", [], |r| {
            r.get(0)
        })
        .unwrap();
    let w = 2.0 * std::f64::consts::PI * f20;
    let mut st = c
        .prepare(
            "SELECT HARM, COEF_C, COEF_S FROM mnl_fourier WHERE concept='MNL' AND \
             NUME_ORDRE=20 AND NOEUD='N2' AND NOM_CMP='DX'",
        )
        .unwrap();
    let m4: f64 = st
        .query_map([], |r| {
            Ok((
                r.get::<_, i64>(0)?,
                r.get::<_, f64>(1)?,
                r.get::<_, f64>(2)?,
            ))
        })
        .unwrap()
        .map(|x| x.unwrap())
        .map(|(k, cc, ss)| (k as f64 * w).powi(4) * cc.hypot(ss))
        .sum();
    let amax = max_abs(rows.iter().map(|r| r[3]));
    let h = rows[1][0] - rows[0][0];
    let bound = h * h / 6.0 * m4 + 1e-9 * amax;
    let mut worst: f64 = 0.0;
    for i in 1..rows.len() - 1 {
        let fd = (rows[i + 1][2] - rows[i - 1][2]) / (rows[i + 1][0] - rows[i - 1][0]);
        worst = worst.max((fd - rows[i][3]).abs());
    }
    assert!(
        worst <= bound,
        "centred difference {worst:e} > bound {bound:e}"
    );
    // The bound is tight enough to matter: 2e-5 of the acceleration here (the first
    // harmonic gives (ωh)²/6 = 6e-6, the 5th, 5⁴·ω⁴·|C_5|, most of the rest), far below a
    // wrong factor on any harmonic.
    assert!(bound < 1e-4 * amax, "{bound:e} vs {amax:e}");
    assert!(worst > 0.1 * bound, "{worst:e} vs {bound:e}");
}

/// RECU_FONCTION on a dyna_trans: a wrong node, group or component is one error naming
/// the keyword and what was expected.
#[test]
fn recu_fonction_on_a_dyna_trans_names_the_wrong_keyword() {
    let dir = tempfile::tempdir().unwrap();
    for (call, keyword, message) in [
        (
            "NOM_CHAM='DEPL', NOEUD='N9', NOM_CMP='DX'",
            "RECU_FONCTION/NOEUD",
            "mesh MAIL of H has no node 'N9'",
        ),
        (
            "NOM_CHAM='DEPL', GROUP_NO='TOUS', NOM_CMP='DX'",
            "RECU_FONCTION/GROUP_NO",
            "GROUP_NO 'TOUS' holds 2 nodes; RECU_FONCTION extracts the history of one node",
        ),
        (
            "NOM_CHAM='DEPL', GROUP_NO='NONE', NOM_CMP='DX'",
            "RECU_FONCTION/GROUP_NO",
            "mesh MAIL has no GROUP_NO 'NONE'",
        ),
        (
            "NOM_CHAM='VITE', NOEUD='N2', NOM_CMP='DY'",
            "RECU_FONCTION/NOM_CMP",
            "component DY of node N2 is blocked",
        ),
        (
            "NOM_CHAM='ACCE', NOEUD='N2', NOM_CMP='DRX'",
            "RECU_FONCTION/NOM_CMP",
            "node N2 has no component DRX in the model of H: H holds DX at N2",
        ),
    ] {
        let extra = format!(
            "H = REST_MODE_NONL(MODE_NON_LINE=MNL, NUME_ORDRE=2, NB_INST=8)\n\
             F = RECU_FONCTION(RESULTAT=H, {call})\n"
        );
        let (code, out, _) = recu_resultat_run(dir.path(), &extra);
        assert_eq!(code, Some(2), "{call}:\n{out}");
        assert!(
            out.contains(&format!("{keyword}: {message}")),
            "{call}:\n{out}"
        );
        assert_eq!(out.matches(" × ").count(), 1, "{call}:\n{out}");
    }
}

/// DETRUIRE of a MODE_NON_LINE result takes its CARA_CHOC sub-table (`MNL_CHOC`) with it,
/// naming that sub-table as well is not an error, and the name can then be computed again.
#[test]
fn detruire_of_a_mode_non_line_result_takes_its_shock_table() {
    let dir = tempfile::tempdir().unwrap();
    let src = std::fs::read_to_string(case("sdnd122a.comm")).unwrap();
    let head = &src[..src.find("FREQ = RECU_FONCTION").unwrap()];
    // A short run: the same model and law, fewer harmonics and branches.
    let short = head
        .replace("NB_HARM_NONL=200", "NB_HARM_NONL=40")
        .replace("NB_BRANCHE=105", "NB_BRANCHE=3");
    assert_ne!(short, head);
    let comm = dir.path().join("detr.comm");
    let body = format!(
        "{short}\nDETRUIRE(CONCEPT=_F(NOM=(MNL, MNL_CHOC)))\n\
         MNL = MODE_NON_LINE(MATR_RIGI=RIGIDITE, MATR_MASS=MASSE,\n\
         ETAT_INIT=_F(MODE_LINE=MODES, NUME_ORDRE=1, DIR_EVOLUTION=-1),\n\
         CHOC=_F(OBSTACLE='PLAN', GROUP_NO='N2', NOM_CMP='DX', JEU=0.01, RIGI_NOR=50.,\n\
         PARA_REGUL=5.e-5),\n\
         RESOLUTION=_F(NB_HARM_LINE=5, NB_HARM_NONL=40, NB_BRANCHE=2, NB_PAS_MAN=1))\n\
         DETRUIRE(CONCEPT=_F(NOM=MNL))\nFIN()\n"
    );
    std::fs::write(&comm, body).unwrap();
    std::fs::copy(case("sdnd122a.mail"), dir.path().join("detr.mail")).unwrap();
    let db = dir.path().join("case.db");
    let o = run_with_db(&comm, &db);
    let out = text(&o);
    assert_eq!(o.status.code(), Some(0), "{out}");
    let conn = rusqlite::Connection::open(&db).unwrap();
    let left: Vec<String> = conn
        .prepare("SELECT name FROM concepts WHERE name LIKE 'MNL%'")
        .unwrap()
        .query_map([], |r| r.get(0))
        .unwrap()
        .collect::<Result<_, _>>()
        .unwrap();
    assert!(left.is_empty(), "{left:?}\n{out}");
    let tables: i64 = conn
        .query_row(
            "SELECT count(*) FROM sqlite_master WHERE name IN ('MNL', 'MNL_CHOC')",
            [],
            |r| r.get(0),
        )
        .unwrap();
    assert_eq!(tables, 0, "{out}");
}

/// A nonlinear mode started from a rigid-body mode (the free–free chain's first, 0 Hz) is
/// refused at ETAT_INIT/NUME_ORDRE with the reason and what to do, not with a numerical
/// failure later; the next mode (the first elastic one) starts.
#[test]
fn a_start_from_a_rigid_body_mode_is_refused_with_its_reason() {
    let dir = tempfile::tempdir().unwrap();
    let src = std::fs::read_to_string(case("chain_free_free.comm")).unwrap();
    let with_mnl = |order: usize| {
        src.replace(
            "FIN()",
            &format!(
                "MNL = MODE_NON_LINE(MATR_RIGI=K, MATR_MASS=M,\n\
                 ETAT_INIT=_F(MODE_LINE=MODES, NUME_ORDRE={order}, COEF_AMPL=1.),\n\
                 CHOC=_F(OBSTACLE='PLAN', NOEUD='N4', NOM_CMP='DX', JEU=0.01, RIGI_NOR=500.,\n\
                 PARA_REGUL=1.e-4),\n\
                 RESOLUTION=_F(NB_HARM_LINE=3, NB_HARM_NONL=30, NB_BRANCHE=2, NB_PAS_MAN=1))\n\
                 FIN()"
            ),
        )
    };
    std::fs::copy(case("chain_free_free.mail"), dir.path().join("ff.mail")).unwrap();
    let comm = dir.path().join("ff.comm");
    std::fs::write(&comm, with_mnl(1)).unwrap();
    let o = run_with_db(&comm, dir.path().join("a.db"));
    let out = text(&o);
    assert_eq!(o.status.code(), Some(2), "{out}");
    assert!(out.contains("MODE_NON_LINE/ETAT_INIT/NUME_ORDRE"), "{out}");
    assert!(out.contains("rigid-body mode"), "{out}");
    assert!(out.contains("start from an elastic mode"), "{out}");
    std::fs::write(&comm, with_mnl(2)).unwrap();
    let o = run_with_db(&comm, dir.path().join("b.db"));
    let out = text(&o);
    assert_eq!(o.status.code(), Some(0), "{out}");
    assert!(out.contains("MODE_NON_LINE MNL: 2 point(s)"), "{out}");
}

/// A MODE_NON_LINE result's name given again to another operator's result drops its old
/// shock table too (as DETRUIRE would): `MNL_CHOC` must not outlive the `MNL` it described.
#[test]
fn a_mode_non_line_name_given_again_drops_its_shock_table() {
    let dir = tempfile::tempdir().unwrap();
    let src = std::fs::read_to_string(case("sdnd122a.comm")).unwrap();
    let head = &src[..src.find("FREQ = RECU_FONCTION").unwrap()];
    let short = head
        .replace("NB_HARM_NONL=200", "NB_HARM_NONL=40")
        .replace("NB_BRANCHE=105", "NB_BRANCHE=3");
    assert_ne!(short, head);
    let comm = dir.path().join("again.comm");
    let db = dir.path().join("case.db");
    std::fs::copy(case("sdnd122a.mail"), dir.path().join("again.mail")).unwrap();
    let shock_tables = |db: &std::path::Path| -> i64 {
        rusqlite::Connection::open(db)
            .unwrap()
            .query_row(
                "SELECT count(*) FROM concepts WHERE name = 'MNL_CHOC'",
                [],
                |r| r.get(0),
            )
            .unwrap()
    };
    // Without the new assignment the shock table is there (else the test says nothing).
    std::fs::write(&comm, format!("{short}\nFIN()\n")).unwrap();
    let o = run_with_db(&comm, &db);
    assert_eq!(o.status.code(), Some(0), "{}", text(&o));
    assert_eq!(shock_tables(&db), 1);
    std::fs::remove_file(&db).unwrap();
    let body = format!("{short}\nMNL = CREA_TABLE(LISTE=_F(PARA='X', LISTE_R=(1., 2.)))\nFIN()\n");
    std::fs::write(&comm, body).unwrap();
    let o = run_with_db(&comm, &db);
    let out = text(&o);
    assert_eq!(o.status.code(), Some(0), "{out}");
    assert_eq!(shock_tables(&db), 0, "{out}");
    let tables: i64 = rusqlite::Connection::open(&db)
        .unwrap()
        .query_row(
            "SELECT count(*) FROM sqlite_master WHERE name = 'MNL_CHOC'",
            [],
            |r| r.get(0),
        )
        .unwrap();
    assert_eq!(tables, 0, "{out}");
}

/// Copies `files` of testcases/ into a fresh directory (so that pictures and databases land
/// there) and runs the first one; returns the directory and the output.
fn run_copied(files: &[&str]) -> (tempfile::TempDir, Output) {
    let dir = tempfile::tempdir().unwrap();
    for f in files {
        std::fs::copy(case(f), dir.path().join(f)).unwrap();
    }
    let o = bin()
        .arg("run")
        .arg(dir.path().join(files[0]))
        .output()
        .unwrap();
    (dir, o)
}

/// A PNG the run drew: decodes, at least 640 x 480, and not one colour.
fn assert_picture(path: &Path) {
    let png = image::open(path).unwrap().to_rgb8();
    assert!(png.width() >= 640 && png.height() >= 480, "{path:?}");
    let first = png.get_pixel(0, 0);
    assert!(png.pixels().any(|p| p != first), "{path:?} is blank");
}

#[test]
fn the_readme_showcase_ends_clean_checked_against_the_exact_curve() {
    let (dir, o) = run_copied(&["nnm_wall.comm", "nnm_wall.mail"]);
    let out = text(&o);
    assert_eq!(o.status.code(), Some(0), "{out}");
    // TEST_RESU of the linear mode, then five rows against the exact frequency.
    assert!(out.contains("tests: 6 OK, 0 NOOK"), "{out}");
    assert_eq!(out.matches(" OK   ANALYTIQUE").count(), 6, "{out}");
    assert!(!out.contains("<A>"), "an alarm in the showcase:\n{out}");
    assert_picture(&dir.path().join("nnm_wall.png"));
}

#[test]
fn the_tutorial_file_checks_runs_clean_and_its_typo_example_says_what_the_tutorial_shows() {
    let (dir, o) = run_copied(&["tutorial_chain.comm", "tutorial_chain.mail"]);
    let out = text(&o);
    assert_eq!(o.status.code(), Some(0), "{out}");
    assert!(out.contains("tests: 4 OK, 0 NOOK"), "{out}");
    // The only alarms: MODE_NON_LINE_1's estimate where every force is resolved, about the
    // rows just past first contact (docs/tutorial.md, checklist point 2).
    assert_eq!(
        out.matches("<A>").count(),
        out.matches("<A> <MODE_NON_LINE_1> the contact forces are resolved")
            .count(),
        "an alarm in the tutorial's run:\n{out}"
    );
    assert_picture(&dir.path().join("tutorial_chain.png"));
    let comm = dir.path().join("tutorial_chain.comm");
    let o = bin().arg("check").arg(&comm).output().unwrap();
    assert_eq!(o.status.code(), Some(0), "{}", text(&o));
    // docs/tutorial.md, section 3: GROUP_NO='BOT' instead of 'BOUT'.
    let src = std::fs::read_to_string(&comm).unwrap();
    std::fs::write(&comm, src.replacen("GROUP_NO='BOUT'", "GROUP_NO='BOT'", 1)).unwrap();
    let o = bin().arg("check").arg(&comm).output().unwrap();
    let out = text(&o);
    assert_eq!(o.status.code(), Some(2), "{out}");
    let tutorial =
        std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("docs/tutorial.md"))
            .unwrap();
    for line in [
        "GROUP_NO 'BOT' is not in the mesh",
        "did you mean 'BOUT'? the mesh has 3 GROUP_NO(s): ENCASTRE, MASSES, BOUT",
    ] {
        assert!(out.contains(line), "{line}:\n{out}");
        assert!(tutorial.contains(line), "docs/tutorial.md lost: {line}");
    }
}

#[test]
fn the_readme_and_tutorial_commands_name_files_that_exist() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    for doc in ["README.md", "docs/tutorial.md"] {
        let text = std::fs::read_to_string(root.join(doc)).unwrap();
        let mut named = 0;
        for word in text.split_whitespace() {
            let word = word.trim_matches(|c: char| "`,;:()".contains(c));
            if word.starts_with("testcases/") && word.ends_with(".comm") {
                assert!(root.join(word).is_file(), "{doc} names {word}");
                named += 1;
            }
        }
        assert!(named > 0, "{doc} names no command file");
    }
}

/// IMPR_TABLE(FORMAT='PNG') of a REST_MODE_NONL time history (a `dyna_trans`), as the
/// README and IMPR_TABLE's catalog promise: `check` accepts it and the run draws the time
/// history and, with COURBE='PHASE', the phase portrait (before, the run stopped on
/// "HIST is a dyna_trans, not a table" after `check` had said OK). TEST_TABLE, whose
/// catalog takes a `dyna_trans` as well, reads it too.
#[test]
fn impr_table_draws_a_rest_mode_nonl_history() {
    let dir = tempfile::tempdir().unwrap();
    let src = std::fs::read_to_string(case("sdnd122a.comm")).unwrap();
    let head = &src[..src.find("FREQ = RECU_FONCTION").unwrap()];
    let short = head
        .replace("NB_HARM_NONL=200", "NB_HARM_NONL=40")
        .replace("NB_BRANCHE=105", "NB_BRANCHE=3");
    assert_ne!(short, head);
    let comm = dir.path().join("hist.comm");
    std::fs::write(
        &comm,
        format!(
            "{short}\nHIST = REST_MODE_NONL(MODE_NON_LINE=MNL, NUME_ORDRE=3, NB_INST=64)\n\
             IMPR_TABLE(TABLE=HIST, FORMAT='PNG', UNITE=31)\n\
             IMPR_TABLE(TABLE=HIST, FORMAT='PNG', COURBE='PHASE', FICHIER='phase.png')\n\
             IMPR_TABLE(TABLE=HIST, FORMAT='SVG', COURBE='PHASE', FICHIER='phase.svg')\n\
             TEST_TABLE(TABLE=HIST, NOM_PARA='NUME_ORDRE', TYPE_TEST='MAX', VALE_CALC_I=64)\n\
             FIN()\n"
        ),
    )
    .unwrap();
    std::fs::copy(case("sdnd122a.mail"), dir.path().join("hist.mail")).unwrap();
    let o = bin().arg("check").arg(&comm).output().unwrap();
    assert_eq!(o.status.code(), Some(0), "{}", text(&o));
    let o = run_with_db(&comm, dir.path().join("hist.db"));
    let out = text(&o);
    assert_eq!(o.status.code(), Some(0), "{out}");
    // The time history: DEPL and VITE panels stacked; the phase portrait: one panel.
    for (file, size) in [("fort.31.png", (1024, 1024)), ("phase.png", (1024, 768))] {
        let img = image::open(dir.path().join(file)).unwrap_or_else(|e| panic!("{file}: {e}"));
        assert_eq!((img.width(), img.height()), size, "{file}");
    }
    // 64 instants of the one free DOF (N2 DX): two panels, then one.
    assert!(out.contains("(128 points)"), "{out}");
    assert!(out.contains("(64 points)"), "{out}");
    // One orbit, one curve: the dyna_trans's NUME_ORDRE numbers its instants, not orbits
    // (a first version drew 64 one-point curves and a legend of 64 entries).
    let svg = std::fs::read_to_string(dir.path().join("phase.svg")).unwrap();
    assert!(
        svg.contains("DEPL N2 DX (m)") && svg.contains("VITE N2 DX (m/s)"),
        "{svg}"
    );
    assert!(!svg.contains("NUME_ORDRE 2"), "a legend entry per instant");
}

/// `--help` lists the user's commands only: `bench` and `study` (developer tools, see
/// docs/performance.md and docs/accuracy.md) are hidden but still run.
#[test]
fn help_hides_the_developer_tools() {
    let o = bin().arg("--help").output().unwrap();
    let out = text(&o);
    assert_eq!(o.status.code(), Some(0), "{out}");
    let commands: Vec<&str> = out
        .lines()
        .filter(|l| l.starts_with("  ") && !l.trim_start().starts_with('-'))
        .filter_map(|l| l.split_whitespace().next())
        .collect();
    for user in ["run", "check", "catalog", "tables", "sweep", "merge"] {
        assert!(commands.contains(&user), "{user} missing:\n{out}");
    }
    for dev in ["bench", "accuracy", "study", "bench-case", "sweep-task"] {
        assert!(!commands.contains(&dev), "{dev} listed:\n{out}");
    }
    for dev in ["bench", "accuracy", "study"] {
        let o = bin().args([dev, "--help"]).output().unwrap();
        assert_eq!(o.status.code(), Some(0), "{dev}: {}", text(&o));
        assert!(text(&o).contains("Usage: aster-nl"), "{}", text(&o));
    }
}

/// An older French study in Latin-1: read when its coding line says so (silently) or when it
/// is not UTF-8 (with a note naming the first such byte); a file that declares UTF-8 but is
/// not is an error at that byte. Before, every one was "stream did not contain valid UTF-8"
/// with no line.
#[test]
fn latin1_command_files_are_read_or_refused_at_the_first_bad_byte() {
    let dir = tempfile::tempdir().unwrap();
    let utf8 = std::fs::read_to_string(case("tables_functions.comm")).unwrap();
    // "# Résultats exacts : cœur du cas" in Latin-1 (é 0xE9) and Windows-1252 (œ 0x9C).
    let comment = b"# R\xE9sultats exacts : c\x9Cur du cas\n";
    let write = |name: &str, first: &[u8]| {
        let path = dir.path().join(name);
        std::fs::write(&path, [first, comment, utf8.as_bytes()].concat()).unwrap();
        path
    };
    let declared = write("declared.comm", b"# -*- coding: latin-1 -*-\n");
    let undeclared = write("undeclared.comm", b"");
    let wrong = write("wrong.comm", b"# -*- coding: utf-8 -*-\n");
    let o = run_with_db(&declared, dir.path().join("a.db"));
    assert_eq!(o.status.code(), Some(0), "{}", text(&o));
    assert!(!text(&o).contains("ENCODING_1"), "{}", text(&o));
    for sub in ["check", "run"] {
        let o = bin()
            .args([sub, undeclared.to_str().unwrap(), "--db"])
            .arg(dir.path().join(format!("{sub}.db")))
            .output()
            .unwrap();
        let out = text(&o);
        assert_eq!(o.status.code(), Some(0), "{sub}: {out}");
        assert!(
            out.contains("<A> <ENCODING_1>")
                && out.contains("undeclared.comm:1:4: byte 0xE9 is not UTF-8")
                && out.contains("coding: latin-1"),
            "{sub}: {out}"
        );
        let o = bin()
            .args([sub, wrong.to_str().unwrap(), "--db"])
            .arg(dir.path().join(format!("w{sub}.db")))
            .output()
            .unwrap();
        let out = text(&o);
        assert_eq!(o.status.code(), Some(2), "{sub}: {out}");
        assert!(out.contains("wrong.comm:2:4"), "{sub}: {out}");
        assert!(out.contains("byte 0xE9 is not UTF-8"), "{sub}: {out}");
    }
}

/// MODE_NON_LINE writes the rows of each branch to a live file beside the study
/// (docs/store.md, "Watching a running MODE_NON_LINE"): after the run it holds every row
/// of the study's table, in order, marked DONE; a user's file of that name is left alone
/// and the next name taken.
#[test]
fn mode_non_line_writes_a_live_file_a_reader_can_query() {
    let dir = tempfile::tempdir().unwrap();
    let src = std::fs::read_to_string(case("sdnd122a.comm")).unwrap();
    let head = &src[..src.find("FREQ = RECU_FONCTION").unwrap()];
    let short = head
        .replace("NB_HARM_NONL=200", "NB_HARM_NONL=40")
        .replace("NB_BRANCHE=105", "NB_BRANCHE=4");
    let comm = dir.path().join("live.comm");
    std::fs::write(&comm, format!("{short}\nFIN()\n")).unwrap();
    std::fs::copy(case("sdnd122a.mail"), dir.path().join("live.mail")).unwrap();
    let mine = dir.path().join("live.MNL.live.db");
    std::fs::write(&mine, "a user's notes").unwrap();
    let db = dir.path().join("live.db");
    let o = run_with_db(&comm, &db);
    let out = text(&o);
    assert_eq!(o.status.code(), Some(0), "{out}");
    assert_eq!(std::fs::read_to_string(&mine).unwrap(), "a user's notes");
    let live = dir.path().join("live.MNL.live2.db");
    assert!(out.contains("live.MNL.live2.db"), "{out}");
    let study = rusqlite::Connection::open(&db).unwrap();
    let want: Vec<(i64, f64, f64)> = study
        .prepare("SELECT NUME_ORDRE, FREQUENCE, ENERGIE FROM MNL ORDER BY NUME_ORDRE")
        .unwrap()
        .query_map([], |r| Ok((r.get(0)?, r.get(1)?, r.get(2)?)))
        .unwrap()
        .map(Result::unwrap)
        .collect();
    let c = rusqlite::Connection::open(&live).unwrap();
    let got: Vec<(i64, f64, f64)> = c
        .prepare("SELECT POINT, FREQUENCE, ENERGIE FROM MNL ORDER BY POINT")
        .unwrap()
        .query_map([], |r| Ok((r.get(0)?, r.get(1)?, r.get(2)?)))
        .unwrap()
        .map(Result::unwrap)
        .collect();
    assert!(want.len() >= 4, "{want:?}");
    assert_eq!(got, want);
    let (branches, state): (i64, String) = c
        .query_row("SELECT branches, state FROM aster_nl_live", [], |r| {
            Ok((r.get(0)?, r.get(1)?))
        })
        .unwrap();
    assert_eq!((branches, state.as_str()), (4, "DONE"));
}

/// The export's result lines as Code_Aster honours them: `F mess` gets everything the run
/// prints, `F resu` what IMPR_TABLE prints to its default unit 8, `R base` is where the
/// database goes. A message file that is the command file is refused before anything
/// runs, and the command file is left as it was.
#[test]
fn export_writes_the_message_and_results_files_and_the_base() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::copy(case("tables_functions.comm"), dir.path().join("t.comm")).unwrap();
    let export = dir.path().join("t.export");
    std::fs::write(
        &export,
        "P actions make_etude\nF comm t.comm D 1\nF mess out/t.mess R 6\n\
         F resu out/t.resu R 8\nR base out/base DC 0\n",
    )
    .unwrap();
    let o = bin().arg("run").arg(&export).output().unwrap();
    let out = text(&o);
    assert_eq!(o.status.code(), Some(0), "{out}");
    let mess = std::fs::read_to_string(dir.path().join("out/t.mess")).unwrap();
    assert!(mess.contains(" OK ") && mess.contains("FIN"), "{mess}");
    assert_eq!(mess, String::from_utf8_lossy(&o.stdout));
    let resu = std::fs::read_to_string(dir.path().join("out/t.resu")).unwrap();
    assert!(
        resu.contains("FREQUENCE") && resu.contains("ENERGIE"),
        "{resu}"
    );
    // The tables went to the results file, not to the message file.
    assert!(!mess.contains(&resu), "{mess}");
    assert!(dir.path().join("out/base/t.db").is_file());
    assert!(!dir.path().join("t.db").exists());

    let bad = dir.path().join("bad.export");
    std::fs::write(&bad, "F comm t.comm D 1\nF mess t.comm R 6\n").unwrap();
    let before = std::fs::read(dir.path().join("t.comm")).unwrap();
    let o = bin().arg("run").arg(&bad).output().unwrap();
    assert_eq!(o.status.code(), Some(2), "{}", text(&o));
    assert!(text(&o).contains("the command file"), "{}", text(&o));
    assert_eq!(std::fs::read(dir.path().join("t.comm")).unwrap(), before);
}
