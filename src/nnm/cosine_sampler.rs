//! Samples of cosine series (even functions of time) and back, at half the cost of
//! `series::Sampler`.
//!
//! An even x(θ) = x₀ + Σ c_k cos kθ, sampled on the N = 2n midpoints θ_j = π(2j+1)/(2n),
//! takes the same value at θ_j and 2π − θ_j = θ_{N−1−j}: its n samples in (0, π) hold
//! everything. Between those samples and the coefficients are the discrete cosine
//! transforms of type III (synthesis, s_j = Σ_k a_k cos(πk(2j+1)/(2n))) and II (analysis,
//! C_k = Σ_j s_j cos(πk(2j+1)/(2n))). Each is one real FFT of n points by Makhoul's
//! reordering (IEEE Trans. ASSP 28, 1980): with v_j = s_{2j} and v_{n−1−j} = s_{2j+1},
//! V = DFT(v) gives C_k = Re(e^{−iπk/(2n)} V_k), and e^{−iπk/(2n)} V_k = C_k − i C_{n−k}
//! (C_n = 0) inverts it. A real FFT of n points costs about half one of N = 2n, and the
//! products of sampled series take n multiplications instead of N.
//!
//! Products are exact for the retained harmonics whenever N = 2n > 3H (as for
//! `series::Sampler`): the offset of the grid by half a step changes no alias, since none
//! reaches a retained harmonic.

use super::series::{ic, is_5_smooth, len, real_fft_plans};
use realfft::num_complex::Complex;
use realfft::{ComplexToReal, RealToComplex};
use std::f64::consts::PI;
use std::sync::Arc;

/// Cosine series ↔ their n samples on the midpoints of a half period.
pub struct CosineSampler {
    n: usize,
    fwd: Arc<dyn RealToComplex<f64>>,
    inv: Arc<dyn ComplexToReal<f64>>,
    /// e^{−iπk/(2n)}, k = 0..=n.
    twiddle: Vec<Complex<f64>>,
}

/// What one transform needs besides its input and output (`CosineSampler::scratch`).
pub struct CosineScratch {
    spec: Vec<Complex<f64>>,
    work: Vec<Complex<f64>>,
    /// The samples in Makhoul's order.
    reordered: Vec<f64>,
}

impl CosineSampler {
    /// A sampler of `n` samples (n ≥ 2); exact products of series of H harmonics need
    /// 2n > 3H (`for_products`).
    pub fn new(n: usize) -> Self {
        let (fwd, inv) = real_fft_plans(n);
        let twiddle = (0..=n)
            .map(|k| {
                let (s, c) = (PI * k as f64 / (2 * n) as f64).sin_cos();
                Complex::new(c, -s)
            })
            .collect();
        CosineSampler {
            n,
            fwd,
            inv,
            twiddle,
        }
    }

    /// The sampler whose products of series of `h` harmonics are exact: the smallest
    /// 5-smooth n with 2n > 3h.
    pub fn for_products(h: usize) -> Self {
        Self::new(smooth_at_least(3 * h / 2 + 1))
    }

    pub fn n(&self) -> usize {
        self.n
    }

    pub fn scratch(&self) -> CosineScratch {
        let len = self.fwd.get_scratch_len().max(self.inv.get_scratch_len());
        CosineScratch {
            spec: vec![Complex::new(0.0, 0.0); self.n / 2 + 1],
            work: vec![Complex::new(0.0, 0.0); len],
            reordered: vec![0.0; self.n],
        }
    }

    /// Samples (length n) of the cosine part of `x` (h harmonics, h < n, the layout of
    /// series.rs); its sine coefficients are not read.
    pub fn synth_with(&self, x: &[f64], h: usize, out: &mut [f64], ws: &mut CosineScratch) {
        let n = self.n;
        let top = h.min(n - 1);
        // G_k = n·a_k/2 (G_0 = n·a_0) of the module doc, divided by n for the unnormalised
        // inverse FFT.
        let g = |k: usize| -> f64 {
            if k == 0 {
                x[0]
            } else if k <= top {
                0.5 * x[ic(k)]
            } else {
                0.0
            }
        };
        for (k, v) in ws.spec.iter_mut().enumerate() {
            *v = self.twiddle[k].conj() * Complex::new(g(k), -g(n - k));
        }
        // V_0 and (n even) V_{n/2} are real in exact arithmetic: the inverse FFT needs them
        // exactly so.
        ws.spec[0].im = 0.0;
        if n.is_multiple_of(2) {
            ws.spec[n / 2] = Complex::new(std::f64::consts::SQRT_2 * g(n / 2), 0.0);
        }
        if self
            .inv
            .process_with_scratch(&mut ws.spec, &mut ws.reordered, &mut ws.work)
            .is_err()
        {
            // Lengths are consistent by construction; leave NaN for the finiteness checks.
            out.iter_mut().for_each(|v| *v = f64::NAN);
            return;
        }
        unorder(&ws.reordered, out);
    }

    /// Cosine coefficients (h harmonics, h < n) of the samples `s` (length n) into `out`,
    /// its sine coefficients set to zero.
    pub fn analyse_with(&self, s: &[f64], h: usize, out: &mut [f64], ws: &mut CosineScratch) {
        let n = self.n;
        reorder(s, &mut ws.reordered);
        if self
            .fwd
            .process_with_scratch(&mut ws.reordered, &mut ws.spec, &mut ws.work)
            .is_err()
        {
            out.iter_mut().for_each(|v| *v = f64::NAN);
            return;
        }
        let nf = n as f64;
        out[..len(h)].fill(0.0);
        out[0] = ws.spec[0].re / nf;
        for k in 1..=h.min(n - 1) {
            let vk = if k <= n / 2 {
                ws.spec[k]
            } else {
                ws.spec[n - k].conj()
            };
            out[ic(k)] = 2.0 * (self.twiddle[k] * vk).re / nf;
        }
    }
}

/// Makhoul's order: v_j = s_{2j}, v_{n−1−j} = s_{2j+1}.
fn reorder(s: &[f64], v: &mut [f64]) {
    let n = v.len();
    for (j, &x) in s.iter().enumerate().take(n) {
        if j % 2 == 0 {
            v[j / 2] = x;
        } else {
            v[n - 1 - j / 2] = x;
        }
    }
}

/// The inverse of `reorder`.
fn unorder(v: &[f64], s: &mut [f64]) {
    let n = v.len();
    for (j, x) in s.iter_mut().enumerate().take(n) {
        *x = if j % 2 == 0 {
            v[j / 2]
        } else {
            v[n - 1 - j / 2]
        };
    }
}

/// Smallest 2^a·3^b·5^c ≥ `need` (and at least 2).
fn smooth_at_least(need: usize) -> usize {
    let mut n = need.max(2);
    while !is_5_smooth(n) {
        n += 1;
    }
    n
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::nnm::series::{self, is};

    fn midpoint(n: usize, j: usize) -> f64 {
        PI * (2 * j + 1) as f64 / (2 * n) as f64
    }

    /// A series with cosine coefficients 1/(k+1)·(−1)^k and sine coefficients that the
    /// even transforms must ignore.
    fn even_series(h: usize) -> Vec<f64> {
        let mut x = vec![0.0; len(h)];
        x[0] = 0.7;
        for k in 1..=h {
            x[ic(k)] = (if k % 2 == 0 { 1.0 } else { -1.0 }) / (k + 1) as f64;
            x[is(h, k)] = 3.0 + k as f64;
        }
        x
    }

    /// Synthesis against the direct sum of cosines, for even and odd n and h up to n − 1
    /// (round-off of a sum of h terms of size ≤ 1: 1e-13).
    #[test]
    fn synthesis_equals_the_direct_cosine_sum() {
        for (n, h) in [(8, 3), (9, 8), (10, 9), (320, 200), (135, 90), (16, 1)] {
            let s = CosineSampler::new(n);
            let x = even_series(h);
            let mut out = vec![0.0; n];
            s.synth_with(&x, h, &mut out, &mut s.scratch());
            for (j, v) in out.iter().enumerate() {
                let t = midpoint(n, j);
                let direct = x[0]
                    + (1..=h)
                        .map(|k| x[ic(k)] * (k as f64 * t).cos())
                        .sum::<f64>();
                assert!(
                    (v - direct).abs() < 1e-13,
                    "n {n} h {h} j {j}: {v} vs {direct}"
                );
            }
        }
    }

    /// Analysis recovers the cosine coefficients of an even series (h < n) and leaves its
    /// sines zero.
    #[test]
    fn analysis_inverts_synthesis() {
        for (n, h) in [(8, 7), (9, 8), (320, 200), (135, 134)] {
            let s = CosineSampler::new(n);
            let x = even_series(h);
            let mut ws = s.scratch();
            let mut samples = vec![0.0; n];
            s.synth_with(&x, h, &mut samples, &mut ws);
            let mut back = vec![1.0; len(h)];
            s.analyse_with(&samples, h, &mut back, &mut ws);
            for k in 0..=h {
                assert!(
                    (back[ic(k)] - x[ic(k)]).abs() < 1e-14,
                    "n {n} h {h} cos {k}"
                );
            }
            assert!(back[h + 1..].iter().all(|v| *v == 0.0));
        }
    }

    /// A product of two even series sampled on the cosine grid equals the one of
    /// `series::Sampler` on the full grid, to round-off, when 2n > 3H.
    #[test]
    fn products_equal_the_full_grid_ones() {
        let h = 200;
        let cs = CosineSampler::for_products(h);
        assert!(2 * cs.n() > 3 * h);
        let mut a = even_series(h);
        let mut b = even_series(h);
        for k in 1..=h {
            a[is(h, k)] = 0.0;
            b[is(h, k)] = 0.0;
            b[ic(k)] *= (0.3 * k as f64).cos();
        }
        let full = series::Sampler::new(series::fft_size_smooth(3 * h));
        let (mut fa, mut fb) = (vec![0.0; full.n()], vec![0.0; full.n()]);
        full.synth(&a, h, &mut fa);
        full.synth(&b, h, &mut fb);
        fa.iter_mut().zip(&fb).for_each(|(p, q)| *p *= q);
        let mut want = vec![0.0; len(h)];
        full.analyse(&mut fa, h, &mut want);
        let mut ws = cs.scratch();
        let (mut ca, mut cb) = (vec![0.0; cs.n()], vec![0.0; cs.n()]);
        cs.synth_with(&a, h, &mut ca, &mut ws);
        cs.synth_with(&b, h, &mut cb, &mut ws);
        ca.iter_mut().zip(&cb).for_each(|(p, q)| *p *= q);
        let mut got = vec![0.0; len(h)];
        cs.analyse_with(&ca, h, &mut got, &mut ws);
        let scale = want.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        for (k, (g, w)) in got.iter().zip(&want).enumerate() {
            assert!((g - w).abs() < 1e-14 * scale, "coefficient {k}: {g} vs {w}");
        }
    }

    #[test]
    fn smooth_sizes() {
        assert_eq!(CosineSampler::for_products(200).n(), 320);
        assert_eq!(smooth_at_least(7), 8);
        assert_eq!(smooth_at_least(301), 320);
    }
}
