//! NORM_MODE through the binary, against closed forms, and CALC_MODES as Code_Aster files
//! call it (no OPTION, SOLVEUR_MODAL/MODE_RIGIDE).
//!
//! The main system is a chain wall – k – m – k – m along X (k = 100 N/m, m = 2 kg): with
//! K = k[[2, -1], [-1, 1]] and M = m·I, ω²_j = (k/m)(3 ∓ √5)/2 and the mode j is
//! (1, r_j) with r_j = (1 ± √5)/2 (the golden ratio and its conjugate), so every
//! normalisation has an exact value: MASS_GENE makes the shape (1, r)/√(m(1 + r²)) and
//! RIGI_GENE = ω²; DX of N1 = 1 makes MASS_GENE = m(1 + r²). Shapes are compared to
//! 1e-12 (the solver and the closed form each lose a few ulps).

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::Command;

const K: f64 = 100.0;
const M: f64 = 2.0;

const CHAIN_MAIL: &str = "TITRE
 two masses on two springs along X
FINSF
COOR_3D
 N0  0.  0.  0.
 N1  1.  0.  0.
 N2  2.  0.  0.
FINSF
SEG2
 S1 N0 N1
 S2 N1 N2
FINSF
POI1
 P1 N1
 P2 N2
FINSF
GROUP_MA NOM=RESSORTS
 S1 S2
FINSF
GROUP_MA NOM=S1
 S1
FINSF
GROUP_MA NOM=S2
 S2
FINSF
GROUP_MA NOM=MASSES
 P1 P2
FINSF
GROUP_NO NOM=WALL
 N0
FINSF
GROUP_NO NOM=TIP
 N2
FINSF
GROUP_NO NOM=ALL
 N0 N1 N2
FINSF
FIN
";

/// The chain up to its assembled RIGI and MASS (N0 held by AFFE_CHAR_CINE, DY and DZ
/// everywhere).
fn chain_head() -> String {
    format!(
        "DEBUT()
import math
k = {K:?}
m = {M:?}
MAIL = LIRE_MAILLAGE(FORMAT='ASTER')
MODELE = AFFE_MODELE(MAILLAGE=MAIL, AFFE=_F(TOUT='OUI', PHENOMENE='MECANIQUE', MODELISATION='DIS_T'))
CARA = AFFE_CARA_ELEM(MODELE=MODELE,
                      DISCRET=(_F(GROUP_MA='RESSORTS', CARA='K_T_D_L', VALE=(k, 0., 0.)),
                               _F(GROUP_MA='MASSES', CARA='M_T_D_N', VALE=m),))
CL = AFFE_CHAR_CINE(MODELE=MODELE, MECA_IMPO=(_F(GROUP_NO='WALL', DX=0.), _F(GROUP_NO='ALL', DY=0., DZ=0.)))
ASSEMBLAGE(MODELE=MODELE, CARA_ELEM=CARA, CHAR_CINE=CL, NUME_DDL=CO('NUME'),
           MATR_ASSE=(_F(MATRICE=CO('RIGI'), OPTION='RIGI_MECA'),
                      _F(MATRICE=CO('MASS'), OPTION='MASS_MECA')))
"
    )
}

/// The same two masses joined by one spring k and free along X (S1 has no stiffness):
/// a rigid-body mode (1, 1) at ω = 0 and (1, -1) at ω² = 2k/m.
fn free_free_head() -> String {
    format!(
        "DEBUT()
k = {K:?}
m = {M:?}
MAIL = LIRE_MAILLAGE(FORMAT='ASTER')
MODELE = AFFE_MODELE(MAILLAGE=MAIL, AFFE=_F(TOUT='OUI', PHENOMENE='MECANIQUE', MODELISATION='DIS_T'))
CARA = AFFE_CARA_ELEM(MODELE=MODELE,
                      DISCRET=(_F(GROUP_MA='S1', CARA='K_T_D_L', VALE=(0., 0., 0.)),
                               _F(GROUP_MA='S2', CARA='K_T_D_L', VALE=(k, 0., 0.)),
                               _F(GROUP_MA='MASSES', CARA='M_T_D_N', VALE=m),))
CL = AFFE_CHAR_CINE(MODELE=MODELE, MECA_IMPO=(_F(GROUP_NO='WALL', DX=0.), _F(GROUP_NO='ALL', DY=0., DZ=0.)))
ASSEMBLAGE(MODELE=MODELE, CARA_ELEM=CARA, CHAR_CINE=CL, NUME_DDL=CO('NUME'),
           MATR_ASSE=(_F(MATRICE=CO('RIGI'), OPTION='RIGI_MECA'),
                      _F(MATRICE=CO('MASS'), OPTION='MASS_MECA')))
"
    )
}

/// ω²_j of the chain, j = 1, 2.
fn omega2(j: usize) -> f64 {
    let s = 5f64.sqrt();
    if j == 1 {
        K / M * (3.0 - s) / 2.0
    } else {
        K / M * (3.0 + s) / 2.0
    }
}

/// r_j = x2/x1 of the chain's mode j.
fn ratio(j: usize) -> f64 {
    let s = 5f64.sqrt();
    if j == 1 {
        (1.0 + s) / 2.0
    } else {
        (1.0 - s) / 2.0
    }
}

struct Run {
    code: Option<i32>,
    out: String,
    db: PathBuf,
    _dir: tempfile::TempDir,
}

/// `aster-nl run` of `comm` with `mail` beside it.
fn run(comm: &str, mail: &str) -> Run {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("case.comm");
    std::fs::write(&path, comm).unwrap();
    std::fs::write(dir.path().join("case.mail"), mail).unwrap();
    let db = dir.path().join("case.db");
    let o = Command::new(env!("CARGO_BIN_EXE_aster-nl"))
        .arg("run")
        .arg(&path)
        .arg("--db")
        .arg(&db)
        .output()
        .unwrap();
    let out = format!(
        "{}{}",
        String::from_utf8_lossy(&o.stdout),
        String::from_utf8_lossy(&o.stderr)
    );
    Run {
        code: o.status.code(),
        out,
        db,
        _dir: dir,
    }
}

fn run_ok(comm: &str, mail: &str, tests: usize) -> Run {
    let r = run(comm, mail);
    assert_eq!(r.code, Some(0), "{comm}\n{}", r.out);
    assert!(
        r.out.contains(&format!("tests: {tests} OK, 0 NOOK")),
        "{comm}\n{}",
        r.out
    );
    r
}

/// One stored mode: FREQ, OMEGA2, MASS_GENE, RIGI_GENE and the shape by (node, cmp).
#[derive(Debug)]
struct Stored {
    freq: f64,
    mass: f64,
    rigi: f64,
    shape: BTreeMap<(String, String), f64>,
}

impl Stored {
    fn at(&self, node: &str, cmp: &str) -> f64 {
        self.shape[&(node.to_string(), cmp.to_string())]
    }
}

fn modes(db: &Path, concept: &str) -> Vec<Stored> {
    let c = rusqlite::Connection::open(db).unwrap();
    let mut stmt = c
        .prepare(
            "SELECT NUME_ORDRE, FREQ, MASS_GENE, RIGI_GENE FROM modes WHERE concept = ?1 \
             ORDER BY NUME_ORDRE",
        )
        .unwrap();
    let rows: Vec<(i64, f64, f64, f64)> = stmt
        .query_map([concept], |r| {
            Ok((r.get(0)?, r.get(1)?, r.get(2)?, r.get(3)?))
        })
        .unwrap()
        .collect::<Result<_, _>>()
        .unwrap();
    let mut shapes = c
        .prepare(
            "SELECT NOEUD, NOM_CMP, value FROM mode_shapes WHERE concept = ?1 AND NUME_ORDRE = ?2",
        )
        .unwrap();
    rows.into_iter()
        .map(|(n, freq, mass, rigi)| {
            let shape = shapes
                .query_map(rusqlite::params![concept, n], |r| {
                    Ok(((r.get(0)?, r.get(1)?), r.get(2)?))
                })
                .unwrap()
                .collect::<Result<_, _>>()
                .unwrap();
            Stored {
                freq,
                mass,
                rigi,
                shape,
            }
        })
        .collect()
}

/// (name, type, operator) of every concept of the study.
fn concepts(db: &Path) -> Vec<(String, String, String)> {
    let c = rusqlite::Connection::open(db).unwrap();
    let mut stmt = c
        .prepare("SELECT name, type, operator FROM concepts ORDER BY rowid")
        .unwrap();
    stmt.query_map([], |r| Ok((r.get(0)?, r.get(1)?, r.get(2)?)))
        .unwrap()
        .collect::<Result<_, _>>()
        .unwrap()
}

fn close(a: f64, b: f64, rel: f64) -> bool {
    (a - b).abs() <= rel * a.abs().max(b.abs()).max(f64::MIN_POSITIVE)
}

#[test]
fn code_aster_pattern_mass_gene_in_place_gives_unit_mass_and_omega2() {
    // The lines of Code_Aster's validation files: CALC_MODES without OPTION, then
    // NORM_MODE in place. TEST_RESU checks the normalised values through the concept.
    let comm = format!(
        "{}MODE_MEC = CALC_MODES(MATR_RIGI=RIGI, MATR_MASS=MASS)
MODE_MEC = NORM_MODE(reuse=MODE_MEC, MODE=MODE_MEC, NORME=\"MASS_GENE\")
S5 = math.sqrt(5.)
TEST_RESU(RESU=(
  _F(RESULTAT=MODE_MEC, NUME_ORDRE=1, PARA='MASS_GENE', VALE_REFE=1., REFERENCE='ANALYTIQUE', PRECISION=1.e-12),
  _F(RESULTAT=MODE_MEC, NUME_ORDRE=2, PARA='MASS_GENE', VALE_REFE=1., REFERENCE='ANALYTIQUE', PRECISION=1.e-12),
  _F(RESULTAT=MODE_MEC, NUME_ORDRE=1, PARA='RIGI_GENE', VALE_REFE=k/m*(3. - S5)/2., REFERENCE='ANALYTIQUE', PRECISION=1.e-12),
  _F(RESULTAT=MODE_MEC, NUME_ORDRE=2, PARA='RIGI_GENE', VALE_REFE=k/m*(3. + S5)/2., REFERENCE='ANALYTIQUE', PRECISION=1.e-12),
  _F(RESULTAT=MODE_MEC, NUME_ORDRE=1, PARA='FREQ', VALE_REFE=math.sqrt(k/m*(3. - S5)/2.)/(2.*math.pi), REFERENCE='ANALYTIQUE', PRECISION=1.e-12),
))
FIN()
",
        chain_head()
    );
    let r = run_ok(&comm, CHAIN_MAIL, 5);
    // Changed in place: one mode_meca, still CALC_MODES's concept.
    let mode_metas: Vec<_> = concepts(&r.db)
        .into_iter()
        .filter(|c| c.1 == "mode_meca")
        .collect();
    assert_eq!(
        mode_metas,
        vec![(
            "MODE_MEC".to_string(),
            "mode_meca".to_string(),
            "CALC_MODES".to_string()
        )]
    );
    let stored = modes(&r.db, "MODE_MEC");
    assert_eq!(stored.len(), 2);
    for (i, s) in stored.iter().enumerate() {
        let j = i + 1;
        assert!(close(s.mass, 1.0, 1e-12), "mode {j}: {s:?}");
        assert!(close(s.rigi, omega2(j), 1e-12), "mode {j}: {s:?}");
        // The shape itself, independently of the stored MASS_GENE: m(x1² + x2²) = 1 and
        // x2/x1 = r_j; zero on the blocked DOFs.
        let (x1, x2) = (s.at("N1", "DX"), s.at("N2", "DX"));
        assert!(
            close(M * (x1 * x1 + x2 * x2), 1.0, 1e-12),
            "mode {j}: {s:?}"
        );
        assert!(close(x2 / x1, ratio(j), 1e-12), "mode {j}: {s:?}");
        assert_eq!(s.at("N0", "DX"), 0.0);
        assert_eq!(s.at("N1", "DY"), 0.0);
    }
}

#[test]
fn a_node_component_becomes_one_and_mode_signe_sets_the_sign() {
    let comm = format!(
        "{}MODES = CALC_MODES(MATR_RIGI=RIGI, MATR_MASS=MASS, OPTION='PLUS_PETITE', CALC_FREQ=_F(NMAX_FREQ=2))
PN1 = NORM_MODE(MODE=MODES, NOEUD='N1', NOM_CMP='DX', INFO=2)
PTIP = NORM_MODE(MODE=MODES, GROUP_NO='TIP', NOM_CMP='DX')
NEG = NORM_MODE(MODE=MODES, NORME='MASS_GENE', MODE_SIGNE=_F(GROUP_NO='TIP', NOM_CMP='DX', SIGNE='NEGATIF'))
POS = NORM_MODE(MODE=MODES, NORME='MASS_GENE', MODE_SIGNE=_F(NOEUD='N2', NOM_CMP='DX'))
S5 = math.sqrt(5.)
TEST_RESU(RESU=(
  _F(RESULTAT=PN1, NUME_ORDRE=1, NOM_CHAM='DEPL', NOEUD='N1', NOM_CMP='DX', VALE_REFE=1., REFERENCE='ANALYTIQUE', PRECISION=1.e-14),
  _F(RESULTAT=PN1, NUME_ORDRE=1, NOM_CHAM='DEPL', NOEUD='N2', NOM_CMP='DX', VALE_REFE=(1. + S5)/2., REFERENCE='ANALYTIQUE', PRECISION=1.e-12),
  _F(RESULTAT=PN1, NUME_ORDRE=2, NOM_CHAM='DEPL', NOEUD='N2', NOM_CMP='DX', VALE_REFE=(1. - S5)/2., REFERENCE='ANALYTIQUE', PRECISION=1.e-12),
))
FIN()
",
        chain_head()
    );
    let r = run_ok(&comm, CHAIN_MAIL, 3);
    // INFO=2: the factor of each mode.
    assert!(
        r.out
            .contains("NORM_MODE PN1: 2 mode(s), DX of node N1 = 1"),
        "{}",
        r.out
    );
    assert!(r.out.contains("FACTEUR"), "{}", r.out);
    let before = modes(&r.db, "MODES");
    for (name, node) in [("PN1", "N1"), ("PTIP", "N2")] {
        for (i, s) in modes(&r.db, name).iter().enumerate() {
            let j = i + 1;
            let r_j = ratio(j);
            assert!(
                close(s.at(node, "DX"), 1.0, 1e-15),
                "{name} mode {j}: {s:?}"
            );
            // The shape is (1, r) or (1/r, 1): MASS_GENE m(1 + r²) or m(1 + 1/r²), and
            // RIGI_GENE ω² times that.
            let mass = if node == "N1" {
                M * (1.0 + r_j * r_j)
            } else {
                M * (1.0 + 1.0 / (r_j * r_j))
            };
            assert!(close(s.mass, mass, 1e-12), "{name} mode {j}: {s:?}");
            assert!(
                close(s.rigi, omega2(j) * mass, 1e-12),
                "{name} mode {j}: {s:?}"
            );
            // Frequencies unchanged.
            assert_eq!(s.freq, before[i].freq);
        }
    }
    for (name, positive) in [("NEG", false), ("POS", true)] {
        for (i, s) in modes(&r.db, name).iter().enumerate() {
            let j = i + 1;
            let r_j = ratio(j);
            let norm = (M * (1.0 + r_j * r_j)).sqrt();
            let tip = s.at("N2", "DX");
            assert_eq!(tip > 0.0, positive, "{name} mode {j}: {s:?}");
            assert!(
                close(tip.abs(), r_j.abs() / norm, 1e-12),
                "{name} mode {j}: {s:?}"
            );
            // N1 moves with N2 in mode 1 and against it in mode 2.
            let n1 = s.at("N1", "DX");
            assert!(
                close(n1, tip.signum() * r_j.signum() / norm, 1e-12),
                "{name} mode {j}: {s:?}"
            );
            assert!(close(s.mass, 1.0, 1e-12));
        }
    }
    // MODES itself is as CALC_MODES left it (TRAN_ROTA: its largest component is +1).
    for s in &before {
        let largest = s
            .shape
            .values()
            .fold(0.0f64, |a, v| if v.abs() > a.abs() { *v } else { a });
        assert!(close(largest, 1.0, 1e-15), "{s:?}");
    }
}

#[test]
fn reuse_changes_the_basis_so_what_was_projected_on_it_is_refused() {
    // A NUME_DDL_GENE of the old shapes no longer describes MODES once NORM_MODE rewrote
    // it in place (a new generation, as for every reuse=): using it is an error.
    let comm = format!(
        "{}MODES = CALC_MODES(MATR_RIGI=RIGI, MATR_MASS=MASS, OPTION='PLUS_PETITE', CALC_FREQ=_F(NMAX_FREQ=2))
NUMEGE = NUME_DDL_GENE(BASE=MODES, STOCKAGE='DIAG')
MODES = NORM_MODE(reuse=MODES, MODE=MODES, NORME='MASS_GENE')
MGEN = PROJ_MATR_BASE(BASE=MODES, NUME_DDL_GENE=NUMEGE, MATR_ASSE=MASS)
FIN()
",
        chain_head()
    );
    let r = run(&comm, CHAIN_MAIL);
    assert_eq!(r.code, Some(2), "{}", r.out);
    assert!(
        r.out
            .contains("NUMEGE was computed from MODES, but MODES has been redefined since"),
        "{}",
        r.out
    );
    // A NUME_DDL_GENE made after NORM_MODE is fine, and the projected mass is I.
    let comm = format!(
        "{}MODES = CALC_MODES(MATR_RIGI=RIGI, MATR_MASS=MASS, OPTION='PLUS_PETITE', CALC_FREQ=_F(NMAX_FREQ=2))
MODES = NORM_MODE(reuse=MODES, MODE=MODES, NORME='MASS_GENE')
NUMEGE = NUME_DDL_GENE(BASE=MODES, STOCKAGE='PLEIN')
MGEN = PROJ_MATR_BASE(BASE=MODES, NUME_DDL_GENE=NUMEGE, MATR_ASSE=MASS)
FIN()
",
        chain_head()
    );
    let r = run_ok(&comm, CHAIN_MAIL, 0);
    let c = rusqlite::Connection::open(&r.db).unwrap();
    let mut stmt = c
        .prepare("SELECT row, col, value FROM gene_entries WHERE concept = 'MGEN'")
        .unwrap();
    let entries: Vec<(i64, i64, f64)> = stmt
        .query_map([], |r| Ok((r.get(0)?, r.get(1)?, r.get(2)?)))
        .unwrap()
        .collect::<Result<_, _>>()
        .unwrap();
    assert!(!entries.is_empty());
    for (i, j, v) in entries {
        let want = if i == j { 1.0 } else { 0.0 };
        assert!((v - want).abs() < 1e-12, "MGEN[{i}, {j}] = {v}");
    }
}

#[test]
fn a_redefinition_without_reuse_makes_a_new_concept_with_the_same_matrices() {
    // `MODES = NORM_MODE(MODE=MODES)`: MODES is replaced by a new concept of NORM_MODE that
    // keeps the matrices it was computed from (PROJ_VECT_BASE reads MATR_MASS from it).
    let comm = format!(
        "{}MODES = CALC_MODES(MATR_RIGI=RIGI, MATR_MASS=MASS, OPTION='PLUS_PETITE', CALC_FREQ=_F(NMAX_FREQ=2))
MODES = NORM_MODE(MODE=MODES, NORME='EUCL')
OTHER = NORM_MODE(MODE=MODES, NORME='EUCL_TRAN')
FIN()
",
        chain_head()
    );
    let r = run_ok(&comm, CHAIN_MAIL, 0);
    let c = concepts(&r.db);
    assert!(
        c.contains(&("MODES".into(), "mode_meca".into(), "NORM_MODE".into())),
        "{c:?}"
    );
    assert!(
        c.contains(&("OTHER".into(), "mode_meca".into(), "NORM_MODE".into())),
        "{c:?}"
    );
    let conn = rusqlite::Connection::open(&r.db).unwrap();
    for name in ["MODES", "OTHER"] {
        let m: String = conn
            .query_row(
                "SELECT json FROM concept_data WHERE concept = ?1 AND key = 'matrices'",
                [name],
                |r| r.get(0),
            )
            .unwrap();
        assert!(
            m.contains("\"RIGI\"") && m.contains("\"MASS\""),
            "{name}: {m}"
        );
        // EUCL = EUCL_TRAN on translations only: x1² + x2² = 1, sign kept.
        for (i, s) in modes(&r.db, name).iter().enumerate() {
            let (x1, x2) = (s.at("N1", "DX"), s.at("N2", "DX"));
            assert!(close(x1 * x1 + x2 * x2, 1.0, 1e-12), "{name} {s:?}");
            assert!(close(x2 / x1, ratio(i + 1), 1e-12), "{name} {s:?}");
            assert!(close(s.mass, M, 1e-12), "{name} {s:?}");
        }
    }
}

/// The chain's modes, then `call`: the run must stop on it with every `expected` text in
/// its output, and leave no concept X.
fn refused(call: &str, expected: &[&str]) {
    let comm = format!(
        "{}MODES = CALC_MODES(MATR_RIGI=RIGI, MATR_MASS=MASS, OPTION='PLUS_PETITE', CALC_FREQ=_F(NMAX_FREQ=2))
{call}
FIN()
",
        chain_head()
    );
    let r = run(&comm, CHAIN_MAIL);
    assert_eq!(r.code, Some(2), "{call}\n{}", r.out);
    for e in expected {
        assert!(r.out.contains(e), "{call}: expected '{e}' in\n{}", r.out);
    }
    assert!(
        !concepts(&r.db).iter().any(|c| c.0 == "X"),
        "{call}: a failed NORM_MODE leaves nothing"
    );
}

#[test]
fn bad_nodes_and_components_are_refused_naming_the_keyword() {
    refused(
        "X = NORM_MODE(MODE=MODES, NOEUD='N9', NOM_CMP='DX')",
        &[
            "NORM_MODE/NOEUD",
            "MODES has no DOF on node 'N9'",
            "N0, N1, N2",
        ],
    );
    refused(
        "X = NORM_MODE(MODE=MODES, NOEUD='N1')",
        &["NORM_MODE", "NOM_CMP"],
    );
    refused(
        "X = NORM_MODE(MODE=MODES, NORME='TRAN', NOM_CMP='DX')",
        &["NORM_MODE/NOM_CMP", "given alone"],
    );
    refused(
        "X = NORM_MODE(MODE=MODES, NOEUD='N1', NOM_CMP='DRX')",
        &["NORM_MODE/NOM_CMP", "node N1 has no DOF DRX", "DX, DY, DZ"],
    );
    refused(
        "X = NORM_MODE(MODE=MODES, NOEUD='N1', NOM_CMP='DXX')",
        &[
            "NORM_MODE/NOM_CMP",
            "unknown component 'DXX'",
            "did you mean 'DRX' or 'DX'?",
        ],
    );
    refused(
        "X = NORM_MODE(MODE=MODES, GROUP_NO='ALL', NOM_CMP='DX')",
        &["NORM_MODE/GROUP_NO", "GROUP_NO 'ALL' holds 3 nodes"],
    );
    refused(
        "X = NORM_MODE(MODE=MODES, NORME='TRAN', NOEUD='N1', NOM_CMP='DX')",
        &["UN_PARMI"],
    );
    refused(
        "X = NORM_MODE(MODE=MODES, AVEC_CMP='DRX')",
        &[
            "NORM_MODE/AVEC_CMP",
            "leaves no DOF of MODES's numbering",
            "DX, DY, DZ",
        ],
    );
    refused(
        "X = NORM_MODE(MODE=MODES, SANS_CMP=('DX', 'DY', 'DZ'))",
        &["NORM_MODE/SANS_CMP", "leaves no DOF"],
    );
    refused(
        "X = NORM_MODE(MODE=MODES, NORME='MASS_GENE', MODE_SIGNE=_F(NOEUD='N7', NOM_CMP='DX'))",
        &["NORM_MODE/MODE_SIGNE/NOEUD", "no DOF on node 'N7'"],
    );
    refused(
        "X = NORM_MODE(MODE=MODES, NORME='MASS_GENE', MASSE=RIGI)",
        &["NORM_MODE/MASSE", "RIGI is a RIGI_MECA matrix"],
    );
    refused(
        "X = NORM_MODE(MODE=MODES, NORME='EUCL', SIGNE='NEGATIF')",
        &["SIGNE"],
    );
}

#[test]
fn a_component_that_is_zero_is_an_error_naming_the_mode_and_keyword() {
    // DX of N0 is blocked: 0 in every mode.
    refused(
        "X = NORM_MODE(MODE=MODES, NOEUD='N0', NOM_CMP='DX')",
        &[
            "NORM_MODE/NOEUD",
            "mode 1 (6.955326e-1 Hz) is 0 on DX of node N0",
            "0 in every mode",
        ],
    );
    // The same through a one-node group names GROUP_NO.
    refused(
        "X = NORM_MODE(MODE=MODES, GROUP_NO='WALL', NOM_CMP='DX')",
        &["NORM_MODE/GROUP_NO", "mode 1", "is 0 on DX of node N0"],
    );
    // Translations only, of a model whose modes move along X only: DY is 0.
    refused(
        "X = NORM_MODE(MODE=MODES, AVEC_CMP='DY')",
        &[
            "NORM_MODE/AVEC_CMP",
            "mode 1",
            "is 0 on the components AVEC_CMP=DY selects",
        ],
    );
}

#[test]
fn rigi_gene_of_a_rigid_body_mode_is_refused_and_mass_gene_scales_it() {
    let comm = format!(
        "{}MODES = CALC_MODES(MATR_RIGI=RIGI, MATR_MASS=MASS, OPTION='PLUS_PETITE', CALC_FREQ=_F(NMAX_FREQ=2))
X = NORM_MODE(MODE=MODES, NORME='RIGI_GENE')
FIN()
",
        free_free_head()
    );
    let r = run(&comm, CHAIN_MAIL);
    assert_eq!(r.code, Some(2), "{}", r.out);
    for e in [
        "NORM_MODE/NORME",
        "mode 1",
        "zero to round-off",
        "MASS_GENE",
    ] {
        assert!(r.out.contains(e), "expected '{e}' in\n{}", r.out);
    }
    // With RAIDE given, the same (the scale of K is RAIDE's).
    let comm = comm.replace("NORME='RIGI_GENE')", "NORME='RIGI_GENE', RAIDE=RIGI)");
    let r = run(&comm, CHAIN_MAIL);
    assert_eq!(r.code, Some(2), "{}", r.out);
    assert!(
        r.out.contains("mode 1") && r.out.contains("zero to round-off"),
        "{}",
        r.out
    );
    // MASS_GENE: the rigid-body mode is (1, 1)/√(2m), the other (1, -1)/√(2m), ω² = 2k/m.
    let comm = format!(
        "{}MODES = CALC_MODES(MATR_RIGI=RIGI, MATR_MASS=MASS, OPTION='PLUS_PETITE', CALC_FREQ=_F(NMAX_FREQ=2))
MODES = NORM_MODE(reuse=MODES, MODE=MODES, NORME='MASS_GENE', MODE_SIGNE=_F(NOEUD='N1', NOM_CMP='DX'))
FIN()
",
        free_free_head()
    );
    let r = run_ok(&comm, CHAIN_MAIL, 0);
    let s = modes(&r.db, "MODES");
    let a = 1.0 / (2.0 * M).sqrt();
    assert!(
        close(s[0].at("N1", "DX"), a, 1e-12) && close(s[0].at("N2", "DX"), a, 1e-12),
        "{s:?}"
    );
    assert!(
        close(s[1].at("N1", "DX"), a, 1e-12) && close(s[1].at("N2", "DX"), -a, 1e-12),
        "{s:?}"
    );
    assert!(s[0].rigi.abs() < 1e-10 * K / M, "{s:?}");
    assert!(close(s[1].rigi, 2.0 * K / M, 1e-12), "{s:?}");
    assert!(close(s[0].mass, 1.0, 1e-12) && close(s[1].mass, 1.0, 1e-12));
}

/// testcases/beam_cantilever.comm up to its CALC_MODES (20 POU_D_E, DY and DRZ free:
/// rotations as large as translations), then `tail`.
fn beam(tail: &str) -> Run {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("testcases");
    let text = std::fs::read_to_string(root.join("beam_cantilever.comm")).unwrap();
    let head = text.split("BETA_L").next().unwrap();
    let mail = std::fs::read_to_string(root.join("beam_cantilever.mail")).unwrap();
    let r = run(&format!("{head}\n{tail}\nFIN()\n"), &mail);
    assert_eq!(r.code, Some(0), "{}", r.out);
    r
}

fn is_translation(cmp: &str) -> bool {
    matches!(cmp, "DX" | "DY" | "DZ")
}

/// The value of largest magnitude of `s` over the components `keep` selects.
fn largest(s: &Stored, keep: &dyn Fn(&str) -> bool) -> f64 {
    s.shape
        .iter()
        .filter(|((_, c), _)| keep(c))
        .fold(0.0f64, |a, (_, v)| if v.abs() > a.abs() { *v } else { a })
}

fn sum_sq(s: &Stored, keep: &dyn Fn(&str) -> bool) -> f64 {
    s.shape
        .iter()
        .filter(|((_, c), _)| keep(c))
        .map(|(_, v)| v * v)
        .sum()
}

#[test]
fn every_norme_and_component_list_on_a_beam_with_rotations() {
    let r = beam(
        "E = NORM_MODE(MODE=MODES, NORME='EUCL')
ET = NORM_MODE(MODE=MODES, NORME='EUCL_TRAN')
T = NORM_MODE(MODE=MODES, NORME='TRAN')
TR = NORM_MODE(MODE=MODES, NORME='TRAN_ROTA')
AC = NORM_MODE(MODE=MODES, AVEC_CMP='DRZ')
SL = NORM_MODE(MODE=MODES, SANS_CMP='LAGR')
SR = NORM_MODE(MODE=MODES, SANS_CMP=('DRX', 'DRY', 'DRZ'))
SG = NORM_MODE(MODE=MODES, NORME='TRAN', MODE_SIGNE=_F(GROUP_NO='ENCAST', NOM_CMP='DY', SIGNE='NEGATIF'))",
    );
    let all = |_: &str| true;
    let before = modes(&r.db, "MODES");
    assert_eq!(before.len(), 5);
    // The factor of a mode: the ratio of the new shape to the old one at the tip.
    let factor = |s: &Stored, b: &Stored| s.at("N20", "DY") / b.at("N20", "DY");
    let check_gene = |name: &str, s: &Stored, b: &Stored| {
        let f = factor(s, b);
        assert_eq!(s.freq, b.freq, "{name}");
        assert!(close(s.mass, b.mass * f * f, 1e-12), "{name}: {s:?}");
        assert!(close(s.rigi, b.rigi * f * f, 1e-12), "{name}: {s:?}");
    };
    let mut rotation_beyond_one = false;
    for (i, b) in before.iter().enumerate() {
        let e = &modes(&r.db, "E")[i];
        assert!(close(sum_sq(e, &all), 1.0, 1e-12));
        assert!(factor(e, b) > 0.0, "EUCL keeps the sign");
        check_gene("E", e, b);
        let et = &modes(&r.db, "ET")[i];
        assert!(close(sum_sq(et, &is_translation), 1.0, 1e-12));
        assert!(
            sum_sq(et, &all) > 1.0 + 1e-3,
            "the rotations are not in EUCL_TRAN"
        );
        assert!(factor(et, b) > 0.0);
        check_gene("ET", et, b);
        let t = &modes(&r.db, "T")[i];
        assert!(close(largest(t, &is_translation), 1.0, 1e-15), "{t:?}");
        check_gene("T", t, b);
        rotation_beyond_one |= largest(t, &all).abs() > 1.0 + 1e-6;
        let tr = &modes(&r.db, "TR")[i];
        assert!(close(largest(tr, &all), 1.0, 1e-15), "{tr:?}");
        check_gene("TR", tr, b);
        let ac = &modes(&r.db, "AC")[i];
        assert!(close(largest(ac, &|c| c == "DRZ"), 1.0, 1e-15), "{ac:?}");
        check_gene("AC", ac, b);
        // SANS_CMP='LAGR' is every component (TRAN_ROTA), SANS_CMP=rotations is TRAN.
        assert_eq!(modes(&r.db, "SL")[i].shape, tr.shape);
        assert_eq!(modes(&r.db, "SR")[i].shape, t.shape);
        // MODE_SIGNE on the clamped node: 0 in every mode, so TRAN's sign stays.
        assert_eq!(modes(&r.db, "SG")[i].shape, t.shape);
    }
    assert!(
        rotation_beyond_one,
        "some mode turns more than it moves: TRAN and TRAN_ROTA differ"
    );
    assert!(
        r.out
            .contains("<A> <NORM_MODE_1> DY of node N0 is 0 in mode(s) 1, 2, 3, 4, 5"),
        "{}",
        r.out
    );
}

#[test]
fn masse_and_raide_recompute_the_generalized_values_over_the_whole_vector() {
    // On the beam (blocked DOFs) the forms recomputed with the matrices over the full
    // vector are those CALC_MODES stored from the free DOFs.
    let r = beam(
        "MG = NORM_MODE(MODE=MODES, NORME='MASS_GENE')
MGM = NORM_MODE(MODE=MODES, NORME='MASS_GENE', MASSE=M, RAIDE=K, AMOR=M, TITRE='with matrices')
RG = NORM_MODE(MODE=MODES, NORME='RIGI_GENE', RAIDE=K)",
    );
    let (mg, mgm, rg) = (modes(&r.db, "MG"), modes(&r.db, "MGM"), modes(&r.db, "RG"));
    for i in 0..5 {
        assert!(close(mgm[i].mass, 1.0, 1e-12), "{:?}", mgm[i]);
        let w2 = (2.0 * std::f64::consts::PI * mg[i].freq).powi(2);
        assert!(close(mgm[i].rigi, w2, 1e-9), "{:?}", mgm[i]);
        assert!(close(mg[i].rigi, mgm[i].rigi, 1e-9));
        assert!(close(rg[i].rigi, 1.0, 1e-12), "{:?}", rg[i]);
        assert!(close(rg[i].mass, 1.0 / w2, 1e-9), "{:?}", rg[i]);
        for (k, v) in &mg[i].shape {
            assert!((v - mgm[i].shape[k]).abs() <= 1e-10 * largest(&mg[i], &|_| true).abs());
        }
    }
}

#[test]
fn masse_and_raide_other_than_the_modes_own_are_the_ones_used() {
    // Matrices of the same chain with m3 = 3 kg and k3 = 2k, on the same DOFs: MASS_GENE
    // with MASSE=MASS3 makes m3·(x1² + x2²) = 1, and RIGI_GENE, read from the modes, is
    // ω²·m·|φ|² = ω²·m/m3; RAIDE=RIGI3 makes RIGI_GENE twice the modes' own.
    let comm = format!(
        "{}MODES = CALC_MODES(MATR_RIGI=RIGI, MATR_MASS=MASS, OPTION='PLUS_PETITE', CALC_FREQ=_F(NMAX_FREQ=2))
CARA3 = AFFE_CARA_ELEM(MODELE=MODELE,
                       DISCRET=(_F(GROUP_MA='RESSORTS', CARA='K_T_D_L', VALE=(2.*k, 0., 0.)),
                                _F(GROUP_MA='MASSES', CARA='M_T_D_N', VALE=3.),))
ASSEMBLAGE(MODELE=MODELE, CARA_ELEM=CARA3, CHAR_CINE=CL, NUME_DDL=CO('NUME3'),
           MATR_ASSE=(_F(MATRICE=CO('RIGI3'), OPTION='RIGI_MECA'),
                      _F(MATRICE=CO('MASS3'), OPTION='MASS_MECA')))
M3 = NORM_MODE(MODE=MODES, NORME='MASS_GENE', MASSE=MASS3)
K3 = NORM_MODE(MODE=MODES, NORME='MASS_GENE', RAIDE=RIGI3)
FIN()
",
        chain_head()
    );
    let r = run_ok(&comm, CHAIN_MAIL, 0);
    for (i, s) in modes(&r.db, "M3").iter().enumerate() {
        let j = i + 1;
        let (x1, x2) = (s.at("N1", "DX"), s.at("N2", "DX"));
        assert!(
            close(3.0 * (x1 * x1 + x2 * x2), 1.0, 1e-12),
            "mode {j}: {s:?}"
        );
        assert!(close(s.mass, 1.0, 1e-12), "mode {j}: {s:?}");
        assert!(close(s.rigi, omega2(j) * M / 3.0, 1e-12), "mode {j}: {s:?}");
    }
    for (i, s) in modes(&r.db, "K3").iter().enumerate() {
        let j = i + 1;
        let (x1, x2) = (s.at("N1", "DX"), s.at("N2", "DX"));
        assert!(
            close(M * (x1 * x1 + x2 * x2), 1.0, 1e-12),
            "mode {j}: {s:?}"
        );
        assert!(close(s.mass, 1.0, 1e-12), "mode {j}: {s:?}");
        assert!(close(s.rigi, 2.0 * omega2(j), 1e-12), "mode {j}: {s:?}");
    }
}

#[test]
fn with_liaison_ddl_the_full_vector_form_is_the_constrained_one() {
    // One node on springs (KX, KY, KZ) and a mass m, held by DX + 2 DY - DZ = 0
    // (LIAISON_DDL: DY, the largest coefficient's DOF, is expressed by the others). M is
    // m·I on DX, DY, DZ, so MASS_GENE=1 means m·(DX² + DY² + DZ²) = 1 over the full stored
    // vector, the dependent DY included.
    let mail = "COOR_3D\n NO1 0.0 0.0 0.0\nFINSF\nPOI1\n P1 NO1\nFINSF\nGROUP_MA\n MASSE\n P1\nFINSF\nGROUP_NO\n NO1\n NO1\nFINSF\nFIN\n";
    let comm = "DEBUT()
MAIL = LIRE_MAILLAGE(FORMAT='ASTER')
MODELE = AFFE_MODELE(MAILLAGE=MAIL, AFFE=_F(TOUT='OUI', PHENOMENE='MECANIQUE', MODELISATION='DIS_T'))
CARA = AFFE_CARA_ELEM(MODELE=MODELE, DISCRET=(_F(GROUP_MA='MASSE', CARA='K_T_D_N', VALE=(1.e3, 3.e3, 7.e3)),
                                             _F(GROUP_MA='MASSE', CARA='M_T_D_N', VALE=1.5)))
CH = AFFE_CHAR_MECA(MODELE=MODELE, LIAISON_DDL=_F(GROUP_NO=('NO1', 'NO1', 'NO1'), DDL=('DX', 'DY', 'DZ'),
                                                  COEF_MULT=(1., 2., -1.), COEF_IMPO=0.))
ASSEMBLAGE(MODELE=MODELE, CARA_ELEM=CARA, CHARGE=CH, NUME_DDL=CO('NUME'),
           MATR_ASSE=(_F(MATRICE=CO('RIGI'), OPTION='RIGI_MECA'),
                      _F(MATRICE=CO('MASS'), OPTION='MASS_MECA')))
MODES = CALC_MODES(MATR_RIGI=RIGI, MATR_MASS=MASS, OPTION='PLUS_PETITE', CALC_FREQ=_F(NMAX_FREQ=2))
MG = NORM_MODE(MODE=MODES, NORME='MASS_GENE', MASSE=MASS, RAIDE=RIGI)
MS = NORM_MODE(MODE=MODES, NORME='MASS_GENE')
FIN()
";
    let r = run_ok(comm, mail, 0);
    let (mg, ms) = (modes(&r.db, "MG"), modes(&r.db, "MS"));
    assert_eq!(mg.len(), 2);
    for (a, b) in mg.iter().zip(&ms) {
        let (x, y, z) = (a.at("NO1", "DX"), a.at("NO1", "DY"), a.at("NO1", "DZ"));
        assert!(y.abs() > 1e-3, "the dependent DOF moves: {a:?}");
        assert!((x + 2.0 * y - z).abs() < 1e-12 * (x.abs() + y.abs() + z.abs()));
        assert!(close(1.5 * (x * x + y * y + z * z), 1.0, 1e-12), "{a:?}");
        assert!(close(a.mass, 1.0, 1e-12));
        let w2 = (2.0 * std::f64::consts::PI * a.freq).powi(2);
        assert!(close(a.rigi, w2, 1e-10), "{a:?}");
        // Without the matrices, the stored values give the same shapes.
        for (k, v) in &a.shape {
            assert!((v - b.shape[k]).abs() < 1e-12, "{a:?} {b:?}");
        }
    }
}

#[test]
fn calc_modes_without_option_and_with_solveur_modal_mode_rigide() {
    // Code_Aster's defaults: OPTION='PLUS_PETITE', NMAX_FREQ=10; a model with fewer free
    // DOFs gets all its modes, as in Code_Aster.
    let comm = format!(
        "{}MODES = CALC_MODES(MATR_RIGI=RIGI, MATR_MASS=MASS)
MR = CALC_MODES(MATR_RIGI=RIGI, MATR_MASS=MASS, SOLVEUR_MODAL=_F(MODE_RIGIDE='NON', METHODE='TRI_DIAG'))
MO = CALC_MODES(MATR_RIGI=RIGI, MATR_MASS=MASS, SOLVEUR_MODAL=_F(MODE_RIGIDE='OUI', METHODE='TRI_DIAG'))
S5 = math.sqrt(5.)
for R in (MODES, MR, MO):
    TEST_RESU(RESU=(
      _F(RESULTAT=R, NUME_ORDRE=1, PARA='FREQ', VALE_REFE=math.sqrt(k/m*(3. - S5)/2.)/(2.*math.pi), REFERENCE='ANALYTIQUE', PRECISION=1.e-12),
      _F(RESULTAT=R, NUME_ORDRE=2, PARA='FREQ', VALE_REFE=math.sqrt(k/m*(3. + S5)/2.)/(2.*math.pi), REFERENCE='ANALYTIQUE', PRECISION=1.e-12),
    ))
FIN()
",
        chain_head()
    );
    let r = run_ok(&comm, CHAIN_MAIL, 6);
    assert!(
        r.out.contains("CALC_MODES: NMAX_FREQ=10 modes asked but the model has 2 free DOFs: all 2 are computed"),
        "{}",
        r.out
    );
    assert_eq!(modes(&r.db, "MODES").len(), 2);
    // A free-free model: the rigid-body mode is found with MODE_RIGIDE='NON' as with 'OUI'.
    for flag in ["NON", "OUI"] {
        let comm = format!(
            "{}MODES = CALC_MODES(MATR_RIGI=RIGI, MATR_MASS=MASS, SOLVEUR_MODAL=_F(MODE_RIGIDE='{flag}', METHODE='TRI_DIAG'))
FIN()
",
            free_free_head()
        );
        let r = run_ok(&comm, CHAIN_MAIL, 0);
        let s = modes(&r.db, "MODES");
        assert_eq!(s.len(), 2, "{}", r.out);
        assert!(s[0].freq < 1e-6, "{flag}: {s:?}");
        let f2 = (2.0 * K / M).sqrt() / (2.0 * std::f64::consts::PI);
        assert!(close(s[1].freq, f2, 1e-12), "{flag}: {s:?}");
        assert!(r.out.contains("(rigid-body mode)"), "{}", r.out);
    }
    // MODE_RIGIDE takes OUI or NON only.
    let comm = format!(
        "{}MODES = CALC_MODES(MATR_RIGI=RIGI, MATR_MASS=MASS, SOLVEUR_MODAL=_F(MODE_RIGIDE='PEUT_ETRE'))
FIN()
",
        chain_head()
    );
    let r = run(&comm, CHAIN_MAIL);
    assert_ne!(r.code, Some(0), "{}", r.out);
    assert!(r.out.contains("MODE_RIGIDE"), "{}", r.out);
}
