//! DYNA_LINE through the binary: the testcase (checked there against the exact solution)
//! and the errors a user meets, each naming its keyword and leaving the database as it was.

mod support;
use support::{case, run_file};

#[test]
fn dyna_line_on_the_chain_with_a_stop_matches_the_exact_solution() {
    let dir = tempfile::tempdir().unwrap();
    let (code, out) = run_file(&case("dyna_line.comm"), &dir.path().join("case.db"));
    assert_eq!(code, Some(0), "{out}");
    assert!(out.contains("tests: 61 OK, 0 NOOK"), "{out}");
    // The bases DYNA_LINE built: 5 modes of the band + the static mode of the shock's
    // node; 2 modes + the static mode; ORTHO='OUI' diagonalises.
    assert!(
        out.contains("DYNA_LINE DL: 6 vector(s) in the basis BASE (STOCKAGE='PLEIN')"),
        "{out}"
    );
    assert!(
        out.contains("DYNA_LINE DL_OR: 6 vector(s) in the basis BASE_OR (STOCKAGE='DIAG')"),
        "{out}"
    );
    assert!(
        out.contains("DYNA_LINE DL_2S: 3 vector(s) in the basis BASE_2S"),
        "{out}"
    );
    // The static response to the load of EXCIT after the 5 modes.
    assert!(
        out.contains(
            "DEFI_BASE_MODALE FS.DL.BASE: 6 vector(s): 5 of FS.DL.MODES, 1 of FS.DL.STAT1"
        ),
        "{out}"
    );
    // TYPE_APPUI='MONO': the pseudo-mode of X after the 5 modes.
    assert!(
        out.contains(
            "DEFI_BASE_MODALE SE.DL.RITZ1: 6 vector(s): 5 of SE.DL.MODES, 1 of SE.DL.STAT1"
        ),
        "{out}"
    );
}

/// The testcase cut before its first DYNA_LINE, with `call` after it: (code, output,
/// concepts in the database after the run).
fn run_with(call: &str) -> (Option<i32>, String, Vec<String>) {
    let dir = tempfile::tempdir().unwrap();
    let text = std::fs::read_to_string(case("dyna_line.comm")).unwrap();
    let head = text.split("\nDL = DYNA_LINE(").next().unwrap();
    std::fs::copy(case("dyna_line.mail"), dir.path().join("c.mail")).unwrap();
    let comm = dir.path().join("c.comm");
    std::fs::write(&comm, format!("{head}\n{call}\nFIN()\n")).unwrap();
    let db = dir.path().join("c.db");
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

const COMMON: &str = "MODELE=MODELE, CARA_ELEM=CARA, CHARGE=BLOC, SCHEMA_TEMPS=SCHEMA, \
                      ETAT_INIT=_F(VITE=VPHYS), INCREMENT=_F(INST_FIN=0.1, PAS=1.e-4), \
                      COMPORTEMENT=SHOCK";

/// Refused: `(code, output)` checked to fail naming `keyword` and `words`, with nothing of
/// the call left in the database.
fn refused(call: &str, keyword: &str, words: &str) {
    let (code, out, names) = run_with(call);
    assert_ne!(code, Some(0), "{out}");
    assert!(out.contains(keyword), "expected {keyword}:\n{out}");
    assert!(out.contains(words), "expected '{words}':\n{out}");
    assert!(
        !names
            .iter()
            .any(|n| n.starts_with("R.") || n == "R" || n == "TG" || n == "B"),
        "a failed DYNA_LINE left {names:?}"
    );
}

#[test]
fn a_band_without_a_mode_is_refused_with_the_lowest_frequency() {
    refused(
        &format!(
            "R = DYNA_LINE(TYPE_CALCUL='TRAN', BASE_CALCUL='GENE', BANDE_ANALYSE=(40., 50.), \
             RESU_GENE=CO('TG'), BASE_RESU=CO('B'), {COMMON})"
        ),
        "DYNA_LINE/BANDE_ANALYSE",
        "holds no mode of the structure",
    );
    let (_, out, _) = run_with(&format!(
        "R = DYNA_LINE(TYPE_CALCUL='TRAN', BASE_CALCUL='GENE', BANDE_ANALYSE=1., {COMMON})"
    ));
    // f_1 = 2 sqrt(k/m) sin(pi/26)/(2 pi) = 3.8368 Hz.
    assert!(
        out.contains("lowest frequency of the structure is 3.836802e0 Hz"),
        "{out}"
    );
}

#[test]
fn a_modal_basis_without_its_band_is_refused() {
    refused(
        &format!("R = DYNA_LINE(TYPE_CALCUL='TRAN', BASE_CALCUL='GENE', {COMMON})"),
        "DYNA_LINE/BANDE_ANALYSE",
        "needs the band",
    );
    refused(
        &format!(
            "R = DYNA_LINE(TYPE_CALCUL='TRAN', BASE_CALCUL='GENE', BANDE_ANALYSE=(20., 10.), {COMMON})"
        ),
        "DYNA_LINE/BANDE_ANALYSE",
        "F_max must exceed F_min",
    );
}

#[test]
fn outputs_must_be_new_names() {
    refused(
        &format!(
            "R = DYNA_LINE(TYPE_CALCUL='TRAN', BASE_CALCUL='GENE', BANDE_ANALYSE=29., \
             RESU_GENE=CO('R'), {COMMON})"
        ),
        "DYNA_LINE/RESU_GENE",
        "the name of DYNA_LINE's result itself",
    );
    refused(
        &format!(
            "R = DYNA_LINE(TYPE_CALCUL='TRAN', BASE_CALCUL='GENE', BANDE_ANALYSE=29., \
             RESU_GENE=CO('TG'), BASE_RESU=CO('TG'), {COMMON})"
        ),
        "DYNA_LINE/BASE_RESU",
        "the same name",
    );
    // A concept where CO('...') is expected: the catalog's type check.
    refused(
        &format!(
            "R = DYNA_LINE(TYPE_CALCUL='TRAN', BASE_CALCUL='GENE', BANDE_ANALYSE=29., \
             BASE_RESU=VPHYS, {COMMON})"
        ),
        "BASE_RESU",
        "CO",
    );
}

#[test]
fn what_dyna_line_does_not_run_is_refused_by_name() {
    refused(
        &format!(
            "R = DYNA_LINE(TYPE_CALCUL='HARM', BASE_CALCUL='GENE', BANDE_ANALYSE=29., {COMMON})"
        ),
        "DYNA_LINE/TYPE_CALCUL",
        "harmonic responses are not computed",
    );
    refused(
        &format!(
            "ACC = DEFI_FONCTION(NOM_PARA='INST', VALE=(0., 0., 1., 1.))\n\
             R = DYNA_LINE(TYPE_CALCUL='TRAN', BASE_CALCUL='GENE', BANDE_ANALYSE=29., \
             EXCIT=_F(TYPE_APPUI='MULTI', DIRECTION=(1., 0., 0.), GROUP_NO='WALL', FONC_MULT=ACC), \
             {COMMON})"
        ),
        "DYNA_LINE/EXCIT/TYPE_APPUI",
        "multi-support excitation",
    );
    refused(
        &format!(
            "R = DYNA_LINE(TYPE_CALCUL='TRAN', BASE_CALCUL='PHYS', \
             AMORTISSEMENT=_F(TYPE_AMOR='MODAL', AMOR_REDUIT=0.01), {COMMON})"
        ),
        "DYNA_LINE/AMORTISSEMENT/TYPE_AMOR",
        "modal damping needs a modal basis",
    );
}

/// An error inside a chained operator names the step and DYNA_LINE's keyword; one about a
/// keyword passed on as written names it under DYNA_LINE.
#[test]
fn errors_of_the_chained_operators_are_told_as_dyna_line_s() {
    refused(
        "R = DYNA_LINE(TYPE_CALCUL='TRAN', BASE_CALCUL='GENE', BANDE_ANALYSE=29., \
             MODELE=MODELE, CARA_ELEM=CARA, CHARGE=BLOC, SCHEMA_TEMPS=SCHEMA, \
             ETAT_INIT=_F(VITE=VPHYS), INCREMENT=_F(INST_FIN=0.1, PAS=1.e-4), \
             COMPORTEMENT=_F(RELATION='DIS_CHOC', GROUP_NO_1='NO6', OBSTACLE=OBST, \
             ORIG_OBST=(6., 0., 0.), NORM_OBST=(0., 1., 0.), JEU=G, RIGI_NOR=KN, \
             NOEUD_2='N9'))",
        "DYNA_LINE/COMPORTEMENT",
        "N9",
    );
}

/// The default step is 1/(5 F_max), Code_Aster's: DIFF_CENTRE on the chain without PAS and
/// F_max = 29 Hz takes 1/145 s steps; over 0.2 s, 29 steps.
#[test]
fn the_default_step_is_a_fifth_of_the_period_of_f_max() {
    let (code, out, _) = run_with(
        "R = DYNA_LINE(TYPE_CALCUL='TRAN', BASE_CALCUL='GENE', BANDE_ANALYSE=29., ENRI_STAT='NON', \
         MODELE=MODELE, CARA_ELEM=CARA, CHARGE=BLOC, SCHEMA_TEMPS=_F(SCHEMA='DIFF_CENTRE'), \
         ETAT_INIT=_F(VITE=VPHYS), INCREMENT=_F(INST_FIN=0.2))",
    );
    assert_eq!(code, Some(0), "{out}");
    assert!(out.contains("29 steps (0 rejected)"), "{out}");
}

/// AMORTISSEMENT=_F(TYPE_AMOR='RAYLEIGH') assembles the damping matrix (here of discrete
/// dampers along the springs, not proportional to K or M): on all six modes (projected, full)
/// and on the physical DOFs the two routes give the same motion, to the integrators'
/// accuracy (measured: 1.8e-13 m at worst, u about 5e-3 m; bound 1e-12 m): a consistency
/// check of the two routes, the modal case having its exact reference in the testcase.
#[test]
fn rayleigh_damping_gives_the_same_motion_on_the_modes_and_the_physical_dofs() {
    let call = |base: &str, band: &str| {
        format!(
            "R{base} = DYNA_LINE(TYPE_CALCUL='TRAN', BASE_CALCUL='{base}', {band} MODELE=MODELE, \
             CARA_ELEM=CARA_A, CHARGE=BLOC, AMORTISSEMENT=_F(TYPE_AMOR='RAYLEIGH'), \
             SCHEMA_TEMPS=_F(SCHEMA='RUNGE_KUTTA_54', TOLERANCE=1.e-10), \
             ETAT_INIT=_F(VITE=VPHYS), INCREMENT=_F(INST_FIN=0.1, PAS=1.e-4), ARCHIVAGE=_F(INST=TI))\n"
        )
    };
    let (code, out, _) = run_with(&format!(
        "CARA_A = AFFE_CARA_ELEM(MODELE=MODELE, DISCRET=(\
           _F(GROUP_MA='RESSORTS', CARA='K_T_D_L', VALE=(K, 0., 0.)),\
           _F(GROUP_MA='MASSES', CARA='M_T_D_N', VALE=M),\
           _F(GROUP_MA='RESSORTS', CARA='A_T_D_L', VALE=(2., 0., 0.))))\n\
         {}{}\
         U_G = RECU_FONCTION(RESULTAT=RGENE, NOM_CHAM='DEPL', GROUP_NO='NO6', NOM_CMP='DX')\n\
         U_P = RECU_FONCTION(RESULTAT=RPHYS, NOM_CHAM='DEPL', GROUP_NO='NO6', NOM_CMP='DX')\n\
         D = CALC_FONCTION(COMB=(_F(FONCTION=U_G, COEF=1.), _F(FONCTION=U_P, COEF=-1.)))\n\
         for t in TI:\n    TEST_FONCTION(VALEUR=_F(FONCTION=D, VALE_PARA=t, VALE_CALC=0., \
         CRITERE='ABSOLU', TOLE_MACHINE=1.e-12))\n\
         TEST_FONCTION(VALEUR=_F(FONCTION=U_P, VALE_PARA=0.1, VALE_CALC=5.50578107e-3, \
         TOLE_MACHINE=1.e-8))\n",
        call("GENE", "BANDE_ANALYSE=40.,"),
        call("PHYS", "")
    ));
    assert_eq!(code, Some(0), "{out}");
    // The last test is a regression value (this run's, 2026-12-07) showing the dampers act:
    // without them u(N6) at 0.1 s is V0 sin(w1 t)/w1 = 5.5378e-3 (the first mode alone).
    assert!(out.contains("tests: 6 OK, 0 NOOK"), "{out}");
}
