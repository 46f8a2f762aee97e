//! What the engine is asked to solve: the reduced structure, its shocks, and the EHMAN
//! settings (the values MODE_NON_LINE's keywords give).

use faer::sparse::SparseColMat;

// The law of a shock, and what each law is: model/law/, where the variants are registered.
pub use crate::nnm::model::law::{CercleForm, ShockLaw};

/// One shock, or one law without an obstacle (a cubic spring: JEU and PARA_REGUL 0,
/// `ContactLaw::has_obstacle`).
#[derive(Clone, Debug)]
pub struct Shock {
    pub law: ShockLaw,
    /// 1 index into the reduced DOFs for PLAN/BI_PLAN (obstacle on the + side for PLAN)
    /// and a cubic spring, 2 for CERCLE.
    pub dofs: Vec<usize>,
    /// JEU.
    pub gap: f64,
    /// RIGI_NOR (a cubic spring's RAIDEUR k₃, N/m³).
    pub stiffness: f64,
    /// PARA_REGUL, dimensionless as in Code_Aster (η_phys = PARA_REGUL·k_ref·JEU²).
    pub regul: f64,
}

impl Shock {
    /// The distance the structure at rest can move before it reaches the obstacle, along
    /// the way out: JEU − |ORIG_OBST| for CERCLE, JEU for the planes, infinite for a law
    /// without an obstacle. Not positive when the structure rests against a ring or outside
    /// it.
    pub fn room(&self) -> f64 {
        if !self.law.has_obstacle() {
            return f64::INFINITY;
        }
        let [cx, cy] = self.law.origin();
        self.gap - cx.hypot(cy)
    }
}

#[derive(Clone, Debug)]
pub struct Problem {
    /// Stiffness and mass reduced to the free DOFs, n×n.
    pub k: SparseColMat<usize, f64>,
    pub m: SparseColMat<usize, f64>,
    pub shocks: Vec<Shock>,
    /// A damped structure under a harmonic force (REPONSE_FORCEE_NL): the forced response
    /// replaces the autonomous problem's unfolding γ and phase condition (system.rs). None
    /// for the conservative structure of MODE_NON_LINE.
    pub forcing: Option<Forcing>,
}

/// The damping and the harmonic excitation of a forced response, on the DOFs of
/// `Problem::k`: M Ü + C U̇ + K U + Pᵀ F = f cos ωt.
#[derive(Clone, Debug)]
pub struct Forcing {
    /// The damping matrix C, n×n.
    pub damping: SparseColMat<usize, f64>,
    /// The amplitude f of the force (N), one value per DOF.
    pub force: Vec<f64>,
}

impl Problem {
    /// The shocks whose law has an obstacle at JEU (`ContactLaw::has_obstacle`).
    pub fn stops(&self) -> impl Iterator<Item = &Shock> + '_ {
        self.shocks.iter().filter(|s| s.law.has_obstacle())
    }

    /// The largest JEU over the shocks with an obstacle, what the lengths of the scaled
    /// equations are measured in (`Scaling::new`); None when no law has a JEU (no shocks,
    /// or only cubic springs: the lengths are then the start's amplitude).
    pub fn largest_gap(&self) -> Option<f64> {
        self.stops().map(|s| s.gap).reduce(f64::max)
    }
}

/// The harmonic counts of a run (NB_HARM_LINE, NB_HARM_NONL): the layout of its points, and
/// all that reading a stored point back needs (REST_MODE_NONL, CALC_STABILITE, the rows).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Harmonics {
    pub h_lin: usize,
    pub h_nonl: usize,
}

impl From<&Harmonics> for Harmonics {
    fn from(h: &Harmonics) -> Harmonics {
        *h
    }
}

impl From<&Settings> for Harmonics {
    fn from(s: &Settings) -> Harmonics {
        s.harmonics
    }
}

/// How a branch is followed (RESOLUTION's continuation keywords and DIR_EVOLUTION): what the
/// continuation reads, apart from the layout of the points.
#[derive(Clone, Debug)]
pub struct Continuation {
    /// NB_BRANCHE.
    pub n_branches: usize,
    /// NB_PAS_MAN.
    pub n_points_per_branch: usize,
    /// NB_ORDRE_MAN.
    pub order: usize,
    pub prec_man: f64,
    pub prec_newton: f64,
    pub iter_newton_max: usize,
    /// CRIT_ORDR_BIFURCATION.
    pub bif_terms: usize,
    /// RESI_RELA_BIFURCATION.
    pub bif_tol: f64,
    /// TEST_BIFURCATION = 'SERIE_DETERMINANT': also test the sign of the bordered
    /// tangent's determinant at every branch end (bifurcation.rs).
    pub det_test: bool,
    /// DIR_EVOLUTION: −1 forward, +1 backward (module doc).
    pub direction: i32,
}

/// The settings of one MODE_NON_LINE run: the harmonic counts (the layout of its points)
/// and the continuation's settings, two types so that what reads only one of them says so.
#[derive(Clone, Debug)]
pub struct Settings {
    pub harmonics: Harmonics,
    pub continuation: Continuation,
}
