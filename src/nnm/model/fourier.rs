//! Truncated Fourier series of one scalar time function.
//!
//! Layout (Code_Aster's): `[x0, c1..cH, s1..sH]`, 2H+1 numbers, for
//! x(θ) = x0 + Σ_k (c_k cos kθ + s_k sin kθ), θ = ωt.
//! Products are exact for the retained harmonics: by convolution (trigonometric product
//! formulas, O(H_a·H_b)) for small series, by FFT of zero-padded samples (O(N log N),
//! N > H_a + H_b + H_out so no aliasing reaches a retained harmonic) for large ones.

use realfft::num_complex::Complex;
use realfft::{ComplexToReal, RealFftPlanner, RealToComplex};
use std::cell::RefCell;
use std::sync::Arc;

/// Number of coefficients of a series with `h` harmonics.
pub fn len(h: usize) -> usize {
    2 * h + 1
}

/// Index of cos(kθ) (k ≥ 1), or of the mean for k = 0.
pub fn ic(k: usize) -> usize {
    k
}

/// Index of sin(kθ), k ≥ 1.
pub fn is(h: usize, k: usize) -> usize {
    h + k
}

/// Position in a series with `h_to` harmonics of coefficient `j` of a series with `h_from`
/// harmonics, or None when that harmonic is not retained.
pub fn map_index(j: usize, h_from: usize, h_to: usize) -> Option<usize> {
    if j == 0 {
        Some(0)
    } else if j <= h_from {
        (j <= h_to).then_some(j)
    } else {
        let k = j - h_from;
        (k <= h_to).then_some(h_to + k)
    }
}

/// d/dθ: (Dx)c_k = k s_k, (Dx)s_k = −k c_k.
pub fn deriv(x: &[f64], h: usize, out: &mut [f64]) {
    out[0] = 0.0;
    for k in 1..=h {
        let kf = k as f64;
        let (c, s) = (x[ic(k)], x[is(h, k)]);
        out[ic(k)] = kf * s;
        out[is(h, k)] = -kf * c;
    }
}

/// Value at θ.
pub fn eval(x: &[f64], h: usize, theta: f64) -> f64 {
    let mut v = x[0];
    for k in 1..=h {
        let (s, c) = (k as f64 * theta).sin_cos();
        v += x[ic(k)] * c + x[is(h, k)] * s;
    }
    v
}

/// Values at θ_j = 2πj/n for j = 0..=n (one period, both ends): each cos kθ_j and sin kθ_j
/// is read from one table of n angles (kj mod n), so the cost is n sin/cos and
/// (n + 1)·h products instead of (n + 1)·h sin/cos (REST_MODE_NONL's time histories).
pub fn eval_uniform(x: &[f64], h: usize, n: usize) -> Vec<f64> {
    let step = 2.0 * std::f64::consts::PI / n as f64;
    let table: Vec<(f64, f64)> = (0..n).map(|m| (m as f64 * step).sin_cos()).collect();
    (0..=n)
        .map(|j| {
            let mut v = x[0];
            let mut m = 0;
            for k in 1..=h {
                // m = k·j mod n, advanced by j at each harmonic.
                m += j % n;
                if m >= n {
                    m -= n;
                }
                let (s, c) = table[m];
                v += x[ic(k)] * c + x[is(h, k)] * s;
            }
            v
        })
        .collect()
}

/// The complex coefficients x̂_k (k = −h..h, index k + h) of a real series: x̂_0 = x_0,
/// x̂_{±k} = (c_k ∓ i s_k)/2.
fn complex_coefficients(x: &[f64], h: usize) -> Vec<Complex<f64>> {
    let mut z = vec![Complex::new(x[0], 0.0); len(h)];
    for k in 1..=h {
        let v = Complex::new(0.5 * x[ic(k)], -0.5 * x[is(h, k)]);
        z[h + k] = v;
        z[h - k] = v.conj();
    }
    z
}

/// out += scale · trunc_hout(a·b), by the convolution of the complex coefficients
/// (ĉ_n = Σ_k â_k b̂_{n−k}, n = 0..hout; the negative n are the conjugates).
pub fn mul_conv_acc(
    a: &[f64],
    ha: usize,
    b: &[f64],
    hb: usize,
    hout: usize,
    scale: f64,
    out: &mut [f64],
) {
    let (za, zb) = (complex_coefficients(a, ha), complex_coefficients(b, hb));
    let (ha_i, hb_i) = (ha as i64, hb as i64);
    for n in 0..=hout.min(ha + hb) {
        let ni = n as i64;
        let (lo, hi) = ((-ha_i).max(ni - hb_i), ha_i.min(ni + hb_i));
        let mut c = Complex::new(0.0, 0.0);
        for k in lo..=hi {
            c += za[(k + ha_i) as usize] * zb[(ni - k + hb_i) as usize];
        }
        if n == 0 {
            out[0] += scale * c.re;
        } else {
            out[ic(n)] += 2.0 * scale * c.re;
            out[is(hout, n)] -= 2.0 * scale * c.im;
        }
    }
}

/// Dense matrix (column-major, (2hout+1) × (2hx+1)) of x ↦ trunc_hout(c·x), x with hx harmonics.
pub fn mul_operator(c: &[f64], hc: usize, hx: usize, hout: usize) -> Vec<f64> {
    let nr = len(hout);
    let mut m = vec![0.0; nr * len(hx)];
    for j in 0..len(hx) {
        let mut e = vec![0.0; len(hx)];
        e[j] = 1.0;
        // The single nonzero of e drives the outer loop: O(hc) per column.
        mul_conv_acc(&e, hx, c, hc, hout, 1.0, &mut m[j * nr..(j + 1) * nr]);
    }
    m
}

/// Smallest power of two strictly above `need` (and at least 8).
pub fn fft_size(need: usize) -> usize {
    (need + 1).next_power_of_two().max(8)
}

/// Smallest even size 2^a·3^b·5^c (a ≥ 1) strictly above `need` (and at least 8): the
/// sizes realfft transforms fastest besides powers of two, up to 25 % fewer samples.
pub fn fft_size_smooth(need: usize) -> usize {
    let mut n = (need + 1).max(8);
    while !(n.is_multiple_of(2) && is_5_smooth(n)) {
        n += 1;
    }
    n
}

/// Dense operator x ↦ trunc_hout(c·x) written into `out` (column-major, leading dimension
/// `ld` ≥ 2hout+1, (2hout+1) × (2hx+1)), from the trigonometric product formulas directly
/// (O(1) per entry; `mul_operator` is the reference). With A(j) = c_{|j|} (cos part,
/// A(0) = 2c₀) and B(j) = sign(j)·s_{|j|}: column cos l gives cos p ← (A(p−l) + A(p+l))/2,
/// sin p ← (B(p−l) + B(p+l))/2, mean ← A(l)/2; column sin l gives cos p ← (B(p+l) −
/// B(p−l))/2, sin p ← (A(p−l) − A(p+l))/2, mean ← B(l)/2.
pub fn fill_mul_operator(
    c: &[f64],
    hc: usize,
    hx: usize,
    hout: usize,
    scale: f64,
    out: &mut [f64],
    ld: usize,
) {
    let a = |j: i64| -> f64 {
        let k = j.unsigned_abs() as usize;
        if k == 0 {
            2.0 * c[0]
        } else if k <= hc {
            c[ic(k)]
        } else {
            0.0
        }
    };
    let b = |j: i64| -> f64 {
        let k = j.unsigned_abs() as usize;
        if k == 0 || k > hc {
            0.0
        } else if j > 0 {
            c[is(hc, k)]
        } else {
            -c[is(hc, k)]
        }
    };
    let hs = 0.5 * scale;
    for l in 0..=hx {
        let li = l as i64;
        let col = &mut out[ic(l) * ld..];
        col[0] += hs * a(li);
        for p in 1..=hout {
            let pi = p as i64;
            col[ic(p)] += hs * (a(pi - li) + a(pi + li));
            col[is(hout, p)] += hs * (b(pi - li) + b(pi + li));
        }
        if l == 0 {
            continue;
        }
        let col = &mut out[is(hx, l) * ld..];
        col[0] += hs * b(li);
        for p in 1..=hout {
            let pi = p as i64;
            col[ic(p)] += hs * (b(pi + li) - b(pi - li));
            col[is(hout, p)] += hs * (a(pi - li) - a(pi + li));
        }
    }
}

thread_local! {
    static PLANNER: RefCell<RealFftPlanner<f64>> = RefCell::new(RealFftPlanner::new());
}

/// The forward and inverse real FFTs of size `n`, from this thread's planner (plans are
/// shared between the samplers of one size).
pub fn real_fft_plans(n: usize) -> (Arc<dyn RealToComplex<f64>>, Arc<dyn ComplexToReal<f64>>) {
    PLANNER.with(|p| {
        let mut p = p.borrow_mut();
        (p.plan_fft_forward(n), p.plan_fft_inverse(n))
    })
}

/// Whether `n` ≥ 1 is 2^a·3^b·5^c.
pub fn is_5_smooth(n: usize) -> bool {
    let mut m = n;
    for p in [2, 3, 5] {
        while m.is_multiple_of(p) {
            m /= p;
        }
    }
    m == 1
}

/// Samples x(2πj/N), j = 0..N−1, and back, by real FFTs of size N.
pub struct Sampler {
    n: usize,
    fwd: Arc<dyn RealToComplex<f64>>,
    inv: Arc<dyn ComplexToReal<f64>>,
}

/// What one transform needs besides its input and output, allocated once per user
/// (`Sampler::scratch`) so that transforms in loops do not allocate.
pub struct FftScratch {
    spec: Vec<Complex<f64>>,
    work: Vec<Complex<f64>>,
}

impl Sampler {
    pub fn new(n: usize) -> Self {
        let (fwd, inv) = real_fft_plans(n);
        Sampler { n, fwd, inv }
    }

    pub fn n(&self) -> usize {
        self.n
    }

    /// A scratch for `synth_with` and `analyse_with`.
    pub fn scratch(&self) -> FftScratch {
        let len = self.fwd.get_scratch_len().max(self.inv.get_scratch_len());
        FftScratch {
            spec: vec![Complex::new(0.0, 0.0); self.n / 2 + 1],
            work: vec![Complex::new(0.0, 0.0); len],
        }
    }

    /// Samples of `x` (h harmonics, h < N/2) into `out` (length N).
    pub fn synth(&self, x: &[f64], h: usize, out: &mut [f64]) {
        self.synth_with(x, h, out, &mut self.scratch())
    }

    /// `synth` with a reused scratch (no allocation).
    pub fn synth_with(&self, x: &[f64], h: usize, out: &mut [f64], ws: &mut FftScratch) {
        let spec = &mut ws.spec;
        let top = h.min(self.n / 2 - 1);
        spec[0] = Complex::new(x[0], 0.0);
        for k in 1..=top {
            spec[k] = Complex::new(0.5 * x[ic(k)], -0.5 * x[is(h, k)]);
        }
        spec[top + 1..].fill(Complex::new(0.0, 0.0));
        // Lengths are consistent by construction, so the only failure (size mismatch) cannot
        // happen; on error leave NaN so callers' finiteness checks report it.
        if self
            .inv
            .process_with_scratch(spec, out, &mut ws.work)
            .is_err()
        {
            out.iter_mut().for_each(|v| *v = f64::NAN);
        }
    }

    /// Coefficients (h harmonics, h < N/2) of the samples `s` (length N); `s` is clobbered.
    pub fn analyse(&self, s: &mut [f64], h: usize, out: &mut [f64]) {
        self.analyse_with(s, h, out, &mut self.scratch())
    }

    /// `analyse` with a reused scratch (no allocation).
    pub fn analyse_with(&self, s: &mut [f64], h: usize, out: &mut [f64], ws: &mut FftScratch) {
        let spec = &mut ws.spec;
        if self
            .fwd
            .process_with_scratch(s, spec, &mut ws.work)
            .is_err()
        {
            out.iter_mut().for_each(|v| *v = f64::NAN);
            return;
        }
        let nf = self.n as f64;
        out[0] = spec[0].re / nf;
        for k in 1..=h {
            let z = spec.get(k).copied().unwrap_or_default();
            out[ic(k)] = 2.0 * z.re / nf;
            out[is(h, k)] = -2.0 * z.im / nf;
        }
    }
}

/// out += scale · trunc_hout(a·b) through FFT samples.
pub fn mul_fft_acc(
    a: &[f64],
    ha: usize,
    b: &[f64],
    hb: usize,
    hout: usize,
    scale: f64,
    out: &mut [f64],
) {
    let s = Sampler::new(fft_size(ha + hb + hout));
    let n = s.n();
    let (mut sa, mut sb) = (vec![0.0; n], vec![0.0; n]);
    s.synth(a, ha, &mut sa);
    s.synth(b, hb, &mut sb);
    for (x, y) in sa.iter_mut().zip(&sb) {
        *x *= y;
    }
    let mut c = vec![0.0; len(hout)];
    s.analyse(&mut sa, hout, &mut c);
    for (o, v) in out.iter_mut().zip(&c) {
        *o += scale * v;
    }
}

/// True when the FFT route is cheaper than the convolution for these sizes.
pub fn prefer_fft(ha: usize, hb: usize, hout: usize) -> bool {
    let conv = (2 * ha + 1) * (2 * hb + 1);
    let n = fft_size(ha + hb + hout);
    let fft = 3 * n * (n.trailing_zeros() as usize + 1) * 2;
    fft < conv
}

/// out += scale · trunc_hout(a·b), by convolution or FFT, whichever is cheaper.
pub fn mul_acc(
    a: &[f64],
    ha: usize,
    b: &[f64],
    hb: usize,
    hout: usize,
    scale: f64,
    out: &mut [f64],
) {
    if prefer_fft(ha, hb, hout) {
        mul_fft_acc(a, ha, b, hb, hout, scale, out)
    } else {
        mul_conv_acc(a, ha, b, hb, hout, scale, out)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn direct(a: &[f64], ha: usize, b: &[f64], hb: usize, hout: usize) -> Vec<f64> {
        // Reference: sample densely, multiply, project by the trapezoid rule (exact for
        // trigonometric polynomials of degree < number of samples).
        let n = 4 * (ha + hb + hout) + 8;
        let mut out = vec![0.0; len(hout)];
        for j in 0..n {
            let t = 2.0 * std::f64::consts::PI * j as f64 / n as f64;
            let p = eval(a, ha, t) * eval(b, hb, t);
            out[0] += p / n as f64;
            for k in 1..=hout {
                out[ic(k)] += 2.0 * p * (k as f64 * t).cos() / n as f64;
                out[is(hout, k)] += 2.0 * p * (k as f64 * t).sin() / n as f64;
            }
        }
        out
    }

    #[test]
    fn uniform_evaluation_matches_pointwise() {
        let h = 37;
        let x: Vec<f64> = (0..len(h))
            .map(|i| (0.7 * i as f64).sin() / (1.0 + i as f64))
            .collect();
        for n in [1usize, 2, 5, 16, 255] {
            let v = eval_uniform(&x, h, n);
            assert_eq!(v.len(), n + 1);
            for (j, &vj) in v.iter().enumerate() {
                let t = 2.0 * std::f64::consts::PI * j as f64 / n as f64;
                // Both sum the same 2h + 1 products; only the angles' round-off differs.
                assert!((vj - eval(&x, h, t)).abs() < 1e-13, "n {n} j {j}");
            }
        }
    }

    #[test]
    fn conv_matches_direct_projection() {
        let a = [0.3, 1.0, -0.5, 0.2, 0.7, -1.1, 0.4];
        let b = [-0.2, 0.5, 0.9, -0.3, 0.1];
        let mut c = vec![0.0; len(4)];
        mul_conv_acc(&a, 3, &b, 2, 4, 1.0, &mut c);
        let d = direct(&a, 3, &b, 2, 4);
        for (x, y) in c.iter().zip(&d) {
            assert!((x - y).abs() < 1e-13, "{c:?} vs {d:?}");
        }
    }

    #[test]
    fn operator_matches_product_and_deriv_is_exact() {
        let c = [0.3, 1.0, -0.5, 0.2, 0.7];
        let x = [1.5, -0.2, 0.4];
        let m = mul_operator(&c, 2, 1, 3);
        let mut y = vec![0.0; len(3)];
        mul_conv_acc(&c, 2, &x, 1, 3, 1.0, &mut y);
        for (r, yr) in y.iter().enumerate() {
            let v: f64 = (0..3).map(|j| m[j * len(3) + r] * x[j]).sum();
            assert!((v - yr).abs() < 1e-14);
        }
        let mut d = vec![0.0; 5];
        deriv(&c, 2, &mut d);
        let t = 0.37;
        let h = 1e-6;
        let fd = (eval(&c, 2, t + h) - eval(&c, 2, t - h)) / (2.0 * h);
        assert!((eval(&d, 2, t) - fd).abs() < 1e-8);
    }

    #[test]
    fn direct_operator_fill_equals_the_convolution_operator() {
        // Every (hc, hx, hout) shape, including hc above and below hx + hout; exact
        // formulas on both sides: equal to round-off.
        for (hc, hx, hout) in [
            (0, 0, 0),
            (2, 1, 3),
            (5, 2, 3),
            (3, 4, 4),
            (7, 7, 7),
            (1, 6, 2),
        ] {
            let c: Vec<f64> = (0..len(hc))
                .map(|i| ((i * 13 % 7) as f64 - 3.0) / 3.0)
                .collect();
            let m = mul_operator(&c, hc, hx, hout);
            let nr = len(hout);
            let ld = nr + 2;
            let mut f = vec![0.0; ld * len(hx)];
            fill_mul_operator(&c, hc, hx, hout, 2.0, &mut f, ld);
            for j in 0..len(hx) {
                for r in 0..nr {
                    assert!(
                        (2.0 * m[j * nr + r] - f[j * ld + r]).abs() < 1e-14,
                        "hc {hc} hx {hx} hout {hout} ({r}, {j})"
                    );
                }
            }
        }
    }

    #[test]
    fn smooth_sizes_are_even_5_smooth_and_above_the_need() {
        assert_eq!(fft_size_smooth(601), 640);
        assert_eq!(fft_size_smooth(3), 8);
        for need in 1..2000 {
            let n = fft_size_smooth(need);
            assert!(n > need && n.is_multiple_of(2) && n <= fft_size(need));
        }
    }

    #[test]
    fn reused_scratch_gives_the_same_samples() {
        let s = Sampler::new(640);
        let mut ws = s.scratch();
        let x: Vec<f64> = (0..len(200)).map(|i| 1.0 / (1.0 + i as f64)).collect();
        let (mut a, mut b) = (vec![0.0; 640], vec![0.0; 640]);
        s.synth(&x, 200, &mut a);
        s.synth_with(&x, 200, &mut b, &mut ws);
        assert_eq!(a, b);
        let mut y = vec![0.0; len(200)];
        s.analyse_with(&mut b, 200, &mut y, &mut ws);
        for (p, q) in x.iter().zip(&y) {
            assert!((p - q).abs() < 1e-15);
        }
        assert!((eval(&x, 200, 2.0 * std::f64::consts::PI * 7.0 / 640.0) - a[7]).abs() < 1e-13);
    }

    proptest! {
        // Property (6): the FFT route gives the convolution's numbers for retained harmonics
        // (both exact; 1e-12 relative to the coefficient scale covers round-off of N ≤ 1024).
        #[test]
        fn fft_product_equals_convolution(
            ha in 0usize..40, hb in 0usize..40, hout in 0usize..60,
            seed in proptest::collection::vec(-1.0f64..1.0, 162)) {
            let a: Vec<f64> = seed[..len(ha)].to_vec();
            let b: Vec<f64> = seed[81..81 + len(hb)].to_vec();
            let mut c1 = vec![0.0; len(hout)];
            let mut c2 = vec![0.0; len(hout)];
            mul_conv_acc(&a, ha, &b, hb, hout, 1.0, &mut c1);
            mul_fft_acc(&a, ha, &b, hb, hout, 1.0, &mut c2);
            let scale: f64 = 1.0 + a.iter().map(|v| v.abs()).sum::<f64>() * b.iter().map(|v| v.abs()).sum::<f64>();
            for (x, y) in c1.iter().zip(&c2) {
                prop_assert!((x - y).abs() <= 1e-12 * scale, "{} vs {}", x, y);
            }
        }
    }
}
