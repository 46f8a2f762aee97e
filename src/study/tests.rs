//! Study tests: the Pareto front on hand-made points, and the measured error trends.

use super::*;

#[test]
fn pareto_front_of_hand_made_points() {
    // (time, error). Dominated: 1 (by 0: dearer and worse), 3 (same cost as 2, worse),
    // 5 (same error as 4, dearer), 6 (NaN). Front sorted by cost: 0, 2, 4, 7.
    let pts = [
        (1.0, 1e-2),
        (2.0, 2e-2),
        (3.0, 1e-3),
        (3.0, 5e-3),
        (5.0, 1e-4),
        (6.0, 1e-4),
        (f64::NAN, 1e-9),
        (10.0, 1e-6),
    ];
    assert_eq!(pareto_front(&pts), vec![0, 2, 4, 7]);
    // Brute force: a point is on the front iff nothing dominates it.
    let dominated = |i: usize| {
        pts.iter().enumerate().any(|(j, q)| {
            j != i && q.0 <= pts[i].0 && q.1 <= pts[i].1 && (q.0 < pts[i].0 || q.1 < pts[i].1)
        })
    };
    let brute: Vec<usize> = (0..pts.len())
        .filter(|&i| pts[i].0.is_finite() && !dominated(i))
        .collect();
    assert_eq!(brute, vec![0, 2, 4, 7]);
    assert!(pareto_front(&[]).is_empty());
}
