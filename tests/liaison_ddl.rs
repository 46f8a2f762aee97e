//! AFFE_CHAR_MECA/LIAISON_DDL through the binary, on generated cases: one node with
//! springs (KX, KY, KZ) and a mass M, held by one or two random linear relations between
//! its DOFs (and sometimes DZ blocked as well). The modes are those of the springs on the
//! constrained space, the null space of the constraint rows: with one row, the 2×2
//! stiffness on an orthonormal basis of the plane normal to it (closed-form eigenvalues);
//! with two, the line along their cross product. That reference never eliminates a DOF,
//! so it checks the elimination aster-nl uses instead of Code_Aster's Lagrange
//! multipliers. The frequencies are compared to 1e-9 relative (the eigensolver and the
//! closed form each lose a few ulps of ω² to cancellation; 1e-9 leaves room for the
//! conditioning of a relation with one small coefficient, and a misapplied relation moves a
//! frequency by far more), and every stored mode shape must satisfy every relation to
//! 1e-12 of its size.

use proptest::prelude::*;
use std::path::Path;
use std::process::Command;

const MESH: &str = "COOR_3D\n NO1 0.0 0.0 0.0\nFINSF\nPOI1\n P1 NO1\nFINSF\nGROUP_MA\n MASSE\n P1\nFINSF\nGROUP_NO\n NO1\n NO1\nFINSF\nFIN\n";

#[derive(Clone, Debug)]
struct Case {
    k: [f64; 3],
    m: f64,
    relations: Vec<[f64; 3]>,
    block_dz: bool,
    /// Name the node by NOEUD (13.x) rather than GROUP_NO.
    by_noeud: bool,
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn unit(a: [f64; 3]) -> [f64; 3] {
    let n = dot(a, a).sqrt();
    [a[0] / n, a[1] / n, a[2] / n]
}

fn k_form(k: [f64; 3], a: [f64; 3], b: [f64; 3]) -> f64 {
    k[0] * a[0] * b[0] + k[1] * a[1] * b[1] + k[2] * a[2] * b[2]
}

impl Case {
    /// The constraint rows: the relations, and DZ = 0 when blocked.
    fn rows(&self) -> Vec<[f64; 3]> {
        let mut rows = self.relations.clone();
        if self.block_dz {
            rows.push([0.0, 0.0, 1.0]);
        }
        rows
    }

    /// The exact ω² of the constrained springs, in increasing order.
    fn omega2(&self) -> Vec<f64> {
        let rows = self.rows();
        match rows.as_slice() {
            [n] => {
                // An orthonormal basis (e1, e2) of the plane normal to n.
                let n = unit(*n);
                let pick = if n[0].abs() < 0.6 {
                    [1.0, 0.0, 0.0]
                } else {
                    [0.0, 1.0, 0.0]
                };
                let e1 = unit(cross(n, pick));
                let e2 = cross(n, e1);
                let (a, b, d) = (
                    k_form(self.k, e1, e1) / self.m,
                    k_form(self.k, e1, e2) / self.m,
                    k_form(self.k, e2, e2) / self.m,
                );
                let mean = 0.5 * (a + d);
                let half = (0.25 * (a - d) * (a - d) + b * b).sqrt();
                vec![mean - half, mean + half]
            }
            [n1, n2] => {
                let d = unit(cross(*n1, *n2));
                vec![k_form(self.k, d, d) / self.m]
            }
            _ => unreachable!("one or two rows"),
        }
    }

    fn comm(&self) -> String {
        let nodes = if self.by_noeud {
            "NOEUD=('NO1', 'NO1', 'NO1')"
        } else {
            "GROUP_NO=('NO1', 'NO1', 'NO1')"
        };
        let relations: Vec<String> = self
            .relations
            .iter()
            .map(|c| {
                format!(
                    "_F({nodes}, DDL=('DX', 'DY', 'DZ'), COEF_MULT=({:e}, {:e}, {:e}), COEF_IMPO=0.)",
                    c[0], c[1], c[2]
                )
            })
            .collect();
        let block = if self.block_dz {
            "DDL_IMPO=_F(GROUP_NO='NO1', DZ=0.),"
        } else {
            ""
        };
        let freqs = self.omega2();
        let tests: Vec<String> = freqs
            .iter()
            .enumerate()
            .map(|(i, w2)| {
                format!(
                    "TEST_RESU(RESU=_F(RESULTAT=MODES, NUME_ORDRE={}, PARA='FREQ', VALE_REFE={:.17e}, REFERENCE='ANALYTIQUE', PRECISION=1.e-9))",
                    i + 1,
                    w2.sqrt() / (2.0 * std::f64::consts::PI)
                )
            })
            .collect();
        format!(
            "DEBUT()
MAIL = LIRE_MAILLAGE(FORMAT='ASTER')
MODELE = AFFE_MODELE(MAILLAGE=MAIL, AFFE=_F(TOUT='OUI', PHENOMENE='MECANIQUE', MODELISATION='DIS_T'))
CARA = AFFE_CARA_ELEM(MODELE=MODELE, DISCRET=(_F(GROUP_MA='MASSE', CARA='K_T_D_N', VALE=({:e}, {:e}, {:e})),
                                             _F(GROUP_MA='MASSE', CARA='M_T_D_N', VALE={:e})))
CH = AFFE_CHAR_MECA(MODELE=MODELE, {block} LIAISON_DDL=({},))
ASSEMBLAGE(MODELE=MODELE, CARA_ELEM=CARA, CHARGE=CH, NUME_DDL=CO('NUME'),
           MATR_ASSE=(_F(MATRICE=CO('RIGI'), OPTION='RIGI_MECA'),
                      _F(MATRICE=CO('MASS'), OPTION='MASS_MECA')))
MODES = CALC_MODES(MATR_RIGI=RIGI, MATR_MASS=MASS, OPTION='PLUS_PETITE', CALC_FREQ=_F(NMAX_FREQ={}))
{}
FIN()
",
            self.k[0],
            self.k[1],
            self.k[2],
            self.m,
            relations.join(", "),
            freqs.len(),
            tests.join("\n")
        )
    }
}

/// The DX, DY, DZ of each stored mode.
fn shapes(db: &Path) -> Vec<[f64; 3]> {
    let c = rusqlite::Connection::open(db).unwrap();
    let mut stmt = c
        .prepare(
            "SELECT NUME_ORDRE, NOM_CMP, value FROM mode_shapes WHERE concept = 'MODES' ORDER BY NUME_ORDRE",
        )
        .unwrap();
    let rows = stmt
        .query_map([], |r| {
            Ok((
                r.get::<_, i64>(0)?,
                r.get::<_, String>(1)?,
                r.get::<_, f64>(2)?,
            ))
        })
        .unwrap();
    let mut out: Vec<[f64; 3]> = Vec::new();
    for row in rows {
        let (order, cmp, v) = row.unwrap();
        let i = usize::try_from(order - 1).unwrap();
        while out.len() <= i {
            out.push([0.0; 3]);
        }
        let c = match cmp.as_str() {
            "DX" => 0,
            "DY" => 1,
            _ => 2,
        };
        out[i][c] = v;
    }
    out
}

/// A coefficient of a relation: of either sign, away from zero, or (one time in four)
/// exactly zero, so that relations on two of the three DOFs are drawn too.
fn coef() -> impl Strategy<Value = f64> {
    prop_oneof![
        1 => Just(0.0),
        3 => (0.1f64..1.0, any::<bool>()).prop_map(|(v, neg)| if neg { -v } else { v }),
    ]
}

fn relation() -> impl Strategy<Value = [f64; 3]> {
    [coef(), coef(), coef()].prop_filter("a relation with a term", |c| c.iter().any(|v| *v != 0.0))
}

fn case() -> impl Strategy<Value = Case> {
    (
        [3.0f64..5.0, 3.0f64..5.0, 3.0f64..5.0],
        0.5f64..5.0,
        prop::collection::vec(relation(), 1..=2),
        any::<bool>(),
        any::<bool>(),
    )
        .prop_map(|(lk, m, relations, block_dz, by_noeud)| Case {
            k: lk.map(|e| 10f64.powf(e)),
            m,
            // With DZ blocked, one relation (two rows in all).
            block_dz: block_dz && relations.len() == 1,
            relations,
            by_noeud,
        })
        .prop_filter("independent rows, and distinct springs", |c| {
            let rows = c.rows();
            let independent = match rows.as_slice() {
                [a, b] => {
                    let x = cross(*a, *b);
                    dot(x, x).sqrt() > 0.2 * dot(*a, *a).sqrt() * dot(*b, *b).sqrt()
                }
                _ => true,
            };
            // Two equal springs make a double eigenvalue, whose shapes are not unique.
            let spread = |a: f64, b: f64| (a - b).abs() > 0.05 * a.max(b);
            independent
                && spread(c.k[0], c.k[1])
                && spread(c.k[1], c.k[2])
                && spread(c.k[0], c.k[2])
        })
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 24, ..ProptestConfig::default() })]

    #[test]
    fn modes_of_springs_held_by_linear_relations(c in case()) {
        let dir = tempfile::tempdir().unwrap();
        let comm = dir.path().join("case.comm");
        std::fs::write(&comm, c.comm()).unwrap();
        std::fs::write(dir.path().join("case.mail"), MESH).unwrap();
        let db = dir.path().join("case.db");
        let o = Command::new(env!("CARGO_BIN_EXE_aster-nl"))
            .arg("run")
            .arg(&comm)
            .arg("--db")
            .arg(&db)
            .output()
            .unwrap();
        let out = format!(
            "{}{}",
            String::from_utf8_lossy(&o.stdout),
            String::from_utf8_lossy(&o.stderr)
        );
        let n = c.omega2().len();
        prop_assert_eq!(o.status.code(), Some(0), "{}\n{}", c.comm(), out);
        prop_assert!(out.contains(&format!("tests: {n} OK, 0 NOOK")), "{}\n{}", c.comm(), out);
        let shapes = shapes(&db);
        prop_assert_eq!(shapes.len(), n);
        for phi in &shapes {
            let size = dot(*phi, *phi).sqrt();
            prop_assert!(size > 0.0);
            for row in c.rows() {
                let r = dot(row, *phi) / (dot(row, row).sqrt() * size);
                prop_assert!(r.abs() < 1e-12, "relation {:?} on shape {:?}: {:e}", row, phi, r);
            }
        }
    }
}

/// A relation with a DOF the node does not carry, and a relation whose lists disagree,
/// are refused naming the keyword; a relation on the physical DOFs of MODE_NON_LINE is
/// refused with the route that takes it.
#[test]
fn bad_relations_name_their_keyword() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("bad.mail"), MESH).unwrap();
    let run = |body: &str| -> String {
        let comm = dir.path().join("bad.comm");
        std::fs::write(
            &comm,
            format!(
                "DEBUT()
MAIL = LIRE_MAILLAGE(FORMAT='ASTER')
MODELE = AFFE_MODELE(MAILLAGE=MAIL, AFFE=_F(TOUT='OUI', PHENOMENE='MECANIQUE', MODELISATION='DIS_T'))
CARA = AFFE_CARA_ELEM(MODELE=MODELE, DISCRET=(_F(GROUP_MA='MASSE', CARA='K_T_D_N', VALE=(1.e4, 2.e4, 3.e4)),
                                             _F(GROUP_MA='MASSE', CARA='M_T_D_N', VALE=1.)))
{body}
FIN()
"
            ),
        )
        .unwrap();
        let o = Command::new(env!("CARGO_BIN_EXE_aster-nl"))
            .arg("run")
            .arg(&comm)
            .arg("--db")
            .arg(dir.path().join("bad.db"))
            .output()
            .unwrap();
        assert_eq!(o.status.code(), Some(2));
        format!(
            "{}{}",
            String::from_utf8_lossy(&o.stdout),
            String::from_utf8_lossy(&o.stderr)
        )
    };
    let out = run("CH = AFFE_CHAR_MECA(MODELE=MODELE, LIAISON_DDL=_F(GROUP_NO=('NO1', 'NO1'), DDL=('DX', 'DRZ'), COEF_MULT=(1., -1.), COEF_IMPO=0.))");
    assert!(out.contains("AFFE_CHAR_MECA/LIAISON_DDL/DDL"), "{out}");
    assert!(
        out.contains("component DRZ does not exist on node NO1"),
        "{out}"
    );
    let out = run("CH = AFFE_CHAR_MECA(MODELE=MODELE, LIAISON_DDL=_F(GROUP_NO='NO1', DDL=('DX', 'DY'), COEF_MULT=(1., -1.), COEF_IMPO=0.))");
    assert!(out.contains("1 node(s), 2 DDL and 2 COEF_MULT"), "{out}");
    let out = run(
        "CH = AFFE_CHAR_MECA(MODELE=MODELE, LIAISON_DDL=_F(GROUP_NO=('NO1', 'NO1'), DDL=('DX', 'DY'), COEF_MULT=(1., -1.), COEF_IMPO=0.))
ASSEMBLAGE(MODELE=MODELE, CARA_ELEM=CARA, CHARGE=CH, NUME_DDL=CO('NUME'),
           MATR_ASSE=(_F(MATRICE=CO('RIGI'), OPTION='RIGI_MECA'), _F(MATRICE=CO('MASS'), OPTION='MASS_MECA')))
MODES = CALC_MODES(MATR_RIGI=RIGI, MATR_MASS=MASS, OPTION='PLUS_PETITE', CALC_FREQ=_F(NMAX_FREQ=1))
MNL = MODE_NON_LINE(ETAT_INIT=_F(MODE_LINE=MODES, NUME_ORDRE=1), MATR_RIGI=RIGI, MATR_MASS=MASS,
                    CHOC=_F(OBSTACLE='PLAN', GROUP_NO='NO1', NOM_CMP='DZ', JEU=1.e-3, RIGI_NOR=1.e5),
                    RESOLUTION=_F(NB_HARM_LINE=3, NB_HARM_NONL=32, NB_BRANCHE=2, NB_PAS_MAN=1))",
    );
    assert!(out.contains("LIAISON_DDL relations"), "{out}");
    assert!(out.contains("MODE_NON_LINE/MATR_RIGI"), "{out}");
}
