//! Model matrices for eigen benchmarks and the timing example (shared via `#[path]`).

use faer::sparse::{SparseColMat, Triplet};

pub type Pair = (SparseColMat<usize, f64>, SparseColMat<usize, f64>);

fn sym(n: usize, lower: &[(usize, usize, f64)]) -> SparseColMat<usize, f64> {
    let mut t = Vec::with_capacity(2 * lower.len());
    for &(i, j, v) in lower {
        t.push(Triplet::new(i, j, v));
        if i != j {
            t.push(Triplet::new(j, i, v));
        }
    }
    SparseColMat::try_new_from_triplets(n, n, &t).expect("valid triplets")
}

/// Fixed-fixed chain of n unit masses and unit springs.
pub fn spring_chain(n: usize) -> Pair {
    let mut kt = Vec::new();
    let mut mt = Vec::new();
    for i in 0..n {
        kt.push((i, i, 2.0));
        mt.push((i, i, 1.0));
        if i + 1 < n {
            kt.push((i + 1, i, -1.0));
        }
    }
    (sym(n, &kt), sym(n, &mt))
}

/// Simply supported Euler–Bernoulli beam (length 1, EI = 1, ρA = 1) with `ne` Hermite
/// elements and consistent mass: 2·ne DOFs (w, θ per node, w blocked at both ends).
/// Exact frequencies ω_j = (jπ)².
pub fn beam(ne: usize) -> Pair {
    let h = 1.0 / ne as f64;
    let ke = [
        [12.0, 6.0 * h, -12.0, 6.0 * h],
        [6.0 * h, 4.0 * h * h, -6.0 * h, 2.0 * h * h],
        [-12.0, -6.0 * h, 12.0, -6.0 * h],
        [6.0 * h, 2.0 * h * h, -6.0 * h, 4.0 * h * h],
    ];
    let me = [
        [156.0, 22.0 * h, 54.0, -13.0 * h],
        [22.0 * h, 4.0 * h * h, 13.0 * h, -3.0 * h * h],
        [54.0, 13.0 * h, 156.0, -22.0 * h],
        [-13.0 * h, -3.0 * h * h, -22.0 * h, 4.0 * h * h],
    ];
    let (kf, mf) = (1.0 / (h * h * h), h / 420.0);
    // Global DOF 2i = w_i, 2i+1 = θ_i; free numbering skips w_0 and w_ne.
    let nglob = 2 * (ne + 1);
    let free = |g: usize| -> Option<usize> {
        if g == 0 || g == 2 * ne {
            None
        } else if g < 2 * ne {
            Some(g - 1)
        } else {
            Some(g - 2)
        }
    };
    let n = nglob - 2;
    let mut kt = Vec::new();
    let mut mt = Vec::new();
    for e in 0..ne {
        let dofs = [2 * e, 2 * e + 1, 2 * e + 2, 2 * e + 3];
        for a in 0..4 {
            for b in 0..=a {
                if let (Some(i), Some(j)) = (free(dofs[a]), free(dofs[b])) {
                    let (i, j) = if i >= j { (i, j) } else { (j, i) };
                    kt.push((i, j, kf * ke[a][b]));
                    mt.push((i, j, mf * me[a][b]));
                }
            }
        }
    }
    (sym(n, &kt), sym(n, &mt))
}
