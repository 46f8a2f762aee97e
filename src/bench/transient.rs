//! `aster-nl bench --only transient` (issue 38): DYNA_VIBRA's integrator on the bar of
//! `models::beam` with its two CERCLE rings as DIS_CHOC shocks, CPU per simulated period
//! against the model's size, on the physical basis (NEWMARK, sparse M and K on the free
//! DOFs) and on the lowest modes (RUNGE_KUTTA_54), measured in-process.

use super::measure::{exponent, median, self_cpu};
use super::{fmt_s, models, Bench};
use crate::error::{Error, Result};
use crate::linalg::eigen::{self, EigenOptions, ModeRequest};
use crate::transient::{
    contact_pulsations, integrate, AdaptiveOptions, Archive, DenseStructure, Friction, NodeRows,
    ObstacleKind, RkPair, Scheme, Shock, ShockSpec, SparseStructure, Structure, TimeGrid,
    Trajectory,
};
use faer::sparse::SparseColMat;
use std::f64::consts::PI;

/// The rings of `models::beam` (`bar_rings`): JEU, RIGI_NOR, centre offset along DY.
const JEU: f64 = 1e-3;
const RIGI_NOR: f64 = 1e4;
const OFFSET: f64 = 0.3 * JEU;
/// Simulated span, in periods of the first linear mode.
const PERIODS: f64 = 5.0;
/// Modes of the GENE basis.
const MODES: usize = 20;
/// A measurement shorter than this (CPU seconds) is repeated: median of 3.
const CHEAP_S: f64 = 2.0;

/// A ring: CERCLE around ORIG_OBST = (0, 0.3 JEU, 0), NORM_OBST = X (local y, z = global
/// Y, Z), node 1 at the origin (only the position relative to ORIG_OBST matters).
fn ring() -> ShockSpec {
    ShockSpec {
        obstacle: ObstacleKind::Cercle,
        orig_obst: [0.0, OFFSET, 0.0],
        norm_obst: [1.0, 0.0, 0.0],
        angl_vril: None,
        node1: [0.0; 3],
        node2: None,
        jeu: JEU,
        dist1: 0.0,
        dist2: 0.0,
        rigi_nor: RIGI_NOR,
        amor_nor: 0.0,
        rigi_tan: 0.0,
        amor_tan: 0.0,
        friction: Friction::None,
        friction_along_x_only: false,
    }
}

fn shocks_on(rows: &[NodeRows]) -> Result<Vec<Shock>> {
    rows.iter()
        .map(|r| Shock::new(ring(), r.clone(), None).map_err(Error::from))
        .collect()
}

/// Lower-triangle triplets of a symmetric matrix stored with both triangles or one
/// (SparseStructure reads an upper entry as its transpose and sums duplicates).
fn lower(a: &SparseColMat<usize, f64>) -> Vec<(usize, usize, f64)> {
    let sym = a.symbolic();
    let (cp, ri, val) = (sym.col_ptr(), sym.row_idx(), a.val());
    let mut t: Vec<(usize, usize, f64)> = (0..a.ncols())
        .flat_map(|j| (cp[j]..cp[j + 1]).map(move |p| (ri[p], j, val[p])))
        .collect();
    if t.iter().any(|&(i, j, _)| i > j) {
        t.retain(|&(i, j, _)| i >= j);
    }
    t
}

/// y = A x for A given by its lower triangle.
fn sym_mul(lower: &[(usize, usize, f64)], x: &[f64]) -> Vec<f64> {
    let mut y = vec![0.0; x.len()];
    for &(i, j, v) in lower {
        y[i] += v * x[j];
        if i != j {
            y[j] += v * x[i];
        }
    }
    y
}

/// CPU seconds of `run` (the median of 3 when one run is cheap) and its last result.
fn timed<T>(mut run: impl FnMut() -> Result<T>) -> Result<(f64, T)> {
    let mut cpus = Vec::with_capacity(3);
    let mut out = None;
    for k in 0..3 {
        let t0 = self_cpu();
        out = Some(run()?);
        cpus.push(self_cpu() - t0);
        if k == 0 && cpus[0] >= CHEAP_S {
            break;
        }
    }
    let out = out.ok_or_else(|| Error::internal("bench transient: no run"))?;
    Ok((median(&mut cpus), out))
}

/// One integration from `init` with a ring on each of `rows`, every 10th step archived.
fn run(
    structure: &dyn Structure,
    rows: &[NodeRows],
    init: (&[f64], &[f64]),
    scheme: Scheme,
    grid: TimeGrid,
) -> Result<Trajectory> {
    let mut shocks = shocks_on(rows)?;
    let archive = Archive::Every(10);
    Ok(integrate(
        structure,
        &mut shocks,
        &[],
        init,
        scheme,
        grid,
        &archive,
        &mut |_| {},
    )?)
}

/// The rings' (DY, DZ) displacements at the end, and the largest ring amplitude over the
/// last period (archived instants).
fn ring_motion(traj: &Trajectory, rows: &[NodeRows], t_last: f64) -> (Vec<[f64; 3]>, f64) {
    let at = |i: usize| rows.iter().map(move |r| r.apply(traj.q_at(i)));
    let end = traj
        .t
        .len()
        .checked_sub(1)
        .map_or(Vec::new(), |i| at(i).collect());
    let late = (0..traj.t.len())
        .filter(|&i| traj.t[i] >= t_last)
        .flat_map(at)
        .fold(0.0, |m: f64, u| m.max(u[1].hypot(u[2])));
    (end, late)
}

impl Bench<'_> {
    pub(super) fn transient_section(&mut self) -> Result<()> {
        self.say("\n## DYNA_VIBRA: CPU per simulated period against the model's size (the bar with two CERCLE rings)\n")?;
        self.say(&format!(
            "Start: the first linear mode scaled so that the ring nodes' largest displacement is \
             2·JEU, v0 = 0; {PERIODS} periods T1 = 2π/ω1; DIS_CHOC CERCLE, JEU {JEU:e}, RIGI_NOR \
             {RIGI_NOR:e}, centre offset 0.3 JEU along DY. PHYS: NEWMARK on the free DOFs, \
             PAS = min(T1/200, 0.5/ω_c). GENE: the {MODES} lowest modes (mass-normalised), \
             RUNGE_KUTTA_54, TOLERANCE 1e-6. Archive every 10th step. In-process CPU \
             (user + system), median of 3 below {CHEAP_S} s. Accuracy: the rings' largest \
             displacement over the last period, and |u_GENE − u_PHYS| of the rings at the end \
             over 2·JEU.\n"
        ))?;
        self.say("| free DOFs | PHYS: steps (rejected) | PHYS: factorisation | PHYS: CPU per period | GENE: modes CPU | GENE: steps (rejected) | GENE: CPU per period | last period's largest ring displacement, PHYS / GENE | end difference / 2·JEU |")?;
        self.say("|---|---|---|---|---|---|---|---|---|")?;
        let elements: &[usize] = if self.opts.quick {
            &[26, 101]
        } else {
            &[26, 101, 251, 1001, 2501]
        };
        let mut pts: [Vec<(f64, f64)>; 6] = Default::default();
        let mut notes = Vec::new();
        for &el in elements {
            let dir = self.opts.dir.join(format!("transient_{el}"));
            let prep = models::prepare(&models::beam(el, 1, 1, 1), &dir)?;
            let p = &prep.problem;
            let n = p.k.nrows();
            let rings = p
                .shocks
                .iter()
                .map(|s| match s.dofs[..] {
                    [dy, dz] => Ok([dy, dz]),
                    _ => Err(Error::internal("bench transient: a ring without (DY, DZ)")),
                })
                .collect::<Result<Vec<_>>>()?;
            let t1 = 2.0 * PI / prep.omega;
            let grid = |dt: f64| TimeGrid {
                t0: 0.0,
                t_end: PERIODS * t1,
                dt,
            };
            // PHYS.
            let rows: Vec<NodeRows> = rings
                .iter()
                .map(|d| NodeRows::selection([None, Some(d[0]), Some(d[1])]))
                .collect();
            let a0 = rows
                .iter()
                .map(|r| r.apply(&prep.mode))
                .fold(0.0, |m: f64, u| m.max(u[1].hypot(u[2])));
            if !(a0 > 0.0 && a0.is_finite()) {
                return Err(Error::internal(
                    "bench transient: the first mode does not move the rings",
                ));
            }
            let q0: Vec<f64> = prep.mode.iter().map(|x| x * 2.0 * JEU / a0).collect();
            let v0 = vec![0.0; n];
            let (m_low, k_low) = (lower(&p.m), lower(&p.k));
            let structure = SparseStructure::new(n, m_low.clone(), k_low, None)?;
            let wc = contact_pulsations(&structure, &shocks_on(&rows)?)?
                .into_iter()
                .fold(0.0, f64::max);
            let pas = if wc > 0.0 {
                (t1 / 200.0).min(0.5 / wc)
            } else {
                t1 / 200.0
            };
            let (_, h) = grid(pas).fixed_steps();
            let (factor_cpu, _) = timed(|| {
                structure
                    .factor(1.0, 0.5 * h, 0.25 * h * h)
                    .map(|_| ())
                    .map_err(Error::from)
            })?;
            let newmark = Scheme::Newmark {
                beta: 0.25,
                gamma: 0.5,
            };
            let phys = timed(|| run(&structure, &rows, (&q0, &v0), newmark, grid(pas)));
            // GENE.
            let request = ModeRequest::Smallest { n: MODES.min(n) };
            let (modes_cpu, set) =
                timed(|| eigen::solve_modes(&p.k, &p.m, &request, &EigenOptions::default()))?;
            let m = set.vectors.len();
            let grows: Vec<NodeRows> = rings
                .iter()
                .map(|d| {
                    let col = |c: usize| set.vectors.iter().map(|v| v[c]).collect::<Vec<_>>();
                    NodeRows::from_modes(&vec![0.0; m], &col(d[0]), &col(d[1]))
                })
                .collect();
            // The start projected on the M-orthonormal modes: q_j = φ_jᵀ M q0.
            let mq0 = sym_mul(&m_low, &q0);
            let g0: Vec<f64> = set
                .vectors
                .iter()
                .map(|v| v.iter().zip(&mq0).map(|(a, b)| a * b).sum())
                .collect();
            let gv0 = vec![0.0; m];
            let gene_structure = DenseStructure::diagonal(vec![1.0; m], set.omega2.clone(), None)?;
            let mut opts = AdaptiveOptions::new(RkPair::DormandPrince54);
            opts.tolerance = 1e-6;
            // The event-located pair (LOCALISATION_CHOC='OUI') docs/performance.md measured.
            opts.locate_contacts = true;
            let rk54 = Scheme::Adaptive(opts);
            let gene = timed(|| run(&gene_structure, &grows, (&g0, &gv0), rk54, grid(pas)));
            let x = n as f64;
            // A failed run is a note under the table and no point of the fits.
            let mut cells = |tag: &str, run: &Result<(f64, Trajectory)>, k: usize| match run {
                Ok((cpu, traj)) => {
                    pts[k].push((x, traj.steps_taken as f64));
                    pts[k + 1].push((x, cpu / PERIODS));
                    [
                        format!("{} ({})", traj.steps_taken, traj.steps_rejected),
                        fmt_s(cpu / PERIODS),
                    ]
                }
                Err(e) => {
                    notes.push(format!("- {tag}, {n} DOFs: {}", e.message));
                    ["failed".into(), "—".into()]
                }
            };
            let [ps, pc] = cells("PHYS", &phys, 0);
            let [gs, gc] = cells("GENE", &gene, 3);
            pts[2].push((x, factor_cpu));
            pts[5].push((x, modes_cpu));
            let last = (PERIODS - 1.0) * t1;
            let (accuracy, end) = match (&phys, &gene) {
                (Ok((_, pt)), Ok((_, gt))) => {
                    let (pe, pl) = ring_motion(pt, &rows, last);
                    let (ge, gl) = ring_motion(gt, &grows, last);
                    let d = pe.iter().zip(&ge).fold(0.0, |m: f64, (a, b)| {
                        m.max((a[1] - b[1]).hypot(a[2] - b[2]))
                    });
                    (
                        format!(
                            "{:.3} / {:.3} mm ({:+.1} %)",
                            1e3 * pl,
                            1e3 * gl,
                            100.0 * (gl - pl) / pl
                        ),
                        format!("{:.1e}", d / (2.0 * JEU)),
                    )
                }
                _ => ("—".into(), "—".into()),
            };
            self.say(&format!(
                "| {n} | {ps} | {} | {pc} | {} | {gs} | {gc} | {accuracy} | {end} |",
                fmt_s(factor_cpu),
                fmt_s(modes_cpu),
            ))?;
        }
        if !notes.is_empty() {
            self.say(&format!("\n{}", notes.join("\n")))?;
        }
        let e: Vec<String> = pts.iter().map(|p| format!("{:.2}", exponent(p))).collect();
        self.say(&format!(
            "\nfitted exponents against the free DOFs (completed runs): PHYS steps {}, CPU per \
             period {}, factorisation {}; GENE steps {}, CPU per period {}, modes {}",
            e[0], e[1], e[2], e[3], e[4], e[5]
        ))
    }
}
