//! REPONSE_FORCEE_NL (aster-nl extension, the forced-response curve with shocks): the
//! testcase checks itself against its shooting and closed-form references; a curve cut by
//! NB_BRANCHE says so; bad input stops with an error naming its keyword and leaves no
//! result behind.

mod support;

use std::path::Path;
use support::{case, run_file};

/// The one-DOF mesh of testcases/forced_plan.mail, and a command file around `call`.
fn write_case(dir: &Path, name: &str, call: &str) -> std::path::PathBuf {
    std::fs::copy(case("forced_plan.mail"), dir.join(format!("{name}.mail"))).unwrap();
    let comm = dir.join(format!("{name}.comm"));
    std::fs::write(
        &comm,
        format!(
            "DEBUT()\n\
             MAIL = LIRE_MAILLAGE(FORMAT='ASTER', UNITE=20)\n\
             MODELE = AFFE_MODELE(MAILLAGE=MAIL, AFFE=_F(GROUP_MA=('M1', 'P2'), \
             PHENOMENE='MECANIQUE', MODELISATION='DIS_T'))\n\
             CARA = AFFE_CARA_ELEM(MODELE=MODELE, DISCRET=(\
             _F(CARA='M_T_D_N', GROUP_MA='P2', VALE=1.0),\
             _F(CARA='K_T_D_N', GROUP_MA='P2', VALE=(0., 0., 0.)),\
             _F(CARA='K_T_D_L', GROUP_MA='M1', VALE=(10., 0., 0.), REPERE='GLOBAL'),))\n\
             CL = AFFE_CHAR_CINE(MODELE=MODELE, MECA_IMPO=(\
             _F(GROUP_NO='N1', DX=0., DY=0., DZ=0.), _F(GROUP_NO='N2', DY=0., DZ=0.),))\n\
             ASSEMBLAGE(MODELE=MODELE, CARA_ELEM=CARA, CHAR_CINE=CL, NUME_DDL=CO('NUMEDDL'),\
             MATR_ASSE=(_F(MATRICE=CO('RIGIDITE'), OPTION='RIGI_MECA'),\
             _F(MATRICE=CO('MASSE'), OPTION='MASS_MECA'),),)\n\
             {call}\n\
             FIN()\n"
        ),
    )
    .unwrap();
    comm
}

/// A REPONSE_FORCEE_NL call on the testcase's model, the keywords given replacing the
/// testcase's (damping, excitation, band).
fn call(damping: &str, excit: &str, band: &str) -> String {
    format!(
        "FRF = REPONSE_FORCEE_NL(MATR_RIGI=RIGIDITE, MATR_MASS=MASSE, {damping}{excit}{band}\
         OBSERVATION=_F(NOEUD='N2', NOM_CMP='DX'),\
         CHOC=_F(OBSTACLE='PLAN', NOEUD='N2', NOM_CMP='DX', JEU=0.01, RIGI_NOR=50., PARA_REGUL=1.e-4),\
         RESOLUTION=_F(NB_HARM_LINE=3, NB_HARM_NONL=9, NB_BRANCHE=3, NB_PAS_MAN=1))"
    )
}

const DAMPING: &str = "AMOR_RAYLEIGH=_F(AMOR_BETA=0.1), ";
const EXCIT: &str = "EXCIT=_F(NOEUD='N2', NOM_CMP='DX', FORCE=0.01), ";
const BAND: &str = "FREQ_MIN=0.3, FREQ_MAX=0.8, ";

#[test]
fn forced_plan_testcase_checks_itself() {
    let dir = tempfile::tempdir().unwrap();
    let (code, out) = run_file(
        &case("forced_plan.comm"),
        &dir.path().join("forced_plan.db"),
    );
    assert_eq!(code, Some(0), "{out}");
    // Three rows against shooting, their frequencies, the two folds, the linear start.
    // ... and the stability of four rows against the growth of a perturbation, two rows
    // around the lower fold.
    assert!(out.contains("tests: 27 OK, 0 NOOK"), "{out}");
    assert!(
        out.contains("443 point(s)") && out.contains("2 turning point(s)"),
        "{out}"
    );
    // Regression counts: the 18 INDETERMINE rows past the upper fold are the only alarm.
    assert!(
        out.contains("stability: 279 STABLE, 146 INSTABLE, 18 INDETERMINE"),
        "{out}"
    );
    assert_eq!(out.matches("<A>").count(), 1, "{out}");
    assert!(
        out.contains("<A> <REPONSE_FORCEE_NL_2> 18 row(s) INDETERMINE"),
        "{out}"
    );
}

/// NB_BRANCHE too small for the band: the rows computed are stored and the alarm says the
/// curve stopped inside the band.
#[test]
fn a_curve_cut_by_nb_branche_says_so() {
    let dir = tempfile::tempdir().unwrap();
    let comm = write_case(dir.path(), "cut", &call(DAMPING, EXCIT, BAND));
    let (code, out) = run_file(&comm, &dir.path().join("cut.db"));
    assert_eq!(code, Some(0), "{out}");
    assert!(
        out.contains("<A> <REPONSE_FORCEE_NL_1> the curve ends at"),
        "{out}"
    );
    assert!(out.contains("FRF: 4 point(s)"), "{out}");
}

/// Bad input stops before any computation, with an error naming the keyword, and no
/// concept FRF is left in the database.
#[test]
fn bad_input_names_its_keyword() {
    let cases = [
        (
            call("", EXCIT, BAND),
            "REPONSE_FORCEE_NL",
            "expected exactly one of MATR_AMOR, AMOR_RAYLEIGH, none given",
        ),
        (
            call(
                "AMOR_RAYLEIGH=_F(AMOR_ALPHA=0., AMOR_BETA=0.), ",
                EXCIT,
                BAND,
            ),
            "REPONSE_FORCEE_NL/AMOR_RAYLEIGH",
            "a forced response needs a damping: the damping matrix is zero",
        ),
        (
            call(
                DAMPING,
                "EXCIT=_F(NOEUD='N2', NOM_CMP='DZ', FORCE=0.01), ",
                BAND,
            ),
            "REPONSE_FORCEE_NL/EXCIT/NOM_CMP",
            "DOF DZ of node N2 is blocked by a boundary condition",
        ),
        (
            call(
                DAMPING,
                "EXCIT=_F(NOEUD='N9', NOM_CMP='DX', FORCE=0.01), ",
                BAND,
            ),
            "REPONSE_FORCEE_NL/EXCIT/NOM_CMP",
            "DOF DX of node N9 does not exist in the numbering of MATR_RIGI",
        ),
        (
            call(
                DAMPING,
                "EXCIT=_F(NOEUD='N2', NOM_CMP='DX', FORCE=0.), ",
                BAND,
            ),
            "REPONSE_FORCEE_NL/EXCIT",
            "the force is zero on every free DOF",
        ),
        (
            call(DAMPING, EXCIT, "FREQ_MIN=0.8, FREQ_MAX=0.3, "),
            "REPONSE_FORCEE_NL/FREQ_MAX",
            "the band is empty: FREQ_MIN = 0.8 Hz is not below FREQ_MAX = 0.3 Hz",
        ),
        (
            call(DAMPING, EXCIT, "FREQ_MIN=0.5, FREQ_MAX=0.5, "),
            "REPONSE_FORCEE_NL/FREQ_MAX",
            "the band is empty",
        ),
        // The structure's frequencies: 0.503 Hz open, 1.233 Hz against the stop; 5 to 6 Hz
        // and its harmonics 2 and 3 (NB_HARM_LINE = 3) are far above both.
        (
            call(DAMPING, EXCIT, "FREQ_MIN=5., FREQ_MAX=6., "),
            "REPONSE_FORCEE_NL/FREQ_MIN",
            "the band 5 to 6 Hz holds no resonance",
        ),
    ];
    let dir = tempfile::tempdir().unwrap();
    for (i, (c, key, want)) in cases.iter().enumerate() {
        let name = format!("bad{i}");
        let comm = write_case(dir.path(), &name, c);
        let db = dir.path().join(format!("{name}.db"));
        let (code, out) = run_file(&comm, &db);
        assert_ne!(code, Some(0), "{c}: {out}");
        assert!(out.contains(key), "{c}: wanted '{key}' in\n{out}");
        assert!(out.contains(want), "{c}: wanted '{want}' in\n{out}");
        assert!(!out.contains("panicked"), "{c}: {out}");
        // The failed operator left nothing: FRF is not a concept of the database.
        let conn = rusqlite::Connection::open(db.as_path()).unwrap();
        let frf: i64 = conn
            .query_row(
                "SELECT count(*) FROM sqlite_master WHERE name = 'FRF'",
                [],
                |r| r.get(0),
            )
            .unwrap_or(0);
        assert_eq!(frf, 0, "{c}: a table FRF was left behind");
    }
}
