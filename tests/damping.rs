//! Damping matrices, OPTION='AMOR_MECA' (Rayleigh from the materials' AMOR_ALPHA and
//! AMOR_BETA, discrete dampers A_...), through the binary: each against an exact reference
//! (a damped oscillator's free decay, the Rayleigh identity ΦᵀCΦ = α Ω² + β on
//! mass-normalised modes), the two routes to the assembled matrix against each other, and
//! the errors and alarms a user meets.

use std::path::{Path, PathBuf};

mod support;
use support::{case, run_file};

/// A finished run of a command file written here: its output and its database.
struct Run {
    code: Option<i32>,
    out: String,
    db: PathBuf,
    _dir: tempfile::TempDir,
}

/// Run `comm` with the mesh `mail` beside it (LIRE_MAILLAGE finds `case.mail`).
fn run_text(comm: &str, mail: &str) -> Run {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("case.mail"), mail).unwrap();
    let file = dir.path().join("case.comm");
    std::fs::write(&file, comm).unwrap();
    let db = dir.path().join("case.db");
    let (code, out) = run_file(&file, &db);
    Run {
        code,
        out,
        db,
        _dir: dir,
    }
}

fn ok(run: &Run) {
    assert_eq!(run.code, Some(0), "{}", run.out);
}

/// The entries (row, col, value) of an assembled matrix, sorted.
fn matrix(db: &Path, name: &str) -> Vec<(i64, i64, f64)> {
    let conn = rusqlite::Connection::open(db).unwrap();
    let mut stmt = conn
        .prepare("SELECT row, col, value FROM matrix_entries WHERE matrix = ?1 ORDER BY row, col")
        .unwrap();
    stmt.query_map([name], |r| Ok((r.get(0)?, r.get(1)?, r.get(2)?)))
        .unwrap()
        .collect::<Result<Vec<_>, _>>()
        .unwrap()
}

/// The generalized matrix `name` as a dense n×n matrix (absent entries: 0).
fn gene_matrix(db: &Path, name: &str, n: usize) -> Vec<Vec<f64>> {
    let conn = rusqlite::Connection::open(db).unwrap();
    let mut stmt = conn
        .prepare("SELECT row, col, value FROM gene_entries WHERE concept = ?1")
        .unwrap();
    let mut a = vec![vec![0.0; n]; n];
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
        a[i as usize][j as usize] = v;
    }
    a
}

/// (OMEGA2, MASS_GENE) of each mode of `name`, in order.
fn modes(db: &Path, name: &str) -> Vec<(f64, f64)> {
    let conn = rusqlite::Connection::open(db).unwrap();
    let mut stmt = conn
        .prepare("SELECT OMEGA2, MASS_GENE FROM modes WHERE concept = ?1 ORDER BY NUME_ORDRE")
        .unwrap();
    stmt.query_map([name], |r| Ok((r.get(0)?, r.get(1)?)))
        .unwrap()
        .collect::<Result<Vec<_>, _>>()
        .unwrap()
}

/// (INST, DEPL) of one node's component in the `dyna_trans` table `name`.
fn history(db: &Path, name: &str, node: &str, cmp: &str) -> Vec<(f64, f64)> {
    let conn = rusqlite::Connection::open(db).unwrap();
    let mut stmt = conn
        .prepare(&format!(
            "SELECT INST, DEPL FROM \"{name}\" WHERE NOEUD = ?1 AND NOM_CMP = ?2 ORDER BY NUME_ORDRE"
        ))
        .unwrap();
    stmt.query_map([node, cmp], |r| Ok((r.get(0)?, r.get(1)?)))
        .unwrap()
        .collect::<Result<Vec<_>, _>>()
        .unwrap()
}

const ONE_NODE: &str = "COOR_3D\n NO1 0.0 0.0 0.0\nFINSF\nPOI1\n P1 NO1\nFINSF\n\
                        GROUP_MA\n MASSE\n P1\nFINSF\nGROUP_NO\n NO1\n NO1\nFINSF\nFIN\n";

/// Free decay of x'' m + c x' + k x = 0 from x0 at rest (underdamped).
fn free_decay(m: f64, c: f64, k: f64, x0: f64, t: f64) -> f64 {
    let w = (k / m).sqrt();
    let xi = c / (2.0 * m * w);
    let wd = w * (1.0 - xi * xi).sqrt();
    x0 * (-xi * w * t).exp() * ((wd * t).cos() + xi * w / wd * (wd * t).sin())
}

/// A one-DOF oscillator (m, k along X) damped only by a discrete A_T_D_N dashpot c, no
/// material: DYNA_VIBRA on the physical DOFs with MATR_AMOR from ASSEMBLAGE, released from
/// x0, follows x0 e^{−ζωt}(cos ω_d t + ζω/ω_d sin ω_d t) at every archived instant.
///
/// Tolerance: RUNGE_KUTTA_54 at TOLERANCE 1e-10 bounds each step's local error to 1e-10 of
/// the largest displacement met (x0); over the few hundred steps of 0.3 s the global error
/// stays of the order of 1e-9 x0 (measured: 2.2e-10 x0). The bound 1e-8 x0 leaves a
/// margin, and is below 1e-5 of what a 1 % error in c changes at the end (the check below: an
/// error in the damping cannot pass).
#[test]
fn a_discrete_dashpot_gives_the_exact_free_decay_on_the_physical_dofs() {
    let (m, k, c, x0) = (2.0, 5.0e3, 5.0, 1.0e-3); // ω = 50 rad/s, ζ = 0.025
    let insts: Vec<String> = (1..=15).map(|i| format!("{}", 0.02 * i as f64)).collect();
    let insts = insts.join(", ");
    let comm = format!(
        "DEBUT()
MAIL = LIRE_MAILLAGE(FORMAT='ASTER')
MO = AFFE_MODELE(MAILLAGE=MAIL, AFFE=_F(TOUT='OUI', PHENOMENE='MECANIQUE', MODELISATION='DIS_T'))
CARA = AFFE_CARA_ELEM(MODELE=MO, DISCRET=(_F(GROUP_MA='MASSE', CARA='K_T_D_N', VALE=({k}, {k}, {k})),
                                         _F(GROUP_MA='MASSE', CARA='M_T_D_N', VALE={m}),
                                         _F(GROUP_MA='MASSE', CARA='A_T_D_N', VALE=({c}, {c}, {c}))))
CL = AFFE_CHAR_CINE(MODELE=MO, MECA_IMPO=_F(GROUP_NO='NO1', DY=0., DZ=0.))
ASSEMBLAGE(MODELE=MO, CARA_ELEM=CARA, CHAR_CINE=CL, NUME_DDL=CO('NUME'),
           MATR_ASSE=(_F(MATRICE=CO('RIGI'), OPTION='RIGI_MECA'),
                      _F(MATRICE=CO('MASS'), OPTION='MASS_MECA'),
                      _F(MATRICE=CO('AMOR'), OPTION='AMOR_MECA')))
U0 = CREA_CHAMP(OPERATION='AFFE', TYPE_CHAM='NOEU_DEPL_R', MAILLAGE=MAIL,
                AFFE=_F(GROUP_NO='NO1', NOM_CMP='DX', VALE={x0}))
TR = DYNA_VIBRA(TYPE_CALCUL='TRAN', BASE_CALCUL='PHYS', MATR_MASS=MASS, MATR_RIGI=RIGI,
                MATR_AMOR=AMOR, SCHEMA_TEMPS=_F(SCHEMA='RUNGE_KUTTA_54', TOLERANCE=1.e-10),
                ETAT_INIT=_F(DEPL=U0), INCREMENT=_F(INST_FIN=0.3, PAS=1.e-4),
                ARCHIVAGE=_F(INST=({insts})))
FIN()
"
    );
    let run = run_text(&comm, ONE_NODE);
    ok(&run);
    assert!(!run.out.contains("<A>"), "{}", run.out);
    // The damping matrix is c on the DOFs (DX, DY, DZ), the blocked ones included.
    let amor = matrix(&run.db, "AMOR");
    for (i, j, v) in &amor {
        assert_eq!(*v, if i == j { c } else { 0.0 }, "{amor:?}");
    }
    let h = history(&run.db, "TR", "NO1", "DX");
    assert_eq!(h.len(), 15, "{h:?}");
    let mut worst: f64 = 0.0;
    let mut sensitivity: f64 = 0.0;
    for &(t, x) in &h {
        worst = worst.max((x - free_decay(m, c, k, x0, t)).abs());
        sensitivity =
            sensitivity.max((free_decay(m, 1.01 * c, k, x0, t) - free_decay(m, c, k, x0, t)).abs());
    }
    eprintln!("dashpot free decay: worst error {:.2e} x0", worst / x0);
    assert!(worst < 1e-8 * x0, "worst error {worst:e}");
    assert!(sensitivity > 1e3 * 1e-8 * x0, "{sensitivity:e}");
}

/// A dashpot on a cell of its own (A_T_D_N only, no stiffness nor mass there): accepted,
/// as Code_Aster's A_ characteristics allow; it adds c to the damping matrix and nothing to
/// the stiffness and mass, which hold the other cell's k and m.
#[test]
fn a_dashpot_alone_on_its_cell_is_accepted_and_adds_only_damping() {
    let (m, k, c) = (2.0, 5.0e3, 7.0);
    let mail = "COOR_3D\n NO1 0.0 0.0 0.0\nFINSF\nPOI1\n P1 NO1\n P2 NO1\nFINSF\n\
                GROUP_MA\n MASSE\n P1\nFINSF\nGROUP_MA\n AMORT\n P2\nFINSF\n\
                GROUP_NO\n NO1\n NO1\nFINSF\nFIN\n";
    let comm = format!(
        "DEBUT()
MAIL = LIRE_MAILLAGE(FORMAT='ASTER')
MO = AFFE_MODELE(MAILLAGE=MAIL, AFFE=_F(TOUT='OUI', PHENOMENE='MECANIQUE', MODELISATION='DIS_T'))
CARA = AFFE_CARA_ELEM(MODELE=MO, DISCRET=(_F(GROUP_MA='MASSE', CARA='K_T_D_N', VALE=({k}, {k}, {k})),
                                         _F(GROUP_MA='MASSE', CARA='M_T_D_N', VALE={m}),
                                         _F(GROUP_MA='AMORT', CARA='A_T_D_N', VALE=({c}, {c}, {c}))))
ASSEMBLAGE(MODELE=MO, CARA_ELEM=CARA, NUME_DDL=CO('NUME'),
           MATR_ASSE=(_F(MATRICE=CO('RIGI'), OPTION='RIGI_MECA'),
                      _F(MATRICE=CO('MASS'), OPTION='MASS_MECA'),
                      _F(MATRICE=CO('AMOR'), OPTION='AMOR_MECA')))
FIN()
"
    );
    let run = run_text(&comm, mail);
    ok(&run);
    for (name, value) in [("AMOR", c), ("RIGI", k), ("MASS", m)] {
        let entries = matrix(&run.db, name);
        assert!(!entries.is_empty(), "{name}");
        for (i, j, v) in &entries {
            assert_eq!(*v, if i == j { value } else { 0.0 }, "{name}: {entries:?}");
        }
    }
}

/// `n` POU_D_E elements along X from N0 (clamped) to N<n>, length 1 m, group POUTRE; the
/// tip node in group BOUT and its POI1 cell PT in group PTS.
fn beam_mesh(n: usize) -> String {
    let mut s = String::from("COOR_3D\n");
    for i in 0..=n {
        s += &format!(" N{i} {} 0.0 0.0\n", i as f64 / n as f64);
    }
    s += "FINSF\nSEG2\n";
    for i in 1..=n {
        s += &format!(" E{i} N{} N{i}\n", i - 1);
    }
    s += &format!("FINSF\nPOI1\n PT N{n}\nFINSF\nGROUP_MA\n POUTRE\n");
    for i in 1..=n {
        s += &format!(" E{i}\n");
    }
    s += &format!("FINSF\nGROUP_MA\n PTS\n PT\nFINSF\nGROUP_NO\n ENCAST\n N0\nFINSF\nGROUP_NO\n BOUT\n N{n}\nFINSF\nFIN\n");
    s
}

/// A clamped steel beam (rectangular section: no repeated frequency), its model and
/// characteristics; `extra_mater` and `extra_cara` complete AFFE_MATERIAU and
/// AFFE_CARA_ELEM. `with_tip` adds a DIS_T element at the tip.
fn beam_head(alpha: f64, beta: f64, with_tip: bool) -> String {
    let tip_model = if with_tip {
        ", _F(GROUP_MA='PTS', PHENOMENE='MECANIQUE', MODELISATION='DIS_T')"
    } else {
        ""
    };
    let tip_cara = if with_tip {
        "DISCRET=(_F(GROUP_MA='PTS', CARA='K_T_D_N', VALE=(1.e4, 2.e4, 3.e4)),
                 _F(GROUP_MA='PTS', CARA='M_T_D_N', VALE=0.5),
                 _F(GROUP_MA='PTS', CARA='A_T_D_N', VALE=(3., 5., 7.))),"
    } else {
        ""
    };
    let tip_mater = if with_tip {
        "MATD = DEFI_MATERIAU(ELAS=_F(E=1., NU=0., AMOR_ALPHA=3.e-4, AMOR_BETA=0.5))
CHMAT = AFFE_MATERIAU(MAILLAGE=MAIL, AFFE=(_F(GROUP_MA='POUTRE', MATER=ACIER),
                                           _F(GROUP_MA='PTS', MATER=MATD)))"
    } else {
        "CHMAT = AFFE_MATERIAU(MAILLAGE=MAIL, AFFE=_F(GROUP_MA='POUTRE', MATER=ACIER))"
    };
    format!(
        "DEBUT()
MAIL = LIRE_MAILLAGE(FORMAT='ASTER')
MO = AFFE_MODELE(MAILLAGE=MAIL, AFFE=(_F(GROUP_MA='POUTRE', PHENOMENE='MECANIQUE',
                                         MODELISATION='POU_D_E'){tip_model}))
ACIER = DEFI_MATERIAU(ELAS=_F(E=2.1e11, NU=0.3, RHO=7800., AMOR_ALPHA={alpha}, AMOR_BETA={beta}))
{tip_mater}
CARA = AFFE_CARA_ELEM(MODELE=MO, {tip_cara}
                      POUTRE=_F(GROUP_MA='POUTRE', SECTION='RECTANGLE', CARA=('HY', 'HZ'),
                                VALE=(0.02, 0.01)))
CL = AFFE_CHAR_CINE(MODELE=MO, MECA_IMPO=_F(GROUP_NO='ENCAST', DX=0., DY=0., DZ=0., DRX=0.,
                                            DRY=0., DRZ=0.))
"
    )
}

/// Projected on modes normalised to a unit generalized mass, a Rayleigh damping
/// C = α K + β M is diagonal with c_i = α ω_i² + β (φᵢᵀKφⱼ = ω_i² δᵢⱼ, φᵢᵀMφⱼ = δᵢⱼ), so the
/// modal damping ratio is ξ_i = c_i/(2 ω_i) = (α ω_i + β/ω_i)/2. Checked on a two-DOF
/// spring–mass chain (discrete elements: their own K and M times the coefficients of the
/// material they carry) and on a clamped beam (POU_D_E: its K_e and consistent M_e), each
/// entry of the full generalized matrix (STOCKAGE='PLEIN') to 1e-10 of the largest.
#[test]
fn rayleigh_damping_projected_on_mass_normalised_modes_is_alpha_omega2_plus_beta() {
    let (alpha, beta) = (2.0e-4, 3.0);
    let chain_mail = "COOR_3D\n N0 0.0 0.0 0.0\n N1 1.0 0.0 0.0\n N2 2.0 0.0 0.0\nFINSF\n\
                      SEG2\n S1 N0 N1\n S2 N1 N2\nFINSF\nPOI1\n P1 N1\n P2 N2\nFINSF\n\
                      GROUP_MA\n RESS\n S1\n S2\nFINSF\nGROUP_MA\n MASSES\n P1\n P2\nFINSF\n\
                      GROUP_NO\n N0\n N0\nFINSF\nFIN\n";
    let chain = format!(
        "DEBUT()
MAIL = LIRE_MAILLAGE(FORMAT='ASTER')
MO = AFFE_MODELE(MAILLAGE=MAIL, AFFE=_F(TOUT='OUI', PHENOMENE='MECANIQUE', MODELISATION='DIS_T'))
MAT = DEFI_MATERIAU(ELAS=_F(E=1., NU=0., AMOR_ALPHA={alpha}, AMOR_BETA={beta}))
CHMAT = AFFE_MATERIAU(MAILLAGE=MAIL, AFFE=_F(TOUT='OUI', MATER=MAT))
CARA = AFFE_CARA_ELEM(MODELE=MO, DISCRET=(
    _F(MAILLE='S1', CARA='K_T_D_L', VALE=(1.e4, 1.e4, 1.e4)),
    _F(MAILLE='S2', CARA='K_T_D_L', VALE=(2.5e4, 2.5e4, 2.5e4)),
    _F(MAILLE='P1', CARA='M_T_D_N', VALE=2.),
    _F(MAILLE='P2', CARA='M_T_D_N', VALE=0.7)))
CL = AFFE_CHAR_CINE(MODELE=MO, MECA_IMPO=(_F(GROUP_NO='N0', DX=0., DY=0., DZ=0.),
                                         _F(TOUT='OUI', DY=0., DZ=0.)))
{tail}",
        tail = PROJECT.replace("NMODES", "2")
    );
    let beam = format!(
        "{}{}",
        beam_head(1.0e-5, 4.0, false),
        PROJECT.replace("NMODES", "6")
    );
    for (name, comm, mail, n, a, b) in [
        ("chain", chain, chain_mail.to_string(), 2, alpha, beta),
        ("beam", beam, beam_mesh(8), 6, 1.0e-5, 4.0),
    ] {
        let run = run_text(&comm, &mail);
        ok(&run);
        let modes = modes(&run.db, "MODES");
        assert_eq!(modes.len(), n, "{name}: {}", run.out);
        let c = gene_matrix(&run.db, "CGEN", n);
        let expected: Vec<f64> = modes.iter().map(|(w2, _)| a * w2 + b).collect();
        let scale = expected.iter().fold(0.0f64, |s, v| s.max(v.abs()));
        let mut worst: f64 = 0.0;
        for i in 0..n {
            assert!((modes[i].1 - 1.0).abs() < 1e-12, "{name}: {modes:?}");
            for (j, cij) in c[i].iter().enumerate() {
                let want = if i == j { expected[i] } else { 0.0 };
                worst = worst.max((cij - want).abs() / scale);
            }
            // The modal damping ratio Rayleigh's formula gives.
            let w = modes[i].0.sqrt();
            let xi = c[i][i] / (2.0 * w);
            let formula = (a * w + b / w) / 2.0;
            assert!(
                (xi - formula).abs() < 1e-10 * formula,
                "{name}: {xi} {formula}"
            );
        }
        eprintln!("{name}: ΦᵀCΦ against α Ω² + β: worst {worst:.1e} of the largest");
        assert!(worst < 1e-10, "{name}: {worst:e}\n{c:?}\n{expected:?}");
        // Both coefficients matter: the mass part alone would be far off.
        assert!(expected.iter().any(|e| (e - b).abs() > 1e-3 * scale));
    }
}

/// The modes, mass-normalised, and the damping projected on them in full storage.
const PROJECT: &str =
    "ASSEMBLAGE(MODELE=MO, CHAM_MATER=CHMAT, CARA_ELEM=CARA, CHAR_CINE=CL, NUME_DDL=CO('NUME'),
           MATR_ASSE=(_F(MATRICE=CO('RIGI'), OPTION='RIGI_MECA'),
                      _F(MATRICE=CO('MASS'), OPTION='MASS_MECA'),
                      _F(MATRICE=CO('AMOR'), OPTION='AMOR_MECA')))
MODES = CALC_MODES(MATR_RIGI=RIGI, MATR_MASS=MASS, OPTION='PLUS_PETITE',
                   CALC_FREQ=_F(NMAX_FREQ=NMODES), NORM_MODE=_F(NORME='MASS_GENE'))
NUMEGE = NUME_DDL_GENE(BASE=MODES, STOCKAGE='PLEIN')
CGEN = PROJ_MATR_BASE(BASE=MODES, NUME_DDL_GENE=NUMEGE, MATR_ASSE=AMOR)
FIN()
";

/// Largest |a − b| over two matrices' entries, which must be at the same positions.
fn largest_difference(a: &[(i64, i64, f64)], b: &[(i64, i64, f64)]) -> f64 {
    assert_eq!(a.len(), b.len());
    a.iter()
        .zip(b)
        .map(|(x, y)| {
            assert_eq!((x.0, x.1), (y.0, y.1));
            (x.2 - y.2).abs()
        })
        .fold(0.0, f64::max)
}

fn largest(a: &[(i64, i64, f64)]) -> f64 {
    a.iter().map(|e| e.2.abs()).fold(0.0, f64::max)
}

/// A beam with a discrete element at its tip, each with its own material (the discrete
/// one with an A_T_D_N dashpot too): ASSEMBLAGE's AMOR_MECA, CALC_MATR_ELEM's AMOR_MECA
/// (K_e, M_e computed) + ASSE_MATRICE, and CALC_MATR_ELEM's AMOR_MECA from the RIGI_MECA
/// and MASS_MECA element matrices given + ASSE_MATRICE give the same matrix, entry by entry
/// to round-off; and it is not the stiffness, the mass or zero.
#[test]
fn calc_matr_elem_and_asse_matrice_give_assemblage_s_damping() {
    let comm = format!(
        "{}ASSEMBLAGE(MODELE=MO, CHAM_MATER=CHMAT, CARA_ELEM=CARA, CHAR_CINE=CL, NUME_DDL=CO('NUME'),
           MATR_ASSE=(_F(MATRICE=CO('AMOR'), OPTION='AMOR_MECA'),
                      _F(MATRICE=CO('RIGI'), OPTION='RIGI_MECA'),
                      _F(MATRICE=CO('MASS'), OPTION='MASS_MECA')))
KE = CALC_MATR_ELEM(OPTION='RIGI_MECA', MODELE=MO, CHAM_MATER=CHMAT, CARA_ELEM=CARA)
ME = CALC_MATR_ELEM(OPTION='MASS_MECA', MODELE=MO, CHAM_MATER=CHMAT, CARA_ELEM=CARA)
CE1 = CALC_MATR_ELEM(OPTION='AMOR_MECA', MODELE=MO, CHAM_MATER=CHMAT, CARA_ELEM=CARA)
CE2 = CALC_MATR_ELEM(OPTION='AMOR_MECA', MODELE=MO, CHAM_MATER=CHMAT, CARA_ELEM=CARA,
                     RIGI_MECA=KE, MASS_MECA=ME)
AMOR1 = ASSE_MATRICE(MATR_ELEM=CE1, NUME_DDL=NUME, CHAR_CINE=CL)
AMOR2 = ASSE_MATRICE(MATR_ELEM=CE2, NUME_DDL=NUME, CHAR_CINE=CL)
FIN()
",
        beam_head(1.0e-5, 4.0, true)
    );
    let run = run_text(&comm, &beam_mesh(6));
    ok(&run);
    assert!(!run.out.contains("<A>"), "{}", run.out);
    let amor = matrix(&run.db, "AMOR");
    let scale = largest(&amor);
    assert!(scale > 0.0);
    for other in ["AMOR1", "AMOR2"] {
        let d = largest_difference(&amor, &matrix(&run.db, other));
        assert!(d <= 1e-14 * scale, "{other}: {d:e} of {scale:e}");
    }
    // Not one of the others: C differs from K and from M by far more than round-off.
    for other in ["RIGI", "MASS"] {
        let d = largest_difference(&amor, &matrix(&run.db, other));
        assert!(d > 1e-3 * scale, "{other}");
    }
}

/// With one material over a model without discrete dampers, the assembled damping is
/// exactly AMOR_ALPHA RIGI + AMOR_BETA MASS, entry by entry (Code_Aster's naming: ALPHA
/// multiplies the stiffness); swapping the two coefficients would fail by far.
#[test]
fn one_material_gives_alpha_times_the_stiffness_plus_beta_times_the_mass() {
    let (alpha, beta) = (1.0e-5, 4.0);
    let comm = format!(
        "{}{}",
        beam_head(alpha, beta, false),
        PROJECT.replace("NMODES", "1")
    );
    let run = run_text(&comm, &beam_mesh(5));
    ok(&run);
    let (c, k, m) = (
        matrix(&run.db, "AMOR"),
        matrix(&run.db, "RIGI"),
        matrix(&run.db, "MASS"),
    );
    let rayleigh: Vec<(i64, i64, f64)> = k
        .iter()
        .zip(&m)
        .map(|(x, y)| {
            assert_eq!((x.0, x.1), (y.0, y.1));
            (x.0, x.1, alpha * x.2 + beta * y.2)
        })
        .collect();
    let d = largest_difference(&c, &rayleigh);
    assert!(d <= 1e-13 * largest(&c), "{d:e}");
    let swapped: Vec<(i64, i64, f64)> = k
        .iter()
        .zip(&m)
        .map(|(x, y)| (x.0, x.1, beta * x.2 + alpha * y.2))
        .collect();
    assert!(largest_difference(&c, &swapped) > largest(&c));
}

/// The transient testcase: free decay of a Rayleigh-damped oscillator on the physical DOFs
/// (two routes to the matrix) and on the modal basis, against the closed form.
#[test]
fn the_rayleigh_testcase_matches_the_damped_free_decay() {
    let dir = tempfile::tempdir().unwrap();
    let (code, out) = run_file(
        &case("dyna_vibra_rayleigh.comm"),
        &dir.path().join("case.db"),
    );
    assert_eq!(code, Some(0), "{out}");
    assert!(out.contains("tests: 15 OK, 0 NOOK"), "{out}");
    assert!(!out.contains("<A>"), "{out}");
}

const ONE_DOF_HEAD: &str = "DEBUT()
MAIL = LIRE_MAILLAGE(FORMAT='ASTER')
MO = AFFE_MODELE(MAILLAGE=MAIL, AFFE=_F(TOUT='OUI', PHENOMENE='MECANIQUE', MODELISATION='DIS_T'))
CARA = AFFE_CARA_ELEM(MODELE=MO, DISCRET=(_F(GROUP_MA='MASSE', CARA='K_T_D_N', VALE=(1., 1., 1.)),
                                         _F(GROUP_MA='MASSE', CARA='M_T_D_N', VALE=1.)))
";

/// AMOR_MECA where nothing is damped: a zero matrix, allowed, with an alarm from each
/// operator (silenced by its id like any alarm).
#[test]
fn a_model_without_damping_gets_a_zero_matrix_and_an_alarm() {
    let comm = format!(
        "{ONE_DOF_HEAD}CE = CALC_MATR_ELEM(OPTION='AMOR_MECA', MODELE=MO, CARA_ELEM=CARA)
ASSEMBLAGE(MODELE=MO, CARA_ELEM=CARA, NUME_DDL=CO('NUME'),
           MATR_ASSE=_F(MATRICE=CO('AMOR'), OPTION='AMOR_MECA'))
FIN()
"
    );
    let run = run_text(&comm, ONE_NODE);
    ok(&run);
    assert!(run.out.contains("<A> <CALC_MATR_ELEM_1>"), "{}", run.out);
    assert!(run.out.contains("<A> <ASSEMBLAGE_1>"), "{}", run.out);
    assert!(matrix(&run.db, "AMOR").iter().all(|e| e.2 == 0.0));
    let silenced = run_text(
        &comm.replace(
            "DEBUT()",
            "DEBUT(IGNORE_ALARM=('CALC_MATR_ELEM_1', 'ASSEMBLAGE_1'))",
        ),
        ONE_NODE,
    );
    ok(&silenced);
    assert!(!silenced.out.contains("<A>"), "{}", silenced.out);
}

/// Errors a user meets, each naming the keyword.
#[test]
fn misuses_of_amor_meca_are_refused_naming_the_keyword() {
    let cases = [
        // RIGI_MECA is read by AMOR_MECA only.
        (
            format!(
                "{ONE_DOF_HEAD}KE = CALC_MATR_ELEM(OPTION='RIGI_MECA', MODELE=MO, CARA_ELEM=CARA)
ME = CALC_MATR_ELEM(OPTION='MASS_MECA', MODELE=MO, CARA_ELEM=CARA, RIGI_MECA=KE)
"
            ),
            ONE_NODE.to_string(),
            "CALC_MATR_ELEM/RIGI_MECA",
            "AMOR_MECA",
        ),
        // A mass given as the stiffness.
        (
            format!(
                "{ONE_DOF_HEAD}ME = CALC_MATR_ELEM(OPTION='MASS_MECA', MODELE=MO, CARA_ELEM=CARA)
CE = CALC_MATR_ELEM(OPTION='AMOR_MECA', MODELE=MO, CARA_ELEM=CARA, RIGI_MECA=ME)
"
            ),
            ONE_NODE.to_string(),
            "CALC_MATR_ELEM/RIGI_MECA",
            "MASS_MECA matrices, RIGI_MECA ones are expected",
        ),
        // AMOR_BETA on a beam whose material has no density.
        (
            beam_head(0.0, 4.0, false).replace(", RHO=7800.", "")
                + "CE = CALC_MATR_ELEM(OPTION='AMOR_MECA', MODELE=MO, CHAM_MATER=CHMAT, CARA_ELEM=CARA)\n",
            beam_mesh(2),
            "CALC_MATR_ELEM/CHAM_MATER",
            "AMOR_BETA multiplies the mass matrix",
        ),
    ];
    for (body, mail, keyword, text) in cases {
        let run = run_text(&format!("{body}FIN()\n"), &mail);
        assert_eq!(run.code, Some(2), "{}", run.out);
        assert!(run.out.contains(keyword), "{keyword}:\n{}", run.out);
        assert!(run.out.contains(text), "{text}:\n{}", run.out);
    }
    // Without AMOR_BETA the beam needs no density: AMOR_ALPHA K_e alone.
    let run = run_text(
        &(beam_head(1.0e-5, 0.0, false).replace(", RHO=7800.", "")
            + "CE = CALC_MATR_ELEM(OPTION='AMOR_MECA', MODELE=MO, CHAM_MATER=CHMAT, CARA_ELEM=CARA)\nFIN()\n"),
        &beam_mesh(2),
    );
    ok(&run);
}

#[test]
fn a_damping_matrix_given_as_stiffness_or_mass_is_refused() {
    // CALC_MODES with the damping as its mass would return "modes" of K φ = ω² C φ.
    let text = std::fs::read_to_string(
        Path::new(env!("CARGO_MANIFEST_DIR")).join("testcases/dyna_vibra_rayleigh.comm"),
    )
    .unwrap();
    let head = text.split("MODES = CALC_MODES").next().unwrap();
    for (call, keyword) in [
        ("X = CALC_MODES(MATR_RIGI=RIGI, MATR_MASS=AMOR, OPTION='PLUS_PETITE', CALC_FREQ=_F(NMAX_FREQ=1))", "CALC_MODES/MATR_MASS"),
        ("X = MODE_STATIQUE(MATR_RIGI=AMOR, MODE_STAT=_F(TOUT='OUI', TOUT_CMP='OUI'))", "MODE_STATIQUE/MATR_RIGI"),
    ] {
        let dir = tempfile::tempdir().unwrap();
        std::fs::copy(
            Path::new(env!("CARGO_MANIFEST_DIR")).join("testcases/dyna_vibra_rayleigh.mail"),
            dir.path().join("case.mail"),
        )
        .unwrap();
        let comm = dir.path().join("case.comm");
        std::fs::write(&comm, format!("{head}\n{call}\nFIN()\n")).unwrap();
        let o = std::process::Command::new(env!("CARGO_BIN_EXE_aster-nl"))
            .arg("run")
            .arg(&comm)
            .arg("--db")
            .arg(dir.path().join("case.db"))
            .output()
            .unwrap();
        let out = format!(
            "{}{}",
            String::from_utf8_lossy(&o.stdout),
            String::from_utf8_lossy(&o.stderr)
        );
        assert_eq!(o.status.code(), Some(2), "{out}");
        assert!(out.contains(keyword), "{out}");
        assert!(out.contains("is a damping matrix"), "{out}");
    }
}

/// MASS_MECA_DIAG: on discrete masses (diagonal already) the lumped mass is the consistent
/// one, entry for entry; a beam's consistent mass couples its nodes, and aster-nl refuses to
/// lump it, naming the option and the cell (rather than give the consistent mass under the
/// lumped name).
#[test]
fn mass_meca_diag_is_the_mass_of_discrete_masses_and_refused_on_beams() {
    let run = run_text(
        &format!(
            "{ONE_DOF_HEAD}
ASSEMBLAGE(MODELE=MO, CARA_ELEM=CARA, NUME_DDL=CO('NUME'),
           MATR_ASSE=(_F(MATRICE=CO('RIGI'), OPTION='RIGI_MECA'),
                      _F(MATRICE=CO('MASS'), OPTION='MASS_MECA'),
                      _F(MATRICE=CO('MDIAG'), OPTION='MASS_MECA_DIAG')))
ME = CALC_MATR_ELEM(OPTION='MASS_MECA_DIAG', MODELE=MO, CARA_ELEM=CARA)
MDIAG2 = ASSE_MATRICE(MATR_ELEM=ME, NUME_DDL=NUME)
FIN()
"
        ),
        ONE_NODE,
    );
    ok(&run);
    let mass = matrix(&run.db, "MASS");
    assert!(!mass.is_empty());
    assert_eq!(matrix(&run.db, "MDIAG"), mass);
    assert_eq!(matrix(&run.db, "MDIAG2"), mass);
    let beam = run_text(
        &format!(
            "{}ME = CALC_MATR_ELEM(OPTION='MASS_MECA_DIAG', MODELE=MO, CHAM_MATER=CHMAT, CARA_ELEM=CARA)\nFIN()\n",
            beam_head(0., 0., false)
        ),
        &beam_mesh(4),
    );
    assert_eq!(beam.code, Some(2), "{}", beam.out);
    assert!(beam.out.contains("CALC_MATR_ELEM/OPTION"), "{}", beam.out);
    assert!(
        beam.out.contains("MASS_MECA_DIAG: the mass of cell E1"),
        "{}",
        beam.out
    );
}
