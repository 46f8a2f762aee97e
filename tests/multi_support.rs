//! Moving supports through the binary: MODE_STATIQUE, CALC_CHAR_SEISME, DYNA_VIBRA with
//! EXCIT MULT_APPUI='OUI', and the absolute motion restored by REST_GENE_PHYS and
//! RECU_FONCTION. The exact references are in testcases/dyna_vibra_seisme.comm; here, that
//! case and the errors a user meets, each naming its keyword.

mod support;
use support::{case, run_file};

/// The seismic case's model and matrices (everything before its references), then `tail`.
fn run_seisme_with(tail: &str) -> (Option<i32>, String) {
    let dir = tempfile::tempdir().unwrap();
    let text = std::fs::read_to_string(case("dyna_vibra_seisme.comm")).unwrap();
    let head = text.split("TI = (").next().unwrap();
    let comm = dir.path().join("seisme.comm");
    std::fs::write(&comm, format!("{head}\n{tail}\nFIN()\n")).unwrap();
    std::fs::copy(
        case("dyna_vibra_seisme.mail"),
        dir.path().join("seisme.mail"),
    )
    .unwrap();
    run_file(&comm, &dir.path().join("case.db"))
}

#[test]
fn a_moving_support_matches_the_exact_relative_and_absolute_motion() {
    let dir = tempfile::tempdir().unwrap();
    let (code, out) = run_file(&case("dyna_vibra_seisme.comm"), &dir.path().join("s.db"));
    assert_eq!(code, Some(0), "{out}");
    assert!(out.contains("tests: 39 OK, 0 NOOK"), "{out}");
    // The wall run and the two-support run located the 18 contact changes of the exact
    // solution.
    assert_eq!(
        out.matches("18 contact change(s) located").count(),
        2,
        "{out}"
    );
}

#[test]
fn attachment_modes_are_the_columns_of_the_flexibility() {
    // FORCE_NODALE on P: u = 1/k at P (one spring to the support), 0 at the support.
    let (code, out) = run_seisme_with(
        "FN = MODE_STATIQUE(MATR_RIGI=RIGI, FORCE_NODALE=_F(GROUP_NO='P', AVEC_CMP='DX'))\n\
         TEST_RESU(RESU=(_F(RESULTAT=FN, NUME_ORDRE=1, NOM_CHAM='DEPL', GROUP_NO='P', NOM_CMP='DX',\n\
                            VALE_REFE=1.e-4, REFERENCE='ANALYTIQUE', PRECISION=1.e-12),\n\
                         _F(RESULTAT=FN, NUME_ORDRE=1, NOM_CHAM='DEPL', GROUP_NO='S', NOM_CMP='DX',\n\
                            VALE_REFE=0., REFERENCE='ANALYTIQUE', CRITERE='ABSOLU', PRECISION=1.e-15)))",
    );
    assert_eq!(code, Some(0), "{out}");
    assert!(out.contains("tests: 4 OK, 0 NOOK"), "{out}");
}

#[test]
fn mult_appui_without_the_static_modes_names_mode_stat() {
    let (code, out) = run_seisme_with(
        "ACC = FORMULE(VALE='sin(INST)', NOM_PARA='INST')\n\
         R = DYNA_VIBRA(TYPE_CALCUL='TRAN', BASE_CALCUL='GENE', MATR_MASS=MGEN, MATR_RIGI=KGEN,\n\
                        EXCIT=_F(VECT_ASSE_GENE=FS, ACCE=ACC, VITE=ACC, DEPL=ACC, MULT_APPUI='OUI',\n\
                                 GROUP_NO='S', DIRECTION=(1., 0., 0.)),\n\
                        INCREMENT=_F(INST_FIN=0.01, PAS=1.e-4))",
    );
    assert_eq!(code, Some(2), "{out}");
    assert!(out.contains("DYNA_VIBRA/MODE_STAT"), "{out}");
}

#[test]
fn a_static_mode_of_a_free_dof_names_avec_cmp() {
    let (code, out) = run_seisme_with(
        "BAD = MODE_STATIQUE(MATR_RIGI=RIGI, MODE_STAT=_F(GROUP_NO='P', AVEC_CMP='DX'))",
    );
    assert_eq!(code, Some(2), "{out}");
    assert!(out.contains("MODE_STAT/AVEC_CMP"), "{out}");
    assert!(out.contains("DOF P DX is not blocked"), "{out}");
}

#[test]
fn a_support_without_its_constraint_mode_is_named() {
    // MSTA holds S DX only: a direction along Y asks for S DY.
    let (code, out) = run_seisme_with(
        "BAD = CALC_CHAR_SEISME(MATR_MASS=MASS, DIRECTION=(0., 1., 0.), MODE_STAT=MSTA, GROUP_NO='S')",
    );
    assert_eq!(code, Some(2), "{out}");
    assert!(out.contains("has no constraint mode of S DY"), "{out}");
}

#[test]
fn absolute_motion_of_a_run_with_fixed_supports_is_refused() {
    let (code, out) = run_seisme_with(
        "R = DYNA_VIBRA(TYPE_CALCUL='TRAN', BASE_CALCUL='GENE', MATR_MASS=MGEN, MATR_RIGI=KGEN,\n\
                        EXCIT=_F(VECT_ASSE_GENE=FS, COEF_MULT=1.),\n\
                        INCREMENT=_F(INST_FIN=0.01, PAS=1.e-4))\n\
         P = REST_GENE_PHYS(RESU_GENE=R, NOM_CHAM='DEPL', MULT_APPUI='OUI')",
    );
    assert_eq!(code, Some(2), "{out}");
    assert!(out.contains("REST_GENE_PHYS/MULT_APPUI"), "{out}");
    assert!(out.contains("without moving supports"), "{out}");
}

#[test]
fn a_structure_its_supports_do_not_hold_has_no_static_mode() {
    // Unblocking the support leaves a free-floating mass and spring: K is singular.
    let dir = tempfile::tempdir().unwrap();
    let text = std::fs::read_to_string(case("dyna_vibra_seisme.comm")).unwrap();
    let head = text.split("MODES = CALC_MODES").next().unwrap().replace(
        "DDL_IMPO=(_F(GROUP_NO=('S', 'S2'), DX=0., DY=0., DZ=0.),",
        "DDL_IMPO=(_F(GROUP_NO=('S', 'S2'), DY=0., DZ=0.),",
    );
    let comm = dir.path().join("seisme.comm");
    std::fs::write(
        &comm,
        format!("{head}\nF = MODE_STATIQUE(MATR_RIGI=RIGI, FORCE_NODALE=_F(GROUP_NO='P', AVEC_CMP='DX'))\nFIN()\n"),
    )
    .unwrap();
    std::fs::copy(
        case("dyna_vibra_seisme.mail"),
        dir.path().join("seisme.mail"),
    )
    .unwrap();
    let (code, out) = run_file(&comm, &dir.path().join("case.db"));
    assert_eq!(code, Some(2), "{out}");
    assert!(out.contains("MODE_STATIQUE/MATR_RIGI"), "{out}");
    assert!(out.contains("do not hold the structure"), "{out}");
}

#[test]
fn dyna_tran_modal_takes_the_moving_supports_too() {
    // Part A of the seismic case in DYNA_TRAN_MODAL's spelling (Code_Aster 10 to 12): the
    // same absolute displacement at 0.3 s as DYNA_VIBRA's (the exact value, 1e-7).
    let (code, out) = run_seisme_with(
        "ACC = FORMULE(VALE='A*sin(W*INST)', A=A, W=W, NOM_PARA='INST')\n\
         VIT = FORMULE(VALE='-A/W*cos(W*INST)', A=A, W=W, NOM_PARA='INST')\n\
         DEP = FORMULE(VALE='-A/W**2*sin(W*INST)', A=A, W=W, NOM_PARA='INST')\n\
         R = DYNA_TRAN_MODAL(MASS_GENE=MGEN, RIGI_GENE=KGEN, MODE_STAT=MSTA,\n\
                             SCHEMA_TEMPS=_F(SCHEMA='RUNGE_KUTTA_54', TOLERANCE=1.e-10),\n\
                             EXCIT=_F(VECT_GENE=FS, ACCE=ACC, VITE=VIT, DEPL=DEP, MULT_APPUI='OUI',\n\
                                      GROUP_NO='S', DIRECTION=(1., 0., 0.)),\n\
                             INCREMENT=_F(INST_FIN=0.3, PAS=1.e-4), ARCHIVAGE=_F(INST=(0.3,)))\n\
         XA = RECU_FONCTION(RESU_GENE=R, NOM_CHAM='DEPL', GROUP_NO='P', NOM_CMP='DX', MULT_APPUI='OUI')\n\
         TEST_FONCTION(VALEUR=_F(FONCTION=XA, VALE_PARA=0.3, VALE_REFE=2.333213610970564e-04,\n\
                                 REFERENCE='ANALYTIQUE', PRECISION=1.e-7))",
    );
    assert_eq!(code, Some(0), "{out}");
    assert!(out.contains("tests: 3 OK, 0 NOOK"), "{out}");
}
