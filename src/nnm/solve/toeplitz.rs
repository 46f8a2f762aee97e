//! Exact solves with a truncated multiplication operator T = Trunc_H(a·) of one real
//! function a(θ), in O(H log H) each, from one column of T⁻¹.
//!
//! In complex coefficients (x̂_k, k = −H..H) T is the Hermitian Toeplitz matrix
//! T_{kl} = â_{k−l}. Let ξ_c = T⁻¹(2 cos Hθ) and ξ_s = T⁻¹(2 sin Hθ) (real series; their
//! complex combination (ξ̂_c − iξ̂_s)/2 is the first column of T⁻¹, the Gohberg–Semencul
//! generator), p(θ) and q(θ) their values, and κ = c_H(ξ_c) + s_H(ξ_s) (four times the
//! corner entry (T⁻¹)₀₀, nonzero whenever the generator exists). The generating function
//! of T⁻¹ is then a Toeplitz Bezoutian, and on any grid of N ≥ 2H+1 equally spaced
//! instants θ_j the solution y = T⁻¹x of a series x with samples r_j is, sample by sample,
//!
//!   κN·y_i = p_i (Σ_j p_j r_j − (C q r)_i) + q_i (Σ_j q_j r_j + (C p r)_i)
//!            + 2 (p q' − p' q)_i r_i,
//!
//! with C the circulant (C v)_i = Σ_{j≠i} cot((θ_i − θ_j)/2) v_j. (Derivation: the kernel
//! Σ_{kl} (T⁻¹)_{kl} e^{ikφ} e^{−ilθ} equals, with Ξ = (p − iq)/2 and δ = φ − θ,
//! 4[Re(Ξ(φ)Ξ̄(θ)) − cot(δ/2) Im(Ξ(φ)Ξ̄(θ))]/κ, and its value at δ = 0 is the limit, the
//! derivative term; the mean over the grid of kernel × samples is exact because every
//! product of two harmonics of order ≤ H that it averages has order < N.) C is diagonal in
//! Fourier: cos kθ ↦ (N − 2k) sin kθ, sin kθ ↦ −(N − 2k) cos kθ (0 < k < N/2), the
//! mean and the Nyquist harmonic ↦ 0. A solve is therefore: the samples of x, two
//! pointwise products, two transforms to the spectrum and two back, a pointwise sum, and
//! the analysis of y: six real FFTs of N = 2m ≥ 2H+2 instants (`Full`), against six
//! complex FFTs of N ≥ 4H+1 for the Gohberg–Semencul product of triangular factors.
//!
//! When a is even in time (a time-symmetric orbit), ξ_c is a cosine series and ξ_s a
//! sine series, so p is even and q odd, and T maps cosine series to cosine series and
//! sine series to sine series. The formula then splits by parity onto the m midpoints of
//! half a period (`Half`): for an even x, p r is even and q r odd (and Σ q r = 0), and C
//! maps each to the other parity; each of the six transforms is a cosine or sine
//! transform of m points, one real FFT of m (cosine_sampler.rs). An odd x takes the same
//! path with the parities exchanged; a mixed x is the sum of both.
//!
//! The formula is exact in exact arithmetic; its round-off is that of a direct solve of T
//! when T is well conditioned (the callers check residuals, contact.rs).

use crate::nnm::model::cosine_sampler::{CosineSampler, CosineScratch};
use crate::nnm::model::fourier::{self, ic, is};
use multiversion::multiversion;
use realfft::num_complex::Complex;
use realfft::{ComplexToReal, RealToComplex};
use std::sync::Arc;

type C = Complex<f64>;

/// The full period on N = 2m instants θ_j = 2πj/N: any generator, any right-hand side.
struct Full {
    n: usize,
    cot: Cot,
    /// Samples of p, q and 2(pq' − p'q).
    p: Vec<f64>,
    q: Vec<f64>,
    d: Vec<f64>,
    r: Vec<f64>,
    u: Vec<f64>,
    v: Vec<f64>,
}

impl Full {
    fn new(m: usize) -> Full {
        let n = 2 * m;
        let z = || vec![0.0; n];
        Full {
            n,
            cot: Cot::new(n),
            p: z(),
            q: z(),
            d: z(),
            r: z(),
            u: z(),
            v: z(),
        }
    }

    /// Samples of the series `x` (h harmonics, 2h < N) into `out`.
    fn synth(&mut self, x: &[f64], h: usize, out: &mut [f64]) {
        let s = &mut self.cot.spec;
        s.fill(C::new(0.0, 0.0));
        s[0] = C::new(x[0], 0.0);
        for k in 1..=h {
            s[k] = C::new(0.5 * x[ic(k)], -0.5 * x[is(h, k)]);
        }
        if self
            .cot
            .inv
            .process_with_scratch(s, out, &mut self.cot.work)
            .is_err()
        {
            // Lengths are the plan's by construction; NaN reaches the callers' checks.
            out.fill(f64::NAN);
        }
    }

    /// The series (h harmonics) of the samples `s` (clobbered) into `x`.
    fn analyse(&mut self, s: &mut [f64], h: usize, x: &mut [f64]) {
        let sp = &mut self.cot.spec;
        if self
            .cot
            .fwd
            .process_with_scratch(s, sp, &mut self.cot.work)
            .is_err()
        {
            x.fill(f64::NAN);
            return;
        }
        let nf = self.n as f64;
        x[0] = sp[0].re / nf;
        for k in 1..=h {
            x[ic(k)] = 2.0 * sp[k].re / nf;
            x[is(h, k)] = -2.0 * sp[k].im / nf;
        }
    }

    fn solve(&mut self, x: &mut [f64], h: usize, scale: f64) {
        let n = self.n;
        let mut r = std::mem::take(&mut self.r);
        self.synth(x, h, &mut r);
        let (p, q, d) = (&self.p[..n], &self.q[..n], &self.d[..n]);
        let (u, v) = (&mut self.u[..n], &mut self.v[..n]);
        for j in 0..n {
            u[j] = p[j] * r[j];
            v[j] = q[j] * r[j];
        }
        let sp = self.cot.apply(u);
        let sq = self.cot.apply(v);
        // u = C p r, v = C q r; y into r.
        for j in 0..n {
            r[j] = scale * (p[j] * (sp - v[j]) + q[j] * (sq + u[j]) + d[j] * r[j]);
        }
        self.analyse(&mut r, h, x);
        self.r = r;
    }
}

/// The m midpoints θ_j = π(2j+1)/(2m) of half a period: a time-symmetric generator, its
/// right-hand sides split into cosine and sine series. The samples of x and y are cosine
/// or sine transforms of m points; C is applied once on the whole period to p r + q r,
/// whose parts of either parity are p r and q r (of opposite parities), and whose image's
/// parts are C p r and C q r (C exchanges parities).
struct Half {
    m: usize,
    tr: CosineSampler,
    ws: CosineScratch,
    /// C on the N = 2m midpoints of the whole period.
    cot: Cot,
    /// Samples of p (even), q (odd) and 2(pq' − p'q) (even).
    p: Vec<f64>,
    q: Vec<f64>,
    d: Vec<f64>,
    r: Vec<f64>,
    /// The whole period's samples (N).
    w: Vec<f64>,
    /// A second buffer of m samples (the generator's derivatives, `set_generator`).
    c: Vec<f64>,
}

/// Parity of a right-hand side on the half period.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Parity {
    Even,
    Odd,
}

impl Half {
    fn new(m: usize) -> Half {
        let tr = CosineSampler::new(m);
        let ws = tr.scratch();
        let z = || vec![0.0; m];
        Half {
            m,
            tr,
            ws,
            cot: Cot::new(2 * m),
            p: z(),
            q: z(),
            d: z(),
            r: z(),
            w: vec![0.0; 2 * m],
            c: z(),
        }
    }

    /// y from the samples r of a right-hand side of `parity` (in `self.r`, y written over
    /// them), `scale` = 1/(κN).
    fn apply(&mut self, parity: Parity, scale: f64) {
        let m = self.m;
        let n = 2 * m;
        let (p, q, d, r) = (&self.p[..m], &self.q[..m], &self.d[..m], &mut self.r[..m]);
        // p r + q r on the whole period: at −θ_j = θ_{N−1−j}, p r keeps or flips its sign
        // with r and q r does the opposite.
        let sign = match parity {
            Parity::Even => 1.0,
            Parity::Odd => -1.0,
        };
        {
            let (lo, hi) = self.w.split_at_mut(m);
            spread_products(lo, hi, p, q, r, sign);
        }
        let sum = self.cot.apply(&mut self.w);
        let (lo, hi) = self.w.split_at(m);
        debug_assert_eq!(hi.len(), n - m);
        combine_halves(r, lo, hi, p, q, d, sum, scale, parity == Parity::Even);
    }

    /// x ← T⁻¹ x_even, x_even the cosine part of x; x's sine coefficients set to zero.
    fn solve_even(&mut self, x: &mut [f64], h: usize, scale: f64) {
        // The cosine part of the layout, [x_0, c_1..c_H], is the plain coefficients.
        self.tr.cos_synth(&x[..=h], &mut self.r, &mut self.ws);
        self.apply(Parity::Even, scale);
        self.tr.cos_analyse(&self.r, &mut x[..=h], &mut self.ws);
        x[h + 1..].fill(0.0);
    }

    /// x ← T⁻¹ x_odd, x_odd the sine part of x; x's mean and cosine coefficients set to zero.
    fn solve_odd(&mut self, x: &mut [f64], h: usize, scale: f64) {
        self.tr.sin_synth(&x[h + 1..], &mut self.r, &mut self.ws);
        self.apply(Parity::Odd, scale);
        self.tr.sin_analyse(&self.r, &mut x[h + 1..], &mut self.ws);
        x[..=h].fill(0.0);
    }
}

/// p r + q r on the whole period from the half period's samples (`Half::apply`): at
/// −θ_j = θ_{N−1−j}, p r keeps or flips its sign with r (`sign`) and q r does the
/// opposite. `hi` runs backwards; zipped iterators let the loop vectorise.
#[multiversion(targets("x86_64+avx+avx2+fma"))]
fn spread_products(lo: &mut [f64], hi: &mut [f64], p: &[f64], q: &[f64], r: &[f64], sign: f64) {
    let pq = p.iter().zip(q).zip(r.iter());
    for ((l, h), ((&pj, &qj), &rj)) in lo.iter_mut().zip(hi.iter_mut().rev()).zip(pq) {
        let (pr, qr) = (pj * rj, qj * rj);
        *l = pr + qr;
        *h = sign * (pr - qr);
    }
}

/// y on the half period from C w (`lo`, and `hi` backwards): the parts of C w even and
/// odd in time at θ_j, then the Bezoutian formula (module doc). `even`: C p r odd, C q r
/// even and Σ q r = 0; else C p r even, C q r odd and Σ p r = 0.
#[allow(clippy::too_many_arguments)]
#[multiversion(targets("x86_64+avx+avx2+fma"))]
fn combine_halves(
    r: &mut [f64],
    lo: &[f64],
    hi: &[f64],
    p: &[f64],
    q: &[f64],
    d: &[f64],
    sum: f64,
    scale: f64,
    even: bool,
) {
    let pqd = p.iter().zip(q).zip(d);
    let ab = lo.iter().zip(hi.iter().rev());
    if even {
        for ((rj, (&a, &b)), ((&pj, &qj), &dj)) in r.iter_mut().zip(ab).zip(pqd) {
            let (ev, od) = (0.5 * (a + b), 0.5 * (a - b));
            *rj = scale * (pj * (sum - ev) + qj * od + dj * *rj);
        }
    } else {
        for ((rj, (&a, &b)), ((&pj, &qj), &dj)) in r.iter_mut().zip(ab).zip(pqd) {
            let (ev, od) = (0.5 * (a + b), 0.5 * (a - b));
            *rj = scale * (qj * (sum + ev) - pj * od + dj * *rj);
        }
    }
}

/// −i·e_k·V_k for every k of a half spectrum (C's eigenvalues, `Cot::apply`).
#[multiversion(targets("x86_64+avx+avx2+fma"))]
fn rotate_spectrum(spec: &mut [C], eig: &[f64]) {
    for (s, &e) in spec.iter_mut().zip(eig) {
        // −i·e·(a + ib) = e·b − i·e·a
        *s = C::new(e * s.im, -e * s.re);
    }
}

/// The circulant C on N equally spaced instants, by real FFTs.
struct Cot {
    fwd: Arc<dyn RealToComplex<f64>>,
    inv: Arc<dyn ComplexToReal<f64>>,
    spec: Vec<C>,
    work: Vec<C>,
    /// Its eigenvalues over N on the half spectrum: −i(N − 2k)/N (0 at k = 0 and N/2).
    eig: Vec<f64>,
}

impl Cot {
    fn new(n: usize) -> Cot {
        let (fwd, inv) = fourier::real_fft_plans(n);
        let work = vec![C::new(0.0, 0.0); fwd.get_scratch_len().max(inv.get_scratch_len())];
        let nf = n as f64;
        let eig = (0..=n / 2)
            .map(|k| {
                if k == 0 || 2 * k == n {
                    0.0
                } else {
                    (nf - 2.0 * k as f64) / nf
                }
            })
            .collect();
        Cot {
            fwd,
            inv,
            spec: vec![C::new(0.0, 0.0); n / 2 + 1],
            work,
            eig,
        }
    }

    /// v ← C v, the sum of v returned.
    fn apply(&mut self, v: &mut [f64]) -> f64 {
        if self
            .fwd
            .process_with_scratch(v, &mut self.spec, &mut self.work)
            .is_err()
        {
            // Lengths are the plan's by construction; NaN reaches the callers' checks.
            v.fill(f64::NAN);
            return f64::NAN;
        }
        let sum = self.spec[0].re;
        rotate_spectrum(&mut self.spec, &self.eig);
        if self
            .inv
            .process_with_scratch(&mut self.spec, v, &mut self.work)
            .is_err()
        {
            v.fill(f64::NAN);
        }
        sum
    }
}

/// T⁻¹ for one T, from its generator (module doc).
pub struct ToeplitzInverse {
    h: usize,
    /// 1/(κN).
    scale: f64,
    /// The generator is time-symmetric: solves on the half period.
    symmetric: bool,
    full: Full,
    half: Half,
    /// Series buffers (derivatives of the generator, the two parts of a mixed solve).
    work: Vec<f64>,
    odd: Vec<f64>,
}

impl ToeplitzInverse {
    /// For operators on series of `h` harmonics: N = 2m instants, m the smallest
    /// 5-smooth number above h.
    pub fn new(h: usize) -> ToeplitzInverse {
        let mut m = h + 1;
        while !fourier::is_5_smooth(m) {
            m += 1;
        }
        ToeplitzInverse {
            h,
            scale: 0.0,
            symmetric: false,
            full: Full::new(m),
            half: Half::new(m),
            work: vec![0.0; fourier::len(h)],
            odd: vec![0.0; fourier::len(h)],
        }
    }

    /// Whether the generator is time-symmetric (`solve_even` and `solve_odd` apply).
    #[cfg(test)]
    pub fn is_symmetric(&self) -> bool {
        self.symmetric
    }

    /// Set the generator from ξ_c = T⁻¹(2 cos Hθ) and ξ_s = T⁻¹(2 sin Hθ); false when κ
    /// vanishes or a value is not finite (no representation: the caller takes another
    /// route). `symmetric`: a is even in time and the caller has made ξ_c a cosine series
    /// and ξ_s a sine series (their other parts are not read).
    pub fn set_generator(&mut self, xi_c: &[f64], xi_s: &[f64], symmetric: bool) -> bool {
        let h = self.h;
        let kappa = xi_c[ic(h)] + xi_s[is(h, h)];
        if !(kappa.is_finite() && kappa != 0.0) || xi_c.iter().chain(xi_s).any(|v| !v.is_finite()) {
            return false;
        }
        self.symmetric = symmetric;
        if symmetric {
            let hf = &mut self.half;
            self.scale = 1.0 / (kappa * (2 * hf.m) as f64);
            // p: the cosines of ξ_c; q: the sines of ξ_s; p' = −Σ k c_k sin kθ and
            // q' = Σ k s_k cos kθ (fourier::deriv), into r and c for the moment.
            hf.tr.cos_synth(&xi_c[..=h], &mut hf.p, &mut hf.ws);
            hf.tr.sin_synth(&xi_s[h + 1..], &mut hf.q, &mut hf.ws);
            fourier::deriv(xi_c, h, &mut self.work);
            hf.tr.sin_synth(&self.work[h + 1..], &mut hf.r, &mut hf.ws);
            fourier::deriv(xi_s, h, &mut self.work);
            hf.tr.cos_synth(&self.work[..=h], &mut hf.c, &mut hf.ws);
            for (((d, &p), &q), (&dp, &dq)) in
                hf.d.iter_mut()
                    .zip(&hf.p)
                    .zip(&hf.q)
                    .zip(hf.r.iter().zip(&hf.c))
            {
                *d = 2.0 * (p * dq - dp * q);
            }
        } else {
            let fl = &mut self.full;
            self.scale = 1.0 / (kappa * fl.n as f64);
            let (mut p, mut q) = (std::mem::take(&mut fl.p), std::mem::take(&mut fl.q));
            fl.synth(xi_c, h, &mut p);
            fl.synth(xi_s, h, &mut q);
            let (mut dp, mut dq) = (std::mem::take(&mut fl.u), std::mem::take(&mut fl.v));
            fourier::deriv(xi_c, h, &mut self.work);
            fl.synth(&self.work, h, &mut dp);
            fourier::deriv(xi_s, h, &mut self.work);
            fl.synth(&self.work, h, &mut dq);
            for (((d, &p), &q), (&dp, &dq)) in
                fl.d.iter_mut().zip(&p).zip(&q).zip(dp.iter().zip(&dq))
            {
                *d = 2.0 * (p * dq - dp * q);
            }
            (fl.p, fl.q, fl.u, fl.v) = (p, q, dp, dq);
        }
        true
    }

    /// x ← T⁻¹ x (a real series of H harmonics).
    pub fn solve(&mut self, x: &mut [f64]) {
        let h = self.h;
        if !self.symmetric {
            return self.full.solve(x, h, self.scale);
        }
        let has_odd = (1..=h).any(|k| x[is(h, k)] != 0.0);
        let has_even = x[0] != 0.0 || (1..=h).any(|k| x[ic(k)] != 0.0);
        if has_odd && has_even {
            self.odd.copy_from_slice(x);
            self.half.solve_odd(&mut self.odd, h, self.scale);
            self.half.solve_even(x, h, self.scale);
            for k in 1..=h {
                x[is(h, k)] = self.odd[is(h, k)];
            }
        } else if has_odd {
            self.half.solve_odd(x, h, self.scale);
        } else if has_even {
            self.half.solve_even(x, h, self.scale);
        }
    }

    /// x ← T⁻¹ x_even, x_even the cosine part of x (its sine coefficients dropped), for a
    /// time-symmetric generator (T then maps cosine series to cosine series): for the
    /// solves of a time-symmetric branch, whose right-hand sides are even in exact
    /// arithmetic (contact.rs). Without one, `solve` of x_even.
    pub fn solve_even(&mut self, x: &mut [f64]) {
        let h = self.h;
        if self.symmetric {
            self.half.solve_even(x, h, self.scale);
        } else {
            for k in 1..=h {
                x[is(h, k)] = 0.0;
            }
            self.full.solve(x, h, self.scale);
        }
    }

    /// x ← T⁻¹ x_odd, x_odd the sine part of x, as `solve_even` for the other parity.
    pub fn solve_odd(&mut self, x: &mut [f64]) {
        let h = self.h;
        if self.symmetric {
            self.half.solve_odd(x, h, self.scale);
        } else {
            x[0] = 0.0;
            for k in 1..=h {
                x[ic(k)] = 0.0;
            }
            self.full.solve(x, h, self.scale);
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

    /// x = A⁻¹ b for the dense column-major n × n matrix A (Gauss–Jordan with partial
    /// pivoting: the independent reference).
    fn dense_solve(a: &[f64], n: usize, b: &[f64]) -> Vec<f64> {
        let mut m: Vec<Vec<f64>> = (0..n)
            .map(|i| (0..n).map(|j| a[j * n + i]).collect())
            .collect();
        let mut x = b.to_vec();
        for c in 0..n {
            let p = (c..n)
                .max_by(|&i, &j| m[i][c].abs().total_cmp(&m[j][c].abs()))
                .unwrap();
            m.swap(c, p);
            x.swap(c, p);
            for r in 0..n {
                if r != c {
                    let f = m[r][c] / m[c][c];
                    let row = m[c].clone();
                    for (v, w) in m[r][c..].iter_mut().zip(&row[c..]) {
                        *v -= f * w;
                    }
                    let xc = x[c];
                    x[r] -= f * xc;
                }
            }
        }
        (0..n).map(|i| x[i] / m[i][i]).collect()
    }

    fn max_rel(got: &[f64], want: &[f64]) -> f64 {
        let scale = want.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        got.iter()
            .zip(want)
            .fold(0.0f64, |m, (g, w)| m.max((g - w).abs()))
            / scale
    }

    /// A positive symbol: 3 + small harmonics (sine ones unless `even`).
    fn symbol(h: usize, even: bool, seed: &mut u64) -> Vec<f64> {
        let mut a = vec![0.0; fourier::len(h)];
        a[0] = 3.0;
        for k in 1..=h {
            let s = 0.4 / (1.0 + 0.1 * h as f64).sqrt();
            a[ic(k)] = s * lcg(seed);
            if !even {
                a[is(h, k)] = s * lcg(seed);
            }
        }
        a
    }

    /// The generator's two solutions from the dense operator.
    fn inverse_for(a: &[f64], h: usize, even: bool) -> (ToeplitzInverse, Vec<f64>) {
        let n = fourier::len(h);
        let op = fourier::mul_operator(a, h, h, h);
        let (mut ec, mut es) = (vec![0.0; n], vec![0.0; n]);
        ec[ic(h)] = 2.0;
        es[is(h, h)] = 2.0;
        let mut xi_c = dense_solve(&op, n, &ec);
        let mut xi_s = dense_solve(&op, n, &es);
        if even {
            // The parts a time-symmetric block keeps (contact.rs splits them exactly).
            for k in 1..=h {
                xi_c[is(h, k)] = 0.0;
                xi_s[ic(k)] = 0.0;
            }
            xi_s[0] = 0.0;
        }
        let mut t = ToeplitzInverse::new(h);
        assert!(t.set_generator(&xi_c, &xi_s, even));
        (t, op)
    }

    /// The solves equal dense solves of the truncated-product operator (fourier::
    /// mul_operator) of a positive symbol, to 1e-12 relative: both are direct, the
    /// operator's condition number is below 10, so round-off of either stays below 1e-13.
    /// General symbols on the whole period; even ones on the half period, for cosine, sine
    /// and mixed right-hand sides. Up to H = 200 (sdnd122a's NB_HARM_NONL) and a size whose
    /// m is not a power of two (H = 30: m = 32; H = 7: m = 8; H = 200: m = 216).
    #[test]
    fn solves_equal_dense_solves() {
        let mut seed = 3u64;
        for h in [1usize, 2, 7, 30, 200] {
            let n = fourier::len(h);
            for even in [false, true] {
                let a = symbol(h, even, &mut seed);
                let (mut t, op) = inverse_for(&a, h, even);
                assert_eq!(t.is_symmetric(), even);
                let rhs: Vec<f64> = (0..n).map(|_| lcg(&mut seed)).collect();
                let want = dense_solve(&op, n, &rhs);
                let mut got = rhs.clone();
                t.solve(&mut got);
                let e = max_rel(&got, &want);
                assert!(e <= 1e-12, "h {h} even {even}: {e:e}");
                if even {
                    let mut cos_part = rhs.clone();
                    let mut sin_part = rhs.clone();
                    for k in 1..=h {
                        cos_part[is(h, k)] = 0.0;
                        sin_part[ic(k)] = 0.0;
                    }
                    sin_part[0] = 0.0;
                    let mut got = rhs.clone();
                    t.solve_even(&mut got);
                    let e = max_rel(&got, &dense_solve(&op, n, &cos_part));
                    assert!(e <= 1e-12, "even part h {h}: {e:e}");
                    assert!((1..=h).all(|k| got[is(h, k)] == 0.0));
                    let mut got = rhs.clone();
                    t.solve_odd(&mut got);
                    let e = max_rel(&got, &dense_solve(&op, n, &sin_part));
                    assert!(e <= 1e-12, "odd part h {h}: {e:e}");
                    assert!(got[0] == 0.0 && (1..=h).all(|k| got[ic(k)] == 0.0));
                }
            }
        }
    }

    /// An indefinite T (a symbol that changes sign, as off the physical root of a law):
    /// κ is then of either sign and the formula holds all the same.
    #[test]
    fn an_indefinite_operator_is_inverted_too() {
        let h = 12;
        let n = fourier::len(h);
        let mut a = vec![0.0; n];
        a[0] = 0.3;
        a[ic(1)] = 1.0;
        a[is(h, 2)] = 0.2;
        let (mut t, op) = inverse_for(&a, h, false);
        let mut seed = 5u64;
        let rhs: Vec<f64> = (0..n).map(|_| lcg(&mut seed)).collect();
        let mut got = rhs.clone();
        t.solve(&mut got);
        let e = max_rel(&got, &dense_solve(&op, n, &rhs));
        assert!(e <= 1e-11, "{e:e}");
    }

    /// No representation without a usable generator.
    #[test]
    fn a_vanishing_corner_is_refused() {
        let h = 3;
        let mut t = ToeplitzInverse::new(h);
        let z = vec![0.0; fourier::len(h)];
        assert!(!t.set_generator(&z, &z, false));
        let mut nan = z.clone();
        nan[ic(h)] = f64::NAN;
        assert!(!t.set_generator(&nan, &z, true));
    }
}
