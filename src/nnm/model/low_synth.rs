//! Samples of a series of few harmonics by direct sums over a table made once:
//! out_j = x_0 + Σ_{k=1..h} (c_k cos kθ_j + s_k sin kθ_j).
//!
//! The displacement of a shock DOF has NB_HARM_LINE harmonics, a handful, while the grids
//! of the sampled products have about 1.5·NB_HARM_NONL instants (hundreds): a transform
//! costs O(N log N) whatever h is, the sums one pass over the grid per table row (h rows
//! for an even series on the half period, 2h with the sines). Measured (release, this
//! machine, realfft 3.5): one pass of n = 320 instants 62 ns, of 640 instants 125 ns; a
//! real inverse FFT of 320 points 0.35 µs, of 640 points 0.75 µs, and the half period's
//! cosine synthesis of 320 instants 0.67 µs (the FFT and its twiddles). The sums are
//! therefore cheaper up to about 10 rows on the half period and 5 on the whole one:
//! [`MAX_ROWS_HALF`] and [`MAX_ROWS_FULL`] stay below. They agree with the transforms to
//! round-off.

use crate::nnm::model::fourier::{ic, is};
use crate::nnm::model::vector::add_scaled;

/// A table of cos kθ_j (and sin kθ_j) for k = 1..=h over n instants, row-major by k.
pub struct LowSynth {
    n: usize,
    h: usize,
    cos: Vec<f64>,
    /// Empty for a table of cosines only (`cosines_only`).
    sin: Vec<f64>,
}

/// The most table rows for which the sums replace a transform, on the half period (the
/// cosine synthesis of a time-symmetric series) and on the whole one (module doc).
pub const MAX_ROWS_HALF: usize = 8;
pub const MAX_ROWS_FULL: usize = 4;

impl LowSynth {
    /// Cosines and sines of `h` harmonics at the instants θ(0..n).
    pub fn new(n: usize, h: usize, theta: impl Fn(usize) -> f64) -> LowSynth {
        let mut cos = Vec::with_capacity(n * h);
        let mut sin = Vec::with_capacity(n * h);
        for k in 1..=h {
            for j in 0..n {
                let (s, c) = (k as f64 * theta(j)).sin_cos();
                cos.push(c);
                sin.push(s);
            }
        }
        LowSynth { n, h, cos, sin }
    }

    /// Cosines only (even series on the midpoints of half a period).
    pub fn cosines_only(n: usize, h: usize, theta: impl Fn(usize) -> f64) -> LowSynth {
        let mut cos = Vec::with_capacity(n * h);
        for k in 1..=h {
            cos.extend((0..n).map(|j| (k as f64 * theta(j)).cos()));
        }
        LowSynth {
            n,
            h,
            cos,
            sin: Vec::new(),
        }
    }

    /// Number of harmonics of the table.
    pub fn h(&self) -> usize {
        self.h
    }

    /// Samples (length n) of `x`, a series of `hx` ≤ h harmonics (layout of fourier.rs);
    /// its sine coefficients are not read by a table of cosines only.
    pub fn synth(&self, x: &[f64], hx: usize, out: &mut [f64]) {
        let n = self.n;
        debug_assert!(hx <= self.h && out.len() == n);
        out.fill(x[0]);
        add_rows(out, &self.cos[..hx * n], &x[ic(1)..=ic(hx)]);
        if !self.sin.is_empty() {
            add_rows(out, &self.sin[..hx * n], &x[is(hx, 1)..=is(hx, hx)]);
        }
    }
}

/// out += Σ_k coefs[k]·rows[k] (rows of out.len(), row-major), zero coefficients skipped.
fn add_rows(out: &mut [f64], rows: &[f64], coefs: &[f64]) {
    for (&c, row) in coefs.iter().zip(rows.chunks_exact(out.len())) {
        if c != 0.0 {
            add_scaled(out, c, row);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::nnm::model::cosine_sampler::CosineSampler;
    use crate::nnm::model::fourier::{self, Sampler};
    use std::f64::consts::PI;

    fn series_of(h: usize) -> Vec<f64> {
        let mut x = vec![0.0; fourier::len(h)];
        x[0] = 0.3;
        for k in 1..=h {
            x[ic(k)] = 1.0 / (k as f64 + 0.5);
            x[is(h, k)] = -0.7 / (k * k) as f64;
        }
        x
    }

    /// Against the transforms the sums replace, on both grids of the products: equal to
    /// round-off (sums of h + 1 terms of size ≤ 2, each a few ulps: 1e-14).
    #[test]
    fn sums_equal_the_transforms() {
        for h in [1, 3, 5, 8] {
            let x = series_of(h);
            let full = Sampler::new(fourier::fft_size_smooth(3 * 200));
            let n = full.n();
            let table = LowSynth::new(n, h, |j| 2.0 * PI * j as f64 / n as f64);
            let (mut a, mut b) = (vec![0.0; n], vec![0.0; n]);
            full.synth(&x, h, &mut a);
            table.synth(&x, h, &mut b);
            for (p, q) in a.iter().zip(&b) {
                assert!((p - q).abs() < 1e-14, "full grid h {h}: {p} vs {q}");
            }
            let half = CosineSampler::for_products(200);
            let m = half.n();
            let table = LowSynth::cosines_only(m, h, |j| PI * (2 * j + 1) as f64 / (2 * m) as f64);
            let (mut a, mut b) = (vec![0.0; m], vec![0.0; m]);
            half.synth_with(&x, h, &mut a, &mut half.scratch());
            table.synth(&x, h, &mut b);
            for (p, q) in a.iter().zip(&b) {
                assert!((p - q).abs() < 1e-14, "half grid h {h}: {p} vs {q}");
            }
        }
    }

    /// A series of fewer harmonics than the table reads only its own coefficients.
    #[test]
    fn fewer_harmonics_than_the_table() {
        let table = LowSynth::new(16, 6, |j| 2.0 * PI * j as f64 / 16.0);
        let x = series_of(2);
        let mut out = vec![0.0; 16];
        table.synth(&x, 2, &mut out);
        for (j, v) in out.iter().enumerate() {
            let t = 2.0 * PI * j as f64 / 16.0;
            let want = x[0]
                + x[ic(1)] * t.cos()
                + x[ic(2)] * (2.0 * t).cos()
                + x[is(2, 1)] * t.sin()
                + x[is(2, 2)] * (2.0 * t).sin();
            assert!((v - want).abs() < 1e-14);
        }
    }
}
