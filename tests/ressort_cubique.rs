//! MODE_NON_LINE/RESSORT_CUBIQUE (aster-nl extension, a cubic spring k₃u³): the Duffing
//! testcase checks itself against the exact period; a spring beside a wall on the same DOF
//! runs, restarts from its CARA_CHOC, is corrected on the exact law and judged stable, with
//! no NaN in its tables and its rows below contact on Duffing's exact frequency; bad input
//! stops with an error naming its keyword.

mod support;

use std::path::Path;
use support::{case, run_file};

/// The one-DOF mesh of testcases/duffing.mail, and a command file around `mnl`.
fn write_case(dir: &Path, name: &str, mnl: &str) -> std::path::PathBuf {
    std::fs::copy(case("duffing.mail"), dir.join(format!("{name}.mail"))).unwrap();
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
             MODES = CALC_MODES(MATR_RIGI=RIGIDITE, MATR_MASS=MASSE, OPTION='PLUS_PETITE', \
             CALC_FREQ=_F(NMAX_FREQ=1))\n\
             {mnl}\n\
             FIN()\n"
        ),
    )
    .unwrap();
    comm
}

/// Duffing's frequency at ENERGIE `e` (m = 1, k = 10, k₃): the exact period of the orbit
/// of that energy, K by the arithmetic–geometric mean.
fn duffing_frequency(k3: f64, e: f64) -> f64 {
    let k = 10.0;
    let a2 = ((k * k + 4.0 * k3 * e).sqrt() - k) / k3;
    let m = k3 * a2 / (2.0 * (k + k3 * a2));
    let (mut a, mut b) = (1.0f64, (1.0 - m).sqrt());
    for _ in 0..30 {
        (a, b) = (0.5 * (a + b), (a * b).sqrt());
    }
    let period = 4.0 / (k + k3 * a2).sqrt() * std::f64::consts::PI / (2.0 * a);
    1.0 / period
}

#[test]
fn duffing_testcase_checks_itself_against_the_exact_period() {
    let dir = tempfile::tempdir().unwrap();
    let (code, out) = run_file(&case("duffing.comm"), &dir.path().join("duffing.db"));
    assert_eq!(code, Some(0), "{out}");
    // Every row against the exact period, the one-harmonic closed form, CARA_CHOC, the
    // orbit's amplitude, the stability verdict.
    assert!(out.contains("tests: 42 OK, 0 NOOK"), "{out}");
    // No contact analysis mistakes the spring for a stop (MODE_NON_LINE_1: a force tail;
    // 9: rows clear of every obstacle off the linear frequency; 3: the law check).
    assert!(!out.contains("<MODE_NON_LINE_"), "{out}");
}

/// A cubic spring and a PLAN stop on the same DOF (m = 1, k = 10, JEU = 0.01, RIGI_NOR = 50,
/// k₃ = 1e4: k₃·JEU²/k = 0.1), corrected on the exact law, then restarted from row 21 (the
/// end of branch 7) and checked for stability.
#[test]
fn a_spring_beside_a_wall_runs_restarts_and_reads_back() {
    let dir = tempfile::tempdir().unwrap();
    let comm = write_case(
        dir.path(),
        "wall_spring",
        "MNL = MODE_NON_LINE(MATR_RIGI=RIGIDITE, MATR_MASS=MASSE,\
         ETAT_INIT=_F(MODE_LINE=MODES, NUME_ORDRE=1, COEF_AMPL=0.5),\
         CHOC=_F(OBSTACLE='PLAN', GROUP_NO='N2', NOM_CMP='DX', JEU=0.01, RIGI_NOR=50., \
         PARA_REGUL=1.e-6),\
         RESSORT_CUBIQUE=_F(NOEUD='N2', NOM_CMP='DX', RAIDEUR=1.e4),\
         RESOLUTION=_F(NB_HARM_LINE=10, NB_HARM_NONL=60, NB_BRANCHE=30, NB_PAS_MAN=3, \
         PREC_MAN=1.e-9, CORR_LOI_EXACTE='OUI'))\n\
         MNL2 = MODE_NON_LINE(MATR_RIGI=RIGIDITE, MATR_MASS=MASSE,\
         ETAT_INIT=_F(MODE_NON_LINE=MNL, NUME_ORDRE=21),\
         RESOLUTION=_F(NB_HARM_LINE=10, NB_HARM_NONL=60, NB_BRANCHE=3, NB_PAS_MAN=3, \
         PREC_MAN=1.e-9))\n\
         MNL = CALC_STABILITE(reuse=MNL, MODE_NON_LINE=MNL, \
         FILTRE=_F(FREQ_MIN=0.1, FREQ_MAX=10.), SCHEMA_TEMPS=_F(NB_INST=1000))\n\
         ORBIT = REST_MODE_NONL(MODE_NON_LINE=MNL, NUME_ORDRE=40, TYPE_RESU='DYNA_TRANS', \
         NB_INST=33)",
    );
    let db = dir.path().join("wall_spring.db");
    let (code, out) = run_file(&comm, &db);
    assert_eq!(code, Some(0), "{out}");
    // Rows clear of the stop sit off the linear frequency because of the spring, not of
    // the regularisation: alarm 9 is not the spring's to raise.
    assert!(!out.contains("<MODE_NON_LINE_9>"), "{out}");
    let c = rusqlite::Connection::open(&db).unwrap();

    // CARA_CHOC: the stop, then the spring (TYPE_CHOC, RIGI_NOR = RAIDEUR, JEU 0, no ring law).
    let shocks: Vec<(String, f64, f64, Option<String>)> = c
        .prepare("SELECT TYPE_CHOC, RIGI_NOR, JEU, LOI_CERCLE FROM MNL_CHOC ORDER BY NUME_CHOC")
        .unwrap()
        .query_map([], |r| Ok((r.get(0)?, r.get(1)?, r.get(2)?, r.get(3)?)))
        .unwrap()
        .map(Result::unwrap)
        .collect();
    assert_eq!(shocks.len(), 2, "{shocks:?}");
    assert_eq!(shocks[1], ("RESSORT_CUBIQUE".into(), 1e4, 0.0, None));

    // Every real cell of both tables is a finite number (no NaN, no empty cell).
    for (table, col) in [
        ("MNL", "FREQUENCE"),
        ("MNL", "ENERGIE"),
        ("MNL", "RESIDU"),
        ("MNL", "AMOR_FICTIF"),
        ("MNL", "ECART_ENERGIE"),
        ("MNL", "ECART_LOI_CHOC"),
        ("MNL", "ENERGIE_MOYENNE"),
        ("MNL", "FREQUENCE_LOI_EXACTE"),
        ("MNL2", "FREQUENCE"),
        ("MNL2", "ECART_LOI_CHOC"),
        ("ORBIT_FORC", "FORCE"),
    ] {
        let bad: i64 = c
            .query_row(
                &format!("SELECT count(*) FROM {table} WHERE NOT ({col} BETWEEN -1e300 AND 1e300)"),
                [],
                |r| r.get(0),
            )
            .unwrap();
        let empty: i64 = c
            .query_row(
                &format!("SELECT count(*) FROM {table} WHERE {col} IS NULL"),
                [],
                |r| r.get(0),
            )
            .unwrap();
        assert_eq!((bad, empty), (0, 0), "{table}.{col}");
    }
    // The spring's force is in REST_MODE_NONL's forces, after the stop's (NUME_CHOC 2).
    let spring_force: f64 = c
        .query_row(
            "SELECT max(abs(FORCE)) FROM ORBIT_FORC WHERE NUME_CHOC = 2",
            [],
            |r| r.get(0),
        )
        .unwrap();
    assert!(spring_force > 0.0);

    let rows: Vec<(i64, f64, f64, String)> = c
        .prepare("SELECT NUME_ORDRE, ENERGIE, FREQUENCE, STABILITE FROM MNL ORDER BY NUME_ORDRE")
        .unwrap()
        .query_map([], |r| Ok((r.get(0)?, r.get(1)?, r.get(2)?, r.get(3)?)))
        .unwrap()
        .map(Result::unwrap)
        .collect();
    assert!(rows.len() > 40, "{}", rows.len());
    // Below first contact the motion is Duffing's (plus the stop's regularised force, of
    // stiffness PARA_REGUL·k·(JEU/(JEU − A))² ≤ 1e-6·10·7.5 there, a shift of 4e-6 at most):
    // rows whose Duffing amplitude stays below 0.65 JEU.
    let k3 = 1e4;
    let below: Vec<_> = rows
        .iter()
        .filter(|r| ((100.0 + 4.0 * k3 * r.1).sqrt() - 10.0) / k3 < (0.65f64 * 0.01).powi(2))
        .collect();
    assert!(!below.is_empty());
    for r in &below {
        let e = (r.2 / duffing_frequency(k3, r.1) - 1.0).abs();
        assert!(e < 4e-6, "row {}: {e:e}", r.0);
    }
    // The frequency rises along the branch, from above the linear one (both laws stiffen)
    // and every row is STABLE (one DOF: no nontrivial multiplier).
    let f0 = 10f64.sqrt() / (2.0 * std::f64::consts::PI);
    assert!(rows[0].2 > f0);
    assert!(rows.windows(2).all(|w| w[1].2 > w[0].2));
    assert!(rows.iter().all(|r| r.3 == "STABLE"), "{rows:?}");

    // The restart read both laws back from CARA_CHOC and, the length unit being the JEU
    // as in the first run, retraces it: its rows are rows 22 to 30 (measured: to the bit).
    let retrace: f64 = c
        .query_row(
            "SELECT max(abs(a.FREQUENCE/b.FREQUENCE - 1) + abs(a.ENERGIE/b.ENERGIE - 1)) \
             FROM MNL2 a JOIN MNL b ON b.NUME_ORDRE = a.NUME_ORDRE + 21",
            [],
            |r| r.get(0),
        )
        .unwrap();
    assert!(retrace < 1e-12, "{retrace:e}");
    let restart_shocks: i64 = c
        .query_row(
            "SELECT count(*) FROM MNL2_CHOC WHERE TYPE_CHOC = 'RESSORT_CUBIQUE' AND RIGI_NOR = 1e4",
            [],
            |r| r.get(0),
        )
        .unwrap();
    assert_eq!(restart_shocks, 1);
}

/// A restart of a model with only a cubic spring: no JEU, so its length unit is the
/// restart row's amplitude, not the first run's (COEF_AMPL): the rows fall elsewhere on
/// the family, still on Duffing's exact frequency (within 2e-5, as duffing.comm's rows at
/// NB_HARM_LINE = 7).
#[test]
fn a_spring_alone_restarts_on_the_same_family() {
    let dir = tempfile::tempdir().unwrap();
    let comm = write_case(
        dir.path(),
        "spring_restart",
        "MNL = MODE_NON_LINE(MATR_RIGI=RIGIDITE, MATR_MASS=MASSE,\
         ETAT_INIT=_F(MODE_LINE=MODES, NUME_ORDRE=1, COEF_AMPL=0.01),\
         RESSORT_CUBIQUE=_F(NOEUD='N2', NOM_CMP='DX', RAIDEUR=1000.),\
         RESOLUTION=_F(NB_HARM_LINE=7, NB_HARM_NONL=21, NB_BRANCHE=10, NB_PAS_MAN=2, \
         PREC_MAN=1.e-9))\n\
         MNL2 = MODE_NON_LINE(MATR_RIGI=RIGIDITE, MATR_MASS=MASSE,\
         ETAT_INIT=_F(MODE_NON_LINE=MNL, NUME_ORDRE=20),\
         RESOLUTION=_F(NB_HARM_LINE=7, NB_HARM_NONL=21, NB_BRANCHE=10, NB_PAS_MAN=2, \
         PREC_MAN=1.e-9))",
    );
    let db = dir.path().join("spring_restart.db");
    let (code, out) = run_file(&comm, &db);
    assert_eq!(code, Some(0), "{out}");
    assert!(!out.contains("<MODE_NON_LINE_"), "{out}");
    let c = rusqlite::Connection::open(&db).unwrap();
    let rows: Vec<(f64, f64)> = c
        .prepare("SELECT ENERGIE, FREQUENCE FROM MNL2 ORDER BY NUME_ORDRE")
        .unwrap()
        .query_map([], |r| Ok((r.get(0)?, r.get(1)?)))
        .unwrap()
        .map(Result::unwrap)
        .collect();
    let start: f64 = c
        .query_row("SELECT ENERGIE FROM MNL WHERE NUME_ORDRE = 20", [], |r| {
            r.get(0)
        })
        .unwrap();
    assert_eq!(rows.len(), 20);
    assert!(rows[0].0 > start && rows.windows(2).all(|w| w[1].0 > w[0].0));
    for (e, f) in &rows {
        let err = (f / duffing_frequency(1000.0, *e) - 1.0).abs();
        assert!(err < 2e-5, "E {e}: {err:e}");
    }
}

/// Bad input stops before any computation, with an error naming the keyword (and the
/// occurrence when there are several).
#[test]
fn bad_spring_input_names_its_keyword() {
    let cases = [
        (
            "_F(NOEUD='N9', NOM_CMP='DX', RAIDEUR=1.)",
            "RESSORT_CUBIQUE/NOEUD: node N9 has no DOF DX",
        ),
        (
            "_F(NOEUD='N2', NOM_CMP='DY', RAIDEUR=1.)",
            "RESSORT_CUBIQUE/NOM_CMP: DOF DY of node N2 is blocked by a boundary condition",
        ),
        (
            "_F(NOEUD='N1', NOM_CMP='DX', RAIDEUR=1.)",
            "RESSORT_CUBIQUE/NOM_CMP: DOF DX of node N1 is blocked",
        ),
        (
            "_F(NOEUD='N2', NOM_CMP='DRX', RAIDEUR=1.)",
            "RESSORT_CUBIQUE/NOM_CMP: expected one of 'DX', 'DY', 'DZ'",
        ),
        (
            "_F(GROUP_NO='NX', NOM_CMP='DX', RAIDEUR=1.)",
            "RESSORT_CUBIQUE/GROUP_NO: mesh MAIL has no GROUP_NO 'NX'",
        ),
        (
            "_F(NOEUD='N2', NOM_CMP='DX', RAIDEUR=0.)",
            "RESSORT_CUBIQUE/RAIDEUR: expected a value > 0.0, got 0.0",
        ),
        (
            "_F(NOEUD='N2', NOM_CMP='DX', RAIDEUR=-3.)",
            "RESSORT_CUBIQUE/RAIDEUR: expected a value > 0.0",
        ),
        (
            "_F(NOEUD='N2', NOM_CMP='DX', RAIDEUR=1.e308*10.)",
            "RESSORT_CUBIQUE/RAIDEUR: the result of '*' is not a finite number",
        ),
        (
            "_F(NOEUD='N2', NOM_CMP='DX', RAIDEUR=float('nan'))",
            "RESSORT_CUBIQUE/RAIDEUR: could not convert 'nan' to a real",
        ),
        (
            "(_F(NOEUD='N2', NOM_CMP='DX', RAIDEUR=1.), _F(GROUP_NO='N2', NOM_CMP='DX', RAIDEUR=2.))",
            "MODE_NON_LINE/RESSORT_CUBIQUE[2]: RESSORT_CUBIQUE[2] acts on the same node and component (N2, DX) as RESSORT_CUBIQUE[1]",
        ),
    ];
    let dir = tempfile::tempdir().unwrap();
    for (i, (springs, want)) in cases.iter().enumerate() {
        let name = format!("bad{i}");
        let comm = write_case(
            dir.path(),
            &name,
            &format!(
                "MNL = MODE_NON_LINE(MATR_RIGI=RIGIDITE, MATR_MASS=MASSE,\
                 ETAT_INIT=_F(MODE_LINE=MODES, NUME_ORDRE=1, COEF_AMPL=0.01),\
                 RESSORT_CUBIQUE={springs},\
                 RESOLUTION=_F(NB_HARM_LINE=3, NB_HARM_NONL=9, NB_BRANCHE=2, NB_PAS_MAN=1))"
            ),
        );
        let (code, out) = run_file(&comm, &dir.path().join(format!("{name}.db")));
        assert_ne!(code, Some(0), "{springs}: {out}");
        assert!(out.contains(want), "{springs}: wanted '{want}' in\n{out}");
        assert!(!out.contains("panicked"), "{springs}: {out}");
    }
}
