//! The physical (sparse) structure against the dense one on the same 3-DOF chain with a
//! stop on the last DOF and Rayleigh-free diagonal damping: same trajectories.

use super::*;
use faer::Mat;

/// Chain k = (2, −1; −1, 2, −1; −1, 1) × 100, masses (1, 2, 1), C = 0.1 M; node's DY is
/// DOF 2. DIFF_CENTRE and NEWMARK trajectories agree to 1e-12 (the same arithmetic up to
/// the order of operations in the solves).
#[test]
fn sparse_and_dense_structures_agree() {
    let kt = vec![
        (0, 0, 200.0),
        (1, 0, -100.0),
        (1, 1, 200.0),
        (2, 1, -100.0),
        (2, 2, 100.0),
    ];
    let mt = vec![(0, 0, 1.0), (1, 1, 2.0), (2, 2, 1.0)];
    let ct: Vec<_> = mt.iter().map(|&(i, j, v)| (i, j, 0.1 * v)).collect();
    let sparse = SparseStructure::new(3, mt.clone(), kt.clone(), Some(ct.clone())).unwrap();
    let dense_of = |t: &[(usize, usize, f64)]| {
        let mut m = Mat::<f64>::zeros(3, 3);
        for &(i, j, v) in t {
            m[(i, j)] += v;
            if i != j {
                m[(j, i)] += v;
            }
        }
        m
    };
    let dense = DenseStructure::full(dense_of(&mt), dense_of(&kt), Some(dense_of(&ct))).unwrap();
    let shock = || {
        let spec = super::stop_spec(0.05, 1e3, 1.0);
        Shock::new(spec, NodeRows::selection([None, Some(2), None]), None).unwrap()
    };
    let grid = TimeGrid {
        t0: 0.0,
        t_end: 2.0,
        dt: 1e-3,
    };
    let forcing = || {
        vec![Forcing {
            generalized_force: vec![0.0, 0.0, 10.0],
            multiplier: Box::new(|t: f64| (5.0 * t).sin()),
        }]
    };
    for scheme in [Scheme::DiffCentre, Scheme::from_name("NEWMARK").unwrap()] {
        let mut out = Vec::new();
        for s in [&sparse as &dyn Structure, &dense as &dyn Structure] {
            let mut shocks = vec![shock()];
            let traj = integrate(
                s,
                &mut shocks,
                &forcing(),
                (&[0.0; 3], &[0.0, 0.0, 0.5]),
                scheme,
                grid,
                &Archive::Every(50),
                &mut |_| {},
            )
            .unwrap();
            out.push(traj);
        }
        let max_pen = out[0].shocks[0].iter().map(|s| s.f_n).fold(0.0, f64::max);
        assert!(max_pen > 0.0, "the stop is reached");
        for (a, b) in out[0].q.iter().zip(&out[1].q) {
            assert!((a - b).abs() < 1e-12, "{scheme:?}: {a} vs {b}");
        }
    }
}
