//! What a call will cost, from its sizes alone, before anything is allocated: operators
//! compare these estimates with the machine's memory and refuse (or warn about) a call
//! that cannot fit or would take very long. The figures are models, not measurements:
//! they aim at the right order of magnitude, and at never being absurdly low, so that a
//! size keyword with a huge value (NB_HARM_NONL=100000, NB_INST=1e9) is caught at once
//! instead of aborting the process after minutes of allocation.
//!
//! Everything is computed in `f64`: absurd inputs give huge (or infinite) estimates,
//! never an integer overflow.

const BYTES_PER_REAL: f64 = 8.0;
/// A sparse entry: its value and a row index (column pointers are negligible).
const BYTES_PER_ENTRY: f64 = 16.0;

/// The sizes of one MODE_NON_LINE call.
#[derive(Clone, Copy, Debug)]
pub struct MnlSizes {
    /// Free DOFs of the reduced problem.
    pub n_dofs: usize,
    /// Stored entries of K and M together (their union pattern, or the sum: an upper bound).
    pub nnz: usize,
    pub h_lin: usize,
    pub h_nonl: usize,
    /// Contact unknowns summed over the shocks, per Fourier coefficient (PLAN 1, BI_PLAN 2,
    /// CERCLE 4 in today's engine).
    pub shock_unknowns: usize,
    /// NB_ORDRE_MAN.
    pub order: usize,
    /// Points kept in memory before they are stored: NB_BRANCHE × NB_PAS_MAN.
    pub stored_points: f64,
}

/// Unknowns of the harmonic-balance system: displacements and velocities on `2·h_lin+1`
/// coefficients per DOF, the contact unknowns on `2·h_nonl+1` coefficients, ω and γ.
pub fn mnl_unknowns(s: &MnlSizes) -> f64 {
    let nl = 2.0 * s.h_lin as f64 + 1.0;
    let nn = 2.0 * s.h_nonl as f64 + 1.0;
    2.0 * s.n_dofs as f64 * nl + s.shock_unknowns as f64 * nn + 2.0
}

/// Peak memory of MODE_NON_LINE, in bytes.
///
/// Model: the series (`order + 1` vectors of the unknowns) plus a few work vectors; the
/// bordered tangent, whose structural part holds K and M once per harmonic
/// (`2·nl·(nnz + n)` entries), whose contact part couples every coefficient of a shock's
/// unknowns with every other (the laws are evaluated in time: a dense block of
/// `(shock_unknowns·nn)²` entries, plus the coupling with the displacement coefficients),
/// and two dense border rows and columns; its sparse LU factors, taken as five times the
/// tangent (fill-in on the dense contact blocks); the time samples of the contact laws
/// (four per coefficient); and the points computed before they are stored.
pub fn memory_estimate(s: &MnlSizes) -> f64 {
    let n = s.n_dofs as f64;
    let nl = 2.0 * s.h_lin as f64 + 1.0;
    let nn = 2.0 * s.h_nonl as f64 + 1.0;
    let unknowns = mnl_unknowns(s);
    let contact = s.shock_unknowns as f64 * nn;
    let tangent =
        2.0 * nl * (s.nnz as f64 + n) + contact * contact + 2.0 * contact * nl + 4.0 * unknowns;
    let vectors = (s.order as f64 + 6.0) * unknowns;
    let samples = 4.0 * nn * (s.shock_unknowns as f64 + 1.0) * 4.0;
    let points = s.stored_points * unknowns;
    BYTES_PER_ENTRY * 6.0 * tangent + BYTES_PER_REAL * (vectors + samples + points)
}

/// Floating-point operations of one series branch of MODE_NON_LINE (one factorisation of
/// the tangent, dominated by the dense contact block, and `order` right-hand sides).
pub fn mnl_branch_flops(s: &MnlSizes) -> f64 {
    let nn = 2.0 * s.h_nonl as f64 + 1.0;
    let contact = s.shock_unknowns as f64 * nn;
    let nl = 2.0 * s.h_lin as f64 + 1.0;
    let structural = 2.0 * nl * (s.nnz as f64 + s.n_dofs as f64);
    contact.powi(3) + 10.0 * structural + s.order as f64 * (structural + contact * contact)
}

/// Peak memory of a time history of `n_inst` instants on `n_dofs` DOFs (REST_MODE_NONL,
/// DYNA_TRANS): displacements, velocities and accelerations kept for every instant, in
/// memory and once more as table rows before they are stored.
pub fn time_history_bytes(n_dofs: usize, n_inst: usize) -> f64 {
    2.0 * 3.0 * BYTES_PER_REAL * n_dofs as f64 * n_inst as f64
}

/// Floating-point operations of a Floquet analysis (CALC_STABILITE): `n_inst` steps of a
/// dense integration of the `2n × 2n` monodromy matrix.
pub fn floquet_flops(n_dofs: usize, n_inst: usize) -> f64 {
    let m = 2.0 * n_dofs as f64;
    n_inst as f64 * 4.0 * m * m * m
}

/// Memory of a Floquet analysis: a handful of dense `2n × 2n` matrices.
pub fn floquet_bytes(n_dofs: usize) -> f64 {
    let m = 2.0 * n_dofs as f64;
    8.0 * BYTES_PER_REAL * m * m
}

#[cfg(test)]
mod tests {
    use super::*;

    fn wall(h_nonl: usize) -> MnlSizes {
        MnlSizes {
            n_dofs: 1,
            nnz: 2,
            h_lin: 5,
            h_nonl,
            shock_unknowns: 1,
            order: 20,
            stored_points: 105.0,
        }
    }

    #[test]
    fn unknowns_follow_the_layout() {
        // 2·1·11 displacement and velocity coefficients, 401 contact coefficients, ω, γ.
        assert_eq!(mnl_unknowns(&wall(200)), 22.0 + 401.0 + 2.0);
    }

    #[test]
    fn the_dense_contact_block_dominates_for_many_harmonics() {
        // NB_HARM_NONL = 100000: (2·10⁵+1)² entries of 16 bytes, factored: > 100 GB.
        let big = memory_estimate(&wall(100_000));
        assert!(big > 1.0e11, "{big}");
        // The documented case (NB_HARM_NONL = 200) fits in a few MB.
        let small = memory_estimate(&wall(200));
        assert!(small < 5.0e7, "{small}");
        assert!(small > 1.0e5, "{small}");
    }

    #[test]
    fn absurd_sizes_give_huge_estimates_not_overflows() {
        let s = MnlSizes {
            h_lin: usize::MAX,
            h_nonl: usize::MAX,
            ..wall(0)
        };
        assert!(memory_estimate(&s) > 1.0e30);
        assert!(time_history_bytes(10, 1_000_000_000) > 1.0e11);
        assert!(floquet_flops(2, 1_000_000_000) > 1.0e11);
    }
}
