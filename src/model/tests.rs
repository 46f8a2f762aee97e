//! End-to-end numerical tests of the model chain against closed forms: element matrices
//! -> numbering -> assembly -> reduced matrices -> a small dense generalized eigen solve
//! done here (M^{-1/2} K M^{-1/2} with faer's self-adjoint eigen solver).

use super::*;
use crate::args::Args;
use crate::mesh::select::Selection;
use crate::model::material::MaterialAssignment;
// The model layer takes typed specs. These tests write the keywords a user writes and
// build the specs with the operators' readers, so that the keyword paths of errors are
// checked too.
use crate::mesh::{Cell, CellKind, Group, Mesh, Node};
use crate::ops::affe_char_cine::kinematic_load;
use crate::ops::affe_modele::model as model_of;
use crate::ops::defi_materiau::material;
use crate::value::{Span, Value};
use faer::sparse::SparseColMat;
use faer::{Mat, Side};

// ---------- builders ----------

/// AFFE_CARA_ELEM's reading of `args` on the model `MO`, the call validated as a user's
/// (the catalog's defaults, such as REPERE, filled in).
fn cara_elem(model_name: &str, model: &Model, mesh: &Mesh, args: &Args) -> Result<CaraElem> {
    let mut call = args.clone();
    call.simple.push((
        "MODELE".into(),
        Value::Concept(crate::value::ConceptRef {
            name: model_name.into(),
            ty: "modele_sdaster".into(),
        }),
        Span::default(),
    ));
    let call = crate::catalog::validate_args("AFFE_CARA_ELEM", &call, None, "test.comm")?;
    crate::ops::affe_cara_elem::cara_elem(model_name, model, mesh, &call)
}

pub(crate) fn s(x: &str) -> Value {
    Value::Str(x.to_string())
}
pub(crate) fn r(x: f64) -> Value {
    Value::Real(x)
}
pub(crate) fn seq(v: Vec<Value>) -> Value {
    Value::Seq(v)
}
pub(crate) fn reals(v: &[f64]) -> Value {
    Value::Seq(v.iter().map(|x| Value::Real(*x)).collect())
}
pub(crate) fn fact(path: &str, simple: Vec<(&str, Value)>) -> Args {
    let mut a = Args::new(path);
    for (k, v) in simple {
        a.simple.push((k.to_string(), v, Span::default()));
    }
    a
}
pub(crate) fn with_facts(mut a: Args, key: &str, occ: Vec<Args>) -> Args {
    a.factor.push((key.to_string(), occ, Span::default()));
    a
}

/// n+1 nodes N1.. on the segment p0-p1, SEG2 cells S1..Sn (group LINE), POI1 cells P1..
/// on every node (group PTS, and INNER for the interior ones); node groups LEFT, RIGHT.
pub(crate) fn line_mesh(n: usize, p0: [f64; 3], p1: [f64; 3]) -> Mesh {
    let nodes: Vec<Node> = (0..=n)
        .map(|i| {
            let t = i as f64 / n as f64;
            Node {
                name: format!("N{}", i + 1),
                coords: [
                    p0[0] + t * (p1[0] - p0[0]),
                    p0[1] + t * (p1[1] - p0[1]),
                    p0[2] + t * (p1[2] - p0[2]),
                ],
            }
        })
        .collect();
    let mut cells: Vec<Cell> = (0..n)
        .map(|i| Cell {
            name: format!("S{}", i + 1),
            kind: CellKind::Seg2,
            nodes: vec![i, i + 1],
        })
        .collect();
    cells.extend((0..=n).map(|i| Cell {
        name: format!("P{}", i + 1),
        kind: CellKind::Poi1,
        nodes: vec![i],
    }));
    Mesh {
        dim: 3,
        nodes,
        cells,
        node_groups: vec![
            Group {
                name: "LEFT".into(),
                members: vec![0],
            },
            Group {
                name: "RIGHT".into(),
                members: vec![n],
            },
        ],
        cell_groups: vec![
            Group {
                name: "LINE".into(),
                members: (0..n).collect(),
            },
            Group {
                name: "PTS".into(),
                members: (n..=2 * n).collect(),
            },
            Group {
                name: "INNER".into(),
                members: (n + 1..2 * n).collect(),
            },
        ],
    }
}

/// Generalized eigenvalues of (K, M), ascending, M symmetric positive definite.
pub(crate) fn gen_eig(k: &SparseColMat<usize, f64>, m: &SparseColMat<usize, f64>) -> Vec<f64> {
    let (kd, md) = (k.to_dense(), m.to_dense());
    let n = kd.nrows();
    let evd = md.self_adjoint_eigen(Side::Lower).unwrap();
    let (u, d) = (evd.U(), evd.S().column_vector());
    assert!(d[0] > 0.0, "mass matrix not positive definite");
    let w = Mat::from_fn(n, n, |i, j| {
        (0..n)
            .map(|p| u[(i, p)] * u[(j, p)] / d[p].sqrt())
            .sum::<f64>()
    });
    let a = &w * &kd * &w;
    let a = Mat::from_fn(n, n, |i, j| 0.5 * (a[(i, j)] + a[(j, i)]));
    a.self_adjoint_eigenvalues(Side::Lower).unwrap()
}

fn omegas(k: &AssembledMatrix, m: &AssembledMatrix) -> Vec<f64> {
    gen_eig(&k.reduced().unwrap(), &m.reduced().unwrap())
        .into_iter()
        .map(|l| l.max(0.0).sqrt())
        .collect()
}

struct Built {
    mesh: Mesh,
    model: Model,
    field: Option<MaterialField>,
    cara: CaraElem,
}

fn build(
    mesh: Mesh,
    affe: Vec<Args>,
    cara_args: Args,
    mat: Option<(f64, f64, f64)>,
) -> Result<Built> {
    let model = model_of("MA", &mesh, &affe)?;
    let field = mat.map(|(e, nu, rho)| {
        let m = material(&with_facts(
            fact("DEFI_MATERIAU", vec![]),
            "ELAS",
            vec![fact(
                "DEFI_MATERIAU/ELAS",
                vec![("E", r(e)), ("NU", r(nu)), ("RHO", r(rho))],
            )],
        ))
        .unwrap();
        MaterialField::build(
            "MA",
            &mesh,
            &[MaterialAssignment {
                on: Selection {
                    all: true,
                    ..Selection::default()
                },
                name: "STEEL".into(),
                material: m,
            }],
        )
        .unwrap()
    });
    let cara = cara_elem("MO", &model, &mesh, &cara_args)?;
    Ok(Built {
        mesh,
        model,
        field,
        cara,
    })
}
use crate::error::Result;

/// K and M assembled with the given kinematic loads (CINE eliminated at assembly, MECA
/// through the element matrices and the numbering).
fn assemble_km(
    b: &Built,
    cine: &[KinematicLoad],
    meca: &[KinematicLoad],
) -> Result<(AssembledMatrix, AssembledMatrix)> {
    let inp = ElemInputs {
        model_name: "MO",
        model: &b.model,
        mesh: &b.mesh,
        field: b.field.as_ref(),
        cara: Some(&b.cara),
    };
    let loads: Vec<(String, KinematicLoad)> = meca
        .iter()
        .enumerate()
        .map(|(i, l)| (format!("CH{i}"), l.clone()))
        .collect();
    let ke = compute_elem_matrices(MatrixKind::RigiMeca, &inp, loads.clone())?;
    let me = compute_elem_matrices(MatrixKind::MassMeca, &inp, loads)?;
    let num = DofNumbering::from_elem_matrices(&b.mesh, &[&ke])?;
    let cine: Vec<&KinematicLoad> = cine.iter().collect();
    Ok((
        assemble(&num, &b.mesh, &[&ke], &cine)?,
        assemble(&num, &b.mesh, &[&me], &cine)?,
    ))
}

fn load(b: &Built, kind: LoadKind, occ: Vec<Vec<(&str, Value)>>) -> Result<KinematicLoad> {
    let occ: Vec<Args> = occ
        .into_iter()
        .map(|o| fact("AFFE_CHAR/DDL_IMPO", o))
        .collect();
    kinematic_load(kind, "MO", &b.model, &b.mesh, &occ)
}

fn dis_t_all() -> Vec<Args> {
    vec![fact(
        "AFFE_MODELE/AFFE",
        vec![
            ("TOUT", s("OUI")),
            ("PHENOMENE", s("MECANIQUE")),
            ("MODELISATION", s("DIS_T")),
        ],
    )]
}

/// Chain of n masses m joined by springs k: n+1 springs (fixed-fixed) or n (fixed-free).
fn chain(
    n: usize,
    k: f64,
    m: f64,
    fixed_free: bool,
    kind: LoadKind,
) -> (AssembledMatrix, AssembledMatrix) {
    let nseg = if fixed_free { n } else { n + 1 };
    let mesh = line_mesh(nseg, [0.0; 3], [nseg as f64, 0.0, 0.0]);
    // masses on interior nodes (and on the free end for fixed-free)
    let mass_group = if fixed_free { "MASSES_FF" } else { "INNER" };
    let mut mesh = mesh;
    mesh.cell_groups.push(Group {
        name: "MASSES_FF".into(),
        members: (nseg + 1..=2 * nseg).collect(),
    });
    let cara = with_facts(
        fact("AFFE_CARA_ELEM", vec![]),
        "DISCRET",
        vec![
            fact(
                "AFFE_CARA_ELEM/DISCRET",
                vec![
                    ("GROUP_MA", s("LINE")),
                    ("CARA", s("K_T_D_L")),
                    ("VALE", reals(&[k, 0.0, 0.0])),
                ],
            ),
            fact(
                "AFFE_CARA_ELEM/DISCRET",
                vec![
                    ("GROUP_MA", s("PTS")),
                    ("CARA", s("K_T_D_N")),
                    ("VALE", reals(&[0.0, 0.0, 0.0])),
                ],
            ),
            fact(
                "AFFE_CARA_ELEM/DISCRET",
                vec![
                    ("GROUP_MA", s(mass_group)),
                    ("CARA", s("M_T_D_N")),
                    ("VALE", reals(&[m])),
                ],
            ),
        ],
    );
    let b = build(mesh, dis_t_all(), cara, None).unwrap();
    let mut occ = vec![
        vec![("TOUT", s("OUI")), ("DY", r(0.0)), ("DZ", r(0.0))],
        vec![("GROUP_NO", s("LEFT")), ("DX", r(0.0))],
    ];
    if !fixed_free {
        occ.push(vec![("GROUP_NO", s("RIGHT")), ("DX", r(0.0))]);
    }
    let l = load(&b, kind, occ).unwrap();
    match kind {
        LoadKind::Cine => assemble_km(&b, &[l], &[]).unwrap(),
        LoadKind::Meca => assemble_km(&b, &[], &[l]).unwrap(),
    }
}

// ---------- discrete chains ----------

#[test]
fn spring_chain_fixed_fixed_matches_closed_form() {
    let (n, k, m) = (6, 10.0, 2.0);
    let (kk, mm) = chain(n, k, m, false, LoadKind::Cine);
    assert_eq!(kk.free_dofs().len(), n);
    let w = omegas(&kk, &mm);
    for (j, wj) in w.iter().enumerate() {
        let jj = (j + 1) as f64;
        let exact =
            2.0 * (k / m).sqrt() * (jj * std::f64::consts::PI / (2.0 * (n as f64 + 1.0))).sin();
        // The discrete chain is exactly this system: only round-off separates them.
        assert!(
            (wj - exact).abs() < 1e-10 * exact,
            "mode {}: {wj} vs {exact}",
            j + 1
        );
    }
}

#[test]
fn spring_chain_fixed_free_matches_closed_form() {
    let (n, k, m) = (5, 3.0, 0.5);
    let (kk, mm) = chain(n, k, m, true, LoadKind::Meca);
    let w = omegas(&kk, &mm);
    assert_eq!(w.len(), n);
    for (j, wj) in w.iter().enumerate() {
        let jj = (j + 1) as f64;
        let exact = 2.0
            * (k / m).sqrt()
            * ((2.0 * jj - 1.0) * std::f64::consts::PI / (2.0 * (2.0 * n as f64 + 1.0))).sin();
        assert!(
            (wj - exact).abs() < 1e-10 * exact,
            "mode {}: {wj} vs {exact}",
            j + 1
        );
    }
}

#[test]
fn char_cine_and_char_meca_give_identical_reduced_matrices() {
    let (kc, mc) = chain(4, 7.0, 1.5, false, LoadKind::Cine);
    let (km, mm) = chain(4, 7.0, 1.5, false, LoadKind::Meca);
    assert_eq!(kc.eliminated, km.eliminated);
    // CINE: eliminated by the assembly only; MECA: already in the numbering.
    assert!(kc.numbering.eliminated.iter().all(|e| !e));
    assert!(km.numbering.eliminated.iter().any(|e| *e));
    for (a, b) in [(&kc, &km), (&mc, &mm)] {
        let (ra, rb) = (
            a.reduced().unwrap().to_dense(),
            b.reduced().unwrap().to_dense(),
        );
        assert_eq!(ra, rb);
        assert_eq!(a.free_dofs(), b.free_dofs());
    }
}

#[test]
fn numbering_is_node_then_component_order() {
    let (kk, _) = chain(2, 1.0, 1.0, false, LoadKind::Cine);
    let names: Vec<String> = kk
        .numbering
        .dofs
        .iter()
        .take(4)
        .map(|d| format!("{}:{}", d.node, d.cmp))
        .collect();
    assert_eq!(names, ["N1:DX", "N1:DY", "N1:DZ", "N2:DX"]);
    assert_eq!(kk.size(), 4 * 3);
    // free: the DX of the 2 interior nodes
    let free: Vec<String> = kk
        .free_dofs()
        .iter()
        .map(|&i| format!("{}:{}", kk.numbering.dofs[i].node, kk.numbering.dofs[i].cmp))
        .collect();
    assert_eq!(free, ["N2:DX", "N3:DX"]);
    let full = kk.expand(&[1.5, -2.0]).unwrap();
    assert_eq!(full.len(), 12);
    assert_eq!((full[3], full[6]), (1.5, -2.0));
    assert_eq!(full.iter().filter(|v| **v != 0.0).count(), 2);
    assert!(kk.expand(&[1.0]).is_err());
    // Full index -> reduced index, and back through restrict: N2:DX (full 3) is reduced 0,
    // N3:DX (full 6) reduced 1; the blocked N1:DX (full 0) and an index past the numbering
    // have none.
    assert_eq!(kk.reduced_index(3), Some(0));
    assert_eq!(kk.reduced_index(6), Some(1));
    assert_eq!(kk.reduced_index(0), None);
    assert_eq!(kk.reduced_index(12), None);
    assert_eq!(kk.restrict(&full), Some(vec![1.5, -2.0]));
    assert_eq!(kk.restrict(&full[..5]), None);
}

// ---------- beams ----------

const E: f64 = 2.1e11;
const RHO: f64 = 7800.0;
const RAD: f64 = 0.02;

fn beam(n: usize, dir: [f64; 3], len: f64) -> Built {
    let p1 = [dir[0] * len, dir[1] * len, dir[2] * len];
    let mesh = line_mesh(n, [0.0; 3], p1);
    let affe = vec![fact(
        "AFFE_MODELE/AFFE",
        vec![
            ("GROUP_MA", s("LINE")),
            ("PHENOMENE", s("MECANIQUE")),
            ("MODELISATION", s("POU_D_E")),
        ],
    )];
    let cara = with_facts(
        fact("AFFE_CARA_ELEM", vec![]),
        "POUTRE",
        vec![fact(
            "AFFE_CARA_ELEM/POUTRE",
            vec![
                ("GROUP_MA", s("LINE")),
                ("SECTION", s("CERCLE")),
                ("CARA", seq(vec![s("R")])),
                ("VALE", reals(&[RAD])),
            ],
        )],
    );
    build(mesh, affe, cara, Some((E, 0.3, RHO))).unwrap()
}

/// √(EI/(ρ A L⁴)) of the test beam.
fn beam_scale(len: f64) -> f64 {
    let pi = std::f64::consts::PI;
    let a = pi * RAD * RAD;
    let i = pi / 4.0 * RAD.powi(4);
    (E * i / (RHO * a * len.powi(4))).sqrt()
}

/// Planar bending in xy (v, θz) of a beam along X: everything else blocked.
fn planar(b: &Built, ends: Vec<Vec<(&str, Value)>>) -> Vec<f64> {
    let mut occ = vec![vec![
        ("TOUT", s("OUI")),
        ("DX", r(0.0)),
        ("DZ", r(0.0)),
        ("DRX", r(0.0)),
        ("DRY", r(0.0)),
    ]];
    occ.extend(ends);
    let l = load(b, LoadKind::Cine, occ).unwrap();
    let (k, m) = assemble_km(b, &[l], &[]).unwrap();
    omegas(&k, &m)
}

const CANTILEVER_BL: [f64; 5] = [
    1.875104068711961,
    4.694091132974175,
    7.854757438237613,
    10.995540734875467,
    14.13716839104647,
];

fn cantilever_errors(n: usize) -> Vec<f64> {
    let len = 2.0;
    let b = beam(n, [1.0, 0.0, 0.0], len);
    let w = planar(
        &b,
        vec![vec![
            ("GROUP_NO", s("LEFT")),
            ("DY", r(0.0)),
            ("DRZ", r(0.0)),
        ]],
    );
    CANTILEVER_BL
        .iter()
        .zip(&w)
        .map(|(bl, wj)| {
            let exact = bl * bl * beam_scale(len);
            (wj - exact) / exact
        })
        .collect()
}

#[test]
fn cantilever_beam_converges_like_h4() {
    let e8 = cantilever_errors(8);
    let e16 = cantilever_errors(16);
    for j in 0..5 {
        // The consistent-mass Hermite beam bounds frequencies from above.
        assert!(
            e16[j] > 0.0 && e8[j] > e16[j],
            "mode {}: {} {}",
            j + 1,
            e8[j],
            e16[j]
        );
    }
    // Measured with 16 elements: mode 1 within 1.3e-7, mode 5 within 4.1e-4; halving h
    // divides the errors by 15.9, 15.7, 15.3 for modes 1-3 (h⁴, the asymptotic 16 being
    // approached from below as h j / L shrinks): assert a ratio in ]14, 17[.
    assert!(e16[0] < 2e-7 && e16[4] < 5e-4, "{e16:?}");
    for j in 0..3 {
        let ratio = e8[j] / e16[j];
        assert!(
            ratio > 14.0 && ratio < 17.0,
            "mode {}: ratio {ratio}",
            j + 1
        );
    }
}

#[test]
fn simply_supported_beam_matches_j_pi_squared() {
    let len = 3.0;
    let errs = |n: usize| -> Vec<f64> {
        let b = beam(n, [1.0, 0.0, 0.0], len);
        let w = planar(
            &b,
            vec![
                vec![("GROUP_NO", s("LEFT")), ("DY", r(0.0))],
                vec![("GROUP_NO", s("RIGHT")), ("DY", r(0.0))],
            ],
        );
        (1..=4)
            .map(|j| {
                let exact = (j as f64 * std::f64::consts::PI).powi(2) * beam_scale(len);
                (w[j - 1] - exact) / exact
            })
            .collect()
    };
    let (e10, e20) = (errs(10), errs(20));
    for j in 0..4 {
        // Measured: e ≈ 0.068 (j h / L)⁴ (4.2e-7 for mode 1 with 20 elements, 1.1e-4
        // for mode 4): the error follows (j h)⁴; bound it by 5e-7 j⁴ at 20 elements.
        let jj = (j + 1) as f64;
        assert!(
            e20[j] > 0.0 && e20[j] < 5e-7 * jj.powi(4),
            "mode {}: {}",
            j + 1,
            e20[j]
        );
        let ratio = e10[j] / e20[j];
        assert!(
            ratio > 14.0 && ratio < 17.0,
            "mode {}: ratio {ratio}",
            j + 1
        );
    }
}

/// All DOFs free except a clamped end: the spectrum must not depend on the beam direction.
fn clamped_spectrum(dir: [f64; 3]) -> Vec<f64> {
    let b = beam(6, dir, 2.0);
    let l = load(
        &b,
        LoadKind::Meca,
        vec![vec![("GROUP_NO", s("LEFT")), ("LIAISON", s("ENCASTRE"))]],
    )
    .unwrap();
    let (k, m) = assemble_km(&b, &[], &[l]).unwrap();
    omegas(&k, &m)
}

#[test]
fn beam_spectrum_is_invariant_under_rotation() {
    let a = clamped_spectrum([1.0, 0.0, 0.0]);
    let c = 1.0 / 3f64.sqrt();
    let b = clamped_spectrum([c, c, c]);
    let v = clamped_spectrum([0.0, 0.0, 1.0]);
    assert_eq!(a.len(), 36);
    for j in 0..a.len() {
        // Round-off of the rotations, relative to the largest frequency of the spectrum.
        let tol = 1e-9 * a[a.len() - 1];
        assert!(
            (a[j] - b[j]).abs() < tol && (a[j] - v[j]).abs() < tol,
            "mode {j}: {} {} {}",
            a[j],
            b[j],
            v[j]
        );
    }
    // Circular section: bending modes come in equal pairs; first pair = cantilever mode 1.
    let exact = CANTILEVER_BL[0].powi(2) * beam_scale(2.0);
    assert!((a[0] - exact).abs() < 1e-5 * exact && (a[1] - exact).abs() < 1e-5 * exact);
}

#[test]
fn free_free_beam_has_six_rigid_body_modes() {
    let len = 2.0;
    let d = 0.5f64.sqrt();
    let b = beam(10, [0.3 / d, -0.4 / d, 0.5 / d], len);
    let (k, m) = assemble_km(&b, &[], &[]).unwrap();
    let lam = gen_eig(&k.reduced().unwrap(), &m.reduced().unwrap());
    // First elastic mode: free-free βL = 4.730040745, a double pair for a circle.
    let w7 = 4.730040744862704f64.powi(2) * beam_scale(len);
    for l in &lam[..6] {
        // Rigid modes are zero up to round-off of the stiffness (~1e-12 of its largest
        // eigenvalue relative to the first elastic one here).
        assert!(l.abs() < 1e-6 * w7 * w7, "rigid eigenvalue {l}");
    }
    assert!(
        (lam[6].sqrt() - w7).abs() < 1e-4 * w7,
        "{} vs {w7}",
        lam[6].sqrt()
    );
}

#[test]
fn bar_axial_modes_fixed_free() {
    // BARRE chain along Y, fixed at the bottom: ω_j = (2j−1)π/(2L) √(E/ρ), transverse
    // DOFs blocked (a bar has no bending stiffness). Consistent mass: error ~ h².
    let errs = |n: usize| {
        let len = 5.0;
        let mesh = line_mesh(n, [0.0; 3], [0.0, len, 0.0]);
        let affe = vec![fact(
            "AFFE_MODELE/AFFE",
            vec![
                ("GROUP_MA", s("LINE")),
                ("PHENOMENE", s("MECANIQUE")),
                ("MODELISATION", s("BARRE")),
            ],
        )];
        let cara = with_facts(
            fact("AFFE_CARA_ELEM", vec![]),
            "BARRE",
            vec![fact(
                "AFFE_CARA_ELEM/BARRE",
                vec![
                    ("GROUP_MA", s("LINE")),
                    ("SECTION", s("GENERALE")),
                    ("CARA", s("A")),
                    ("VALE", r(1e-3)),
                ],
            )],
        );
        let b = build(mesh, affe, cara, Some((E, 0.3, RHO))).unwrap();
        let l = load(
            &b,
            LoadKind::Cine,
            vec![
                vec![("TOUT", s("OUI")), ("DX", r(0.0)), ("DZ", r(0.0))],
                vec![("GROUP_NO", s("LEFT")), ("DY", r(0.0))],
            ],
        )
        .unwrap();
        let (k, m) = assemble_km(&b, &[l], &[]).unwrap();
        let w = omegas(&k, &m);
        let exact = std::f64::consts::PI / (2.0 * len) * (E / RHO).sqrt();
        (w[0] - exact) / exact
    };
    let (e10, e20) = (errs(10), errs(20));
    assert!(e10 > 0.0 && e20 > 0.0 && e20 < 1e-3, "{e10} {e20}");
    let ratio = e10 / e20;
    assert!(ratio > 3.8 && ratio < 4.2, "ratio {ratio}");
}

// ---------- errors ----------

fn cara_err(cara: Args) -> String {
    let mesh = line_mesh(2, [0.0; 3], [2.0, 0.0, 0.0]);
    match build(mesh, dis_t_all(), cara, None) {
        Ok(_) => panic!("expected an error"),
        Err(e) => e.to_string(),
    }
}

fn discret(v: Vec<Vec<(&str, Value)>>) -> Args {
    with_facts(
        fact("AFFE_CARA_ELEM", vec![]),
        "DISCRET",
        v.into_iter()
            .map(|o| fact("AFFE_CARA_ELEM/DISCRET", o))
            .collect(),
    )
}

#[test]
fn wrong_cell_kind_for_cara_is_refused() {
    let e = cara_err(discret(vec![vec![
        ("GROUP_MA", s("PTS")),
        ("CARA", s("K_T_D_L")),
        ("VALE", reals(&[1.0, 1.0, 1.0])),
    ]]));
    assert!(
        e.contains("K_T_D_L is for SEG2 cells but cell P1 is a POI1"),
        "{e}"
    );
}

#[test]
fn wrong_value_count_is_refused() {
    let e = cara_err(discret(vec![vec![
        ("GROUP_MA", s("LINE")),
        ("CARA", s("K_T_D_L")),
        ("VALE", reals(&[1.0, 1.0])),
    ]]));
    // The keyword path (from the spec) says VALE; the model says what is wrong.
    assert!(
        e.contains(
            "AFFE_CARA_ELEM/DISCRET/VALE: K_T_D_L on a DIS_T element expects 3 values, got 2"
        ),
        "{e}"
    );
}

#[test]
fn discrete_without_characteristic_names_the_group() {
    let e = cara_err(discret(vec![vec![
        ("GROUP_MA", s("LINE")),
        ("CARA", s("K_T_D_L")),
        ("VALE", reals(&[1.0, 1.0, 1.0])),
    ]]));
    assert!(
        e.contains("without stiffness, mass nor damping: cells P1, P2, P3 (GROUP_MA INNER, PTS)"),
        "{e}"
    );
}

#[test]
fn unknown_group_is_refused() {
    let e = cara_err(discret(vec![vec![
        ("GROUP_MA", s("NOPE")),
        ("CARA", s("K_T_D_N")),
        ("VALE", reals(&[1.0, 1.0, 1.0])),
    ]]));
    assert!(e.contains("GROUP_MA 'NOPE' is not in the mesh"), "{e}");
}

#[test]
fn beam_without_material_or_rho_is_refused() {
    let mut b = beam(2, [1.0, 0.0, 0.0], 1.0);
    b.field = None;
    let e = assemble_km(&b, &[], &[]).unwrap_err().to_string();
    assert!(
        e.contains("no material with ELAS on cells S1, S2 (GROUP_MA LINE)"),
        "{e}"
    );
    let mut b = beam(2, [1.0, 0.0, 0.0], 1.0);
    if let Some(f) = b.field.as_mut() {
        for m in f.materials.values_mut() {
            if let Some(el) = m.elas.as_mut() {
                el.rho = None;
            }
        }
    }
    let e = assemble_km(&b, &[], &[]).unwrap_err().to_string();
    assert!(e.contains("MASS_MECA needs the density RHO"), "{e}");
}

#[test]
fn blocking_a_missing_component_is_refused() {
    let (kk, _) = chain(2, 1.0, 1.0, false, LoadKind::Cine);
    let _ = kk;
    let mesh = line_mesh(2, [0.0; 3], [2.0, 0.0, 0.0]);
    let cara = discret(vec![
        vec![
            ("GROUP_MA", s("LINE")),
            ("CARA", s("K_T_D_L")),
            ("VALE", reals(&[1.0, 1.0, 1.0])),
        ],
        vec![
            ("GROUP_MA", s("PTS")),
            ("CARA", s("M_T_D_N")),
            ("VALE", reals(&[1.0])),
        ],
    ]);
    let b = build(mesh, dis_t_all(), cara, None).unwrap();
    let e = load(
        &b,
        LoadKind::Meca,
        vec![vec![("NOEUD", seq(vec![s("N2")])), ("DRX", r(0.0))]],
    )
    .unwrap_err()
    .to_string();
    assert!(e.contains("component DRX does not exist on node N2"), "{e}");
}

// ---------- 2D and rotational discrete elements ----------

#[test]
fn two_d_chain_with_discret_2d() {
    // 2D_DIS_T: 3 masses between 4 springs along X (fixed-fixed), DY blocked everywhere.
    let (n, k, m) = (3, 4.0, 0.25);
    let mesh = line_mesh(n + 1, [0.0; 3], [4.0, 0.0, 0.0]);
    let affe = vec![fact(
        "AFFE_MODELE/AFFE",
        vec![
            ("TOUT", s("OUI")),
            ("PHENOMENE", s("MECANIQUE")),
            ("MODELISATION", s("2D_DIS_T")),
        ],
    )];
    let d = |g: &str, cara: &str, v: &[f64]| {
        fact(
            "AFFE_CARA_ELEM/DISCRET_2D",
            vec![("GROUP_MA", s(g)), ("CARA", s(cara)), ("VALE", reals(v))],
        )
    };
    let cara = with_facts(
        fact("AFFE_CARA_ELEM", vec![]),
        "DISCRET_2D",
        vec![d("LINE", "K_T_D_L", &[k, 0.0]), d("PTS", "M_T_D_N", &[m])],
    );
    let b = build(mesh, affe, cara, None).unwrap();
    let l = load(
        &b,
        LoadKind::Cine,
        vec![
            vec![("TOUT", s("OUI")), ("DY", r(0.0))],
            vec![("GROUP_NO", s("LEFT")), ("DX", r(0.0))],
            vec![("GROUP_NO", s("RIGHT")), ("DX", r(0.0))],
        ],
    )
    .unwrap();
    let (kk, mm) = assemble_km(&b, &[l], &[]).unwrap();
    assert_eq!(kk.size(), 2 * (n + 2));
    let w = omegas(&kk, &mm);
    for (j, wj) in w.iter().enumerate() {
        let exact = 2.0
            * (k / m).sqrt()
            * (((j + 1) as f64) * std::f64::consts::PI / (2.0 * (n as f64 + 1.0))).sin();
        assert!(
            (wj - exact).abs() < 1e-10 * exact,
            "mode {}: {wj} vs {exact}",
            j + 1
        );
    }
    // The second node's DX is the first free DOF.
    assert_eq!(kk.reduced_index_of("N2", Cmp::Dx), Some(0));
    assert_eq!(kk.reduced_index_of("N1", Cmp::Dx), None);
}

#[test]
fn dis_tr_torsion_oscillator_with_offset_mass() {
    // One node N2 tied to clamped N1 by K_TR_D_L; a point mass m at CDG (0, 0, h) on N2
    // plus Ixx at the CDG. Only DY and DRX free: the 2×2 problem
    // K = diag(ky, krx), M = [[m, −m h], [−m h, Ixx + m h²]] has the eigenvalues below.
    let (ky, krx, m, h, ixx) = (50.0, 7.0, 2.0, 0.3, 0.1);
    let mesh = line_mesh(1, [0.0; 3], [1.0, 0.0, 0.0]);
    let affe = vec![fact(
        "AFFE_MODELE/AFFE",
        vec![
            ("TOUT", s("OUI")),
            ("PHENOMENE", s("MECANIQUE")),
            ("MODELISATION", s("DIS_TR")),
        ],
    )];
    let mut g = mesh.clone();
    g.cell_groups.push(Group {
        name: "TIP".into(),
        members: vec![2],
    });
    let d = |gr: &str, cara: &str, v: &[f64]| {
        fact(
            "AFFE_CARA_ELEM/DISCRET",
            vec![("GROUP_MA", s(gr)), ("CARA", s(cara)), ("VALE", reals(v))],
        )
    };
    let cara = with_facts(
        fact("AFFE_CARA_ELEM", vec![]),
        "DISCRET",
        vec![
            d("LINE", "K_TR_D_L", &[1.0, ky, 1.0, krx, 1.0, 1.0]),
            d("PTS", "K_TR_D_N", &[0.0; 6]),
            d(
                "TIP",
                "M_TR_D_N",
                &[m, 0.0, 0.0, h, ixx, 1.0, 1.0, 0.0, 0.0, 0.0],
            ),
            d("LINE", "M_TR_D_L", &[1.0, 1.0, 1.0, 1.0]),
        ],
    );
    // M_TR_D_L is not supported: the catalog refuses it (not in CARA's `into`), naming
    // the keyword.
    let e = build(g.clone(), affe.clone(), cara, None)
        .err()
        .unwrap()
        .to_string();
    assert!(
        e.contains("AFFE_CARA_ELEM/DISCRET/CARA") && e.contains("got 'M_TR_D_L'"),
        "{e}"
    );
    let cara = with_facts(
        fact("AFFE_CARA_ELEM", vec![]),
        "DISCRET",
        vec![
            d("LINE", "K_TR_D_L", &[1.0, ky, 1.0, krx, 1.0, 1.0]),
            d("PTS", "K_TR_D_N", &[0.0; 6]),
            d(
                "TIP",
                "M_TR_D_N",
                &[m, 0.0, 0.0, h, ixx, 1.0, 1.0, 0.0, 0.0, 0.0],
            ),
        ],
    );
    let b = build(g, affe, cara, None).unwrap();
    let l = load(
        &b,
        LoadKind::Meca,
        vec![
            vec![("GROUP_NO", s("LEFT")), ("LIAISON", s("ENCASTRE"))],
            vec![
                ("GROUP_NO", s("RIGHT")),
                ("DX", r(0.0)),
                ("DZ", r(0.0)),
                ("DRY", r(0.0)),
                ("DRZ", r(0.0)),
            ],
        ],
    )
    .unwrap();
    let (kk, mm) = assemble_km(&b, &[], &[l]).unwrap();
    let lam = gen_eig(&kk.reduced().unwrap(), &mm.reduced().unwrap());
    // det(K − λM) = 0: a λ² + b λ + c with a = m Ixx (m² h² cancels), b = −(ky (Ixx + m h²)
    // + krx m), c = ky krx.
    let a = m * ixx;
    let bq = -(ky * (ixx + m * h * h) + krx * m);
    let c = ky * krx;
    let disc = (bq * bq - 4.0 * a * c).sqrt();
    let exact = [(-bq - disc) / (2.0 * a), (-bq + disc) / (2.0 * a)];
    assert_eq!(lam.len(), 2);
    for j in 0..2 {
        assert!(
            (lam[j] - exact[j]).abs() < 1e-10 * exact[j],
            "{lam:?} vs {exact:?}"
        );
    }
}

#[test]
fn numbering_from_model_and_loads_equals_numbering_from_matrices() {
    let (km, _) = chain(3, 2.0, 1.0, false, LoadKind::Meca);
    // Rebuild the same chain's model-side numbering directly.
    let mesh = line_mesh(4, [0.0; 3], [4.0, 0.0, 0.0]);
    let model = model_of("MA", &mesh, &dis_t_all()).unwrap();
    let occ: Vec<Args> = vec![
        fact(
            "X",
            vec![("TOUT", s("OUI")), ("DY", r(0.0)), ("DZ", r(0.0))],
        ),
        fact("X", vec![("GROUP_NO", s("LEFT")), ("DX", r(0.0))]),
        fact("X", vec![("GROUP_NO", s("RIGHT")), ("DX", r(0.0))]),
    ];
    let l = kinematic_load(LoadKind::Meca, "MO", &model, &mesh, &occ).unwrap();
    let num = DofNumbering::from_model("MO", &model, &mesh, &[&l]).unwrap();
    assert_eq!(num.dofs, km.numbering.dofs);
    assert_eq!(num.eliminated, km.numbering.eliminated);
}

#[test]
fn tout_skips_nodes_and_components_not_carried() {
    // DIS_TR on the segments, DIS_T on an extra POI1 (on an orphan node N9 too): TOUT with
    // DRX blocks DRX where it exists, skips the translation-only node; a component carried
    // nowhere is still an error.
    let mut mesh = line_mesh(2, [0.0; 3], [2.0, 0.0, 0.0]);
    mesh.nodes.push(Node {
        name: "N9".into(),
        coords: [5.0, 5.0, 5.0],
    });
    mesh.nodes.push(Node {
        name: "N10".into(),
        coords: [6.0, 5.0, 5.0],
    });
    mesh.cells.push(Cell {
        name: "PX".into(),
        kind: CellKind::Poi1,
        nodes: vec![4],
    });
    mesh.cell_groups.push(Group {
        name: "PX".into(),
        members: vec![mesh.cells.len() - 1],
    });
    let affe = vec![
        fact(
            "AFFE_MODELE/AFFE",
            vec![
                ("GROUP_MA", s("LINE")),
                ("PHENOMENE", s("MECANIQUE")),
                ("MODELISATION", s("DIS_TR")),
            ],
        ),
        fact(
            "AFFE_MODELE/AFFE",
            vec![
                ("GROUP_MA", s("PX")),
                ("PHENOMENE", s("MECANIQUE")),
                ("MODELISATION", s("DIS_T")),
            ],
        ),
    ];
    let model = model_of("MA", &mesh, &affe).unwrap();
    let occ = vec![fact("X", vec![("TOUT", s("OUI")), ("DRX", r(0.0))])];
    let l = kinematic_load(LoadKind::Cine, "MO", &model, &mesh, &occ).unwrap();
    let nodes: Vec<&str> = l.blocked.iter().map(|b| b.node.as_str()).collect();
    assert_eq!(nodes, ["N1", "N2", "N3"]);
    // Explicitly naming the translation-only node is an error.
    let occ = vec![fact("X", vec![("NOEUD", s("N10")), ("DRX", r(0.0))])];
    let e = kinematic_load(LoadKind::Cine, "MO", &model, &mesh, &occ).unwrap_err();
    assert!(
        e.message
            .contains("component DRX does not exist on node N10"),
        "{e}"
    );
    let only_t = model_of("MA", &mesh, &dis_t_all()).unwrap();
    let occ = vec![fact("X", vec![("TOUT", s("OUI")), ("DRZ", r(0.0))])];
    let e = kinematic_load(LoadKind::Cine, "MO", &only_t, &mesh, &occ).unwrap_err();
    assert!(e.message.contains("component DRZ exists on none"), "{e}");
}
