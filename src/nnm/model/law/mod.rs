//! The contact laws, one file each (plan.rs, bi_plan.rs, cercle.rs, ressort_cubique.rs): a law owns its own
//! unknowns, its equations recast as quadratic ones in scaled units (lengths divided by the
//! largest JEU g_ref, forces by k_ref·g_ref; see `system::Scaling`), its start from
//! displacement samples, its pointwise force and tangent in physical units, its
//! penetration, and whether it can be rescaled far up a branch (`ContactLaw`). A law is
//! registered once, in `ShockLaw::with` below: the rest of the engine asks the law.
//!
//! Each law lists its own unknown series and its equations as constant, linear and quadratic
//! terms; the tangent is derived from the same list (system.rs), so residual and Jacobian
//! cannot disagree. With s = JEU/g_ref, α = RIGI_NOR/k_ref and η = PARA_REGUL:
//! - PLAN (f):             f²/α − f (u − s) − η s² = 0
//!   (Code_Aster's F(F/α − (u/JEU − 1)) = η with F = f/(k_ref·JEU), i.e. the physical law
//!   f(f − α(u−g)) = α η_phys with η_phys = PARA_REGUL·k_ref·JEU²).
//! - BI_PLAN (f, z):       f − η u − f z = 0,   z − (f/α − u)²/s² = 0
//!   (Code_Aster's F − η u/JEU − F Z = 0, Z = (F/α − u/JEU)², with its sign; the same law
//!   in physical units: docs/ehman.md §2).
//! - CERCLE, LOI_CERCLE='RAYON' (fx, fy, r, φ), R5.07.01 eq. (12) as Code_Aster writes it,
//!   with d = (ux − ex, uy − ey) the displacement from the ring centre:
//!   φ²/α − φ (r − s) − η s² = 0 (PLAN's law on the radial distance r),
//!   r² − |d|² = 0, fx r − φ dx = 0, fy r − φ dy = 0. In contact the force is α(r − s) along
//!   d/r; inside the ring it is φ ≈ η s²/(s − r) along d/r, a force of nearly constant
//!   magnitude η s that turns with d. Where the orbit passes through the centre that force
//!   changes sign within an instant and the equations degenerate: r² = |d|² has a double root
//!   and f r = φ d leaves the direction free (pointwise Jacobian 2r³√((r−s)² + 4ηs²/α), zero
//!   at r = 0). The start takes the root r = |d| sample by sample, as Code_Aster does, with
//!   no force at an instant exactly at the centre; the harmonic balance then follows the
//!   truncated series of r, which stays close to |d| (docs/mode_non_line.md, "CERCLE").
//! - CERCLE, LOI_CERCLE='SECANTE' (fx, fy, λ, z), aster-nl's form, with d as above and
//!   F = (fx, fy):  F − λ d = 0 (two equations),  λ − η − λ z = 0,
//!   z − |F/α − d|²/s² = 0. λ is the secant stiffness of the ring, F/d. With r = |d| and
//!   φ = λ r the force magnitude, these are BI_PLAN's equations at the radial distance:
//!   φ(1 − (φ/α − r)²/s²) = η r, so the force is α(r − s) along d in contact and a weak
//!   spring η d/(1 − r²/s²) toward the centre inside the ring. Nothing divides by r: at the
//!   centre λ = η, z = 0, F = 0, and an orbit through the centre is as regular as any other.
//!   With a centred ring and motion along one component (dx ≡ 0) the first equation gives
//!   fx ≡ 0 and, pointwise, the rest is BI_PLAN's law (f = λ u); in harmonic balance the
//!   force series is λ·u truncated instead of f, another truncation of the same regularised
//!   system (the BI_PLAN branch is recovered to the truncation error, nnm/tests/mod.rs).
//!   The two forms agree in contact and differ inside the ring (a force of magnitude ≈ η s
//!   along d/r for 'RAYON', a weak spring for 'SECANTE'); both differences vanish as η → 0.
//! - RESSORT_CUBIQUE (f, w), a cubic spring k₃u³ (no obstacle, no JEU, no η), with
//!   β = k₃L²/k_ref (L the length unit the law carries):  f − β w u = 0,  w − u² = 0.
//!
//! Pointwise Jacobian of each law with respect to its own unknowns on its physical root
//! (what the determinant test of condensed_det.rs and a pointwise preconditioner rely on):
//! PLAN √((u−s)² + 4ηs²/α) > 0; BI_PLAN ψ_f = 1 − z − 2f(f/α − u)/(α s²) > 0; CERCLE 'RAYON'
//! 2r³√((r−s)² + 4ηs²/α) ≥ 0, zero at the centre; CERCLE 'SECANTE'
//! (eliminating F = λ d, whose block is the identity) 1 − z − 2λ(λ/α − 1) r²/(α s²), which
//! is BI_PLAN's ψ_f at the radial distance (f = φ = λ r): > 0, and 1 at the centre;
//! RESSORT_CUBIQUE 1 (triangular in (f, w)).
//! ψ_f > 0 on the physical root for every u: f(1 − (f/α − u)²/s²) is a cubic in f that
//! increases on the interval (max(0, α(u − s)), α u) holding that root (its critical points
//! lie at α(2u ± √(u² + 3s²))/3, outside it). A three-unknown vector form F(1 − z) = η d
//! has determinant (1 − z)·ψ_f instead; its factor 1 − z = η r/φ is tiny in contact, where
//! the truncated series of z overshoots 1 and the harmonic-balance block changes sign
//! (nnm/tests/mod.rs, cercle_law_block_keeps_its_determinant_sign_along_branches); λ avoids it.

use crate::nnm::error::{Error, Result, Setting};

mod bi_plan;
mod cercle;
mod plan;
mod ressort_cubique;

use bi_plan::BiPlan;
use cercle::Cercle;
pub use cercle::CercleForm;
use plan::Plan;
use ressort_cubique::RessortCubique;

/// The contact law of a shock, as the user chose it (CHOC/OBSTACLE, LOI_CERCLE, ORIG_OBST;
/// RESSORT_CUBIQUE). A new law is one variant here, one arm of [`ShockLaw::with`] (and of
/// [`ShockLaw::scaled`] when it carries a length), and its own file.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum ShockLaw {
    Plan,
    BiPlan,
    Cercle {
        origin: [f64; 2],
        form: CercleForm,
    },
    /// A cubic spring k₃u³ (k₃ = `Shock::stiffness`), its equations in lengths of `unit`
    /// metres: 1 as the user gives it ([`ShockLaw::RESSORT_CUBIQUE`]), the scaled length
    /// once [`ShockLaw::scaled`].
    RessortCubique {
        unit: f64,
    },
}
#[cfg(test)]
use {bi_plan::biplan_force, plan::plan_force};

/// A variable a law equation depends on: one of its own unknown series (H_nl harmonics) or a
/// displacement component of its DOFs (H_l harmonics, zero-padded to H_nl).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Var {
    Own(usize),
    U(usize),
}

/// coef · a · b added to equation `eq`.
#[derive(Clone, Copy, Debug)]
pub struct Term {
    pub eq: usize,
    pub coef: f64,
    pub a: Var,
    pub b: Var,
}

/// coef · var added to equation `eq`.
#[derive(Clone, Copy, Debug)]
pub struct Lin {
    pub eq: usize,
    pub coef: f64,
    pub var: Var,
}

/// The equations of one shock: as many as its own unknowns.
#[derive(Clone, Debug)]
pub struct LawEqs {
    pub n_own: usize,
    pub quad: Vec<Term>,
    pub lin: Vec<Lin>,
    /// Constants (on the mean, harmonic 0) per equation.
    pub cst: Vec<(usize, f64)>,
    /// (component, own variable) pairs: the force each component receives.
    pub forces: Vec<(usize, usize)>,
}

fn quad_term(eq: usize, coef: f64, a: Var, b: Var) -> Term {
    Term { eq, coef, a, b }
}
fn lin_term(eq: usize, coef: f64, var: Var) -> Lin {
    Lin { eq, coef, var }
}

/// Displacement component `i` of one instant (a missing one is a bug of the caller).
fn component(u: &[f64], i: usize) -> Result<f64> {
    u.get(i)
        .copied()
        .ok_or_else(|| Error::internal("contact law component missing"))
}

/// The samples of displacement component `i` (a missing one is a bug of the caller).
fn samples(u: &[Vec<f64>], i: usize) -> Result<&[f64]> {
    u.get(i)
        .map(Vec::as_slice)
        .ok_or_else(|| Error::internal("law component missing"))
}

/// ½α·d² for a penetration d > 0, 0 otherwise: the penalty energy of a stop.
fn penalty(alpha: f64, d: f64) -> f64 {
    if d > 0.0 {
        0.5 * alpha * d * d
    } else {
        0.0
    }
}

/// What a contact law is to the engine. Scaled quantities: s = JEU/g_ref, α = RIGI_NOR/k_ref,
/// η = PARA_REGUL, the displacement and the origin in units of g_ref. Physical ones: α =
/// RIGI_NOR, gap = JEU, η = PARA_REGUL·k_ref·JEU² (point_law.rs), metres.
pub trait ContactLaw {
    /// Its parameters (JEU, RIGI_NOR, PARA_REGUL as given) are ones it can be solved with:
    /// by default each finite and positive (the regularised laws are singular at η = 0).
    fn validate(&self, gap: f64, stiffness: f64, regul: f64) -> Result<()> {
        if !(gap.is_finite() && gap > 0.0) {
            return Err(
                Error::input(format!("JEU must be positive, got {gap}")).setting(Setting::ShockGap)
            );
        }
        if !(stiffness.is_finite() && stiffness > 0.0) {
            return Err(
                Error::input(format!("RIGI_NOR must be positive, got {stiffness}"))
                    .setting(Setting::ShockStiffness),
            );
        }
        if !(regul.is_finite() && regul > 0.0) {
            return Err(Error::input(format!(
                "PARA_REGUL must be positive (the regularised law is singular at 0), got {regul}"
            ))
            .setting(Setting::ShockRegularisation));
        }
        Ok(())
    }

    /// Displacement components the law reads (1, or 2 for a ring).
    fn n_comp(&self) -> usize;

    /// Its own unknown series.
    fn n_own(&self) -> usize;

    /// The physical value of one scaled unit of each own unknown, given the units of force,
    /// length and stiffness.
    fn own_units(&self, force: f64, length: f64, stiffness: f64) -> Vec<f64>;

    /// The own unknowns that hold the force components the structure receives (placed
    /// first): f for the planes, f_x and f_y for a ring.
    fn force_unknowns(&self) -> std::ops::Range<usize> {
        0..1
    }

    /// The obstacle's origin relative to the rest position (a ring's ORIG_OBST), in the
    /// units the law was built in.
    fn origin(&self) -> [f64; 2] {
        [0.0, 0.0]
    }

    /// Its equations stay well conditioned when the lengths are re-expressed in a unit of
    /// the motion's size far up a branch (rescale.rs).
    fn rescalable(&self) -> bool;

    /// The law is an obstacle at JEU that the structure reaches (a stop, a ring): its JEU
    /// sets the length unit of the scaled equations (`Problem::largest_gap`), it has a
    /// penetration, a room before contact (`Shock::room`), and a force series whose tail
    /// is a contact pulse (MODE_NON_LINE_1). False for a law with no JEU that acts at every
    /// displacement (a spring): those analyses skip it (docs/mode_non_line.md).
    fn has_obstacle(&self) -> bool {
        true
    }

    /// The unit of its law defect (ECART_LOI_CHOC): α·JEU for a stop or a ring (physical
    /// α = RIGI_NOR); None for a law without a force of its own size, whose defect is
    /// judged against the largest force of the orbit.
    fn force_unit(&self, alpha: f64, gap: f64) -> Option<f64> {
        Some(alpha * gap)
    }

    /// Its equations, scaled.
    fn equations(&self, s: f64, alpha: f64, eta: f64) -> LawEqs;

    /// Samples of its own unknowns from samples of its displacement components, scaled (a
    /// start point: consistent with the law sample by sample).
    fn own_from_u(&self, s: f64, alpha: f64, eta: f64, u: &[Vec<f64>]) -> Result<Vec<Vec<f64>>>;

    /// The penetration of the nonsmooth law at displacement `u` (its first `n_comp`
    /// components are read): negative while the structure is clear of the obstacle.
    fn penetration(&self, u: [f64; 2], gap: f64) -> f64;

    /// The penetration ENERGIE's penalty term is computed from (energy.rs), as the stored
    /// tables computed it.
    fn energy_penetration(&self, u: [f64; 2], gap: f64) -> f64 {
        self.penetration(u, gap)
    }

    /// The energy stored in the law at `u` that ENERGIE counts, Code_Aster's: the penalty
    /// ½α(penetration)₊² of the nonsmooth stop (the regularisation's own is left out).
    fn energy(&self, u: [f64; 2], alpha: f64, gap: f64) -> f64 {
        penalty(alpha, self.energy_penetration(u, gap))
    }

    /// The same energy from `penetration`, for averages over the period (ENERGIE_MOYENNE)
    /// and the exact law's energy.
    fn mean_energy(&self, u: [f64; 2], alpha: f64, gap: f64) -> f64 {
        penalty(alpha, self.penetration(u, gap))
    }

    /// Force components at displacement `u` (the first `n_comp` entries), physical units.
    fn force(&self, u: &[f64], alpha: f64, gap: f64, eta: f64) -> Result<[f64; 2]>;

    /// Force components and their Jacobian (row-major n_comp × n_comp), physical units.
    fn eval(&self, u: &[f64], alpha: f64, gap: f64, eta: f64) -> Result<(Vec<f64>, Vec<f64>)>;

    /// The exact (unregularised) penalty law at `u`: force α·(penetration)₊ along the
    /// obstacle's normal and its Jacobian (row-major 2 × 2, the first n_comp rows and
    /// columns used), physical units (CORR_LOI_EXACTE, the accuracy advice).
    fn exact_force(&self, u: [f64; 2], alpha: f64, gap: f64) -> ([f64; 2], [f64; 4]);

    /// The stiffness of the regularised law at rest, η/JEU² per side a plane has (the shift
    /// of the linear frequency it causes before any contact), or None for a law whose
    /// regularised force at rest is not a spring about the rest position (a ring).
    fn stiffness_at_rest(&self, gap: f64, eta: f64) -> Option<f64>;
}

impl ShockLaw {
    /// The law behind the typed spec: the one place where a law is registered.
    pub fn with<R>(self, f: impl FnOnce(&dyn ContactLaw) -> R) -> R {
        match self {
            ShockLaw::Plan => f(&Plan),
            ShockLaw::BiPlan => f(&BiPlan),
            ShockLaw::Cercle { origin, form } => f(&Cercle { origin, form }),
            ShockLaw::RessortCubique { unit } => f(&RessortCubique { unit }),
        }
    }

    /// The cubic spring as the user gives it: its equations in metres.
    pub const RESSORT_CUBIQUE: ShockLaw = ShockLaw::RessortCubique { unit: 1.0 };

    /// The same law with its lengths in units of `length` (the scaled equations'): a
    /// ring's origin, a spring's unit.
    pub fn scaled(self, length: f64) -> ShockLaw {
        match self {
            ShockLaw::Cercle { origin, form } => ShockLaw::Cercle {
                origin: [origin[0] / length, origin[1] / length],
                form,
            },
            ShockLaw::RessortCubique { unit } => ShockLaw::RessortCubique {
                unit: unit * length,
            },
            law => law,
        }
    }

    pub fn n_comp(self) -> usize {
        self.with(|l| l.n_comp())
    }

    pub fn n_own(self) -> usize {
        self.with(|l| l.n_own())
    }

    /// See [`ContactLaw::force_unknowns`].
    pub fn force_unknowns(self) -> std::ops::Range<usize> {
        self.with(|l| l.force_unknowns())
    }

    /// See [`ContactLaw::origin`].
    pub fn origin(self) -> [f64; 2] {
        self.with(|l| l.origin())
    }

    pub fn rescalable(self) -> bool {
        self.with(|l| l.rescalable())
    }

    /// See [`ContactLaw::has_obstacle`].
    pub fn has_obstacle(self) -> bool {
        self.with(|l| l.has_obstacle())
    }

    /// See [`ContactLaw::force_unit`].
    pub fn force_unit(self, alpha: f64, gap: f64) -> Option<f64> {
        self.with(|l| l.force_unit(alpha, gap))
    }
}

/// The equations of a law with scaled gap `s`, stiffness `alpha`, PARA_REGUL `eta` (the
/// law's origin already scaled, `ShockLaw::scaled`).
pub fn equations(law: ShockLaw, s: f64, alpha: f64, eta: f64) -> LawEqs {
    law.with(|l| l.equations(s, alpha, eta))
}

/// Samples of a law's own unknowns from samples of its displacement components (a start
/// point: consistent with the law sample by sample, then projected on the harmonics).
pub fn own_from_u(
    law: ShockLaw,
    s: f64,
    alpha: f64,
    eta: f64,
    u: &[Vec<f64>],
) -> Result<Vec<Vec<f64>>> {
    law.with(|l| l.own_from_u(s, alpha, eta, u))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn biplan_root_solves_the_law_and_is_odd() {
        let (s, a, e) = (1.0, 5.0, 1e-3);
        for &u in &[0.3, 0.99, 1.0, 1.2, 3.0] {
            let f = biplan_force(u, s, a, e);
            let z = (f / a - u).powi(2) / (s * s);
            assert!((f - e * u - f * z).abs() < 1e-10 * (1.0 + f.abs()));
            assert_eq!(biplan_force(-u, s, a, e), -f);
        }
        // Far in contact the force is close to α(u − s).
        assert!((biplan_force(3.0, s, a, e) - a * 2.0).abs() < 1e-2);
    }

    #[test]
    fn plan_root_is_positive_and_smooth_max() {
        let (a, c) = (50.0, 5e-5);
        for &d in &[-1.0, -1e-3, 0.0, 1e-3, 1.0] {
            let f = plan_force(d, a, c);
            assert!(f > 0.0);
            assert!((f * f / a - f * d - c).abs() < 1e-12 * (1.0 + f * f));
        }
    }

    /// Residual and Jacobian (row-major, n_own²) with respect to the law's own unknowns of
    /// the equations listed in `eqs`, evaluated at one instant (a pointwise evaluation of
    /// the term list, independent of the harmonic-balance assembly).
    fn pointwise(eqs: &LawEqs, own: &[f64], u: &[f64]) -> (Vec<f64>, Vec<f64>) {
        let n = eqs.n_own;
        let val = |v: Var| match v {
            Var::Own(i) => own[i],
            Var::U(i) => u[i],
        };
        let (mut r, mut j) = (vec![0.0; n], vec![0.0; n * n]);
        for &(e, c) in &eqs.cst {
            r[e] += c;
        }
        for t in &eqs.lin {
            r[t.eq] += t.coef * val(t.var);
            if let Var::Own(i) = t.var {
                j[t.eq * n + i] += t.coef;
            }
        }
        for t in &eqs.quad {
            r[t.eq] += t.coef * val(t.a) * val(t.b);
            if let Var::Own(i) = t.a {
                j[t.eq * n + i] += t.coef * val(t.b);
            }
            if let Var::Own(i) = t.b {
                j[t.eq * n + i] += t.coef * val(t.a);
            }
        }
        (r, j)
    }

    fn det4(m: &[f64]) -> f64 {
        // Laplace expansion along the first row of 3×3 minors.
        let minor = |c: usize| {
            let cols: Vec<usize> = (0..4).filter(|&k| k != c).collect();
            let e = |r: usize, k: usize| m[r * 4 + cols[k]];
            e(1, 0) * (e(2, 1) * e(3, 2) - e(2, 2) * e(3, 1))
                - e(1, 1) * (e(2, 0) * e(3, 2) - e(2, 2) * e(3, 0))
                + e(1, 2) * (e(2, 0) * e(3, 1) - e(2, 1) * e(3, 0))
        };
        (0..4)
            .map(|c| [1.0, -1.0, 1.0, -1.0][c] * m[c] * minor(c))
            .sum()
    }

    /// A ring's own unknowns from own_from_u at each radial distance in `radii` and three
    /// directions from its centre, with the Jacobian of its listed equations there; asserts
    /// that they solve those equations to round-off. Returns (r, u, own, Jacobian).
    #[allow(clippy::type_complexity)]
    fn ring_roots(
        law: ShockLaw,
        s: f64,
        a: f64,
        eta: f64,
        radii: &[f64],
    ) -> Vec<(f64, [f64; 2], Vec<f64>, Vec<f64>)> {
        let ShockLaw::Cercle {
            origin: [ex, ey], ..
        } = law
        else {
            panic!("a ring")
        };
        let eqs = equations(law, s, a, eta);
        assert_eq!(eqs.n_own, 4);
        let mut out = Vec::new();
        for &r in radii {
            for theta in [0.0f64, 2.0, 4.5] {
                let u = [ex + r * theta.cos(), ey + r * theta.sin()];
                let own = own_from_u(law, s, a, eta, &[vec![u[0]], vec![u[1]]]).unwrap();
                let own: Vec<f64> = own.iter().map(|v| v[0]).collect();
                let (res, jac) = pointwise(&eqs, &own, &u);
                let scale = 1.0 + own.iter().fold(0.0f64, |m, v| m.max(v.abs()));
                assert!(
                    res.iter().all(|v| v.abs() < 1e-12 * scale),
                    "r {r}: {res:?}"
                );
                out.push((r, u, own, jac));
            }
        }
        out
    }

    #[test]
    fn radial_ring_root_solves_eq_12_with_the_jacobian_2r3_psi() {
        // R5.07.01 eq. (12) in scaled units: s = 1.3, α = 50, η = 1e-3, centre (0.2, −0.1).
        // At each radial distance the own unknowns from own_from_u must solve the listed
        // equations to round-off, the force must be PLAN's root along d/r (an independent
        // quadratic formula here), and the Jacobian's determinant must be 2r³ψ with
        // ψ = √((r − s)² + 4ηs²/α) (module doc): zero at the centre, positive elsewhere.
        let (s, a, eta, ex, ey) = (1.3, 50.0, 1e-3, 0.2, -0.1);
        let law = ShockLaw::Cercle {
            origin: [ex, ey],
            form: CercleForm::Radial,
        };
        for (r, u, own, jac) in
            ring_roots(law, s, a, eta, &[0.0, 1e-3, 0.3, 1.29, 1.3, 1.31, 2.0, 4.0])
        {
            let scale = 1.0 + own.iter().fold(0.0f64, |m, v| m.max(v.abs()));
            // φ²/α − φ(r − s) − ηs² = 0: φ = α/2 ((r − s) + √((r − s)² + 4ηs²/α)).
            let q = ((r - s) * (r - s) + 4.0 * eta * s * s / a).sqrt();
            let phi = 0.5 * a * ((r - s) + q);
            assert!((own[3] - phi).abs() < 1e-9 * phi.max(1e-3), "r {r}");
            assert!((own[2] - r).abs() < 1e-15 * (1.0 + r));
            let det = det4(&jac);
            let want = 2.0 * r.powi(3) * q;
            assert!(
                (det - want).abs() <= 1e-9 * want.max(1e-300),
                "r {r}: {det} {want}"
            );
            if r > 0.0 {
                let dir = [(u[0] - ex) / r, (u[1] - ey) / r];
                assert!((own[0] - phi * dir[0]).abs() < 1e-12 * scale);
                assert!((own[1] - phi * dir[1]).abs() < 1e-12 * scale);
            } else {
                // Exactly at the centre: the physical root r = 0, no force direction.
                assert_eq!((own[0], own[1]), (0.0, 0.0));
            }
        }
    }

    #[test]
    fn cercle_root_solves_its_equations_with_a_positive_jacobian_through_the_centre() {
        // Scaled ring: s = 1, α = 50, η = 1e-3, centre (0.2, −0.1). Radial distances from the
        // centre itself to deep contact; at each the own unknowns from own_from_u must solve
        // the listed equations (to round-off), and the determinant of their Jacobian must be
        // BI_PLAN's ψ_f = 1 − z − 2φ(φ/α − r)/(α s²) at r, positive; 1 at the centre.
        let (s, a, eta, ex, ey) = (1.0, 50.0, 1e-3, 0.2, -0.1);
        let law = ShockLaw::Cercle {
            origin: [ex, ey],
            form: CercleForm::Secant,
        };
        for (r, _, own, jac) in ring_roots(
            law,
            s,
            a,
            eta,
            &[0.0, 1e-9, 0.3, 0.999, 1.0, 1.001, 1.5, 3.0],
        ) {
            let phi = own[2] * r;
            let z = own[3];
            let psi = 1.0 - z - 2.0 * phi * (phi / a - r) / (a * s * s);
            let det = det4(&jac);
            assert!(
                psi > 0.0 && (det / psi - 1.0).abs() < 1e-9,
                "r {r}: {det} {psi}"
            );
            if r == 0.0 {
                assert_eq!(own, vec![0.0, 0.0, eta, 0.0]);
                assert!((det - 1.0).abs() < 1e-15);
            }
        }
    }
}
