//! The nontrivial Floquet multipliers without guessing which two are the trivial pair:
//! the monodromy matrix restricted to the directions the trivial pair does not live in.
//!
//! Why: the trivial pair of a conservative family is a Jordan block at +1, which an error ε
//! in Φ splits into 1 ± O(√ε). Taking "the two multipliers closest to +1" as that pair then
//! fails wherever a nontrivial real multiplier sits closer to +1 than √ε: it is dropped as
//! trivial and a split trivial one is kept, and the verdict flips from row to row.
//!
//! How: the variational equation M δÜ + K_t(t) δU = 0 (K_t symmetric) is a linear
//! Hamiltonian system, so Φ preserves ω(y₁, y₂) = u₁ᵀM v₂ − v₁ᵀM u₂ (y = (u, v)) whatever
//! the orbit K_t is taken along. With a = ẏ(0) (the orbit's own tangent, Φa = a on an exact
//! orbit) and the covector l = ω(a, ·): l(Φy) = ω(Φa, Φy) = l(y), so ker l is invariant and
//! contains a. In a basis [a, b, W] with l(b) = 1 and W ⊂ ker l a complement of a, Φ is block
//! triangular with the two trivial +1 on the diagonal and R (the map induced on
//! ker l / span a) in the W block: eig(R) are exactly the 2n − 2 nontrivial multipliers.
//! Taking b along lᵀ and W the Euclidean complement of {a, lᵀ} (which are orthogonal,
//! l(a) = ω(a, a) = 0) makes the basis orthonormal: R = Wᵀ Φ W. An error ε in Φ or in a then
//! moves eig(R) by O(ε) instead of O(√ε) (except for a nontrivial multiplier itself at +1).
//! Coordinates are (u, v/ω) so that both halves share units.

use crate::nnm::error::{Error, Result};
use faer::Mat;

/// eig(Wᵀ Φ W) for the monodromy `phi` (2n × 2n, state (u, v)), the mass `m` (n × n), the
/// orbit's tangent `a` = (U̇(0), Ü(0)) and its pulsation `omega`. Empty for one DOF (only the
/// trivial pair exists).
pub(super) fn nontrivial_multipliers(
    phi: &Mat<f64>,
    m: &Mat<f64>,
    a: &[f64],
    omega: f64,
) -> Result<Vec<(f64, f64)>> {
    let n = m.nrows();
    if n < 2 {
        return Ok(Vec::new());
    }
    let n2 = 2 * n;
    // Scaled coordinates z = D y, D = diag(1, 1/ω); Φ_s = D Φ D⁻¹.
    let d = |i: usize| if i < n { 1.0 } else { 1.0 / omega };
    let az: Vec<f64> = (0..n2).map(|i| a[i] * d(i)).collect();
    // l(z) ∝ a_uᵀ M z_v − a_vᵀ M z_u: coefficients (−M a_v, M a_u) (M symmetric).
    let mut l = vec![0.0; n2];
    for i in 0..n {
        let (mut mv, mut mu) = (0.0, 0.0);
        for j in 0..n {
            mv += m[(i, j)] * az[n + j];
            mu += m[(i, j)] * az[j];
        }
        l[i] = -mv;
        l[n + i] = mu;
    }
    let q1 = unit(&az).ok_or_else(|| {
        Error::numerical("the orbit does not move at t = 0: no trivial pair to take out")
    })?;
    // l ⊥ a exactly in exact arithmetic; remove the round-off before normalising.
    let dot = |x: &[f64], y: &[f64]| x.iter().zip(y).map(|(p, q)| p * q).sum::<f64>();
    let c = dot(&l, &q1);
    let l_perp: Vec<f64> = l.iter().zip(&q1).map(|(x, q)| x - c * q).collect();
    let q2 = unit(&l_perp)
        .ok_or_else(|| Error::numerical("the symplectic form vanishes on the orbit tangent"))?;
    let w = complement(&[q1, q2], n2);
    // R = Wᵀ Φ_s W with Φ_s[i][j] = d(i) Φ[i][j] / d(j).
    let phi_w = Mat::from_fn(n2, n2 - 2, |i, k| {
        (0..n2)
            .map(|j| d(i) * phi[(i, j)] / d(j) * w[k][j])
            .sum::<f64>()
    });
    let r = Mat::from_fn(n2 - 2, n2 - 2, |p, k| {
        (0..n2).map(|i| w[p][i] * phi_w[(i, k)]).sum::<f64>()
    });
    let eig = r
        .eigenvalues()
        .map_err(|e| Error::numerical(format!("eigenvalues of the reduced monodromy: {e:?}")))?;
    let mut out: Vec<(f64, f64)> = eig.iter().map(|z| (z.re, z.im)).collect();
    out.sort_by(|x, y| y.0.hypot(y.1).total_cmp(&x.0.hypot(x.1)));
    Ok(out)
}

fn unit(v: &[f64]) -> Option<Vec<f64>> {
    let norm = v.iter().map(|x| x * x).sum::<f64>().sqrt();
    (norm > 0.0 && norm.is_finite()).then(|| v.iter().map(|x| x / norm).collect())
}

/// An orthonormal basis of the Euclidean complement of the orthonormal `taken` in ℝⁿ²:
/// Gram–Schmidt (twice, for orthogonality to round-off) of the unit vectors, those least
/// covered by `taken` first, each kept when enough of it is left: first half of it, then
/// 0.9/√n₂ (while k directions are missing, Σᵢ |P eᵢ|² = k over the projections P on them,
/// so some eᵢ keeps at least 1/√n₂: the sweeps always complete the basis).
fn complement(taken: &[Vec<f64>; 2], n2: usize) -> Vec<Vec<f64>> {
    let mut order: Vec<usize> = (0..n2).collect();
    let cover = |i: usize| taken.iter().map(|q| q[i] * q[i]).sum::<f64>();
    order.sort_by(|&i, &j| cover(i).total_cmp(&cover(j)));
    let mut basis: Vec<Vec<f64>> = taken.to_vec();
    let mut used = vec![false; n2];
    for keep in [0.5, 0.9 / (n2 as f64).sqrt()] {
        for &i in &order {
            if basis.len() == n2 {
                break;
            }
            if used[i] {
                continue;
            }
            let mut v = vec![0.0; n2];
            v[i] = 1.0;
            for _ in 0..2 {
                for q in &basis {
                    let c: f64 = q.iter().zip(&v).map(|(a, b)| a * b).sum();
                    for (x, y) in v.iter_mut().zip(q) {
                        *x -= c * y;
                    }
                }
            }
            let norm = v.iter().map(|x| x * x).sum::<f64>().sqrt();
            if norm > keep {
                used[i] = true;
                basis.push(v.iter().map(|x| x / norm).collect());
            }
        }
    }
    basis.split_off(2)
}
