//! Padé approximants of an ANM series with one common denominator (Cochelin, Damil &
//! Potier-Ferry's remedy for short ANM steps; docs/nnm.md, "Padé approximants").
//!
//! The series X(a) − X0 = Σ_{k=1..N} a^k X_k is replaced by P(a)/Q(a), Q(a) = 1 + Σ_{j=1..N−1}
//! d_j a^j a scalar polynomial and P(a) = Σ_{k=1..N−1} a^k P_k, P_k = Σ_{j=0..k−1} d_j X_{k−j}
//! (d_0 = 1). The d_j make the order-N coefficient of Q·(X − X0), X_N + Σ_j d_j X_{N−j}, as
//! small as the lower terms allow: its least-squares projection onto span(X_1..X_{N−1}) is
//! cancelled (what is left, orthogonal to every lower term, is the neglected part). Q·(X − X0)
//! then equals P to order N − 1 exactly, so the approximant agrees with the series where the
//! series converges, and Q's roots stand for the singularity that limits the series (a
//! nearby branch of the regularised law, the kink of contact onset): beyond the series'
//! radius the rational form stays accurate for a while.
//!
//! Everything is computed in the reduced variable ā = a/s, s the series' own step length,
//! so that the terms s^k X_k are of comparable size and the least-squares problem is well
//! scaled. Columns that are linearly dependent on earlier ones (a geometric tail) are
//! dropped from the projection (their coefficients set to zero).

use crate::nnm::continuation::anm::{dot, norm};

/// A rational form P(ā)/Q(ā) of one series, ā = a/scale.
pub struct Pade {
    /// s: the series' step length that a is reduced by.
    scale: f64,
    /// e_j = d_j s^j, j = 1..N−1 (Q(ā) = 1 + Σ e_j ā^j).
    den: Vec<f64>,
    /// P̄_k = s^k P_k, k = 1..N−1.
    num: Vec<Vec<f64>>,
}

/// Relative size below which a Gram–Schmidt column counts as dependent on the earlier ones.
const DEPENDENT: f64 = 1.0e-10;

impl Pade {
    /// The approximant of the series with terms X_1..X_N (`terms[0]` = X_1), reduced by
    /// `scale` (> 0). None with fewer than three terms or a non-finite result.
    pub fn new(terms: &[Vec<f64>], scale: f64) -> Option<Pade> {
        let n_terms = terms.len();
        if n_terms < 3 || !(scale.is_finite() && scale > 0.0) {
            return None;
        }
        // W_k = s^k X_k.
        let mut sk = 1.0;
        let w: Vec<Vec<f64>> = terms
            .iter()
            .map(|t| {
                sk *= scale;
                t.iter().map(|v| v * sk).collect()
            })
            .collect();
        let m = n_terms - 1;
        let c = least_squares(&w[..m], &w[m])?;
        // e_j = c_{N−j}: the coefficient of W_{N−j}, j = 1..N−1 (c[i] belongs to W_{i+1}).
        let den: Vec<f64> = (1..=m).map(|j| c[m - j]).collect();
        let num: Vec<Vec<f64>> = (1..=m)
            .map(|k| {
                let mut p = w[k - 1].clone();
                for j in 1..k {
                    let e = den[j - 1];
                    for (pi, wi) in p.iter_mut().zip(&w[k - j - 1]) {
                        *pi += e * wi;
                    }
                }
                p
            })
            .collect();
        let ok = den.iter().all(|v| v.is_finite()) && num.iter().flatten().all(|v| v.is_finite());
        ok.then_some(Pade { scale, den, num })
    }

    /// Q and dQ/dā at ā.
    fn q(&self, ab: f64) -> (f64, f64) {
        let (mut q, mut dq, mut p) = (1.0, 0.0, 1.0);
        for (j, e) in self.den.iter().enumerate() {
            dq += (j + 1) as f64 * e * p;
            p *= ab;
            q += e * p;
        }
        (q, dq)
    }

    /// The smallest ā in (0, `upto`] at which Q comes within `margin` of zero (the first
    /// pole, approached), scanning `samples` equal steps; None if Q stays above it.
    pub fn first_pole_within(&self, upto: f64, samples: usize, margin: f64) -> Option<f64> {
        (1..=samples)
            .map(|i| upto * i as f64 / samples as f64)
            .find(|&ab| self.q(ab).0 <= margin)
            .map(|ab| ab * self.scale)
    }

    /// X(a) = X0 + P(ā)/Q(ā).
    pub fn eval(&self, x0: &[f64], a: f64) -> Vec<f64> {
        let ab = a / self.scale;
        let (q, _) = self.q(ab);
        let mut x = x0.to_vec();
        let mut p = 1.0;
        for t in &self.num {
            p *= ab;
            let f = p / q;
            for (xi, ti) in x.iter_mut().zip(t) {
                *xi += f * ti;
            }
        }
        x
    }

    /// d/da of P/Q at a, normalised: (P'Q − PQ')/Q², the direction only.
    pub fn unit_tangent(&self, a: f64) -> Vec<f64> {
        let ab = a / self.scale;
        let (q, dq) = self.q(ab);
        let n = self.num.first().map_or(0, |t| t.len());
        let mut d = vec![0.0; n];
        // Σ ā^k P̄_k (Σ k ā^{k−1} P̄_k) Q − (Σ ā^k P̄_k) Q'.
        let mut p = 1.0; // ā^{k−1}
        for (k, t) in self.num.iter().enumerate() {
            let dp = (k + 1) as f64 * p; // d ā^k / dā
            let v = p * ab; // ā^k
            let f = dp * q - v * dq;
            for (di, ti) in d.iter_mut().zip(t) {
                *di += f * ti;
            }
            p *= ab;
        }
        let nd = norm(&d);
        d.iter_mut().for_each(|v| *v /= nd);
        d
    }
}

/// The coefficients c minimising ‖Σ_i c_i cols[i] + rhs‖ (modified Gram–Schmidt with one
/// re-orthogonalisation; dependent columns get coefficient 0). None if not finite.
fn least_squares(cols: &[Vec<f64>], rhs: &[f64]) -> Option<Vec<f64>> {
    let m = cols.len();
    let mut q: Vec<Vec<f64>> = Vec::with_capacity(m);
    // r[i][j], i ≤ j: the upper-triangular factor; kept[i]: column i independent.
    let mut r = vec![vec![0.0; m]; m];
    let mut kept = vec![false; m];
    let scale = cols.iter().map(|c| norm(c)).fold(0.0f64, f64::max);
    if !(scale.is_finite() && scale > 0.0) {
        return None;
    }
    for j in 0..m {
        let mut v = cols[j].clone();
        for _ in 0..2 {
            for (i, qi) in q.iter().enumerate() {
                if !kept[i] {
                    continue;
                }
                let h = dot(qi, &v);
                r[i][j] += h;
                for (vk, qk) in v.iter_mut().zip(qi) {
                    *vk -= h * qk;
                }
            }
        }
        let nv = norm(&v);
        if nv > DEPENDENT * scale {
            r[j][j] = nv;
            v.iter_mut().for_each(|x| *x /= nv);
            kept[j] = true;
        }
        q.push(v);
    }
    // Qᵀ(−rhs), then back substitution on the kept columns.
    let b: Vec<f64> = q
        .iter()
        .zip(&kept)
        .map(|(qi, &k)| if k { -dot(qi, rhs) } else { 0.0 })
        .collect();
    let mut c = vec![0.0; m];
    for i in (0..m).rev() {
        if !kept[i] {
            continue;
        }
        let s: f64 = (i + 1..m)
            .filter(|&j| kept[j])
            .map(|j| r[i][j] * c[j])
            .sum();
        c[i] = (b[i] - s) / r[i][i];
    }
    c.iter().all(|v| v.is_finite()).then_some(c)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A vector series with a simple pole, X(a) − X0 = v·a/(1 − a/ρ) = Σ a^k v/ρ^{k−1}: every
    /// term is parallel to X_1, so only X_1 enters the projection, Q = 1 − (a/ρ)^{N−1}, and
    /// P/Q = v·a/(1 − a/ρ) exactly (the numerator's factor cancels): exact at and past the
    /// series' radius ρ, where the 10-term series is already off by the neglected tail.
    #[test]
    fn a_simple_pole_is_represented_exactly() {
        let v = [0.3, -1.2, 0.5];
        let rho: f64 = 2.0;
        let terms: Vec<Vec<f64>> = (1..=10)
            .map(|k| v.iter().map(|x| x / rho.powi(k - 1)).collect())
            .collect();
        let p = Pade::new(&terms, 0.5).unwrap();
        let x0 = [1.0, 2.0, 3.0];
        for a in [0.1, 1.0, 1.9] {
            let x = p.eval(&x0, a);
            for i in 0..3 {
                let exact = x0[i] + v[i] * a / (1.0 - a / rho);
                assert!(
                    (x[i] - exact).abs() <= 1e-10 * exact.abs().max(1.0),
                    "{a}: {x:?}"
                );
            }
        }
        // Q's first zero is at ρ: Q = 0.05 at ρ·0.95^{1/9}.
        let pole = p.first_pole_within(10.0, 10_000, 0.05).unwrap();
        assert!(
            (pole / (rho * 0.95f64.powf(1.0 / 9.0)) - 1.0).abs() < 1e-3,
            "{pole}"
        );
    }

    /// Two directions with different geometric rates: X_k = u r1^{k−1} + w r2^{k−1}. One
    /// scalar Q of degree N − 1 is not the exact (1 − r1 a)(1 − r2 a), but Q·(X − X0) − P is
    /// O(a^{N+1}): the approximant is at least as close to the sum as the truncated series.
    #[test]
    fn agrees_with_the_series_inside_its_radius() {
        let u = [1.0, 0.0, 0.2];
        let w = [0.0, 1.0, -0.4];
        let (r1, r2): (f64, f64) = (0.8, -0.3);
        let terms: Vec<Vec<f64>> = (1..=12)
            .map(|k| {
                (0..3)
                    .map(|i| u[i] * r1.powi(k - 1) + w[i] * r2.powi(k - 1))
                    .collect()
            })
            .collect();
        let p = Pade::new(&terms, 0.4).unwrap();
        let x0 = [0.0; 3];
        let a: f64 = 0.4;
        let x = p.eval(&x0, a);
        let exact: Vec<f64> = (0..3)
            .map(|i| u[i] * a / (1.0 - r1 * a) + w[i] * a / (1.0 - r2 * a))
            .collect();
        let mut series = vec![0.0; 3];
        for (k, t) in terms.iter().enumerate() {
            for i in 0..3 {
                series[i] += a.powi(k as i32 + 1) * t[i];
            }
        }
        let dist = |y: &[f64]| norm(&y.iter().zip(&exact).map(|(a, b)| a - b).collect::<Vec<_>>());
        assert!(
            dist(&x) <= dist(&series),
            "{} vs {}",
            dist(&x),
            dist(&series)
        );
        // Past the series' radius for r1 (1/0.8 = 1.25) the series diverges; P/Q does not.
        let a_far: f64 = 1.0;
        let far = p.eval(&x0, a_far);
        assert!(far.iter().all(|v| v.is_finite()));
        // The tangent agrees with the derivative of the exact sum.
        let t = p.unit_tangent(a);
        let d: Vec<f64> = (0..3)
            .map(|i| u[i] / (1.0 - r1 * a).powi(2) + w[i] / (1.0 - r2 * a).powi(2))
            .collect();
        let nd = norm(&d);
        for i in 0..3 {
            assert!((t[i] - d[i] / nd).abs() < 1e-6, "{t:?}");
        }
    }
}
