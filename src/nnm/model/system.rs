//! The harmonic-balance system R(X) = C + L(X) + Q(X, X) in scaled units, and its tangent.
//!
//! Unknowns X (all scaled): U (n DOFs × (2H_l+1), DOF-major), V (same), the contact unknowns
//! of each shock (each series 2H_nl+1), Ω = ω/ω_ref, γ. Equations: U' = V on 0..H_l (rows of
//! U), Ω M D V + K U + Pᵀ F + γ M V = 0 on 0..H_l (rows of V), each law's equations on
//! 0..H_nl (rows of its unknowns), and the phase condition (row of Ω): the reference DOF has
//! zero velocity at t = 0, Σ_k k·us_k = 0. One equation fewer than unknowns: a curve.
//!
//! A forced response (`Problem::forcing`, REPONSE_FORCEE_NL) is the same system with the
//! damping C V added to and the force f cos(ωt) subtracted from the rows of V, and the row
//! of Ω saying γ = 0: the force fixes the phase, so there is neither a time shift to remove
//! nor a family of orbits to unfold, and Ω is the free unknown the curve is followed in.

use crate::nnm::error::{Error, Result, Setting};
use crate::nnm::model::cosine_sampler::CosineSampler;
use crate::nnm::model::fourier::{self, Sampler};
use crate::nnm::model::law::{self, LawEqs, Var};
use crate::nnm::model::low_synth::{self, LowSynth};
use crate::nnm::model::problem::Harmonics;
use crate::nnm::model::vector;
use crate::nnm::model::workspace::{QuadWork, Workspace};
use crate::nnm::{Continuation, Problem, Settings, ShockLaw};
use faer::prelude::*;
use faer::sparse::{SparseColMat, Triplet};
use multiversion::multiversion;
use std::f64::consts::PI;

/// Size, relative to its block's largest coefficient, below which a coefficient that a
/// time-symmetric X would not have counts as round-off (`Layout::is_time_symmetric`).
/// Measured on sdnd122a's stored points: at most 3.6e-16.
const SYMMETRY_ROUND_OFF: f64 = 1e-13;

/// Whether the sine part of the series `x` (h harmonics) is round-off: at most
/// SYMMETRY_ROUND_OFF times its largest coefficient (a zero series is one).
#[multiversion(targets("x86_64+avx+avx2+fma"))]
pub fn is_cosine_series(x: &[f64], h: usize) -> bool {
    let big = x.iter().fold(0.0f64, |m, a| m.max(a.abs()));
    (1..=h).all(|k| x[fourier::is(h, k)].abs() <= SYMMETRY_ROUND_OFF * big)
}

/// Compressed columns of a scaled matrix (our own copy, scaled once).
#[derive(Clone, Debug)]
pub struct ScaledEntries {
    pub entries: Vec<(usize, usize, f64)>,
}

impl ScaledEntries {
    fn from_faer(a: &SparseColMat<usize, f64>, scale: f64) -> Self {
        let sym = a.symbolic();
        let (cp, ri, v) = (sym.col_ptr(), sym.row_idx(), a.val());
        let mut entries = Vec::with_capacity(v.len());
        for j in 0..a.ncols() {
            for p in cp[j]..cp[j + 1] {
                entries.push((ri[p], j, v[p] * scale));
            }
        }
        ScaledEntries { entries }
    }

    /// out (DOF-major blocks of `nl`) += A · x.
    pub fn mul_blocks(&self, x: &[f64], nl: usize, out: &mut [f64]) {
        for &(i, lay, a) in &self.entries {
            for j in 0..nl {
                out[i * nl + j] += a * x[lay * nl + j];
            }
        }
    }
}

/// Reference scales of the scaled equations.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Scaling {
    /// Lengths (m): the largest JEU.
    pub length: f64,
    /// Stiffness (N/m): k_ref.
    pub stiffness: f64,
    /// Mass (kg): m_ref.
    pub mass: f64,
    /// Pulsation (rad/s): √(stiffness/mass).
    pub omega: f64,
}

/// How much one step of iterative refinement may change a computed (A⁻¹)pp for it to count
/// as computed (three digits: k_ref is a scale; it enters the law only through PARA_REGUL,
/// whose effect on the results is itself ∝ PARA_REGUL). Measured on the bench's bar, clamped
/// at both ends: 1.8e-6 at 2 501 elements, 0.18 and of the wrong sign at 25 001.
const INVERSE_DIAG_REPRODUCIBLE: f64 = 1e-3;

/// (A⁻¹)pp of a symmetric matrix (K or M) at the reference DOF; None when A is singular
/// (a free structure) or (A⁻¹)pp is not positive: the caller falls back to the diagonal.
/// An error when A is regular but too ill-conditioned for (A⁻¹)pp to be computed in double
/// precision (checked by one step of iterative refinement, which leaves a well-conditioned
/// value unchanged to round-off): there the diagonal fallback would silently give another
/// k_ref, hence another law for the same PARA_REGUL.
fn inverse_diag(
    a: &SparseColMat<usize, f64>,
    p: usize,
    (symbol, what): (&str, &str),
) -> Result<Option<f64>> {
    let Ok(lu) = a.sp_lu() else {
        return Ok(None);
    };
    let n = a.nrows();
    let mut z = vec![0.0; n];
    z[p] = 1.0;
    lu.solve_in_place(MatMut::from_column_major_slice_mut(&mut z, n, 1));
    let v = z[p];
    if !v.is_finite() {
        return Ok(None);
    }
    // r = e_p − A z, then one correction A⁻¹ r.
    let mut r = vec![0.0; n];
    r[p] = 1.0;
    let sym = a.symbolic();
    let (cp, ri, vals) = (sym.col_ptr(), sym.row_idx(), a.val());
    for (j, zj) in z.iter().enumerate() {
        for k in cp[j]..cp[j + 1] {
            r[ri[k]] -= vals[k] * zj;
        }
    }
    lu.solve_in_place(MatMut::from_column_major_slice_mut(&mut r, n, 1));
    let change = r[p].abs() / v.abs();
    if change.is_nan() || change > INVERSE_DIAG_REPRODUCIBLE {
        return Err(Error::numerical(format!(
            "the {what} matrix is too ill-conditioned for ({symbol}⁻¹)pp at the reference DOF \
             (DOF {p}) to be computed in double precision: one step of iterative refinement \
             changes it by {change:.1e} (relative) from {v:.6e}"
        ))
        .setting(Setting::Shocks)
        .hint(format!(
            "the reference {what} {}_ref = 1/({symbol}⁻¹)pp (Code_Aster's scaling, \
             docs/mode_non_line.md) cannot be trusted: {}",
            symbol.to_lowercase(),
            if symbol == "K" {
                "a beam meshed with N elements in one span has a condition number growing like N⁴ \
                 (about 10¹⁷ at 25 000 POU_D_E elements); use fewer elements per span, or more supports"
            } else {
                "the mass matrix spans too many orders of magnitude (e.g. a few tiny lumped masses \
                 beside the structure's); check the masses given in AFFE_CARA_ELEM"
            }
        )));
    }
    Ok((v > 0.0).then_some(v))
}

/// The diagonal entry (p, p) of `a` (the sum of its stored entries there).
pub(in crate::nnm) fn diag(a: &SparseColMat<usize, f64>, p: usize) -> f64 {
    ScaledEntries::from_faer(a, 1.0)
        .entries
        .iter()
        .filter(|e| e.0 == p && e.1 == p)
        .map(|e| e.2)
        .sum()
}

impl Scaling {
    /// Code_Aster's scaling: displacements by the largest JEU, k_ref = 1/(K⁻¹)pp and
    /// m_ref = 1/(M⁻¹)pp at the DOF p Code_Aster takes: the LAST component of the FIRST
    /// shock (in CHOC order) that has the largest JEU (for CERCLE with NOM_CMP=('DX','DY'),
    /// DY). PARA_REGUL is scaled by k_ref, so another choice would make the same PARA_REGUL
    /// a different law. Without shocks: lengths by `amplitude` and the diagonal of K and M
    /// at DOF `p`. A singular K (free structure) falls back to the diagonal too. With laws
    /// but none with a JEU (only cubic springs, `ContactLaw::has_obstacle`): lengths by
    /// `amplitude` (the start's, COEF_AMPL times the mode's largest component, so that the
    /// scaled displacements start at 1 and β = k₃L²/k_ref is the cubic force's share at
    /// that amplitude), k_ref and m_ref as with shocks at DOF `p`.
    pub fn new(problem: &Problem, amplitude: f64, p_noshock: usize) -> Result<Scaling> {
        let largest = problem.stops().map(|s| s.gap).fold(f64::NAN, f64::max);
        let (g, p) = match problem.stops().find(|s| s.gap == largest) {
            Some(s) => (s.gap, s.dofs.last().copied().unwrap_or(0)),
            // Shocks whose JEU are all NaN: refused below.
            None if problem.stops().next().is_some() => (f64::NAN, 0),
            None => (amplitude, p_noshock),
        };
        let k = match problem.shocks.is_empty() {
            false => inverse_diag(&problem.k, p, ("K", "stiffness"))?.map(|v| 1.0 / v),
            true => None,
        }
        .unwrap_or_else(|| diag(&problem.k, p));
        let m = match problem.shocks.is_empty() {
            false => inverse_diag(&problem.m, p, ("M", "mass"))?.map(|v| 1.0 / v),
            true => None,
        }
        .unwrap_or_else(|| diag(&problem.m, p));
        if !(g.is_finite() && g > 0.0 && k.is_finite() && k > 0.0 && m.is_finite() && m > 0.0) {
            return Err(Error::input(format!(
                "cannot scale the problem (length {g:e}, stiffness {k:e}, mass {m:e} at DOF {p}); \
                 the stiffness and mass matrices must be positive at the reference DOF"
            )));
        }
        Ok(Scaling {
            length: g,
            stiffness: k,
            mass: m,
            omega: (k / m).sqrt(),
        })
    }
}

/// One shock in scaled units, with the position of its unknowns in X.
#[derive(Clone, Debug)]
pub struct ShockSys {
    /// The law, its origin in scaled units (`ShockLaw::scaled`).
    pub law: ShockLaw,
    pub dofs: Vec<usize>,
    /// JEU in scaled units.
    pub gap: f64,
    pub alpha: f64,
    pub eta: f64,
    pub eqs: LawEqs,
    pub offset: usize,
    /// The distinct variables of the quadratic terms (order of the time samples).
    pub vars: Vec<Var>,
    /// The quadratic terms grouped by (equation, first variable): Σ coef·a·b over a group is
    /// a·(Σ coef·b), one sampled product per group instead of one per term.
    pub groups: Vec<TermGroup>,
}

/// Quadratic terms of one equation that share their first variable.
#[derive(Clone, Debug)]
pub struct TermGroup {
    pub eq: usize,
    /// Index of the first variable in `ShockSys::vars`.
    pub a: usize,
    /// (index in `ShockSys::vars`, coefficient) of the second variables.
    pub b: Vec<(usize, f64)>,
}

/// The groups of `eqs.quad` over `vars` (ShockSys::groups).
fn term_groups(eqs: &LawEqs, vars: &[Var]) -> Vec<TermGroup> {
    let slot = |v: Var| vars.iter().position(|&w| w == v).unwrap_or(0);
    let mut groups: Vec<TermGroup> = Vec::new();
    for t in &eqs.quad {
        let (a, b) = (slot(t.a), slot(t.b));
        match groups.iter_mut().find(|g| g.eq == t.eq && g.a == a) {
            Some(g) => g.b.push((b, t.coef)),
            None => groups.push(TermGroup {
                eq: t.eq,
                a,
                b: vec![(b, t.coef)],
            }),
        }
    }
    groups
}

/// Time samples of one X for the sampled products (`System::quad_sum_cached`), per shock:
/// every law variable (`ShockSys::vars`), and for every term group the combination
/// Σ coef·b of its second variables. Sample-contiguous rows of `System::product_samples`.
#[derive(Clone, Debug, Default)]
pub struct Samples {
    /// Per shock: vars.len() rows, then groups.len() rows.
    shocks: Vec<Vec<f64>>,
    grid: Grid,
}

/// The instants of `Samples`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Grid {
    /// N instants over the period, for any X.
    #[default]
    Full,
    /// The n ≈ N/2 midpoints of a half period (cosine_sampler.rs), for a time-symmetric X
    /// (`Layout::is_time_symmetric`): every law variable is then even in time, and only the
    /// cosine parts are sampled (their sine parts are round-off, and dropped).
    Cosine,
}

#[derive(Clone, Copy, Debug)]
/// Where each unknown sits in X.
pub struct Layout {
    /// DOFs of the structure.
    pub n: usize,
    /// Harmonics of the displacements (NB_HARM_LINE) and of the contact unknowns (NB_HARM_NONL).
    pub h_lin: usize,
    pub h_nonl: usize,
    /// Fourier coefficients per series: 2·h_lin + 1 and 2·h_nonl + 1.
    pub n_coef_lin: usize,
    pub n_coef_nonl: usize,
    /// Unknowns in all: U, V, the contact unknowns, ω, γ.
    pub n_unk: usize,
}

impl Layout {
    pub fn u(&self, i: usize) -> usize {
        i * self.n_coef_lin
    }
    pub fn v(&self, i: usize) -> usize {
        (self.n + i) * self.n_coef_lin
    }
    pub fn omega(&self) -> usize {
        self.n_unk - 2
    }
    pub fn gamma(&self) -> usize {
        self.n_unk - 1
    }
    /// Number of equations (one fewer than unknowns).
    pub fn n_eq(&self) -> usize {
        self.n_unk - 1
    }

    /// Whether X is time-symmetric to round-off: U and the contact unknowns even in time
    /// (no sine coefficients), V odd (no cosine ones), as on a conservative motion through a
    /// state of zero velocity at t = 0, which the phase condition chooses. The system is
    /// reversible (t → −t maps a solution to a solution, U and the laws' unknowns kept, V
    /// negated), so a continuation from such a point stays on such points in exact
    /// arithmetic. Each block's other coefficients are compared with that block's largest.
    pub fn is_time_symmetric(&self, x: &[f64]) -> bool {
        let (ncl, ncn, hl, hn) = (self.n_coef_lin, self.n_coef_nonl, self.h_lin, self.h_nonl);
        let max_abs = |v: &[f64]| v.iter().fold(0.0f64, |m, a| m.max(a.abs()));
        let u = &x[..self.n * ncl];
        let v = &x[self.n * ncl..2 * self.n * ncl];
        let f = &x[2 * self.n * ncl..self.omega()];
        let (bu, bv, bf) = (max_abs(u), max_abs(v), max_abs(f));
        let small = |a: f64, big: f64| a.abs() <= SYMMETRY_ROUND_OFF * big;
        u.chunks(ncl)
            .all(|s| (1..=hl).all(|k| small(s[fourier::is(hl, k)], bu)))
            && v.chunks(ncl)
                .all(|s| small(s[0], bv) && (1..=hl).all(|k| small(s[fourier::ic(k)], bv)))
            && f.chunks(ncn)
                .all(|s| (1..=hn).all(|k| small(s[fourier::is(hn, k)], bf)))
    }

    /// The layout of X for `problem` and `settings` and the offset in X of each shock's
    /// contact unknowns, as `System::new` places them, without building a system (no
    /// scaling, matrices or FFT plan): what reading stored points needs.
    pub fn of(problem: &Problem, harmonics: impl Into<Harmonics>) -> (Layout, Vec<usize>) {
        let h = harmonics.into();
        let n = problem.k.nrows();
        let hl = h.h_lin;
        let hn = if problem.shocks.is_empty() {
            hl
        } else {
            h.h_nonl
        };
        let (nl, nn) = (fourier::len(hl), fourier::len(hn));
        let mut offset = 2 * n * nl;
        let mut offsets = Vec::with_capacity(problem.shocks.len());
        for s in &problem.shocks {
            offsets.push(offset);
            offset += s.law.n_own() * nn;
        }
        let lay = Layout {
            n,
            h_lin: hl,
            h_nonl: hn,
            n_coef_lin: nl,
            n_coef_nonl: nn,
            n_unk: offset + 2,
        };
        (lay, offsets)
    }
}

pub struct System {
    pub lay: Layout,
    pub k: ScaledEntries,
    pub m: ScaledEntries,
    /// The damping and force of a forced response (None: the autonomous problem).
    pub forced: Option<ForcedTerms>,
    pub shocks: Vec<ShockSys>,
    pub ref_dof: usize,
    pub scaling: Scaling,
    /// Samples N = fft_size(3·H_nl) (a power of two): the start's pointwise laws and the
    /// mean energy sample with it, so its size is part of their results.
    sampler: Sampler,
    /// The sampled products of `quad_sum_cached`: the smallest 5-smooth N > 3·H_nl, which
    /// makes them exact for the retained harmonics as any N > 3·H_nl does (up to 37 %
    /// fewer samples than `sampler`).
    products: Sampler,
    /// The sampled products of the series of a time-symmetric branch (`Grid::Cosine`),
    /// exact as `products` is, at about half its cost.
    cosine: CosineSampler,
    /// The displacements' samples by direct sums (low_synth.rs) on the grids of the
    /// products, when NB_HARM_LINE is small enough for them to be cheaper.
    low_full: Option<LowSynth>,
    low_cosine: Option<LowSynth>,
}

/// The damping and the force of a forced response in scaled units (`Problem::forcing`). The
/// velocity unknowns are dU/dτ with τ = ω_ref·t, so C·u̇ divided by k_ref·g_ref is
/// (C·ω_ref/k_ref)·V.
#[derive(Clone, Debug)]
pub struct ForcedTerms {
    /// C·ω_ref/k_ref.
    pub c: ScaledEntries,
    /// f/(k_ref·g_ref), one value per DOF: the cosine of harmonic 1 of the rows of V.
    pub f: Vec<f64>,
}

/// Validate the problem and settings against each other (keyword-named errors).
pub fn validate(problem: &Problem, settings: &Settings) -> Result<()> {
    // In this order: the matrices, the harmonics, the continuation's settings, the shocks.
    validate_matrices(problem)?;
    validate_forcing(problem)?;
    validate_harmonics(problem, settings.into())?;
    validate_continuation(&settings.continuation)?;
    validate_shocks(problem)
}

/// What reading a stored point needs of a problem: its matrices, its harmonic counts and
/// its shocks (not the continuation's settings, which restitution does not use).
pub fn validate_problem(problem: &Problem, harmonics: Harmonics) -> Result<()> {
    validate_matrices(problem)?;
    validate_harmonics(problem, harmonics)?;
    validate_shocks(problem)
}

fn validate_matrices(problem: &Problem) -> Result<()> {
    let n = problem.k.nrows();
    if problem.k.ncols() != n || problem.m.nrows() != n || problem.m.ncols() != n || n == 0 {
        return Err(Error::input(format!(
            "stiffness ({}×{}) and mass ({}×{}) must be square, non-empty and of the same size",
            problem.k.nrows(),
            problem.k.ncols(),
            problem.m.nrows(),
            problem.m.ncols()
        ))
        .setting(Setting::Stiffness));
    }
    if problem
        .k
        .val()
        .iter()
        .chain(problem.m.val())
        .any(|v| !v.is_finite())
    {
        return Err(
            Error::input("the stiffness or mass matrix has non-finite entries")
                .setting(Setting::Stiffness),
        );
    }
    Ok(())
}

/// The damping and the force of a forced response: of the size of K, finite, a force not
/// all zero.
fn validate_forcing(problem: &Problem) -> Result<()> {
    let Some(f) = &problem.forcing else {
        return Ok(());
    };
    let n = problem.k.nrows();
    if f.damping.nrows() != n
        || f.damping.ncols() != n
        || f.damping.val().iter().any(|v| !v.is_finite())
    {
        return Err(Error::input(format!(
            "the damping matrix must be {n}×{n} (the size of the stiffness matrix) and finite, got {}×{}",
            f.damping.nrows(),
            f.damping.ncols()
        ))
        .setting(Setting::Damping));
    }
    if f.force.len() != n
        || f.force.iter().any(|v| !v.is_finite())
        || f.force.iter().all(|&v| v == 0.0)
    {
        return Err(Error::input(format!(
            "the force must have {n} finite values (one per free DOF), not all zero; got {}",
            f.force.len()
        ))
        .setting(Setting::Force));
    }
    Ok(())
}

fn validate_harmonics(problem: &Problem, settings: Harmonics) -> Result<()> {
    if settings.h_lin == 0 {
        return Err(Error::input("NB_HARM_LINE must be at least 1").setting(Setting::HarmLine));
    }
    if !problem.shocks.is_empty() && settings.h_nonl < settings.h_lin {
        return Err(Error::input(format!(
            "NB_HARM_NONL ({}) must be at least NB_HARM_LINE ({})",
            settings.h_nonl, settings.h_lin
        ))
        .setting(Setting::HarmNonl));
    }
    Ok(())
}

fn validate_continuation(cont: &Continuation) -> Result<()> {
    if cont.order < 2 {
        return Err(Error::input("NB_ORDRE_MAN must be at least 2").setting(Setting::SeriesOrder));
    }
    if cont.n_points_per_branch == 0 {
        return Err(Error::input("NB_PAS_MAN must be at least 1").setting(Setting::StepsPerBranch));
    }
    if !(cont.prec_man > 0.0 && cont.prec_newton > 0.0) {
        return Err(Error::input("PREC_MAN and PREC_NEWTON must be positive")
            .setting(Setting::SeriesPrecision));
    }
    Ok(())
}

fn validate_shocks(problem: &Problem) -> Result<()> {
    let n = problem.k.nrows();
    for (i, s) in problem.shocks.iter().enumerate() {
        let want = s.law.n_comp();
        let ctx = |e: Error| e.hint(format!("shock number {}", i + 1));
        if s.dofs.len() != want || s.dofs.iter().any(|&d| d >= n) {
            return Err(ctx(Error::input(format!(
                "shock needs {want} component(s) among the {n} free DOFs, got {:?}",
                s.dofs
            ))
            .setting(Setting::ShockComponents)));
        }
        s.law
            .with(|l| l.validate(s.gap, s.stiffness, s.regul))
            .map_err(ctx)?;
    }
    Ok(())
}

impl System {
    pub fn new(
        problem: &Problem,
        settings: &Settings,
        scaling: Scaling,
        ref_dof: usize,
    ) -> Result<System> {
        validate(problem, settings)?;
        Self::build(problem, settings.into(), scaling, ref_dof)
    }

    /// A system built from the harmonic counts alone, for what needs no continuation
    /// settings (reading a stored point, timing a contact block).
    pub fn of_harmonics(
        problem: &Problem,
        harmonics: Harmonics,
        scaling: Scaling,
        ref_dof: usize,
    ) -> Result<System> {
        validate_problem(problem, harmonics)?;
        Self::build(problem, harmonics, scaling, ref_dof)
    }

    fn build(
        problem: &Problem,
        harmonics: Harmonics,
        scaling: Scaling,
        ref_dof: usize,
    ) -> Result<System> {
        let (lay, offsets) = Layout::of(problem, harmonics);
        let mut shocks = Vec::new();
        for (s, &offset) in problem.shocks.iter().zip(&offsets) {
            let law = s.law.scaled(scaling.length);
            let (gs, alpha) = (s.gap / scaling.length, s.stiffness / scaling.stiffness);
            let eqs = law::equations(law, gs, alpha, s.regul);
            let mut vars: Vec<Var> = Vec::new();
            for v in eqs.quad.iter().flat_map(|t| [t.a, t.b]) {
                if !vars.contains(&v) {
                    vars.push(v);
                }
            }
            let groups = term_groups(&eqs, &vars);
            shocks.push(ShockSys {
                law,
                dofs: s.dofs.clone(),
                gap: gs,
                alpha,
                eta: s.regul,
                eqs,
                offset,
                vars,
                groups,
            });
        }
        let hn = lay.h_nonl;
        let products = Sampler::new(fourier::fft_size_smooth(3 * hn));
        let cosine = CosineSampler::for_products(hn);
        let hl = lay.h_lin;
        let low_full = (2 * hl <= low_synth::MAX_ROWS_FULL).then(|| {
            let n = products.n();
            LowSynth::new(n, hl, |j| 2.0 * PI * j as f64 / n as f64)
        });
        let low_cosine = (hl <= low_synth::MAX_ROWS_HALF).then(|| {
            let n = cosine.n();
            LowSynth::cosines_only(n, hl, |j| PI * (2 * j + 1) as f64 / (2 * n) as f64)
        });
        let forced = problem.forcing.as_ref().map(|f| ForcedTerms {
            c: ScaledEntries::from_faer(&f.damping, scaling.omega / scaling.stiffness),
            f: f.force
                .iter()
                .map(|v| v / (scaling.stiffness * scaling.length))
                .collect(),
        });
        Ok(System {
            lay,
            k: ScaledEntries::from_faer(&problem.k, 1.0 / scaling.stiffness),
            m: ScaledEntries::from_faer(&problem.m, 1.0 / scaling.mass),
            forced,
            shocks,
            ref_dof,
            scaling,
            sampler: Sampler::new(fourier::fft_size(3 * hn)),
            products,
            cosine,
            low_full,
            low_cosine,
        })
    }

    /// The scratch of this system's residual, sampled products and series, sized once.
    pub fn workspace(&self) -> Workspace {
        let lay = self.lay;
        let nnl = lay.n * lay.n_coef_lin;
        let max_own = self.shocks.iter().map(|sh| sh.eqs.n_own).max().unwrap_or(0);
        Workspace {
            fft: self.products.scratch(),
            cosine: self.cosine.scratch(),
            quad: QuadWork {
                su: vec![0.0; nnl],
                sv: vec![0.0; nnl],
                w: vec![0.0; nnl],
                d: vec![0.0; lay.n_coef_lin],
                c: vec![0.0; lay.n_coef_nonl],
                acc: vec![0.0; max_own * self.products.n().max(self.cosine.n())],
            },
            pool: Vec::new(),
        }
    }

    /// Whether t → −t maps a solution to a solution (U and the laws' unknowns kept, V
    /// negated): the autonomous problem is, a damped forced response is not. Only then can
    /// a time-symmetric point be followed on time-symmetric points (`Layout::is_time_symmetric`).
    pub fn is_reversible(&self) -> bool {
        self.forced.is_none()
    }

    pub fn sampler(&self) -> &Sampler {
        &self.sampler
    }

    /// A law variable of `x` as a slice and its number of harmonics.
    fn var<'a>(&self, x: &'a [f64], sh: &ShockSys, v: Var) -> (&'a [f64], usize) {
        let lay = &self.lay;
        match v {
            Var::Own(k) => (
                &x[sh.offset + k * lay.n_coef_nonl..sh.offset + (k + 1) * lay.n_coef_nonl],
                lay.h_nonl,
            ),
            Var::U(c) => {
                let d = sh.dofs[c];
                (&x[lay.u(d)..lay.u(d) + lay.n_coef_lin], lay.h_lin)
            }
        }
    }

    /// Time samples of `x` for the sampled products (`Samples`), on the full grid.
    pub fn samples(&self, x: &[f64], ws: &mut Workspace) -> Samples {
        self.samples_on(x, Grid::Full, ws)
    }

    /// Number of instants of `grid`.
    fn grid_len(&self, grid: Grid) -> usize {
        match grid {
            Grid::Full => self.products.n(),
            Grid::Cosine => self.cosine.n(),
        }
    }

    /// Time samples of `x` on `grid` (`Grid::Cosine`: its cosine parts only).
    pub fn samples_on(&self, x: &[f64], grid: Grid, ws: &mut Workspace) -> Samples {
        let mut out = ws.take_samples();
        self.samples_into(x, grid, &mut out, ws);
        out
    }

    /// [`System::samples_on`] into `out`, whose buffers are reused (no allocation once
    /// they have their size).
    pub fn samples_into(&self, x: &[f64], grid: Grid, out: &mut Samples, work: &mut Workspace) {
        let ns = self.grid_len(grid);
        let Workspace {
            fft: ws,
            cosine: cws,
            ..
        } = work;
        let low = match grid {
            Grid::Full => self.low_full.as_ref(),
            Grid::Cosine => self.low_cosine.as_ref(),
        };
        out.grid = grid;
        out.shocks.resize_with(self.shocks.len(), Vec::new);
        for (sh, rows) in self.shocks.iter().zip(out.shocks.iter_mut()) {
            let nv = sh.vars.len();
            // Every row is written below (a group without terms is zeroed).
            rows.resize((nv + sh.groups.len()) * ns, 0.0);
            let (vs, gs) = rows.split_at_mut(nv * ns);
            for (&v, o) in sh.vars.iter().zip(vs.chunks_exact_mut(ns)) {
                let (s, h) = self.var(x, sh, v);
                match (grid, low) {
                    (_, Some(table)) if h <= table.h() => table.synth(s, h, o),
                    (Grid::Full, _) => self.products.synth_with(s, h, o, ws),
                    (Grid::Cosine, _) => self.cosine.synth_with(s, h, o, cws),
                }
            }
            for (g, o) in sh.groups.iter().zip(gs.chunks_exact_mut(ns)) {
                if g.b.is_empty() {
                    o.fill(0.0);
                }
                for (k, &(b, coef)) in g.b.iter().enumerate() {
                    let src = &vs[b * ns..(b + 1) * ns];
                    if k == 0 {
                        vector::scaled(o, coef, src);
                    } else {
                        vector::add_scaled(o, coef, src);
                    }
                }
            }
        }
    }

    /// out (length n_eq) += Σ Q(a_i, b_i).
    pub fn quad_sum(&self, pairs: &[(&[f64], &[f64])], out: &mut [f64], ws: &mut Workspace) {
        self.quad_sum_cached(pairs, None, out, ws)
    }

    /// Same, with the time samples of each pair given (`samples(a_i)`, `samples(b_i)`) so
    /// that a series of orders synthesises each term once (ANM right-hand sides).
    pub fn quad_sum_cached(
        &self,
        pairs: &[(&[f64], &[f64])],
        cache: Option<&[(&Samples, &Samples)]>,
        out: &mut [f64],
        work: &mut Workspace,
    ) {
        let lay = self.lay;
        let (n, nl, hl) = (lay.n, lay.n_coef_lin, lay.h_lin);
        // Structural rows: Ω_a D U_b (rows of U) and M (Ω_a D V_b + γ_a V_b) (rows of V),
        // linear in b: D Σ Ω_a U_b and M (D Σ Ω_a V_b + Σ γ_a V_b), one derivative each.
        let nnl = n * nl;
        {
            let QuadWork { su, sv, w, d, .. } = &mut work.quad;
            su.fill(0.0);
            sv.fill(0.0);
            w.fill(0.0);
            for (a, b) in pairs {
                let (om, ga) = (a[lay.omega()], a[lay.gamma()]);
                let (ub, vb) = (&b[lay.u(0)..lay.u(0) + nnl], &b[lay.v(0)..lay.v(0) + nnl]);
                for (x, v) in su.iter_mut().zip(ub) {
                    *x += om * v;
                }
                for ((y, z), v) in sv.iter_mut().zip(w.iter_mut()).zip(vb) {
                    *y += om * v;
                    *z += ga * v;
                }
            }
            for i in 0..n {
                let r = i * nl..(i + 1) * nl;
                fourier::deriv(&su[r.clone()], hl, d);
                for (o, v) in out[lay.u(i)..lay.u(i) + nl].iter_mut().zip(d.iter()) {
                    *o += v;
                }
                fourier::deriv(&sv[r.clone()], hl, d);
                for (o, v) in w[r].iter_mut().zip(d.iter()) {
                    *o += v;
                }
            }
            self.m.mul_blocks(w, nl, &mut out[lay.v(0)..lay.v(0) + nnl]);
        }
        if self.shocks.is_empty() {
            return;
        }
        // Every product accumulated in the time domain, one FFT back per equation: cheaper
        // than convolutions at every H_nl measured (5 to 1000; at H_nl = 50, 0.06 s against
        // 0.41 s for 40 branches of sdnd122a, release). Samples on the cosine grid serve
        // only together (one time-symmetric series); any other mix is sampled afresh.
        let uniform = |c: &[(&Samples, &Samples)]| {
            let g = c.first().map_or(Grid::Full, |p| p.0.grid);
            c.iter().all(|(a, b)| a.grid == g && b.grid == g)
        };
        match cache {
            Some(c) if uniform(c) => self.shock_products(c, out, work),
            _ => {
                // A pair (x, x) (the residual) is sampled once; the samples' buffers come
                // from the workspace's pool and go back to it.
                let mut owned: Vec<(Samples, Option<Samples>)> = Vec::with_capacity(pairs.len());
                for (a, b) in pairs {
                    let sa = self.samples(a, work);
                    let sb = (!std::ptr::eq(*a, *b)).then(|| self.samples(b, work));
                    owned.push((sa, sb));
                }
                let refs: Vec<(&Samples, &Samples)> = owned
                    .iter()
                    .map(|(a, b)| (a, b.as_ref().unwrap_or(a)))
                    .collect();
                self.shock_products(&refs, out, work);
                drop(refs);
                work.recycle_samples(
                    owned
                        .into_iter()
                        .flat_map(|(a, b)| std::iter::once(a).chain(b)),
                );
            }
        }
    }

    /// out (the rows of the contact unknowns) += the sampled products of `cache`, one
    /// transform back per equation; every pair on one grid.
    fn shock_products(
        &self,
        cache: &[(&Samples, &Samples)],
        out: &mut [f64],
        work: &mut Workspace,
    ) {
        let lay = self.lay;
        let grid = cache.first().map_or(Grid::Full, |p| p.0.grid);
        let ns = self.grid_len(grid);
        let Workspace {
            fft: ws,
            cosine: cws,
            quad: QuadWork { c, acc, .. },
            ..
        } = work;
        for (k, sh) in self.shocks.iter().enumerate() {
            let nv = sh.vars.len();
            let acc = &mut acc[..sh.eqs.n_own * ns];
            acc.fill(0.0);
            for (gi, g) in sh.groups.iter().enumerate() {
                let row = &mut acc[g.eq * ns..(g.eq + 1) * ns];
                accumulate_products(row, cache, k, g.a * ns, (nv + gi) * ns);
            }
            for (e, s) in acc.chunks_exact_mut(ns).enumerate() {
                match grid {
                    Grid::Full => self.products.analyse_with(s, lay.h_nonl, c, ws),
                    Grid::Cosine => self.cosine.analyse_with(s, lay.h_nonl, c, cws),
                }
                let o = sh.offset + e * lay.n_coef_nonl;
                for (y, v) in out[o..o + lay.n_coef_nonl].iter_mut().zip(c.iter()) {
                    *y += v;
                }
            }
        }
    }

    /// ‖|K||U|‖: the size of the stiffness terms of the velocity equations at `x` (the
    /// componentwise absolute values, what bounds their round-off).
    pub fn stiffness_term_norm(&self, x: &[f64]) -> f64 {
        let lay = self.lay;
        let nl = lay.n_coef_lin;
        let mut t = vec![0.0; lay.n * nl];
        for &(i, c, a) in &self.k.entries {
            let a = a.abs();
            for j in 0..nl {
                t[i * nl + j] += a * x[lay.u(c) + j].abs();
            }
        }
        t.iter().map(|v| v * v).sum::<f64>().sqrt()
    }

    /// R(X) = C + L(X) + Q(X, X), length n_eq.
    pub fn residual(&self, x: &[f64], ws: &mut Workspace) -> Vec<f64> {
        let mut r = vec![0.0; self.lay.n_eq()];
        self.residual_into(x, &mut r, ws);
        r
    }

    /// [`System::residual`] into `r` (length n_eq), overwritten.
    pub fn residual_into(&self, x: &[f64], r: &mut [f64], ws: &mut Workspace) {
        let lay = self.lay;
        let (n, nl, hl, hn, nn) = (
            lay.n,
            lay.n_coef_lin,
            lay.h_lin,
            lay.h_nonl,
            lay.n_coef_nonl,
        );
        r.fill(0.0);
        self.quad_sum(&[(x, x)], r, ws);
        for i in 0..n {
            for j in 0..nl {
                r[lay.u(i) + j] -= x[lay.v(i) + j];
            }
        }
        self.k
            .mul_blocks(&x[0..n * nl], nl, &mut r[lay.v(0)..lay.v(0) + n * nl]);
        for sh in &self.shocks {
            for &(c, v) in &sh.eqs.forces {
                let (d, o) = (sh.dofs[c], sh.offset + v * nn);
                for j in 0..nl {
                    if let Some(t) = fourier::map_index(j, hl, hn) {
                        r[lay.v(d) + j] += x[o + t];
                    }
                }
            }
            for t in &sh.eqs.lin {
                let (s, h) = self.var(x, sh, t.var);
                let o = sh.offset + t.eq * nn;
                for (j, &v) in s.iter().enumerate() {
                    if let Some(p) = fourier::map_index(j, h, hn) {
                        r[o + p] += t.coef * v;
                    }
                }
            }
            for &(e, c) in &sh.eqs.cst {
                r[sh.offset + e * nn] += c;
            }
        }
        match &self.forced {
            None => {
                r[lay.omega()] = (1..=hl)
                    .map(|k| k as f64 * x[lay.u(self.ref_dof) + fourier::is(hl, k)])
                    .sum();
            }
            Some(fc) => {
                fc.c.mul_blocks(
                    &x[lay.v(0)..lay.v(0) + n * nl],
                    nl,
                    &mut r[lay.v(0)..lay.v(0) + n * nl],
                );
                for (i, f) in fc.f.iter().enumerate() {
                    r[lay.v(i) + fourier::ic(1)] -= f;
                }
                r[lay.omega()] = x[lay.gamma()];
            }
        }
    }

    /// Triplets of the square bordered tangent [dR/dX(x0); borderᵀ]. The pattern depends
    /// only on the layout (zeros are kept), so the symbolic factorisation can be reused.
    pub fn tangent(&self, x0: &[f64], border: &[f64]) -> Vec<Triplet<usize, usize, f64>> {
        let lay = self.lay;
        let (n, nl, hl, hn, nn) = (
            lay.n,
            lay.n_coef_lin,
            lay.h_lin,
            lay.h_nonl,
            lay.n_coef_nonl,
        );
        let (om, ga) = (x0[lay.omega()], x0[lay.gamma()]);
        let mut t = Vec::new();
        let mut push = |r: usize, c: usize, v: f64| t.push(Triplet::new(r, c, v));
        let mut d = vec![0.0; nl];
        let mut mdv = vec![0.0; n * nl];
        let mut mv = vec![0.0; n * nl];
        let mut dv = vec![0.0; n * nl];
        for i in 0..n {
            fourier::deriv(
                &x0[lay.v(i)..lay.v(i) + nl],
                hl,
                &mut dv[i * nl..(i + 1) * nl],
            );
        }
        self.m.mul_blocks(&dv, nl, &mut mdv);
        self.m
            .mul_blocks(&x0[lay.v(0)..lay.v(0) + n * nl], nl, &mut mv);
        for i in 0..n {
            let (ru, cu, cv) = (lay.u(i), lay.u(i), lay.v(i));
            fourier::deriv(&x0[cu..cu + nl], hl, &mut d);
            for j in 0..nl {
                push(ru + j, cv + j, -1.0);
                push(ru + j, lay.omega(), d[j]);
                push(lay.v(i) + j, lay.omega(), mdv[i * nl + j]);
                push(lay.v(i) + j, lay.gamma(), mv[i * nl + j]);
            }
            for k in 1..=hl {
                let kf = k as f64;
                push(ru + fourier::ic(k), cu + fourier::is(hl, k), om * kf);
                push(ru + fourier::is(hl, k), cu + fourier::ic(k), -om * kf);
            }
        }
        for &(i, c, a) in &self.k.entries {
            for j in 0..nl {
                push(lay.v(i) + j, lay.u(c) + j, a);
            }
        }
        for &(i, c, a) in &self.m.entries {
            let (r, cv) = (lay.v(i), lay.v(c));
            for j in 0..nl {
                push(r + j, cv + j, ga * a);
            }
            for k in 1..=hl {
                let kf = k as f64;
                push(r + fourier::ic(k), cv + fourier::is(hl, k), om * kf * a);
                push(r + fourier::is(hl, k), cv + fourier::ic(k), -om * kf * a);
            }
        }
        for sh in &self.shocks {
            for &(c, v) in &sh.eqs.forces {
                let (dd, o) = (sh.dofs[c], sh.offset + v * nn);
                for j in 0..nl {
                    if let Some(p) = fourier::map_index(j, hl, hn) {
                        push(lay.v(dd) + j, o + p, 1.0);
                    }
                }
            }
            // Blocks (equation, variable): multiplier series accumulated from the terms.
            let mut blocks: Vec<((usize, Var), Vec<f64>)> = Vec::new();
            let mut add = |key: (usize, Var), s: &[f64], h: usize, coef: f64| {
                let idx = match blocks.iter().position(|b| b.0 == key) {
                    Some(i) => i,
                    None => {
                        blocks.push((key, vec![0.0; nn]));
                        blocks.len() - 1
                    }
                };
                for (j, &v) in s.iter().enumerate() {
                    if let Some(p) = fourier::map_index(j, h, hn) {
                        blocks[idx].1[p] += coef * v;
                    }
                }
            };
            for tm in &sh.eqs.quad {
                let (sa, ha) = self.var(x0, sh, tm.a);
                let (sb, hb) = self.var(x0, sh, tm.b);
                add((tm.eq, tm.a), sb, hb, tm.coef);
                add((tm.eq, tm.b), sa, ha, tm.coef);
            }
            for tm in &sh.eqs.lin {
                add((tm.eq, tm.var), &[1.0], 0, tm.coef);
            }
            for ((e, v), mult) in &blocks {
                let (hx, col0) = match *v {
                    Var::Own(k) => (hn, sh.offset + k * nn),
                    Var::U(c) => (hl, lay.u(sh.dofs[c])),
                };
                let op = fourier::mul_operator(mult, hn, hx, hn);
                let row0 = sh.offset + e * nn;
                for j in 0..fourier::len(hx) {
                    for r in 0..nn {
                        push(row0 + r, col0 + j, op[j * nn + r]);
                    }
                }
            }
        }
        match &self.forced {
            None => {
                for k in 1..=hl {
                    push(
                        lay.omega(),
                        lay.u(self.ref_dof) + fourier::is(hl, k),
                        k as f64,
                    );
                }
            }
            Some(fc) => {
                for &(i, c, a) in &fc.c.entries {
                    for j in 0..nl {
                        push(lay.v(i) + j, lay.v(c) + j, a);
                    }
                }
                push(lay.omega(), lay.gamma(), 1.0);
            }
        }
        for (c, &b) in border.iter().enumerate() {
            push(lay.n_eq(), c, b);
        }
        t
    }
}

/// Number of unknowns of `x` for this problem and these settings.
pub fn unknown_count(problem: &Problem, settings: &Settings) -> usize {
    Layout::of(problem, settings).0.n_unk
}

/// row += Σ_pairs a·b, a the samples at `ia` of each pair's first member (shock `k`), b
/// those at `ib` of its second, row.len() samples each.
#[multiversion(targets("x86_64+avx+avx2+fma"))]
fn accumulate_products<'s>(
    row: &mut [f64],
    pairs: &[(&'s Samples, &'s Samples)],
    k: usize,
    ia: usize,
    ib: usize,
) {
    let ns = row.len();
    let factors = |p: &(&'s Samples, &'s Samples)| -> (&'s [f64], &'s [f64]) {
        let (a, b) = (&p.0.shocks[k], &p.1.shocks[k]);
        (&a[ia..ia + ns], &b[ib..ib + ns])
    };
    // Four products per pass: the row is loaded and stored a quarter as often (the ANM's
    // right-hand sides sum up to NB_ORDRE_MAN pairs).
    let mut quads = pairs.chunks_exact(4);
    for q in &mut quads {
        let [(a0, b0), (a1, b1), (a2, b2), (a3, b3)] = [
            factors(&q[0]),
            factors(&q[1]),
            factors(&q[2]),
            factors(&q[3]),
        ];
        for (i, o) in row.iter_mut().enumerate() {
            *o += (a0[i] * b0[i] + a1[i] * b1[i]) + (a2[i] * b2[i] + a3[i] * b3[i]);
        }
    }
    for pair in quads.remainder() {
        let (a, b) = factors(pair);
        for ((o, p), q) in row.iter_mut().zip(a).zip(b) {
            *o += p * q;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn matrix(rows: &[[f64; 2]; 2]) -> SparseColMat<usize, f64> {
        let t: Vec<Triplet<usize, usize, f64>> = (0..2)
            .flat_map(|i| (0..2).map(move |j| (i, j)))
            .map(|(i, j)| Triplet::new(i, j, rows[i][j]))
            .collect();
        SparseColMat::try_new_from_triplets(2, 2, &t).unwrap()
    }

    /// Q diag(1, λ₂) Qᵀ with Q the rotation by θ.
    fn rotated(theta: f64, l2: f64) -> SparseColMat<usize, f64> {
        let (c, s) = (theta.cos(), theta.sin());
        matrix(&[
            [c * c + l2 * s * s, c * s * (1.0 - l2)],
            [c * s * (1.0 - l2), s * s + l2 * c * c],
        ])
    }

    #[test]
    fn inverse_diagonal_of_a_well_conditioned_matrix_is_exact() {
        // (A⁻¹)₀₀ = c² + s²/λ₂ for A = Q diag(1, λ₂) Qᵀ.
        let (theta, l2) = (0.3_f64, 1e-3);
        let exact = theta.cos().powi(2) + theta.sin().powi(2) / l2;
        let v = inverse_diag(&rotated(theta, l2), 0, ("K", "stiffness"))
            .unwrap()
            .unwrap();
        // cond 1e3: a few ulps times the condition number.
        assert!((v - exact).abs() <= 1e-12 * exact, "{v} against {exact}");
    }

    /// Stiffness of a clamped–clamped Euler–Bernoulli beam of length 1 in `elements` equal
    /// Hermite elements, unknowns (deflection, rotation) of the inner nodes.
    fn clamped_beam(elements: usize, ei: f64) -> SparseColMat<usize, f64> {
        let h = 1.0 / elements as f64;
        let k = ei / h.powi(3);
        let ke = [
            [12.0, 6.0 * h, -12.0, 6.0 * h],
            [6.0 * h, 4.0 * h * h, -6.0 * h, 2.0 * h * h],
            [-12.0, -6.0 * h, 12.0, -6.0 * h],
            [6.0 * h, 2.0 * h * h, -6.0 * h, 4.0 * h * h],
        ];
        let mut t = Vec::new();
        for e in 0..elements {
            // Global unknown of local i: node e + i/2 (node 0 and the last are clamped).
            let dof = |i: usize| {
                let node = e + i / 2;
                (node >= 1 && node < elements).then(|| 2 * (node - 1) + i % 2)
            };
            for (a, row) in ke.iter().enumerate() {
                for (b, v) in row.iter().enumerate() {
                    if let (Some(r), Some(c)) = (dof(a), dof(b)) {
                        t.push(Triplet::new(r, c, k * v));
                    }
                }
            }
        }
        let n = 2 * (elements - 1);
        SparseColMat::try_new_from_triplets(n, n, &t).unwrap()
    }

    #[test]
    fn the_flexibility_of_a_clamped_beam_is_its_closed_form() {
        // Hermite elements are nodally exact for point loads: at a from one end (b = 1 − a),
        // the deflection under a unit load is a³b³ / (3 EI), L = 1.
        let (elements, ei) = (300, 228.0);
        let node = elements / 3;
        let (a, b) = (
            node as f64 / elements as f64,
            1.0 - node as f64 / elements as f64,
        );
        let exact = a.powi(3) * b.powi(3) / (3.0 * ei);
        let k = clamped_beam(elements, ei);
        let v = inverse_diag(&k, 2 * (node - 1), ("K", "stiffness"))
            .unwrap()
            .unwrap();
        // cond ∝ elements⁴ ≈ 1e10 here: ε times that, with margin.
        assert!((v - exact).abs() <= 1e-5 * exact, "{v} against {exact}");
    }

    #[test]
    fn a_beam_beyond_double_precision_is_refused_not_rescaled() {
        // 25 000 elements in one span: cond ∝ 25 000⁴ ≈ 4e17, no digit of (K⁻¹)pp is left
        // (the bench's bar: 1.8e-1 change by one refinement step, of the wrong sign).
        let elements = 25_000;
        let k = clamped_beam(elements, 228.0);
        let err = inverse_diag(&k, 2 * (elements / 3 - 1), ("K", "stiffness")).unwrap_err();
        assert!(
            err.message.contains("too ill-conditioned"),
            "{}",
            err.message
        );
        assert!(err.message.contains("(K⁻¹)pp"), "{}", err.message);
        let hint = err.hint.unwrap_or_default();
        assert!(
            hint.contains("k_ref") && hint.contains("per span"),
            "{hint}"
        );
        // The same matrix as a mass matrix: the hint names m_ref and the masses, not K.
        let err = inverse_diag(&k, 2 * (elements / 3 - 1), ("M", "mass")).unwrap_err();
        assert!(err.message.contains("(M⁻¹)pp"), "{}", err.message);
        let hint = err.hint.unwrap_or_default();
        assert!(
            hint.contains("m_ref") && hint.contains("AFFE_CARA_ELEM") && !hint.contains("k_ref"),
            "{hint}"
        );
    }

    #[test]
    fn a_singular_matrix_falls_back_to_the_diagonal() {
        let r = inverse_diag(&matrix(&[[1.0, 1.0], [1.0, 1.0]]), 0, ("K", "stiffness"));
        assert!(matches!(r, Ok(None)), "{r:?}");
    }

    /// The sampled products of symmetric terms on the cosine grid equal those on the full
    /// grid, to round-off (1e-13 of the largest: sums of a few hundred products of size
    /// ≤ 1), for every law; a mix of grids is sampled afresh on the full grid and gives the
    /// full result exactly.
    #[test]
    fn cosine_grid_products_equal_the_full_grid_ones() {
        use crate::nnm::{CercleForm, ShockLaw};
        for law in [
            ShockLaw::Plan,
            ShockLaw::BiPlan,
            ShockLaw::Cercle {
                origin: [0.0, 0.0],
                form: CercleForm::Secant,
            },
            ShockLaw::Cercle {
                origin: [0.0, 0.0],
                form: CercleForm::Radial,
            },
        ] {
            let (sys, _) = crate::nnm::analysis::route_timing::system_and_point(law, 40).unwrap();
            let lay = sys.lay;
            let term = |seed: usize| -> Vec<f64> {
                let mut x: Vec<f64> = (0..lay.n_unk)
                    .map(|i| (((i + seed) * 7919) % 101) as f64 / 101.0 - 0.5)
                    .collect();
                for d in 0..lay.n {
                    for k in 1..=lay.h_lin {
                        x[lay.u(d) + fourier::is(lay.h_lin, k)] = 0.0;
                    }
                }
                for sh in &sys.shocks {
                    for o in 0..sh.eqs.n_own {
                        for k in 1..=lay.h_nonl {
                            x[sh.offset + o * lay.n_coef_nonl + fourier::is(lay.h_nonl, k)] = 0.0;
                        }
                    }
                }
                x
            };
            let (a, b) = (term(1), term(5));
            let pairs: Vec<(&[f64], &[f64])> = vec![(&a, &b), (&b, &a), (&a, &a)];
            let mut ws = sys.workspace();
            let mut want = vec![0.0; lay.n_eq()];
            sys.quad_sum(&pairs, &mut want, &mut ws);
            let (ca, cb) = (
                sys.samples_on(&a, Grid::Cosine, &mut ws),
                sys.samples_on(&b, Grid::Cosine, &mut ws),
            );
            let cache = [(&ca, &cb), (&cb, &ca), (&ca, &ca)];
            let mut got = vec![0.0; lay.n_eq()];
            sys.quad_sum_cached(&pairs, Some(&cache), &mut got, &mut ws);
            let scale = want.iter().fold(0.0f64, |m, v| m.max(v.abs()));
            for (i, (g, w)) in got.iter().zip(&want).enumerate() {
                assert!(
                    (g - w).abs() <= 1e-13 * scale,
                    "{law:?} row {i}: {g} vs {w}"
                );
            }
            let fa = sys.samples(&a, &mut ws);
            let mixed = [(&fa, &cb), (&cb, &ca), (&ca, &ca)];
            let mut again = vec![0.0; lay.n_eq()];
            sys.quad_sum_cached(&pairs, Some(&mixed), &mut again, &mut ws);
            assert_eq!(again, want, "{law:?}: a mix of grids");
        }
    }

    /// The system is read-only once built: two threads share one, each with its own
    /// workspace, and get the residual a fresh workspace gives, to the bit; a workspace
    /// whose buffers (and pool of samples) served other points first gives it too.
    #[test]
    fn a_shared_system_with_reused_workspaces_gives_the_same_residual() {
        use crate::nnm::{CercleForm, ShockLaw};
        fn shareable<T: Sync + Send>(_: &T) {}
        let law = ShockLaw::Cercle {
            origin: [0.1, 0.0],
            form: CercleForm::Secant,
        };
        let (sys, x) = crate::nnm::analysis::route_timing::system_and_point(law, 40).unwrap();
        shareable(&sys);
        let fresh = sys.residual(&x, &mut sys.workspace());
        let other: Vec<f64> = x.iter().map(|v| 0.7 * v + 0.01).collect();
        let per_thread: Vec<Vec<f64>> = std::thread::scope(|scope| {
            let runs: Vec<_> = (0..2)
                .map(|_| {
                    scope.spawn(|| {
                        let mut ws = sys.workspace();
                        let mut r = vec![0.0; sys.lay.n_eq()];
                        sys.residual_into(&other, &mut r, &mut ws);
                        sys.residual_into(&x, &mut r, &mut ws);
                        r
                    })
                })
                .collect();
            runs.into_iter()
                .map(|h| h.join().expect("a residual thread panicked"))
                .collect()
        });
        assert!(fresh.iter().any(|v| *v != 0.0));
        for r in per_thread {
            assert_eq!(r, fresh);
        }
    }
}
