//! The contact block of one shock in the tangent, solved by its structure.
//!
//! A law's equations, linearised at X0, read A_ff δF + A_fu δu = r_f, with A_ff the
//! n_own × n_own array of truncated multiplication operators x ↦ Trunc_{H_nl}(J_ek(t)·x),
//! J(t) the pointwise Jacobian of the law's equations with respect to its own unknowns, and
//! A_fu the same with respect to the displacement components of the shock (H_l harmonics,
//! zero-padded). Everything is derived from the generic law description (`LawEqs`: constant,
//! linear and quadratic terms), never from the law's name.
//!
//! Three ways to solve with A_ff, chosen once per shock from a cost model:
//! - **Dense**: A_ff assembled ((n_own·(2H_nl+1))², from the Fourier series of J) and
//!   factorised by LU: cheap when the block is small.
//! - **Krylov**: GMRES on A_ff applied by FFT (N > 3H_nl samples make the truncated product
//!   exact), right-preconditioned by P = Trunc(J(t)⁻¹ ·), the pointwise inverse. A_ff P is
//!   the identity plus a perturbation whose spectrum is clustered with a handful of
//!   outliers, so GMRES converges in about ten iterations at any H_nl, each costing a few
//!   real FFTs: O(H_nl log H_nl) per solve instead of O(H_nl²), and no O(H_nl³)
//!   factorisation. If a Krylov solve stagnates (J(t) singular somewhere, off the physical
//!   root of a law) the block falls back to the dense route when that fits in memory.
//! - **Toeplitz** (laws with one own unknown, e.g. PLAN): A_ff is then a Toeplitz matrix
//!   in complex coefficients, and every solve with it follows exactly from one column of
//!   its inverse by a Toeplitz Bezoutian formula (toeplitz.rs). That column comes from two
//!   Krylov solves per factorisation (one per parity on the half period for a
//!   time-symmetric block, parity_block.rs); every further solve (W's columns, the
//!   right-hand sides) is then six real FFTs of about 2H_nl points, exact to round-off.
//!   W's columns are checked together by the residual of one weighted sum of them, and
//!   each on its own (refined, or handed to GMRES) only if that fails; when the check
//!   passes at the first try, the right-hand sides' solves with the same inverse are taken
//!   unchecked, else each is checked too.
//!
//! The structure sees the block only through W = A_ff⁻¹ A_fu (m = n_comp·(2H_l+1)
//! columns: one solve each per factorisation) and one solve A_ff⁻¹ r_f per right-hand side.

use crate::nnm::error::{Error, Result};
use crate::nnm::model::fourier::{self, FftScratch, Sampler};
use crate::nnm::model::law::{LawEqs, Var};
use crate::nnm::model::system::{is_cosine_series, Layout, ShockSys};
use crate::nnm::solve::dense_lu::{try_zeroed, DenseLu};
use crate::nnm::solve::gmres::{self, Gmres, Preconditioned};
use crate::nnm::solve::parity_block::{Parity, ParityBlock};
use crate::nnm::solve::toeplitz::ToeplitzInverse;

/// How a shock's block is solved.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Method {
    Dense,
    Krylov,
    Toeplitz,
}

/// Relative residual asked of each Krylov solve: the dense LU's accuracy, so that results
/// do not depend on the route (gmres.rs adds the backward-error floor).
const KRYLOV_RTOL: f64 = 1e-14;
/// Krylov cycle length and number of cycles (observed: 5–15 iterations per solve).
const KRYLOV_CYCLE: usize = 40;
const KRYLOV_CYCLES: usize = 4;
/// Largest block dimension the dense route (chosen or fallback) may take: 2.1e7 values,
/// 170 MB.
const DENSE_MAX_DIM: usize = 4600;

/// Cost model of one factorisation followed by `rhs` solves, in units of one dense flop.
/// Krylov: per solve `ITER_GUESS` iterations of 2 operator applications (n_own inverse and
/// n_own forward real FFTs of N samples each, ~`FFT_FLOPS`·N·log₂N, and the pointwise
/// products) plus the Gram-Schmidt work; dense: (2/3)d³ + 2d²·(solves). `KRYLOV_PENALTY`
/// is the measured ratio of the time of one Krylov flop-equivalent to one dense LU flop
/// (scattered FFT butterflies against blocked LU kernels); `aster-nl bench` prints the
/// crossover this model gives and the measured one.
const ITER_GUESS: f64 = 10.0;
const FFT_FLOPS: f64 = 2.5;
pub const KRYLOV_PENALTY: f64 = 4.0;

/// Toeplitz: two Krylov solves, then per solve six complex FFTs of N' ≥ 2nn − 1 (twice a
/// real one's flops) and one operator application (the residual check). These are the
/// costs of the Gohberg–Semencul solves the route used before its Bezoutian form, about
/// twice what a solve now costs; they are kept on purpose: the route is measured 2–10×
/// faster than the dense LU from H_nl 10 to 160 (`aster-nl bench --only routes`), but on
/// stiff stops it leaves AMOR_FICTIF one to two orders above what the dense LU leaves
/// (tests/hard_cases.rs: 2.4e-8 against ≤ 1e-9 on the 20-mass chain, 9.9e-11 against
/// ≤ 1e-12 at RIGI_NOR = 1e8), so the crossover stays where these constants put it
/// (docs/performance_history.md, fifth round).
pub fn cost(method: Method, n_own: usize, nn: usize, ns: usize, solves: usize) -> f64 {
    let d = (n_own * nn) as f64;
    let s = solves as f64;
    let nsf = ns as f64;
    let apply =
        2.0 * n_own as f64 * FFT_FLOPS * nsf * nsf.log2() + 2.0 * (n_own * n_own) as f64 * nsf;
    let per_iter = 2.0 * apply + 4.0 * ITER_GUESS * d;
    match method {
        Method::Dense => 2.0 / 3.0 * d * d * d + 2.0 * d * d * s,
        Method::Krylov => KRYLOV_PENALTY * s * ITER_GUESS * per_iter,
        Method::Toeplitz => {
            let nf = fourier::fft_size_smooth(2 * nn) as f64;
            let gs = 6.0 * 2.0 * FFT_FLOPS * nf * nf.log2() + 16.0 * nf;
            KRYLOV_PENALTY * (2.0 * ITER_GUESS * per_iter + s * (gs + apply))
        }
    }
}

/// The route the cost model picks for a block, given the solves made per factorisation.
pub fn choose(n_own: usize, nn: usize, ns: usize, solves: usize) -> Method {
    let d = n_own * nn;
    let mut best = (Method::Krylov, cost(Method::Krylov, n_own, nn, ns, solves));
    if n_own == 1 {
        let c = cost(Method::Toeplitz, n_own, nn, ns, solves);
        if c < best.1 {
            best = (Method::Toeplitz, c);
        }
    }
    if d <= DENSE_MAX_DIM && cost(Method::Dense, n_own, nn, ns, solves) <= best.1 {
        return Method::Dense;
    }
    best.0
}

/// Reals held by one shock's block (route chosen or fallback), from its sizes alone, in
/// `f64` so that absurd sizes give huge values, never an overflow: the Krylov basis and
/// work vectors, W (d × m), the pointwise Jacobians, their inverses and the samples
/// (N ≈ 3H_nl instants), and the dense block (d²) where the dense route may be taken
/// (d ≤ `DENSE_MAX_DIM`). `nn` = 2H_nl+1, `nl` = 2H_l+1. Used by `budget`.
pub fn block_reals(n_own: f64, n_comp: f64, nn: f64, nl: f64) -> f64 {
    let d = n_own * nn;
    let m = n_comp * nl;
    let ns = 1.5 * nn + 8.0;
    let cycle = KRYLOV_CYCLE as f64;
    let krylov = (cycle + 4.0) * d + (cycle + 1.0) * (cycle + 5.0);
    let samples = ns * (2.0 * n_own * n_own + n_own * n_comp + 3.0 * n_own + 2.0);
    let dense = if d <= DENSE_MAX_DIM as f64 {
        d * d
    } else {
        0.0
    };
    // The Toeplitz route (one own unknown): seven complex vectors of N' ≈ 2nn, the two
    // generator solves and the residual.
    let toeplitz = if n_own == 1.0 {
        28.0 * nn + 4.0 * d
    } else {
        0.0
    };
    krylov + d * m + samples + dense + 3.0 * d + toeplitz
}

/// Flops of W and `solves` further solves of one block whose size is given in `f64`
/// (`budget`): the cheaper of the two routes of [`cost`], with N ≈ 3H_nl samples.
pub fn solve_flops(n_own: f64, nn: f64, solves: f64) -> f64 {
    let d = n_own * nn;
    let dense = 2.0 / 3.0 * d * d * d + 2.0 * d * d * solves;
    let ns = 1.5 * nn + 8.0;
    let apply = 2.0 * n_own * FFT_FLOPS * ns * ns.log2() + 2.0 * n_own * n_own * ns;
    let per_iter = 2.0 * apply + 4.0 * ITER_GUESS * d;
    let krylov = KRYLOV_PENALTY * solves * ITER_GUESS * per_iter;
    let fast = if n_own == 1.0 {
        let nf = 2.0 * nn;
        let gs = 12.0 * FFT_FLOPS * nf * nf.log2() + 16.0 * nf;
        krylov.min(KRYLOV_PENALTY * (2.0 * ITER_GUESS * per_iter + solves * (gs + apply)))
    } else {
        krylov
    };
    if d <= DENSE_MAX_DIM as f64 {
        dense.min(fast)
    } else {
        fast
    }
}

/// The pointwise Jacobians of one law at the samples of one period, and the operators
/// built on them (the Krylov operator and its preconditioner).
struct Pointwise {
    sampler: Sampler,
    ws: FftScratch,
    ns: usize,
    n_own: usize,
    n_comp: usize,
    h_nonl: usize,
    h_lin: usize,
    n_coef_nonl: usize,
    /// J(t) w.r.t. the own unknowns, sample-major: [t][e·n_own + k].
    jac: Vec<f64>,
    /// J(t) w.r.t. the displacement components: [t][e·n_comp + c].
    jac_u: Vec<f64>,
    /// J(t)⁻¹: [t][k·n_own + e].
    inv: Vec<f64>,
    /// J and J⁻¹ entry-major, [e·n_own + k][t]: what `mul` streams through, so that its
    /// inner loop runs over contiguous samples (measured: the sample-major loop was 30 % of
    /// a 3-mass chain's ring run, docs/performance.md).
    jac_t: Vec<f64>,
    inv_t: Vec<f64>,
    /// Samples, variable-major [k][t]: inputs and outputs of the pointwise products.
    xs: Vec<f64>,
    ys: Vec<f64>,
    /// Bound of ‖A_ff‖₂ (√2·max_t ‖J(t)‖_F: the coefficient norm is within √2 of the
    /// time-L² norm in which a multiplication operator's norm is max |J|).
    bound: f64,
}

impl Pointwise {
    fn new(sh: &ShockSys, lay: &Layout, ns: usize) -> Pointwise {
        let (n_own, n_comp) = (sh.eqs.n_own, sh.dofs.len());
        let sampler = Sampler::new(ns);
        let ws = sampler.scratch();
        Pointwise {
            sampler,
            ws,
            ns,
            n_own,
            n_comp,
            h_nonl: lay.h_nonl,
            h_lin: lay.h_lin,
            n_coef_nonl: lay.n_coef_nonl,
            jac: vec![0.0; ns * n_own * n_own],
            jac_u: vec![0.0; ns * n_own * n_comp],
            inv: vec![0.0; ns * n_own * n_own],
            jac_t: vec![0.0; ns * n_own * n_own],
            inv_t: vec![0.0; ns * n_own * n_own],
            xs: vec![0.0; ns * (n_own + n_comp)],
            ys: vec![0.0; ns * n_own],
            bound: 0.0,
        }
    }

    /// J(t) and J_u(t) at `x0` from the law's terms, and the pointwise inverse. Err with
    /// the first sample where J(t) is singular. `even`: X0 is time-symmetric, so J and J_u
    /// are even in time in exact arithmetic; their samples at t and −t are set to their
    /// mean, which makes the operator exactly real in complex coefficients (the real
    /// Toeplitz route, toeplitz.rs, is then an inverse of the operator its solves
    /// are checked against, not of a neighbour one round-off away).
    fn linearise(
        &mut self,
        sh: &ShockSys,
        lay: &Layout,
        x0: &[f64],
        even: bool,
    ) -> std::result::Result<(), usize> {
        let (ns, no, nc) = (self.ns, self.n_own, self.n_comp);
        // Samples of every variable: own unknowns then components.
        for k in 0..no {
            let o = sh.offset + k * lay.n_coef_nonl;
            self.sampler.synth_with(
                &x0[o..o + lay.n_coef_nonl],
                lay.h_nonl,
                &mut self.xs[k * ns..(k + 1) * ns],
                &mut self.ws,
            );
        }
        for c in 0..nc {
            let o = lay.u(sh.dofs[c]);
            let dst = &mut self.xs[(no + c) * ns..(no + c + 1) * ns];
            self.sampler
                .synth_with(&x0[o..o + lay.n_coef_lin], lay.h_lin, dst, &mut self.ws);
        }
        jacobians(
            &sh.eqs,
            &self.xs,
            ns,
            (no, nc),
            &mut self.jac,
            &mut self.jac_u,
        );
        if even {
            symmetrise_samples(&mut self.jac, ns, no * no);
            symmetrise_samples(&mut self.jac_u, ns, no * nc);
        }
        let mut bound = 0.0f64;
        let mut a = vec![0.0; no * no];
        for j in 0..ns {
            let m = &self.jac[j * no * no..(j + 1) * no * no];
            bound = bound.max(m.iter().map(|v| v * v).sum::<f64>().sqrt());
            a.copy_from_slice(m);
            if !invert_small(&mut a, &mut self.inv[j * no * no..(j + 1) * no * no], no) {
                return Err(j);
            }
        }
        self.bound = std::f64::consts::SQRT_2 * bound;
        let nn2 = no * no;
        for (src, dst) in [(&self.jac, &mut self.jac_t), (&self.inv, &mut self.inv_t)] {
            for (j, m) in src.chunks_exact(nn2).enumerate() {
                for (q, v) in m.iter().enumerate() {
                    dst[q * ns + j] = *v;
                }
            }
        }
        Ok(())
    }

    /// y = Trunc(M(t)·x(t)), M = J or (`inverse`) J⁻¹; x, y: n_own series of H_nl.
    fn mul(&mut self, x: &[f64], y: &mut [f64], inverse: bool) {
        let (ns, no, nn, hn) = (self.ns, self.n_own, self.n_coef_nonl, self.h_nonl);
        for k in 0..no {
            self.sampler.synth_with(
                &x[k * nn..(k + 1) * nn],
                hn,
                &mut self.xs[k * ns..(k + 1) * ns],
                &mut self.ws,
            );
        }
        // y_e(t) = Σ_k M_ek(t)·x_k(t), k ascending from 0 (the same sums, in the same order,
        // as sample by sample), over contiguous samples.
        let m = if inverse { &self.inv_t } else { &self.jac_t };
        for (e, ye) in self.ys.chunks_exact_mut(ns).enumerate().take(no) {
            ye.fill(0.0);
            for (k, xk) in self.xs.chunks_exact(ns).enumerate().take(no) {
                let mek = &m[(e * no + k) * ns..(e * no + k + 1) * ns];
                for ((y, x), a) in ye.iter_mut().zip(xk).zip(mek) {
                    *y += a * x;
                }
            }
        }
        for e in 0..no {
            self.sampler.analyse_with(
                &mut self.ys[e * ns..(e + 1) * ns],
                hn,
                &mut y[e * nn..(e + 1) * nn],
                &mut self.ws,
            );
        }
    }

    /// b = A_fu e_{c,j}: the law equations' response to harmonic j of component c.
    fn coupling_column(&mut self, c: usize, j: usize, b: &mut [f64]) {
        let (ns, no, nc, nn) = (self.ns, self.n_own, self.n_comp, self.n_coef_nonl);
        let nl = fourier::len(self.h_lin);
        let mut e = vec![0.0; nl];
        e[j] = 1.0;
        let us = &mut self.xs[..ns];
        self.sampler.synth_with(&e, self.h_lin, us, &mut self.ws);
        for q in 0..no {
            for t in 0..ns {
                self.ys[q * ns + t] = self.jac_u[t * no * nc + q * nc + c] * self.xs[t];
            }
        }
        for q in 0..no {
            self.sampler.analyse_with(
                &mut self.ys[q * ns..(q + 1) * ns],
                self.h_nonl,
                &mut b[q * nn..(q + 1) * nn],
                &mut self.ws,
            );
        }
    }

    /// Fourier series (H_nl harmonics) of entry `idx` of the sample-major array `src` with
    /// `stride` entries per sample: exact, J has at most H_nl harmonics.
    fn entry_series(&mut self, which_u: bool, idx: usize, out: &mut [f64]) {
        let ns = self.ns;
        let (src, stride) = if which_u {
            (&self.jac_u, self.n_own * self.n_comp)
        } else {
            (&self.jac, self.n_own * self.n_own)
        };
        for t in 0..ns {
            self.ys[t] = src[t * stride + idx];
        }
        self.sampler
            .analyse_with(&mut self.ys[..ns], self.h_nonl, out, &mut self.ws);
    }
}

impl Preconditioned for Pointwise {
    fn apply(&mut self, x: &[f64], y: &mut [f64]) {
        self.mul(x, y, false);
    }
    fn precondition(&mut self, x: &[f64], y: &mut [f64]) {
        self.mul(x, y, true);
    }
    fn norm_bound(&self) -> f64 {
        self.bound
    }
}

/// J(t) (sample-major [t][e·n_own + k]) and J_u(t) ([t][e·n_comp + c]) from the law's
/// terms at the samples `xs` of its variables (variable-major [var][t]: the `no` own
/// unknowns, then the `nc` displacement components), `ns` instants.
pub(in crate::nnm) fn jacobians(
    eqs: &LawEqs,
    xs: &[f64],
    ns: usize,
    (no, nc): (usize, usize),
    jac: &mut [f64],
    jac_u: &mut [f64],
) {
    let slot = |v: Var| match v {
        Var::Own(k) => k,
        Var::U(c) => no + c,
    };
    jac.fill(0.0);
    jac_u.fill(0.0);
    // d(coef·a·b)/da = coef·b, d/db = coef·a (a = b gives 2·coef·a).
    for t in &eqs.quad {
        for (wrt, other) in [(t.a, t.b), (t.b, t.a)] {
            let src = &xs[slot(other) * ns..(slot(other) + 1) * ns];
            match wrt {
                Var::Own(k) => {
                    for (j, x) in src.iter().enumerate() {
                        jac[j * no * no + t.eq * no + k] += t.coef * x;
                    }
                }
                Var::U(c) => {
                    for (j, x) in src.iter().enumerate() {
                        jac_u[j * no * nc + t.eq * nc + c] += t.coef * x;
                    }
                }
            }
        }
    }
    for l in &eqs.lin {
        match l.var {
            Var::Own(k) => {
                for j in 0..ns {
                    jac[j * no * no + l.eq * no + k] += l.coef;
                }
            }
            Var::U(c) => {
                for j in 0..ns {
                    jac_u[j * no * nc + l.eq * nc + c] += l.coef;
                }
            }
        }
    }
}

/// The weight of W's column `col` in the sum `toeplitz_w` checks: between 1 and 2, none
/// equal to another.
fn column_weight(col: usize) -> f64 {
    1.0 + (0.618_033_988_749_895 * (col + 1) as f64).fract()
}

/// Samples at t_j and t_{N−j} (`ns` samples of blocks of `len`, sample-major) set to
/// their mean: the even part of a function of time.
fn symmetrise_samples(v: &mut [f64], ns: usize, len: usize) {
    for j in 1..ns.div_ceil(2) {
        let (lo, hi) = v.split_at_mut((ns - j) * len);
        for (a, b) in lo[j * len..(j + 1) * len].iter_mut().zip(&mut hi[..len]) {
            let m = 0.5 * (*a + *b);
            *a = m;
            *b = m;
        }
    }
}

/// Inverse of the n × n row-major matrix `a` (destroyed) into `inv` (row-major), by
/// Gauss-Jordan with partial pivoting; false when a pivot vanishes relative to the
/// matrix's largest entry.
fn invert_small(a: &mut [f64], inv: &mut [f64], n: usize) -> bool {
    if n == 1 {
        let d = a[0];
        inv[0] = 1.0 / d;
        return d != 0.0 && inv[0].is_finite();
    }
    let scale = a.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    if !(scale > 0.0 && scale.is_finite()) {
        return false;
    }
    inv.fill(0.0);
    for i in 0..n {
        inv[i * n + i] = 1.0;
    }
    for col in 0..n {
        let p = (col..n)
            .max_by(|&r, &s| a[r * n + col].abs().total_cmp(&a[s * n + col].abs()))
            .unwrap_or(col);
        let piv = a[p * n + col];
        if piv.abs() <= 1e-14 * scale {
            return false;
        }
        if p != col {
            for j in 0..n {
                a.swap(p * n + j, col * n + j);
                inv.swap(p * n + j, col * n + j);
            }
        }
        let r = 1.0 / piv;
        for j in 0..n {
            a[col * n + j] *= r;
            inv[col * n + j] *= r;
        }
        for i in 0..n {
            if i != col {
                let f = a[i * n + col];
                if f != 0.0 {
                    for j in 0..n {
                        a[i * n + j] -= f * a[col * n + j];
                        inv[i * n + j] -= f * inv[col * n + j];
                    }
                }
            }
        }
    }
    true
}

/// Counters of one block (for reports and the bench).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Counters {
    pub factorisations: usize,
    pub solves: usize,
    pub krylov_iterations: usize,
    pub dense_fallbacks: usize,
    /// Toeplitz-route solves refined once more (their first residual check failed).
    pub refinements: usize,
    /// Toeplitz-route solves taken unchecked, W's columns having checked the inverse.
    pub unchecked: usize,
}

/// The contact block of one shock, linearised at one X0.
pub struct ContactBlock {
    /// Index of the shock (errors name CHOC number + 1).
    shock: usize,
    method: Method,
    /// The route of the current factorisation (the chosen one, or dense after a fallback).
    active: Method,
    d: usize,
    m: usize,
    n_coef_lin: usize,
    n_coef_nonl: usize,
    pw: Pointwise,
    gmres: Gmres,
    dense: DenseLu,
    /// On a time-symmetric point of the Toeplitz route, the block restricted to cosine or
    /// sine series and the Krylov workspaces of the two generator solves.
    parity: Option<ParityBlock>,
    gmres_even: Gmres,
    gmres_odd: Gmres,
    /// The Toeplitz route's inverse (laws with one own unknown), its two generator
    /// solutions and the residual of a checked solve.
    gs: Option<ToeplitzInverse>,
    xi: [Vec<f64>; 2],
    res: Vec<f64>,
    /// Weighted sums of W's right-hand sides and solutions (the check of `toeplitz_w`).
    res_b: Vec<f64>,
    res_x: Vec<f64>,
    /// The Toeplitz route's inverse passed its check on every column of W at the first
    /// try (`toeplitz_w`): further solves of this factorisation are not checked.
    trusted: bool,
    /// X0 is time-symmetric (`Layout::is_time_symmetric`), Toeplitz route: the symbol is
    /// even and T real. A right-hand side whose sine part is round-off (`is_cosine_series`:
    /// the series of a symmetric branch) is solved as a cosine series by real FFTs
    /// (`ToeplitzInverse::solve_even`).
    symmetric: bool,
    /// W = A_ff⁻¹ A_fu, column-major d × m, columns ordered component-major (c·nl + j).
    w: Vec<f64>,
    b: Vec<f64>,
    x: Vec<f64>,
    series: Vec<f64>,
    pub counters: Counters,
}

impl ContactBlock {
    /// `solves`: the right-hand sides expected per factorisation (for the cost model);
    /// `force`: a route imposed (tests, bench), else the model's choice.
    pub fn new(
        sh: &ShockSys,
        shock: usize,
        lay: &Layout,
        solves: usize,
        force: Option<Method>,
    ) -> Result<ContactBlock> {
        let (n_own, n_comp) = (sh.eqs.n_own, sh.dofs.len());
        let d = n_own * lay.n_coef_nonl;
        let m = n_comp * lay.n_coef_lin;
        // Exact truncated products need N > 3H_nl (and > 2H_nl + H_l, implied).
        let ns = fourier::fft_size_smooth(3 * lay.h_nonl);
        let mut method = force.unwrap_or_else(|| choose(n_own, lay.n_coef_nonl, ns, solves + m));
        if method == Method::Toeplitz && n_own != 1 {
            // Block Toeplitz (several own unknowns) has no scalar formula: Krylov.
            method = Method::Krylov;
        }
        let toeplitz = n_own == 1 && method == Method::Toeplitz;
        Ok(ContactBlock {
            shock,
            method,
            active: method,
            d,
            m,
            n_coef_lin: lay.n_coef_lin,
            n_coef_nonl: lay.n_coef_nonl,
            pw: Pointwise::new(sh, lay, ns),
            gmres: Gmres::new(d, KRYLOV_CYCLE, KRYLOV_CYCLES),
            dense: DenseLu::default(),
            parity: toeplitz.then(|| ParityBlock::new(lay.h_nonl, n_comp)),
            gmres_even: Gmres::new(
                if toeplitz { lay.h_nonl + 1 } else { 0 },
                KRYLOV_CYCLE,
                KRYLOV_CYCLES,
            ),
            gmres_odd: Gmres::new(
                if toeplitz { lay.h_nonl } else { 0 },
                KRYLOV_CYCLE,
                KRYLOV_CYCLES,
            ),
            gs: (n_own == 1 && method == Method::Toeplitz)
                .then(|| ToeplitzInverse::new(lay.h_nonl)),
            xi: if method == Method::Toeplitz {
                [vec![0.0; d], vec![0.0; d]]
            } else {
                [Vec::new(), Vec::new()]
            },
            res: vec![0.0; d],
            res_b: if method == Method::Toeplitz {
                vec![0.0; d]
            } else {
                Vec::new()
            },
            res_x: if method == Method::Toeplitz {
                vec![0.0; d]
            } else {
                Vec::new()
            },
            trusted: false,
            symmetric: false,
            w: try_zeroed(d * m, "the contact coupling W")?,
            b: vec![0.0; d],
            x: vec![0.0; d],
            series: vec![0.0; lay.n_coef_nonl],
            counters: Counters::default(),
        })
    }

    /// Dimension of the block (n_own·(2H_nl+1)) and number of coupled structural unknowns.
    pub fn dims(&self) -> (usize, usize) {
        (self.d, self.m)
    }

    pub fn w(&self) -> &[f64] {
        &self.w
    }

    fn err(&self, what: String) -> Error {
        Error::numerical(format!("CHOC {}: {what}", self.shock + 1)).hint(
            "the branch may have left the physical root of the regularised law; \
             lower PREC_MAN or raise PARA_REGUL",
        )
    }

    /// Linearise at `x0` and compute W.
    pub fn factor(&mut self, sh: &ShockSys, lay: &Layout, x0: &[f64]) -> Result<()> {
        self.counters.factorisations += 1;
        self.symmetric = self.method == Method::Toeplitz && lay.is_time_symmetric(x0);
        let mut singular_at = self.pw.linearise(sh, lay, x0, self.symmetric).err();
        if self.symmetric {
            // The generator solves' operators, on the half period (parity_block.rs).
            if let Some(pb) = self.parity.as_mut() {
                if !pb.linearise(sh, lay, x0) {
                    singular_at = singular_at.or(Some(0));
                }
            }
        }
        self.active = self.method;
        self.trusted = false;
        if self.method == Method::Toeplitz {
            if singular_at.is_none() && self.toeplitz_w()? {
                return Ok(());
            }
            // No representation: the dense route where it fits, else Krylov's handling.
            if self.d <= DENSE_MAX_DIM {
                self.counters.dense_fallbacks += 1;
                self.active = Method::Dense;
                return self.dense_w();
            }
            self.active = Method::Krylov;
        }
        if self.active == Method::Krylov {
            match singular_at {
                None => match self.krylov_w() {
                    Ok(()) => return Ok(()),
                    Err(e) if self.d > DENSE_MAX_DIM => return Err(e),
                    Err(_) => {}
                },
                Some(j) if self.d > DENSE_MAX_DIM => {
                    return Err(self.err(format!(
                        "the law's pointwise Jacobian is singular at instant {j} of {} \
                         (no preconditioner), and the block ({} unknowns) is too large for a dense factorisation",
                        self.pw.ns, self.d
                    )))
                }
                Some(_) => {}
            }
            self.counters.dense_fallbacks += 1;
            self.active = Method::Dense;
        }
        self.dense_w()
    }

    fn krylov_w(&mut self) -> Result<()> {
        let (d, nl) = (self.d, self.n_coef_lin);
        for col in 0..self.m {
            let (c, j) = (col / nl, col % nl);
            self.pw.coupling_column(c, j, &mut self.b);
            // From zero: the previous factorisation's column (one branch away) was measured
            // to save no iterations here, only to cost the guess's residual.
            let krylov = self
                .gmres
                .solve(
                    &mut self.pw,
                    &self.b,
                    &mut self.w[col * d..(col + 1) * d],
                    KRYLOV_RTOL,
                )
                .map_err(|f| self.krylov_error(f))?;
            self.counters.krylov_iterations += krylov.iterations;
        }
        Ok(())
    }

    /// The Toeplitz route's factorisation: the generator from two Krylov solves (one on a
    /// time-symmetric block, `symmetric_generators`), then W.
    /// Ok(false): no representation (a Krylov solve failed or ξ₀ = 0), take the dense
    /// route; an Err only when that cannot be taken either.
    fn toeplitz_w(&mut self) -> Result<bool> {
        let (d, nn, hn) = (self.d, self.n_coef_nonl, self.pw.h_nonl);
        if self.symmetric {
            if !self.symmetric_generators()? {
                return Ok(false);
            }
        } else {
            for (i, idx) in [fourier::ic(hn), fourier::is(hn, hn)]
                .into_iter()
                .enumerate()
            {
                self.b.fill(0.0);
                self.b[idx] = 2.0;
                // From the generator of the previous factorisation (a nearby block).
                match self
                    .gmres
                    .solve_from(&mut self.pw, &self.b, &mut self.xi[i], KRYLOV_RTOL)
                {
                    Ok(krylov) => self.counters.krylov_iterations += krylov.iterations,
                    Err(f) if self.d > DENSE_MAX_DIM => return Err(self.krylov_error(f)),
                    Err(_) => return Ok(false),
                }
            }
        }
        let Some(gs) = self.gs.as_mut() else {
            return Ok(false);
        };
        if !gs.set_generator(&self.xi[0], &self.xi[1], self.symmetric) {
            return Ok(false);
        }
        debug_assert_eq!(d, nn);
        // A_fu into W from the series of J_u (exact, J_u has at most H_nl harmonics),
        // then solved in place: no transform per column.
        self.fill_coupling();
        // Every column solved, then one weighted sum of them checked: the columns spread
        // over every harmonic, so their sum checks the inverse as well as each of them
        // would (weights unequal, so that no two columns' errors can cancel by symmetry).
        // Only when that check fails is each column checked, and refined, on its own.
        self.res_b.fill(0.0);
        self.res_x.fill(0.0);
        for col in 0..self.m {
            let mut x = std::mem::take(&mut self.x);
            self.b.copy_from_slice(&self.w[col * d..(col + 1) * d]);
            self.clean_column(col);
            x.copy_from_slice(&self.b);
            let parity = self.column_parity(col);
            let Some(gs) = self.gs.as_mut() else {
                return Ok(false);
            };
            match parity {
                Some(true) => gs.solve_even(&mut x),
                Some(false) => gs.solve_odd(&mut x),
                None => gs.solve(&mut x),
            }
            let wt = column_weight(col);
            for ((sb, sx), (b, xv)) in self
                .res_b
                .iter_mut()
                .zip(self.res_x.iter_mut())
                .zip(self.b.iter().zip(&x))
            {
                *sb += wt * b;
                *sx += wt * xv;
            }
            self.w[col * d..(col + 1) * d].copy_from_slice(&x);
            self.x = x;
        }
        self.b.copy_from_slice(&self.res_b);
        let sum_x = std::mem::take(&mut self.res_x);
        let passed = self.toeplitz_check(&sum_x);
        self.res_x = sum_x;
        if passed {
            // W's columns are the check of this inverse: the series' solves with it are
            // not checked again (`solve`).
            self.trusted = self.m >= 2;
            return Ok(true);
        }
        // Each column on its own, against its right-hand side (A_fu's column again).
        let solutions = self.w.clone();
        self.fill_coupling();
        for col in 0..self.m {
            self.b.copy_from_slice(&self.w[col * d..(col + 1) * d]);
            self.clean_column(col);
            let mut x = solutions[col * d..(col + 1) * d].to_vec();
            let ok = self.toeplitz_refine(&mut x)?;
            self.w[col * d..(col + 1) * d].copy_from_slice(&x);
            if !ok {
                return Ok(false);
            }
        }
        Ok(true)
    }

    /// On a time-symmetric block, whether column `col` of A_fu is even (a displacement
    /// cosine or the mean: Some(true)) or odd (a sine); None on any other block.
    fn column_parity(&self, col: usize) -> Option<bool> {
        self.symmetric
            .then(|| col % self.n_coef_lin <= self.pw.h_lin)
    }

    /// A column of A_fu in `b`, on a time-symmetric block, without its part of the other
    /// parity (round-off: J_u is even), so that it is checked against what was solved.
    fn clean_column(&mut self, col: usize) {
        let hn = self.pw.h_nonl;
        match self.column_parity(col) {
            Some(true) => self.b[hn + 1..].fill(0.0),
            Some(false) => self.b[..=hn].fill(0.0),
            None => {}
        }
    }

    /// Whether x solves A_ff x = b (`self.b`) to the Krylov solves' residual test.
    fn toeplitz_check(&mut self, x: &[f64]) -> bool {
        self.pw.mul(x, &mut self.res, false);
        for (r, b) in self.res.iter_mut().zip(&self.b) {
            *r = b - *r;
        }
        let nr = gmres::norm(&self.res);
        nr.is_finite()
            && gmres::converged(
                nr,
                gmres::norm(&self.b),
                self.pw.bound,
                gmres::norm(x),
                KRYLOV_RTOL,
            )
    }

    /// The two generator solutions of a time-symmetric block: A_ff (j even) maps cosine
    /// series to cosine series and sine series to sine series, so ξ_c = A_ff⁻¹(2 cos Hθ)
    /// is a cosine series and ξ_s = A_ff⁻¹(2 sin Hθ) a sine series, each one Krylov solve
    /// of the block restricted to its parity on the half period (parity_block.rs), from the
    /// previous factorisation's generator (a nearby block). Ok(false) as `toeplitz_w`.
    fn symmetric_generators(&mut self) -> Result<bool> {
        let hn = self.pw.h_nonl;
        let Some(pb) = self.parity.as_mut() else {
            return Ok(false);
        };
        let mut failure = None;
        for parity in [Parity::Even, Parity::Odd] {
            let dim = pb.dim(parity);
            let (b, x) = (&mut self.res_b[..dim], &mut self.res_x[..dim]);
            // 2 cos Hθ is the last cosine coefficient, 2 sin Hθ the last sine one.
            b.fill(0.0);
            b[dim - 1] = 2.0;
            let (xi, gmres) = match parity {
                Parity::Even => (&mut self.xi[0][..=hn], &mut self.gmres_even),
                Parity::Odd => (&mut self.xi[1][hn + 1..], &mut self.gmres_odd),
            };
            x.copy_from_slice(xi);
            match gmres.solve_from(pb.select(parity), b, x, KRYLOV_RTOL) {
                Ok(krylov) => self.counters.krylov_iterations += krylov.iterations,
                Err(f) => {
                    failure = Some(f);
                    break;
                }
            }
            xi.copy_from_slice(x);
        }
        // The other parts of the generators are zero.
        self.xi[0][hn + 1..].fill(0.0);
        self.xi[1][..=hn].fill(0.0);
        match failure {
            None => Ok(true),
            Some(f) if self.d > DENSE_MAX_DIM => Err(self.krylov_error(f)),
            Some(_) => Ok(false),
        }
    }

    /// x ← A_ff⁻¹ b (`self.b`) on the Toeplitz route, accepted by the Krylov solves'
    /// residual test; refined twice by the same inverse, then by GMRES, if needed.
    /// Ok(false): no accepted solution (the caller falls back to the dense route).
    fn toeplitz_solve(&mut self, x: &mut [f64]) -> Result<bool> {
        let Some(gs) = self.gs.as_mut() else {
            return Ok(false);
        };
        let h = self.pw.h_nonl;
        if self.symmetric && is_cosine_series(&self.b, h) {
            // The sine part of an even right-hand side is round-off: dropped here, so that
            // a checked solve is checked against the right-hand side it solved. One with a
            // larger sine part (a series leaving a symmetric X0 along a symmetry-breaking
            // direction, at a bifurcation) is solved whole.
            for k in 1..=h {
                self.b[fourier::is(h, k)] = 0.0;
            }
            x.copy_from_slice(&self.b);
            gs.solve_even(x);
        } else {
            x.copy_from_slice(&self.b);
            gs.solve(x);
        }
        if self.trusted && x.iter().all(|v| v.is_finite()) {
            self.counters.unchecked += 1;
            return Ok(true);
        }
        self.toeplitz_refine(x)
    }

    /// `x`, a solution of A_ff x = b (`self.b`) by the Toeplitz route's inverse, checked by
    /// the Krylov solves' residual test and refined if needed (`toeplitz_solve`).
    fn toeplitz_refine(&mut self, x: &mut [f64]) -> Result<bool> {
        let nb = gmres::norm(&self.b);
        let a_norm = self.pw.bound;
        for refinement in 0..3 {
            self.pw.mul(x, &mut self.res, false);
            for (r, b) in self.res.iter_mut().zip(&self.b) {
                *r = b - *r;
            }
            let nr = gmres::norm(&self.res);
            if !nr.is_finite() {
                return Ok(false);
            }
            if gmres::converged(nr, nb, a_norm, gmres::norm(x), KRYLOV_RTOL) {
                return Ok(true);
            }
            if refinement < 2 {
                self.counters.refinements += 1;
                let Some(gs) = self.gs.as_mut() else {
                    return Ok(false);
                };
                gs.solve(&mut self.res);
                for (xi, r) in x.iter_mut().zip(&self.res) {
                    *xi += r;
                }
            }
        }
        // GMRES (pointwise preconditioner) on the remaining residual (rare: its own
        // vector, the generators stay as the next factorisation's first guesses).
        let mut delta = vec![0.0; self.d];
        let r = self.res.clone();
        let out = self.gmres.solve(&mut self.pw, &r, &mut delta, KRYLOV_RTOL);
        match out {
            Ok(krylov) => {
                self.counters.krylov_iterations += krylov.iterations;
                for (xi, dv) in x.iter_mut().zip(&delta) {
                    *xi += dv;
                }
                Ok(true)
            }
            Err(f) if self.d > DENSE_MAX_DIM => Err(self.krylov_error(f)),
            Err(_) => Ok(false),
        }
    }

    fn krylov_error(&self, f: gmres::Failure) -> Error {
        match f {
            gmres::Failure::NotFinite => self.err("the contact block's Krylov solve produced non-finite values".into()),
            gmres::Failure::Stagnated {
                iterations,
                relative_residual,
            } => self.err(format!(
                "the contact block is singular or too ill-conditioned: GMRES stagnated at relative residual {relative_residual:.2e} after {iterations} iterations"
            )),
        }
    }

    /// Assemble A_ff densely from the Fourier series of J and factorise it.
    fn dense_factor(&mut self) -> Result<()> {
        let (d, nn, no, hn) = (self.d, self.n_coef_nonl, self.pw.n_own, self.pw.h_nonl);
        let mut series = std::mem::take(&mut self.series);
        self.dense.storage(d)?.fill(0.0);
        for e in 0..no {
            for k in 0..no {
                self.pw.entry_series(false, e * no + k, &mut series);
                if series.iter().all(|&v| v == 0.0) {
                    continue;
                }
                let a = self.dense.storage_mut();
                fourier::fill_mul_operator(
                    &series,
                    hn,
                    hn,
                    hn,
                    1.0,
                    &mut a[k * nn * d + e * nn..],
                    d,
                );
            }
        }
        self.series = series;
        self.dense
            .factor()
            .map_err(|e| self.err(format!("the contact block is singular ({})", e.message)))
    }

    /// A_fu (d × m, column-major) into W, from the Fourier series of J_u.
    fn fill_coupling(&mut self) {
        let (d, nn) = (self.d, self.n_coef_nonl);
        let (no, nc, hn, hl) = (self.pw.n_own, self.pw.n_comp, self.pw.h_nonl, self.pw.h_lin);
        let nl = fourier::len(hl);
        let mut series = std::mem::take(&mut self.series);
        self.w.fill(0.0);
        for e in 0..no {
            for c in 0..nc {
                self.pw.entry_series(true, e * nc + c, &mut series);
                if series.iter().all(|&v| v == 0.0) {
                    continue;
                }
                fourier::fill_mul_operator(
                    &series,
                    hn,
                    hl,
                    hn,
                    1.0,
                    &mut self.w[c * nl * d + e * nn..],
                    d,
                );
            }
        }
        self.series = series;
    }

    /// The dense route: A_ff factorised, A_fu assembled (from the series of J_u), W solved.
    fn dense_w(&mut self) -> Result<()> {
        self.dense_factor()?;
        let m = self.m;
        self.fill_coupling();
        self.dense.solve(&mut self.w, m)
    }

    /// r ← A_ff⁻¹ r (length d).
    pub fn solve(&mut self, r: &mut [f64]) -> Result<()> {
        self.counters.solves += 1;
        match self.active {
            Method::Dense => self.dense.solve(r, 1),
            Method::Toeplitz => {
                // A trusted inverse and the cosine series of a time-symmetric branch (the
                // series' solves): solved in place, unchecked (`toeplitz_solve`).
                let h = self.pw.h_nonl;
                self.b.copy_from_slice(r);
                if self.trusted && self.symmetric && is_cosine_series(r, h) {
                    if let Some(gs) = self.gs.as_mut() {
                        gs.solve_even(r);
                        if r.iter().all(|v| v.is_finite()) {
                            self.counters.unchecked += 1;
                            return Ok(());
                        }
                        r.copy_from_slice(&self.b);
                    }
                }
                let mut x = std::mem::take(&mut self.x);
                let ok = self.toeplitz_solve(&mut x);
                self.x = x;
                if ok? {
                    r.copy_from_slice(&self.x);
                    Ok(())
                } else if self.d > DENSE_MAX_DIM {
                    Err(self.err(
                        "the contact block's Toeplitz solve did not reach its residual".into(),
                    ))
                } else {
                    // As for Krylov below: the rest of this factorisation on the dense route.
                    self.counters.dense_fallbacks += 1;
                    self.active = Method::Dense;
                    self.dense_factor()?;
                    self.dense.solve(r, 1)
                }
            }
            Method::Krylov => {
                self.b.copy_from_slice(r);
                match self
                    .gmres
                    .solve(&mut self.pw, &self.b, &mut self.x, KRYLOV_RTOL)
                {
                    Ok(krylov) => {
                        self.counters.krylov_iterations += krylov.iterations;
                        r.copy_from_slice(&self.x);
                        Ok(())
                    }
                    // The rest of this factorisation's solves on the dense route (W, from
                    // converged Krylov solves, stays: it agrees with the dense one to
                    // round-off and the condensed matrix was built with it).
                    Err(f) if self.d > DENSE_MAX_DIM => Err(self.krylov_error(f)),
                    Err(_) => {
                        self.counters.dense_fallbacks += 1;
                        self.active = Method::Dense;
                        self.dense_factor()?;
                        self.dense.solve(r, 1)
                    }
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::nnm::analysis::route_timing::system_and_point;
    use crate::nnm::ShockLaw;

    /// Largest difference of `a` from `b`, relative to b's largest entry.
    fn rel(a: &[f64], b: &[f64]) -> f64 {
        let scale = b.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        a.iter()
            .zip(b)
            .fold(0.0f64, |m, (p, q)| m.max((p - q).abs()))
            / scale
    }

    /// On the Toeplitz route, W (its coupling from the series of J_u, then checked column
    /// by column) and the right-hand sides' solves, unchecked once W has passed, equal the
    /// dense route's LU solves to 1e-12 relative: both are direct, and this PLAN block's
    /// condition number is small, so round-off of either stays far below that.
    #[test]
    fn toeplitz_solves_trusted_after_w_equal_dense_solves() {
        let (sys, x) = system_and_point(ShockLaw::Plan, 40).unwrap();
        let (lay, sh) = (sys.lay, &sys.shocks[0]);
        let mut toeplitz = ContactBlock::new(sh, 0, &lay, 8, Some(Method::Toeplitz)).unwrap();
        let mut dense = ContactBlock::new(sh, 0, &lay, 8, Some(Method::Dense)).unwrap();
        toeplitz.factor(sh, &lay, &x).unwrap();
        dense.factor(sh, &lay, &x).unwrap();
        assert_eq!(toeplitz.active, Method::Toeplitz);
        assert!(
            toeplitz.trusted,
            "W's columns passed their check at the first try"
        );
        assert!(rel(toeplitz.w(), dense.w()) < 1e-12);
        for k in 0..3 {
            let r: Vec<f64> = (0..toeplitz.d)
                .map(|i| ((i * 7919 + 31 * k) % 101) as f64 / 101.0 - 0.5)
                .collect();
            let (mut a, mut b) = (r.clone(), r);
            toeplitz.solve(&mut a).unwrap();
            dense.solve(&mut b).unwrap();
            assert!(rel(&a, &b) < 1e-12, "solve {k}: {:e}", rel(&a, &b));
        }
        assert_eq!(toeplitz.counters.unchecked, 3);
        assert_eq!(toeplitz.counters.refinements, 0);
    }

    /// A time-symmetric point (U and the contact force cosine series, V zero): the block
    /// is marked symmetric, its inverse is the real one, W's columns pass their check, and
    /// the solve of an even right-hand side by real FFTs equals the dense route's to 1e-12
    /// relative (as above). A round-off sine part of the right-hand side is dropped: the
    /// solve of rhs + 1e-18 sine equals that of rhs. A larger one (a series leaving the
    /// point along a symmetry-breaking direction) is solved whole, as the dense route does.
    /// A point with a sine in U is not symmetric.
    #[test]
    fn a_time_symmetric_point_takes_the_real_route() {
        let (sys, mut x) = system_and_point(ShockLaw::Plan, 40).unwrap();
        let (lay, sh) = (sys.lay, &sys.shocks[0]);
        assert!(!lay.is_time_symmetric(&x), "U(1) has a sine");
        x[lay.u(1) + fourier::is(lay.h_lin, 1)] = 0.0;
        x[lay.u(1) + fourier::ic(1)] = 0.4;
        crate::nnm::model::contact_samples::init_contact(&sys, &mut x).unwrap();
        assert!(lay.is_time_symmetric(&x));
        let mut toeplitz = ContactBlock::new(sh, 0, &lay, 8, Some(Method::Toeplitz)).unwrap();
        let mut dense = ContactBlock::new(sh, 0, &lay, 8, Some(Method::Dense)).unwrap();
        toeplitz.factor(sh, &lay, &x).unwrap();
        dense.factor(sh, &lay, &x).unwrap();
        assert_eq!(toeplitz.active, Method::Toeplitz);
        assert!(toeplitz.symmetric && toeplitz.trusted);
        assert!(toeplitz.gs.as_ref().is_some_and(|g| g.is_symmetric()));
        assert!(rel(toeplitz.w(), dense.w()) < 1e-12);
        let h = lay.h_nonl;
        let even: Vec<f64> = (0..toeplitz.d)
            .map(|i| {
                let is_sine = i > h;
                if is_sine {
                    0.0
                } else {
                    ((i * 7919) % 101) as f64 / 101.0 - 0.5
                }
            })
            .collect();
        let (mut a, mut b) = (even.clone(), even.clone());
        toeplitz.solve(&mut a).unwrap();
        dense.solve(&mut b).unwrap();
        assert!(rel(&a, &b) < 1e-12, "{:e}", rel(&a, &b));
        let mut c = even.clone();
        c[fourier::is(h, 3)] = 1e-18;
        toeplitz.solve(&mut c).unwrap();
        assert_eq!(a, c);
        let mut d = even.clone();
        d[fourier::is(h, 3)] = 1e-3;
        let mut e = d.clone();
        toeplitz.solve(&mut d).unwrap();
        dense.solve(&mut e).unwrap();
        assert!(rel(&d, &e) < 1e-12, "{:e}", rel(&d, &e));
    }

    #[test]
    fn small_inverse_matches_and_detects_singularity() {
        let mut a = vec![2.0, 1.0, 0.0, 1.0, 3.0, 1.0, 0.0, 1.0, 4.0];
        let a0 = a.clone();
        let mut inv = vec![0.0; 9];
        assert!(invert_small(&mut a, &mut inv, 3));
        for i in 0..3 {
            for j in 0..3 {
                let v: f64 = (0..3).map(|k| a0[i * 3 + k] * inv[k * 3 + j]).sum();
                assert!((v - if i == j { 1.0 } else { 0.0 }).abs() < 1e-14);
            }
        }
        let mut s = vec![1.0, 2.0, 2.0, 4.0];
        assert!(!invert_small(&mut s, &mut inv[..4], 2));
        // A zero leading pivot needs the row exchange.
        let mut p = vec![0.0, 1.0, 1.0, 0.0];
        assert!(invert_small(&mut p, &mut inv[..4], 2));
        assert_eq!(&inv[..4], &[0.0, 1.0, 1.0, 0.0]);
    }

    #[test]
    fn the_cost_model_prefers_dense_for_small_blocks_and_krylov_for_large() {
        let ns = |hn: usize| fourier::fft_size_smooth(3 * hn);
        assert_eq!(choose(1, 41, ns(20), 40), Method::Dense);
        assert_eq!(choose(4, 2001, ns(1000), 40), Method::Krylov);
    }
}
