//! The models of the bench, written the way users write them: a mesh (.mail) and a command
//! file (.comm) that assembles the matrices, computes the linear modes and runs
//! MODE_NON_LINE. The same files serve the whole runs (any aster-nl binary, old or new)
//! and the engine-level runs (the prefix up to CALC_MODES run in-process, the engine
//! called directly with the matrices and the mode it produced).

use crate::error::{Error, Result};
use crate::interp;
use crate::nnm::{self, Continuation, Harmonics, Problem, Settings};
use crate::ops::mode_non_line::problem::engine_shocks;
use crate::ops::Units;
use crate::store::mnl::StoredShock;
use crate::store::{matrix, modes as mode_store, Store};
use std::fmt::Write as _;
use std::path::Path;

/// MODE_NON_LINE settings of a case (RESOLUTION and ETAT_INIT).
#[derive(Clone, Debug)]
pub struct Mnl {
    pub h_lin: usize,
    pub h_nonl: usize,
    pub branches: usize,
    pub points: usize,
    pub order: usize,
    pub prec_man: f64,
    pub prec_newton: f64,
    pub direction: i32,
    /// None: chosen from the mode so that the first ring node starts at 0.9 JEU.
    pub coef_ampl: Option<f64>,
    pub det_test: bool,
}

/// One model: mesh, the command-file prefix up to CALC_MODES, its shocks and settings.
#[derive(Clone, Debug)]
pub struct Case {
    pub name: String,
    pub mail: String,
    pub prefix: String,
    pub shocks: Vec<StoredShock>,
    pub mnl: Mnl,
}

fn mnl(h_lin: usize, h_nonl: usize, branches: usize, points: usize) -> Mnl {
    Mnl {
        h_lin,
        h_nonl,
        branches,
        points,
        order: 20,
        prec_man: 1e-8,
        prec_newton: 1e-9,
        // Forward, toward increasing amplitude (DIR_EVOLUTION=-1, docs/mode_non_line.md).
        direction: -1,
        coef_ampl: None,
        det_test: true,
    }
}

fn ring(
    node: &str,
    cmps: [&str; 2],
    gap: f64,
    stiffness: f64,
    regul: f64,
    origin: [f64; 3],
) -> StoredShock {
    StoredShock {
        obstacle: "CERCLE".into(),
        node: node.into(),
        cmps: cmps.iter().map(|c| c.to_string()).collect(),
        gap,
        stiffness,
        regul,
        origin,
        loi_cercle: "RAYON".into(),
    }
}

/// The bars' two CERCLE rings at nodes N`a` and N`b` (DY, DZ): JEU 1 mm, RIGI_NOR 1e4,
/// PARA_REGUL 1e-4, centre offset 0.3 JEU along DY.
fn bar_rings(a: usize, b: usize) -> Vec<StoredShock> {
    let gap = 1e-3;
    let o = [0.0, 0.3 * gap, 0.0];
    [a, b]
        .iter()
        .map(|n| ring(&format!("N{n}"), ["DY", "DZ"], gap, 1e4, 1e-4, o))
        .collect()
}

/// sdnd122a (testcases/sdnd122a.comm): one DOF against a wall, H_nl varied.
pub fn wall(h_nonl: usize, branches: usize) -> Case {
    let mail = include_str!("../../testcases/sdnd122a.mail").to_string();
    let comm = include_str!("../../testcases/sdnd122a.comm");
    let prefix = comm[..comm.find("MNL = MODE_NON_LINE").unwrap_or(comm.len())].to_string();
    Case {
        name: format!("sdnd122a H_nl {h_nonl}"),
        mail,
        prefix,
        shocks: vec![StoredShock {
            obstacle: "PLAN".into(),
            node: "N2".into(),
            cmps: vec!["DX".into()],
            gap: 0.01,
            stiffness: 50.0,
            regul: 5e-5,
            origin: [0.0; 3],
            loi_cercle: "RAYON".into(),
        }],
        mnl: Mnl {
            h_lin: 5,
            h_nonl,
            branches,
            points: 1,
            order: 20,
            prec_man: 1e-14,
            prec_newton: 1e-9,
            direction: -1,
            coef_ampl: Some(1.0),
            det_test: true,
        },
    }
}

/// Steel tube (POU_D_E, CERCLE section R = 1 cm, EP = 1 mm).
const BEAM_PREFIX: &str = "DEBUT(CODE=_F(NIV_PUB_WEB='INTERNET'))
MAIL = LIRE_MAILLAGE(FORMAT='ASTER', UNITE=20)
MODELE = AFFE_MODELE(MAILLAGE=MAIL, AFFE=_F(GROUP_MA='TUBE', PHENOMENE='MECANIQUE', MODELISATION='POU_D_E'))
ACIER = DEFI_MATERIAU(ELAS=_F(E=2.e11, NU=0.3, RHO=7800.))
CHMAT = AFFE_MATERIAU(MAILLAGE=MAIL, AFFE=_F(TOUT='OUI', MATER=ACIER))
CARA = AFFE_CARA_ELEM(MODELE=MODELE, POUTRE=_F(GROUP_MA='TUBE', SECTION='CERCLE', CARA=('R', 'EP'), VALE=(0.01, 0.001)))
";

fn assemble_and_modes(bc: &str) -> String {
    format!(
        "BLOC = AFFE_CHAR_CINE(MODELE=MODELE, MECA_IMPO=({bc}))
ASSEMBLAGE(MODELE=MODELE, CHAM_MATER=CHMAT, CARA_ELEM=CARA, CHAR_CINE=BLOC, NUME_DDL=CO('NUME'),
           MATR_ASSE=(_F(MATRICE=CO('RIGIDITE'), OPTION='RIGI_MECA'),
                      _F(MATRICE=CO('MASSE'), OPTION='MASS_MECA'),),)
MODES = CALC_MODES(MATR_RIGI=RIGIDITE, MATR_MASS=MASSE, OPTION='PLUS_PETITE', CALC_FREQ=_F(NMAX_FREQ=1))
"
    )
}

fn mail_of(title: &str, nodes: &[(String, [f64; 3])], groups_no: &[(&str, Vec<String>)]) -> String {
    let mut s = format!("TITRE\n {title}\nFINSF\nCOOR_3D\n");
    for (n, p) in nodes {
        let _ = writeln!(s, " {n} {:.12e} {:.12e} {:.12e}", p[0], p[1], p[2]);
    }
    s.push_str("FINSF\nSEG2\n");
    for i in 1..nodes.len() {
        let _ = writeln!(s, " E{i} {} {}", nodes[i - 1].0, nodes[i].0);
    }
    s.push_str("FINSF\nGROUP_MA\n TUBE\n");
    for i in 1..nodes.len() {
        let _ = writeln!(s, " E{i}");
    }
    s.push_str("FINSF\n");
    for (g, members) in groups_no {
        let _ = writeln!(s, "GROUP_NO\n {g}");
        for m in members {
            let _ = writeln!(s, " {m}");
        }
        s.push_str("FINSF\n");
    }
    s.push_str("FIN\n");
    s
}

/// An sdnl137a-like U-tube: two legs of 1 m and a 0.5 m top (3 + 4 + 3 POU_D_E elements,
/// 11 nodes), clamped at both feet (54 free DOFs), a CERCLE ring (JEU 1 mm) at the
/// second node of each leg acting on (DX, DZ). Its first mode is out of plane (DZ): a
/// centred ring would see an orbit through its centre, which the CERCLE law of this
/// version refuses, so `offset` (in JEU) moves the ring centres along DX (0: centred).
pub fn utube(h_nonl: usize, branches: usize, points: usize, offset: f64) -> Case {
    let (h, w) = (1.0, 0.5);
    let mut nodes = Vec::new();
    for i in 0..=3 {
        nodes.push((
            format!("N{}", nodes.len() + 1),
            [0.0, h * i as f64 / 3.0, 0.0],
        ));
    }
    for i in 1..=4 {
        nodes.push((
            format!("N{}", nodes.len() + 1),
            [w * i as f64 / 4.0, h, 0.0],
        ));
    }
    for i in 1..=3 {
        nodes.push((
            format!("N{}", nodes.len() + 1),
            [w, h * (1.0 - i as f64 / 3.0), 0.0],
        ));
    }
    let mail = mail_of(
        "U-tube, 10 POU_D_E elements",
        &nodes,
        &[
            ("PIEDS", vec!["N1".into(), "N11".into()]),
            ("R1", vec!["N2".into()]),
            ("R2", vec!["N10".into()]),
        ],
    );
    let prefix = format!(
        "{BEAM_PREFIX}{}",
        assemble_and_modes("_F(GROUP_NO='PIEDS', DX=0., DY=0., DZ=0., DRX=0., DRY=0., DRZ=0.),")
    );
    let gap = 1e-3;
    let o = [offset * gap, 0.0, 0.0];
    Case {
        name: "U-tube".into(),
        mail,
        prefix,
        shocks: vec![
            ring("N2", ["DX", "DZ"], gap, 1e4, 1e-4, o),
            ring("N10", ["DX", "DZ"], gap, 1e4, 1e-4, o),
        ],
        mnl: mnl(1, h_nonl, branches, points),
    }
}

/// A straight steel bar along X of `elements` POU_D_E elements (1 m, rectangular section
/// 13.7 × 10 mm: its first mode bends in XZ, the first in XY is 1.37 times higher, clear of
/// the harmonics 2–5 of the first), clamped at both ends, bending in both planes
/// (DX and DRX blocked: 4 free DOFs per inner node), with CERCLE rings (JEU 1 mm, centre
/// offset 0.3 JEU along DY, across the motion) at two nodes placed symmetrically near L/3
/// and 2L/3 acting on (DY, DZ).
pub fn beam(elements: usize, h_lin: usize, h_nonl: usize, branches: usize) -> Case {
    let elements = elements.max(3);
    let nodes: Vec<(String, [f64; 3])> = (0..=elements)
        .map(|i| (format!("N{i}"), [i as f64 / elements as f64, 0.0, 0.0]))
        .collect();
    let a = (elements + 1) / 3;
    let b = elements - a;
    let all: Vec<String> = nodes.iter().map(|n| n.0.clone()).collect();
    let mail = mail_of(
        "straight tube",
        &nodes,
        &[
            ("ENDS", vec!["N0".into(), format!("N{elements}")]),
            ("ALL", all),
        ],
    );
    let prefix = format!(
        "{}{}",
        BEAM_PREFIX.replace(
            "SECTION='CERCLE', CARA=('R', 'EP'), VALE=(0.01, 0.001)",
            "SECTION='RECTANGLE', CARA=('HY', 'HZ'), VALE=(0.0137, 0.01)"
        ),
        assemble_and_modes(
            "_F(GROUP_NO='ENDS', DX=0., DY=0., DZ=0., DRX=0., DRY=0., DRZ=0.), _F(GROUP_NO='ALL', DX=0., DRX=0.),"
        )
    );
    Case {
        name: format!("bar {} DOFs", 4 * (elements - 1)),
        mail,
        prefix,
        shocks: bar_rings(a, b),
        mnl: mnl(h_lin, h_nonl, branches, 1),
    }
}

/// Ratio of successive span lengths of `spans` (unequal spans: no cluster of modes).
pub const SPAN_RATIO: f64 = 0.95;

/// Elements per span of `spans`, in their order along the bar: geometric in SPAN_RATIO,
/// summing to `elements` (at least 4 each), the longest in the middle (index `spans / 2`)
/// and the others alternately left and right of it, shorter and shorter toward both
/// clamped ends (a clamped end stiffens its span: the longest span there would not carry
/// the first mode).
pub fn span_elements(spans: usize, elements: usize) -> Vec<usize> {
    let spans = spans.max(1);
    let elements = elements.max(4 * spans);
    let w: Vec<f64> = (0..spans).map(|i| SPAN_RATIO.powi(i as i32)).collect();
    let sum: f64 = w.iter().sum();
    let mut n: Vec<usize> = w
        .iter()
        .map(|wi| ((elements as f64 * wi / sum).round() as usize).max(4))
        .collect();
    // Round-off goes to the longest span (it stays the longest).
    let total: usize = n.iter().sum();
    n[0] = (n[0] + elements).saturating_sub(total).max(4);
    // By decreasing length: the middle, then one left, one right, ...
    let mid = spans / 2;
    let mut order = vec![0; spans];
    for (k, nk) in n.iter().enumerate() {
        let pos = if k % 2 == 1 {
            mid - k.div_ceil(2)
        } else {
            mid + k / 2
        };
        order[pos] = *nk;
    }
    order
}

/// A continuous bar on simple supports: `beam()`'s bar (rectangular section 13.7 × 10 mm,
/// clamped at both ends, DX and DRX blocked everywhere: 4 free DOFs per inner node)
/// prolonged to `spans` spans of unequal lengths (geometric, ratio SPAN_RATIO, the longest,
/// 1 m, in the middle: span_elements) with one element size for all, `elements` in all;
/// the inner span ends (GROUP_NO SUPPORTS) have DY = DZ = 0. The condition number of K
/// grows like the fourth power of the elements of one span, not of the whole bar, so the
/// longest span's count (about 2 500 at 10⁵ DOFs) is what must stay moderate. CERCLE rings
/// as beam()'s (JEU 1 mm, centre offset 0.3 JEU along DY) at the quarter and the middle of
/// the longest span, where the first mode (its first bending mode in XZ) moves.
pub fn spans(spans: usize, elements: usize, h_lin: usize, h_nonl: usize, branches: usize) -> Case {
    let per = span_elements(spans, elements);
    let spans = per.len();
    let elements: usize = per.iter().sum();
    let longest = spans / 2;
    let h = 1.0 / per[longest] as f64;
    let nodes: Vec<(String, [f64; 3])> = (0..=elements)
        .map(|i| (format!("N{i}"), [i as f64 * h, 0.0, 0.0]))
        .collect();
    let mut supports = Vec::new();
    let mut end = 0;
    for n in &per[..spans - 1] {
        end += n;
        supports.push(format!("N{end}"));
    }
    let all: Vec<String> = nodes.iter().map(|n| n.0.clone()).collect();
    let mut groups = vec![
        ("ENDS", vec!["N0".into(), format!("N{elements}")]),
        ("ALL", all),
    ];
    let mut bc = String::from(
        "_F(GROUP_NO='ENDS', DX=0., DY=0., DZ=0., DRX=0., DRY=0., DRZ=0.), _F(GROUP_NO='ALL', DX=0., DRX=0.),",
    );
    if !supports.is_empty() {
        groups.push(("SUPPORTS", supports));
        bc.push_str(" _F(GROUP_NO='SUPPORTS', DY=0., DZ=0.),");
    }
    let mail = mail_of(
        &format!("continuous tube on {} supports", spans + 1),
        &nodes,
        &groups,
    );
    let prefix = format!(
        "{}{}",
        BEAM_PREFIX.replace(
            "SECTION='CERCLE', CARA=('R', 'EP'), VALE=(0.01, 0.001)",
            "SECTION='RECTANGLE', CARA=('HY', 'HZ'), VALE=(0.0137, 0.01)"
        ),
        assemble_and_modes(&bc)
    );
    let start: usize = per[..longest].iter().sum();
    let (quarter, mid) = (start + per[longest] / 4, start + per[longest] / 2);
    Case {
        name: format!(
            "bar on {} supports, {} DOFs",
            spans + 1,
            4 * (elements - 1) - 2 * (spans - 1)
        ),
        mail,
        prefix,
        shocks: bar_rings(mid, quarter),
        mnl: mnl(h_lin, h_nonl, branches, 1),
    }
}

/// A fixed-free chain of `n` unit masses and springs k = 10 (DIS_T), a PLAN stop
/// (JEU 0.01, RIGI_NOR = k, PARA_REGUL 1e-4) at its free end.
pub fn chain(n: usize, h_lin: usize, h_nonl: usize, branches: usize) -> Case {
    let n = n.max(1);
    let mut mail = format!("TITRE\n chain of {n} masses\nFINSF\nCOOR_3D\n");
    for i in 0..=n {
        let _ = writeln!(mail, " N{i} {}.0 0.0 0.0", i);
    }
    mail.push_str("FINSF\nSEG2\n");
    for i in 1..=n {
        let _ = writeln!(mail, " S{i} N{} N{i}", i - 1);
    }
    mail.push_str("FINSF\nPOI1\n");
    for i in 1..=n {
        let _ = writeln!(mail, " P{i} N{i}");
    }
    mail.push_str("FINSF\nGROUP_MA\n RESSORTS\n");
    for i in 1..=n {
        let _ = writeln!(mail, " S{i}");
    }
    mail.push_str("FINSF\nGROUP_MA\n MASSES\n");
    for i in 1..=n {
        let _ = writeln!(mail, " P{i}");
    }
    mail.push_str("FINSF\nGROUP_NO\n BASE\n N0\nFINSF\nGROUP_NO\n ALL\n");
    for i in 0..=n {
        let _ = writeln!(mail, " N{i}");
    }
    let _ = write!(mail, "FINSF\nGROUP_NO\n END\n N{n}\nFINSF\nFIN\n");
    let prefix = "DEBUT(CODE=_F(NIV_PUB_WEB='INTERNET'))
MAIL = LIRE_MAILLAGE(FORMAT='ASTER', UNITE=20)
MODELE = AFFE_MODELE(MAILLAGE=MAIL, AFFE=_F(TOUT='OUI', PHENOMENE='MECANIQUE', MODELISATION='DIS_T'))
CARA = AFFE_CARA_ELEM(MODELE=MODELE, DISCRET=(_F(GROUP_MA='RESSORTS', CARA='K_T_D_L', VALE=(10., 0., 0.)),
                                              _F(GROUP_MA='MASSES', CARA='M_T_D_N', VALE=1.),))
BLOC = AFFE_CHAR_CINE(MODELE=MODELE, MECA_IMPO=(_F(GROUP_NO='BASE', DX=0.), _F(GROUP_NO='ALL', DY=0., DZ=0.),))
ASSEMBLAGE(MODELE=MODELE, CARA_ELEM=CARA, CHAR_CINE=BLOC, NUME_DDL=CO('NUME'),
           MATR_ASSE=(_F(MATRICE=CO('RIGIDITE'), OPTION='RIGI_MECA'),
                      _F(MATRICE=CO('MASSE'), OPTION='MASS_MECA'),),)
MODES = CALC_MODES(MATR_RIGI=RIGIDITE, MATR_MASS=MASSE, OPTION='PLUS_PETITE', CALC_FREQ=_F(NMAX_FREQ=1))
"
    .to_string();
    Case {
        name: format!("chain {n} DOFs"),
        mail,
        prefix,
        shocks: vec![StoredShock {
            obstacle: "PLAN".into(),
            node: format!("N{n}"),
            cmps: vec!["DX".into()],
            gap: 0.01,
            stiffness: 10.0,
            regul: 1e-4,
            origin: [0.0; 3],
            loi_cercle: "RAYON".into(),
        }],
        mnl: mnl(h_lin, h_nonl, branches, 1),
    }
}

/// A real as the .comm language reads it (Rust's shortest round-trip exponent form).
fn fmt_real(v: f64) -> String {
    format!("{v:e}")
}

/// The whole command file: the prefix, then MODE_NON_LINE with `coef_ampl`, then FIN.
/// `plus_forward`: write for a binary that reads DIR_EVOLUTION=1 as forward (aster-nl
/// before the DIR_EVOLUTION change, e.g. main 33a8926), so that old and new binaries
/// compute the same branches.
pub fn full_comm(case: &Case, coef_ampl: f64, plus_forward: bool) -> String {
    let m = &case.mnl;
    let direction = if plus_forward {
        -m.direction
    } else {
        m.direction
    };
    let mut choc = String::new();
    for s in &case.shocks {
        let cmps = if s.cmps.len() == 1 {
            format!("'{}'", s.cmps[0])
        } else {
            format!(
                "({})",
                s.cmps
                    .iter()
                    .map(|c| format!("'{c}'"))
                    .collect::<Vec<_>>()
                    .join(", ")
            )
        };
        let orig = if s.obstacle == "CERCLE" {
            format!(
                ", ORIG_OBST=({}, {}, {}), LOI_CERCLE='{}'",
                fmt_real(s.origin[0]),
                fmt_real(s.origin[1]),
                fmt_real(s.origin[2]),
                s.loi_cercle
            )
        } else {
            String::new()
        };
        let _ = write!(
            choc,
            "_F(OBSTACLE='{}', NOEUD='{}', NOM_CMP={cmps}, JEU={}, RIGI_NOR={}, PARA_REGUL={}{orig}),\n                          ",
            s.obstacle,
            s.node,
            fmt_real(s.gap),
            fmt_real(s.stiffness),
            fmt_real(s.regul)
        );
    }
    format!(
        "{}
MNL = MODE_NON_LINE(MATR_RIGI=RIGIDITE, MATR_MASS=MASSE,
                    ETAT_INIT=_F(MODE_LINE=MODES, NUME_ORDRE=1, DIR_EVOLUTION={}, COEF_AMPL={}),
                    CHOC=({choc}),
                    RESOLUTION=_F(METHODE='EHMAN', NB_HARM_LINE={}, NB_HARM_NONL={}, NB_BRANCHE={},
                                  NB_ORDRE_MAN={}, PREC_MAN={}, PREC_NEWTON={}, ITER_NEWTON_MAXI=15,
                                  NB_PAS_MAN={}, TEST_BIFURCATION='{}'))
FIN()
",
        case.prefix,
        direction,
        fmt_real(coef_ampl),
        m.h_lin,
        m.h_nonl,
        m.branches,
        m.order,
        fmt_real(m.prec_man),
        fmt_real(m.prec_newton),
        m.points,
        if m.det_test {
            "SERIE_DETERMINANT"
        } else {
            "SERIE"
        }
    )
}

/// What the engine needs, read from the prefix's run.
pub struct Prepared {
    pub problem: Problem,
    pub settings: Settings,
    pub mode: Vec<f64>,
    pub omega: f64,
    pub coef_ampl: f64,
    /// Nonzeros of K ∪ M (reduced), for bytes-per-nonzero figures.
    pub nnz: usize,
}

/// Run the prefix in-process in `dir` (mesh written there), then build the engine problem.
pub fn prepare(case: &Case, dir: &Path) -> Result<Prepared> {
    let io = |e: std::io::Error| Error::new(crate::error::ErrorKind::Io, format!("bench: {e}"));
    std::fs::create_dir_all(dir).map_err(io)?;
    let mail = dir.join("case.mail");
    std::fs::write(&mail, &case.mail).map_err(io)?;
    let db = dir.join("prefix.db");
    let _ = std::fs::remove_file(&db);
    let mut units = Units::default();
    units.map.insert(20, mail);
    let src = crate::lang::Source {
        name: "prefix.comm".into(),
        text: format!("{}FIN()\n", case.prefix),
    };
    let mut sink = std::io::sink();
    let summary = interp::run_source(&src, db.clone(), units, false, None, &mut sink)?;
    if let Some(e) = summary.error {
        return Err(e);
    }
    let store = Store::open(&db)?;
    let k = matrix::load_matrix(&store, "RIGIDITE")?;
    let m = matrix::load_matrix(&store, "MASSE")?;
    let shocks = engine_shocks(&case.shocks, &k)?;
    let modes = mode_store::load_modes(&store, "MODES")?;
    let mode1 = modes
        .mode(1)
        .ok_or_else(|| Error::internal("bench: no linear mode"))?;
    let mode = k
        .restrict(&mode1.shape)
        .ok_or_else(|| Error::internal("bench: a mode shorter than its numbering"))?;
    let omega = mode1.omega2.max(0.0).sqrt();
    let problem = Problem {
        forcing: None,
        k: k.reduced()?,
        m: m.reduced()?,
        shocks,
    };
    let mm = &case.mnl;
    let coef_ampl = match mm.coef_ampl {
        Some(c) => c,
        None => {
            // With shocks the start displacement is COEF_AMPL × mode × (largest JEU): the
            // shock node nearest its obstacle starts at 0.8 of its JEU (inside every gap).
            let g = problem.shocks.iter().fold(0.0f64, |a, s| a.max(s.gap));
            let worst = problem
                .shocks
                .iter()
                .map(|s| s.dofs.iter().map(|&d| mode[d].abs()).fold(0.0, f64::max) / s.gap)
                .fold(0.0, f64::max);
            0.8 / (g * worst.max(1e-300))
        }
    };
    let nnz = {
        let mut set = std::collections::BTreeSet::new();
        for a in [&problem.k, &problem.m] {
            let sym = a.symbolic();
            for j in 0..a.ncols() {
                for p in sym.col_ptr()[j]..sym.col_ptr()[j + 1] {
                    set.insert((sym.row_idx()[p], j));
                }
            }
        }
        set.len()
    };
    let settings = Settings {
        harmonics: Harmonics {
            h_lin: mm.h_lin,
            h_nonl: mm.h_nonl,
        },
        continuation: Continuation {
            n_branches: mm.branches,
            n_points_per_branch: mm.points,
            order: mm.order,
            prec_man: mm.prec_man,
            prec_newton: mm.prec_newton,
            iter_newton_max: 15,
            bif_terms: 3,
            bif_tol: 1e-4,
            det_test: mm.det_test,
            direction: if mm.direction >= 0 { 1 } else { -1 },
        },
    };
    let _ = nnm::unknown_count(&problem, &settings);
    Ok(Prepared {
        problem,
        settings,
        mode,
        omega,
        coef_ampl,
        nnz,
    })
}
