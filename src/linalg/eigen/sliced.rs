//! Spectrum slicing: the lowest `n` modes of K φ = ω² M φ for a large `n`, one interval
//! of ω² at a time.
//!
//! The first slice is the lowest [`SLICE_MODES`] + 1 modes from one shift, as for a
//! few modes (rigid-body modes included); its top boundary is put in the middle of the
//! gap between its last two modes, and the highest one dropped. Each further slice is an
//! interval (lo, hi] of ω² whose mode count Sylvester's inertia gives (one LDLᵀ of
//! K − hi·M), hi chosen from the previous slice's density so that it holds about
//! [`SLICE_MODES`]; its modes are the band of that interval, from a shift at its centre
//! (the modes nearest that shift are exactly the interval's). Slices are M-orthogonal to
//! each other because their eigenvalues differ; nothing is orthogonalised across them,
//! which is what makes slicing O(n·nev·slice) instead of O(n·nev²).
//!
//! Every slice is checked by its Sylvester count (the band solver's own check), so the
//! union is the complete set of modes below the last boundary; the `n` lowest are kept.

use super::sym::SymSparse;
use super::SLICE_MODES;
use super::{count_below, frequency, one_shift_modes, EigenOptions, ModeRequest, ModeSet, Shared};
use crate::error::{Error, Result};

/// Tries at placing one boundary before taking what it gives.
const BOUNDARY_TRIES: usize = 8;

/// The `n` lowest modes, slice by slice.
pub(crate) fn smallest(
    shared: &mut Shared,
    k: &SymSparse,
    m: &SymSparse,
    n: usize,
    opts: &EigenOptions,
    scale: f64,
) -> Result<ModeSet> {
    let first = one_shift_modes(
        shared,
        k,
        m,
        &ModeRequest::Smallest { n: SLICE_MODES + 1 },
        opts,
        scale,
        None,
    )?;
    let mut omega2 = first.omega2;
    let mut vectors = first.vectors;
    let (Some(top), Some(below)) = (omega2.pop(), omega2.last().copied()) else {
        return Err(Error::internal(
            "the first slice returned fewer modes than asked",
        ));
    };
    vectors.pop();
    let mut lo = 0.5 * (below + top);
    let mut count_lo = count_below(shared, k, m, lo, scale, opts.factor)?;
    if count_lo != omega2.len() {
        return Err(Error::numerical(format!(
            "the first {} modes do not match Sylvester's count below their top ({count_lo})",
            omega2.len()
        ))
        .hint("multiple or very close frequencies: ask for fewer modes or a band"));
    }
    // The previous slice's width and count, for the density of the next one.
    let mut width = (lo - omega2.first().copied().unwrap_or(0.0)).max(f64::MIN_POSITIVE);
    let mut held = count_lo.max(1);
    let mut slices = 1;
    let mut solves = String::new();
    let counter = Counter { k, m, opts, scale };
    while omega2.len() < n {
        let want = SLICE_MODES.min(n - omega2.len());
        let (hi, count_hi) =
            counter.next_boundary(shared, lo, count_lo, width / held as f64, want)?;
        let band = ModeRequest::Band {
            f_min: frequency(lo),
            f_max: frequency(hi),
        };
        // The band's counts are the boundaries' own: no factorisation to count them again.
        let counts = Some((count_lo, count_hi));
        let slice = one_shift_modes(shared, k, m, &band, opts, scale, counts)?;
        if slice.omega2.len() != count_hi - count_lo {
            return Err(Error::numerical(format!(
                "the slice ({:e}, {:e}] Hz holds {} modes (Sylvester count) but {} were found",
                frequency(lo),
                frequency(hi),
                count_hi - count_lo,
                slice.omega2.len()
            ))
            .hint("multiple or very close frequencies: ask for fewer modes or a band"));
        }
        omega2.extend(slice.omega2);
        vectors.extend(slice.vectors);
        width = hi - lo;
        held = (count_hi - count_lo).max(1);
        lo = hi;
        count_lo = count_hi;
        slices += 1;
        solves = slice.method;
    }
    omega2.truncate(n);
    vectors.truncate(n);
    Ok(ModeSet {
        omega2,
        vectors,
        residuals: vec![],
        method: format!(
            "spectrum slicing, {slices} slices of about {SLICE_MODES} modes (first: {}; last: \
             {solves})",
            first.method
        ),
    })
}

/// Sylvester counts of one problem.
struct Counter<'a> {
    k: &'a SymSparse,
    m: &'a SymSparse,
    opts: &'a EigenOptions,
    scale: f64,
}

impl Counter<'_> {
    /// The next slice's top boundary hi > lo and the count of modes below it: about `want`
    /// modes in (lo, hi], at most twice that, guessed from the previous slice's ω² width
    /// per mode and corrected by Sylvester's count.
    fn next_boundary(
        &self,
        shared: &mut Shared,
        lo: f64,
        count_lo: usize,
        width_per_mode: f64,
        want: usize,
    ) -> Result<(f64, usize)> {
        let want = want.max(1);
        let mut step = width_per_mode * want as f64;
        let mut best: Option<(f64, usize)> = None;
        for _ in 0..BOUNDARY_TRIES {
            let hi = lo + step;
            let count = count_below(shared, self.k, self.m, hi, self.scale, self.opts.factor)?;
            let inside = count.saturating_sub(count_lo);
            if inside > 0 {
                best = Some((hi, count));
            }
            if (want..=2 * want).contains(&inside) {
                return Ok((hi, count));
            }
            step *= if inside == 0 {
                2.0
            } else {
                // Proportional, damped so that a dense cluster does not overshoot back to 0.
                (want as f64 / inside as f64).clamp(0.25, 4.0)
            };
        }
        best.ok_or_else(|| {
            Error::numerical(format!(
                "no mode found above {:e} Hz while slicing the spectrum",
                frequency(lo)
            ))
            .hint("ask for fewer modes: the model may have fewer finite frequencies")
        })
    }
}
