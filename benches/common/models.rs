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

/// Membrane: nx × ny grid of unit masses, unit springs to the 4 neighbours, fixed edges
/// (the 5-point Laplacian: a banded matrix of bandwidth nx with fill-in when factorised).
/// Exact ω² = 4 sin²(iπ/(2(nx+1))) + 4 sin²(jπ/(2(ny+1))).
pub fn membrane(nx: usize, ny: usize) -> Pair {
    let n = nx * ny;
    let mut kt = Vec::new();
    let mut mt = Vec::new();
    for y in 0..ny {
        for x in 0..nx {
            let i = y * nx + x;
            kt.push((i, i, 4.0));
            mt.push((i, i, 1.0));
            if x + 1 < nx {
                kt.push((i + 1, i, -1.0));
            }
            if y + 1 < ny {
                kt.push((i + nx, i, -1.0));
            }
        }
    }
    (sym(n, &kt), sym(n, &mt))
}

/// The `count` lowest exact ω of [`membrane`].
pub fn membrane_omegas(nx: usize, ny: usize, count: usize) -> Vec<f64> {
    let s = |i: usize, n: usize| (i as f64 * std::f64::consts::PI / (2.0 * (n as f64 + 1.0))).sin();
    let mut w2: Vec<f64> = Vec::new();
    for i in 1..=count.min(nx) {
        for j in 1..=count.min(ny) {
            w2.push(4.0 * s(i, nx).powi(2) + 4.0 * s(j, ny).powi(2));
        }
    }
    w2.sort_by(f64::total_cmp);
    w2.into_iter().take(count).map(f64::sqrt).collect()
}
