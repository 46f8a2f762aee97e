//! Dense linear algebra of the references (models of at most a dozen DOFs): the solution of
//! K x = b, and the generalised eigenproblem K φ = ω² M φ by a Cholesky factor of M and
//! cyclic Jacobi rotations. Written here so that no reference shares a solver with the code
//! it checks.

/// Row-major dense matrix of size n × n.
pub type Dense = Vec<f64>;

/// Solves A x = b by Gaussian elimination with partial pivoting; None if A is singular.
pub fn solve(a: &[f64], b: &[f64]) -> Option<Vec<f64>> {
    let n = b.len();
    let mut a = a.to_vec();
    let mut x = b.to_vec();
    for c in 0..n {
        let p = (c..n).max_by(|&i, &j| a[i * n + c].abs().total_cmp(&a[j * n + c].abs()))?;
        if a[p * n + c] == 0.0 {
            return None;
        }
        for j in 0..n {
            a.swap(c * n + j, p * n + j);
        }
        x.swap(c, p);
        for i in c + 1..n {
            let f = a[i * n + c] / a[c * n + c];
            for j in c..n {
                a[i * n + j] -= f * a[c * n + j];
            }
            x[i] -= f * x[c];
        }
    }
    for c in (0..n).rev() {
        let s: f64 = (c + 1..n).map(|j| a[c * n + j] * x[j]).sum();
        x[c] = (x[c] - s) / a[c * n + c];
    }
    Some(x)
}

/// The inverse of A, column by column.
pub fn inverse(a: &[f64], n: usize) -> Option<Dense> {
    let mut inv = vec![0.0; n * n];
    for c in 0..n {
        let mut e = vec![0.0; n];
        e[c] = 1.0;
        let x = solve(a, &e)?;
        for r in 0..n {
            inv[r * n + c] = x[r];
        }
    }
    Some(inv)
}

/// y = A x.
pub fn mul(a: &[f64], x: &[f64]) -> Vec<f64> {
    let n = x.len();
    (0..n)
        .map(|i| (0..n).map(|j| a[i * n + j] * x[j]).sum())
        .collect()
}

/// ½ xᵀ A x.
pub fn half_quad(a: &[f64], x: &[f64]) -> f64 {
    0.5 * x.iter().zip(mul(a, x)).map(|(p, q)| p * q).sum::<f64>()
}

/// Eigenpairs of K φ = ω² M φ (K, M symmetric, M positive definite): ω² ascending and the
/// shapes φ (mass-normalised, φᵀ M φ = 1).
pub fn modes(k: &[f64], m: &[f64], n: usize) -> Option<(Vec<f64>, Vec<Vec<f64>>)> {
    // M = L Lᵀ.
    let mut l = vec![0.0; n * n];
    for i in 0..n {
        for j in 0..=i {
            let s: f64 = (0..j).map(|p| l[i * n + p] * l[j * n + p]).sum();
            if i == j {
                let d = m[i * n + i] - s;
                if d <= 0.0 {
                    return None;
                }
                l[i * n + i] = d.sqrt();
            } else {
                l[i * n + j] = (m[i * n + j] - s) / l[j * n + j];
            }
        }
    }
    let linv = inverse(&l, n)?;
    // A = L⁻¹ K L⁻ᵀ.
    let mut a = vec![0.0; n * n];
    for i in 0..n {
        for j in 0..n {
            let mut s = 0.0;
            for p in 0..n {
                for q in 0..n {
                    s += linv[i * n + p] * k[p * n + q] * linv[j * n + q];
                }
            }
            a[i * n + j] = s;
        }
    }
    let mut v = vec![0.0; n * n];
    for i in 0..n {
        v[i * n + i] = 1.0;
    }
    for _sweep in 0..100 {
        let off: f64 = (0..n)
            .flat_map(|i| (0..n).filter(move |&j| j != i).map(move |j| (i, j)))
            .map(|(i, j)| a[i * n + j] * a[i * n + j])
            .sum();
        let diag: f64 = (0..n).map(|i| a[i * n + i] * a[i * n + i]).sum();
        if off <= 1e-30 * diag {
            break;
        }
        for p in 0..n {
            for q in p + 1..n {
                let apq = a[p * n + q];
                if apq == 0.0 {
                    continue;
                }
                let theta = (a[q * n + q] - a[p * n + p]) / (2.0 * apq);
                let t = theta.signum() / (theta.abs() + (theta * theta + 1.0).sqrt());
                let t = if theta == 0.0 { 1.0 } else { t };
                let c = 1.0 / (t * t + 1.0).sqrt();
                let s = t * c;
                for r in 0..n {
                    let (arp, arq) = (a[r * n + p], a[r * n + q]);
                    a[r * n + p] = c * arp - s * arq;
                    a[r * n + q] = s * arp + c * arq;
                }
                for r in 0..n {
                    let (apr, aqr) = (a[p * n + r], a[q * n + r]);
                    a[p * n + r] = c * apr - s * aqr;
                    a[q * n + r] = s * apr + c * aqr;
                }
                for r in 0..n {
                    let (vrp, vrq) = (v[r * n + p], v[r * n + q]);
                    v[r * n + p] = c * vrp - s * vrq;
                    v[r * n + q] = s * vrp + c * vrq;
                }
            }
        }
    }
    let mut order: Vec<usize> = (0..n).collect();
    order.sort_by(|&i, &j| a[i * n + i].total_cmp(&a[j * n + j]));
    let w2 = order.iter().map(|&i| a[i * n + i]).collect();
    // φ = L⁻ᵀ y.
    let shapes = order
        .iter()
        .map(|&c| {
            (0..n)
                .map(|r| (0..n).map(|p| linv[p * n + r] * v[p * n + c]).sum())
                .collect()
        })
        .collect();
    Some((w2, shapes))
}
