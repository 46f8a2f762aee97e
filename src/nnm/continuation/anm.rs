//! Asymptotic numerical method: the power series X(a) = X0 + Σ a^p X_p of one branch.
//!
//! One factorisation of the bordered tangent [L_t; tᵀ] (t: the previous branch's end
//! tangent, or a guess at the start) serves every order: order 1 is its solution y for the
//! right-hand side (0, 1), X_1 = ±y/‖y‖; order p solves for z with (−Σ Q(X_r, X_{p−r}), 0)
//! and adds the multiple of y that makes X_p·X_1 = 0 (y spans the kernel of L_t).
//! Step length: Code_Aster's, a_max = (PREC_MAN/‖R_{N+1}‖)^{1/(N+1)} with R_{N+1} the
//! residual of the first neglected order (not the classic estimate (ε‖X_1‖/‖X_N‖)^{1/(N−1)}, docs/ehman.md §4): with it
//! the NB_BRANCHE of Code_Aster's command files covers the same energy range (sdnd122a:
//! 105 branches reach past ENERGIE = 6.5e-3, which the classic estimate does not).

use crate::nnm::continuation::pade::Pade;
use crate::nnm::error::{Error, Result};
use crate::nnm::model::system::{Grid, Samples, System};
use crate::nnm::model::workspace::Workspace;
use crate::nnm::solve::linear_solver::TangentSolver;

pub struct Series {
    /// X_1..X_N (terms[0] = X_1).
    pub terms: Vec<Vec<f64>>,
    pub a_max: f64,
    /// Distance along a to a simple bifurcation detected from the geometric tail, when it
    /// lies inside this branch.
    pub bifurcation: Option<f64>,
    /// The rational form of the terms that `eval` and `unit_tangent` use instead of the
    /// power series, when the step was extended by it (series_step.rs, pade.rs).
    pub pade: Option<Pade>,
}

pub use crate::nnm::model::vector::dot_in_order as dot;

pub fn norm(a: &[f64]) -> f64 {
    dot(a, a).sqrt()
}

impl Series {
    /// X(a).
    pub fn eval(&self, x0: &[f64], a: f64) -> Vec<f64> {
        if let Some(p) = &self.pade {
            return p.eval(x0, a);
        }
        self.eval_series(x0, a)
    }

    /// X(a) from the power series itself.
    pub fn eval_series(&self, x0: &[f64], a: f64) -> Vec<f64> {
        let mut x = x0.to_vec();
        let mut ap = 1.0;
        for t in &self.terms {
            ap *= a;
            for (xi, ti) in x.iter_mut().zip(t) {
                *xi += ap * ti;
            }
        }
        x
    }

    /// dX/da at a, normalised.
    pub fn unit_tangent(&self, a: f64) -> Vec<f64> {
        if let Some(p) = &self.pade {
            return p.unit_tangent(a);
        }
        let mut d = vec![0.0; self.terms.first().map_or(0, |t| t.len())];
        let mut ap = 1.0;
        for (p, t) in self.terms.iter().enumerate() {
            for (di, ti) in d.iter_mut().zip(t) {
                *di += (p + 1) as f64 * ap * ti;
            }
            ap *= a;
        }
        let n = norm(&d);
        d.iter_mut().for_each(|v| *v /= n);
        d
    }
}

/// Settings of one series computation.
pub struct AnmParams {
    pub order: usize,
    pub prec: f64,
    pub bif_terms: usize,
    pub bif_tol: f64,
}

/// Compute the series at `x0`, `solver` holding the factorisation of the bordered tangent
/// [R_X(x0); borderᵀ]; `orient(X_1)` returns ±1, the sign that X_1 must take to keep the
/// wanted direction.
pub fn compute(
    sys: &System,
    ws: &mut Workspace,
    solver: &mut dyn TangentSolver,
    x0: &[f64],
    p: &AnmParams,
    orient: &dyn Fn(&[f64]) -> f64,
) -> Result<Series> {
    let n = sys.lay.n_unk;
    let mut y = vec![0.0; n];
    y[n - 1] = 1.0;
    solver.solve(sys, &mut y)?;
    let ny = norm(&y);
    if !(ny.is_finite() && ny > 0.0) {
        return Err(Error::numerical(
            "the tangent direction (order 1) is zero or not finite: singular bordered tangent",
        ));
    }
    let mut x1: Vec<f64> = y.iter().map(|v| v / ny).collect();
    if orient(&x1) < 0.0 {
        x1.iter_mut().for_each(|v| *v = -*v);
    }
    let y_x1 = dot(&y, &x1);
    // Each term's law variables sampled in time once: every product of two terms is then a
    // pointwise product (cheaper than a convolution at every H_nl measured, 5 to 1000).
    // When X0 and X_1 are time-symmetric, every term is in exact arithmetic (the system is
    // reversible, the phase condition keeps t = 0 a turning point, and the orders' right-
    // hand sides are products of symmetric terms), so the law variables are cosine series:
    // sampled on half the instants, their sine parts (round-off) dropped from the
    // products. X_1 is checked too: at a symmetry-breaking bifurcation the branch leaves
    // a symmetric X0 along a direction that is not.
    let grid =
        if sys.is_reversible() && sys.lay.is_time_symmetric(x0) && sys.lay.is_time_symmetric(&x1) {
            Grid::Cosine
        } else {
            Grid::Full
        };
    let sampled = |x: &[f64], ws: &mut Workspace| sys.samples_on(x, grid, ws);
    let mut samples = vec![sampled(&x1, ws)];
    let mut terms = vec![x1];
    for order in 2..=p.order {
        let mut rhs = vec![0.0; n];
        let pairs: Vec<(&[f64], &[f64])> = (1..order)
            .map(|r| (terms[r - 1].as_slice(), terms[order - r - 1].as_slice()))
            .collect();
        let cache: Vec<_> = (1..order)
            .map(|r| (&samples[r - 1], &samples[order - r - 1]))
            .collect();
        sys.quad_sum_cached(&pairs, Some(&cache), &mut rhs[..n - 1], ws);
        rhs.iter_mut().for_each(|v| *v = -*v);
        rhs[n - 1] = 0.0;
        solver.solve(sys, &mut rhs)?;
        let c = dot(&rhs, &terms[0]) / y_x1;
        for (z, yi) in rhs.iter_mut().zip(&y) {
            *z -= c * yi;
        }
        if rhs.iter().any(|v| !v.is_finite()) {
            return Err(Error::numerical(format!(
                "series term of order {order} is not finite"
            )));
        }
        samples.push(sampled(&rhs, ws));
        terms.push(rhs);
    }
    let last = terms.len();
    let mut a_max = step_length(sys, ws, &terms, Some(&samples), p.prec);
    ws.recycle_samples(samples);
    let mut bifurcation = None;
    if let Some(r) = geometric_ratio(&terms, p.bif_terms, p.bif_tol) {
        // Cochelin & Medale (2013): the tail is X_p ≈ X_N r^{p−N}; remove it from every
        // term, and the remaining series is regular through the bifurcation at a = 1/r.
        let a_b = 1.0 / r;
        if a_b > 0.0 {
            let xn = terms[last - 1].clone();
            for (i, t) in terms.iter_mut().enumerate() {
                let f = r.powi(i as i32 + 1 - last as i32);
                for (ti, xi) in t.iter_mut().zip(&xn) {
                    *ti -= f * xi;
                }
            }
            terms.pop();
            let a_reg = step_length(sys, ws, &terms, None, p.prec);
            if a_reg.is_finite() && a_reg >= a_b {
                a_max = a_reg;
                bifurcation = Some(a_b);
            } else {
                // The bifurcation lies beyond what the regular part reaches: keep the
                // original series; the next branch will meet it.
                terms.push(vec![0.0; n]);
                let xn_ref = &xn;
                for (i, t) in terms.iter_mut().enumerate() {
                    let f = r.powi(i as i32 + 1 - last as i32);
                    for (ti, xi) in t.iter_mut().zip(xn_ref) {
                        *ti += f * xi;
                    }
                }
            }
        }
    }
    // A (nearly) linear problem has vanishing high orders and an unbounded a_max: cap the
    // step at ten times the size of the point (a linear family is exact at any length).
    let cap = 10.0 * norm(x0).max(1.0);
    if a_max > cap {
        a_max = cap;
    }
    if !(a_max.is_finite() && a_max > 0.0) {
        return Err(Error::numerical(format!(
            "the step length a_max = {a_max} is not usable"
        )));
    }
    Ok(Series {
        terms,
        a_max,
        bifurcation,
        pade: None,
    })
}

/// a_max = (PREC_MAN/‖R_{N+1}‖)^{1/(N+1)}, R_{N+1} = Σ_{r=1..N} Q(X_r, X_{N+1−r}) the
/// residual of the first neglected order, so that ‖R(X(a_max))‖ ≈ PREC_MAN.
/// `samples`: the terms' time samples (`System::samples`), when the caller has them.
fn step_length(
    sys: &System,
    ws: &mut Workspace,
    terms: &[Vec<f64>],
    samples: Option<&[Samples]>,
    prec: f64,
) -> f64 {
    let last = terms.len();
    let mut r = vec![0.0; sys.lay.n_eq()];
    let pairs: Vec<(&[f64], &[f64])> = (1..=last)
        .map(|k| (terms[k - 1].as_slice(), terms[last - k].as_slice()))
        .collect();
    match samples {
        Some(s) => {
            let cache: Vec<_> = (1..=last).map(|k| (&s[k - 1], &s[last - k])).collect();
            sys.quad_sum_cached(&pairs, Some(&cache), &mut r, ws);
        }
        None => sys.quad_sum(&pairs, &mut r, ws),
    }
    (prec / norm(&r).max(f64::MIN_POSITIVE)).powf(1.0 / (last + 1) as f64)
}

/// Signed common ratio r of the last `m` terms when they form a geometric series along one
/// direction: consecutive ratios agree and consecutive terms are aligned, within `tol`.
pub fn geometric_ratio(terms: &[Vec<f64>], m: usize, tol: f64) -> Option<f64> {
    let n = terms.len();
    if m < 2 || n < m + 1 {
        return None;
    }
    let mut ratios = Vec::new();
    for p in n - m + 1..n {
        let (a, b) = (&terms[p - 1], &terms[p]);
        let (na, nb) = (norm(a), norm(b));
        if na == 0.0 || nb == 0.0 {
            return None;
        }
        let c = dot(a, b) / (na * nb);
        if 1.0 - c.abs() > tol {
            return None;
        }
        ratios.push(dot(a, b) / (na * na));
    }
    for w in ratios.windows(2) {
        if (w[1] / w[0] - 1.0).abs() > tol {
            return None;
        }
    }
    ratios.last().copied()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn geometric_tail_is_recognised() {
        let d = [0.6, -0.8];
        let mk = |p: i32, r: f64| d.iter().map(|v| v * r.powi(p)).collect::<Vec<f64>>();
        let terms: Vec<Vec<f64>> = (1..=10).map(|p| mk(p, 1.7)).collect();
        let r = geometric_ratio(&terms, 3, 1e-8).unwrap();
        assert!((r - 1.7).abs() < 1e-12);
        let mut bent = terms.clone();
        bent[9][0] += 0.3;
        assert!(geometric_ratio(&bent, 3, 1e-4).is_none());
    }
}
