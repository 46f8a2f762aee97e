//! Integration of the variational equation M δÜ + K_t(t) δU = 0 over one period, all 2n
//! columns of the fundamental matrix at once, from δU(0) = [I 0], δV(0) = [0 I].
//! The result is the monodromy matrix Φ(T) = [[δU(T)], [δV(T)]] (2n × 2n).

use super::Linearised;
use crate::nnm::error::{Error, Result};
use faer::linalg::solvers::Llt;
use faer::prelude::Solve;
use faer::Mat;

/// Σ cᵢ Aᵢ (all the same shape), column by column on contiguous storage.
fn comb(terms: &[(f64, &Mat<f64>)]) -> Mat<f64> {
    let (r, c) = terms
        .first()
        .map(|t| (t.1.nrows(), t.1.ncols()))
        .unwrap_or((0, 0));
    let mut out = Mat::zeros(r, c);
    for j in 0..c {
        let o = out.col_as_slice_mut(j);
        for (s, a) in terms {
            for (y, x) in o.iter_mut().zip(a.col_as_slice(j)) {
                *y += s * x;
            }
        }
    }
    out
}

fn start(n: usize) -> (Mat<f64>, Mat<f64>) {
    let u = Mat::from_fn(n, 2 * n, |i, j| if i == j { 1.0 } else { 0.0 });
    let v = Mat::from_fn(n, 2 * n, |i, j| if i + n == j { 1.0 } else { 0.0 });
    (u, v)
}

fn stack(u: &Mat<f64>, v: &Mat<f64>) -> Mat<f64> {
    let n = u.nrows();
    Mat::from_fn(2 * n, u.ncols(), |i, j| {
        if i < n {
            u[(i, j)]
        } else {
            v[(i - n, j)]
        }
    })
}

/// −M⁻¹ K_t(t) U.
fn acceleration(lin: &Linearised, mass: &Llt<f64>, t: f64, u: &Mat<f64>) -> Result<Mat<f64>> {
    let mut a = lin.stiffness(t)? * u;
    mass.solve_in_place(a.as_mut());
    Ok(comb(&[(-1.0, &a)]))
}

/// Newmark average acceleration (β = 1/4, γ = 1/2), `n_steps` equal steps over T. Each
/// step solves (M + βh² K_t(t+h)) A⁺ = −K_t(t+h)(U + hV + (½ − β)h² A).
pub fn newmark(lin: &Linearised, mass: &Llt<f64>, n_steps: usize) -> Result<Mat<f64>> {
    let (beta, gamma) = (0.25, 0.5);
    let h = lin.orbit.period() / n_steps as f64;
    let (mut u, mut v) = start(lin.n);
    let mut a = acceleration(lin, mass, 0.0, &u)?;
    for s in 1..=n_steps {
        let kt = lin.stiffness(h * s as f64)?;
        let pred = comb(&[(1.0, &u), (h, &v), ((0.5 - beta) * h * h, &a)]);
        let lhs = comb(&[(1.0, &lin.m), (beta * h * h, &kt)]);
        let mut a_new = comb(&[(-1.0, &(&kt * &pred))]);
        lhs.partial_piv_lu().solve_in_place(a_new.as_mut());
        if a_new.col_iter().any(|c| c.iter().any(|x| !x.is_finite())) {
            return Err(Error::numerical(format!(
                "Newmark: singular iteration matrix M + βh²K_t at step {s}"
            )));
        }
        u = comb(&[(1.0, &pred), (beta * h * h, &a_new)]);
        v = comb(&[(1.0, &v), (h * (1.0 - gamma), &a), (h * gamma, &a_new)]);
        a = a_new;
    }
    Ok(stack(&u, &v))
}

/// Classical RK4 on (δU, δV)' = (δV, −M⁻¹ K_t δU), `n_steps` equal steps over T.
pub fn rk4(lin: &Linearised, mass: &Llt<f64>, n_steps: usize) -> Result<Mat<f64>> {
    let h = lin.orbit.period() / n_steps as f64;
    let (mut u, mut v) = start(lin.n);
    for s in 0..n_steps {
        let t = h * s as f64;
        let (k1u, k1v) = (v.clone(), acceleration(lin, mass, t, &u)?);
        let k2u = comb(&[(1.0, &v), (0.5 * h, &k1v)]);
        let k2v = acceleration(lin, mass, t + 0.5 * h, &comb(&[(1.0, &u), (0.5 * h, &k1u)]))?;
        let k3u = comb(&[(1.0, &v), (0.5 * h, &k2v)]);
        let k3v = acceleration(lin, mass, t + 0.5 * h, &comb(&[(1.0, &u), (0.5 * h, &k2u)]))?;
        let k4u = comb(&[(1.0, &v), (h, &k3v)]);
        let k4v = acceleration(lin, mass, t + h, &comb(&[(1.0, &u), (h, &k3u)]))?;
        let w = h / 6.0;
        u = comb(&[
            (1.0, &u),
            (w, &k1u),
            (2.0 * w, &k2u),
            (2.0 * w, &k3u),
            (w, &k4u),
        ]);
        v = comb(&[
            (1.0, &v),
            (w, &k1v),
            (2.0 * w, &k2v),
            (2.0 * w, &k3v),
            (w, &k4v),
        ]);
    }
    Ok(stack(&u, &v))
}
