//! Restarted GMRES with a right preconditioner, for the contact blocks of the tangent.
//!
//! Right preconditioning (solve A P u = b, x = P u) minimises the residual of the original
//! system, so the stopping test is on ‖b − A x‖ itself. Each cycle ends with the true
//! residual recomputed from x (the Arnoldi estimate drifts from it near round-off), and a
//! solve is accepted when that residual is at the level a backward-stable direct solve
//! leaves: ‖b − A x‖ ≤ rtol·‖b‖ + BACKWARD·ε·‖A‖·‖x‖, ‖A‖ an upper bound the operator
//! supplies (and never above FLOOR_CAP·‖b‖). The workspace is allocated once for a dimension and a cycle length.

pub use crate::nnm::model::vector::norm;
use crate::nnm::model::vector::{add_scaled, dot, sub_scaled};

/// An operator and its preconditioner, applied to vectors of the workspace's dimension.
pub trait Preconditioned {
    /// y = A x.
    fn apply(&mut self, x: &[f64], y: &mut [f64]);
    /// y = P x.
    fn precondition(&mut self, x: &[f64], y: &mut [f64]);
    /// An upper bound of ‖A‖₂ (for the backward-error part of the stopping test).
    fn norm_bound(&self) -> f64;
}

/// Multiple of ε·‖A‖·‖x‖ accepted as converged (what an FFT-applied operator's own
/// round-off leaves: a few ε·log₂N).
const BACKWARD: f64 = 64.0;

/// Largest relative residual the backward-error floor may excuse.
const FLOOR_CAP: f64 = 1e-10;

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Stats {
    pub iterations: usize,
    /// ‖b − A x‖ / ‖b‖ at the end.
    pub relative_residual: f64,
}

#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Failure {
    /// The residual stopped decreasing above the tolerance (singular or too ill-conditioned
    /// operator for this preconditioner).
    Stagnated {
        iterations: usize,
        relative_residual: f64,
    },
    /// A value became NaN or infinite.
    NotFinite,
}

/// The acceptance test of a solve x of A x = b (module doc): residual norm `nr`, ‖b‖ = `nb`,
/// ‖A‖ ≤ `a_norm`, ‖x‖ = `nx`. The backward-error floor covers the last digits only: a
/// residual above FLOOR_CAP·‖b‖ is no solution whatever ‖x‖ (a singular A makes x explode).
pub fn converged(nr: f64, nb: f64, a_norm: f64, nx: f64, rtol: f64) -> bool {
    let target = rtol * nb;
    let floor = target + BACKWARD * f64::EPSILON * a_norm * nx;
    nr <= target || (nr <= floor && nr <= FLOOR_CAP * nb)
}

pub struct Gmres {
    n: usize,
    m: usize,
    max_cycles: usize,
    /// Krylov basis, (m+1) vectors of n.
    v: Vec<f64>,
    /// Hessenberg matrix after the Givens rotations, column-major (m+1) × m.
    h: Vec<f64>,
    cs: Vec<f64>,
    sn: Vec<f64>,
    g: Vec<f64>,
    y: Vec<f64>,
    w: Vec<f64>,
    z: Vec<f64>,
    r: Vec<f64>,
}

impl Gmres {
    /// Workspace for dimension `n`, cycles of `m` iterations, at most `max_cycles` cycles.
    pub fn new(n: usize, m: usize, max_cycles: usize) -> Gmres {
        let m = m.max(1);
        Gmres {
            n,
            m,
            max_cycles: max_cycles.max(1),
            v: vec![0.0; (m + 1) * n],
            h: vec![0.0; (m + 1) * m],
            cs: vec![0.0; m],
            sn: vec![0.0; m],
            g: vec![0.0; m + 1],
            y: vec![0.0; m],
            w: vec![0.0; n],
            z: vec![0.0; n],
            r: vec![0.0; n],
        }
    }

    /// Solve A x = b to relative residual `rtol` (or to the backward-error floor); `x` is
    /// overwritten (the initial guess is zero).
    pub fn solve(
        &mut self,
        op: &mut dyn Preconditioned,
        b: &[f64],
        x: &mut [f64],
        rtol: f64,
    ) -> Result<Stats, Failure> {
        x.fill(0.0);
        self.iterate(op, b, x, rtol)
    }

    /// [`Gmres::solve`] from the initial guess in `x` (the solution of a nearby system: the
    /// same block at the previous factorisation), accepted by the same test. A guess that
    /// does not lead there (stagnation near the floor, non-finite values) is dropped and the
    /// solve restarts from zero, so the outcome is never worse than `solve`'s.
    pub fn solve_from(
        &mut self,
        op: &mut dyn Preconditioned,
        b: &[f64],
        x: &mut [f64],
        rtol: f64,
    ) -> Result<Stats, Failure> {
        if x.iter().all(|v| *v == 0.0) || !x.iter().all(|v| v.is_finite()) {
            return self.solve(op, b, x, rtol);
        }
        match self.iterate(op, b, x, rtol) {
            Ok(st) => Ok(st),
            Err(_) => self.solve(op, b, x, rtol),
        }
    }

    /// The restarted iteration from the guess in `x` (zero or not).
    fn iterate(
        &mut self,
        op: &mut dyn Preconditioned,
        b: &[f64],
        x: &mut [f64],
        rtol: f64,
    ) -> Result<Stats, Failure> {
        let n = self.n;
        let nb = norm(b);
        if nb == 0.0 {
            x.fill(0.0);
            return Ok(Stats {
                iterations: 0,
                relative_residual: 0.0,
            });
        }
        if !nb.is_finite() {
            return Err(Failure::NotFinite);
        }
        let a_norm = op.norm_bound();
        let mut beta = nb;
        self.r.copy_from_slice(b);
        if x.iter().any(|v| *v != 0.0) {
            op.apply(x, &mut self.w);
            for (r, ax) in self.r.iter_mut().zip(&self.w) {
                *r -= ax;
            }
            beta = norm(&self.r);
            if !beta.is_finite() {
                return Err(Failure::NotFinite);
            }
            if converged(beta, nb, a_norm, norm(x), rtol) {
                return Ok(Stats {
                    iterations: 0,
                    relative_residual: beta / nb,
                });
            }
        }
        let mut iterations = 0;
        for _cycle in 0..self.max_cycles {
            let target = rtol * nb;
            let k = self.cycle(op, beta, target, &mut iterations)?;
            // x += P (V_k y).
            self.w.fill(0.0);
            for (j, &yj) in self.y[..k].iter().enumerate() {
                add_scaled(&mut self.w, yj, &self.v[j * n..(j + 1) * n]);
            }
            op.precondition(&self.w, &mut self.z);
            for (xi, zi) in x.iter_mut().zip(&self.z) {
                *xi += zi;
            }
            // True residual.
            op.apply(x, &mut self.w);
            for ((r, bi), ax) in self.r.iter_mut().zip(b).zip(&self.w) {
                *r = bi - ax;
            }
            let nr = norm(&self.r);
            if !nr.is_finite() {
                return Err(Failure::NotFinite);
            }
            if converged(nr, nb, a_norm, norm(x), rtol) {
                return Ok(Stats {
                    iterations,
                    relative_residual: nr / nb,
                });
            }
            // A cycle that did not halve the residual will not converge by restarting.
            if nr > 0.5 * beta {
                return Err(Failure::Stagnated {
                    iterations,
                    relative_residual: nr / nb,
                });
            }
            beta = nr;
        }
        Err(Failure::Stagnated {
            iterations,
            relative_residual: norm(&self.r) / nb,
        })
    }

    /// One Arnoldi cycle from the residual in `self.r` (norm `beta`); leaves the
    /// coefficients in `self.y` and returns their number.
    fn cycle(
        &mut self,
        op: &mut dyn Preconditioned,
        beta: f64,
        target: f64,
        iterations: &mut usize,
    ) -> Result<usize, Failure> {
        let (n, m) = (self.n, self.m);
        let ld = m + 1;
        for (v, r) in self.v[..n].iter_mut().zip(&self.r) {
            *v = r / beta;
        }
        self.g.fill(0.0);
        self.g[0] = beta;
        let mut k = 0;
        while k < m {
            // w = A P v_k.
            {
                let (head, _) = self.v.split_at((k + 1) * n);
                op.precondition(&head[k * n..], &mut self.z);
            }
            op.apply(&self.z, &mut self.w);
            *iterations += 1;
            // Modified Gram-Schmidt, twice (the second pass keeps the basis orthogonal to
            // working precision, which a 1e-14 target needs).
            let col = &mut self.h[k * ld..(k + 1) * ld];
            col.fill(0.0);
            for _pass in 0..2 {
                for (j, hj) in col.iter_mut().enumerate().take(k + 1) {
                    let vj = &self.v[j * n..(j + 1) * n];
                    let c = dot(&self.w, vj);
                    *hj += c;
                    sub_scaled(&mut self.w, c, vj);
                }
            }
            let hn = norm(&self.w);
            if !hn.is_finite() {
                return Err(Failure::NotFinite);
            }
            col[k + 1] = hn;
            if hn > 0.0 {
                let next = &mut self.v[(k + 1) * n..(k + 2) * n];
                for (v, w) in next.iter_mut().zip(&self.w) {
                    *v = w / hn;
                }
            }
            // Previous rotations, then a new one that zeroes h[k+1].
            for j in 0..k {
                let (a, b) = (col[j], col[j + 1]);
                col[j] = self.cs[j] * a + self.sn[j] * b;
                col[j + 1] = -self.sn[j] * a + self.cs[j] * b;
            }
            let (a, b) = (col[k], col[k + 1]);
            let rho = a.hypot(b);
            let (c, s) = if rho == 0.0 {
                (1.0, 0.0)
            } else {
                (a / rho, b / rho)
            };
            self.cs[k] = c;
            self.sn[k] = s;
            col[k] = rho;
            col[k + 1] = 0.0;
            self.g[k + 1] = -s * self.g[k];
            self.g[k] *= c;
            k += 1;
            // A breakdown (hn = 0) means the solution lies in the basis built so far.
            if self.g[k].abs() <= target || hn == 0.0 {
                break;
            }
        }
        // Back substitution with the triangular R.
        for i in (0..k).rev() {
            let mut s = self.g[i];
            for j in i + 1..k {
                s -= self.h[j * ld + i] * self.y[j];
            }
            let d = self.h[i * ld + i];
            self.y[i] = if d != 0.0 { s / d } else { 0.0 };
        }
        Ok(k)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A dense nonsymmetric test operator with a diagonal (Jacobi) preconditioner.
    struct Dense {
        n: usize,
        a: Vec<f64>,
        inv_diag: Vec<f64>,
    }

    impl Preconditioned for Dense {
        fn apply(&mut self, x: &[f64], y: &mut [f64]) {
            for (yi, row) in y.iter_mut().zip(self.a.chunks_exact(self.n)) {
                *yi = row.iter().zip(x).map(|(a, b)| a * b).sum();
            }
        }
        fn precondition(&mut self, x: &[f64], y: &mut [f64]) {
            for ((yi, d), xi) in y.iter_mut().zip(&self.inv_diag).zip(x) {
                *yi = d * xi;
            }
        }
        fn norm_bound(&self) -> f64 {
            self.a.iter().map(|v| v * v).sum::<f64>().sqrt()
        }
    }

    fn operator(n: usize, spread: f64) -> Dense {
        // Diagonal from 1 to `spread` plus a small nonsymmetric coupling.
        let mut a = vec![0.0; n * n];
        for i in 0..n {
            a[i * n + i] = 1.0 + spread * i as f64 / n as f64;
            for j in 0..n {
                if i != j {
                    a[i * n + j] = 0.3 * (((i * 7 + j * 3) % 11) as f64 / 11.0 - 0.5) / n as f64;
                }
            }
        }
        let inv_diag = (0..n).map(|i| 1.0 / a[i * n + i]).collect();
        Dense { n, a, inv_diag }
    }

    #[test]
    fn solves_to_the_requested_residual_and_restarts() {
        let n = 60;
        let mut op = operator(n, 1e3);
        let x_true: Vec<f64> = (0..n).map(|i| (i as f64 * 0.37).sin()).collect();
        let mut b = vec![0.0; n];
        op.apply(&x_true, &mut b);
        // Short cycles force restarts.
        for m in [60, 5] {
            let mut g = Gmres::new(n, m, 50);
            let mut x = vec![0.0; n];
            let st = g.solve(&mut op, &b, &mut x, 1e-13).unwrap();
            let mut r = vec![0.0; n];
            op.apply(&x, &mut r);
            let res = r
                .iter()
                .zip(&b)
                .map(|(a, c)| (a - c).powi(2))
                .sum::<f64>()
                .sqrt()
                / norm(&b);
            assert!(res < 1e-13, "m {m}: residual {res}");
            assert!((st.relative_residual - res).abs() < 1e-15);
            let err = x
                .iter()
                .zip(&x_true)
                .map(|(a, c)| (a - c).abs())
                .fold(0.0, f64::max);
            assert!(err < 1e-11, "m {m}: error {err}");
        }
    }

    #[test]
    fn a_singular_operator_is_reported_as_stagnation() {
        let n = 20;
        let mut op = operator(n, 1.0);
        // Two equal rows: singular; a right-hand side outside the range.
        for j in 0..n {
            op.a[n + j] = op.a[j];
        }
        let mut b = vec![0.0; n];
        b[1] = 1.0;
        let mut g = Gmres::new(n, 30, 5);
        let mut x = vec![0.0; n];
        match g.solve(&mut op, &b, &mut x, 1e-13) {
            Err(Failure::Stagnated {
                relative_residual, ..
            }) => {
                assert!(relative_residual > 1e-3)
            }
            other => panic!("expected stagnation, got {other:?}"),
        }
    }

    /// From the solution of a nearby system the solve needs fewer iterations and meets the
    /// same residual; a useless guess (non-finite) falls back to the cold solve.
    #[test]
    fn a_warm_start_meets_the_same_test_in_fewer_iterations() {
        let n = 60;
        let mut op = operator(n, 1e3);
        let b: Vec<f64> = (0..n).map(|i| (i as f64 * 0.21).cos()).collect();
        let mut g = Gmres::new(n, 40, 4);
        let mut x = vec![0.0; n];
        let cold = g.solve(&mut op, &b, &mut x, 1e-13).unwrap();
        // A nearby operator: the old solution as the guess.
        for i in 0..n {
            op.a[i * n + i] *= 1.0 + 1e-6;
        }
        let mut warm_x = x.clone();
        let warm = g.solve_from(&mut op, &b, &mut warm_x, 1e-13).unwrap();
        let mut cold_x = vec![0.0; n];
        let again = g.solve(&mut op, &b, &mut cold_x, 1e-13).unwrap();
        assert!(warm.relative_residual <= 1e-13, "{warm:?}");
        assert!(
            warm.iterations < again.iterations,
            "{warm:?} vs {again:?} ({cold:?})"
        );
        let mut bad = vec![f64::NAN; n];
        let st = g.solve_from(&mut op, &b, &mut bad, 1e-13).unwrap();
        assert_eq!(st.iterations, again.iterations);
    }

    #[test]
    fn zero_right_hand_side_gives_zero() {
        let mut op = operator(5, 1.0);
        let mut g = Gmres::new(5, 5, 2);
        let mut x = vec![1.0; 5];
        let st = g.solve(&mut op, &[0.0; 5], &mut x, 1e-14).unwrap();
        assert_eq!(st.iterations, 0);
        assert!(x.iter().all(|&v| v == 0.0));
    }
}
