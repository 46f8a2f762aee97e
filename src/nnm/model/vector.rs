//! Dot products and norms of the engine's vectors.
//!
//! A plain `iter().sum()` is one dependent chain of additions (the compiler may not
//! reorder floating-point sums), so it runs at one addition per add latency. Eight
//! independent partial sums, added pairwise at the end, let the compiler use SIMD lanes and
//! keep several additions in flight: about four times faster on the 400–1000-long vectors
//! of GMRES's Gram–Schmidt and the series, and the rounding error bound is that of
//! a sum of n/8 terms instead of n.
//!
//! These loops, and the other hot loops of the engine (the transforms' twiddles, the
//! Toeplitz route's pointwise formulas, the sampled products), are compiled twice: for any
//! x86-64 and for processors with AVX2 and FMA, the version chosen once at run time
//! (`multiversion`). Rust never contracts a product and a sum into one FMA on its own, so
//! both versions round alike: the results are the same to the last bit (measured on every
//! table of sdnd122a), only the speed differs (docs/performance_history.md, seventh round).

use multiversion::multiversion;

/// Σ a_i b_i over the common length.
#[multiversion(targets("x86_64+avx+avx2+fma"))]
pub fn dot(a: &[f64], b: &[f64]) -> f64 {
    let n = a.len().min(b.len());
    let (a, b) = (&a[..n], &b[..n]);
    let mut acc = [0.0f64; 8];
    let (ca, cb) = (a.chunks_exact(8), b.chunks_exact(8));
    let (ra, rb) = (ca.remainder(), cb.remainder());
    for (x, y) in ca.zip(cb) {
        for ((s, p), q) in acc.iter_mut().zip(x).zip(y) {
            *s += p * q;
        }
    }
    let tail: f64 = ra.iter().zip(rb).map(|(x, y)| x * y).sum();
    let quads = [
        acc[0] + acc[4],
        acc[1] + acc[5],
        acc[2] + acc[6],
        acc[3] + acc[7],
    ];
    (quads[0] + quads[2]) + (quads[1] + quads[3]) + tail
}

/// Σ a_i b_i summed in order, one addition after the other: the series' own products
/// (anm.rs, linear_solver.rs), whose rounding the branch ends inherit. A sensitive run
/// (hard/grazing_jump.comm without its jump checks) takes another way at grazing when
/// these sums are reassociated, so they keep their order.
pub fn dot_in_order(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

/// y ← y − c·x over the common length (GMRES's Gram–Schmidt, the expansion δF = q − W δu).
#[multiversion(targets("x86_64+avx+avx2+fma"))]
pub fn sub_scaled(y: &mut [f64], c: f64, x: &[f64]) {
    for (yi, xi) in y.iter_mut().zip(x) {
        *yi -= c * xi;
    }
}

/// y ← y + c·x over the common length.
#[multiversion(targets("x86_64+avx+avx2+fma"))]
pub fn add_scaled(y: &mut [f64], c: f64, x: &[f64]) {
    for (yi, xi) in y.iter_mut().zip(x) {
        *yi += c * xi;
    }
}

/// y ← c·x over the common length.
#[multiversion(targets("x86_64+avx+avx2+fma"))]
pub fn scaled(y: &mut [f64], c: f64, x: &[f64]) {
    for (yi, xi) in y.iter_mut().zip(x) {
        *yi = c * xi;
    }
}

/// Euclidean norm.
pub fn norm(a: &[f64]) -> f64 {
    dot(a, a).sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Integers (exact in f64) for every length around the chunk size: the blocked sum
    /// equals the exact one whatever the remainder.
    #[test]
    fn dot_equals_the_exact_sum_at_every_remainder() {
        for n in 0..40 {
            let a: Vec<f64> = (0..n).map(|i| (i % 7) as f64 - 3.0).collect();
            let b: Vec<f64> = (0..n).map(|i| (i % 5) as f64 + 1.0).collect();
            let exact: i64 = (0..n)
                .map(|i| ((i % 7) as i64 - 3) * ((i % 5) as i64 + 1))
                .sum();
            assert_eq!(dot(&a, &b), exact as f64, "n = {n}");
        }
        assert_eq!(norm(&[3.0, 4.0]), 5.0);
        // Unequal lengths: the common prefix.
        assert_eq!(dot(&[1.0, 2.0, 3.0], &[1.0, 1.0]), 3.0);
    }
}
