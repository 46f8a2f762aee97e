//! Pareto front of (time, error) and the cheapest setting for a target accuracy.

use super::measure::Measurement;

/// Indices of the Pareto-optimal points of `(cost, error)` pairs, sorted by cost: a point is
/// on the front when no other point is at most as costly and at most as wrong, and strictly
/// better in one of the two. Non-finite pairs are never on the front (nor dominate).
pub fn pareto_front(points: &[(f64, f64)]) -> Vec<usize> {
    let mut idx: Vec<usize> = (0..points.len())
        .filter(|&i| points[i].0.is_finite() && points[i].1.is_finite())
        .collect();
    // By cost, then error: a sweep keeps each point whose error is below every cheaper one.
    idx.sort_by(|&a, &b| {
        points[a]
            .0
            .total_cmp(&points[b].0)
            .then(points[a].1.total_cmp(&points[b].1))
    });
    let mut front = Vec::new();
    let mut best = f64::INFINITY;
    for i in idx {
        if points[i].1 < best {
            best = points[i].1;
            front.push(i);
        }
    }
    front
}

/// The cheapest measured setting whose error meets a target.
#[derive(Clone, Debug)]
pub struct Recommendation {
    pub target: f64,
    /// Index into the measurements, None if no setting met the target.
    pub index: Option<usize>,
}

/// For each target, the cheapest successful measurement with error ≤ target (necessarily a
/// Pareto point).
pub fn recommend(ms: &[Measurement], targets: &[f64]) -> Vec<Recommendation> {
    targets
        .iter()
        .map(|&target| Recommendation {
            target,
            index: (0..ms.len())
                .filter(|&i| ms[i].ok() && ms[i].max_rel_error <= target)
                .min_by(|&a, &b| ms[a].cost().total_cmp(&ms[b].cost())),
        })
        .collect()
}

/// The (cost, error) pairs (cost: `Measurement::cost`) of measurements, NaN for failed runs.
pub fn cost_error(ms: &[Measurement]) -> Vec<(f64, f64)> {
    ms.iter()
        .map(|m| {
            if m.ok() {
                (m.cost(), m.max_rel_error)
            } else {
                (f64::NAN, f64::NAN)
            }
        })
        .collect()
}
