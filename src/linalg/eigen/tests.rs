//! Eigen solver tests against closed forms (spring–mass chains).

use super::*;
use faer::sparse::Triplet;

fn faer_sym(n: usize, lower: &[(usize, usize, f64)]) -> SparseColMat<usize, f64> {
    // Both triangles stored, as assembly produces them.
    let mut t = Vec::new();
    for &(i, j, v) in lower {
        t.push(Triplet::new(i, j, v));
        if i != j {
            t.push(Triplet::new(j, i, v));
        }
    }
    SparseColMat::try_new_from_triplets(n, n, &t).unwrap()
}

/// N masses `mass` linked by springs `k`; `fixed` = both ends tied to walls, else free-free.
fn chain(
    n: usize,
    k: f64,
    mass: f64,
    fixed: bool,
) -> (SparseColMat<usize, f64>, SparseColMat<usize, f64>) {
    let mut kt = Vec::new();
    let mut mt = Vec::new();
    for i in 0..n {
        let ends = if fixed {
            2.0
        } else {
            (i > 0) as u8 as f64 + (i + 1 < n) as u8 as f64
        };
        kt.push((i, i, ends * k));
        mt.push((i, i, mass));
        if i + 1 < n {
            kt.push((i + 1, i, -k));
        }
    }
    (faer_sym(n, &kt), faer_sym(n, &mt))
}

/// Two identical, uncoupled fixed-fixed chains of `n1` masses: every frequency is double.
fn twin_chains(
    n1: usize,
    k: f64,
    mass: f64,
) -> (SparseColMat<usize, f64>, SparseColMat<usize, f64>) {
    let mut kt = Vec::new();
    let mut mt = Vec::new();
    for c in 0..2 {
        let o = c * n1;
        for i in 0..n1 {
            kt.push((o + i, o + i, 2.0 * k));
            mt.push((o + i, o + i, mass));
            if i + 1 < n1 {
                kt.push((o + i + 1, o + i, -k));
            }
        }
    }
    (faer_sym(2 * n1, &kt), faer_sym(2 * n1, &mt))
}

/// Fixed-fixed: ω_j = 2√(k/m) sin(jπ/(2(N+1))), j = 1..N.
fn fixed_omega(j: usize, n: usize, k: f64, m: f64) -> f64 {
    2.0 * (k / m).sqrt() * (j as f64 * PI / (2.0 * (n as f64 + 1.0))).sin()
}

/// Free-free: ω_j = 2√(k/m) sin(jπ/(2N)), j = 0..N-1 (j = 0: rigid-body mode).
fn free_omega(j: usize, n: usize, k: f64, m: f64) -> f64 {
    2.0 * (k / m).sqrt() * (j as f64 * PI / (2.0 * n as f64)).sin()
}

fn opts(method: Method) -> EigenOptions {
    EigenOptions {
        force: Some(method),
        ..Default::default()
    }
}

/// Largest |φᵢᵀMφⱼ − δᵢⱼ|.
fn orthonormality_error(set: &ModeSet, m: &SparseColMat<usize, f64>) -> f64 {
    let ms = SymSparse::from_faer(m, "mass").unwrap();
    let mut worst = 0.0f64;
    for (i, a) in set.vectors.iter().enumerate() {
        for (j, b) in set.vectors.iter().enumerate() {
            let g = ms.form(a, b) - if i == j { 1.0 } else { 0.0 };
            worst = worst.max(g.abs());
        }
    }
    worst
}

fn omegas(set: &ModeSet) -> Vec<f64> {
    set.omega2.iter().map(|w| w.max(0.0).sqrt()).collect()
}

#[test]
fn dense_fixed_chain_matches_closed_form() {
    let (n, k, mass) = (10, 1.0e4, 2.5);
    let (km, mm) = chain(n, k, mass, true);
    let set = solve_modes(&km, &mm, &ModeRequest::Smallest { n }, &opts(Method::Dense)).unwrap();
    assert!(set.method.contains("dense"));
    for (j, w) in omegas(&set).iter().enumerate() {
        let exact = fixed_omega(j + 1, n, k, mass);
        // 10 DOFs, condition ~50: a dense eigensolver is accurate to ~1e-14 here.
        assert!(
            (w - exact).abs() <= 1e-12 * exact,
            "mode {}: {w} vs {exact}",
            j + 1
        );
    }
    assert!(orthonormality_error(&set, &mm) < 1e-12);
    // Frequencies in Hz follow from ω.
    let f = set.frequencies();
    assert!((f[0] - fixed_omega(1, n, k, mass) / (2.0 * PI)).abs() < 1e-12 * f[0]);
}

#[test]
fn lanczos_long_fixed_chain_ten_smallest() {
    let (n, k, mass) = (20_000, 3.0e5, 0.7);
    let (km, mm) = chain(n, k, mass, true);
    let set = solve_modes(
        &km,
        &mm,
        &ModeRequest::Smallest { n: 10 },
        &opts(Method::Lanczos),
    )
    .unwrap();
    assert!(set.method.contains("Lanczos"), "{}", set.method);
    assert_eq!(set.omega2.len(), 10);
    for (j, w) in omegas(&set).iter().enumerate() {
        let exact = fixed_omega(j + 1, n, k, mass);
        // Required accuracy of the brief: relative error < 1e-8 on ω although the
        // condition number of K is ~1.6e8 (shift-invert keeps the low end accurate).
        assert!(
            (w - exact).abs() < 1e-8 * exact,
            "mode {}: {w} vs {exact}",
            j + 1
        );
    }
    assert!(orthonormality_error(&set, &mm) < 1e-10);
    assert!(
        set.residuals.iter().all(|r| *r < 1e-8),
        "{:?}",
        set.residuals
    );
}

#[test]
fn free_free_chain_has_rigid_body_mode_both_solvers() {
    let (k, mass) = (1.0e3, 1.0);
    for (n, method) in [(40, Method::Dense), (3000, Method::Lanczos)] {
        let (km, mm) = chain(n, k, mass, false);
        let set = solve_modes(&km, &mm, &ModeRequest::Smallest { n: 6 }, &opts(method)).unwrap();
        // Rigid-body mode: ω² is round-off. Absolute tolerance 1e-8·(k/m), i.e. a frequency
        // below ~1.6e-5 Hz for a chain whose highest ω² is 4k/m.
        assert!(
            set.omega2[0].abs() < 1e-8 * k / mass,
            "{method:?}: rigid ω² = {}",
            set.omega2[0]
        );
        assert!(!set.frequencies()[0].is_nan());
        for j in 1..6 {
            let exact = free_omega(j, n, k, mass);
            let w = set.omega2[j].sqrt();
            assert!(
                (w - exact).abs() < 1e-8 * exact,
                "{method:?} mode {j}: {w} vs {exact}"
            );
        }
        assert!(orthonormality_error(&set, &mm) < 1e-10, "{method:?}");
    }
}

#[test]
fn band_returns_exactly_the_modes_inside() {
    let (n, k, mass) = (1200, 2.0e4, 1.5);
    let (km, mm) = chain(n, k, mass, true);
    // Band edges halfway between modes 37/38 and 52/53 (in Hz): modes 38..=52 inside.
    let hz = |j: usize| fixed_omega(j, n, k, mass) / (2.0 * PI);
    let (f_min, f_max) = (0.5 * (hz(37) + hz(38)), 0.5 * (hz(52) + hz(53)));
    for method in [Method::Dense, Method::Lanczos] {
        let set =
            solve_modes(&km, &mm, &ModeRequest::Band { f_min, f_max }, &opts(method)).unwrap();
        assert_eq!(set.omega2.len(), 15, "{method:?}");
        for (i, w) in omegas(&set).iter().enumerate() {
            let exact = fixed_omega(38 + i, n, k, mass);
            assert!(
                (w - exact).abs() < 1e-9 * exact,
                "{method:?}: {w} vs {exact}"
            );
        }
        assert!(orthonormality_error(&set, &mm) < 1e-10, "{method:?}");
    }
    // An empty band.
    let (a, b) = (0.4 * hz(1), 0.6 * hz(1));
    for method in [Method::Dense, Method::Lanczos] {
        let set = solve_modes(
            &km,
            &mm,
            &ModeRequest::Band { f_min: a, f_max: b },
            &opts(method),
        )
        .unwrap();
        assert!(set.omega2.is_empty());
    }
}

#[test]
fn centre_returns_the_n_closest() {
    let (n, k, mass) = (1500, 1.0e4, 1.0);
    let (km, mm) = chain(n, k, mass, true);
    let fc = fixed_omega(200, n, k, mass) / (2.0 * PI) * 1.0003;
    // Independent reference: sort all closed-form frequencies by distance to fc.
    let mut idx: Vec<usize> = (1..=n).collect();
    let dist = |j: usize| (fixed_omega(j, n, k, mass) / (2.0 * PI) - fc).abs();
    idx.sort_by(|&a, &b| dist(a).total_cmp(&dist(b)));
    let mut expect: Vec<usize> = idx[..7].to_vec();
    expect.sort();
    for method in [Method::Dense, Method::Lanczos] {
        let set = solve_modes(
            &km,
            &mm,
            &ModeRequest::Centre { f: fc, n: 7 },
            &opts(method),
        )
        .unwrap();
        assert_eq!(set.omega2.len(), 7);
        for (w, &j) in omegas(&set).iter().zip(&expect) {
            let exact = fixed_omega(j, n, k, mass);
            assert!(
                (w - exact).abs() < 1e-9 * exact,
                "{method:?}: {w} vs mode {j} {exact}"
            );
        }
    }
}

#[test]
fn dense_and_lanczos_agree_on_an_irregular_chain() {
    // Springs and masses varying along the chain: no closed form, so the two solvers
    // check each other (they share no code beyond the matrix product).
    let n = 900;
    let mut kt = Vec::new();
    let mut mt = Vec::new();
    for i in 0..n {
        let ki = 1.0e3 * (1.0 + 0.5 * ((i as f64) * 0.37).sin());
        let kn = 1.0e3 * (1.0 + 0.5 * ((i as f64 + 1.0) * 0.37).sin());
        kt.push((i, i, ki + kn));
        mt.push((i, i, 1.0 + 0.3 * ((i as f64) * 1.3).cos()));
        if i + 1 < n {
            kt.push((i + 1, i, -kn));
        }
    }
    let (km, mm) = (faer_sym(n, &kt), faer_sym(n, &mt));
    let req = ModeRequest::Smallest { n: 12 };
    let d = solve_modes(&km, &mm, &req, &opts(Method::Dense)).unwrap();
    let l = solve_modes(&km, &mm, &req, &opts(Method::Lanczos)).unwrap();
    for (a, b) in d.omega2.iter().zip(&l.omega2) {
        assert!((a - b).abs() < 1e-9 * a.abs(), "dense {a} vs Lanczos {b}");
    }
    // Same mode shapes up to sign: |φ_dᵀ M φ_l| = 1.
    let ms = SymSparse::from_faer(&mm, "mass").unwrap();
    for (a, b) in d.vectors.iter().zip(&l.vectors) {
        assert!((ms.form(a, b).abs() - 1.0).abs() < 1e-8);
    }
}

#[test]
fn lanczos_finds_both_copies_of_double_modes() {
    // Two identical, uncoupled fixed-fixed chains: every frequency is double. A single
    // Krylov sequence sees one copy only; the inertia check must bring in the other.
    let (n1, k, mass) = (1000, 1.0, 1.0);
    let (km, mm) = twin_chains(n1, k, mass);
    let set = solve_modes(
        &km,
        &mm,
        &ModeRequest::Smallest { n: 6 },
        &opts(Method::Lanczos),
    )
    .unwrap();
    for (i, w) in omegas(&set).iter().enumerate() {
        let exact = fixed_omega(i / 2 + 1, n1, k, mass);
        assert!((w - exact).abs() < 1e-9 * exact, "mode {i}: {w} vs {exact}");
    }
    assert!(orthonormality_error(&set, &mm) < 1e-10);
}

#[test]
fn massless_dofs_give_no_mode_and_condense_correctly() {
    // 2p+1 DOFs between walls, springs k; only the p even positions carry mass m. The
    // massless nodes condense to springs k/2, so ω_j = 2√(k/(2m)) sin(jπ/(2(p+1))).
    let (p, k, mass) = (60, 8.0, 2.0);
    let n = 2 * p + 1;
    let mut kt = Vec::new();
    let mut mt = Vec::new();
    for i in 0..n {
        kt.push((i, i, 2.0 * k));
        if i % 2 == 1 {
            mt.push((i, i, mass));
        }
        if i + 1 < n {
            kt.push((i + 1, i, -k));
        }
    }
    let (km, mm) = (faer_sym(n, &kt), faer_sym(n, &mt));
    for method in [Method::Dense, Method::Lanczos] {
        let set = solve_modes(&km, &mm, &ModeRequest::Smallest { n: 10 }, &opts(method)).unwrap();
        for (j, w) in omegas(&set).iter().enumerate() {
            let exact = fixed_omega(j + 1, p, k / 2.0, mass);
            assert!(
                (w - exact).abs() < 1e-9 * exact,
                "{method:?} mode {}: {w} vs {exact}",
                j + 1
            );
        }
        assert!(orthonormality_error(&set, &mm) < 1e-10, "{method:?}");
    }
    // Only p finite frequencies exist: asking for more is an error, not a panic.
    let r = solve_modes(
        &km,
        &mm,
        &ModeRequest::Smallest { n: p + 1 },
        &opts(Method::Dense),
    );
    assert!(r.is_err());
}

#[test]
fn bad_requests_are_errors() {
    let (km, mm) = chain(5, 1.0, 1.0, true);
    let o = EigenOptions::default();
    let e = solve_modes(
        &km,
        &mm,
        &ModeRequest::Band {
            f_min: 2.0,
            f_max: 1.0,
        },
        &o,
    )
    .unwrap_err();
    assert_eq!(e.keyword.as_deref(), Some("CALC_FREQ/FREQ"));
    assert!(solve_modes(&km, &mm, &ModeRequest::Smallest { n: 6 }, &o).is_err());
    assert!(solve_modes(&km, &mm, &ModeRequest::Centre { f: f64::NAN, n: 1 }, &o).is_err());
    let (k4, _) = chain(4, 1.0, 1.0, true);
    assert!(solve_modes(&k4, &mm, &ModeRequest::Smallest { n: 1 }, &o).is_err());
    // Zero requested modes: an empty set.
    let s = solve_modes(
        &km,
        &mm,
        &ModeRequest::Smallest { n: 0 },
        &opts(Method::Lanczos),
    )
    .unwrap();
    assert!(s.omega2.is_empty());
}

#[test]
fn frequency_never_nan() {
    assert_eq!(frequency(-1e-12), 0.0);
    assert!((frequency(omega2_of(3.5)) - 3.5).abs() < 1e-14);
}

#[test]
fn upper_triangle_storage_is_accepted() {
    let (n, k, mass) = (8, 5.0, 1.0);
    let mut t = Vec::new();
    for i in 0..n {
        t.push(Triplet::new(i, i, 2.0 * k));
        if i + 1 < n {
            t.push(Triplet::new(i, i + 1, -k)); // upper only
        }
    }
    let km = SparseColMat::try_new_from_triplets(n, n, &t).unwrap();
    let (_, mm) = chain(n, k, mass, true);
    let set = solve_modes(
        &km,
        &mm,
        &ModeRequest::Smallest { n: 3 },
        &EigenOptions::default(),
    )
    .unwrap();
    for (j, w) in omegas(&set).iter().enumerate() {
        let exact = fixed_omega(j + 1, n, k, mass);
        assert!((w - exact).abs() < 1e-12 * exact);
    }
}

// Each user of the shared model builders needs only some of them.
#[allow(dead_code)]
#[path = "../../../benches/common/models.rs"]
mod models;

#[test]
fn simply_supported_beam_both_solvers() {
    // Hermite beam elements, translations and rotations (DOFs of different scales, a
    // banded matrix). Exact ω_j = (jπ)² for L = EI = ρA = 1. The discretisation error
    // on ω scales as (jh)⁴ (measured with this builder: 6.75e-6 for mode 10 with 100
    // elements, converging at order 4), i.e. ≈ 1.1e-8 for mode 6 with 300 elements, so
    // 1e-7 leaves room for it while catching any solver error.
    let (k, m) = models::beam(300);
    for method in [Method::Dense, Method::Lanczos] {
        let set = solve_modes(&k, &m, &ModeRequest::Smallest { n: 6 }, &opts(method)).unwrap();
        for (j, w) in omegas(&set).iter().enumerate() {
            let exact = ((j + 1) as f64 * PI).powi(2);
            assert!(
                (w - exact).abs() < 1e-7 * exact,
                "{method:?} mode {}: {w} vs {exact}",
                j + 1
            );
        }
        assert!(orthonormality_error(&set, &m) < 1e-10, "{method:?}");
    }
}

#[test]
fn lanczos_with_locked_vectors_finds_the_rest() {
    // Explicit deflation: with the lowest 3 modes locked, a pass must return modes 4..6.
    let (n, k, mass) = (500, 1.0, 1.0);
    let (km, mm) = chain(n, k, mass, true);
    let ks = SymSparse::from_faer(&km, "k").unwrap();
    let ms = SymSparse::from_faer(&mm, "m").unwrap();
    let o = EigenOptions::default();
    let mut fac = ShiftedFactor::new(&ks, &ms, 0.0, FactorKind::Auto).unwrap();
    let mut work = LanczosWork::default();
    let first = lanczos_pass(&ks, &ms, &mut fac, 3, &[], &o, &mut 0, &mut work).unwrap();
    let locked: Vec<Vec<f64>> = first.iter().map(|p| p.1.clone()).collect();
    let mut next = lanczos_pass(&ks, &ms, &mut fac, 3, &locked, &o, &mut 0, &mut work).unwrap();
    next.sort_by(|a, b| a.0.total_cmp(&b.0));
    for (i, (w2, _)) in next.iter().enumerate() {
        let exact = fixed_omega(i + 4, n, k, mass);
        assert!(
            (w2.sqrt() - exact).abs() < 1e-9 * exact,
            "{} vs {exact}",
            w2.sqrt()
        );
    }
}

#[test]
fn band_from_zero_includes_rigid_body_mode() {
    // Free-free chain, band [0, f] with f halfway between elastic modes 3 and 4: the
    // rigid-body mode (ω² ≈ 0, reported at 0 Hz) and 3 elastic modes.
    let (n, k, mass) = (2500, 50.0, 0.5);
    let (km, mm) = chain(n, k, mass, false);
    let hz = |j: usize| free_omega(j, n, k, mass) / (2.0 * PI);
    let f_max = 0.5 * (hz(3) + hz(4));
    for method in [Method::Dense, Method::Lanczos] {
        let set = solve_modes(
            &km,
            &mm,
            &ModeRequest::Band { f_min: 0.0, f_max },
            &opts(method),
        )
        .unwrap();
        assert_eq!(set.omega2.len(), 4, "{method:?}: {:?}", set.frequencies());
        // Same absolute tolerance on the rigid mode as above: 1e-8·k/m.
        assert!(set.omega2[0].abs() < 1e-8 * k / mass, "{method:?}");
        for j in 1..4 {
            let exact = free_omega(j, n, k, mass);
            assert!(
                (set.omega2[j].sqrt() - exact).abs() < 1e-8 * exact,
                "{method:?} mode {j}"
            );
        }
    }
}

#[test]
fn normalize_through_faer_matrices() {
    let (km, mm) = chain(30, 4.0, 2.0, true);
    let set = solve_modes(
        &km,
        &mm,
        &ModeRequest::Smallest { n: 2 },
        &EigenOptions::default(),
    )
    .unwrap();
    let mut phi = set.vectors[1].clone();
    let r = normalize(
        &mut phi,
        &km,
        &mm,
        &ModeNorm::LargestComponent {
            mask: vec![true; 30],
        },
    )
    .unwrap();
    let biggest = phi
        .iter()
        .fold(0.0f64, |a, v| if v.abs() > a.abs() { *v } else { a });
    assert!((biggest - 1.0).abs() < 1e-15);
    // Rayleigh quotient is scale-free: gen_stiff / gen_mass = ω².
    assert!((r.gen_stiff / r.gen_mass - set.omega2[1]).abs() < 1e-10 * set.omega2[1]);
    // Wrong length: an error, not a panic.
    let mut short = vec![1.0; 29];
    assert!(normalize(&mut short, &km, &mm, &ModeNorm::MassGene).is_err());
}

#[test]
fn lanczos_on_a_tiny_model_returns_every_mode() {
    // Basis as large as the model: the Krylov space is the whole space and the
    // exhausted-subspace path must still return every mode correctly.
    let (n, k, mass) = (6, 3.0, 1.5);
    let (km, mm) = chain(n, k, mass, true);
    let set = solve_modes(
        &km,
        &mm,
        &ModeRequest::Smallest { n },
        &opts(Method::Lanczos),
    )
    .unwrap();
    assert_eq!(set.omega2.len(), n);
    for (j, w) in omegas(&set).iter().enumerate() {
        let exact = fixed_omega(j + 1, n, k, mass);
        assert!(
            (w - exact).abs() < 1e-10 * exact,
            "mode {}: {w} vs {exact}",
            j + 1
        );
    }
    assert!(orthonormality_error(&set, &mm) < 1e-10);
}

/// The fixed–fixed chain's K = tridiag(−1, 2, −1) and its lowest mode φ_i = sin(iπ/(n+1))
/// (positive): |φ|ᵀ|K||φ| / φᵀKφ is the ratio of the eigenvalues of tridiag(1, 2, 1) and
/// of K for that same vector, (2 + 2c)/(2 − 2c) = cot²(π/(2(n+1))), c = cos(π/(n+1)):
/// the closed form `omega2_precision` must give times ε, growing like n². (φᵀKφ carries the
/// very rounding it measures, ε·4e5 ≈ 1e-10 relative at n = 1000: hence 1e-9.)
#[test]
fn omega2_precision_is_the_closed_form_of_the_chain() {
    for n in [10usize, 100, 1000] {
        let mut lower = Vec::new();
        for i in 0..n {
            lower.push((i, i, 2.0));
            if i + 1 < n {
                lower.push((i + 1, i, -1.0));
            }
        }
        let k = sym::SymSparse::from_lower_triplets(n, &lower);
        let h = std::f64::consts::PI / (n + 1) as f64;
        let phi: Vec<f64> = (1..=n).map(|i| (i as f64 * h).sin()).collect();
        let exact = f64::EPSILON / (0.5 * h).tan().powi(2);
        let got = omega2_precision(&k, &phi);
        assert!(
            (got / exact - 1.0).abs() < 1e-9,
            "n = {n}: {got:e} vs {exact:e}"
        );
    }
    // A mode of no stiffness (rigid-body): judged absolutely, not by this ratio.
    let free = sym::SymSparse::from_lower_triplets(2, &[(0, 0, 1.0), (1, 0, -1.0), (1, 1, 1.0)]);
    assert!(omega2_precision(&free, &[1.0, 1.0]).is_infinite());
}

/// Many lowest modes by spectrum slicing against the closed form of a fixed chain, and
/// against the free-free chain's (a rigid-body mode in the first slice). 250 modes of a
/// 3000-mass chain: six slices; every ω² within 1e-9 of the exact one (the shift-invert
/// residual tolerance 1e-12 on θ leaves ~1e-12 on ω²; 1e-9 keeps margin for the condition
/// of the chain, ~4e6), every vector M-orthonormal to every other, across slices too.
#[test]
fn many_smallest_modes_by_slices_match_the_closed_form() {
    let (n, k, mass) = (3000, 2.0e4, 0.5);
    let count = 250;
    assert!(count > 2 * SLICE_MODES);
    for fixed in [true, false] {
        let (km, mm) = chain(n, k, mass, fixed);
        let set = solve_modes(
            &km,
            &mm,
            &ModeRequest::Smallest { n: count },
            &opts(Method::Lanczos),
        )
        .unwrap();
        assert!(set.method.contains("spectrum slicing"), "{}", set.method);
        assert_eq!(set.omega2.len(), count);
        // On ω² (the rigid-body mode's ω² is round-off, ~1e-17 of the spectral scale, whose
        // square root is not), relative to ω₁² at the low end.
        let low = fixed_omega(1, n, k, mass).powi(2);
        for (j, w2) in set.omega2.iter().enumerate() {
            let exact = if fixed {
                fixed_omega(j + 1, n, k, mass)
            } else {
                free_omega(j, n, k, mass)
            }
            .powi(2);
            assert!(
                (w2 - exact).abs() <= 1e-9 * exact.max(low),
                "fixed {fixed}, mode {}: ω² {w2} vs {exact}",
                j + 1
            );
        }
        assert!(orthonormality_error(&set, &mm) < 1e-9);
    }
}

/// Slicing where every frequency is double (two identical uncoupled chains): each slice's
/// Sylvester count makes its band solver find both copies.
#[test]
fn slices_find_both_copies_of_double_modes() {
    let (n1, k, mass) = (1500, 1.0, 1.0);
    let (km, mm) = twin_chains(n1, k, mass);
    let count = 2 * SLICE_MODES + 40;
    let set = solve_modes(
        &km,
        &mm,
        &ModeRequest::Smallest { n: count },
        &opts(Method::Lanczos),
    )
    .unwrap();
    assert!(set.method.contains("spectrum slicing"), "{}", set.method);
    for (i, w) in omegas(&set).iter().enumerate() {
        let exact = fixed_omega(i / 2 + 1, n1, k, mass);
        assert!((w - exact).abs() < 1e-9 * exact, "mode {i}: {w} vs {exact}");
    }
    assert!(orthonormality_error(&set, &mm) < 1e-9);
}

#[test]
fn quadratic_form_matches_the_product_and_the_dense_form() {
    // An irregular symmetric pattern (diagonal, neighbours, a far coupling), columns with
    // and without a diagonal entry.
    let n = 57;
    let mut lower = Vec::new();
    for j in 0..n {
        if j % 5 != 3 {
            lower.push((j, j, 2.0 + (j % 7) as f64));
        }
        if j + 1 < n {
            lower.push((j + 1, j, -1.0 + 0.25 * (j % 3) as f64));
        }
        if j + 13 < n && j % 4 == 0 {
            lower.push((j + 13, j, 0.25));
        }
    }
    let a = SymSparse::from_lower_triplets(n, &lower);
    let x: Vec<f64> = (0..n).map(|i| ((i * 7 % 11) as f64) - 5.0).collect();
    let dense = a.to_dense();
    let exact: f64 = (0..n)
        .flat_map(|i| (0..n).map(move |j| (i, j)))
        .map(|(i, j)| x[i] * dense[(i, j)] * x[j])
        .sum();
    // Integers and quarters times small integers: every partial sum is exact in binary, so
    // the three sums agree to the last bit.
    assert_eq!(a.quadratic(&x), exact);
    assert_eq!(a.form(&x, &x), exact);
}

/// The one-shift fallback's basis at the size that was killed: 10⁶ DOFs, 364 modes, 748
/// vectors twice (the basis and its M-products), 12.0 GB; the automatic size is never below
/// 40 vectors.
#[test]
fn the_one_shift_fallback_basis_is_sized_before_it_is_allocated() {
    let big = super::one_shift_basis_bytes(1_000_000, 364, 0);
    assert_eq!(big, 2.0 * 749.0 * 1e6 * 8.0);
    assert_eq!(
        super::one_shift_basis_bytes(10, 1, 0),
        2.0 * 41.0 * 10.0 * 8.0
    );
    assert_eq!(
        super::one_shift_basis_bytes(10, 1, 7),
        2.0 * 8.0 * 10.0 * 8.0
    );
}
