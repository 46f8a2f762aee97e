//! The studied systems, their energy ranges and the grids of settings.

use super::measure::Config;
use crate::nnm::exact::Oscillator;
use crate::nnm::{Problem, Shock, ShockLaw};
use faer::sparse::{SparseColMat, Triplet};

/// sdnd122: m = 1, k = 10, PLAN stop at JEU = 0.01 with RIGI_NOR = 50.
pub const WALL: Oscillator = Oscillator {
    m: 1.0,
    k: 10.0,
    g: 0.01,
    alpha: 50.0,
};

/// The energy range is [LOW·E_c, HIGH·E_c], E_c the energy at which the orbit first touches
/// the stop: from just past grazing (where the frequency starts to rise) to well into the
/// stiffened regime (the sdnd122 test energy 6.5e-3 = 13 E_c lies inside for the wall).
pub const LOW: f64 = 1.2;
pub const HIGH: f64 = 20.0;

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CaseKind {
    Wall,
    Chain2,
}

impl CaseKind {
    pub fn name(self) -> &'static str {
        match self {
            CaseKind::Wall => "wall",
            CaseKind::Chain2 => "chain2",
        }
    }
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum GridSize {
    Small,
    Full,
}

/// A system, its starting linear mode and the energy range over which it is measured.
#[derive(Clone, Debug)]
pub struct StudyCase {
    pub kind: CaseKind,
    /// Stiffness, mass and the stop; the stop's PARA_REGUL is set per measurement.
    pub problem: Problem,
    /// Lowest linear mode, largest component 1, and its pulsation (rad/s).
    pub mode: Vec<f64>,
    pub omega: f64,
    /// Energy of first contact (J).
    pub contact_energy: f64,
}

impl StudyCase {
    pub fn new(kind: CaseKind) -> StudyCase {
        match kind {
            CaseKind::Wall => StudyCase {
                kind,
                problem: Problem {
                    k: sparse(1, &[(0, 0, WALL.k)]),
                    m: sparse(1, &[(0, 0, WALL.m)]),
                    shocks: vec![stop(ShockLaw::Plan, 0)],
                },
                mode: vec![1.0],
                omega: (WALL.k / WALL.m).sqrt(),
                contact_energy: WALL.contact_energy(),
            },
            CaseKind::Chain2 => {
                // Wall–m1–m2 with springs k = 10, masses 1: K = [[2k, −k], [−k, k]]. Lowest
                // mode in closed form: λ = k(3 − √5)/2, φ = (k/(2k − λ), 1) (m2 moves most).
                let k = 10.0;
                let lam = k * (3.0 - 5f64.sqrt()) / 2.0;
                let phi1 = k / (2.0 * k - lam);
                let g = 0.01;
                StudyCase {
                    kind,
                    problem: Problem {
                        k: sparse(2, &[(0, 0, 2.0 * k), (0, 1, -k), (1, 0, -k), (1, 1, k)]),
                        m: sparse(2, &[(0, 0, 1.0), (1, 1, 1.0)]),
                        shocks: vec![stop(ShockLaw::BiPlan, 1)],
                    },
                    mode: vec![phi1, 1.0],
                    omega: lam.sqrt(),
                    // The linear mode with m2 at amplitude JEU: ½ω²φᵀMφ·JEU².
                    contact_energy: 0.5 * lam * (phi1 * phi1 + 1.0) * g * g,
                }
            }
        }
    }

    /// The measured energy range.
    pub fn range(&self) -> (f64, f64) {
        (LOW * self.contact_energy, HIGH * self.contact_energy)
    }

    /// The problem with the stop's PARA_REGUL set.
    pub fn problem_with(&self, regul: f64) -> Problem {
        let mut p = self.problem.clone();
        for s in &mut p.shocks {
            s.regul = regul;
        }
        p
    }
}

fn stop(law: ShockLaw, dof: usize) -> Shock {
    Shock {
        law,
        dofs: vec![dof],
        gap: WALL.g,
        stiffness: WALL.alpha,
        regul: 5e-5,
    }
}

fn sparse(n: usize, e: &[(usize, usize, f64)]) -> SparseColMat<usize, f64> {
    let t: Vec<Triplet<usize, usize, f64>> =
        e.iter().map(|&(r, c, v)| Triplet::new(r, c, v)).collect();
    // The entries above are in range by construction.
    SparseColMat::try_new_from_triplets(n, n, &t).unwrap_or_else(|_| unreachable!())
}

/// The base of the sweeps: sdnd122's settings with the default PREC_MAN.
pub const BASE: Config = Config {
    sweep: "base",
    h_lin: 5,
    h_nonl: 200,
    regul: 5e-5,
    prec_man: 1e-9,
};

fn with(sweep: &'static str, h_lin: usize, h_nonl: usize, regul: f64, prec_man: f64) -> Config {
    Config {
        sweep,
        h_lin,
        h_nonl,
        regul,
        prec_man,
    }
}

/// The settings measured for a case. Full: one-at-a-time sweeps around `BASE` plus a
/// diagonal in (NB_HARM_NONL, PARA_REGUL), refined together since the regularisation and
/// the truncation errors interact (a sharper law needs more harmonics): η ∝ H_nl⁻², the
/// width of the smoothed kink in time scaling like √η. Small: a cheap grid for the tests
/// and a quick look (H_l = 3, PREC_MAN = 1e-6).
pub fn grid(kind: CaseKind, size: GridSize) -> Vec<Config> {
    let mut v = Vec::new();
    match size {
        GridSize::Small => {
            for hn in [15, 30, 60, 120] {
                v.push(with("H_nl", 3, hn, 1e-5, 1e-6));
            }
            for eta in [1e-3, 1e-4] {
                v.push(with("eta", 3, 120, eta, 1e-6));
            }
        }
        GridSize::Full => {
            v.push(BASE);
            let hns: &[usize] = match kind {
                CaseKind::Wall => &[25, 50, 100, 400, 800],
                CaseKind::Chain2 => &[25, 50, 100, 400],
            };
            for &hn in hns {
                v.push(with("H_nl", 5, hn, BASE.regul, BASE.prec_man));
            }
            for eta in [1e-3, 1e-4, 1e-5, 1e-6, 1e-7] {
                v.push(with("eta", 5, 400, eta, BASE.prec_man));
            }
            for hl in [3, 10] {
                v.push(with("H_l", hl, BASE.h_nonl, BASE.regul, BASE.prec_man));
            }
            for pm in [1e-6, 1e-14] {
                v.push(with("PREC_MAN", 5, BASE.h_nonl, BASE.regul, pm));
            }
            for (hn, eta) in [(25, 1e-3), (50, 2.5e-4), (100, 6e-5), (400, 4e-6)] {
                v.push(with("diagonal", 5, hn, eta, 1e-6));
            }
        }
    }
    v
}

/// The reference of chain2: the finest settings of its grid and beyond (state them in the
/// report). NB_PAS_MAN is raised by `reference_curve` for a dense curve.
pub fn chain2_reference_config(size: GridSize) -> Config {
    match size {
        GridSize::Small => with("reference", 5, 240, 1e-6, 1e-9),
        GridSize::Full => with("reference", 7, 800, 1e-7, 1e-10),
    }
}
