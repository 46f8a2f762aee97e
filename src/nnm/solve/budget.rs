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

/// The sizes of one shock: its own unknowns per Fourier coefficient (PLAN 1, BI_PLAN 2,
/// CERCLE 4 in today's engine) and the displacement components it acts on.
#[derive(Clone, Copy, Debug)]
pub struct ShockSizes {
    pub unknowns: usize,
    pub components: usize,
}

/// The sizes of one MODE_NON_LINE call.
#[derive(Clone, Debug)]
pub struct MnlSizes {
    /// Free DOFs of the reduced problem.
    pub n_dofs: usize,
    /// Stored entries of K and M together (their union pattern, or the sum: an upper bound).
    pub nnz: usize,
    pub h_lin: usize,
    pub h_nonl: usize,
    pub shocks: Vec<ShockSizes>,
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
    let own: f64 = s.shocks.iter().map(|c| c.unknowns as f64).sum();
    2.0 * s.n_dofs as f64 * nl + own * nn + 2.0
}

/// Fill of the condensed tangent's sparse LU factors relative to its entries, with a margin:
/// on the bench's bar (10⁴ and 10⁵ DOFs, H_l 5) the engine measured about 2.5 kB per
/// nonzero of K ∪ M (docs/performance.md), where this model (K and M counted separately)
/// gives about 2.5 times as much; meshes with wider fronts than a bar fill more.
const LU_FILL: f64 = 8.0;

/// Entries of the condensed tangent that the sparse LU factorises (linear_solver.rs,
/// condensed_tangent.rs): per harmonic the pattern of K ∪ M on cos and sin coupled (four blocks;
/// one for the mean), the dense Ω and γ columns, and per shock its Schur block
/// (components·(2H_l+1))².
fn reduced_entries(s: &MnlSizes) -> f64 {
    let n = s.n_dofs as f64;
    let nl = 2.0 * s.h_lin as f64 + 1.0;
    let schur: f64 = s
        .shocks
        .iter()
        .map(|c| (c.components as f64 * nl).powi(2))
        .sum();
    (2.0 * nl - 1.0) * (s.nnz as f64 + n) + 3.0 * n * nl + schur
}

/// Peak memory of MODE_NON_LINE, in bytes.
///
/// Model of the structured solver (docs/nnm.md): the condensed tangent over U, Ω and γ and
/// its sparse LU factors (`LU_FILL` times its entries, 16 bytes each: value and index);
/// per shock its contact block (`contact::block_reals`: Krylov workspace, the coupling W,
/// the time samples of the law, and the dense block where the dense route may be taken);
/// K and M as triplets; the series (`order + 1` vectors of the unknowns) plus work
/// vectors; and the points computed before they are stored (scaled and physical).
pub fn memory_estimate(s: &MnlSizes) -> f64 {
    let nl = 2.0 * s.h_lin as f64 + 1.0;
    let nn = 2.0 * s.h_nonl as f64 + 1.0;
    let unknowns = mnl_unknowns(s);
    let reduced = (LU_FILL + 1.0) * reduced_entries(s);
    let contact: f64 = s
        .shocks
        .iter()
        .map(|c| {
            crate::nnm::solve::contact::block_reals(c.unknowns as f64, c.components as f64, nn, nl)
        })
        .sum();
    let matrices = 3.0 * s.nnz as f64;
    let vectors = (s.order as f64 + 12.0) * unknowns;
    let points = 2.0 * s.stored_points * unknowns;
    BYTES_PER_ENTRY * reduced + BYTES_PER_REAL * (contact + matrices + vectors + points)
}

/// Floating-point operations of one series branch of MODE_NON_LINE: one factorisation of
/// the condensed tangent (taken as `LU_FILL` times its entries squared over its dimension,
/// the work of a banded elimination) and per shock the W columns and `order` solves of
/// its contact block (dense or Krylov, whichever the cost model of contact.rs picks), and
/// `order` right-hand sides through the factors.
pub fn mnl_branch_flops(s: &MnlSizes) -> f64 {
    let nl = 2.0 * s.h_lin as f64 + 1.0;
    let dim = s.n_dofs as f64 * nl + 2.0;
    let entries = LU_FILL * reduced_entries(s);
    let factor = entries * entries / dim;
    let order = s.order as f64;
    let contact: f64 = s
        .shocks
        .iter()
        .map(|c| {
            let solves = c.components as f64 * nl + order;
            crate::nnm::solve::contact::solve_flops(
                c.unknowns as f64,
                2.0 * s.h_nonl as f64 + 1.0,
                solves,
            )
        })
        .sum();
    factor + order * 4.0 * entries + contact
}

/// Memory of one row of an in-memory table before it is stored: the row's vector (header
/// and allocation overhead), its cells (24 bytes each) and the texts of its `texts` text
/// cells (a node or component name: one smallest allocation each, 32 bytes).
fn table_row_bytes(cells: usize, texts: usize) -> f64 {
    24.0 + 16.0 + 24.0 * cells as f64 + 32.0 * texts as f64
}

/// Peak memory of a time history of `n_inst` instants on `n_dofs` DOFs with
/// `n_force_components` contact-force components (REST_MODE_NONL): per instant and DOF the
/// displacement, velocity and acceleration and one table row of 7 cells (2 texts), per
/// instant and force component the force and one row of 6 cells (2 texts), the rows'
/// vectors growing by doubling (up to twice their length). For sdnd122a (one DOF, one
/// force component) this gives 600 bytes per instant; measured: 547 (peak resident memory
/// 70.9 MB at NB_INST = 10⁵ against 16.3 MB at 256, docs/store.md "Sizes").
pub fn time_history_bytes(n_dofs: usize, n_force_components: usize, n_inst: usize) -> f64 {
    let per_dof = 3.0 * BYTES_PER_REAL + table_row_bytes(7, 2) + 24.0;
    let per_force = BYTES_PER_REAL + table_row_bytes(6, 2) + 24.0;
    n_inst as f64 * (n_dofs as f64 * per_dof + n_force_components as f64 * per_force)
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
            shocks: vec![ShockSizes {
                unknowns: 1,
                components: 1,
            }],
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
    fn sizes_that_cannot_fit_give_estimates_beyond_any_machine() {
        // The structured solver holds no (2H_nl+1)² block beyond DENSE_MAX_DIM: memory
        // grows like H_nl × (NB_BRANCHE·NB_PAS_MAN + NB_ORDRE_MAN). NB_HARM_NONL = 10⁸:
        // 2·10⁸ contact coefficients × (2·105 stored + 32 work vectors) × 8 bytes, plus
        // the Krylov basis (44 vectors): > 400 GB.
        let big = memory_estimate(&wall(100_000_000));
        assert!(big > 4.0e11, "{big}");
        // NB_HARM_NONL = 100000: about 0.5 GB, which a workstation has.
        let mid = memory_estimate(&wall(100_000));
        assert!(mid > 2.0e8 && mid < 2.0e9, "{mid}");
        // The documented case (NB_HARM_NONL = 200): the dense block (401², 1.3 MB) counts.
        let small = memory_estimate(&wall(200));
        assert!(small < 5.0e7, "{small}");
        assert!(small > 401.0 * 401.0 * 8.0, "{small}");
    }

    #[test]
    fn a_large_beam_fits_a_workstation() {
        // 10⁴ DOFs, about 12 entries of K ∪ M per row, H_l 5, H_nl 200, two CERCLE
        // rings: the condensed tangent (11·10⁴ unknowns) dominates, well under 10 GB.
        let s = MnlSizes {
            n_dofs: 10_000,
            nnz: 240_000,
            h_lin: 5,
            h_nonl: 200,
            shocks: vec![
                ShockSizes {
                    unknowns: 4,
                    components: 2
                };
                2
            ],
            order: 20,
            stored_points: 50.0,
        };
        let b = memory_estimate(&s);
        assert!(b > 1.0e8 && b < 1.0e10, "{b}");
    }

    #[test]
    fn absurd_sizes_give_huge_estimates_not_overflows() {
        let s = MnlSizes {
            h_lin: usize::MAX,
            h_nonl: usize::MAX,
            ..wall(0)
        };
        assert!(memory_estimate(&s) > 1.0e30);
        assert!(time_history_bytes(10, 1, 1_000_000_000) > 1.0e11);
        assert!(floquet_flops(2, 1_000_000_000) > 1.0e11);
    }
}
