//! Exact solves with a truncated multiplication operator of one scalar series, in
//! O(H log H) each, from the Gohberg–Semencul formula.
//!
//! In complex coefficients (x̂_k, k = −H..H; x = Σ x̂_k e^{ikθ}), x ↦ Trunc_H(a·x) is the
//! (2H+1)² Toeplitz matrix T_{kl} = â_{k−l}. With ξ = T⁻¹e₀ (first column of the inverse,
//! e₀ the harmonic −H) and ξ₀ ≠ 0, and T Hermitian (a real: â_{−k} = conj(â_k), so the
//! last column of T⁻¹ is the reversed conjugate of ξ):
//!
//!   ξ₀ T⁻¹ = L(ξ) L(ξ̄)ᵀ − L(Z J ξ̄) L(Z J ξ)ᵀ,
//!
//! L(v) the lower-triangular Toeplitz matrix of first column v, Z the down-shift and J the
//! exchange. Each factor is a linear convolution or correlation, applied by complex FFTs of
//! size N ≥ 4H+1 (no wrap-around onto a retained entry): a solve is six FFTs once the four
//! generators' spectra are known (`set_generator`, once per factorisation). When a is
//! even in time (a time-symmetric orbit), T and ξ are real and a real right-hand side
//! (an even series) is solved by six real FFTs instead (`EvenGs`). The formula
//! is exact in exact arithmetic; its round-off is that of a direct solve of T when T is
//! well conditioned, and the caller checks it by residuals (contact.rs).

use super::series;
use realfft::num_complex::Complex;
use realfft::{ComplexToReal, RealFftPlanner, RealToComplex};
use rustfft::{Fft, FftPlanner};
use std::cell::RefCell;
use std::sync::Arc;

type C = Complex<f64>;

thread_local! {
    static PLANNER: RefCell<FftPlanner<f64>> = RefCell::new(FftPlanner::new());
    static REAL_PLANNER: RefCell<RealFftPlanner<f64>> = RefCell::new(RealFftPlanner::new());
}

/// Complex coefficients (index k + H, k = −H..H) of a real series with `h` harmonics
/// (series.rs layout: x̂₀ = x₀, x̂_{±k} = (c_k ∓ i s_k)/2).
pub fn to_complex(x: &[f64], h: usize, out: &mut [C]) {
    out[h] = C::new(x[0], 0.0);
    for k in 1..=h {
        let z = C::new(0.5 * x[series::ic(k)], -0.5 * x[series::is(h, k)]);
        out[h + k] = z;
        out[h - k] = z.conj();
    }
}

/// The real series of Hermitian-symmetric complex coefficients (the real part of the
/// function they describe, if they are not quite symmetric).
pub fn from_complex(z: &[C], h: usize, out: &mut [f64]) {
    out[0] = z[h].re;
    for k in 1..=h {
        // Average of the +k and conjugated −k entries: exact for symmetric input.
        let v = 0.5 * (z[h + k] + z[h - k].conj());
        out[series::ic(k)] = 2.0 * v.re;
        out[series::is(h, k)] = -2.0 * v.im;
    }
}

/// The Gohberg–Semencul inverse in real arithmetic, for a real ξ (T real: the symbol a is
/// even in time, as on a time-symmetric orbit) applied to real coefficient vectors (even
/// right-hand sides). The four kernels and every intermediate are then real sequences,
/// so the six transforms of a solve are real FFTs of the same size, about half the work
/// of complex ones.
struct EvenGs {
    fwd: Arc<dyn RealToComplex<f64>>,
    inv: Arc<dyn ComplexToReal<f64>>,
    scratch: Vec<C>,
    /// Half spectra (N/2 + 1) of the kernels, scaled as GsInverse's.
    corr1: Vec<C>,
    corr2: Vec<C>,
    conv1: Vec<C>,
    conv2: Vec<C>,
    b: Vec<f64>,
    u1: Vec<f64>,
    u2: Vec<f64>,
    sb: Vec<C>,
    s1: Vec<C>,
    s2: Vec<C>,
}

impl EvenGs {
    fn new(nfft: usize) -> EvenGs {
        let (fwd, inv) = REAL_PLANNER.with(|p| {
            let mut p = p.borrow_mut();
            (p.plan_fft_forward(nfft), p.plan_fft_inverse(nfft))
        });
        let len = fwd.get_scratch_len().max(inv.get_scratch_len());
        let spec = || vec![C::new(0.0, 0.0); nfft / 2 + 1];
        EvenGs {
            fwd,
            inv,
            scratch: vec![C::new(0.0, 0.0); len],
            corr1: spec(),
            corr2: spec(),
            conv1: spec(),
            conv2: spec(),
            b: vec![0.0; nfft],
            u1: vec![0.0; nfft],
            u2: vec![0.0; nfft],
            sb: spec(),
            s1: spec(),
            s2: spec(),
        }
    }

    /// b ← T⁻¹ b for real coefficient vectors b (length n ≤ N/2).
    fn solve(&mut self, b: &mut [f64]) {
        let n = b.len();
        self.b[..n].copy_from_slice(b);
        self.b[n..].fill(0.0);
        let _ = self
            .fwd
            .process_with_scratch(&mut self.b, &mut self.sb, &mut self.scratch);
        for ((s1, s2), (bb, (c1, c2))) in self
            .s1
            .iter_mut()
            .zip(self.s2.iter_mut())
            .zip(self.sb.iter().zip(self.corr1.iter().zip(&self.corr2)))
        {
            *s1 = bb * c1;
            *s2 = bb * c2;
        }
        // The spectra of real sequences: their first (and, N even, last) entries are real
        // up to the products' round-off, which the inverse transform wants exactly real.
        for s in [&mut self.s1, &mut self.s2] {
            s[0].im = 0.0;
            if let Some(last) = s.last_mut() {
                last.im = 0.0;
            }
        }
        let _ = self
            .inv
            .process_with_scratch(&mut self.s1, &mut self.u1, &mut self.scratch);
        let _ = self
            .inv
            .process_with_scratch(&mut self.s2, &mut self.u2, &mut self.scratch);
        self.u1[n..].fill(0.0);
        self.u2[n..].fill(0.0);
        let _ = self
            .fwd
            .process_with_scratch(&mut self.u1, &mut self.s1, &mut self.scratch);
        let _ = self
            .fwd
            .process_with_scratch(&mut self.u2, &mut self.s2, &mut self.scratch);
        for (o, ((u1, u2), (c1, c2))) in self.sb.iter_mut().zip(
            self.s1
                .iter()
                .zip(&self.s2)
                .zip(self.conv1.iter().zip(&self.conv2)),
        ) {
            *o = u1 * c1 - u2 * c2;
        }
        self.sb[0].im = 0.0;
        if let Some(last) = self.sb.last_mut() {
            last.im = 0.0;
        }
        let _ = self
            .inv
            .process_with_scratch(&mut self.sb, &mut self.b, &mut self.scratch);
        b.copy_from_slice(&self.b[..n]);
    }
}

/// The Gohberg–Semencul representation of T⁻¹ for one T (module doc).
pub struct GsInverse {
    h: usize,
    n: usize,
    nfft: usize,
    fwd: Arc<dyn Fft<f64>>,
    inv: Arc<dyn Fft<f64>>,
    scratch: Vec<C>,
    /// Spectra (scaled by 1/N, and the last two by 1/(N·ξ₀)) of the correlation kernels
    /// of ξ̄ and ZJξ, and of the convolution kernels ξ and ZJξ̄.
    corr1: Vec<C>,
    corr2: Vec<C>,
    conv1: Vec<C>,
    conv2: Vec<C>,
    b: Vec<C>,
    u1: Vec<C>,
    u2: Vec<C>,
    /// The real form, made on the first real generator; `real` says whether the current
    /// generator is one.
    even: Option<Box<EvenGs>>,
    real: bool,
}

impl GsInverse {
    /// For operators on series of `h` harmonics.
    pub fn new(h: usize) -> GsInverse {
        let n = series::len(h);
        let nfft = series::fft_size_smooth(2 * n - 2);
        let (fwd, inv) = PLANNER.with(|p| {
            let mut p = p.borrow_mut();
            (p.plan_fft_forward(nfft), p.plan_fft_inverse(nfft))
        });
        let len = fwd
            .get_inplace_scratch_len()
            .max(inv.get_inplace_scratch_len());
        let z = || vec![C::new(0.0, 0.0); nfft];
        GsInverse {
            h,
            n,
            nfft,
            fwd,
            inv,
            scratch: vec![C::new(0.0, 0.0); len],
            corr1: z(),
            corr2: z(),
            conv1: z(),
            conv2: z(),
            b: z(),
            u1: z(),
            u2: z(),
            even: None,
            real: false,
        }
    }

    /// Whether the current generator is real (T real), so that `solve_real` applies.
    #[cfg(test)]
    pub fn is_real(&self) -> bool {
        self.real
    }

    /// Harmonics of the series the operator acts on.
    pub fn harmonics(&self) -> usize {
        self.h
    }

    /// Set ξ = T⁻¹e₀ (length 2H+1); false when ξ₀ vanishes or ξ is not finite (no
    /// representation: the caller takes another route). `real`: the caller knows T to be
    /// real (an even symbol), so that ξ is real in exact arithmetic; its imaginary part,
    /// the error of the solves that gave ξ, is then dropped and the solves of real
    /// right-hand sides take real FFTs (`solve_real`).
    pub fn set_generator(&mut self, xi: &[C], real: bool) -> bool {
        let (n, nf) = (self.n, self.nfft);
        // A real generator is its real part (the rest is the error of the solves).
        let xi_at = |k: usize| if real { C::new(xi[k].re, 0.0) } else { xi[k] };
        let x0 = xi_at(0);
        if x0.norm().partial_cmp(&0.0) != Some(std::cmp::Ordering::Greater)
            || xi.iter().any(|v| !(v.re.is_finite() && v.im.is_finite()))
        {
            return false;
        }
        let scale = 1.0 / nf as f64;
        let zero = C::new(0.0, 0.0);
        // Correlation u_i = Σ_{j≥i} g_{j−i} b_j is the cyclic convolution of b with the
        // kernel w_0 = g_0, w_{N−k} = g_k.
        self.corr1.fill(zero);
        self.corr2.fill(zero);
        self.conv1.fill(zero);
        self.conv2.fill(zero);
        // (ZJv)_0 = 0, (ZJv)_i = v_{n−i}.
        for k in 0..n {
            let g1 = xi_at(k).conj();
            let g2 = if k == 0 { zero } else { xi_at(n - k) };
            let pos = if k == 0 { 0 } else { nf - k };
            self.corr1[pos] = g1 * scale;
            self.corr2[pos] = g2 * scale;
            self.conv1[k] = xi_at(k);
            self.conv2[k] = if k == 0 { zero } else { xi_at(n - k).conj() };
        }
        let s = scale / x0;
        for v in self.conv1.iter_mut().chain(self.conv2.iter_mut()) {
            *v *= s;
        }
        self.real = real;
        if self.real {
            self.set_real_spectra();
            return true;
        }
        for buf in [
            &mut self.corr1,
            &mut self.corr2,
            &mut self.conv1,
            &mut self.conv2,
        ] {
            self.fwd.process_with_scratch(buf, &mut self.scratch);
        }
        true
    }

    /// A real generator's kernels (already in `corr1`..`conv2`, before their transforms):
    /// their half spectra by real FFTs, and the complex spectra as those half spectra's
    /// Hermitian extensions, so both solves use the same real kernels.
    fn set_real_spectra(&mut self) {
        let nf = self.nfft;
        let even = self.even.get_or_insert_with(|| Box::new(EvenGs::new(nf)));
        let EvenGs {
            fwd,
            scratch,
            corr1,
            corr2,
            conv1,
            conv2,
            b: work,
            ..
        } = &mut **even;
        for (buf, half) in [
            (&mut self.corr1, corr1),
            (&mut self.corr2, corr2),
            (&mut self.conv1, conv1),
            (&mut self.conv2, conv2),
        ] {
            for (w, v) in work.iter_mut().zip(buf.iter()) {
                *w = v.re;
            }
            // Lengths are the plan's by construction: no error can come back.
            let _ = fwd.process_with_scratch(work, half, scratch);
            buf[..half.len()].copy_from_slice(half);
            for k in half.len()..nf {
                buf[k] = buf[nf - k].conj();
            }
        }
    }

    /// b ← T⁻¹ b for a real coefficient vector b (length 2H+1) by real FFTs, when the
    /// generator is real (`is_real`); false, b untouched, when it is not.
    pub fn solve_real(&mut self, b: &mut [f64]) -> bool {
        match self.even.as_mut() {
            Some(even) if self.real => {
                even.solve(b);
                true
            }
            _ => false,
        }
    }

    /// b ← T⁻¹ b (complex coefficients, length 2H+1).
    pub fn solve_complex(&mut self, b: &mut [C]) {
        let (n, zero) = (self.n, C::new(0.0, 0.0));
        self.b[..n].copy_from_slice(b);
        self.b[n..].fill(zero);
        self.fwd
            .process_with_scratch(&mut self.b, &mut self.scratch);
        for ((u1, u2), (bb, (c1, c2))) in self
            .u1
            .iter_mut()
            .zip(self.u2.iter_mut())
            .zip(self.b.iter().zip(self.corr1.iter().zip(&self.corr2)))
        {
            *u1 = bb * c1;
            *u2 = bb * c2;
        }
        self.inv
            .process_with_scratch(&mut self.u1, &mut self.scratch);
        self.inv
            .process_with_scratch(&mut self.u2, &mut self.scratch);
        self.u1[n..].fill(zero);
        self.u2[n..].fill(zero);
        self.fwd
            .process_with_scratch(&mut self.u1, &mut self.scratch);
        self.fwd
            .process_with_scratch(&mut self.u2, &mut self.scratch);
        for (o, ((u1, u2), (c1, c2))) in self.b.iter_mut().zip(
            self.u1
                .iter()
                .zip(&self.u2)
                .zip(self.conv1.iter().zip(&self.conv2)),
        ) {
            *o = u1 * c1 - u2 * c2;
        }
        self.inv
            .process_with_scratch(&mut self.b, &mut self.scratch);
        b.copy_from_slice(&self.b[..n]);
    }
}

/// Real-series solves: `x ← A⁻¹ x` for A = Trunc_H(a·) in the series layout, through the
/// complex coefficients.
pub struct RealGs {
    pub gs: GsInverse,
    z: Vec<C>,
    e: Vec<f64>,
}

impl RealGs {
    pub fn new(h: usize) -> RealGs {
        RealGs {
            gs: GsInverse::new(h),
            z: vec![C::new(0.0, 0.0); series::len(h)],
            e: vec![0.0; series::len(h)],
        }
    }

    /// Set the generator from the real solutions ξ_c = A⁻¹(2 cos Hθ) and
    /// ξ_s = A⁻¹(2 sin Hθ): T⁻¹e₀ = (ξ̂_c − i ξ̂_s)/2 (e₀ = (2cos Hθ − i·2 sin Hθ)/2 in
    /// complex coefficients is the harmonic −H alone).
    /// `real`: the symbol is even in time (`GsInverse::set_generator`).
    pub fn set_from_real(&mut self, xi_c: &[f64], xi_s: &[f64], real: bool) -> bool {
        let h = self.gs.harmonics();
        let n = series::len(h);
        let mut zc = vec![C::new(0.0, 0.0); n];
        to_complex(xi_c, h, &mut zc);
        to_complex(xi_s, h, &mut self.z);
        let mi = C::new(0.0, -1.0);
        for (c, s) in zc.iter_mut().zip(&self.z) {
            *c = 0.5 * (*c + mi * s);
        }
        self.gs.set_generator(&zc, real)
    }

    /// x ← A⁻¹ x (real series of H harmonics).
    pub fn solve(&mut self, x: &mut [f64]) {
        let h = self.gs.harmonics();
        to_complex(x, h, &mut self.z);
        self.gs.solve_complex(&mut self.z);
        from_complex(&self.z, h, x);
    }

    /// x ← A⁻¹ x_even, x_even the cosine part of x (its sine coefficients dropped), for a
    /// real generator (`GsInverse::is_real`), by real FFTs: x̂_even is real and symmetric,
    /// and so is T⁻¹x̂_even, whose sine part is zero. For the solves of a time-symmetric
    /// branch, whose right-hand sides are even in exact arithmetic (contact.rs). Without a
    /// real generator, `solve` of x_even.
    pub fn solve_even(&mut self, x: &mut [f64]) {
        let h = self.gs.harmonics();
        let e = &mut self.e;
        e[h] = x[0];
        for k in 1..=h {
            let v = 0.5 * x[series::ic(k)];
            e[h + k] = v;
            e[h - k] = v;
        }
        let real = self.gs.solve_real(e);
        for k in 1..=h {
            x[series::is(h, k)] = 0.0;
        }
        if !real {
            return self.solve(x);
        }
        x[0] = e[h];
        for k in 1..=h {
            x[series::ic(k)] = e[h + k] + e[h - k];
        }
    }

    /// x ← A⁻¹ x and y ← A⁻¹ y by one complex solve: A is real, so T maps the Hermitian
    /// coefficient vectors of real series to Hermitian ones, and T⁻¹(x̂ + iŷ) splits into
    /// its Hermitian part T⁻¹x̂ and i times its other part T⁻¹ŷ.
    pub fn solve_pair(&mut self, x: &mut [f64], y: &mut [f64]) {
        let h = self.gs.harmonics();
        let z = &mut self.z;
        let i = C::new(0.0, 1.0);
        z[h] = C::new(x[0], y[0]);
        for k in 1..=h {
            let a = C::new(0.5 * x[series::ic(k)], -0.5 * x[series::is(h, k)]);
            let b = C::new(0.5 * y[series::ic(k)], -0.5 * y[series::is(h, k)]);
            z[h + k] = a + i * b;
            z[h - k] = a.conj() + i * b.conj();
        }
        self.gs.solve_complex(z);
        x[0] = z[h].re;
        y[0] = z[h].im;
        for k in 1..=h {
            let (p, m) = (z[h + k], z[h - k].conj());
            // Hermitian part (x̂_k) and the other part over i (ŷ_k).
            let a = 0.5 * (p + m);
            let b = (p - m) * C::new(0.0, -0.5);
            x[series::ic(k)] = 2.0 * a.re;
            x[series::is(h, k)] = -2.0 * a.im;
            y[series::ic(k)] = 2.0 * b.re;
            y[series::is(h, k)] = -2.0 * b.im;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn lcg(seed: &mut u64) -> f64 {
        *seed = seed
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        ((*seed >> 11) as f64 / (1u64 << 53) as f64) - 0.5
    }

    /// Dense T⁻¹ by Gauss–Jordan on complex numbers (the independent reference).
    fn dense_solve(t: &[Vec<C>], b: &[C]) -> Vec<C> {
        let n = b.len();
        let mut a: Vec<Vec<C>> = t.to_vec();
        let mut x = b.to_vec();
        for c in 0..n {
            let p = (c..n)
                .max_by(|&i, &j| a[i][c].norm().total_cmp(&a[j][c].norm()))
                .unwrap();
            a.swap(c, p);
            x.swap(c, p);
            for r in 0..n {
                if r != c {
                    let f = a[r][c] / a[c][c];
                    let pivot_row = a[c].clone();
                    for (ark, v) in a[r][c..n].iter_mut().zip(&pivot_row[c..n]) {
                        *ark -= f * v;
                    }
                    let v = x[c];
                    x[r] -= f * v;
                }
            }
        }
        (0..n).map(|i| x[i] / a[i][i]).collect()
    }

    /// The Gohberg–Semencul solve equals a dense solve of the Toeplitz matrix of a
    /// positive symbol (to 1e-12 relative: both are direct, the matrix's condition number
    /// is below 10, so round-off of either stays below 1e-13), and the real-series route
    /// equals the truncated-product operator's dense inverse (series::mul_operator).
    #[test]
    fn gohberg_semencul_solves_equal_dense_solves() {
        let mut seed = 3u64;
        for h in [1usize, 2, 7, 30] {
            let n = series::len(h);
            // a = 3 + small harmonics: positive, T Hermitian positive definite.
            let mut a = vec![0.0; n];
            a[0] = 3.0;
            for v in a[1..].iter_mut() {
                *v = 0.4 * lcg(&mut seed) / (1.0 + 0.1 * h as f64).sqrt();
            }
            let mut ahat = vec![C::new(0.0, 0.0); n];
            to_complex(&a, h, &mut ahat);
            let coef = |m: i64| -> C {
                let k = m.unsigned_abs() as usize;
                if k > h {
                    C::new(0.0, 0.0)
                } else if m >= 0 {
                    ahat[h + k]
                } else {
                    ahat[h - k]
                }
            };
            let t: Vec<Vec<C>> = (0..n)
                .map(|i| (0..n).map(|j| coef(i as i64 - j as i64)).collect())
                .collect();
            let mut e0 = vec![C::new(0.0, 0.0); n];
            e0[0] = C::new(1.0, 0.0);
            let xi = dense_solve(&t, &e0);
            let mut gs = GsInverse::new(h);
            assert!(gs.set_generator(&xi, false));
            let b: Vec<C> = (0..n)
                .map(|_| C::new(lcg(&mut seed), lcg(&mut seed)))
                .collect();
            let want = dense_solve(&t, &b);
            let mut got = b.clone();
            gs.solve_complex(&mut got);
            let scale = want.iter().fold(0.0f64, |m, v| m.max(v.norm()));
            let err = got
                .iter()
                .zip(&want)
                .fold(0.0f64, |m, (g, w)| m.max((g - w).norm()));
            assert!(err <= 1e-12 * scale, "h {h}: {err:e} vs {scale:e}");

            // Real route against the dense real operator.
            let op = series::mul_operator(&a, h, h, h);
            let (mut xc, mut xs) = (vec![0.0; n], vec![0.0; n]);
            xc[series::ic(h)] = 2.0;
            xs[series::is(h, h)] = 2.0;
            let real_dense = |rhs: &[f64]| -> Vec<f64> {
                let tr: Vec<Vec<C>> = (0..n)
                    .map(|i| (0..n).map(|j| C::new(op[j * n + i], 0.0)).collect())
                    .collect();
                let b: Vec<C> = rhs.iter().map(|&v| C::new(v, 0.0)).collect();
                dense_solve(&tr, &b).iter().map(|v| v.re).collect()
            };
            xc = real_dense(&xc);
            xs = real_dense(&xs);
            let mut rg = RealGs::new(h);
            assert!(rg.set_from_real(&xc, &xs, false));
            let rhs: Vec<f64> = (0..n).map(|_| lcg(&mut seed)).collect();
            let want = real_dense(&rhs);
            let mut got = rhs.clone();
            rg.solve(&mut got);
            let scale = want.iter().fold(0.0f64, |m, v| m.max(v.abs()));
            let err = got
                .iter()
                .zip(&want)
                .fold(0.0f64, |m, (g, w)| m.max((g - w).abs()));
            assert!(err <= 1e-12 * scale, "real h {h}: {err:e} vs {scale:e}");

            // Two real solves by one complex one.
            let rhs2: Vec<f64> = (0..n).map(|_| lcg(&mut seed)).collect();
            let want2 = real_dense(&rhs2);
            let (mut p, mut q) = (rhs.clone(), rhs2.clone());
            rg.solve_pair(&mut p, &mut q);
            for (got, want) in [(&p, &want), (&q, &want2)] {
                let scale = want.iter().fold(0.0f64, |m, v| m.max(v.abs()));
                let err = got
                    .iter()
                    .zip(want.iter())
                    .fold(0.0f64, |m, (g, w)| m.max((g - w).abs()));
                assert!(err <= 1e-12 * scale, "pair h {h}: {err:e} vs {scale:e}");
            }
        }
    }

    /// An even symbol (a cosine series): T is real, and the real route's solves
    /// (`solve_even`, and the complex one from the real generator) equal dense solves of
    /// the truncated-product operator (to 1e-12 relative: the symbol is positive and its
    /// condition number below 10, so either's round-off stays below 1e-13). Up to
    /// H_nl 200, sdnd122a's size, so that the real FFTs of 810 points are exercised.
    #[test]
    fn even_symbol_real_route_equals_dense_solves() {
        let mut seed = 11u64;
        for h in [1usize, 2, 7, 30, 200] {
            let n = series::len(h);
            let mut a = vec![0.0; n];
            a[0] = 3.0;
            for k in 1..=h {
                a[series::ic(k)] = 0.4 * lcg(&mut seed) / (1.0 + 0.1 * h as f64).sqrt();
            }
            let op = series::mul_operator(&a, h, h, h);
            let tr: Vec<Vec<C>> = (0..n)
                .map(|i| (0..n).map(|j| C::new(op[j * n + i], 0.0)).collect())
                .collect();
            let real_dense = |rhs: &[f64]| -> Vec<f64> {
                let b: Vec<C> = rhs.iter().map(|&v| C::new(v, 0.0)).collect();
                dense_solve(&tr, &b).iter().map(|v| v.re).collect()
            };
            let (mut xc, mut xs) = (vec![0.0; n], vec![0.0; n]);
            xc[series::ic(h)] = 2.0;
            xs[series::is(h, h)] = 2.0;
            let mut rg = RealGs::new(h);
            assert!(rg.set_from_real(&real_dense(&xc), &real_dense(&xs), true));
            assert!(rg.gs.is_real());
            let rhs: Vec<f64> = (0..n).map(|_| lcg(&mut seed)).collect();
            let mut even = rhs.clone();
            for k in 1..=h {
                even[series::is(h, k)] = 0.0;
            }
            let max_err = |got: &[f64], want: &[f64]| {
                let scale = want.iter().fold(0.0f64, |m, v| m.max(v.abs()));
                let err = got
                    .iter()
                    .zip(want)
                    .fold(0.0f64, |m, (g, w)| m.max((g - w).abs()));
                err / scale
            };
            let mut got = rhs.clone();
            rg.solve(&mut got);
            let e = max_err(&got, &real_dense(&rhs));
            assert!(e <= 1e-12, "complex route, h {h}: {e:e}");
            // solve_even drops the sine part of its right-hand side.
            let mut got = rhs.clone();
            rg.solve_even(&mut got);
            let e = max_err(&got, &real_dense(&even));
            assert!(e <= 1e-12, "real route, h {h}: {e:e}");
            assert!((1..=h).all(|k| got[series::is(h, k)] == 0.0));
        }
    }
}
