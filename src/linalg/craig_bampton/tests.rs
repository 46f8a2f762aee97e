//! The reduction against exact properties: with every interior mode kept the basis spans
//! the whole space (same frequencies as the full model); with fewer, Rayleigh–Ritz on
//! nested subspaces (frequencies from above, never rising as modes are added); the
//! constraint modes are static equilibria of the interior.

use super::*;
use crate::linalg::eigen::{solve_modes, EigenOptions, Method, ModeRequest};

/// A fixed–fixed chain of `n` masses with uneven masses and springs (no two frequencies
/// equal), both triangles stored, plus a spring from mass 1 to mass `n − 2` so that the
/// matrix is not merely tridiagonal.
fn chain(n: usize) -> (SparseColMat<usize, f64>, SparseColMat<usize, f64>) {
    let mut k = Vec::new();
    let mut m = Vec::new();
    let spring = |i: usize| 1.0 + 0.37 * ((i * 7) % 5) as f64;
    for i in 0..n {
        m.push((i, i, 1.0 + 0.21 * ((i * 3) % 4) as f64));
        k.push((i, i, spring(i) + spring(i + 1)));
        if i + 1 < n {
            k.push((i, i + 1, -spring(i + 1)));
            k.push((i + 1, i, -spring(i + 1)));
        }
    }
    let (a, b, s) = (1, n - 2, 0.5);
    k.extend([(a, a, s), (b, b, s), (a, b, -s), (b, a, -s)]);
    (
        from_triplets(n, n, &k).unwrap(),
        from_triplets(n, n, &m).unwrap(),
    )
}

fn frequencies(k: &SparseColMat<usize, f64>, m: &SparseColMat<usize, f64>) -> Vec<f64> {
    let opts = EigenOptions {
        force: Some(Method::Dense),
        ..EigenOptions::default()
    };
    solve_modes(k, m, &ModeRequest::Smallest { n: k.nrows() }, &opts)
        .unwrap()
        .omega2
}

#[test]
fn every_interior_mode_kept_gives_the_full_models_frequencies() {
    let n = 12;
    let (k, m) = chain(n);
    let red = craig_bampton(&k, &m, &[3, 8], ModeCut::Count(n), usize::MAX).unwrap();
    assert_eq!(red.size(), n);
    let exact = frequencies(&k, &m);
    let got = frequencies(
        &red.project_stiffness(&k).unwrap(),
        &red.project_mass(&m).unwrap(),
    );
    for (e, g) in exact.iter().zip(&got) {
        // Two dense eigensolves of well-conditioned 12×12 pencils: round-off, a few ε·cond.
        assert!((g - e).abs() <= 1e-11 * e, "{g} against {e}");
    }
}

#[test]
fn truncated_bases_approach_from_above_and_never_rise() {
    let n = 40;
    let (k, m) = chain(n);
    let exact = frequencies(&k, &m);
    let mut previous = [f64::INFINITY; 3];
    for count in [0, 2, 5, 10, 20, 38] {
        let red = craig_bampton(&k, &m, &[9, 30], ModeCut::Count(count), usize::MAX).unwrap();
        assert_eq!(red.size(), 2 + count);
        let got = frequencies(
            &red.project_stiffness(&k).unwrap(),
            &red.project_mass(&m).unwrap(),
        );
        for j in 0..3.min(got.len()) {
            // Rayleigh–Ritz: from above; nested subspaces: never higher than with fewer
            // modes. Round-off allowance 1e-12 relative.
            assert!(
                got[j] >= exact[j] * (1.0 - 1e-12),
                "mode {j}: {} < {}",
                got[j],
                exact[j]
            );
            assert!(
                got[j] <= previous[j] * (1.0 + 1e-12),
                "mode {j} rose with {count} modes"
            );
            previous[j] = got[j];
        }
    }
    // All 38 interior modes: the full space again.
    assert!((previous[0] - exact[0]).abs() <= 1e-11 * exact[0]);
}

#[test]
fn constraint_modes_are_static_equilibria_and_modes_vanish_on_the_retained_dofs() {
    let n = 15;
    let (k, m) = chain(n);
    let retained = [2, 11];
    let red = craig_bampton(&k, &m, &retained, ModeCut::UpTo(0.2), usize::MAX).unwrap();
    let ks = SymSparse::from_faer(&k, "K").unwrap();
    let mut f = vec![0.0; n];
    for (c, col) in red.columns.iter().enumerate() {
        ks.mul(col, &mut f);
        for i in 0..n {
            if c < retained.len() {
                // Unit motion of its own DOF, none of the other retained one, and no force
                // on the interior (up to the solve's round-off).
                let own = if i == retained[c] { 1.0 } else { 0.0 };
                if retained.contains(&i) {
                    assert_eq!(col[i], own);
                } else {
                    assert!(f[i].abs() < 1e-13, "force {} at interior DOF {i}", f[i]);
                }
            } else if retained.contains(&i) {
                assert_eq!(col[i], 0.0);
            }
        }
    }
    // The band: every kept mode at or below 0.2 Hz, and the next one above it.
    let f_cut = 0.2;
    assert!(!red.omega2.is_empty() && red.omega2.len() < n - 2);
    assert!(red.omega2.iter().all(|&w| frequency(w) <= f_cut));
    let all = craig_bampton(&k, &m, &retained, ModeCut::Count(n), usize::MAX).unwrap();
    assert!(frequency(all.omega2[red.omega2.len()]) > f_cut);
}

#[test]
fn coordinates_and_expansion_are_inverse_on_the_basis() {
    let n = 20;
    let (k, m) = chain(n);
    let red = craig_bampton(&k, &m, &[4, 15], ModeCut::Count(6), usize::MAX).unwrap();
    let ms = SymSparse::from_faer(&m, "M").unwrap();
    let q: Vec<f64> = (0..red.size()).map(|i| (i as f64 * 0.7).sin()).collect();
    let mut u = vec![0.0; n];
    red.expand_into(&q, &mut u);
    let back = red.coordinates(&ms, &u).unwrap();
    for (a, b) in q.iter().zip(&back) {
        assert!((a - b).abs() < 1e-13, "{a} against {b}");
    }
}

#[test]
fn an_interior_not_held_by_its_supports_is_refused() {
    // Two masses joined by a spring, nothing else: with mass 0 retained, mass 1 floats.
    let k = from_triplets(
        2,
        2,
        &[(0, 0, 1.0), (1, 1, 1.0), (0, 1, -1.0), (1, 0, -1.0)],
    )
    .unwrap();
    let m = from_triplets(2, 2, &[(0, 0, 1.0), (1, 1, 1.0)]).unwrap();
    // mass 1 is held by the spring to mass 0: fine.
    assert!(craig_bampton(&k, &m, &[0], ModeCut::Count(1), usize::MAX).is_ok());
    // Three masses, the third tied to nothing: singular.
    let k3 = from_triplets(
        3,
        3,
        &[(0, 0, 2.0), (1, 1, 1.0), (0, 1, -1.0), (1, 0, -1.0)],
    )
    .unwrap();
    let m3 = from_triplets(3, 3, &[(0, 0, 1.0), (1, 1, 1.0), (2, 2, 1.0)]).unwrap();
    let e = craig_bampton(&k3, &m3, &[0], ModeCut::Count(1), usize::MAX).unwrap_err();
    assert!(e.message.contains("not held"), "{}", e.message);
}

#[test]
fn a_series_expands_entry_by_entry() {
    let n = 10;
    let (k, m) = chain(n);
    let red = craig_bampton(&k, &m, &[2, 7], ModeCut::Count(3), usize::MAX).unwrap();
    let series: Vec<Vec<f64>> = (0..red.size())
        .map(|j| vec![j as f64, 1.0 - j as f64, 0.5 * j as f64])
        .collect();
    let out = red.expand_series(&series);
    for e in 0..3 {
        let q: Vec<f64> = series.iter().map(|s| s[e]).collect();
        let mut u = vec![0.0; n];
        red.expand_into(&q, &mut u);
        for (d, ud) in u.iter().enumerate() {
            assert!((out[d][e] - ud).abs() <= 1e-15 * (1.0 + ud.abs()));
        }
    }
}

/// Every entry of Tᵀ A T (the ones the projection leaves out included), by columns.
fn full_projection(red: &Reduction, a: &SparseColMat<usize, f64>) -> Vec<Vec<f64>> {
    let sym = SymSparse::from_faer(a, "A").unwrap();
    let mut at = vec![0.0; red.n];
    red.columns
        .iter()
        .map(|tj| {
            sym.mul(tj, &mut at);
            red.columns.iter().map(|ti| dot(ti, &at)).collect()
        })
        .collect()
}

/// Largest |stored − full| over every entry, and the largest |full| entry.
fn projection_error(full: &[Vec<f64>], projected: &SparseColMat<usize, f64>) -> (f64, f64) {
    let stored = projected.to_dense();
    let (mut worst, mut scale) = (0.0f64, 0.0f64);
    for (j, col) in full.iter().enumerate() {
        for (i, &v) in col.iter().enumerate() {
            scale = scale.max(v.abs());
            worst = worst.max((v - stored[(i, j)]).abs());
        }
    }
    (worst, scale)
}

#[test]
fn the_blocks_left_out_of_the_projection_are_zero_to_round_off() {
    let n = 30;
    let (k, m) = chain(n);
    let red = craig_bampton(&k, &m, &[6, 21], ModeCut::Count(12), usize::MAX).unwrap();
    for (a, projected) in [
        (&k, red.project_stiffness(&k).unwrap()),
        (&m, red.project_mass(&m).unwrap()),
    ] {
        // Every entry of the whole Tᵀ A T, the ones not stored included.
        let (worst, scale) = projection_error(&full_projection(&red, a), &projected);
        assert!(worst <= 1e-13 * scale, "{worst:e} against {scale:e}");
    }
}

/// A mode that is not exact (here one perturbed by hand, its residual saying so) keeps its
/// couplings with the other modes: the projection stays Tᵀ A T entry for entry.
#[test]
fn an_inexact_mode_keeps_its_couplings() {
    let n = 30;
    let (k, m) = chain(n);
    let mut red = craig_bampton(&k, &m, &[6, 21], ModeCut::Count(8), usize::MAX).unwrap();
    let b = red.retained.len();
    for (i, x) in red.columns[b + 3].iter_mut().enumerate() {
        if !red.retained.contains(&i) {
            *x += 1e-3 * (i as f64).sin();
        }
    }
    red.residuals[3] = 1e-4;
    for (a, projected) in [
        (&k, red.project_stiffness(&k).unwrap()),
        (&m, red.project_mass(&m).unwrap()),
    ] {
        let full = full_projection(&red, a);
        let (worst, scale) = projection_error(&full, &projected);
        assert!(worst <= 1e-13 * scale, "{worst:e} against {scale:e}");
        // The perturbed mode's couplings with the other modes.
        let coupling = (b..red.size())
            .filter(|&j| j != b + 3)
            .map(|j| full[j][b + 3].abs())
            .fold(0.0f64, f64::max);
        // The perturbation made those couplings real, not round-off.
        assert!(coupling > 1e-8 * scale, "{coupling:e}");
    }
}

/// A basis larger than the caller allows is refused before any mode is computed, whether
/// the modes are counted or lie below a cut-off (Sylvester's count).
#[test]
fn a_basis_larger_than_allowed_is_refused() {
    let n = 30;
    let (k, m) = chain(n);
    let e = craig_bampton(&k, &m, &[6, 21], ModeCut::Count(10), 8).unwrap_err();
    assert!(e.message.contains("12 columns"), "{}", e.message);
    let all = craig_bampton(&k, &m, &[6, 21], ModeCut::UpTo(1e6), 20).unwrap_err();
    assert!(all.message.contains("30 columns"), "{}", all.message);
    assert!(craig_bampton(&k, &m, &[6, 21], ModeCut::Count(10), 12).is_ok());
}
