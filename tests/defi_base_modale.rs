//! DEFI_BASE_MODALE through the binary: Ritz bases of normal modes and static vectors on a
//! chain of six masses (testcases/dyna_vibra_ritz.mail), used by the modal chain
//! (NUME_DDL_GENE, PROJ_MATR_BASE, PROJ_BASE, DYNA_VIBRA, REST_GENE_PHYS) and checked
//! against DYNA_VIBRA on the physical DOFs (an independent integration of the full model),
//! against exact properties of the bases, and for the errors a user meets.

mod support;
use support::{case, run_file};

/// The chain of testcases/dyna_vibra_ritz.comm: six masses m = 1 on springs k = 1e4 from a
/// wall, its matrices on NUME, its 5 lowest modes, the first mode's velocity (0.2 m/s at
/// N6), a stop on either side of N6 (gap 5 mm, stiffness 3e3) and the archived instants.
/// STAT is a static vector computed without MODE_STATIQUE: the one mode of the chain with
/// its mass at N6 (1e-6 kg elsewhere), K^-1 e(N6) to about 1e-6.
const PRELUDE: &str = "DEBUT()
import math
N = 6 ; M = 1. ; K = 1.e4 ; KN = 3.e3 ; G = 5.e-3 ; V0 = 0.2
TH = math.pi/(2*N + 1)
MAIL = LIRE_MAILLAGE(FORMAT='ASTER')
MODELE = AFFE_MODELE(MAILLAGE=MAIL, AFFE=_F(TOUT='OUI', PHENOMENE='MECANIQUE', MODELISATION='DIS_T'))
CARA = AFFE_CARA_ELEM(MODELE=MODELE, DISCRET=(_F(GROUP_MA='RESSORTS', CARA='K_T_D_L', VALE=(K, 0., 0.)),
                                             _F(GROUP_MA='MASSES', CARA='M_T_D_N', VALE=M)))
CARAS = AFFE_CARA_ELEM(MODELE=MODELE, DISCRET=(_F(GROUP_MA='RESSORTS', CARA='K_T_D_L', VALE=(K, 0., 0.)),
                                              _F(GROUP_MA='INNER', CARA='M_T_D_N', VALE=1.e-6),
                                              _F(GROUP_MA='TIP', CARA='M_T_D_N', VALE=M)))
BLOC = AFFE_CHAR_MECA(MODELE=MODELE, DDL_IMPO=(_F(GROUP_NO='WALL', DX=0.), _F(GROUP_NO='ALL', DY=0., DZ=0.)))
KEL = CALC_MATR_ELEM(OPTION='RIGI_MECA', MODELE=MODELE, CARA_ELEM=CARA, CHARGE=BLOC)
MEL = CALC_MATR_ELEM(OPTION='MASS_MECA', MODELE=MODELE, CARA_ELEM=CARA, CHARGE=BLOC)
MELS = CALC_MATR_ELEM(OPTION='MASS_MECA', MODELE=MODELE, CARA_ELEM=CARAS, CHARGE=BLOC)
NUME = NUME_DDL(MATR_RIGI=KEL)
RIGI = ASSE_MATRICE(MATR_ELEM=KEL, NUME_DDL=NUME)
MASS = ASSE_MATRICE(MATR_ELEM=MEL, NUME_DDL=NUME)
MASSS = ASSE_MATRICE(MATR_ELEM=MELS, NUME_DDL=NUME)
MODES = CALC_MODES(MATR_RIGI=RIGI, MATR_MASS=MASS, OPTION='PLUS_PETITE', CALC_FREQ=_F(NMAX_FREQ=5))
STAT = CALC_MODES(MATR_RIGI=RIGI, MATR_MASS=MASSS, OPTION='PLUS_PETITE', CALC_FREQ=_F(NMAX_FREQ=1))
VPHYS = CREA_CHAMP(OPERATION='AFFE', TYPE_CHAM='NOEU_DEPL_R', MAILLAGE=MAIL,
                   AFFE=(_F(GROUP_NO='NO1', NOM_CMP='DX', VALE=V0*math.sin(1*TH)/math.sin(N*TH)),
                         _F(GROUP_NO='NO2', NOM_CMP='DX', VALE=V0*math.sin(2*TH)/math.sin(N*TH)),
                         _F(GROUP_NO='NO3', NOM_CMP='DX', VALE=V0*math.sin(3*TH)/math.sin(N*TH)),
                         _F(GROUP_NO='NO4', NOM_CMP='DX', VALE=V0*math.sin(4*TH)/math.sin(N*TH)),
                         _F(GROUP_NO='NO5', NOM_CMP='DX', VALE=V0*math.sin(5*TH)/math.sin(N*TH)),
                         _F(GROUP_NO='NO6', NOM_CMP='DX', VALE=V0)))
OBST = DEFI_OBSTACLE(TYPE='PLAN_Y')
SHOCK = _F(RELATION='DIS_CHOC', INTITULE='TIP', GROUP_NO_1='NO6', OBSTACLE=OBST,
           ORIG_OBST=(6., 0., 0.), NORM_OBST=(0., 1., 0.), JEU=G, RIGI_NOR=KN)
# The contact's onset and release on step ends (LOCALISATION_CHOC='OUI'): bases of the
# same span give the same run to 1e-9 (Code_Aster's RUNGE_KUTTA_54: 3e-7 apart).
SCHEMA = _F(SCHEMA='RUNGE_KUTTA_54', TOLERANCE=1.e-10, LOCALISATION_CHOC='OUI')
TI = (0.02, 0.04, 0.06, 0.08, 0.1)
";

/// The transient `TR_<tag>` on basis `base` and its displacements `U_<tag>`.
fn transient(base: &str, tag: &str) -> String {
    format!(
        "PROJ_BASE(BASE={base}, STOCKAGE='PLEIN',
          MATR_ASSE_GENE=(_F(MATRICE=CO('MG_{tag}'), MATR_ASSE=MASS), _F(MATRICE=CO('KG_{tag}'), MATR_ASSE=RIGI)),
          VECT_ASSE_GENE=_F(VECTEUR=CO('VG_{tag}'), VECT_ASSE=VPHYS, TYPE_VECT='VITE'))
TR_{tag} = DYNA_VIBRA(TYPE_CALCUL='TRAN', BASE_CALCUL='GENE', MATR_MASS=MG_{tag}, MATR_RIGI=KG_{tag},
                     SCHEMA_TEMPS=SCHEMA, ETAT_INIT=_F(VITE=VG_{tag}),
                     INCREMENT=_F(INST_FIN=0.1, PAS=1.e-4), ARCHIVAGE=_F(INST=TI), COMPORTEMENT=SHOCK)
U_{tag} = REST_GENE_PHYS(RESU_GENE=TR_{tag}, NOM_CHAM='DEPL')
"
    )
}

const PHYS: &str = "PH = DYNA_VIBRA(TYPE_CALCUL='TRAN', BASE_CALCUL='PHYS', MATR_MASS=MASS, MATR_RIGI=RIGI,
                SCHEMA_TEMPS=SCHEMA, ETAT_INIT=_F(VITE=VPHYS), INCREMENT=_F(INST_FIN=0.1, PAS=1.e-4),
                ARCHIVAGE=_F(INST=TI), COMPORTEMENT=SHOCK)
";

/// A study in a fresh directory: `body` after PRELUDE, the chain's mesh beside it.
struct Study {
    dir: tempfile::TempDir,
    code: Option<i32>,
    out: String,
}

impl Study {
    fn run(body: &str) -> Study {
        Study::run_text(&format!("{PRELUDE}{body}\nFIN()\n"))
    }

    fn run_text(text: &str) -> Study {
        let dir = tempfile::tempdir().unwrap();
        std::fs::copy(case("dyna_vibra_ritz.mail"), dir.path().join("ritz.mail")).unwrap();
        let comm = dir.path().join("ritz.comm");
        std::fs::write(&comm, text).unwrap();
        let (code, out) = run_file(&comm, &dir.path().join("ritz.db"));
        Study { dir, code, out }
    }

    fn ok(body: &str) -> Study {
        let s = Study::run(body);
        assert_eq!(s.code, Some(0), "{}", s.out);
        s
    }

    fn conn(&self) -> rusqlite::Connection {
        rusqlite::Connection::open(self.dir.path().join("ritz.db")).unwrap()
    }

    /// DEPL of every DX of the dyna_trans `name`, in (NUME_ORDRE, NOEUD) order.
    fn depl(&self, name: &str) -> Vec<f64> {
        let conn = self.conn();
        let mut stmt = conn
            .prepare(&format!(
                "SELECT DEPL FROM \"{name}\" WHERE NOM_CMP = 'DX' ORDER BY NUME_ORDRE, NOEUD"
            ))
            .unwrap();
        let v: Vec<f64> = stmt
            .query_map([], |r| r.get(0))
            .unwrap()
            .collect::<Result<_, _>>()
            .unwrap();
        // 5 instants, 6 nodes with a free DX (N0 is blocked).
        assert_eq!(v.len(), 30, "{name}: {v:?}");
        v
    }

    /// DEPL of N6's DX (the shock's DOF) in the dyna_trans `name`, at the 5 instants.
    fn tip(&self, name: &str) -> Vec<f64> {
        self.depl(name).chunks(6).map(|c| c[5]).collect()
    }

    /// The generalized matrix `name`, row-major, size n.
    fn gene(&self, name: &str, n: usize) -> Vec<f64> {
        let conn = self.conn();
        let mut stmt = conn
            .prepare("SELECT row, col, value FROM gene_entries WHERE concept = ?1")
            .unwrap();
        let mut a = vec![0.0; n * n];
        for e in stmt
            .query_map([name], |r| {
                Ok((
                    r.get::<_, i64>(0)?,
                    r.get::<_, i64>(1)?,
                    r.get::<_, f64>(2)?,
                ))
            })
            .unwrap()
        {
            let (i, j, v) = e.unwrap();
            a[i as usize * n + j as usize] = v;
        }
        a
    }

    /// (NUME_ORDRE, FREQ, OMEGA2, MASS_GENE, RIGI_GENE) of the mode_meca `name`.
    fn modes(&self, name: &str) -> Vec<(i64, f64, f64, f64, f64)> {
        let conn = self.conn();
        let mut stmt = conn
            .prepare(
                "SELECT NUME_ORDRE, FREQ, OMEGA2, MASS_GENE, RIGI_GENE FROM modes \
                 WHERE concept = ?1 ORDER BY NUME_ORDRE",
            )
            .unwrap();
        stmt.query_map([name], |r| {
            Ok((r.get(0)?, r.get(1)?, r.get(2)?, r.get(3)?, r.get(4)?))
        })
        .unwrap()
        .collect::<Result<_, _>>()
        .unwrap()
    }

    /// The DX values of vector `nume_ordre` of `name` at N1..N6.
    fn shape(&self, name: &str, nume_ordre: i64) -> Vec<f64> {
        let conn = self.conn();
        let mut stmt = conn
            .prepare(
                "SELECT value FROM mode_shapes WHERE concept = ?1 AND NUME_ORDRE = ?2 \
                 AND NOM_CMP = 'DX' AND NOEUD != 'N0' ORDER BY NOEUD",
            )
            .unwrap();
        stmt.query_map(rusqlite::params![name, nume_ordre], |r| r.get(0))
            .unwrap()
            .collect::<Result<_, _>>()
            .unwrap()
    }
}

/// max |a − b| / max |b|.
fn rel_diff(a: &[f64], b: &[f64]) -> f64 {
    let scale = b.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    a.iter()
        .zip(b)
        .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()))
        / scale
}

/// The basis of `better` (with a static vector) is closer to the physical run PH than
/// that of `worse`: by a factor 3 at least at the shock's DOF, and over every DOF.
fn improves(s: &Study, worse: &str, better: &str) {
    let (ph, tip) = (s.depl("PH"), s.tip("PH"));
    let (w, b) = (
        rel_diff(&s.tip(worse), &tip),
        rel_diff(&s.tip(better), &tip),
    );
    assert!(b < w / 3.0, "at N6: {worse} {w:e}, {better} {b:e}");
    let (w, b) = (
        rel_diff(&s.depl(worse), &ph),
        rel_diff(&s.depl(better), &ph),
    );
    assert!(b < w / 1.5, "every DOF: {worse} {w:e}, {better} {b:e}");
}

/// max |A − I|.
fn identity_error(a: &[f64], n: usize) -> f64 {
    (0..n * n).fold(0.0f64, |m, k| {
        let target = if k / n == k % n { 1.0 } else { 0.0 };
        m.max((a[k] - target).abs())
    })
}

#[test]
fn the_ritz_testcase_matches_the_exact_solution() {
    let text = std::fs::read_to_string(case("dyna_vibra_ritz.comm")).unwrap();
    let s = Study::run_text(&text);
    assert_eq!(s.code, Some(0), "{}", s.out);
    assert!(s.out.contains("tests: 37 OK, 0 NOOK"), "{}", s.out);
    // The complete basis (5 modes + the static mode) against the physical DOFs: the same
    // equations in other coordinates, each integrated to TOLERANCE 1e-10 (the scheme's
    // steps differ, so they agree to the integration error, measured 4.4e-11, not to
    // round-off).
    let ph = s.depl("PH");
    for tag in ["FULL", "ORTH"] {
        let d = rel_diff(&s.depl(&format!("U_{tag}")), &ph);
        assert!(d < 1e-9, "{tag}: {d:e}");
    }
    // The static mode improves the truncated basis: at the shock's DOF, the largest
    // error relative to its largest displacement falls from 3.3e-2 (2 modes) to 6.8e-3
    // (2 modes + MSTAT); over every DOF, from 3.5e-2 to 1.6e-2 (the modes left out still
    // carry the inner masses' share).
    improves(&s, "U_2", "U_2S");
    // MSTAT = K^-1 e(N6): the generalized stiffness couples mode j and MSTAT by
    // φ_jᵀ K K^-1 e = φ_j(N6), and MSTATᵀ K MSTAT = 6/k. Stored in full (STOCKAGE='PLEIN').
    let kg = s.gene("KG_FULL", 6);
    for j in 0..5 {
        let phi = s.shape("MODES", j as i64 + 1);
        assert!(
            (kg[j * 6 + 5] - phi[5]).abs() < 1e-12 && (kg[5 * 6 + j] - phi[5]).abs() < 1e-12,
            "mode {}: {} against φ(N6) = {}",
            j + 1,
            kg[j * 6 + 5],
            phi[5]
        );
    }
    assert!((kg[35] - 6e-4).abs() < 1e-15, "{}", kg[35]);
    // BORTH: mass-orthonormal, and (complete, modes first) the modes themselves: its
    // stiffness is diagonal.
    assert!(identity_error(&s.gene("MG_ORTH", 6), 6) < 1e-12);
    let kg = s.gene("KG_ORTH", 6);
    let off = (0..36)
        .filter(|k| k / 6 != k % 6)
        .fold(0.0f64, |m, k| m.max(kg[k].abs()));
    assert!(off < 1e-10 * kg[35], "{off:e}");
}

#[test]
fn a_static_vector_from_calc_modes_completes_and_improves_the_basis() {
    // STAT, from CALC_MODES (no MODE_STATIQUE): the complete basis of 5 modes + STAT gives
    // the physical run to the integration error; 2 modes + STAT beat 2 modes.
    let s = Study::ok(&format!(
        "{PHYS}
BFULL = DEFI_BASE_MODALE(RITZ=(_F(MODE_MECA=MODES), _F(MODE_INTF=STAT)), NUME_REF=NUME)
B2S = DEFI_BASE_MODALE(RITZ=(_F(MODE_MECA=MODES, NMAX_MODE=2), _F(MODE_INTF=STAT)))
B2 = DEFI_BASE_MODALE(RITZ=_F(MODE_MECA=MODES, NMAX_MODE=2))
{}{}{}",
        transient("BFULL", "FULL"),
        transient("B2S", "2S"),
        transient("B2", "2")
    ));
    let ph = s.depl("PH");
    let full = rel_diff(&s.depl("U_FULL"), &ph);
    assert!(full < 1e-9, "{full:e}");
    improves(&s, "U_2", "U_2S");
    // The result names the stiffness and mass of its first basis (PROJ_VECT_BASE took the
    // velocity's coordinates in that mass).
    let conn = s.conn();
    let m: String = conn
        .query_row(
            "SELECT json FROM concept_data WHERE concept = 'B2S' AND key = 'matrices'",
            [],
            |r| r.get(0),
        )
        .unwrap();
    assert!(m.contains("\"RIGI\"") && m.contains("\"MASS\""), "{m}");
    // Not orthonormalised: each vector keeps what its basis said of it.
    let b2s = s.modes("B2S");
    let (modes, stat) = (s.modes("MODES"), s.modes("STAT"));
    assert_eq!(b2s.len(), 3);
    assert_eq!(&b2s[..2], &modes[..2]);
    assert_eq!((b2s[2].1, b2s[2].3), (stat[0].1, stat[0].3));
}

#[test]
fn ortho_gives_a_mass_orthonormal_basis_of_the_same_span() {
    let s = Study::ok(&format!(
        "MSTAT = MODE_STATIQUE(MATR_RIGI=RIGI, MATR_MASS=MASS, FORCE_NODALE=_F(GROUP_NO='NO6', AVEC_CMP='DX'))
B2S = DEFI_BASE_MODALE(RITZ=(_F(MODE_MECA=MODES, NMAX_MODE=2), _F(MODE_INTF=MSTAT, NMAX_MODE=1)))
B2O = DEFI_BASE_MODALE(RITZ=(_F(MODE_MECA=MODES, NMAX_MODE=2), _F(MODE_INTF=MSTAT, NMAX_MODE=1)),
                       NUME_REF=NUME, ORTHO='OUI', MATRICE=MASS)
BOB = DEFI_BASE_MODALE(ORTHO_BASE=_F(BASE=B2S))
{}{}",
        transient("B2S", "2S"),
        transient("B2O", "2O")
    ));
    // PROJ_MATR_BASE of the mass on the orthonormalised basis: the identity.
    let mg = s.gene("MG_2O", 3);
    assert!(identity_error(&mg, 3) < 1e-10, "{mg:?}");
    // The one on the basis as it was is not diagonal: MSTAT is not M-orthogonal to modes.
    let raw = s.gene("MG_2S", 3);
    assert!(raw[2].abs() > 1e-6, "{raw:?}");
    let kg = s.gene("KG_2O", 3);
    for (l, m) in s.modes("B2O").iter().enumerate() {
        let (_, freq, omega2, mass, rigi) = *m;
        assert_eq!(mass, 1.0);
        // RIGI_GENE = φᵀKφ (PROJ_MATR_BASE's diagonal), FREQ its Rayleigh frequency.
        assert!((rigi - kg[l * 3 + l]).abs() < 1e-9 * rigi, "{rigi} {kg:?}");
        assert!((omega2 - rigi).abs() < 1e-12 * rigi);
        let f = rigi.sqrt() / (2.0 * std::f64::consts::PI);
        assert!((freq - f).abs() < 1e-12 * f, "{freq} {f}");
    }
    // ORTHO_BASE without MATRICE: the mass the basis names; the same vectors.
    let bob = s.modes("BOB");
    assert_eq!(bob.len(), 3);
    for l in 1..=3 {
        let (a, b) = (s.shape("BOB", l), s.shape("B2O", l));
        assert!(rel_diff(&a, &b) < 1e-12, "{a:?} {b:?}");
    }
    // Same span: the transient on either is the same to the integration error.
    let d = rel_diff(&s.depl("U_2O"), &s.depl("U_2S"));
    assert!(d < 1e-9, "{d:e}");
}

#[test]
fn nmax_mode_keeps_the_first_vectors_of_each_concept() {
    let s = Study::ok(
        "B = DEFI_BASE_MODALE(RITZ=(_F(MODE_MECA=(MODES, STAT, MODES), NMAX_MODE=(2, 0, 1)),
                               _F(MODE_INTF=MODES, NMAX_MODE=9)), INFO=2)
C = DEFI_BASE_MODALE(RITZ=_F(MODE_MECA=MODES))
NUMEGE = NUME_DDL_GENE(BASE=B, STOCKAGE='PLEIN')",
    );
    let (b, modes) = (s.modes("B"), s.modes("MODES"));
    // 2 of MODES, none of STAT, 1 of MODES, then all 5 of MODES (9 asked: alarm).
    let orders: Vec<i64> = b.iter().map(|m| m.0).collect();
    assert_eq!(orders, (1..=8).collect::<Vec<_>>());
    let from = [0, 1, 0, 0, 1, 2, 3, 4];
    for (l, &j) in from.iter().enumerate() {
        assert_eq!(b[l].1, modes[j].1, "vector {}", l + 1);
        assert_eq!(s.shape("B", l as i64 + 1), s.shape("MODES", j as i64 + 1));
    }
    assert!(
        s.out.contains("<DEFI_BASE_MODALE_2>")
            && s.out.contains("NMAX_MODE=9 for MODES, which holds 5"),
        "{}",
        s.out
    );
    assert!(s
        .out
        .contains("8 vector(s): 2 of MODES, 0 of STAT, 1 of MODES, 5 of MODES"));
    // Without NMAX_MODE: every vector.
    assert_eq!(s.modes("C"), modes);
}

#[test]
fn dependent_vectors_are_left_out_with_an_alarm() {
    let s = Study::ok(
        "B = DEFI_BASE_MODALE(RITZ=(_F(MODE_MECA=MODES, NMAX_MODE=3), _F(MODE_MECA=(MODES, STAT), NMAX_MODE=(2, 1))),
                     ORTHO='OUI', MATRICE=MASS)",
    );
    assert_eq!(s.modes("B").len(), 4, "{}", s.out);
    assert!(
        s.out.contains("<DEFI_BASE_MODALE_1> 2 vector(s) left out")
            && s.out.contains("vector 4 (NUME_ORDRE 1 of MODES")
            && s.out.contains("vector 5 (NUME_ORDRE 2 of MODES"),
        "{}",
        s.out
    );
    assert!(
        s.out.contains(
            "4 vector(s): 3 of MODES, 0 of MODES, 1 of STAT (2 dependent vector(s) left out)"
        ),
        "{}",
        s.out
    );
}

#[test]
fn reuse_extends_a_basis_with_static_vectors() {
    let s = Study::ok(
        "BASE = DEFI_BASE_MODALE(RITZ=_F(MODE_MECA=MODES, NMAX_MODE=3))
OLD = NUME_DDL_GENE(BASE=BASE, STOCKAGE='PLEIN')
BASE = DEFI_BASE_MODALE(reuse=BASE, RITZ=(_F(BASE_MODALE=BASE), _F(MODE_INTF=STAT)))
NUMEGE = NUME_DDL_GENE(BASE=BASE, STOCKAGE='PLEIN')
KG = PROJ_MATR_BASE(BASE=BASE, NUME_DDL_GENE=NUMEGE, MATR_ASSE=RIGI)",
    );
    let b = s.modes("BASE");
    assert_eq!(b.len(), 4);
    assert_eq!(s.shape("BASE", 4), s.shape("STAT", 1));
    assert_eq!(s.gene("KG", 4).len(), 16);
    // What was numbered on the basis before it was extended is out of date.
    let e = Study::run(
        "BASE = DEFI_BASE_MODALE(RITZ=_F(MODE_MECA=MODES, NMAX_MODE=3))
OLD = NUME_DDL_GENE(BASE=BASE, STOCKAGE='PLEIN')
BASE = DEFI_BASE_MODALE(reuse=BASE, RITZ=(_F(BASE_MODALE=BASE), _F(MODE_INTF=STAT)))
KG = PROJ_MATR_BASE(BASE=BASE, NUME_DDL_GENE=OLD, MATR_ASSE=RIGI)",
    );
    assert_eq!(e.code, Some(2), "{}", e.out);
    assert!(e.out.contains("BASE has been redefined since"), "{}", e.out);
    // reuse= must be the basis it extends.
    let e = Study::run(
        "BASE = DEFI_BASE_MODALE(RITZ=_F(MODE_MECA=MODES, NMAX_MODE=3))
BASE = DEFI_BASE_MODALE(reuse=BASE, RITZ=(_F(MODE_MECA=MODES), _F(MODE_INTF=STAT)))",
    );
    assert_eq!(e.code, Some(2), "{}", e.out);
    assert!(e.out.contains("BASE_MODALE"), "{}", e.out);
}

/// A call that must stop the run: the output names `keyword` and says `says`.
fn refused(body: &str, keyword: &str, says: &str) {
    let s = Study::run(body);
    assert_eq!(s.code, Some(2), "{body}\n{}", s.out);
    assert!(
        s.out.contains(keyword) && s.out.contains(says),
        "{body}: expected {keyword} and '{says}' in\n{}",
        s.out
    );
    let conn = s.conn();
    let n: i64 = conn
        .query_row("SELECT COUNT(*) FROM concepts WHERE name = 'B'", [], |r| {
            r.get(0)
        })
        .unwrap();
    assert_eq!(n, 0, "a refused call leaves nothing");
}

#[test]
fn bases_on_another_numbering_are_refused() {
    // A model of half the chain: its modes are on other DOFs.
    let half = "MOD2 = AFFE_MODELE(MAILLAGE=MAIL, AFFE=_F(GROUP_MA=('HALF_RES', 'HALF_MAS'), PHENOMENE='MECANIQUE', MODELISATION='DIS_T'))
CAR2 = AFFE_CARA_ELEM(MODELE=MOD2, DISCRET=(_F(GROUP_MA='HALF_RES', CARA='K_T_D_L', VALE=(K, 0., 0.)),
                                           _F(GROUP_MA='HALF_MAS', CARA='M_T_D_N', VALE=M)))
BLO2 = AFFE_CHAR_MECA(MODELE=MOD2, DDL_IMPO=(_F(GROUP_NO='WALL', DX=0.), _F(NOEUD=('N0', 'N1', 'N2', 'N3'), DY=0., DZ=0.)))
KEL2 = CALC_MATR_ELEM(OPTION='RIGI_MECA', MODELE=MOD2, CARA_ELEM=CAR2, CHARGE=BLO2)
MEL2 = CALC_MATR_ELEM(OPTION='MASS_MECA', MODELE=MOD2, CARA_ELEM=CAR2, CHARGE=BLO2)
NUM2 = NUME_DDL(MATR_RIGI=KEL2)
RIG2 = ASSE_MATRICE(MATR_ELEM=KEL2, NUME_DDL=NUM2)
MAS2 = ASSE_MATRICE(MATR_ELEM=MEL2, NUME_DDL=NUM2)
MOD2S = CALC_MODES(MATR_RIGI=RIG2, MATR_MASS=MAS2, OPTION='PLUS_PETITE', CALC_FREQ=_F(NMAX_FREQ=2))
";
    refused(
        &format!("{half}B = DEFI_BASE_MODALE(RITZ=(_F(MODE_MECA=MODES), _F(MODE_INTF=MOD2S)))"),
        "DEFI_BASE_MODALE/RITZ[2]/MODE_INTF",
        "MOD2S is on",
    );
    refused(
        &format!("{half}B = DEFI_BASE_MODALE(RITZ=_F(MODE_MECA=MODES), NUME_REF=NUM2)"),
        "DEFI_BASE_MODALE/RITZ/MODE_MECA",
        "of NUME_REF=NUM2",
    );
    refused(
        &format!("{half}B = DEFI_BASE_MODALE(RITZ=_F(MODE_MECA=MODES), ORTHO='OUI', MATRICE=MAS2)"),
        "DEFI_BASE_MODALE/MATRICE",
        "MAS2 is not assembled on the DOF numbering",
    );
}

#[test]
fn wrong_or_unsupported_keywords_are_refused_by_name() {
    refused(
        "B = DEFI_BASE_MODALE(RITZ=_F(MODE_MECA=MODES), ORTHO='OUI')",
        "DEFI_BASE_MODALE/MATRICE",
        "missing mandatory keyword MATRICE when ORTHO is 'OUI'",
    );
    refused(
        "B = DEFI_BASE_MODALE(CLASSIQUE=_F(INTERF_DYNA=NUME, MODE_MECA=MODES))",
        "DEFI_BASE_MODALE/CLASSIQUE",
        "is not supported",
    );
    refused(
        "B = DEFI_BASE_MODALE(DIAG_MASS=_F(MODE_MECA=MODES, MODE_STAT=STAT))",
        "DEFI_BASE_MODALE/DIAG_MASS",
        "ORTHO='OUI'",
    );
    refused(
        "B = DEFI_BASE_MODALE(RITZ=_F(MODE_MECA=MODES), INTERF_DYNA=NUME)",
        "DEFI_BASE_MODALE/INTERF_DYNA",
        "interfaces",
    );
    refused(
        "B = DEFI_BASE_MODALE(RITZ=_F(MODE_MECA=(MODES, STAT), NMAX_MODE=2))",
        "DEFI_BASE_MODALE/RITZ/NMAX_MODE",
        "1 count(s) for the 2 concept(s)",
    );
    refused(
        "B = DEFI_BASE_MODALE(RITZ=_F(MODE_MECA=MODES, NMAX_MODE=0))",
        "DEFI_BASE_MODALE/RITZ",
        "no vector",
    );
    refused(
        "B = DEFI_BASE_MODALE(RITZ=_F(MODE_MECA=MODES, NMAX_MODE=-1))",
        "DEFI_BASE_MODALE/RITZ/NMAX_MODE",
        "expected a value >= 0, got -1",
    );
    refused(
        "B = DEFI_BASE_MODALE(ORTHO_BASE=_F(BASE=MODES), NUME_REF=NUME)",
        "DEFI_BASE_MODALE/NUME_REF",
        "belongs to RITZ",
    );
}

#[test]
fn a_ritz_basis_stored_diagonal_raises_the_coupling_alarm_and_holds_the_static_flexibility() {
    // 2 modes + the static mode of N6 (MODE_STATIQUE): numbered with STOCKAGE='DIAG', the
    // stiffness couplings φ_j(N6) are dropped (alarm PROJ_MATR_BASE_1); numbered in full,
    // no alarm. DYNA_VIBRA's flexibility check measures rᵀΦ(ΦᵀKΦ)⁻¹Φᵀr: the static mode of
    // the shock's DOF makes the share 1, so VERI_CHOC with a strict SEUIL passes (the sum
    // over K-orthogonal vectors would have counted the two modes' part twice, above 1;
    // with the two modes alone the share is below 1 and VERI_CHOC stops the run).
    let s = Study::ok(
        "MSTAT = MODE_STATIQUE(MATR_RIGI=RIGI, FORCE_NODALE=_F(GROUP_NO='NO6', AVEC_CMP='DX'))
B2S = DEFI_BASE_MODALE(RITZ=(_F(MODE_MECA=MODES, NMAX_MODE=2), _F(MODE_INTF=MSTAT)), NUME_REF=NUME)
PROJ_BASE(BASE=B2S, STOCKAGE='DIAG', MATR_ASSE_GENE=_F(MATRICE=CO('KD'), MATR_ASSE=RIGI))
PROJ_BASE(BASE=B2S, STOCKAGE='PLEIN',
          MATR_ASSE_GENE=(_F(MATRICE=CO('MP'), MATR_ASSE=MASS), _F(MATRICE=CO('KP'), MATR_ASSE=RIGI)),
          VECT_ASSE_GENE=_F(VECTEUR=CO('VP'), VECT_ASSE=VPHYS, TYPE_VECT='VITE'))
TR = DYNA_VIBRA(TYPE_CALCUL='TRAN', BASE_CALCUL='GENE', MATR_MASS=MP, MATR_RIGI=KP,
                SCHEMA_TEMPS=SCHEMA, ETAT_INIT=_F(VITE=VP), VERI_CHOC=_F(SEUIL=1.e-6),
                INCREMENT=_F(INST_FIN=0.01, PAS=1.e-4), COMPORTEMENT=SHOCK)
",
    );
    assert_eq!(s.out.matches("PROJ_MATR_BASE_1").count(), 1, "{}", s.out);
    assert!(
        s.out.contains("KD: B2S is not orthogonal for RIGI"),
        "{}",
        s.out
    );
    assert!(!s.out.contains("DYNA_VIBRA_2"), "{}", s.out);
    let modes_only = Study::run(
        "B2 = DEFI_BASE_MODALE(RITZ=_F(MODE_MECA=MODES, NMAX_MODE=2), NUME_REF=NUME)
PROJ_BASE(BASE=B2, STOCKAGE='PLEIN',
          MATR_ASSE_GENE=(_F(MATRICE=CO('MP'), MATR_ASSE=MASS), _F(MATRICE=CO('KP'), MATR_ASSE=RIGI)),
          VECT_ASSE_GENE=_F(VECTEUR=CO('VP'), VECT_ASSE=VPHYS, TYPE_VECT='VITE'))
TR = DYNA_VIBRA(TYPE_CALCUL='TRAN', BASE_CALCUL='GENE', MATR_MASS=MP, MATR_RIGI=KP,
                SCHEMA_TEMPS=SCHEMA, ETAT_INIT=_F(VITE=VP), VERI_CHOC=_F(SEUIL=1.e-6),
                INCREMENT=_F(INST_FIN=0.01, PAS=1.e-4), COMPORTEMENT=SHOCK)
",
    );
    assert_eq!(modes_only.code, Some(2), "{}", modes_only.out);
    assert!(modes_only.out.contains("VERI_CHOC"), "{}", modes_only.out);
}
