//! FORMULE, CALC_FONC_INTERP and CALC_FONCTION driven through the `aster-nl` binary:
//! testcases/functions_formule.comm, Code_Aster's usage patterns (sdnd102a, sdnd104a,
//! sdnd121a), the errors (file, line, keyword), `check`, and a formula kept by POURSUITE.

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

fn case(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("testcases")
        .join(name)
}

/// Writes `comm` as `case.comm` in `dir` and runs `aster-nl <verb>` on it.
fn run_in(dir: &Path, verb: &str, comm: &str) -> (Option<i32>, String) {
    let path = dir.join("case.comm");
    std::fs::write(&path, comm).unwrap();
    let o = bin().arg(verb).arg(&path).output().unwrap();
    (o.status.code(), text(&o))
}

fn run(comm: &str) -> (Option<i32>, String) {
    let dir = tempfile::tempdir().unwrap();
    run_in(dir.path(), "run", comm)
}

/// The run's summary line, "tests: n OK, m NOOK".
fn summary(out: &str) -> &str {
    out.lines()
        .find(|l| l.starts_with("tests:"))
        .unwrap_or("no summary")
}

#[test]
fn the_testcase_passes_every_check() {
    let dir = tempfile::tempdir().unwrap();
    for f in ["functions_formule.comm", "functions_formule.mail"] {
        std::fs::copy(case(f), dir.path().join(f)).unwrap();
    }
    let o = bin()
        .arg("run")
        .arg(dir.path().join("functions_formule.comm"))
        .output()
        .unwrap();
    let out = text(&o);
    assert_eq!(o.status.code(), Some(0), "{out}");
    // 5 formula values, 3 sampled, 8 CALC_FONCTION, 2 x 5 DYNA_VIBRA instants.
    assert_eq!(summary(&out), "tests: 26 OK, 0 NOOK", "{out}");
    assert!(!out.contains("<A>"), "{out}");
}

/// sdnd102a's pattern: formulas of INST with their constant as a keyword, sampled by
/// CALC_FONC_INTERP on a DEFI_LIST_REEL with LINEAIRE prolongations, combined by COMB.
/// ACCE1 + ACCE2 = 0 at every node; between nodes and beyond them (LINEAIRE) too, since
/// the two chords are opposite. Exact references: sin at W t = pi/2 is 1 (to an ulp).
#[test]
fn sdnd102a_pattern_formule_calc_fonc_interp_comb() {
    let (code, out) = run("DEBUT()
L_INST = DEFI_LIST_REEL(DEBUT=0.0, INTERVALLE=_F(JUSQU_A=1.0, PAS=0.0001))
OMEGAA = 2.0 * pi * 10.0
ACCE1 = FORMULE(VALE=\"sin(OMEGAA*INST) \", OMEGAA=OMEGAA, NOM_PARA=\"INST\")
ACCELER1 = CALC_FONC_INTERP(FONCTION=ACCE1, LIST_PARA=L_INST, NOM_PARA=\"INST\",
    PROL_DROITE=\"LINEAIRE\", PROL_GAUCHE=\"LINEAIRE\", NOM_RESU=\"ACCE\")
ACCE2 = FORMULE(VALE=\"- sin(OMEGAA*INST) \", OMEGAA=OMEGAA, NOM_PARA=\"INST\")
ACCELER2 = CALC_FONC_INTERP(FONCTION=ACCE2, LIST_PARA=L_INST, NOM_PARA=\"INST\",
    PROL_DROITE=\"LINEAIRE\", PROL_GAUCHE=\"LINEAIRE\", NOM_RESU=\"ACCE\")
DIFF = CALC_FONCTION(COMB=(_F(FONCTION=ACCELER1, COEF=1.0), _F(FONCTION=ACCELER2, COEF=1.0)))
TEST_FONCTION(VALEUR=(
    _F(FONCTION=DIFF, VALE_PARA=0.1, VALE_CALC=0.0, CRITERE='ABSOLU', TOLE_MACHINE=1.e-15),
    _F(FONCTION=DIFF, VALE_PARA=0.33335, VALE_CALC=0.0, CRITERE='ABSOLU', TOLE_MACHINE=1.e-15),
    _F(FONCTION=DIFF, VALE_PARA=1.5, VALE_CALC=0.0, CRITERE='ABSOLU', TOLE_MACHINE=1.e-15),
    _F(FONCTION=ACCELER1, VALE_PARA=0.025, VALE_REFE=1.0, REFERENCE='ANALYTIQUE',
       PRECISION=1.e-15),
    _F(FONCTION=ACCE1, VALE_PARA=0.025, VALE_REFE=1.0, REFERENCE='ANALYTIQUE',
       PRECISION=1.e-15),))
FIN()
");
    assert_eq!(code, Some(0), "{out}");
    assert_eq!(summary(&out), "tests: 5 OK, 0 NOOK", "{out}");
}

/// sdnd121a's pattern: a lower-case keyword (f=f), `pi` from the file's context, and the
/// formula given directly to DYNA_VIBRA's FONC_MULT (sdnd104a does the same with ACCE2).
/// The formula equals Fa sin(2 pi f t) written in the file (the same f64 operations).
#[test]
fn sdnd121a_pattern_lower_case_keyword_and_pi() {
    let (code, out) = run("DEBUT()
f = 5
Fa = 3.0e3
EXCIT = FORMULE(VALE=\"Fa*sin(2*pi*f*(INST))\", Fa=Fa, f=f, NOM_PARA=\"INST\")
for t in (0.01, 0.037, 0.05, 0.2):
    TEST_FONCTION(VALEUR=_F(FONCTION=EXCIT, VALE_PARA=t, VALE_REFE=Fa*sin(2*pi*f*t),
                            REFERENCE='ANALYTIQUE', PRECISION=0.))
x = EXCIT(0.05)
TEST_FONCTION(VALEUR=_F(FONCTION=EXCIT, VALE_PARA=0.05, VALE_REFE=x, REFERENCE='ANALYTIQUE',
                        PRECISION=0.))
FIN()
");
    assert_eq!(code, Some(0), "{out}");
    assert_eq!(summary(&out), "tests: 5 OK, 0 NOOK", "{out}");
}

/// The variables of the file the expression reads are captured when FORMULE runs: a later
/// assignment does not change the formula (Code_Aster's formula keeps its context).
#[test]
fn file_variables_are_captured_at_definition() {
    let (code, out) = run("DEBUT()
A = 2.
F = FORMULE(VALE='A*X', NOM_PARA='X')
A = 100.
TEST_FONCTION(VALEUR=_F(FONCTION=F, VALE_PARA=3., VALE_REFE=6., REFERENCE='ANALYTIQUE',
                        PRECISION=0.))
print('F(3) =', F(3.), 'A =', A)
FIN()
");
    assert_eq!(code, Some(0), "{out}");
    assert!(out.contains("F(3) = 6.0 A = 100.0"), "{out}");
}

/// Each error stops the run at FORMULE's line (or the line that uses the formula) and
/// names the keyword.
#[test]
fn errors_name_the_line_and_the_keyword() {
    let cases: &[(&str, &[&str])] = &[
        (
            "W = 3.\nF = FORMULE(VALE='sin(W*INST))', NOM_PARA='INST')\n",
            &[
                "case.comm:2:",
                "VALE",
                "unmatched ')' (column 12 of 'sin(W*INST))')",
            ],
        ),
        (
            "F = FORMULE(VALE='2*INST +', NOM_PARA='INST')\n",
            &["case.comm:1:", "VALE", "invalid syntax"],
        ),
        (
            "F = FORMULE(VALE='sin(OMEGA*INST)', OMEGAA=3., NOM_PARA='INST')\n",
            &[
                "case.comm:1:",
                "VALE",
                "name 'OMEGA' is not defined",
                "did you mean 'OMEGAA'?",
            ],
        ),
        (
            "T = DEFI_FONCTION(NOM_PARA='INST', VALE=(0., 0., 1., 1.))\n\
             F = FORMULE(VALE='G*INST', G=T, NOM_PARA='INST')\n",
            &[
                "case.comm:2:",
                "G= binds a name",
                "a formula computes with numbers only",
            ],
        ),
        (
            "F = FORMULE(VALE_C='INST', NOM_PARA='INST')\n",
            &[
                "case.comm:1:",
                "FORMULE/VALE_C",
                "complex formulas (VALE_C) are not supported",
            ],
        ),
        (
            "F = FORMULE(VALE='X*Y', NOM_PARA=('X', 'Y'))\n\
             TEST_FONCTION(VALEUR=_F(FONCTION=F, VALE_PARA=1., VALE_CALC=1.))\n",
            &[
                "case.comm:2:",
                "FONCTION",
                "formula F has 2 parameters (X, Y)",
            ],
        ),
        (
            "F = FORMULE(VALE='log(INST)', NOM_PARA='INST')\n\
             TEST_FONCTION(VALEUR=_F(FONCTION=F, VALE_PARA=-1., VALE_CALC=1.))\n",
            &[
                "case.comm:2:",
                "formula F at INST=-1: log(): math domain error",
            ],
        ),
        (
            "F = FORMULE(VALE='INST', NOM_PARA='INST')\n\
             G = CALC_FONC_INTERP(FONCTION=F, VALE_PARA=(0., 2., 1.))\n",
            &[
                "case.comm:2:",
                "CALC_FONC_INTERP/VALE_PARA",
                "must increase strictly",
            ],
        ),
        (
            "F = FORMULE(VALE='INST', NOM_PARA='INST')\n\
             G = CALC_FONC_INTERP(FONCTION=F, VALE_PARA=(0., 1.), NOM_PARA='FREQ')\n",
            &[
                "case.comm:2:",
                "NOM_PARA",
                "F is a function of INST, not of FREQ",
            ],
        ),
        (
            "A = DEFI_FONCTION(NOM_PARA='INST', VALE=(0., 0., 1., 1.))\n\
             B = DEFI_FONCTION(NOM_PARA='INST', VALE=(2., 0., 3., 1.))\n\
             C = CALC_FONCTION(COMB=(_F(FONCTION=A, COEF=1.), _F(FONCTION=B, COEF=1.)))\n",
            &["case.comm:3:", "COMB", "no abscissa in common"],
        ),
        (
            "A = DEFI_FONCTION(NOM_PARA='INST', VALE=(0., 0., 1., 1.))\n\
             C = CALC_FONCTION(INTEGRE=_F(FONCTION=A, METHODE='SIMPSON'))\n",
            &["case.comm:2:", "INTEGRE/METHODE", "SIMPSON"],
        ),
    ];
    for (body, expected) in cases {
        // DEBUT() on the body's first line, so that the lines count as in the body.
        let (code, out) = run(&format!("DEBUT() ; {body}FIN()\n"));
        assert_eq!(code, Some(2), "{body}\n{out}");
        for e in *expected {
            assert!(out.contains(e), "{body}: expected {e}\n{out}");
        }
    }
}

/// `aster-nl check` runs no operator but finds what FORMULE would refuse, and accepts the
/// rest (a formula called like a function is a value only a run knows).
#[test]
fn check_finds_formula_errors_and_accepts_good_files() {
    let dir = tempfile::tempdir().unwrap();
    let (code, out) = run_in(
        dir.path(),
        "check",
        "DEBUT()
W = 3.
F = FORMULE(VALE='sin(W*INST)', NOM_PARA='INST')
x = F(0.5) * 2
G = CALC_FONC_INTERP(FONCTION=F, VALE_PARA=(0., 0.5, 1.))
C = CALC_FONCTION(COMB=(_F(FONCTION=G, COEF=2.), _F(FONCTION=G, COEF=-1.)))
TEST_FONCTION(VALEUR=_F(FONCTION=F, VALE_PARA=0.5, VALE_CALC=x))
FIN()
",
    );
    assert_eq!(code, Some(0), "{out}");
    let (code, out) = run_in(
        dir.path(),
        "check",
        "DEBUT()
F = FORMULE(VALE='sin(OMEGA*INST)', NOM_PARA='INST')
G = FORMULE(VALE='cos(INST', NOM_PARA='INST')
FIN()
",
    );
    assert_eq!(code, Some(2), "{out}");
    assert!(out.contains("2 error(s)"), "{out}");
    assert!(out.contains("name 'OMEGA' is not defined"), "{out}");
    assert!(out.contains("was never closed"), "{out}");
}

/// A formula is kept in the database: a run continued by POURSUITE calls it, samples it
/// and gives it to TEST_FONCTION.
#[test]
fn a_formula_survives_poursuite() {
    let dir = tempfile::tempdir().unwrap();
    let db = dir.path().join("study.db");
    let first = dir.path().join("first.comm");
    std::fs::write(
        &first,
        "DEBUT()\nW = 4.\nF = FORMULE(VALE='W*INST**2 + 1', NOM_PARA='INST')\nFIN()\n",
    )
    .unwrap();
    let o = bin()
        .arg("run")
        .arg(&first)
        .arg("--db")
        .arg(&db)
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(0), "{}", text(&o));
    let second = dir.path().join("second.comm");
    std::fs::write(
        &second,
        "POURSUITE()
G = CALC_FONC_INTERP(FONCTION=F, VALE_PARA=(0., 1., 2.))
TEST_FONCTION(VALEUR=(_F(FONCTION=F, VALE_PARA=0.5, VALE_REFE=2., REFERENCE='ANALYTIQUE',
                         PRECISION=0.),
                      _F(FONCTION=G, VALE_PARA=1.5, VALE_REFE=(5. + 17.) / 2.,
                         REFERENCE='ANALYTIQUE', PRECISION=0.),))
print('F(3) =', F(3.))
FIN()
",
    )
    .unwrap();
    let o = bin()
        .arg("run")
        .arg(&second)
        .arg("--db")
        .arg(&db)
        .output()
        .unwrap();
    let out = text(&o);
    assert_eq!(o.status.code(), Some(0), "{out}");
    assert!(out.contains("F(3) = 37.0"), "{out}");
    assert_eq!(summary(&out), "tests: 2 OK, 0 NOOK", "{out}");
}
