//! Integration of the variational equation M δÜ + C δU̇ + K_t(t) δU = 0 over one period
//! (C = 0 on a conservative system), all 2n columns of the fundamental matrix at once, from
//! δU(0) = [I 0], δV(0) = [0 I]. The result is the monodromy matrix
//! Φ(T) = [[δU(T)], [δV(T)]] (2n × 2n). A forced system carries one more column: the
//! orbit's own tangent ẏ(0), under the source −ω f sin ωt its time derivative adds to the
//! equation (`forced.rs`: the orbit defect of a forced point).

use super::Linearised;
use crate::nnm::error::{Error, Result};
use crate::nnm::solve::dense_lu::DenseLu;
use faer::linalg::matmul::matmul;
use faer::linalg::solvers::Llt;
use faer::prelude::Solve;
use faer::{Accum, Mat, Par};

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

/// [I 0] and [0 I], and for a forced system the orbit's tangent as a last column.
fn start(lin: &Linearised) -> (Mat<f64>, Mat<f64>) {
    let n = lin.n;
    let tangent = lin.forced.as_ref().map(|_| lin.orbit_tangent());
    let cols = 2 * n + usize::from(tangent.is_some());
    let pick = |i: usize, j: usize, off: usize| match &tangent {
        Some(y) if j == 2 * n => y[i + off],
        _ => f64::from(u8::from(i + off == j)),
    };
    let u = Mat::from_fn(n, cols, |i, j| pick(i, j, 0));
    let v = Mat::from_fn(n, cols, |i, j| pick(i, j, n));
    (u, v)
}

/// K_t U (+ C V) (− s(t) on the tangent column of a forced system): the force that M
/// times the acceleration balances. One thread (`solve_seq`: rayon's hand-offs cost more
/// than these products; measured, they were 40 % of forced_plan's run in wake-ups).
fn restoring(lin: &Linearised, kt: &Mat<f64>, t: f64, u: &Mat<f64>, v: &Mat<f64>) -> Mat<f64> {
    let mut r = Mat::zeros(kt.nrows(), u.ncols());
    matmul(r.as_mut(), Accum::Replace, kt, u, 1.0, Par::Seq);
    if let Some(forced) = &lin.forced {
        matmul(r.as_mut(), Accum::Add, &forced.c, v, 1.0, Par::Seq);
        let last = 2 * lin.n;
        let s = forced.source(lin.orbit.omega, t);
        for (x, si) in r.col_as_slice_mut(last).iter_mut().zip(&s) {
            *x -= si;
        }
    }
    r
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

/// −M⁻¹ (K_t(t) U + C V − s(t)).
fn acceleration(
    lin: &Linearised,
    mass: &Llt<f64>,
    t: f64,
    u: &Mat<f64>,
    v: &Mat<f64>,
) -> Result<Mat<f64>> {
    let mut a = restoring(lin, &lin.stiffness(t)?, t, u, v);
    mass.solve_in_place(a.as_mut());
    Ok(comb(&[(-1.0, &a)]))
}

/// Newmark average acceleration (β = 1/4, γ = 1/2), `n_steps` equal steps over T. Each
/// step solves (M + γh C + βh² K_t(t+h)) A⁺ = −K_t(t+h) Û − C V̂ (+ s(t+h)), with the
/// predictors Û = U + hV + (½ − β)h² A and V̂ = V + (1 − γ)h A.
pub fn newmark(lin: &Linearised, mass: &Llt<f64>, n_steps: usize) -> Result<Mat<f64>> {
    let (beta, gamma) = (0.25, 0.5);
    let h = lin.orbit.period() / n_steps as f64;
    let (mut u, mut v) = start(lin);
    let mut a = acceleration(lin, mass, 0.0, &u, &v)?;
    let mut lu = DenseLu::default();
    for s in 1..=n_steps {
        let t = h * s as f64;
        let kt = lin.stiffness(t)?;
        let pred = comb(&[(1.0, &u), (h, &v), ((0.5 - beta) * h * h, &a)]);
        let pred_v;
        let (lhs, v_hat) = match &lin.forced {
            Some(forced) => {
                pred_v = comb(&[(1.0, &v), ((1.0 - gamma) * h, &a)]);
                let terms = [(1.0, &lin.m), (gamma * h, &forced.c), (beta * h * h, &kt)];
                (comb(&terms), &pred_v)
            }
            // Conservative: V̂ is not used (no C).
            None => (comb(&[(1.0, &lin.m), (beta * h * h, &kt)]), &v),
        };
        let mut a_new = comb(&[(-1.0, &restoring(lin, &kt, t, &pred, v_hat))]);
        let singular = || {
            Error::numerical(format!(
                "Newmark: singular iteration matrix M + βh²K_t at step {s}"
            ))
        };
        solve_seq(&mut lu, &lhs, &mut a_new).map_err(|_| singular())?;
        if a_new.col_iter().any(|c| c.iter().any(|x| !x.is_finite())) {
            return Err(singular());
        }
        u = comb(&[(1.0, &pred), (beta * h * h, &a_new)]);
        v = comb(&[(1.0, &v), (h * (1.0 - gamma), &a), (h * gamma, &a_new)]);
        a = a_new;
    }
    Ok(stack(&u, &v))
}

/// Solves `lhs` X = `rhs` in place on one thread: faer's default LU hands the recursion
/// to rayon, whose wake-ups cost far more than a step of a few DOFs (measured: the
/// stability of forced_plan's 443 one-DOF rows took 16 s of mostly system time, 2 s on
/// one thread).
fn solve_seq(lu: &mut DenseLu, lhs: &Mat<f64>, rhs: &mut Mat<f64>) -> Result<()> {
    let n = lhs.nrows();
    let store = lu.storage(n)?;
    for j in 0..n {
        store[j * n..(j + 1) * n].copy_from_slice(lhs.col_as_slice(j));
    }
    lu.factor()?;
    let ncols = rhs.ncols();
    let mut flat: Vec<f64> = (0..ncols)
        .flat_map(|j| rhs.col_as_slice(j).to_vec())
        .collect();
    lu.solve(&mut flat, ncols)?;
    for j in 0..ncols {
        rhs.col_as_slice_mut(j)
            .copy_from_slice(&flat[j * n..(j + 1) * n]);
    }
    Ok(())
}

/// Classical RK4 on (δU, δV)' = (δV, −M⁻¹ (K_t δU + C δV)), `n_steps` equal steps over T.
pub fn rk4(lin: &Linearised, mass: &Llt<f64>, n_steps: usize) -> Result<Mat<f64>> {
    let h = lin.orbit.period() / n_steps as f64;
    let (mut u, mut v) = start(lin);
    for s in 0..n_steps {
        let t = h * s as f64;
        let (k1u, k1v) = (v.clone(), acceleration(lin, mass, t, &u, &v)?);
        let k2u = comb(&[(1.0, &v), (0.5 * h, &k1v)]);
        let k2v = acceleration(
            lin,
            mass,
            t + 0.5 * h,
            &comb(&[(1.0, &u), (0.5 * h, &k1u)]),
            &k2u,
        )?;
        let k3u = comb(&[(1.0, &v), (0.5 * h, &k2v)]);
        let k3v = acceleration(
            lin,
            mass,
            t + 0.5 * h,
            &comb(&[(1.0, &u), (0.5 * h, &k2u)]),
            &k3u,
        )?;
        let k4u = comb(&[(1.0, &v), (h, &k3v)]);
        let k4v = acceleration(lin, mass, t + h, &comb(&[(1.0, &u), (h, &k3u)]), &k4u)?;
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
