//! DYNA_VIBRA's chain through the binary: the transient cases of `testcases/` (each checked
//! there against an exact reference) and the errors a user meets, each naming its keyword.

use std::path::Path;
use std::process::Command;

mod support;
use support::{case, run_file};

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

/// A ring (CERCLE) hit on both sides by a node moving across its centre on isotropic
/// springs: the symmetric impact oscillator along the line of the start, exact in closed
/// form (testcases/dyna_vibra_ring.comm), on the modal basis of a degenerate pair and on
/// the physical DOFs.
#[test]
fn a_node_across_a_ring_matches_the_symmetric_impact_oscillator() {
    let out = run_case("dyna_vibra_ring.comm", 26);
    // Contacts begin at tA + j·T/2 (tA = 5.236e-3 s, T = 0.0269676 s) and last
    // tB = 3.012e-3 s: 37 of them within 0.5 s (the last from 0.4907 to 0.4937 s), each an
    // onset and a release, on each of the two runs.
    assert_eq!(
        out.matches("74 contact change(s) located").count(),
        2,
        "{out}"
    );
}

#[test]
fn the_coulomb_oscillator_loses_two_c_per_half_swing_then_sticks() {
    run_case("dyna_vibra_friction.comm", 23);
}

#[test]
fn devoge_on_a_two_node_coulomb_oscillator_and_a_damped_free_vibration() {
    run_case("dyna_vibra_devoge.comm", 14);
}

#[test]
fn a_slider_held_on_an_inclined_line_by_liaison_ddl_loses_two_c_per_half_swing() {
    run_case("dyna_vibra_slider_inclined.comm", 11);
}

#[test]
fn two_masses_meeting_through_a_bi_plan_match_the_impact_oscillator() {
    let out = run_case("dyna_vibra_two_masses.comm", 36);
    assert!(out.contains("23 contact change(s) located"), "{out}");
}

#[test]
fn a_damped_oscillator_under_a_step_force_by_coef_mult_and_fonc_mult() {
    run_case("dyna_vibra_forced.comm", 21);
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

/// LOCALISATION_CHOC='OUI' (aster-nl extension) keeps the event-located pairs: the steps
/// of RUNGE_KUTTA_54 and RUNGE_KUTTA_32 end at the 12 onsets and 11 releases of the impact
/// oscillator's 0.5 s; Code_Aster's algorithm, the default, locates none.
#[test]
fn localisation_choc_oui_locates_the_contact_changes() {
    let call = |name: &str, schema: &str, extra: &str| {
        format!(
            "{name} = DYNA_VIBRA(TYPE_CALCUL='TRAN', BASE_CALCUL='GENE', MATR_MASS=MGEN, \
             MATR_RIGI=KGEN, ETAT_INIT=_F(VITE=VGEN), \
             SCHEMA_TEMPS=_F(SCHEMA='{schema}', TOLERANCE=1.e-8{extra}), \
             INCREMENT=_F(INST_FIN=0.5, PAS=1.e-3), {SHOCK})\n"
        )
    };
    let calls = [
        call("LOC54", "RUNGE_KUTTA_54", ", LOCALISATION_CHOC='OUI'"),
        call("LOC32", "RUNGE_KUTTA_32", ", LOCALISATION_CHOC='OUI'"),
        call("CA54", "RUNGE_KUTTA_54", ""),
        call("CA32", "RUNGE_KUTTA_32", ", LOCALISATION_CHOC='NON'"),
    ]
    .concat();
    let (code, out, _) = run_impact_with(&calls);
    assert_eq!(code, Some(0), "{out}");
    for (name, located) in [("LOC54", 23), ("LOC32", 23), ("CA54", 0), ("CA32", 0)] {
        let line = out
            .lines()
            .find(|l| l.starts_with(&format!("DYNA_VIBRA {name}:")))
            .unwrap_or_else(|| panic!("{name}:\n{out}"));
        assert!(
            line.ends_with(&format!(" {located} contact change(s) located")),
            "{line}"
        );
    }
}

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
    assert!(
        out.contains("INCREMENT/PAS") && out.contains("1e-3"),
        "{out}"
    );
    assert!(!names.iter().any(|n| n == "TR"), "{names:?}");
    // 6.3 steps per contact: accepted, with the alarm naming the step to take.
    for scheme in ["NEWMARK", "DIFF_CENTRE"] {
        let (code, out, _) = run(scheme, "5.e-4");
        assert_eq!(code, Some(0), "{out}");
        assert!(
            out.contains("<DYNA_VIBRA_1>") && out.contains("6.3 steps"),
            "{out}"
        );
    }
    // 10 steps per contact or more: no alarm.
    let (code, out, _) = run("NEWMARK", "2.5e-4");
    assert_eq!(code, Some(0), "{out}");
    assert!(!out.contains("DYNA_VIBRA_1"), "{out}");
}

/// The rows (INST, NUME_CMP, DEPL, VITE) of table concept `name` in the database `db`.
fn rows(db: &Path, name: &str) -> Vec<(f64, i64, f64, f64)> {
    let conn = rusqlite::Connection::open(db).unwrap();
    let mut stmt = conn
        .prepare(&format!(
            "SELECT INST, NUME_CMP, DEPL, VITE FROM \"{name}\" ORDER BY NUME_ORDRE, NUME_CMP"
        ))
        .unwrap();
    stmt.query_map([], |r| Ok((r.get(0)?, r.get(1)?, r.get(2)?, r.get(3)?)))
        .unwrap()
        .collect::<Result<Vec<_>, _>>()
        .unwrap()
}

#[test]
fn dyna_tran_modal_in_either_spelling_is_dyna_vibra() {
    // Version 10's names (MASS_GENE, METHODE, AMOR_REDUIT, VITE_INIT_GENE, CHOC) and the
    // later ones (MATR_MASS, SCHEMA_TEMPS, AMOR_MODAL, VITE) give DYNA_VIBRA's DEVOGE run to
    // the bit, with its default TOLERANCE.
    let choc = SHOCK.replace("COMPORTEMENT=_F(RELATION='DIS_CHOC', ", "CHOC=_F(");
    let dir = tempfile::tempdir().unwrap();
    let text = std::fs::read_to_string(case("dyna_vibra_impact.comm")).unwrap();
    let head = text.split("TI = (").next().unwrap();
    std::fs::copy(
        case("dyna_vibra_impact.mail"),
        dir.path().join("impact.mail"),
    )
    .unwrap();
    let comm = dir.path().join("impact.comm");
    std::fs::write(
        &comm,
        format!(
            "{head}\n\
             A = DYNA_TRAN_MODAL(MASS_GENE=MGEN, RIGI_GENE=KGEN, METHODE='DEVOGE', AMOR_REDUIT=0.01, \
             ETAT_INIT=_F(VITE_INIT_GENE=VGEN), INCREMENT=_F(INST_FIN=0.05, PAS=1.e-4), {choc})\n\
             B = DYNA_TRAN_MODAL(MATR_MASS=MGEN, MATR_RIGI=KGEN, SCHEMA_TEMPS=_F(SCHEMA='DEVOGE'), \
             AMOR_MODAL=_F(AMOR_REDUIT=0.01), ETAT_INIT=_F(VITE=VGEN), \
             INCREMENT=_F(INST_FIN=0.05, PAS=1.e-4), {choc})\n\
             C = DYNA_VIBRA(TYPE_CALCUL='TRAN', BASE_CALCUL='GENE', MATR_MASS=MGEN, MATR_RIGI=KGEN, \
             SCHEMA_TEMPS=_F(SCHEMA='DEVOGE'), AMOR_MODAL=_F(AMOR_REDUIT=0.01), \
             ETAT_INIT=_F(VITE=VGEN), INCREMENT=_F(INST_FIN=0.05, PAS=1.e-4), {SHOCK})\n\
             FIN()\n"
        ),
    )
    .unwrap();
    let db = dir.path().join("case.db");
    let (code, out) = run_file(&comm, &db);
    assert_eq!(code, Some(0), "{out}");
    let c = rows(&db, "C");
    assert!(c.len() > 10, "{}", c.len());
    assert_eq!(rows(&db, "A"), c);
    assert_eq!(rows(&db, "B"), c);
}

#[test]
fn a_dyna_tran_modal_error_names_the_keyword_as_written() {
    let call = "A = DYNA_TRAN_MODAL(MASS_GENE=MASS, RIGI_GENE=KGEN, METHODE='EULER', \
                INCREMENT=_F(INST_FIN=0.05, PAS=1.e-5))";
    let (code, out, _) = run_impact_with(call);
    assert_ne!(code, Some(0), "{out}");
    // MASS is an assembled matrix: the catalog of DYNA_TRAN_MODAL refuses it by its name.
    assert!(out.contains("MASS_GENE"), "{out}");
    let call = format!(
        "A = DYNA_TRAN_MODAL(MASS_GENE=MGEN, RIGI_GENE=KGEN, METHODE='EULER', \
         ETAT_INIT=_F(VITE_INIT_GENE=VGEN), INCREMENT=_F(INST_FIN=0.05, PAS=5.e-3), {})",
        SHOCK.replace("COMPORTEMENT=_F(RELATION='DIS_CHOC', ", "CHOC=_F(")
    );
    let (code, out, _) = run_impact_with(&call);
    assert_ne!(code, Some(0), "{out}");
    assert!(out.contains("DYNA_TRAN_MODAL/INCREMENT/PAS"), "{out}");
}

#[test]
fn a_run_of_more_steps_than_nb_pas_maxi_is_refused_before_it_starts() {
    // 1e12 steps: refused at once, naming the count, instead of running for days.
    let call = format!(
        "TR = DYNA_VIBRA(TYPE_CALCUL='TRAN', BASE_CALCUL='GENE', MATR_MASS=MGEN, \
         MATR_RIGI=KGEN, SCHEMA_TEMPS=_F(SCHEMA='NEWMARK'), ETAT_INIT=_F(VITE=VGEN), \
         INCREMENT=_F(INST_FIN=1.e7, PAS=1.e-5), ARCHIVAGE=_F(PAS_ARCH=1000000000), {SHOCK})"
    );
    let (code, out, names) = run_impact_with(&call);
    assert_ne!(code, Some(0), "{out}");
    assert!(
        out.contains("1e12 steps") && out.contains("NB_PAS_MAXI"),
        "{out}"
    );
    assert!(!names.iter().any(|n| n == "TR"), "{names:?}");
    // The adaptive schemes stop at NB_PAS_MAXI.
    let call = format!(
        "TR = DYNA_VIBRA(TYPE_CALCUL='TRAN', BASE_CALCUL='GENE', MATR_MASS=MGEN, \
         MATR_RIGI=KGEN, SCHEMA_TEMPS=_F(SCHEMA='RUNGE_KUTTA_54'), ETAT_INIT=_F(VITE=VGEN), \
         INCREMENT=_F(INST_FIN=0.5, PAS=1.e-4, NB_PAS_MAXI=100), {SHOCK})"
    );
    let (code, out, _) = run_impact_with(&call);
    assert_ne!(code, Some(0), "{out}");
    assert!(
        out.contains("more than 100 steps") && out.contains("NB_PAS_MAXI"),
        "{out}"
    );
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

/// A chain of ten masses from a wall (testcases/chain_fixed_free.mail: k = 50, m = 0.5),
/// a shock at its free end N10, on a basis of its `modes` lowest modes: (code, output).
fn chain_with_modes(modes: usize) -> (Option<i32>, String) {
    chain_with_modes_and(modes, "")
}

/// As [`chain_with_modes`], with `extra` keywords of DYNA_VIBRA (", KEY=...").
fn chain_with_modes_and(modes: usize, extra: &str) -> (Option<i32>, String) {
    run_chain(&format!(
        "MODES = CALC_MODES(MATR_RIGI=K, MATR_MASS=M, OPTION='PLUS_PETITE', CALC_FREQ=_F(NMAX_FREQ={modes}))\n\
         NG = NUME_DDL_GENE(BASE=MODES, STOCKAGE='DIAG')\n\
         MG = PROJ_MATR_BASE(BASE=MODES, NUME_DDL_GENE=NG, MATR_ASSE=M)\n\
         KG = PROJ_MATR_BASE(BASE=MODES, NUME_DDL_GENE=NG, MATR_ASSE=K)\n\
         PLAN = DEFI_OBSTACLE(TYPE='PLAN_Y')\n\
         TR = DYNA_VIBRA(TYPE_CALCUL='TRAN', BASE_CALCUL='GENE', MATR_MASS=MG, MATR_RIGI=KG, \
         SCHEMA_TEMPS=_F(SCHEMA='RUNGE_KUTTA_54'), INCREMENT=_F(INST_FIN=0.1, PAS=1.e-3), \
         COMPORTEMENT=_F(RELATION='DIS_CHOC', NOEUD_1='N10', OBSTACLE=PLAN, \
         ORIG_OBST=(9., 0., 0.), NORM_OBST=(0., 1., 0.), JEU=1.01, RIGI_NOR=1.e3){extra})"
    ))
}

/// The chain of testcases/chain_fixed_free.mail assembled (matrices K, M on NUME), then
/// `body`: (code, output).
fn run_chain(body: &str) -> (Option<i32>, String) {
    let dir = tempfile::tempdir().unwrap();
    std::fs::copy(case("chain_fixed_free.mail"), dir.path().join("chain.mail")).unwrap();
    let comm = dir.path().join("chain.comm");
    std::fs::write(
        &comm,
        format!(
            "DEBUT()\n\
             MAIL = LIRE_MAILLAGE(FORMAT='ASTER', UNITE=20)\n\
             MODELE = AFFE_MODELE(MAILLAGE=MAIL, AFFE=_F(TOUT='OUI', PHENOMENE='MECANIQUE', MODELISATION='DIS_T'))\n\
             CARA = AFFE_CARA_ELEM(MODELE=MODELE, DISCRET=(_F(GROUP_MA='RESSORTS', CARA='K_T_D_L', VALE=(50., 0., 0.)), \
             _F(GROUP_MA='MASSES', CARA='M_T_D_N', VALE=0.5)))\n\
             CL = AFFE_CHAR_CINE(MODELE=MODELE, MECA_IMPO=(_F(GROUP_NO='WALL', DX=0.), _F(GROUP_NO='ALL', DY=0., DZ=0.)))\n\
             ASSEMBLAGE(MODELE=MODELE, CARA_ELEM=CARA, CHAR_CINE=CL, NUME_DDL=CO('NUME'), \
             MATR_ASSE=(_F(MATRICE=CO('K'), OPTION='RIGI_MECA'), _F(MATRICE=CO('M'), OPTION='MASS_MECA')))\n\
             {body}\n\
             FIN()\n"
        ),
    )
    .unwrap();
    run_file(&comm, &dir.path().join("case.db"))
}

#[test]
fn a_basis_without_the_static_flexibility_of_the_shock_is_named() {
    // Mode j of the fixed-free chain, mass-normalised, has the flexibility
    // sin²(Nθ_j)/((2N + 1) k sin²(θ_j/2)) at the free end, θ_j = (2j − 1)π/(2N + 1); the
    // static one is N/k. With N = 10 the first mode holds 84.8 % of it.
    let (n, k) = (10.0f64, 50.0f64);
    let theta = std::f64::consts::PI / (2.0 * n + 1.0);
    let share =
        (n * theta).sin().powi(2) / ((2.0 * n + 1.0) * k * (theta / 2.0).sin().powi(2)) / (n / k);
    let (code, out) = chain_with_modes(1);
    assert_eq!(code, Some(0), "{out}");
    assert!(out.contains("<DYNA_VIBRA_2>"), "{out}");
    assert!(
        out.contains(&format!("holds {:.1} %", 100.0 * share)),
        "{share}: {out}"
    );
    // Every mode: the whole flexibility, no alarm.
    let (code, out) = chain_with_modes(10);
    assert_eq!(code, Some(0), "{out}");
    assert!(!out.contains("DYNA_VIBRA_2"), "{out}");
}

#[test]
fn veri_choc_holds_the_basis_error_to_seuil() {
    // One mode holds the share s of the free end's static flexibility computed in the test
    // above; the criterion is sqrt(1 - s) = 0.390.
    let (n, k) = (10.0f64, 50.0f64);
    let theta = std::f64::consts::PI / (2.0 * n + 1.0);
    let share =
        (n * theta).sin().powi(2) / ((2.0 * n + 1.0) * k * (theta / 2.0).sin().powi(2)) / (n / k);
    let criterion = format!("{:.3e}", (1.0 - share).sqrt());
    let (code, out) = chain_with_modes_and(1, ", VERI_CHOC=_F(SEUIL=0.3)");
    assert_eq!(code, Some(2), "{out}");
    assert!(out.contains("DYNA_VIBRA/VERI_CHOC/SEUIL"), "{out}");
    assert!(out.contains(&criterion), "{criterion}: {out}");
    let (code, out) = chain_with_modes_and(1, ", VERI_CHOC=_F(SEUIL=0.3, STOP_CRITERE='NON')");
    assert_eq!(code, Some(0), "{out}");
    assert!(
        out.contains("<DYNA_VIBRA_3>") && out.contains(&criterion),
        "{out}"
    );
    // Code_Aster's default SEUIL 0.5 accepts it; the whole basis passes any SEUIL.
    let (code, out) = chain_with_modes_and(1, ", VERI_CHOC=_F()");
    assert_eq!(code, Some(0), "{out}");
    assert!(!out.contains("DYNA_VIBRA_3"), "{out}");
    let (code, out) = chain_with_modes_and(10, ", VERI_CHOC=_F(SEUIL=1.e-6)");
    assert_eq!(code, Some(0), "{out}");
}

#[test]
fn a_band_from_a_negative_frequency_takes_the_modes_from_zero() {
    // Code_Aster's files write FREQ=(-0.1, f) to take the rigid-body modes in: on the
    // fixed-free chain (no rigid mode) the same three modes as FREQ=(0, f); the third mode
    // is at 2 sqrt(k/m) sin(5 pi/42)/(2 pi) = 1.1845 Hz, the fourth at 1.6383 Hz.
    let (code, out) = run_chain(
        "A = CALC_MODES(MATR_RIGI=K, MATR_MASS=M, OPTION='BANDE', CALC_FREQ=_F(FREQ=(-0.1, 1.4)))\n\
         B = CALC_MODES(MATR_RIGI=K, MATR_MASS=M, OPTION='BANDE', CALC_FREQ=_F(FREQ=(0., 1.4)))",
    );
    assert_eq!(code, Some(0), "{out}");
    assert!(out.contains("CALC_MODES A: 3 mode(s)"), "{out}");
    assert!(out.contains("CALC_MODES B: 3 mode(s)"), "{out}");
}

/// RECU_FONCTION's instant keywords belong to a transient result: on a table they are
/// refused naming the keyword (INTERP_NUME, CRITERE and PRECISION keep their defaults).
#[test]
fn recu_fonction_instants_on_a_table_are_refused() {
    let (code, out) = run_chain(
        "T = CREA_TABLE(LISTE=(_F(PARA='X', LISTE_R=(0., 1.)), _F(PARA='Y', LISTE_R=(1., 2.))))\n\
         F = RECU_FONCTION(TABLE=T, PARA_X='X', PARA_Y='Y')\n\
         G = RECU_FONCTION(TABLE=T, PARA_X='X', PARA_Y='Y', INST=(0.5,))",
    );
    assert_eq!(code, Some(2), "{out}");
    assert!(out.contains("RECU_FONCTION/INST"), "{out}");
    assert!(out.contains("not rows of a table"), "{out}");
}

#[test]
fn proche_finds_the_mode_nearest_each_frequency_once() {
    // The chain's exact frequencies: 2 sqrt(k/m) sin((2j - 1) pi / (2 (2N + 1))) / (2 pi).
    let f = |j: f64| {
        2.0 * (100.0f64).sqrt() * ((2.0 * j - 1.0) * std::f64::consts::PI / 42.0).sin()
            / (2.0 * std::f64::consts::PI)
    };
    // Near mode 2 twice (once from each side) and near mode 5: two modes.
    let (code, out) = run_chain(&format!(
        "MODES = CALC_MODES(MATR_RIGI=K, MATR_MASS=M, OPTION='PROCHE', CALC_FREQ=_F(FREQ=({}, {}, {})))\n\
         TEST_RESU(RESU=(_F(RESULTAT=MODES, NUME_ORDRE=1, PARA='FREQ', VALE_REFE={}, REFERENCE='ANALYTIQUE', PRECISION=1.e-8),\n\
         _F(RESULTAT=MODES, NUME_ORDRE=2, PARA='FREQ', VALE_REFE={}, REFERENCE='ANALYTIQUE', PRECISION=1.e-8)))",
        0.97 * f(2.0),
        1.02 * f(2.0),
        f(5.0) + 0.1,
        f(2.0),
        f(5.0)
    ));
    assert_eq!(code, Some(0), "{out}");
    assert!(
        out.contains("MODES: 2 mode(s)") && out.contains("tests: 2 OK, 0 NOOK"),
        "{out}"
    );
}

/// `check` knows the shocks' table a DYNA_VIBRA with shocks creates beside its result
/// (`<result>_CHOC`), as the run does; a table of that name without shocks stays unknown.
#[test]
fn check_knows_the_shocks_table() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::copy(
        case("dyna_vibra_impact.mail"),
        dir.path().join("impact.mail"),
    )
    .unwrap();
    let src = std::fs::read_to_string(case("dyna_vibra_impact.comm")).unwrap();
    let check = |extra: &str| {
        let comm = dir.path().join("impact.comm");
        std::fs::write(&comm, src.replace("FIN()", &format!("{extra}\nFIN()"))).unwrap();
        let o = Command::new(env!("CARGO_BIN_EXE_aster-nl"))
            .arg("check")
            .arg(&comm)
            .output()
            .unwrap();
        let out = format!(
            "{}{}",
            String::from_utf8_lossy(&o.stdout),
            String::from_utf8_lossy(&o.stderr)
        );
        (o.status.code(), out)
    };
    let (code, out) = check("IMPR_TABLE(TABLE=RK_CHOC)");
    assert_eq!(code, Some(0), "{out}");
    let (code, out) = check("IMPR_TABLE(TABLE=MGEN_CHOC)");
    assert_ne!(code, Some(0), "{out}");
    assert!(out.contains("'MGEN_CHOC' is not defined"), "{out}");
}

/// A one-node obstacle given a NOEUD_2 acts on node 1 alone, as Code_Aster's shock law
/// does (a shock between two nodes is a BI_ obstacle): alarm DYNA_VIBRA_4, and the run
/// equals the one without NOEUD_2 (same archived shock force).
#[test]
fn a_one_node_obstacle_ignores_noeud_2() {
    let body = |node2: &str| {
        format!(
            "MODES = CALC_MODES(MATR_RIGI=K, MATR_MASS=M, OPTION='PLUS_PETITE', CALC_FREQ=_F(NMAX_FREQ=10))\n\
             NG = NUME_DDL_GENE(BASE=MODES, STOCKAGE='DIAG')\n\
             MG = PROJ_MATR_BASE(BASE=MODES, NUME_DDL_GENE=NG, MATR_ASSE=M)\n\
             KG = PROJ_MATR_BASE(BASE=MODES, NUME_DDL_GENE=NG, MATR_ASSE=K)\n\
             V = CREA_CHAMP(OPERATION='AFFE', TYPE_CHAM='NOEU_DEPL_R', MAILLAGE=MAIL, AFFE=_F(NOEUD='N10', NOM_CMP='DX', VALE=0.1))\n\
             VG = PROJ_VECT_BASE(BASE=MODES, NUME_DDL_GENE=NG, VECT_ASSE=V, TYPE_VECT='VITE')\n\
             PLAN = DEFI_OBSTACLE(TYPE='PLAN_Y')\n\
             TR = DYNA_VIBRA(TYPE_CALCUL='TRAN', BASE_CALCUL='GENE', MATR_MASS=MG, MATR_RIGI=KG, \
             ETAT_INIT=_F(VITE=VG), SCHEMA_TEMPS=_F(SCHEMA='RUNGE_KUTTA_54'), INCREMENT=_F(INST_FIN=0.5, PAS=1.e-3), \
             ARCHIVAGE=_F(INST=(0.25, 0.5)), \
             COMPORTEMENT=_F(RELATION='DIS_CHOC', NOEUD_1='N10', {node2} OBSTACLE=PLAN, INTITULE='STOP', \
             ORIG_OBST=(9., 0., 0.), NORM_OBST=(0., 1., 0.), JEU=1.005, RIGI_NOR=1.e3))\n\
             F = RECU_FONCTION(RESU_GENE=TR, INTITULE='STOP', PARA_X='INST', PARA_Y='FN')\n\
             IMPR_FONCTION(FORMAT='TABLEAU', COURBE=_F(FONCTION=F))"
        )
    };
    let (code, alone) = run_chain(&body(""));
    assert_eq!(code, Some(0), "{alone}");
    let (code, with) = run_chain(&body("NOEUD_2='N9',"));
    assert_eq!(code, Some(0), "{with}");
    assert!(
        with.contains("<DYNA_VIBRA_4>") && with.contains("NOEUD_2 = N9 is ignored"),
        "{with}"
    );
    assert!(!alone.contains("DYNA_VIBRA_4"), "{alone}");
    // The printed force histories are the same.
    let table = |out: &str| -> Vec<String> {
        out.lines()
            .filter(|l| l.trim_start().starts_with(|c: char| c.is_ascii_digit()))
            .map(str::to_string)
            .collect()
    };
    assert!(!table(&alone).is_empty(), "{alone}");
    // The stop is met (a nonzero force is printed).
    assert!(
        table(&alone).iter().any(|l| l
            .split_whitespace()
            .nth(1)
            .and_then(|v| v.parse::<f64>().ok())
            .is_some_and(|v| v > 0.0)),
        "{alone}"
    );
    assert_eq!(table(&alone), table(&with));
}
