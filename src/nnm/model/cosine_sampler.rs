//! Samples of cosine series (even functions of time) and back, at half the cost of
//! `fourier::Sampler`.
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
//! `fourier::Sampler`): the offset of the grid by half a step changes no alias, since none
//! reaches a retained harmonic.

use crate::nnm::model::fourier::{is_5_smooth, len, real_fft_plans};
use multiversion::multiversion;
use realfft::num_complex::Complex;
use realfft::{ComplexToReal, RealToComplex};
use std::f64::consts::PI;
use std::sync::Arc;

/// Cosine series ↔ their n samples on the midpoints of a half period.
pub struct CosineSampler {
    n: usize,
    fwd: Arc<dyn RealToComplex<f64>>,
    inv: Arc<dyn ComplexToReal<f64>>,
    /// e^{−iπk/(2n)}, k = 0..=n, as real and imaginary parts (loops over them vectorise).
    tw_re: Vec<f64>,
    tw_im: Vec<f64>,
}

/// What one transform needs besides its input and output (`CosineSampler::scratch`).
pub struct CosineScratch {
    spec: Vec<Complex<f64>>,
    work: Vec<Complex<f64>>,
    /// The samples in Makhoul's order.
    reordered: Vec<f64>,
    /// The coefficients G_k (k = 0..=n) of a synthesis, and the n coefficients of an
    /// analysis.
    g: Vec<f64>,
    coefs: Vec<f64>,
}

impl CosineSampler {
    /// A sampler of `n` samples (n ≥ 2); exact products of series of H harmonics need
    /// 2n > 3H (`for_products`).
    pub fn new(n: usize) -> Self {
        let (fwd, inv) = real_fft_plans(n);
        let (tw_re, tw_im) = (0..=n)
            .map(|k| {
                let (s, c) = (PI * k as f64 / (2 * n) as f64).sin_cos();
                (c, -s)
            })
            .unzip();
        CosineSampler {
            n,
            fwd,
            inv,
            tw_re,
            tw_im,
        }
    }

    /// The sampler whose products of series of `h` harmonics are exact: the smallest
    /// 5-smooth n with 2n > 3h.
    pub fn for_products(h: usize) -> Self {
        Self::new(smooth_at_least(3 * h / 2 + 1))
    }

    /// The sampler of the smallest 5-smooth n ≥ `need`.
    pub fn at_least(need: usize) -> Self {
        Self::new(smooth_at_least(need))
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
            g: vec![0.0; self.n + 1],
            coefs: vec![0.0; self.n],
        }
    }

    /// Samples (length n) of the cosine part of `x` (h harmonics, h < n, the layout of
    /// fourier.rs); its sine coefficients are not read.
    pub fn synth_with(&self, x: &[f64], h: usize, out: &mut [f64], ws: &mut CosineScratch) {
        let top = h.min(self.n - 1);
        ws.g.fill(0.0);
        ws.g[0] = x[0];
        for (g, &c) in ws.g[1..=top].iter_mut().zip(&x[1..=top]) {
            *g = 0.5 * c;
        }
        self.synth_g(out, ws);
    }

    /// Cosine coefficients (h harmonics, h < n) of the samples `s` (length n) into `out`,
    /// its sine coefficients set to zero.
    pub fn analyse_with(&self, s: &[f64], h: usize, out: &mut [f64], ws: &mut CosineScratch) {
        out[..len(h)].fill(0.0);
        let top = h.min(self.n - 1);
        if self.analyse_all(s, false, ws) {
            out[..=top].copy_from_slice(&ws.coefs[..=top]);
        } else {
            out.fill(f64::NAN);
        }
    }

    /// Samples of a_0 + Σ_{k=1}^{K} a_k cos kθ, `a` = [a_0..a_K] with K < n (the plain
    /// coefficients of an even function, as `cos_analyse` gives them); `a` not empty.
    pub fn cos_synth(&self, a: &[f64], out: &mut [f64], ws: &mut CosineScratch) {
        let top = a.len().min(self.n).saturating_sub(1);
        ws.g.fill(0.0);
        ws.g[0] = a[0];
        for (g, &c) in ws.g[1..=top].iter_mut().zip(&a[1..=top]) {
            *g = 0.5 * c;
        }
        self.synth_g(out, ws);
    }

    /// All n cosine coefficients [a_0..a_{n−1}] of the samples `s` of an even function
    /// (into `a`, length at most n: the first ones).
    pub fn cos_analyse(&self, s: &[f64], a: &mut [f64], ws: &mut CosineScratch) {
        let k = a.len().min(self.n);
        if self.analyse_all(s, false, ws) {
            a[..k].copy_from_slice(&ws.coefs[..k]);
        } else {
            a.fill(f64::NAN);
        }
    }

    /// Samples of Σ_{k=1}^{K} b_k sin kθ, `b` = [b_1..b_K] with K ≤ n (an odd function).
    /// On these instants sin((n − k)θ_j) = (−1)^j cos kθ_j, so this is the cosine
    /// synthesis of the reversed coefficients, every other sample negated.
    pub fn sin_synth(&self, b: &[f64], out: &mut [f64], ws: &mut CosineScratch) {
        let (n, top) = (self.n, b.len().min(self.n));
        // Cosine coefficient k' is b_{n−k'}, present when 1 ≤ n − k' ≤ K; G_0 = b_n.
        ws.g.fill(0.0);
        if top == n {
            ws.g[0] = b[n - 1];
        }
        for (i, &c) in b[..top.min(n - 1)].iter().enumerate() {
            ws.g[n - 1 - i] = 0.5 * c;
        }
        self.synth_g(out, ws);
        negate_odd_samples(out);
    }

    /// The sine coefficients [b_1..b_K] (K = b.len() ≤ n) of the samples `s` of an odd
    /// function (`sin_synth`'s inverse).
    pub fn sin_analyse(&self, s: &[f64], b: &mut [f64], ws: &mut CosineScratch) {
        let n = self.n;
        if !self.analyse_all(s, true, ws) {
            b.fill(f64::NAN);
            return;
        }
        for (i, v) in b.iter_mut().enumerate().take(n) {
            *v = ws.coefs[n - 1 - i];
        }
    }

    /// The inverse DCT of type III of the coefficients G_k in `ws.g` (k = 0..=n, the
    /// module doc's G_k over n), into `out`.
    fn synth_g(&self, out: &mut [f64], ws: &mut CosineScratch) {
        let n = self.n;
        let g = &ws.g;
        twiddle_synth(&mut ws.spec, g, &self.tw_re, &self.tw_im, n);
        // V_0 and (n even) V_{n/2} are real in exact arithmetic: the inverse FFT needs them
        // exactly so.
        ws.spec[0].im = 0.0;
        if n.is_multiple_of(2) {
            ws.spec[n / 2] = Complex::new(std::f64::consts::SQRT_2 * g[n / 2], 0.0);
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

    /// All n cosine coefficients of `s` (`alternate`: of (−1)^j s_j) into `ws.coefs`:
    /// C_k/n for k = 0, 2C_k/n else, C_k = Re(e^{−iπk/(2n)} V_k), V the DFT of the samples
    /// in Makhoul's order. False if the transform failed.
    fn analyse_all(&self, s: &[f64], alternate: bool, ws: &mut CosineScratch) -> bool {
        let n = self.n;
        reorder(s, alternate, &mut ws.reordered);
        if self
            .fwd
            .process_with_scratch(&mut ws.reordered, &mut ws.spec, &mut ws.work)
            .is_err()
        {
            return false;
        }
        twiddle_analyse(&mut ws.coefs, &ws.spec, &self.tw_re, &self.tw_im, n);
        true
    }
}

/// The spectrum of the inverse DCT from the G_k: conj(tw_k)·(g_k − i g_{n−k}),
/// k = 0..=n/2 (`synth_g`).
#[multiversion(targets("x86_64+avx+avx2+fma"))]
fn twiddle_synth(spec: &mut [Complex<f64>], g: &[f64], tw_re: &[f64], tw_im: &[f64], n: usize) {
    let half = n / 2;
    for ((((v, &a), &b), &tr), &ti) in spec[..=half]
        .iter_mut()
        .zip(&g[..=half])
        .zip(g[n - half..=n].iter().rev())
        .zip(&tw_re[..=half])
        .zip(&tw_im[..=half])
    {
        *v = Complex::new(tr * a - ti * b, -tr * b - ti * a);
    }
}

/// The n cosine coefficients from the DFT V of the reordered samples: C_k/n for k = 0,
/// 2C_k/n else, C_k = Re(e^{−iπk/(2n)} V_k) (`analyse_all`).
#[multiversion(targets("x86_64+avx+avx2+fma"))]
fn twiddle_analyse(c: &mut [f64], spec: &[Complex<f64>], tw_re: &[f64], tw_im: &[f64], n: usize) {
    let two_n = 2.0 / n as f64;
    let half = n / 2;
    c[0] = spec[0].re / n as f64;
    for (((o, z), &tr), &ti) in c[1..=half]
        .iter_mut()
        .zip(&spec[1..=half])
        .zip(&tw_re[1..=half])
        .zip(&tw_im[1..=half])
    {
        *o = two_n * (tr * z.re - ti * z.im);
    }
    // V_k = conj(V_{n−k}) beyond n/2.
    for (((o, z), &tr), &ti) in c[half + 1..n]
        .iter_mut()
        .zip(spec[1..n - half].iter().rev())
        .zip(&tw_re[half + 1..n])
        .zip(&tw_im[half + 1..n])
    {
        *o = two_n * (tr * z.re + ti * z.im);
    }
}

/// s_j ← (−1)^j s_j.
#[multiversion(targets("x86_64+avx+avx2+fma"))]
fn negate_odd_samples(s: &mut [f64]) {
    for pair in s.chunks_exact_mut(2) {
        pair[1] = -pair[1];
    }
}

/// Makhoul's order: v_j = s_{2j}, v_{n−1−j} = s_{2j+1}; with `alternate`, of (−1)^j s_j
/// (every odd sample negated).
#[multiversion(targets("x86_64+avx+avx2+fma"))]
fn reorder(s: &[f64], alternate: bool, v: &mut [f64]) {
    let n = v.len();
    let odd = if alternate { -1.0 } else { 1.0 };
    let (lo, hi) = v.split_at_mut(n.div_ceil(2));
    for ((a, b), pair) in lo
        .iter_mut()
        .zip(hi.iter_mut().rev())
        .zip(s.chunks_exact(2))
    {
        *a = pair[0];
        *b = odd * pair[1];
    }
    if n % 2 == 1 {
        lo[n / 2] = s[n - 1];
    }
}

/// The inverse of `reorder`.
#[multiversion(targets("x86_64+avx+avx2+fma"))]
fn unorder(v: &[f64], s: &mut [f64]) {
    let n = v.len();
    let (lo, hi) = v.split_at(n.div_ceil(2));
    for ((pair, &a), &b) in s.chunks_exact_mut(2).zip(lo).zip(hi.iter().rev()) {
        pair[0] = a;
        pair[1] = b;
    }
    if n % 2 == 1 {
        s[n - 1] = lo[n / 2];
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
    use crate::nnm::model::fourier::{self, ic, is};

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
    /// `fourier::Sampler` on the full grid, to round-off, when 2n > 3H.
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
        let full = fourier::Sampler::new(fourier::fft_size_smooth(3 * h));
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

    /// The plain transforms against direct sums of cosines and sines (every coefficient up
    /// to n − 1, resp. n, for even and odd n), and each analysis inverting its synthesis
    /// (round-off of sums of n terms of size ≤ 1: 1e-12).
    #[test]
    fn plain_cosine_and_sine_transforms_equal_direct_sums() {
        for n in [2usize, 5, 8, 9, 216, 135] {
            let s = CosineSampler::new(n);
            let mut ws = s.scratch();
            let a: Vec<f64> = (0..n)
                .map(|k| ((k * 37 % 11) as f64 - 5.0) / (k + 1) as f64)
                .collect();
            let b: Vec<f64> = (1..=n)
                .map(|k| ((k * 53 % 13) as f64 - 6.0) / k as f64)
                .collect();
            let (mut cs, mut ss) = (vec![0.0; n], vec![0.0; n]);
            s.cos_synth(&a, &mut cs, &mut ws);
            s.sin_synth(&b, &mut ss, &mut ws);
            for j in 0..n {
                let t = midpoint(n, j);
                let c = a[0] + (1..n).map(|k| a[k] * (k as f64 * t).cos()).sum::<f64>();
                let sn = (1..=n)
                    .map(|k| b[k - 1] * (k as f64 * t).sin())
                    .sum::<f64>();
                assert!(
                    (cs[j] - c).abs() < 1e-12,
                    "n {n} cos j {j}: {} vs {c}",
                    cs[j]
                );
                assert!(
                    (ss[j] - sn).abs() < 1e-12,
                    "n {n} sin j {j}: {} vs {sn}",
                    ss[j]
                );
            }
            let (mut a2, mut b2) = (vec![0.0; n], vec![0.0; n]);
            s.cos_analyse(&cs, &mut a2, &mut ws);
            s.sin_analyse(&ss, &mut b2, &mut ws);
            for k in 0..n {
                assert!((a2[k] - a[k]).abs() < 1e-12, "n {n} a_{k}");
                assert!((b2[k] - b[k]).abs() < 1e-12, "n {n} b_{}", k + 1);
            }
            // Fewer coefficients: the first ones, the rest taken as zero.
            let mut part = vec![0.0; n];
            s.sin_synth(&b[..1], &mut part, &mut ws);
            for (j, v) in part.iter().enumerate() {
                assert!((v - b[0] * midpoint(n, j).sin()).abs() < 1e-13);
            }
        }
    }

    #[test]
    fn smooth_sizes() {
        assert_eq!(CosineSampler::for_products(200).n(), 320);
        assert_eq!(smooth_at_least(7), 8);
        assert_eq!(smooth_at_least(301), 320);
    }
}
