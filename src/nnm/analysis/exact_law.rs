//! Newton correction of a harmonic-balance point on the exact (unregularised) penalty law of
//! each shock, by alternating frequency–time (AFT) evaluation. Code_Aster has no equivalent;
//! MODE_NON_LINE's RESOLUTION/CORR_LOI_EXACTE = 'OUI' applies it to every stored point
//! ([`correct_point`], column FREQUENCE_LOI_EXACTE), and the accuracy study
//! (`aster-nl accuracy`) measures it.
//!
//! EHMAN solves the regularised law (PARA_REGUL = η), whose frequency error is ∝ η
//! (docs/accuracy.md, trend 2). Here the branch point found by EHMAN is the starting guess
//! of a small Newton problem on the nonsmooth law itself:
//! - unknowns: the displacement harmonics U (n DOFs × (2H_l+1), DOF-major, Code_Aster's
//!   layout 0, C1..CH, S1..SH), ω and the unfolding parameter γ (zero on a solution); no
//!   velocity and no contact unknowns;
//! - equations: the harmonic balance ω² M D²U + γω M DU + K U + F̂(U) = 0 on harmonics
//!   0..H_l (D = d/dθ), F̂ the harmonics of the exact law's force f(u(θ_j)) sampled at N
//!   instants θ_j = 2πj/N (PLAN α·max(0, u − g), BI_PLAN α·(|u| − g)₊·sign u, CERCLE
//!   α(r − g)₊·d/r with d the displacement from the ring centre); the phase condition (zero
//!   velocity of the reference DOF at t = 0, as in EHMAN); and the point's energy held
//!   fixed ([`HeldEnergy`]), so the frequency–energy curve is what is corrected;
//! - Jacobian by AFT too: the law's derivative pointwise in time (α·H(u − g), or CERCLE's
//!   2×2 α[(1 − g/r)I + (g/r) d̂d̂ᵀ]) sampled at the same instants, its harmonics up to 2H_l,
//!   and the product operator of that series (`fourier::fill_mul_operator`), which is the
//!   exact derivative of the sampled residual (no aliasing reaches a retained product
//!   harmonic when N > 4H_l). The sampled residual is piecewise smooth in U (it changes form
//!   only when a sample crosses the gap), so Newton converges quadratically once the set of
//!   samples in contact is settled.
//!
//! The remaining error is the truncation at H_l harmonics and the sampling of the kink of
//! the law (O(N⁻²) on the force harmonics; `DEFAULT_SAMPLES_PER_COEF`, docs/accuracy.md).
//! The linear algebra is dense (dimension n·(2H_l+1) + 2, at most [`MAX_DENSE`]).
//! Units are physical in and out; internally lengths are divided by the largest JEU,
//! forces by k_ref·JEU and the pulsations by the starting ω. No SQL, no keywords.

// Component and sample indices address several arrays at once (samples, forces,
// derivatives, DOFs), as in the law formulas. (The large shared `Error` is allowed once, at
// the crate root: src/lib.rs.)
#![allow(clippy::needless_range_loop)]

use crate::nnm::error::{Error, Result};
use crate::nnm::model::fourier::{self, Sampler};
use crate::nnm::model::point_law::{eta_phys, PointLaw};
use crate::nnm::solve::dense_lu::DenseLu;
use crate::nnm::{Problem, ShockLaw};
use std::f64::consts::{FRAC_PI_2, PI};

/// Which energy of the orbit the correction keeps equal to the starting point's.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum HeldEnergy {
    /// Code_Aster's ENERGIE: ½uᵀKu + ½vᵀMv plus the penalty energy at ωt = π/2.
    Instant,
    /// The same formula averaged over the period (ENERGIE_MOYENNE).
    Mean,
}

/// Settings of the correction.
#[derive(Clone, Copy, Debug)]
pub struct ExactLawSettings {
    /// NB_HARM_LINE of the point (the corrected orbit has the same harmonics).
    pub h_lin: usize,
    /// Time samples per period (0: [`default_samples`]); raised to the smallest power of
    /// two above 4·H_l + 1 if smaller.
    pub samples: usize,
    /// Convergence: ‖R‖/max(1, ‖X‖) of the scaled equations (PREC_NEWTON).
    pub prec: f64,
    /// ITER_NEWTON_MAXI.
    pub iter_max: usize,
    pub held: HeldEnergy,
}

/// Default samples per Fourier coefficient of a displacement (N ≥ this·(2H_l+1)).
pub const DEFAULT_SAMPLES_PER_COEF: usize = 64;

/// Largest dense system (n·(2H_l+1) + 2) the correction accepts.
pub const MAX_DENSE: usize = 4000;

/// Dimension of the dense system of a correction: n·(2H_l+1) displacement harmonics, ω and
/// γ.
pub fn dense_size(n_dofs: usize, h_lin: usize) -> usize {
    n_dofs.saturating_mul(fourier::len(h_lin)).saturating_add(2)
}

/// Refuses, from the sizes alone (nothing allocated), a correction whose dense system
/// would exceed [`MAX_DENSE`] or that has no harmonic to correct.
pub fn check_size(n_dofs: usize, h_lin: usize) -> Result<()> {
    if h_lin == 0 {
        return Err(Error::validation(
            "the exact-law correction needs NB_HARM_LINE ≥ 1",
        ));
    }
    let dim = dense_size(n_dofs, h_lin);
    if dim > MAX_DENSE {
        return Err(Error::validation(format!(
            "the exact-law correction solves a dense system of n·(2·NB_HARM_LINE + 1) + 2 = \
             {n_dofs}·{} + 2 = {dim} unknowns, more than the {MAX_DENSE} it accepts",
            fourier::len(h_lin)
        )));
    }
    Ok(())
}

/// Corrects a computed branch point on the exact law with its ENERGIE_MOYENNE held
/// (`settings.held` is taken as [`HeldEnergy::Mean`]): the frequency of the returned orbit
/// is the exact-law frequency at the point's ENERGIE_MOYENNE.
pub fn correct_point(
    problem: &Problem,
    settings: &ExactLawSettings,
    p: &crate::nnm::Point,
) -> Result<ExactPoint> {
    let n = problem
        .k
        .nrows()
        .saturating_mul(fourier::len(settings.h_lin));
    if p.x.len() < n {
        return Err(Error::internal(
            "exact-law correction: the point has fewer unknowns than its displacements",
        ));
    }
    let set = ExactLawSettings {
        held: HeldEnergy::Mean,
        ..*settings
    };
    correct(problem, &set, &p.x[..n], p.omega, p.energy_mean)
}

/// The default number of samples for `h_lin` harmonics: the smallest power of two above
/// `DEFAULT_SAMPLES_PER_COEF`·(2H_l+1).
pub fn default_samples(h_lin: usize) -> usize {
    fourier::fft_size(DEFAULT_SAMPLES_PER_COEF * fourier::len(h_lin))
}

/// Samples per period for `h_lin` harmonics and `per_coef` samples per coefficient (0: the
/// default): the smallest power of two above per_coef·(2H_l+1), and above 4H_l + 1.
pub fn samples_for(h_lin: usize, per_coef: usize) -> usize {
    if per_coef == 0 {
        return default_samples(h_lin);
    }
    fourier::fft_size(per_coef * fourier::len(h_lin)).max(fourier::fft_size(4 * h_lin + 1))
}

/// The corrected orbit.
#[derive(Clone, Debug)]
pub struct ExactPoint {
    /// rad/s.
    pub omega: f64,
    /// Hz.
    pub frequency: f64,
    /// 1/s (zero to round-off on a converged orbit of the conservative system).
    pub gamma: f64,
    /// ENERGIE of the corrected orbit (J).
    pub energy: f64,
    /// ENERGIE's formula averaged over the period (J).
    pub energy_mean: f64,
    /// Displacement harmonics, n × (2H_l+1), physical units.
    pub u: Vec<f64>,
    /// Newton iterations made.
    pub iterations: usize,
    /// ‖R‖/max(1, ‖X‖) before each iteration and at the end (iterations + 1 values).
    pub residuals: Vec<f64>,
    /// Samples per period used.
    pub samples: usize,
}

/// One shock, in physical units.
struct ExactShock {
    law: ShockLaw,
    dofs: Vec<usize>,
    gap: f64,
    alpha: f64,
    /// The engine's regularised law, when the harmonic balance is solved on it instead of
    /// the exact law ([`correct_on_law`]); the held energy keeps the exact penalty.
    regularised: Option<PointLaw>,
}

/// The problem's data laid out for assembly.
struct Ctx {
    n: usize,
    h: usize,
    nl: usize,
    dim: usize,
    k: Vec<(usize, usize, f64)>,
    m: Vec<(usize, usize, f64)>,
    shocks: Vec<ExactShock>,
    smp: Sampler,
    /// Length, stiffness and pulsation scales.
    len: f64,
    kref: f64,
    w0: f64,
    phase_dof: usize,
    held: HeldEnergy,
    target: f64,
}

fn entries(a: &faer::sparse::SparseColMat<usize, f64>) -> Vec<(usize, usize, f64)> {
    let sym = a.symbolic();
    let (cp, ri, v) = (sym.col_ptr(), sym.row_idx(), a.val());
    let mut e = Vec::with_capacity(v.len());
    for j in 0..a.ncols() {
        for p in cp[j]..cp[j + 1] {
            e.push((ri[p], j, v[p]));
        }
    }
    e
}

/// Force of one shock's law and its derivative, pointwise: `u` the displacements of its
/// components at one instant; returns (f, J) with J row-major ncomp × ncomp.
fn law(sh: &ExactShock, u: [f64; 2]) -> ([f64; 2], [f64; 4]) {
    sh.law.with(|l| l.exact_force(u, sh.alpha, sh.gap))
}

/// The force in the harmonic balance: the exact law, or the regularised one when asked
/// (a law that cannot be evaluated gives NaN, which stops Newton with an error).
fn balance_law(sh: &ExactShock, u: [f64; 2]) -> ([f64; 2], [f64; 4]) {
    let Some(pl) = &sh.regularised else {
        return law(sh, u);
    };
    match pl.eval(&u[..pl.n_comp()]) {
        Ok((f, j)) => {
            let mut fo = [0.0; 2];
            let mut jo = [0.0; 4];
            fo[..f.len()].copy_from_slice(&f);
            if j.len() == 1 {
                jo[0] = j[0];
            } else {
                jo[..j.len()].copy_from_slice(&j);
            }
            (fo, jo)
        }
        Err(_) => ([f64::NAN; 2], [f64::NAN; 4]),
    }
}

/// Penalty energy ½α(δ)₊² of one shock at one instant (δ the penetration).
fn penalty(sh: &ExactShock, u: [f64; 2]) -> f64 {
    sh.law.with(|l| l.mean_energy(u, sh.alpha, sh.gap))
}

impl Ctx {
    /// Scaled residual `r` and Jacobian `jac` (column-major dim × dim) at scaled unknowns
    /// x = [U/len, ω/w0, γ/w0].
    fn assemble(&self, x: &[f64], r: &mut [f64], jac: &mut [f64]) {
        let (n, h, nl, dim) = (self.n, self.h, self.nl, self.dim);
        let (len, kref, w0) = (self.len, self.kref, self.w0);
        let iw = n * nl;
        let ig = iw + 1;
        let omega = x[iw] * w0;
        let gamma = x[ig] * w0;
        let u: Vec<f64> = x[..iw].iter().map(|v| v * len).collect();
        r.fill(0.0);
        jac.fill(0.0);
        // Harmonic balance, scaled by 1/(kref·len); ∂/∂(u/len) = ∂/∂u·len.
        let rs = 1.0 / (kref * len);
        let js = 1.0 / kref;
        for &(i, j, v) in &self.k {
            for p in 0..nl {
                r[i * nl + p] += rs * v * u[j * nl + p];
                jac[(j * nl + p) * dim + i * nl + p] += js * v;
            }
        }
        for &(i, j, v) in &self.m {
            let (ui, uj) = (i * nl, j * nl);
            for k in 1..=h {
                let kf = k as f64;
                let (c, s) = (fourier::ic(k), fourier::is(h, k));
                let (uc, us) = (u[uj + c], u[uj + s]);
                // ω² M D²u: −k²ω²; γω M Du: cos ← k·s, sin ← −k·c.
                r[ui + c] += rs * v * (-kf * kf * omega * omega * uc + gamma * omega * kf * us);
                r[ui + s] += rs * v * (-kf * kf * omega * omega * us - gamma * omega * kf * uc);
                jac[(uj + c) * dim + ui + c] += js * v * (-kf * kf * omega * omega);
                jac[(uj + s) * dim + ui + s] += js * v * (-kf * kf * omega * omega);
                jac[(uj + s) * dim + ui + c] += js * v * gamma * omega * kf;
                jac[(uj + c) * dim + ui + s] -= js * v * gamma * omega * kf;
                // ∂/∂ω and ∂/∂γ, times w0 for the scaled unknowns.
                let cw = rs * w0 * v;
                jac[iw * dim + ui + c] += cw * (-2.0 * kf * kf * omega * uc + gamma * kf * us);
                jac[iw * dim + ui + s] += cw * (-2.0 * kf * kf * omega * us - gamma * kf * uc);
                jac[ig * dim + ui + c] += cw * omega * kf * us;
                jac[ig * dim + ui + s] -= cw * omega * kf * uc;
            }
        }
        // Contact forces by AFT.
        let ns = self.smp.n();
        let nj = fourier::len(2 * h);
        let mut ws = self.smp.scratch();
        let mut us = [vec![0.0; ns], vec![0.0; ns]];
        let mut fs = [vec![0.0; ns], vec![0.0; ns]];
        let mut ps = [vec![0.0; ns], vec![0.0; ns]];
        let mut ds = [vec![0.0; ns], vec![0.0; ns], vec![0.0; ns], vec![0.0; ns]];
        let mut coef = vec![0.0; nj];
        let mut pen_mean = 0.0;
        let mut pen_grad = vec![0.0; iw];
        for sh in &self.shocks {
            let nc = sh.dofs.len().min(2);
            for c in 0..nc {
                let d = sh.dofs[c];
                self.smp
                    .synth_with(&u[d * nl..(d + 1) * nl], h, &mut us[c], &mut ws);
            }
            for t in 0..ns {
                let ut = [us[0][t], if nc > 1 { us[1][t] } else { 0.0 }];
                let (f, jt) = balance_law(sh, ut);
                for c in 0..nc {
                    fs[c][t] = f[c];
                    for c2 in 0..nc {
                        ds[c * 2 + c2][t] = jt[c * 2 + c2];
                    }
                }
                if sh.regularised.is_some() {
                    let (pf, _) = law(sh, ut);
                    for c in 0..nc {
                        ps[c][t] = pf[c];
                    }
                }
                pen_mean += penalty(sh, ut) / ns as f64;
            }
            for c in 0..nc {
                let d = sh.dofs[c];
                let mut fh = vec![0.0; nl];
                self.smp.analyse_with(&mut fs[c], h, &mut fh, &mut ws);
                for p in 0..nl {
                    r[d * nl + p] += rs * fh[p];
                }
                // The exact penalty's force when the balance uses the regularised law.
                if sh.regularised.is_some() {
                    self.smp.analyse_with(&mut ps[c], h, &mut fh, &mut ws);
                }
                // Gradient of the mean penalty energy: the force's harmonics, mean of
                // f·φ_q = a0 for the mean, a_k/2 and b_k/2 for the others.
                for p in 0..nl {
                    pen_grad[d * nl + p] += if p == 0 { fh[0] } else { 0.5 * fh[p] };
                }
                for c2 in 0..nc {
                    let d2 = sh.dofs[c2];
                    self.smp
                        .analyse_with(&mut ds[c * 2 + c2], 2 * h, &mut coef, &mut ws);
                    fourier::fill_mul_operator(
                        &coef,
                        2 * h,
                        h,
                        h,
                        js,
                        &mut jac[d2 * nl * dim + d * nl..],
                        dim,
                    );
                }
            }
        }
        // Phase: Σ_k k·s_k of the reference DOF (scaled unknowns).
        let rp = iw;
        let pd = self.phase_dof * nl;
        for k in 1..=h {
            let kf = k as f64;
            r[rp] += kf * x[pd + fourier::is(h, k)];
            jac[(pd + fourier::is(h, k)) * dim + rp] = kf;
        }
        // Energy held fixed, relative to the target.
        let re = ig;
        let es = 1.0 / self.target;
        let (e, grad_u, de_dw) = self.energy(self.held, &u, omega, pen_mean, &pen_grad);
        r[re] = (e - self.target) * es;
        for q in 0..iw {
            jac[q * dim + re] = grad_u[q] * es * len;
        }
        jac[iw * dim + re] = de_dw * es * w0;
    }

    /// The energy of kind `held` of the orbit (U physical, ω in rad/s), in J.
    fn energy_of(&self, held: HeldEnergy, u: &[f64], omega: f64) -> f64 {
        let ns = self.smp.n();
        let mut us = [vec![0.0; ns], vec![0.0; ns]];
        let mut pen_mean = 0.0;
        for sh in &self.shocks {
            let nc = sh.dofs.len().min(2);
            for c in 0..nc {
                let d = sh.dofs[c];
                self.smp
                    .synth(&u[d * self.nl..(d + 1) * self.nl], self.h, &mut us[c]);
            }
            for t in 0..ns {
                let ut = [us[0][t], if nc > 1 { us[1][t] } else { 0.0 }];
                pen_mean += penalty(sh, ut) / ns as f64;
            }
        }
        let zeros = vec![0.0; u.len()];
        self.energy(held, u, omega, pen_mean, &zeros).0
    }

    /// The held energy, its gradient in U and its derivative in ω.
    fn energy(
        &self,
        held: HeldEnergy,
        u: &[f64],
        omega: f64,
        pen_mean: f64,
        pen_grad: &[f64],
    ) -> (f64, Vec<f64>, f64) {
        let (n, h, nl) = (self.n, self.h, self.nl);
        let mut g = vec![0.0; n * nl];
        match held {
            HeldEnergy::Instant => {
                let (b, db) = basis_at(h, FRAC_PI_2);
                let at = |i: usize, w: &[f64]| -> f64 {
                    (0..nl).map(|q| w[q] * u[i * nl + q]).sum::<f64>()
                };
                let us: Vec<f64> = (0..n).map(|i| at(i, &b)).collect();
                let vs: Vec<f64> = (0..n).map(|i| at(i, &db)).collect();
                let mut e = 0.0;
                let mut ew = 0.0;
                let mut gu = vec![0.0; n];
                let mut gv = vec![0.0; n];
                for &(i, j, v) in &self.k {
                    e += 0.5 * v * us[i] * us[j];
                    gu[i] += 0.5 * v * us[j];
                    gu[j] += 0.5 * v * us[i];
                }
                for &(i, j, v) in &self.m {
                    ew += 0.5 * v * vs[i] * vs[j];
                    gv[i] += 0.5 * v * vs[j] * omega * omega;
                    gv[j] += 0.5 * v * vs[i] * omega * omega;
                }
                e += omega * omega * ew;
                for sh in &self.shocks {
                    let nc = sh.dofs.len().min(2);
                    let ut = [us[sh.dofs[0]], if nc > 1 { us[sh.dofs[1]] } else { 0.0 }];
                    e += penalty(sh, ut);
                    let (f, _) = law(sh, ut);
                    for c in 0..nc {
                        gu[sh.dofs[c]] += f[c];
                    }
                }
                for i in 0..n {
                    for q in 0..nl {
                        g[i * nl + q] = gu[i] * b[q] + gv[i] * db[q];
                    }
                }
                (e, g, 2.0 * omega * ew)
            }
            HeldEnergy::Mean => {
                // Parseval: mean of x·y = x0 y0 + ½ Σ (c c' + s s').
                let w = |q: usize| if q == 0 { 1.0 } else { 0.5 };
                let k2 = |q: usize| -> f64 {
                    let k = if q <= h { q } else { q - h };
                    (k * k) as f64
                };
                let mut e = pen_mean;
                let mut ew = 0.0;
                for &(i, j, v) in &self.k {
                    for q in 0..nl {
                        e += 0.5 * v * w(q) * u[i * nl + q] * u[j * nl + q];
                        g[i * nl + q] += 0.5 * v * w(q) * u[j * nl + q];
                        g[j * nl + q] += 0.5 * v * w(q) * u[i * nl + q];
                    }
                }
                for &(i, j, v) in &self.m {
                    for q in 1..nl {
                        let c = 0.5 * v * w(q) * k2(q);
                        ew += c * u[i * nl + q] * u[j * nl + q];
                        g[i * nl + q] += c * u[j * nl + q] * omega * omega;
                        g[j * nl + q] += c * u[i * nl + q] * omega * omega;
                    }
                }
                e += omega * omega * ew;
                for (gq, pq) in g.iter_mut().zip(pen_grad) {
                    *gq += pq;
                }
                (e, g, 2.0 * omega * ew)
            }
        }
    }
}

/// Values at θ of the basis functions of a series with h harmonics and of their θ-derivatives.
fn basis_at(h: usize, theta: f64) -> (Vec<f64>, Vec<f64>) {
    let nl = fourier::len(h);
    let mut b = vec![0.0; nl];
    let mut db = vec![0.0; nl];
    b[0] = 1.0;
    for k in 1..=h {
        let kf = k as f64;
        let (s, c) = (kf * theta).sin_cos();
        b[fourier::ic(k)] = c;
        b[fourier::is(h, k)] = s;
        db[fourier::ic(k)] = -kf * s;
        db[fourier::is(h, k)] = kf * c;
    }
    (b, db)
}

/// The DOF whose velocity is held at zero at t = 0: the first, unless it barely moves
/// (then the one that moves most), as EHMAN chooses it.
fn phase_dof(u: &[f64], n: usize, nl: usize) -> usize {
    let amp: Vec<f64> = (0..n)
        .map(|i| {
            u[i * nl + 1..(i + 1) * nl]
                .iter()
                .map(|v| v * v)
                .sum::<f64>()
                .sqrt()
        })
        .collect();
    let big = amp.iter().fold(0.0f64, |a, &b| a.max(b));
    if amp.first().is_some_and(|&a| a > 1e-3 * big) {
        0
    } else {
        (0..n)
            .max_by(|&a, &b| amp[a].total_cmp(&amp[b]))
            .unwrap_or(0)
    }
}

/// Corrects one point: `u0` its displacement harmonics (n × (2H_l+1), physical units, the
/// first n·(2H_l+1) values of `Point::x`), `omega0` its pulsation (rad/s), `energy` the
/// energy to hold (J, of the kind `settings.held`, usually the point's own). Returns the
/// corrected orbit, or an error when Newton does not reach `settings.prec` in
/// `settings.iter_max` iterations or the system is too large.
pub fn correct(
    problem: &Problem,
    settings: &ExactLawSettings,
    u0: &[f64],
    omega0: f64,
    energy: f64,
) -> Result<ExactPoint> {
    correct_on_law(problem, settings, u0, omega0, energy, Variant::default())
}

/// Which law a correction solves on, and how.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Variant {
    /// The engine's regularised law (PARA_REGUL, `point_law.rs`) instead of the exact one:
    /// the harmonic balance at NB_HARM_LINE with the force's harmonics computed from the
    /// law in time, as if NB_HARM_NONL were unbounded (error_sources.rs). The held energy
    /// keeps Code_Aster's penalty ½α(δ)₊² (as ENERGIE does).
    pub regularised: bool,
    /// Backtracking on ‖R‖: a Newton step that does not lower the residual is halved (up
    /// to [`BACKTRACKS`] times). A stiff stop barely touched makes the sampled law's
    /// residual kink sharply, and full steps then cycle; CORR_LOI_EXACTE keeps full steps.
    pub damped: bool,
}

/// Halvings of a damped Newton step at most.
pub const BACKTRACKS: usize = 12;

/// [`correct`] on the law and with the iteration of `variant`.
pub fn correct_on_law(
    problem: &Problem,
    settings: &ExactLawSettings,
    u0: &[f64],
    omega0: f64,
    energy: f64,
    variant: Variant,
) -> Result<ExactPoint> {
    let ctx = context(problem, settings, u0, omega0, energy, variant.regularised)?;
    let (n, nl, dim, len, ns) = (ctx.n, ctx.nl, ctx.dim, ctx.len, ctx.smp.n());
    let mut x: Vec<f64> = u0[..n * nl].iter().map(|v| v / len).collect();
    x.push(1.0);
    x.push(0.0);
    let mut r = vec![0.0; dim];
    let mut lu = DenseLu::default();
    let mut residuals = Vec::new();
    let norm = |v: &[f64]| v.iter().map(|a| a * a).sum::<f64>().sqrt();
    let mut it = 0;
    loop {
        let jac = lu.storage(dim)?;
        ctx.assemble(&x, &mut r, jac);
        let res = norm(&r) / norm(&x).max(1.0);
        residuals.push(res);
        if !res.is_finite() {
            return Err(Error::numerical(
                "the exact-law correction diverged (non-finite residual)",
            ));
        }
        if res <= settings.prec {
            break;
        }
        if it >= settings.iter_max {
            return Err(Error::numerical(format!(
                "the exact-law correction did not converge: ‖R‖ = {res:.3e} > {:.1e} after \
                 {it} iterations",
                settings.prec
            )));
        }
        lu.factor().map_err(|e| {
            Error::numerical(format!(
                "the exact-law correction's tangent is singular ({})",
                e.message
            ))
        })?;
        lu.solve(&mut r, 1)?;
        let mut lambda = 1.0;
        if variant.damped {
            let (mut rt, mut jt) = (vec![0.0; dim], vec![0.0; dim * dim]);
            for _ in 0..BACKTRACKS {
                let xt: Vec<f64> = x.iter().zip(&r).map(|(a, d)| a - lambda * d).collect();
                ctx.assemble(&xt, &mut rt, &mut jt);
                let rest = norm(&rt) / norm(&xt).max(1.0);
                if rest.is_finite() && rest < res {
                    break;
                }
                lambda *= 0.5;
            }
        }
        for (xi, di) in x.iter_mut().zip(&r) {
            *xi -= lambda * di;
        }
        it += 1;
    }
    let u: Vec<f64> = x[..n * nl].iter().map(|v| v * len).collect();
    let omega = x[n * nl] * omega0;
    let gamma = x[n * nl + 1] * omega0;
    Ok(ExactPoint {
        omega,
        frequency: omega / (2.0 * PI),
        gamma,
        energy: ctx.energy_of(HeldEnergy::Instant, &u, omega),
        energy_mean: ctx.energy_of(HeldEnergy::Mean, &u, omega),
        u,
        iterations: it,
        residuals,
        samples: ns,
    })
}

/// The checked data of a correction.
fn context(
    problem: &Problem,
    settings: &ExactLawSettings,
    u0: &[f64],
    omega0: f64,
    energy: f64,
    regularised: bool,
) -> Result<Ctx> {
    let n = problem.k.nrows();
    let h = settings.h_lin;
    let nl = fourier::len(h);
    check_size(n, h)?;
    let dim = n * nl + 2;
    if u0.len() < n * nl || !(omega0.is_finite() && omega0 > 0.0) {
        return Err(Error::internal(
            "exact-law correction: starting point of the wrong size or pulsation",
        ));
    }
    if !(energy.is_finite() && energy > 0.0) {
        return Err(Error::numerical(format!(
            "the exact-law correction needs a positive energy to hold (got {energy:e} J)"
        )));
    }
    let min_samples = fourier::fft_size(4 * h + 1);
    let ns = if settings.samples == 0 {
        default_samples(h)
    } else {
        settings.samples.max(min_samples)
    };
    let etas = if regularised {
        eta_phys(problem)?
    } else {
        vec![0.0; problem.shocks.len()]
    };
    let shocks: Vec<ExactShock> = problem
        .shocks
        .iter()
        .zip(etas)
        .map(|(s, eta)| ExactShock {
            law: s.law,
            dofs: s.dofs.clone(),
            gap: s.gap,
            alpha: s.stiffness,
            regularised: regularised.then_some(PointLaw {
                law: s.law,
                alpha: s.stiffness,
                gap: s.gap,
                eta,
            }),
        })
        .collect();
    let k = entries(&problem.k);
    let m = entries(&problem.m);
    let diag = |e: &[(usize, usize, f64)]| {
        e.iter()
            .filter(|t| t.0 == t.1)
            .fold(0.0f64, |a, t| a.max(t.2.abs()))
    };
    let kref = diag(&k).max(omega0 * omega0 * diag(&m));
    let umax = u0[..n * nl].iter().fold(0.0f64, |a, v| a.max(v.abs()));
    let gmax = shocks.iter().fold(0.0f64, |a, s| a.max(s.gap));
    let len = if gmax > 0.0 { gmax } else { umax.max(1e-300) };
    Ok(Ctx {
        n,
        h,
        nl,
        dim,
        k,
        m,
        shocks,
        smp: Sampler::new(ns),
        len,
        kref: if kref > 0.0 { kref } else { 1.0 },
        w0: omega0,
        phase_dof: phase_dof(u0, n, nl),
        held: settings.held,
        target: energy,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::accuracy::{cases, measure, CaseKind, Config, StudyCase};
    use crate::nnm::{continue_while, start_from_mode, CercleForm, Point, Shock};
    use faer::sparse::{SparseColMat, Triplet};

    /// EHMAN's branch of a study case up to energy `top`.
    fn branch(kind: CaseKind, cfg: &Config, top: f64) -> (StudyCase, Vec<Point>) {
        let case = StudyCase::new(kind);
        let problem = case.problem_with(cfg.regul);
        let s = measure::settings(cfg, 5, false);
        let st = start_from_mode(&problem, &s, &case.mode, 1.0, case.omega).unwrap();
        let out = continue_while(&problem, &s, st, &mut |r, _| r.energy_range.1 <= top);
        assert!(out.error.is_none(), "{:?}", out.error);
        (case, out.points)
    }

    fn coarse(h_lin: usize) -> Config {
        Config {
            sweep: "test",
            h_lin,
            h_nonl: 20,
            regul: 1e-3,
            prec_man: 1e-6,
            exact_law: 0,
        }
    }

    fn settings(h_lin: usize, prec: f64) -> ExactLawSettings {
        ExactLawSettings {
            h_lin,
            samples: samples_for(h_lin, 64),
            prec,
            iter_max: 15,
            held: HeldEnergy::Mean,
        }
    }

    /// Largest relative deviation from the closed form of the wall's points corrected on
    /// the exact law, and of EHMAN's own points.
    fn wall_errors(h_lin: usize) -> (f64, f64, usize) {
        let (case, pts) = branch(CaseKind::Wall, &coarse(h_lin), 1e-2);
        let (lo, hi) = case.range();
        let nl = fourier::len(h_lin);
        let (mut e_ehman, mut e_exact, mut count) = (0.0f64, 0.0f64, 0);
        for p in pts.iter().filter(|p| p.energy >= lo && p.energy <= hi) {
            let c = correct(
                &case.problem,
                &settings(h_lin, 1e-9),
                &p.x[..nl],
                p.omega,
                p.energy_mean,
            )
            .unwrap();
            // The held energy is held.
            assert!((c.energy_mean / p.energy_mean - 1.0).abs() < 1e-9);
            assert!(c.gamma.abs() < 1e-9 * c.omega, "γ = {:e}", c.gamma);
            e_ehman = e_ehman.max((p.frequency / cases::WALL.frequency_plan(p.energy) - 1.0).abs());
            e_exact =
                e_exact.max((c.frequency / cases::WALL.frequency_plan(p.energy_mean) - 1.0).abs());
            count += 1;
        }
        (e_ehman, e_exact, count)
    }

    #[test]
    fn corrected_wall_frequency_matches_the_exact_closed_form() {
        // sdnd122's oscillator over [1.2, 20]·E_c, EHMAN at η = 1e-3 (its points 1.6e-3 off
        // the closed form, trend 2 of docs/accuracy.md), every point corrected on the exact
        // law. What is left is the truncation at H_l harmonics (the sampling error, O(N⁻²)
        // at 64 samples per coefficient, is far below it: 16 per coefficient changed the
        // H_l = 10 error by 40 %, 64 by 1 %). The exact orbit is C¹ with jumps of ü at the
        // impacts, so its coefficients fall like k⁻³ and the truncated Galerkin orbit's
        // frequency converges at least as fast as H_l⁻³: measured 5.9e-6 at H_l = 10 and
        // 2.9e-7 at 20. The tolerances: 2e-5 at H_l = 10 (3× the measured value, 80× below
        // EHMAN's error at the same points) and a fall by at least 2³ = 8 to H_l = 20.
        let (ehman10, exact10, n10) = wall_errors(10);
        let (_, exact20, n20) = wall_errors(20);
        assert!(n10 > 20 && n20 > 20, "{n10}, {n20} points");
        assert!(ehman10 > 1e-3, "EHMAN at η = 1e-3: {ehman10:e}");
        assert!(exact10 < 2e-5, "corrected at H_l = 10: {exact10:e}");
        assert!(
            exact20 < exact10 / 8.0,
            "H_l 10: {exact10:e}, H_l 20: {exact20:e}"
        );
    }

    #[test]
    fn correction_converges_quadratically() {
        // A point of the η = 1e-3 branch at about 10 E_c (well into contact): Newton on the
        // sampled exact law, asked for 1e-14. Quadratic: each residual above the round-off
        // floor (1e-13) is at most C·(previous)² with one C for the whole sequence; and it
        // reaches PREC_NEWTON = 1e-9 within 4 iterations.
        let (case, pts) = branch(CaseKind::Wall, &coarse(10), 1e-2);
        let target = 10.0 * case.contact_energy;
        let p = pts
            .iter()
            .min_by(|a, b| {
                (a.energy - target)
                    .abs()
                    .total_cmp(&(b.energy - target).abs())
            })
            .unwrap();
        let nl = fourier::len(10);
        let c = correct(
            &case.problem,
            &settings(10, 1e-14),
            &p.x[..nl],
            p.omega,
            p.energy_mean,
        )
        .unwrap();
        let r = &c.residuals;
        assert!(r.len() >= 3, "{r:?}");
        assert!(r[0] > 1e-5, "the start is off the exact law: {r:?}");
        let ratios: Vec<f64> = r
            .windows(2)
            .filter(|w| w[1] > 1e-13)
            .map(|w| w[1] / (w[0] * w[0]))
            .collect();
        assert!(ratios.iter().all(|&q| q < 1e3), "{r:?}: {ratios:?}");
        let first_below = r.iter().position(|&x| x <= 1e-9).unwrap();
        assert!(first_below <= 4, "{r:?}");
    }

    /// A two-DOF chain with one shock of each law.
    fn two_dof(law: ShockLaw) -> Problem {
        let sp = |e: &[(usize, usize, f64)]| {
            let t: Vec<_> = e.iter().map(|&(r, c, v)| Triplet::new(r, c, v)).collect();
            SparseColMat::try_new_from_triplets(2, 2, &t).unwrap()
        };
        Problem {
            forcing: None,
            k: sp(&[(0, 0, 20.0), (0, 1, -10.0), (1, 0, -10.0), (1, 1, 10.0)]),
            m: sp(&[(0, 0, 1.0), (1, 1, 2.0)]),
            shocks: vec![Shock {
                law,
                dofs: if matches!(law, ShockLaw::Cercle { .. }) {
                    vec![0, 1]
                } else {
                    vec![1]
                },
                gap: 0.01,
                stiffness: 50.0,
                regul: 1e-3,
            }],
        }
    }

    #[test]
    fn jacobian_matches_finite_differences() {
        // Every law, exact and regularised (PARA_REGUL 1e-3), both held energies, at an
        // orbit that enters the stop for part of the period: central differences of the
        // sampled residual (step 1e-7 in scaled units; no sample crosses the gap within it
        // at this orbit, so the exact law's residual is smooth there, the regularised one
        // everywhere, and the difference is accurate to ~1e-8 relative to the Jacobian's
        // size).
        let h = 3;
        let nl = fourier::len(h);
        let mut u0 = vec![0.0; 2 * nl];
        for (i, amp) in [(0usize, 0.008), (1, 0.013)] {
            u0[i * nl + fourier::ic(1)] = amp;
            u0[i * nl + fourier::ic(2)] = 0.1 * amp;
            u0[i * nl + fourier::is(h, 2)] = -0.05 * amp;
            u0[i * nl + fourier::ic(3)] = 0.02 * amp;
            u0[i * nl] = 0.001;
        }
        for law in [
            ShockLaw::Plan,
            ShockLaw::BiPlan,
            ShockLaw::Cercle {
                origin: [0.0005, -0.0003],
                form: CercleForm::Secant,
            },
        ] {
            for (held, regularised) in [
                (HeldEnergy::Instant, false),
                (HeldEnergy::Mean, false),
                (HeldEnergy::Instant, true),
                (HeldEnergy::Mean, true),
            ] {
                let p = two_dof(law);
                let set = ExactLawSettings {
                    held,
                    ..settings(h, 1e-9)
                };
                let ctx = context(&p, &set, &u0, 3.0, 1e-3, regularised).unwrap();
                let dim = ctx.dim;
                let mut x: Vec<f64> = u0.iter().map(|v| v / ctx.len).collect();
                x.extend([1.1, 0.05]);
                let mut r = vec![0.0; dim];
                let mut jac = vec![0.0; dim * dim];
                ctx.assemble(&x, &mut r, &mut jac);
                let big = jac.iter().fold(0.0f64, |a, v| a.max(v.abs()));
                let (mut rp, mut rm, mut scratch) =
                    (vec![0.0; dim], vec![0.0; dim], vec![0.0; dim * dim]);
                let step = 1e-7;
                for j in 0..dim {
                    let mut xp = x.clone();
                    xp[j] += step;
                    ctx.assemble(&xp, &mut rp, &mut scratch);
                    let mut xm = x.clone();
                    xm[j] -= step;
                    ctx.assemble(&xm, &mut rm, &mut scratch);
                    for i in 0..dim {
                        let fd = (rp[i] - rm[i]) / (2.0 * step);
                        let a = jac[j * dim + i];
                        assert!(
                            (fd - a).abs() <= 1e-6 * big,
                            "{law:?} {held:?} regularised {regularised}: J[{i}][{j}] = {a:e}, \
                             differences {fd:e}"
                        );
                    }
                }
            }
        }
    }
}
