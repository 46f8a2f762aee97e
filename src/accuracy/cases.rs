//! The studied systems, their energy ranges and the grids of settings.

use crate::nnm::exact::Oscillator;
use crate::nnm::{Problem, Shock, ShockLaw};
use faer::sparse::{SparseColMat, Triplet};

/// The settings that vary in the study; the others are fixed (`settings`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Config {
    /// Which sweep the setting belongs to ("base", "H_nl", "eta", "H_l", "PREC_MAN",
    /// "diagonal", "reference").
    pub sweep: &'static str,
    /// NB_HARM_LINE.
    pub h_lin: usize,
    /// NB_HARM_NONL.
    pub h_nonl: usize,
    /// PARA_REGUL.
    pub regul: f64,
    /// PREC_MAN.
    pub prec_man: f64,
    /// Every computed point in the range corrected on the exact (unregularised) law
    /// (`nnm::exact_law`) with this many time samples per displacement coefficient; 0: not
    /// corrected (EHMAN's own points are measured).
    pub exact_law: usize,
}

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
                    forcing: None,
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
                        forcing: None,
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

/// The base of the sweeps. NB_HARM_LINE = 15, not sdnd122's 5: measured, the truncation of
/// the displacements (H_l) alone costs 1.3e-3 at H_l = 5 and 6.6e-5 at H_l = 15 over the
/// range (H_nl = 100, η = 1e-5; docs/accuracy.md), so at H_l = 5 the effects of
/// NB_HARM_NONL and PARA_REGUL would be invisible.
pub const BASE: Config = Config {
    sweep: "base",
    h_lin: 15,
    h_nonl: 100,
    regul: 1e-5,
    prec_man: 1e-9,
    exact_law: 0,
};

/// sdnd122's own settings (Code_Aster's validation case), measured as they are.
pub const SDND122: Config = Config {
    sweep: "sdnd122",
    h_lin: 5,
    h_nonl: 200,
    regul: 5e-5,
    prec_man: 1e-14,
    exact_law: 0,
};

fn with(sweep: &'static str, h_lin: usize, h_nonl: usize, regul: f64, prec_man: f64) -> Config {
    Config {
        sweep,
        h_lin,
        h_nonl,
        regul,
        prec_man,
        exact_law: 0,
    }
}

/// A setting whose points are corrected on the exact law (`Config::exact_law`).
fn exact(h_lin: usize, h_nonl: usize, regul: f64, prec_man: f64, per_coef: usize) -> Config {
    Config {
        exact_law: per_coef,
        ..with("exact", h_lin, h_nonl, regul, prec_man)
    }
}

/// The settings measured for a case. Full: one-at-a-time sweeps around `BASE` plus a
/// diagonal in (NB_HARM_NONL, PARA_REGUL), refined together since the regularisation and
/// the truncation errors interact (a sharper law needs more harmonics). On the wall the
/// diagonal runs from (40, 1e-3) to (1000, 1e-7), η falling a decade while H_nl grows about
/// 2.5 times (its first point at H_nl = H_l, the smallest the engine accepts), at H_l = 40 and PREC_MAN = 1e-9 so that neither the displacements' truncation
/// nor the series hides what H_nl and η do (small η with a loose PREC_MAN is measured once
/// in the PREC_MAN sweep). The wall's η sweep sits at H_nl = 200. BI_PLAN (chain2) carries
/// two contact unknowns, so its H_nl stay lower for the same time budget. Small: a cheap
/// grid for the tests and a quick look (H_l = 10, PREC_MAN = 1e-6).
pub fn grid(kind: CaseKind, size: GridSize) -> Vec<Config> {
    let mut v = Vec::new();
    let b = BASE;
    match (size, kind) {
        (GridSize::Small, _) => {
            for hn in [10, 20, 40] {
                v.push(with("H_nl", 10, hn, 1e-5, 1e-6));
            }
            for eta in [1e-3, 1e-4] {
                v.push(with("eta", 10, 80, eta, 1e-6));
            }
            v.push(exact(10, 20, 1e-3, 1e-6, 16));
        }
        (GridSize::Full, CaseKind::Wall) => {
            v.push(b);
            v.push(SDND122);
            for hl in [5, 10, 20, 30, 40] {
                v.push(with("H_l", hl, b.h_nonl, b.regul, b.prec_man));
            }
            for hn in [25, 50, 200, 400] {
                v.push(with("H_nl", b.h_lin, hn, b.regul, b.prec_man));
            }
            for eta in [1e-3, 1e-4, 1e-5, 1e-6, 1e-7] {
                v.push(with("eta", 20, 200, eta, b.prec_man));
            }
            for pm in [1e-6, 1e-14] {
                v.push(with("PREC_MAN", b.h_lin, b.h_nonl, b.regul, pm));
            }
            // Small η with a loose PREC_MAN (the diagonal has the same at 1e-9).
            v.push(with("PREC_MAN", 40, 400, 1e-6, 1e-6));
            for (hn, eta) in [
                (40, 1e-3),
                (60, 1e-4),
                (150, 1e-5),
                (400, 1e-6),
                (1000, 1e-7),
            ] {
                v.push(with("diagonal", 40, hn, eta, 1e-9));
            }
            // Coarse everything, for the cheapest 1e-3.
            for (hl, hn) in [(7, 30), (10, 30), (10, 60)] {
                v.push(with("coarse", hl, hn, 1e-4, 1e-6));
            }
            // Everything refined at once, toward 1e-5; the last tells whether H_l = 40
            // limits the finest diagonal points.
            for (hl, hn, eta) in [
                (30, 200, 1e-6),
                (40, 200, 1e-6),
                (40, 400, 1e-7),
                (60, 400, 1e-7),
            ] {
                v.push(with("fine", hl, hn, eta, 1e-9));
            }
            // EHMAN at coarse settings (η 1e-3, H_nl = max(H_l, 20)), every point then
            // corrected on the exact law; the samples per coefficient at two H_l.
            for hl in [5, 10, 15, 20, 30, 40, 60] {
                v.push(exact(hl, hl.max(20), 1e-3, 1e-6, 64));
            }
            for hl in [10, 40] {
                for spc in [4, 16] {
                    v.push(exact(hl, hl.max(20), 1e-3, 1e-6, spc));
                }
            }
        }
        (GridSize::Full, CaseKind::Chain2) => {
            // Two impacts per period on the end mass of a chain: NB_HARM_LINE limits the
            // accuracy even more than on the wall, so the sweeps sit at H_l = 20.
            let b = Config {
                h_lin: 20,
                h_nonl: 60,
                ..b
            };
            v.push(b);
            for hl in [5, 10, 15, 30] {
                v.push(with("H_l", hl, b.h_nonl, b.regul, b.prec_man));
            }
            for hn in [20, 30, 120] {
                v.push(with("H_nl", b.h_lin, hn, b.regul, b.prec_man));
            }
            for eta in [1e-3, 1e-4, 1e-6] {
                v.push(with("eta", b.h_lin, 120, eta, b.prec_man));
            }
            for pm in [1e-6, 1e-14] {
                v.push(with("PREC_MAN", b.h_lin, b.h_nonl, b.regul, pm));
            }
            for (hn, eta) in [(20, 1e-3), (40, 2.5e-4), (80, 6e-5)] {
                v.push(with("diagonal", b.h_lin, hn, eta, 1e-6));
            }
            for (hl, hn) in [(10, 30), (15, 30)] {
                v.push(with("coarse", hl, hn, 1e-4, 1e-6));
            }
            for hl in [30, 40] {
                v.push(with("fine", hl, 120, 1e-6, 1e-9));
            }
            for hl in [5, 10, 15, 20, 30, 40] {
                v.push(exact(hl, hl.max(20), 1e-3, 1e-6, 64));
            }
            for spc in [4, 16] {
                v.push(exact(20, 20, 1e-3, 1e-6, spc));
            }
        }
    }
    v
}

/// Settings at which the cost of TEST_BIFURCATION = 'SERIE_DETERMINANT' is measured (run
/// with and without it): the base, then a large NB_HARM_LINE (the test's extra solves grow
/// with n_dof·(2·H_l + 1)), then a large NB_HARM_NONL (where factorising dominates). None on
/// the small grid.
pub fn det_test_grid(kind: CaseKind, size: GridSize) -> Vec<Config> {
    match (size, kind) {
        (GridSize::Small, _) => vec![],
        (GridSize::Full, CaseKind::Wall) => vec![
            with("det", 15, 100, 1e-5, 1e-9),
            with("det", 40, 100, 1e-5, 1e-9),
            with("det", 40, 400, 1e-6, 1e-9),
        ],
        (GridSize::Full, CaseKind::Chain2) => vec![
            with("det", 20, 60, 1e-5, 1e-9),
            with("det", 40, 120, 1e-6, 1e-9),
        ],
    }
}

/// The reference of chain2: finer than every measured setting in each parameter (state
/// them in the report). NB_PAS_MAN is raised by `reference_curve` for a dense curve.
pub fn chain2_reference_config(size: GridSize) -> Config {
    match size {
        GridSize::Small => with("reference", 15, 100, 1e-6, 1e-9),
        GridSize::Full => with("reference", 50, 240, 5e-7, 1e-10),
    }
}
