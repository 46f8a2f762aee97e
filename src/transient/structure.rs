//! The linear part M q̈ + C q̇ + K q of the equations, as the schemes see it: products,
//! the mass solve, the factorisation of a_m M + a_c C + a_k K for a fixed step, and the
//! largest eigenvalue of M⁻¹(K + K_extra) for the explicit scheme's stability limit.
//! Implementations: [`super::dense::DenseStructure`] (generalized matrices) and
//! [`super::sparse::SparseStructure`] (physical matrices on the free DOFs).

use super::error::TransientError;

/// A factorised matrix, solved many times with the same workspace.
pub trait LinearSolver {
    /// x ← A⁻¹ x.
    fn solve(&mut self, x: &mut [f64]) -> Result<(), TransientError>;
}

/// M, C, K of the linear structure (symmetric, M definite).
pub trait Structure {
    /// Number of unknowns.
    fn n(&self) -> usize;
    /// out ← K q.
    fn apply_stiffness(&self, q: &[f64], out: &mut [f64]);
    /// out ← C v (zero without damping).
    fn apply_damping(&self, v: &[f64], out: &mut [f64]);
    /// out ← M a.
    fn apply_mass(&self, a: &[f64], out: &mut [f64]);
    /// Whether C is present (a scheme may skip C v).
    fn has_damping(&self) -> bool;
    /// rhs ← M⁻¹ rhs (M factorised once, at construction).
    fn solve_mass(&self, rhs: &mut [f64]) -> Result<(), TransientError>;
    /// Factorises a_m M + a_c C + a_k K (an implicit scheme's matrix for a fixed step).
    fn factor(
        &self,
        a_m: f64,
        a_c: f64,
        a_k: f64,
    ) -> Result<Box<dyn LinearSolver + '_>, TransientError>;
    /// The largest eigenvalue ω²_max of (K + K_extra, M), K_extra given by its product
    /// (`extra(x, out)` adds K_extra x to out). The default is a power iteration (an
    /// estimate from below, converged to 1e-8 relative or 2000 iterations).
    fn max_eigenvalue(&self, extra: &dyn Fn(&[f64], &mut [f64])) -> Result<f64, TransientError> {
        power_iteration(self, extra, 2000)
    }
    /// A rough ω²_max, from below: `iterations` steps of the power iteration at most (for
    /// a scale, where [`Structure::max_eigenvalue`]'s convergence would cost thousands of
    /// mass solves on a large model).
    fn max_eigenvalue_estimate(
        &self,
        extra: &dyn Fn(&[f64], &mut [f64]),
        iterations: usize,
    ) -> Result<f64, TransientError> {
        power_iteration(self, extra, iterations)
    }
}

/// Power iteration on M⁻¹(K + K_extra) from a deterministic start, `max_iter` steps at
/// most.
pub(crate) fn power_iteration<S: Structure + ?Sized>(
    s: &S,
    extra: &dyn Fn(&[f64], &mut [f64]),
    max_iter: usize,
) -> Result<f64, TransientError> {
    let n = s.n();
    if n == 0 {
        return Ok(0.0);
    }
    // A start with every component present (a low-discrepancy sequence).
    let mut x: Vec<f64> = (0..n)
        .map(|i| 0.5 + ((i as f64 + 1.0) * 0.618_033_988_749_895).fract())
        .collect();
    let mut y = vec![0.0; n];
    let mut mx = vec![0.0; n];
    let mut lambda = 0.0;
    for _ in 0..max_iter {
        s.apply_stiffness(&x, &mut y);
        extra(&x, &mut y);
        // Rayleigh quotient xᵀ(K+Ke)x / xᵀMx.
        s.apply_mass(&x, &mut mx);
        let num: f64 = x.iter().zip(&y).map(|(a, b)| a * b).sum();
        let den: f64 = x.iter().zip(&mx).map(|(a, b)| a * b).sum();
        let new = if den > 0.0 { num / den } else { 0.0 };
        s.solve_mass(&mut y)?;
        let norm = y.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        if !(norm > 0.0 && norm.is_finite()) {
            return Ok(new.max(0.0));
        }
        for (xi, yi) in x.iter_mut().zip(&y) {
            *xi = yi / norm;
        }
        if (new - lambda).abs() <= 1e-8 * new.abs() {
            return Ok(new);
        }
        lambda = new;
    }
    Ok(lambda)
}
