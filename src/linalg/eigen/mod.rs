//! The symmetric generalized eigenproblem K φ = ω² M φ of CALC_MODES.
//!
//! Inputs are the reduced (free-DOF) stiffness K (positive semi-definite: free-free
//! models have rigid-body modes at ω ≈ 0) and mass M (positive definite, or semi-definite
//! when some DOFs carry no mass: those give infinite frequencies, never returned).
//!
//! Two solvers, chosen by size (see [`DENSE_MAX_DOFS`]) unless [`EigenOptions::force`]:
//! - dense ([`dense`]): Cholesky reduction and a full symmetric eigensolve,
//!   O(n²) memory, every mode at once;
//! - shift-invert Lanczos ([`lanczos`]) on (K − σM)⁻¹M with one sparse LDLᵀ
//!   of K − σM ([`shift`]), O(nnz(L) + n·ncv) memory.
//!
//! The sparse path never trusts Lanczos alone to have found every mode (a single Krylov
//! sequence misses copies of multiple eigenvalues): Sylvester's inertia counts the modes in
//! the interval the answer spans, and missing ones are sought by further deflated passes.

pub mod dense;
pub mod lanczos;
pub mod norm;
pub mod shift;
pub mod sliced;
pub mod sym;

use self::dense::solve_dense;
use self::lanczos::{lanczos, LanczosParams, LanczosWork};
pub use self::norm::{largest_component_scale, ModeNorm, Normalized};
pub use self::shift::FactorKind;
use self::shift::{ShiftPattern, ShiftedFactor};
use self::sym::{norm2, SymSparse};
use crate::error::{Error, Result};
use faer::sparse::SparseColMat;
use std::f64::consts::PI;

/// Models with at most this many free DOFs use the dense solver: its O(n²) memory is
/// 18 MB at 1500 DOFs and the full eigensolve takes well under a second there, while
/// shift-invert Lanczos pays off for larger models or few modes.
pub const DENSE_MAX_DOFS: usize = 1500;

/// Shift below 0, relative to the spectral scale tr K / tr M, used when K is singular
/// (rigid-body modes): small enough to stay below the first elastic ω² of any sensible
/// model, large enough that K + δM keeps a condition number ~1e10, far from breakdown.
const RIGID_SHIFT: f64 = 1e-10;

/// The dense solver's δ in K + δM when K is singular. Every eigenvalue moves by δ, so δ
/// needs no care about the spectrum; but the eigenvalues of L⁻¹ML⁻ᵀ are μ = 1/(ω² + δ)
/// and those of the rigid-body modes, 1/δ, set the round-off of all the others:
/// relative error ≈ ε (ω² + δ)/δ. δ = 1e-2·tr K/tr M keeps that at round-off level
/// (a 5-mass free-free chain lost 2.6e-7 relative with δ = 1e-10·tr K/tr M).
const DENSE_RIGID_SHIFT: f64 = 1e-2;

/// Largest number of Lanczos passes (each one deflating the modes already found).
const MAX_PASSES: usize = 8;

/// What the factorisations and Lanczos runs of one problem share: the pattern of K − σM
/// with its symbolic factorisation (built at the first shift), and the Lanczos workspace.
#[derive(Default)]
pub(crate) struct Shared {
    pattern: Option<ShiftPattern>,
    work: LanczosWork,
}

impl Shared {
    /// The LDLᵀ of K − σM on the problem's common pattern.
    fn factor(
        &mut self,
        k: &SymSparse,
        m: &SymSparse,
        sigma: f64,
        kind: FactorKind,
    ) -> Result<ShiftedFactor> {
        if self.pattern.is_none() {
            self.pattern = Some(ShiftPattern::new(k, m, kind)?);
        }
        match &self.pattern {
            Some(p) => ShiftedFactor::from_pattern(p, sigma),
            None => Err(Error::internal("the pattern of K - σM was not built")),
        }
    }
}

/// PLUS_PETITE of more modes than twice this is computed slice by slice ([`sliced`]):
/// each slice, an interval of ω² holding about this many modes, gets its own shift and a
/// Krylov basis of ~2.4× its modes. One basis for every mode would cost O(n·nev²) in
/// orthogonalisation and hold 2·nev + 20 vectors of n (measured on a 30 000-DOF bar asked
/// for 300 modes: 42 s, and its residuals reached 1e-4); slices cost O(n·nev·slice).
/// Smaller slices orthogonalise against smaller bases and measured faster (2×10⁴-DOF bar,
/// 364 modes, 2026-12-07: the slices' time 2.62 s at 40 modes, 2.05 s at 20, best of three),
/// but they move modes from the first shift to band shifts, and the low ω² of a fine mesh
/// depend on the factorisation that found them beyond round-off: on the 10⁵-DOF bar, modes
/// 21 to 40 moved by up to 2.7e-5 relative with slices of 20 (2.8e-10 with 40), so 40 stays.
pub const SLICE_MODES: usize = 40;

/// Which modes to compute (CALC_MODES / OPTION and CALC_FREQ).
#[derive(Clone, Debug, PartialEq)]
pub enum ModeRequest {
    /// OPTION='PLUS_PETITE': the n lowest frequencies.
    Smallest { n: usize },
    /// OPTION='BANDE': every mode with f_min ≤ f ≤ f_max (Hz).
    Band { f_min: f64, f_max: f64 },
    /// OPTION='CENTRE': the n modes whose frequencies are closest to f (Hz).
    Centre { f: f64, n: usize },
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Method {
    Dense,
    Lanczos,
}

#[derive(Clone, Debug)]
pub struct EigenOptions {
    /// Force a solver (tests, benchmarks); `None` chooses by size.
    pub force: Option<Method>,
    /// Lanczos convergence tolerance on the shift-invert residual, relative to |θ|.
    pub tol: f64,
    /// Lanczos basis size (0: automatic, max(2·nev + 20, 40)).
    pub ncv: usize,
    pub max_restarts: usize,
    /// Sparse factorisation variant (tests force each one).
    pub factor: FactorKind,
    /// Largest relative residual of a mode returned; above it the solve is an error.
    /// CALC_MODES's frequencies are checked at 1e-6; a reduction basis needs only a good
    /// subspace (its matrices are projected exactly) and accepts far less accurate modes.
    pub max_residual: f64,
}

impl Default for EigenOptions {
    fn default() -> Self {
        EigenOptions {
            force: None,
            tol: 1e-12,
            ncv: 0,
            max_restarts: 300,
            factor: FactorKind::Auto,
            max_residual: 1e-6,
        }
    }
}

/// Modes sorted by ascending ω², vectors M-orthonormal (φᵀMφ = 1).
#[derive(Clone, Debug)]
pub struct ModeSet {
    pub omega2: Vec<f64>,
    pub vectors: Vec<Vec<f64>>,
    /// ‖Kφ − ω²Mφ‖ / ‖(K + s·10⁻⁶ M)φ‖ per mode, s = tr K / tr M (a spectral scale
    /// keeping the ratio meaningful for rigid-body modes, where Kφ ≈ 0).
    pub residuals: Vec<f64>,
    /// Which solver was used, for INFO=2.
    pub method: String,
}

impl ModeSet {
    pub fn frequencies(&self) -> Vec<f64> {
        self.omega2.iter().map(|&w| frequency(w)).collect()
    }
    fn empty(method: &str) -> Self {
        ModeSet {
            omega2: vec![],
            vectors: vec![],
            residuals: vec![],
            method: method.to_string(),
        }
    }
}

/// How precisely double precision determines the ω² of the mode φ of K: ε·|φ|ᵀ|K||φ| /
/// φᵀKφ, relative. The stored entries of K carry rounding errors of ε relative each (and a
/// factorisation adds errors of the same form), which move ω² by up to that much; for a
/// smooth mode of a fine mesh the stiffness terms cancel almost entirely (φᵀKφ ≪ |φ|ᵀ|K||φ|,
/// by the square of the number of elements per half wavelength for a beam) and the lowest
/// frequencies lose digits whatever the solver. Infinite when φᵀKφ ≤ 0 (rigid-body modes,
/// whose ω² is judged absolutely instead).
pub fn omega2_precision(k: &SymSparse, phi: &[f64]) -> f64 {
    let q = k.form(phi, phi);
    if q > 0.0 {
        f64::EPSILON * k.abs_form(phi) / q
    } else {
        f64::INFINITY
    }
}

/// f = √max(ω², 0) / 2π: round-off negative ω² of rigid-body modes give 0 Hz, never NaN.
pub fn frequency(omega2: f64) -> f64 {
    omega2.max(0.0).sqrt() / (2.0 * PI)
}

/// ω² of a frequency in Hz.
pub fn omega2_of(f: f64) -> f64 {
    let w = 2.0 * PI * f;
    w * w
}

/// Computes the requested modes of K φ = ω² M φ.
pub fn solve_modes(
    k: &SparseColMat<usize, f64>,
    m: &SparseColMat<usize, f64>,
    req: &ModeRequest,
    opts: &EigenOptions,
) -> Result<ModeSet> {
    let ks = SymSparse::from_faer(k, "stiffness")?;
    let ms = SymSparse::from_faer(m, "mass")?;
    solve_modes_sym(&ks, &ms, req, opts)
}

/// How many eigenvalues ω² of K φ = ω² M φ lie strictly below each value of `omega2s`
/// (Sylvester's inertia of K − σM: one LDLᵀ per value, on one symbolic pattern), without
/// computing any mode.
pub fn counts_below(
    k: &SparseColMat<usize, f64>,
    m: &SparseColMat<usize, f64>,
    omega2s: &[f64],
) -> Result<Vec<usize>> {
    let ks = SymSparse::from_faer(k, "stiffness")?;
    let ms = SymSparse::from_faer(m, "mass")?;
    let scale = spectral_scale(&ks, &ms)?;
    let mut shared = Shared::default();
    omega2s
        .iter()
        .map(|&sigma| count_below(&mut shared, &ks, &ms, sigma, scale, FactorKind::Auto))
        .collect()
}

/// Same as [`solve_modes`] on matrices already in [`SymSparse`] form.
pub fn solve_modes_sym(
    ks: &SymSparse,
    ms: &SymSparse,
    req: &ModeRequest,
    opts: &EigenOptions,
) -> Result<ModeSet> {
    let n = ks.n;
    if ms.n != n {
        return Err(Error::internal(format!(
            "stiffness has {n} DOFs but mass has {}",
            ms.n
        )));
    }
    check_request(req, n)?;
    let method = opts.force.unwrap_or(if n <= DENSE_MAX_DOFS {
        Method::Dense
    } else {
        Method::Lanczos
    });
    let scale = spectral_scale(ks, ms)?;
    let mut set = match method {
        Method::Dense => dense_modes(ks, ms, req, scale)?,
        Method::Lanczos => lanczos_modes(&mut Shared::default(), ks, ms, req, opts, scale)?,
    };
    set.residuals = set
        .omega2
        .iter()
        .zip(&set.vectors)
        .map(|(&w, v)| residual(ks, ms, w, v, scale))
        .collect();
    // A residual this large means a solve went wrong (e.g. an unstable factorisation);
    // better an error than wrong frequencies.
    if let Some((i, r)) = set
        .residuals
        .iter()
        .enumerate()
        .find(|(_, r)| r.is_nan() || **r > opts.max_residual)
    {
        return Err(Error::numerical(format!(
            "mode {} (f = {:e} Hz) has a relative residual {r:e}: the eigensolver is not accurate",
            i + 1,
            frequency(set.omega2[i])
        ))
        .hint("try another frequency band or shift"));
    }
    Ok(set)
}

fn check_request(req: &ModeRequest, n: usize) -> Result<()> {
    let bad = |msg: String, kw: &str| Err(Error::validation(msg).keyword(kw));
    match *req {
        ModeRequest::Smallest { n: nev } if nev > n => bad(
            format!("{nev} modes requested but the model has only {n} free DOFs"),
            "CALC_FREQ/NMAX_FREQ",
        ),
        ModeRequest::Centre { n: nev, .. } if nev > n => bad(
            format!("{nev} modes requested but the model has only {n} free DOFs"),
            "CALC_FREQ/NMAX_FREQ",
        ),
        ModeRequest::Centre { f, .. } if !(f.is_finite() && f >= 0.0) => bad(
            format!("the centre frequency must be finite and non-negative, got {f}"),
            "CALC_FREQ/FREQ",
        ),
        ModeRequest::Band { f_min, f_max }
            if !(f_min.is_finite() && f_max.is_finite() && f_min <= f_max && f_max >= 0.0) =>
        {
            bad(
                format!(
                    "the band needs finite frequencies with f_min <= f_max, got [{f_min}, {f_max}]"
                ),
                "CALC_FREQ/FREQ",
            )
        }
        _ => Ok(()),
    }
}

/// tr K / tr M: a typical ω² of the model, used to size tolerances and the shift.
fn spectral_scale(k: &SymSparse, m: &SymSparse) -> Result<f64> {
    let tk: f64 = k.diag().iter().map(|d| d.abs()).sum();
    let tm: f64 = m.diag().iter().map(|d| d.abs()).sum();
    if tm <= 0.0 {
        return Err(Error::numerical("the mass matrix is zero on the free DOFs")
            .hint("check the density (RHO) in DEFI_MATERIAU and the mass matrix option"));
    }
    Ok(if tk > 0.0 { tk / tm } else { 1.0 })
}

fn residual(k: &SymSparse, m: &SymSparse, omega2: f64, v: &[f64], scale: f64) -> f64 {
    let n = k.n;
    let (mut kv, mut mv) = (vec![0.0; n], vec![0.0; n]);
    k.mul(v, &mut kv);
    m.mul(v, &mut mv);
    let r: Vec<f64> = kv.iter().zip(&mv).map(|(a, b)| a - omega2 * b).collect();
    let d: Vec<f64> = kv
        .iter()
        .zip(&mv)
        .map(|(a, b)| a + 1e-6 * scale * b)
        .collect();
    let den = norm2(&d);
    if den > 0.0 {
        norm2(&r) / den
    } else {
        f64::INFINITY
    }
}

fn dense_modes(k: &SymSparse, m: &SymSparse, req: &ModeRequest, scale: f64) -> Result<ModeSet> {
    let all = solve_dense(k, m, DENSE_RIGID_SHIFT * scale)?;
    let method = if all.delta.is_nan() {
        "dense (Cholesky of M, symmetric eigensolver)".to_string()
    } else {
        let chol = if all.delta == 0.0 {
            "K".to_string()
        } else {
            format!("K + δM, δ = {:e}", all.delta)
        };
        let mut dropped = String::new();
        if all.infinite > 0 {
            dropped += &format!(
                ", {} infinite frequencies of massless DOFs dropped",
                all.infinite
            );
        }
        if all.unresolved > 0 {
            dropped += &format!(
                ", {} highest frequencies beyond double precision's reach (K too badly \
                 conditioned) dropped",
                all.unresolved
            );
        }
        format!("dense (Cholesky of {chol}, symmetric eigensolver of the inverse form{dropped})")
    };
    let pairs: Vec<(f64, Vec<f64>)> = all.omega2.into_iter().zip(all.vectors).collect();
    let chosen = select(pairs, req)?;
    let (omega2, mut vectors): (Vec<f64>, Vec<Vec<f64>>) = chosen.into_iter().unzip();
    // The eigenvector error of the inverse form is ~ε·μ_max/gap: with the tiny δ of
    // rigid-body modes, enough to spoil M-orthogonality at 1e-8. What is lost is exactly
    // the components along the other modes, which Gram–Schmidt removes.
    m_orthonormalize(&mut vectors, m);
    Ok(ModeSet {
        omega2,
        vectors,
        residuals: vec![],
        method,
    })
}

/// Gram–Schmidt in the M inner product (two passes), in place.
fn m_orthonormalize(vectors: &mut [Vec<f64>], m: &SymSparse) {
    let mut mv: Vec<Vec<f64>> = Vec::with_capacity(vectors.len());
    for i in 0..vectors.len() {
        let (done, rest) = vectors.split_at_mut(i);
        let v = &mut rest[0];
        let mut w = vec![0.0; v.len()];
        for _pass in 0..2 {
            for (u, mu) in done.iter().zip(&mv) {
                let c = sym::dot(mu, v);
                v.iter_mut().zip(u).for_each(|(a, b)| *a -= c * b);
            }
        }
        m.mul(v, &mut w);
        let nrm = sym::dot(v, &w).max(0.0).sqrt();
        if nrm > 0.0 {
            v.iter_mut().for_each(|a| *a /= nrm);
            w.iter_mut().for_each(|a| *a /= nrm);
        }
        mv.push(w);
    }
}

/// Picks the requested modes out of a set (sorted or not); returns them by ascending ω².
fn select(mut pairs: Vec<(f64, Vec<f64>)>, req: &ModeRequest) -> Result<Vec<(f64, Vec<f64>)>> {
    pairs.sort_by(|a, b| a.0.total_cmp(&b.0));
    match *req {
        ModeRequest::Smallest { n } => {
            if pairs.len() < n {
                return Err(Error::numerical(format!(
                    "only {} finite frequencies exist, {n} were requested",
                    pairs.len()
                ))
                .keyword("CALC_FREQ/NMAX_FREQ"));
            }
            pairs.truncate(n);
        }
        ModeRequest::Band { f_min, f_max } => {
            pairs.retain(|(w, _)| (f_min..=f_max).contains(&frequency(*w)));
        }
        ModeRequest::Centre { f, n } => {
            if pairs.len() < n {
                return Err(Error::numerical(format!(
                    "only {} finite frequencies exist, {n} were requested",
                    pairs.len()
                ))
                .keyword("CALC_FREQ/NMAX_FREQ"));
            }
            pairs.sort_by(|a, b| {
                (frequency(a.0) - f)
                    .abs()
                    .total_cmp(&(frequency(b.0) - f).abs())
            });
            pairs.truncate(n);
            pairs.sort_by(|a, b| a.0.total_cmp(&b.0));
        }
    }
    Ok(pairs)
}

/// Factorises K − σM, nudging σ off an eigenvalue if the factorisation breaks down.
fn factor_near(
    shared: &mut Shared,
    k: &SymSparse,
    m: &SymSparse,
    sigma: f64,
    scale: f64,
    kind: FactorKind,
) -> Result<ShiftedFactor> {
    let mut s = sigma;
    let mut last = None;
    for attempt in 0..4 {
        match shared.factor(k, m, s, kind) {
            Ok(f) => return Ok(f),
            Err(e) => last = Some(e),
        }
        let step = 1e-7 * (sigma.abs() + 1e-6 * scale) * (1 << attempt) as f64;
        s = sigma + step;
    }
    Err(last.unwrap_or_else(|| Error::internal("factorisation retry loop ran no attempt")))
}

/// Number of eigenvalues strictly below σ (Sylvester).
pub(crate) fn count_below(
    shared: &mut Shared,
    k: &SymSparse,
    m: &SymSparse,
    sigma: f64,
    scale: f64,
    kind: FactorKind,
) -> Result<usize> {
    Ok(factor_near(shared, k, m, sigma, scale, kind)?.negative_count())
}

/// One Lanczos pass with the factor of K − σM; returns (ω², φ) pairs.
#[allow(clippy::too_many_arguments)]
fn lanczos_pass(
    k: &SymSparse,
    m: &SymSparse,
    fac: &mut ShiftedFactor,
    nev: usize,
    locked: &[Vec<f64>],
    opts: &EigenOptions,
    op_count: &mut usize,
    work: &mut LanczosWork,
) -> Result<Vec<(f64, Vec<f64>)>> {
    let n = k.n;
    let ncv = if opts.ncv > 0 {
        opts.ncv
    } else {
        (2 * nev + 20).max(40)
    };
    let params = LanczosParams {
        nev,
        ncv,
        tol: opts.tol,
        max_restarts: opts.max_restarts,
        // A different start vector for every deflated pass, reproducible run to run.
        seed: 0x9E37_79B9 + locked.len() as u64,
    };
    let sigma = fac.sigma;
    let out = lanczos(n, m, |y| fac.solve_in_place(y), locked, &params, work)?;
    *op_count += out.op_count;
    Ok(out
        .theta
        .into_iter()
        .zip(out.vectors)
        .filter(|(t, _)| *t != 0.0)
        .map(|(t, v)| (sigma + 1.0 / t, v))
        .collect())
}

fn lanczos_modes(
    shared: &mut Shared,
    k: &SymSparse,
    m: &SymSparse,
    req: &ModeRequest,
    opts: &EigenOptions,
    scale: f64,
) -> Result<ModeSet> {
    if let ModeRequest::Smallest { n } = *req {
        if n > 2 * SLICE_MODES {
            // A slice boundary inside a cluster of nearly equal frequencies can defeat the
            // slices' counts; one shift with deflated passes then finds them, slowly, in a
            // Krylov basis of about 2n vectors: refused when that basis alone would not fit
            // (a 10⁶-DOF model asked for 364 modes needs 12 GB for it and was killed by the
            // system instead of stopping with a reason).
            match sliced::smallest(shared, k, m, n, opts, scale) {
                Ok(set) => return Ok(set),
                Err(e) => {
                    let bytes = one_shift_basis_bytes(k.n, n, opts.ncv);
                    if let Some((room, why)) = crate::process::memory_limit() {
                        if bytes > FALLBACK_SHARE * room {
                            return Err(Error::numerical(format!(
                                "the {n} lowest modes: spectrum slicing failed ({}), and one \
                                 Lanczos sequence for all of them would need {:.1} GB for its \
                                 Krylov basis, more than half of the {:.1} GB available {why}",
                                e.message,
                                bytes / 1e9,
                                room / 1e9
                            ))
                            .hint(
                                "ask for fewer modes at once (CALC_MODES: NMAX_FREQ, or a \
                                 BANDE; MODE_NON_LINE's REDUCTION: a lower COEF_COUPURE)",
                            ));
                        }
                    }
                }
            }
        }
    }
    one_shift_modes(shared, k, m, req, opts, scale, None)
}

/// The one-shift fallback of a failed spectrum slicing is refused above this share of the
/// memory left: its Krylov blocks are most of what it allocates, and the rest of the run
/// (the factor, the model) needs room too.
const FALLBACK_SHARE: f64 = 0.5;

/// Bytes of the Krylov basis and its M-products of one Lanczos sequence for `nev` modes of
/// an `n`-DOF problem: 2(ncv + 1) vectors of n (lanczos.rs), ncv = `ncv` or max(2·nev + 20, 40).
fn one_shift_basis_bytes(n: usize, nev: usize, ncv: usize) -> f64 {
    let ncv = if ncv > 0 { ncv } else { (2 * nev + 20).max(40) };
    2.0 * (ncv + 1) as f64 * n as f64 * std::mem::size_of::<f64>() as f64
}

/// The requested modes from one shift (and deflated passes at that shift). `band_counts`:
/// Sylvester's counts below a band's two ends when the caller has them (spectrum slicing),
/// instead of two factorisations here.
fn one_shift_modes(
    shared: &mut Shared,
    k: &SymSparse,
    m: &SymSparse,
    req: &ModeRequest,
    opts: &EigenOptions,
    scale: f64,
    band_counts: Option<(usize, usize)>,
) -> Result<ModeSet> {
    let kind = opts.factor;
    // The shift and the ω² interval [lo, hi] whose mode count must be matched.
    let mut ready: Option<ShiftedFactor> = None;
    let (sigma, method) = match *req {
        ModeRequest::Smallest { n: 0 } | ModeRequest::Centre { n: 0, .. } => {
            return Ok(ModeSet::empty("none (no mode requested)"))
        }
        ModeRequest::Smallest { .. } => {
            // σ = 0 is best when K is safely definite; with rigid-body modes K is singular
            // and σ goes slightly below 0 so K − σM stays positive definite.
            match shared.factor(k, m, 0.0, kind) {
                Ok(f) if f.negative_count() == 0 && f.min_relative_pivot() > 1e-10 => {
                    ready = Some(f);
                    (0.0, "definite stiffness")
                }
                _ => (
                    -RIGID_SHIFT * scale,
                    "singular stiffness (rigid-body modes), σ < 0",
                ),
            }
        }
        ModeRequest::Band { f_min, f_max } => {
            let lo = omega2_of(f_min.max(0.0));
            let hi = omega2_of(f_max);
            (0.5 * (lo + hi), "σ at the band centre")
        }
        ModeRequest::Centre { f, .. } => (omega2_of(f), "σ at the centre frequency"),
    };
    // A failed σ = 0 attempt of PLUS_PETITE also cost a factorisation.
    let zero_attempt = usize::from(matches!(req, ModeRequest::Smallest { .. }) && ready.is_none());
    let mut fac = match ready {
        Some(f) => f,
        None => factor_near(shared, k, m, sigma, scale, kind)?,
    };
    if matches!(req, ModeRequest::Smallest { .. }) && fac.negative_count() > 0 {
        return Err(Error::numerical(format!(
            "the stiffness matrix has {} negative eigenvalues: it is not positive semi-definite",
            fac.negative_count()
        ))
        .hint("check the boundary conditions and material data"));
    }
    // Band: how many modes to find, from the inertia at both ends.
    let band_count = match (req, band_counts) {
        (ModeRequest::Band { .. }, Some((below_lo, below_hi))) => {
            Some(below_hi.saturating_sub(below_lo))
        }
        (&ModeRequest::Band { f_min, f_max }, None) => {
            let below_hi = count_below(shared, k, m, omega2_of(f_max), scale, kind)?;
            let below_lo = if f_min > 0.0 {
                count_below(shared, k, m, omega2_of(f_min), scale, kind)?
            } else {
                0
            };
            Some(below_hi.saturating_sub(below_lo))
        }
        _ => None,
    };
    if band_count == Some(0) {
        return Ok(ModeSet::empty(&format!(
            "shift-invert Lanczos ({method}): band is empty"
        )));
    }
    let target = match *req {
        ModeRequest::Smallest { n } | ModeRequest::Centre { n, .. } => n,
        ModeRequest::Band { .. } => band_count.unwrap_or(0),
    };

    let mut found: Vec<(f64, Vec<f64>)> = Vec::new();
    let mut nev = target;
    let mut passes = 0;
    let mut op_count = 0;
    let counted_here = band_count.is_some() && band_counts.is_none();
    let mut factorizations = 1 + zero_attempt + if counted_here { 2 } else { 0 };
    loop {
        passes += 1;
        let locked: Vec<Vec<f64>> = found.iter().map(|p| p.1.clone()).collect();
        let new = lanczos_pass(
            k,
            m,
            &mut fac,
            nev,
            &locked,
            opts,
            &mut op_count,
            &mut shared.work,
        )?;
        if new.is_empty() && passes > 1 {
            break;
        }
        found.extend(new);
        // Which modes the request takes from what we have, and how many are missing.
        let missing = match *req {
            ModeRequest::Band { .. } => {
                let inside = select(found.clone(), req)?.len();
                target.saturating_sub(inside)
            }
            _ if found.len() < target => target - found.len(),
            _ => {
                let chosen = select(found.clone(), req)?;
                let (lo, hi) = span(&chosen, req);
                let lo_abs = if lo.is_finite() { lo.abs() } else { 0.0 };
                let tol = 1e-9 * hi.abs().max(lo_abs) + 1e-12 * scale;
                let count = count_below(shared, k, m, hi + tol, scale, kind)?
                    - if lo.is_finite() {
                        count_below(shared, k, m, lo - tol, scale, kind)?
                    } else {
                        0
                    };
                factorizations += if lo.is_finite() { 2 } else { 1 };
                let have = found
                    .iter()
                    .filter(|p| p.0 >= lo - tol && p.0 <= hi + tol)
                    .count();
                count.saturating_sub(have)
            }
        };
        if missing == 0 {
            break;
        }
        if passes >= MAX_PASSES {
            return Err(Error::numerical(format!(
                "shift-invert Lanczos still misses {missing} mode(s) after {passes} passes"
            ))
            .hint("multiple or very close frequencies: ask for a narrower band"));
        }
        nev = missing;
    }
    let chosen = select(found, req)?;
    if let Some(c) = band_count {
        if chosen.len() != c {
            return Err(Error::numerical(format!(
                "the band holds {c} modes (Sylvester count) but {} were found",
                chosen.len()
            ))
            .hint("a mode sits on a band edge: widen the band slightly"));
        }
    }
    let (omega2, vectors) = chosen.into_iter().unzip();
    Ok(ModeSet {
        omega2,
        vectors,
        residuals: vec![],
        method: format!(
            "shift-invert Lanczos ({method}, σ = {:e}, {passes} pass(es), {op_count} solves, \
             {factorizations} sparse LDLᵀ)",
            fac.sigma
        ),
    })
}

/// ω² interval the chosen modes span: (−∞, max] for the lowest modes, the frequency
/// window |f − f_c| ≤ d for CENTRE.
fn span(chosen: &[(f64, Vec<f64>)], req: &ModeRequest) -> (f64, f64) {
    let top = chosen.iter().map(|p| p.0).fold(f64::NEG_INFINITY, f64::max);
    match *req {
        ModeRequest::Centre { f, .. } => {
            let d = chosen
                .iter()
                .map(|p| (frequency(p.0) - f).abs())
                .fold(0.0, f64::max);
            let lo = if f - d > 0.0 {
                omega2_of(f - d)
            } else {
                f64::NEG_INFINITY
            };
            (lo, omega2_of(f + d))
        }
        _ => (f64::NEG_INFINITY, top),
    }
}

/// NORM_MODE on one mode given as faer matrices: scales `phi` in place.
pub fn normalize(
    phi: &mut [f64],
    k: &SparseColMat<usize, f64>,
    m: &SparseColMat<usize, f64>,
    norm: &ModeNorm,
) -> Result<Normalized> {
    let ks = SymSparse::from_faer(k, "stiffness")?;
    let ms = SymSparse::from_faer(m, "mass")?;
    norm::normalize(phi, &ks, &ms, norm)
}

#[cfg(test)]
mod tests;
