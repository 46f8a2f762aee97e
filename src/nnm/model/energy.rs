//! Energies of a periodic solution, in scaled units (multiply by k_ref·g_ref² for joules).
//!
//! - `energy_ca`: Code_Aster's ENERGIE: ½uᵀKu + ½vᵀMv at ωt = π/2 plus the penalty energy
//!   ½α(u − JEU)² of each shock in contact at that instant (PLAN one side, BI_PLAN both
//!   sides; CERCLE ½α(r − JEU)², our extension). With the phase condition (zero velocity of
//!   the reference DOF at t = 0) the instant π/2 is mid-swing, usually out of contact, where
//!   this is the total energy of the nonsmooth system.
//! - `energy_spread`: the total energy of the regularised system sampled over one period,
//!   E(θ) = ½uᵀKu + ½vᵀMv + Σ ∫ f du (the work of the contact forces, integrated exactly in
//!   Fourier space); (max − min)/ENERGIE. Zero for an exact periodic orbit.

use crate::nnm::model::fourier::{self, Sampler};
use crate::nnm::model::system::System;
use std::f64::consts::FRAC_PI_2;

/// Time-averaged ½uᵀKu + ½vᵀMv (Parseval), quadratic in x: the size of the motion that
/// orients a start from linear modes (DIR_EVOLUTION).
pub fn mean_quadratic_energy(sys: &System, x: &[f64]) -> f64 {
    let lay = sys.lay;
    let nl = lay.n_coef_lin;
    let w = |j: usize| if j == 0 { 1.0 } else { 0.5 };
    let mut e = 0.0;
    for &(i, c, a) in &sys.k.entries {
        for j in 0..nl {
            e += 0.5 * a * w(j) * x[lay.u(i) + j] * x[lay.u(c) + j];
        }
    }
    for &(i, c, a) in &sys.m.entries {
        for j in 0..nl {
            e += 0.5 * a * w(j) * x[lay.v(i) + j] * x[lay.v(c) + j];
        }
    }
    e
}

fn quad_form(entries: &[(usize, usize, f64)], y: &[f64]) -> f64 {
    entries.iter().map(|&(i, c, a)| 0.5 * a * y[i] * y[c]).sum()
}

/// Displacements and velocities of every DOF at θ.
fn state_at(sys: &System, x: &[f64], theta: f64) -> (Vec<f64>, Vec<f64>) {
    let lay = sys.lay;
    let u = (0..lay.n)
        .map(|i| fourier::eval(&x[lay.u(i)..lay.u(i) + lay.n_coef_lin], lay.h_lin, theta))
        .collect();
    let v = (0..lay.n)
        .map(|i| fourier::eval(&x[lay.v(i)..lay.v(i) + lay.n_coef_lin], lay.h_lin, theta))
        .collect();
    (u, v)
}

/// Code_Aster's ENERGIE (scaled).
pub fn energy_ca(sys: &System, x: &[f64]) -> f64 {
    let (u, v) = state_at(sys, x, FRAC_PI_2);
    let mut e = quad_form(&sys.k.entries, &u) + quad_form(&sys.m.entries, &v);
    for sh in &sys.shocks {
        let comps = [u[sh.dofs[0]], sh.dofs.get(1).map_or(0.0, |&d| u[d])];
        e += sh.law.with(|l| l.energy(comps, sh.alpha, sh.gap));
    }
    e
}

/// Code_Aster's ENERGIE in joules (the scaled [`energy_ca`] times the scaling's energy unit).
pub fn energy_ca_joules(sys: &System, x: &[f64]) -> f64 {
    let s = sys.scaling;
    energy_ca(sys, x) * s.stiffness * s.length * s.length
}

/// ENERGIE's formula averaged over one period (column ENERGIE_MOYENNE, beyond Code_Aster):
/// the mean of ½uᵀKu + ½vᵀMv (Parseval, exact) plus the mean over the contact sampler's
/// instants of each shock's penalty energy, with the same penalty as [`energy_ca`]. On an
/// exact periodic orbit of the nonsmooth system the total energy is constant and this is
/// ENERGIE; on a truncated harmonic balance the energy at the one instant π/2 carries the
/// truncation's ripple, which the mean averages out (docs/mode_non_line.md, "Outputs").
pub fn energy_mean_ca(sys: &System, x: &[f64]) -> f64 {
    let lay = sys.lay;
    let smp = sys.sampler();
    let ns = smp.n();
    let mut e = mean_quadratic_energy(sys, x);
    let mut u = vec![vec![0.0; ns]; 2];
    let mut ws = smp.scratch();
    for sh in &sys.shocks {
        for (c, &d) in sh.dofs.iter().enumerate().take(2) {
            let coefs = &x[lay.u(d)..lay.u(d) + lay.n_coef_lin];
            smp.synth_with(coefs, lay.h_lin, &mut u[c], &mut ws);
        }
        let total: f64 = sh.law.with(|l| {
            (0..ns)
                .map(|j| l.mean_energy([u[0][j], u[1][j]], sh.alpha, sh.gap))
                .sum()
        });
        e += total / ns as f64;
    }
    e
}

/// Samples over one period (θ_j = 2πj/N) of the total energy of the regularised system.
///
/// ½uᵀKu + ½vᵀMv is a trigonometric polynomial of degree 2H_l: its coefficients are
/// Σ_i ½ u_i·(Ku)_i (products of series, O(n·H_l²) after one product by K and one by M),
/// added to those of the contact work and sampled by one FFT (not n values per sample:
/// O(N·nnz) was 0.7 s per point at 10⁴ DOFs).
pub fn energy_samples(sys: &System, x: &[f64]) -> Vec<f64> {
    let lay = sys.lay;
    let (n, hl, hn, nl, nn) = (
        lay.n,
        lay.h_lin,
        lay.h_nonl,
        lay.n_coef_lin,
        lay.n_coef_nonl,
    );
    let hw = hn + hl;
    let smp = Sampler::new(fourier::fft_size(2 * hw));
    let ns = smp.n();
    let nw = fourier::len(hw);
    // Work of the contact forces: p = Σ f_c u_c', W = ∫ p dθ (exact in Fourier space).
    let mut p = vec![0.0; nw];
    let mut du = vec![0.0; nl];
    for sh in &sys.shocks {
        for &(c, v) in &sh.eqs.forces {
            let d = sh.dofs[c];
            fourier::deriv(&x[lay.u(d)..lay.u(d) + nl], hl, &mut du);
            let f = &x[sh.offset + v * nn..sh.offset + (v + 1) * nn];
            fourier::mul_acc(f, hn, &du, hl, hw, 1.0, &mut p);
        }
    }
    let mut w = vec![0.0; nw];
    for k in 1..=hw {
        let kf = k as f64;
        w[fourier::ic(k)] = -p[fourier::is(hw, k)] / kf;
        w[fourier::is(hw, k)] = p[fourier::ic(k)] / kf;
    }
    // ½uᵀKu + ½vᵀMv as a series of degree 2H_l ≤ H_l + H_nl, added to W.
    let u = &x[lay.u(0)..lay.u(0) + n * nl];
    let v = &x[lay.v(0)..lay.v(0) + n * nl];
    let mut ku = vec![0.0; n * nl];
    let mut mv = vec![0.0; n * nl];
    sys.k.mul_blocks(u, nl, &mut ku);
    sys.m.mul_blocks(v, nl, &mut mv);
    for i in 0..n {
        let r = i * nl..(i + 1) * nl;
        fourier::mul_conv_acc(&u[r.clone()], hl, &ku[r.clone()], hl, hw, 0.5, &mut w);
        fourier::mul_conv_acc(&v[r.clone()], hl, &mv[r], hl, hw, 0.5, &mut w);
    }
    let mut ws = vec![0.0; ns];
    smp.synth(&w, hw, &mut ws);
    ws.iter()
        .enumerate()
        .map(|(j, e)| e + p[0] * 2.0 * std::f64::consts::PI * j as f64 / ns as f64)
        .collect()
}

/// (max − min) of the sampled total energy over one period, relative to `reference`.
pub fn energy_spread(sys: &System, x: &[f64], reference: f64) -> f64 {
    let e = energy_samples(sys, x);
    let (lo, hi) = e
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &v| {
            (a.min(v), b.max(v))
        });
    (hi - lo) / reference.abs().max(f64::MIN_POSITIVE)
}

/// Dominant harmonic (≥ 1) of the DOF with the largest spectrum.
pub fn harm_max(sys: &System, x: &[f64]) -> usize {
    let lay = sys.lay;
    let amp = |i: usize, k: usize| {
        let u = &x[lay.u(i)..lay.u(i) + lay.n_coef_lin];
        u[fourier::ic(k)].hypot(u[fourier::is(lay.h_lin, k)])
    };
    let best_dof = (0..lay.n)
        .max_by(|&a, &b| {
            let sa: f64 = (1..=lay.h_lin).map(|k| amp(a, k).powi(2)).sum();
            let sb: f64 = (1..=lay.h_lin).map(|k| amp(b, k).powi(2)).sum();
            sa.total_cmp(&sb)
        })
        .unwrap_or(0);
    (1..=lay.h_lin)
        .max_by(|&a, &b| amp(best_dof, a).total_cmp(&amp(best_dof, b)))
        .unwrap_or(1)
}
