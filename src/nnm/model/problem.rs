//! What the engine is asked to solve: the reduced structure, its shocks, and the EHMAN
//! settings (the values MODE_NON_LINE's keywords give).

use faer::sparse::SparseColMat;

#[derive(Clone, Copy, Debug, PartialEq)]
pub enum ShockLaw {
    Plan,
    BiPlan,
    Cercle { origin: [f64; 2], form: CercleForm },
}

impl ShockLaw {
    /// The contact unknowns that hold the force components the structure receives (laws.rs
    /// places them first): f for PLAN and BI_PLAN, f_x and f_y for CERCLE.
    pub fn force_unknowns(self) -> std::ops::Range<usize> {
        match self {
            ShockLaw::Cercle { .. } => 0..2,
            ShockLaw::Plan | ShockLaw::BiPlan => 0..1,
        }
    }

    /// The obstacle's origin relative to the rest position: CERCLE's ORIG_OBST, 0 for the
    /// planes.
    pub fn origin(self) -> [f64; 2] {
        match self {
            ShockLaw::Cercle { origin, .. } => origin,
            ShockLaw::Plan | ShockLaw::BiPlan => [0.0, 0.0],
        }
    }
}

/// Which regularisation of the ring law (CHOC/LOI_CERCLE; laws.rs gives both).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CercleForm {
    /// R5.07.01 eq. (12), Code_Aster's: PLAN's regularised law on the radial distance r,
    /// the force along d/r (unknowns f_x, f_y, r, f).
    Radial,
    /// aster-nl's: BI_PLAN's law at the radial distance through a secant stiffness λ
    /// (unknowns f_x, f_y, λ, z), regular through the ring centre.
    Secant,
}

#[derive(Clone, Debug)]
pub struct Shock {
    pub law: ShockLaw,
    /// 1 index into the reduced DOFs for PLAN/BI_PLAN (obstacle on the + side for PLAN),
    /// 2 for CERCLE.
    pub dofs: Vec<usize>,
    /// JEU.
    pub gap: f64,
    /// RIGI_NOR.
    pub stiffness: f64,
    /// PARA_REGUL, dimensionless as in Code_Aster (η_phys = PARA_REGUL·k_ref·JEU²).
    pub regul: f64,
}

impl Shock {
    /// The distance the structure at rest can move before it reaches the obstacle, along
    /// the way out: JEU − |ORIG_OBST| for CERCLE, JEU for the planes. Not positive when the
    /// structure rests against a ring or outside it.
    pub fn room(&self) -> f64 {
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
}

#[derive(Clone, Debug)]
pub struct Settings {
    pub h_lin: usize,
    pub h_nonl: usize,
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
