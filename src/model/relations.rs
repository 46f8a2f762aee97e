//! Linear relations between DOFs (AFFE_CHAR_MECA/LIAISON_DDL: Σ cᵢ·uᵢ = c₀), applied by
//! elimination as the blocked DOFs are.
//!
//! Code_Aster dualises each relation with Lagrange multipliers. aster-nl expresses one
//! DOF of each relation (its *dependent* DOF) in terms of the others, so that every
//! operator keeps working on independent coordinates q with u = T·q: the reduced
//! matrices are TᵀAT, a mode or an orbit computed on q is written back as T·q, and a force
//! on an independent DOF stays on its own coordinate. Both give the same modes, because
//! both solve the same problem on the same constrained space {u : Σ cᵢ·uᵢ = 0}.
//!
//! As with DDL_IMPO, the imposed value c₀ is kept but modal and nonlinear-mode analysis
//! use only the homogeneous relation (AFFE_CHAR_MECA warns when c₀ ≠ 0).

use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;

/// One relation on the DOFs of a numbering: Σ coef·u[dof] = rhs.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct DofRelation {
    /// (DOF index in the numbering, coefficient); a DOF may appear more than once (the
    /// coefficients add).
    pub terms: Vec<(usize, f64)>,
    pub rhs: f64,
}

/// A coefficient below this fraction of a relation's largest is round-off of the
/// elimination (a relation that repeats or combines earlier ones), not a term.
const NEGLIGIBLE: f64 = 1e-12;

/// The dependent DOFs of a set of relations, each as a combination of independent DOFs
/// (DOFs neither blocked nor dependent): u[s] = Σ t·u[j].
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Dependence {
    dependent: BTreeMap<usize, Vec<(usize, f64)>>,
}

impl Dependence {
    /// Eliminate one DOF per relation, in order (Gauss–Jordan): each relation is first
    /// written in the independent DOFs (blocked DOFs are zero, dependent ones replaced by
    /// their expression); its term of largest magnitude (the first of equal ones) becomes
    /// dependent and is replaced in the earlier expressions. A relation that reduces to
    /// nothing (it repeats earlier ones, or holds only blocked DOFs) eliminates nothing.
    pub fn build(blocked: &[bool], relations: &[DofRelation]) -> Dependence {
        let mut dependent: BTreeMap<usize, Vec<(usize, f64)>> = BTreeMap::new();
        for rel in relations {
            let scale = rel.terms.iter().fold(0.0_f64, |m, t| m.max(t.1.abs()));
            let mut row: BTreeMap<usize, f64> = BTreeMap::new();
            for &(i, c) in &rel.terms {
                if blocked.get(i).copied().unwrap_or(true) {
                    continue;
                }
                match dependent.get(&i) {
                    Some(expr) => {
                        for &(j, t) in expr {
                            *row.entry(j).or_insert(0.0) += c * t;
                        }
                    }
                    None => *row.entry(i).or_insert(0.0) += c,
                }
            }
            row.retain(|_, c| c.abs() > NEGLIGIBLE * scale);
            let Some((&s, &cs)) = row
                .iter()
                .fold(None, |best: Option<(&usize, &f64)>, (i, c)| match best {
                    Some((_, b)) if b.abs() >= c.abs() => best,
                    _ => Some((i, c)),
                })
            else {
                continue;
            };
            let expr: Vec<(usize, f64)> = row
                .iter()
                .filter(|(&j, _)| j != s)
                .map(|(&j, &c)| (j, -c / cs))
                .collect();
            for other in dependent.values_mut() {
                if let Some(pos) = other.iter().position(|&(j, _)| j == s) {
                    let (_, a) = other.swap_remove(pos);
                    let mut merged: BTreeMap<usize, f64> = other.drain(..).collect();
                    for &(j, t) in &expr {
                        *merged.entry(j).or_insert(0.0) += a * t;
                    }
                    other.extend(merged);
                }
            }
            dependent.insert(s, expr);
        }
        Dependence { dependent }
    }

    pub fn is_empty(&self) -> bool {
        self.dependent.is_empty()
    }

    /// Whether DOF `i` is expressed by a relation in terms of others.
    pub fn is_dependent(&self, i: usize) -> bool {
        self.dependent.contains_key(&i)
    }

    /// The expression of a dependent DOF: (independent DOF, coefficient).
    pub fn expression(&self, i: usize) -> Option<&[(usize, f64)]> {
        self.dependent.get(&i).map(Vec::as_slice)
    }

    /// Fill the dependent entries of a full vector from its independent ones.
    pub fn complete(&self, full: &mut [f64]) {
        for (&s, expr) in &self.dependent {
            let v: f64 = expr
                .iter()
                .map(|&(j, t)| t * full.get(j).copied().unwrap_or(0.0))
                .sum();
            if let Some(x) = full.get_mut(s) {
                *x = v;
            }
        }
    }

    /// TᵀAT as triplets on the reduced coordinates: `reduced[i]` is the coordinate of an
    /// independent DOF i (None for blocked and dependent DOFs); duplicates not summed.
    pub fn transform(
        &self,
        triplets: &[(usize, usize, f64)],
        reduced: &[Option<usize>],
    ) -> Vec<(usize, usize, f64)> {
        // Each DOF as (coordinate, weight) pairs: itself, its expression, or nothing.
        let weights = |i: usize| -> Vec<(usize, f64)> {
            match self.dependent.get(&i) {
                Some(expr) => expr
                    .iter()
                    .filter_map(|&(j, t)| Some((reduced.get(j).copied().flatten()?, t)))
                    .collect(),
                None => reduced
                    .get(i)
                    .copied()
                    .flatten()
                    .map(|r| vec![(r, 1.0)])
                    .unwrap_or_default(),
            }
        };
        let mut out = Vec::with_capacity(triplets.len());
        for &(i, j, v) in triplets {
            let (wi, wj) = (weights(i), weights(j));
            for &(a, ta) in &wi {
                for &(b, tb) in &wj {
                    out.push((a, b, ta * v * tb));
                }
            }
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rel(terms: &[(usize, f64)]) -> DofRelation {
        DofRelation {
            terms: terms.to_vec(),
            rhs: 0.0,
        }
    }

    /// Every relation holds on the vector that `complete` fills from arbitrary
    /// independent values (to round-off), and the count of dependent DOFs is the rank.
    fn holds(dep: &Dependence, n: usize, relations: &[DofRelation], blocked: &[bool]) {
        let mut u: Vec<f64> = (0..n).map(|i| 1.0 + 0.37 * i as f64).collect();
        for (i, b) in blocked.iter().enumerate() {
            if *b {
                u[i] = 0.0;
            }
        }
        dep.complete(&mut u);
        for r in relations {
            let s: f64 = r.terms.iter().map(|&(i, c)| c * u[i]).sum();
            assert!(s.abs() < 1e-12, "relation {r:?} gives {s}");
        }
    }

    #[test]
    fn one_relation_makes_its_largest_term_dependent() {
        // 0.5 u0 - 2 u1 + u2 = 0: u1 = 0.25 u0 + 0.5 u2.
        let rels = [rel(&[(0, 0.5), (1, -2.0), (2, 1.0)])];
        let dep = Dependence::build(&[false; 3], &rels);
        assert!(dep.is_dependent(1));
        let e = dep.expression(1).unwrap();
        assert_eq!(e, &[(0, 0.25), (2, 0.5)]);
        holds(&dep, 3, &rels, &[false; 3]);
    }

    #[test]
    fn chained_and_repeated_relations_are_eliminated_once_each() {
        // u0 = u1, u1 = u2, u0 = u2 (the third repeats the first two), u3 + u4 = 0.
        let rels = [
            rel(&[(0, 1.0), (1, -1.0)]),
            rel(&[(1, 1.0), (2, -1.0)]),
            rel(&[(0, 1.0), (2, -1.0)]),
            rel(&[(3, 1.0), (4, 1.0)]),
        ];
        let blocked = [false; 5];
        let dep = Dependence::build(&blocked, &rels);
        assert_eq!(dep.dependent.len(), 3, "{dep:?}");
        // Expressions hold only independent DOFs.
        for expr in dep.dependent.values() {
            assert!(expr.iter().all(|(j, _)| !dep.is_dependent(*j)));
        }
        holds(&dep, 5, &rels, &blocked);
    }

    #[test]
    fn blocked_dofs_drop_out_of_a_relation() {
        // u0 + u1 + u2 = 0 with u1 blocked: u0 = -u2 (or u2 = -u0).
        let rels = [rel(&[(0, 1.0), (1, 1.0), (2, 1.0)])];
        let blocked = [false, true, false];
        let dep = Dependence::build(&blocked, &rels);
        assert_eq!(dep.dependent.len(), 1);
        assert!(!dep.is_dependent(1));
        holds(&dep, 3, &rels, &blocked);
        // A relation on blocked DOFs only eliminates nothing.
        let dep = Dependence::build(&[true, true], &[rel(&[(0, 1.0), (1, 2.0)])]);
        assert!(dep.is_empty());
    }

    #[test]
    fn transform_is_t_transpose_a_t() {
        // A = diag(1, 2, 3), u1 = u0 (u0 - u1 = 0): on q = u0, u2: TᵀAT = diag(1 + 2, 3).
        let dep = Dependence::build(&[false; 3], &[rel(&[(0, 1.0), (1, -1.0)])]);
        let dependent_one = dep.is_dependent(1);
        let reduced = if dependent_one {
            vec![Some(0), None, Some(1)]
        } else {
            vec![None, Some(0), Some(1)]
        };
        let a = [(0, 0, 1.0), (1, 1, 2.0), (2, 2, 3.0)];
        let mut t = dep.transform(&a, &reduced);
        t.sort_by_key(|e| (e.0, e.1));
        let sum = |r: usize, c: usize| -> f64 {
            t.iter().filter(|e| e.0 == r && e.1 == c).map(|e| e.2).sum()
        };
        assert_eq!(sum(0, 0), 3.0);
        assert_eq!(sum(1, 1), 3.0);
        assert_eq!(sum(0, 1), 0.0);
    }
}
