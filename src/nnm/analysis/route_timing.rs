//! Measured cost of the routes of a contact block (contact.rs) against NB_HARM_NONL,
//! for `aster-nl bench`: where the cost model's choice lands against the measured
//! crossover.

use crate::nnm::error::{Error, Result};
use crate::nnm::model::contact_samples::init_contact;
use crate::nnm::model::system::{Scaling, System};
use crate::nnm::solve::contact::{self, ContactBlock, Method};
use crate::nnm::solve::linear_solver::solves_per_factorisation;
use crate::nnm::{model::fourier, CercleForm, Harmonics, Problem, Shock, ShockLaw};
use faer::sparse::{SparseColMat, Triplet};
use std::time::Instant;

/// One row: a law at one H_nl, wall seconds of one factorisation + `solves` solves (best
/// of a few repeats), Krylov iterations per solve, the cost model's choice.
#[derive(Clone, Debug)]
pub struct RouteRow {
    pub law: &'static str,
    pub h_nonl: usize,
    pub dense_s: f64,
    pub krylov_s: f64,
    pub krylov_iterations: f64,
    /// The Toeplitz route (laws with one own unknown): at the point as made (a sine part
    /// in U: the whole period), and at the same point made time-symmetric (the half
    /// period).
    pub toeplitz_s: Option<f64>,
    pub toeplitz_symmetric_s: Option<f64>,
    pub model_choice: Method,
}

fn diag(n: usize, v: f64) -> Result<SparseColMat<usize, f64>> {
    let t: Vec<Triplet<usize, usize, f64>> = (0..n).map(|i| Triplet::new(i, i, v)).collect();
    SparseColMat::try_new_from_triplets(n, n, &t)
        .map_err(|e| Error::internal(format!("diagonal matrix: {e:?}")))
}

/// A point in contact: the first DOF at 1.3 JEU in its first harmonic, the second (CERCLE)
/// at 0.4 JEU in quadrature, contact unknowns from their laws.
pub(in crate::nnm) fn system_and_point(law: ShockLaw, h_nonl: usize) -> Result<(System, Vec<f64>)> {
    let dofs: Vec<usize> = (0..law.n_comp()).collect();
    let p = Problem {
        forcing: None,
        k: diag(2, 10.0)?,
        m: diag(2, 1.0)?,
        shocks: vec![Shock {
            law,
            dofs,
            gap: 0.01,
            stiffness: 50.0,
            regul: 5e-5,
        }],
    };
    let h = Harmonics { h_lin: 5, h_nonl };
    let sys = System::of_harmonics(&p, h, Scaling::new(&p, 1.0, 0)?, 0)?;
    let lay = sys.lay;
    let mut x = vec![0.0; lay.n_unk];
    x[lay.u(0) + fourier::ic(1)] = 1.3;
    x[lay.u(1) + fourier::is(lay.h_lin, 1)] = 0.4;
    x[lay.omega()] = 1.0;
    init_contact(&sys, &mut x)?;
    Ok((sys, x))
}

pub fn contact_route_timings(h_values: &[usize], solves: usize) -> Result<Vec<RouteRow>> {
    let mut rows = Vec::new();
    let laws = [
        ("PLAN", ShockLaw::Plan),
        (
            "CERCLE",
            ShockLaw::Cercle {
                origin: [0.0, 0.003],
                form: CercleForm::Secant,
            },
        ),
    ];
    for (name, law) in laws {
        for &h in h_values {
            let (sys, x) = system_and_point(law, h)?;
            let lay = sys.lay;
            let sh = &sys.shocks[0];
            let rhs: Vec<f64> = (0..sh.eqs.n_own * lay.n_coef_nonl)
                .map(|i| ((i * 7919) % 101) as f64 / 101.0 - 0.5)
                .collect();
            let time = |m: Method, x: &[f64]| -> Result<(f64, f64)> {
                let mut block = ContactBlock::new(sh, 0, &lay, solves, Some(m))?;
                let mut best = f64::INFINITY;
                let repeats = if h >= 320 { 2 } else { 5 };
                for _ in 0..repeats {
                    let t = Instant::now();
                    block.factor(sh, &lay, x)?;
                    let mut r = rhs.clone();
                    for _ in 0..solves {
                        r.copy_from_slice(&rhs);
                        block.solve(&mut r)?;
                    }
                    best = best.min(t.elapsed().as_secs_f64());
                }
                let c = block.counters;
                let per_solve = c.krylov_iterations as f64
                    / (c.solves + c.factorisations * block.dims().1).max(1) as f64;
                Ok((best, per_solve))
            };
            let (dense_s, _) = time(Method::Dense, &x)?;
            let (krylov_s, krylov_iterations) = time(Method::Krylov, &x)?;
            let (toeplitz_s, toeplitz_symmetric_s) = if sh.eqs.n_own == 1 {
                // Without the other DOF's sine part, U and the contact unknowns are even.
                let mut even = x.clone();
                even[lay.u(1)..lay.u(1) + lay.n_coef_lin].fill(0.0);
                debug_assert!(lay.is_time_symmetric(&even) && !lay.is_time_symmetric(&x));
                (
                    Some(time(Method::Toeplitz, &x)?.0),
                    Some(time(Method::Toeplitz, &even)?.0),
                )
            } else {
                (None, None)
            };
            let ns = fourier::fft_size_smooth(3 * h);
            rows.push(RouteRow {
                law: name,
                h_nonl: h,
                dense_s,
                krylov_s,
                krylov_iterations,
                toeplitz_s,
                toeplitz_symmetric_s,
                model_choice: contact::choose(
                    sh.eqs.n_own,
                    lay.n_coef_nonl,
                    ns,
                    solves + sh.dofs.len() * lay.n_coef_lin,
                ),
            });
        }
    }
    let _ = solves_per_factorisation;
    Ok(rows)
}
