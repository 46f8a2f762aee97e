//! Two branches compared at common energies: runs that land their rows at different
//! ENERGIE (a reduced run against the full one) are compared by local cubic interpolation
//! of the reference's FREQUENCE in log ENERGIE, with the interpolation's own error measured
//! on the reference (every other row from the others).

/// (ENERGIE, value) rows, ENERGIE increasing.
pub type Curve = [(f64, f64)];

/// The cubic through the four rows of `c` nearest to `e`, in log ENERGIE (`c` has at least
/// four rows).
pub fn interpolate(c: &Curve, e: f64) -> f64 {
    let x = e.ln();
    let i = c.partition_point(|p| p.0.ln() < x);
    let i = i.saturating_sub(2).min(c.len().saturating_sub(4));
    let pts = &c[i..(i + 4).min(c.len())];
    pts.iter()
        .enumerate()
        .map(|(a, pa)| {
            let w: f64 = pts
                .iter()
                .enumerate()
                .filter(|(b, _)| *b != a)
                .map(|(_, pb)| (x - pb.0.ln()) / (pa.0.ln() - pb.0.ln()))
                .product();
            w * pa.1
        })
        .sum()
}

/// Largest |value − reference(E)| / scale(value) over the rows of `other` strictly inside
/// `reference`'s energies, one row in from each end (so that every cubic is centred), and
/// how many rows were compared. None when `reference` has fewer than four rows or is not
/// increasing in ENERGIE.
pub fn worst_difference(
    reference: &Curve,
    other: &Curve,
    scale: impl Fn(f64) -> f64,
) -> Option<(f64, usize)> {
    if reference.len() < 4 || reference.windows(2).any(|w| w[1].0 <= w[0].0) {
        return None;
    }
    let (lo, hi) = (reference[1].0, reference[reference.len() - 2].0);
    let d: Vec<f64> = other
        .iter()
        .filter(|p| p.0 > lo && p.0 < hi)
        .map(|p| (p.1 - interpolate(reference, p.0)).abs() / scale(p.1))
        .collect();
    Some((d.iter().copied().fold(0.0, f64::max), d.len()))
}

/// What interpolating `c` errs, measured: its odd rows from its even ones, relative. At
/// the full spacing a cubic errs about 1/16 of this.
pub fn interpolation_error(c: &Curve) -> Option<f64> {
    let even: Vec<(f64, f64)> = c.iter().step_by(2).copied().collect();
    let odd: Vec<(f64, f64)> = c.iter().skip(1).step_by(2).copied().collect();
    worst_difference(&even, &odd, f64::abs).map(|(w, _)| w)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A cubic in log E is interpolated exactly; a smooth curve's error falls as the
    /// fourth power of the spacing.
    #[test]
    fn cubics_are_exact_and_the_error_falls_with_the_spacing() {
        let cubic = |x: f64| 1.0 + 0.3 * x - 0.02 * x * x + 0.001 * x * x * x;
        let c: Vec<(f64, f64)> = (0..20)
            .map(|i| {
                let x = i as f64 * 0.3;
                (x.exp(), cubic(x))
            })
            .collect();
        let e = (1.37f64).exp();
        assert!((interpolate(&c, e) - cubic(1.37)).abs() < 1e-13);
        let curve = |step: f64| -> Vec<(f64, f64)> {
            (0..(6.0 / step) as usize)
                .map(|i| {
                    let x = i as f64 * step;
                    (x.exp(), 50.0 + x.sin())
                })
                .collect()
        };
        let coarse = interpolation_error(&curve(0.2)).unwrap();
        let fine = interpolation_error(&curve(0.1)).unwrap();
        assert!(fine < coarse / 10.0, "{coarse:e} {fine:e}");
        // A curve that is not increasing in ENERGIE is no reference.
        let mut bad = curve(0.2);
        bad.swap(3, 4);
        assert!(worst_difference(&bad, &bad, f64::abs).is_none());
    }
}
