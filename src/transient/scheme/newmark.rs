//! NEWMARK (BETA, GAMMA; 0.25, 0.5 is the average acceleration, unconditionally stable
//! for the linear part). The shock forces are iterated, not extrapolated: at each step the
//! end-of-step acceleration solves
//!   M a + C (v̂ + γh a) + K (q̂ + βh² a) = f(t+h) + Σ_s Φ_sᵀ F_s(q̂ + βh² a, v̂ + γh a)
//! by Newton's method, the tangent being S + Σ_s D_sᵀ W_s D_s with S = M + γh C + βh² K
//! factorised once for the run, D_s the 3 relative rows of shock s and W_s = βh² K_s + γh C_s
//! its 3×3 tangent (normal penalty, plus RIGI_TAN/AMOR_TAN while sticking). The low-rank
//! shock part is handled by the Woodbury identity with G = D S⁻¹ Dᵀ (3 columns per shock,
//! computed once): each iteration costs two solves with S and a small dense solve of size
//! 3 × (number of shocks). The shock law is piecewise linear, so the iterations end
//! exactly in a few steps; they stop when the residual is below 1e-10 of |M a| (or the
//! correction below 1e-12 of |a|), when a correction saw no shock in contact (the step is
//! then linear and solved exactly by the factorised matrix), or when corrections below
//! 1e-8 of |a| stop decreasing (the round-off floor of K q, which grows with K's
//! conditioning: a fixed bound failed on beams of 400 DOFs and more); at most 50
//! iterations ([`TransientError::NotConverged`]).
//! Code_Aster's default TRAITEMENT_NONL='EXPLICITE' would take the forces from the previous
//! step instead (first order in time near contact); the iterated form keeps second order.
//! Unconditional stability holds for the linear part only: with PAS of the order of a
//! contact's duration (ω_c·PAS ≳ 1, ω_c² = (k + RIGI_NOR)/m) the trapezoidal rule with a
//! penalty contact can return more energy at a release than the impact stored, and grows.

use crate::transient::dis_choc::Shock;
use crate::transient::error::{try_zeros, TransientError};
use crate::transient::structure::{LinearSolver, Structure};
use crate::transient::system::{Model, Work};

const MAX_ITER: usize = 50;

/// A correction (relative to |a|) small enough that, once corrections stop decreasing,
/// the iterations are at the round-off floor of the residual.
const STALL_INCREMENT: f64 = 1e-8;

/// The scheme's factor and workspaces (nothing is allocated in `step`).
pub(crate) struct Newmark<'s> {
    beta: f64,
    gamma: f64,
    h: f64,
    solver: Box<dyn LinearSolver + 's>,
    p: usize,
    /// G = D S⁻¹ Dᵀ, p × p row-major.
    g: Vec<f64>,
    /// I + W G and its right-hand side.
    mat: Vec<f64>,
    w: Vec<f64>,
    dz: Vec<f64>,
    rhs: Vec<f64>,
    qp: Vec<f64>,
    vp: Vec<f64>,
    anew: Vec<f64>,
    r: Vec<f64>,
    z: Vec<f64>,
    ma: Vec<f64>,
}

fn inf_norm(x: &[f64]) -> f64 {
    x.iter().fold(0.0f64, |m, v| m.max(v.abs()))
}

impl<'s> Newmark<'s> {
    pub fn new(
        structure: &'s dyn Structure,
        shocks: &[Shock],
        beta: f64,
        gamma: f64,
        h: f64,
    ) -> Result<Newmark<'s>, TransientError> {
        let n = structure.n();
        let mut solver = structure.factor(1.0, gamma * h, beta * h * h)?;
        let p = 3 * shocks.len();
        let mut g = try_zeros("NEWMARK's shock matrix", p * p)?;
        let mut col = try_zeros("NEWMARK's workspace", n)?;
        for (sj, shock_j) in shocks.iter().enumerate() {
            for cj in 0..3 {
                col.iter_mut().for_each(|x| *x = 0.0);
                let mut unit = [0.0; 3];
                unit[cj] = 1.0;
                shock_j.relative_rows().add_transpose(unit, &mut col);
                solver.solve(&mut col)?;
                for (si, shock_i) in shocks.iter().enumerate() {
                    let u = shock_i.relative_rows().apply(&col);
                    for ci in 0..3 {
                        g[(3 * si + ci) * p + 3 * sj + cj] = u[ci];
                    }
                }
            }
        }
        Ok(Newmark {
            beta,
            gamma,
            h,
            solver,
            p,
            g,
            mat: try_zeros("NEWMARK's workspace", p * p)?,
            w: try_zeros("NEWMARK's workspace", p * p)?,
            dz: try_zeros("NEWMARK's workspace", p)?,
            rhs: try_zeros("NEWMARK's workspace", p)?,
            qp: try_zeros("NEWMARK's workspace", n)?,
            vp: try_zeros("NEWMARK's workspace", n)?,
            anew: try_zeros("NEWMARK's workspace", n)?,
            r: try_zeros("NEWMARK's workspace", n)?,
            z: try_zeros("NEWMARK's workspace", n)?,
            ma: col,
        })
    }

    /// One step from t to t + h (the h of `new`); `ws.evals` holds the shocks at the new
    /// state.
    #[allow(clippy::too_many_arguments)]
    pub fn step(
        &mut self,
        model: &Model,
        shocks: &[Shock],
        t: f64,
        q: &mut [f64],
        v: &mut [f64],
        a: &mut [f64],
        ws: &mut Work,
    ) -> Result<(), TransientError> {
        let (h, beta, gamma) = (self.h, self.beta, self.gamma);
        let n = q.len();
        for i in 0..n {
            self.qp[i] = q[i] + h * v[i] + (0.5 - beta) * h * h * a[i];
            self.vp[i] = v[i] + (1.0 - gamma) * h * a[i];
        }
        self.anew.copy_from_slice(a);
        let mut last_incr = f64::INFINITY;
        let mut prev_incr = f64::INFINITY;
        let mut linear = false;
        let mut iter = 0;
        loop {
            for i in 0..n {
                q[i] = self.qp[i] + beta * h * h * self.anew[i];
                v[i] = self.vp[i] + gamma * h * self.anew[i];
            }
            model.force(shocks, t + h, q, v, ws);
            model.structure.apply_mass(&self.anew, &mut self.ma);
            for i in 0..n {
                self.r[i] = ws.r[i] - self.ma[i];
            }
            let res = inf_norm(&self.r);
            // Converged: the residual or the correction at round-off; or no shock was
            // engaged in the last correction nor is now (the factorised matrix then solved
            // the step exactly: what is left is the round-off of K q, which grows with the
            // conditioning of K and may stay above any fixed bound); or the corrections
            // stopped decreasing while already small (the round-off floor).
            let stalled = iter >= 2 && last_incr >= 0.5 * prev_incr && last_incr <= STALL_INCREMENT;
            let exact = linear && !engaged(shocks, ws);
            if res <= 1e-10 * inf_norm(&self.ma) || last_incr <= 1e-12 || exact || stalled {
                break;
            }
            if iter == MAX_ITER {
                return Err(TransientError::NotConverged {
                    t: t + h,
                    iterations: iter,
                    increment: last_incr,
                });
            }
            linear = !self.correction(shocks, ws)?;
            let amax = inf_norm(&self.anew);
            for i in 0..n {
                self.anew[i] += self.z[i];
            }
            prev_incr = last_incr;
            last_incr = inf_norm(&self.z) / amax.max(inf_norm(&self.anew)).max(f64::MIN_POSITIVE);
            iter += 1;
        }
        a.copy_from_slice(&self.anew);
        Ok(())
    }

    /// z ← (S + Dᵀ W D)⁻¹ r by Woodbury: z = S⁻¹(r − Dᵀ w), (I + W G) w = W D S⁻¹ r.
    /// Whether a shock's tangent took part (false: z = S⁻¹ r, the step's linear solve).
    fn correction(&mut self, shocks: &[Shock], ws: &Work) -> Result<bool, TransientError> {
        let (h, beta, gamma, p) = (self.h, self.beta, self.gamma, self.p);
        self.z.copy_from_slice(&self.r);
        self.solver.solve(&mut self.z)?;
        self.w.iter_mut().for_each(|x| *x = 0.0);
        let mut any = false;
        for (s, (shock, ev)) in shocks.iter().zip(&ws.evals).enumerate() {
            let (k, c) = shock.tangent(ev);
            for i in 0..3 {
                for j in 0..3 {
                    let wij = beta * h * h * k[i][j] + gamma * h * c[i][j];
                    any |= wij != 0.0;
                    self.w[(3 * s + i) * p + 3 * s + j] = wij;
                }
            }
        }
        if !any {
            return Ok(false);
        }
        for (s, shock) in shocks.iter().enumerate() {
            let u = shock.relative_rows().apply(&self.z);
            self.dz[3 * s..3 * s + 3].copy_from_slice(&u);
        }
        // mat = I + W G (W block diagonal), rhs = W dz.
        for i in 0..p {
            let b = 3 * (i / 3);
            for j in 0..p {
                let mut v = if i == j { 1.0 } else { 0.0 };
                for k in b..b + 3 {
                    v += self.w[i * p + k] * self.g[k * p + j];
                }
                self.mat[i * p + j] = v;
            }
            self.rhs[i] = (b..b + 3).map(|k| self.w[i * p + k] * self.dz[k]).sum();
        }
        solve_dense(&mut self.mat, &mut self.rhs, p)?;
        // z = S⁻¹ (r − Dᵀ w).
        self.z.copy_from_slice(&self.r);
        for (s, shock) in shocks.iter().enumerate() {
            let wv = [-self.rhs[3 * s], -self.rhs[3 * s + 1], -self.rhs[3 * s + 2]];
            shock.relative_rows().add_transpose(wv, &mut self.z);
        }
        self.solver.solve(&mut self.z)?;
        Ok(true)
    }
}

/// Gaussian elimination with partial pivoting, in place (a: p × p row-major, b: p).
fn solve_dense(a: &mut [f64], b: &mut [f64], p: usize) -> Result<(), TransientError> {
    for k in 0..p {
        let piv = (k..p)
            .max_by(|&i, &j| a[i * p + k].abs().total_cmp(&a[j * p + k].abs()))
            .unwrap_or(k);
        let pivot = a[piv * p + k].abs();
        if pivot.is_nan() || pivot == 0.0 {
            return Err(TransientError::Singular {
                what: "NEWMARK's shock correction matrix".into(),
            });
        }
        if piv != k {
            for j in 0..p {
                a.swap(k * p + j, piv * p + j);
            }
            b.swap(k, piv);
        }
        let d = a[k * p + k];
        for i in k + 1..p {
            let f = a[i * p + k] / d;
            if f != 0.0 {
                for j in k..p {
                    a[i * p + j] -= f * a[k * p + j];
                }
                b[i] -= f * b[k];
            }
        }
    }
    for k in (0..p).rev() {
        let s: f64 = (k + 1..p).map(|j| a[k * p + j] * b[j]).sum();
        b[k] = (b[k] - s) / a[k * p + k];
    }
    Ok(())
}

/// Whether a shock contributes a tangent at the state `ws.evals` was evaluated at.
fn engaged(shocks: &[Shock], ws: &Work) -> bool {
    shocks.iter().zip(&ws.evals).any(|(shock, ev)| {
        let (k, c) = shock.tangent(ev);
        k.iter().chain(c.iter()).flatten().any(|&x| x != 0.0)
    })
}
