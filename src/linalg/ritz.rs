//! Ritz bases (DEFI_BASE_MODALE): vectors of several bases put end to end, each basis
//! truncated to its first vectors, and their orthonormalisation in the metric of a
//! symmetric matrix (ORTHO='OUI', ORTHO_BASE). No SQL, no keywords.
//!
//! Vectors are in the full numbering of their DOFs (every DOF, zero on the blocked ones;
//! the DOFs a LIAISON_DDL relation expresses carry their expression's value). The metric
//! is the assembled matrix over that full numbering, both triangles given by entries. That
//! form is the right one with relations too: a vector satisfying the relations is u = T q
//! (q its values on the free DOFs, T the relations' expansion), so uᵀ A u = qᵀ (Tᵀ A T) q
//! is the form of the reduced matrix CALC_MODES and PROJ_MATR_BASE work with; and on
//! blocked DOFs the vectors vanish, so those rows and columns of A do not count.

use crate::error::{Error, Result};

/// A vector whose part left after the projection on the vectors before it is below this
/// share of its own norm (in the metric) is taken as dependent on them and dropped: once
/// normalised it would be that much amplified round-off (ε/1e-8 ≈ 1e-8 of its direction
/// would be noise), a direction the basis already holds.
pub const DEPENDENCE_RATIO: f64 = 1e-8;

/// vᵀAv below −this × |v|ᵀ|A||v| (beyond round-off) says A is not a metric.
const NEGATIVE_FORM: f64 = 1e-10;

/// A symmetric matrix of size n by its (row, col, value) entries, both triangles stored:
/// the metric of an orthonormalisation, or the form of a generalized quantity.
#[derive(Clone, Copy, Debug)]
pub struct Metric<'a> {
    n: usize,
    entries: &'a [(usize, usize, f64)],
}

impl<'a> Metric<'a> {
    /// Checks that every entry lies inside the size.
    pub fn new(n: usize, entries: &'a [(usize, usize, f64)]) -> Result<Metric<'a>> {
        if let Some(&(i, j, _)) = entries.iter().find(|e| e.0 >= n || e.1 >= n) {
            return Err(Error::internal(format!(
                "matrix entry ({i}, {j}) outside its size {n}"
            )));
        }
        Ok(Metric { n, entries })
    }

    pub fn size(&self) -> usize {
        self.n
    }

    /// y = A x (x, y of length n).
    fn apply(&self, x: &[f64], y: &mut [f64]) {
        y.fill(0.0);
        for &(i, j, v) in self.entries {
            y[i] += v * x[j];
        }
    }

    /// xᵀ A y.
    pub fn form(&self, x: &[f64], y: &[f64]) -> Result<f64> {
        check_lengths(self.n, &[x, y])?;
        let mut ay = vec![0.0; self.n];
        self.apply(y, &mut ay);
        Ok(dot(x, &ay))
    }

    /// |x|ᵀ |A| |x|: the size of the terms of xᵀAx, against which its round-off is judged.
    fn abs_form(&self, x: &[f64]) -> f64 {
        self.entries
            .iter()
            .map(|&(i, j, v)| (x[i] * v * x[j]).abs())
            .sum()
    }
}

/// The first vectors of several bases, end to end.
#[derive(Clone, Debug, PartialEq)]
pub struct Concatenation<T> {
    /// The vectors kept, in order: part 1's, then part 2's...
    pub items: Vec<T>,
    /// For each item: (the part it comes from, its index in that part), 0-based.
    pub origin: Vec<(usize, usize)>,
    /// The parts whose count asked for more vectors than they have (all of them kept):
    /// (part, count asked, vectors it has).
    pub short: Vec<(usize, usize, usize)>,
}

/// Each part's first `count` items (all of them when `None`; 0 keeps none), in order. A
/// count above a part's size keeps the whole part and is reported in `short`.
pub fn concatenate<T: Clone>(parts: &[(&[T], Option<usize>)]) -> Concatenation<T> {
    let total: usize = parts
        .iter()
        .map(|(items, count)| count.map_or(items.len(), |c| c.min(items.len())))
        .sum();
    let mut out = Concatenation {
        items: Vec::with_capacity(total),
        origin: Vec::with_capacity(total),
        short: Vec::new(),
    };
    for (p, (items, count)) in parts.iter().enumerate() {
        let keep = match *count {
            Some(c) if c > items.len() => {
                out.short.push((p, c, items.len()));
                items.len()
            }
            Some(c) => c,
            None => items.len(),
        };
        for (k, item) in items.iter().take(keep).enumerate() {
            out.items.push(item.clone());
            out.origin.push((p, k));
        }
    }
    out
}

/// An error naming the first vector whose length is not `n`.
pub fn check_lengths(n: usize, vectors: &[&[f64]]) -> Result<()> {
    match vectors.iter().position(|v| v.len() != n) {
        Some(k) => Err(Error::internal(format!(
            "vector {} has {} values for {n} DOFs",
            k + 1,
            vectors[k].len()
        ))),
        None => Ok(()),
    }
}

/// A vector left out of an orthonormal basis as dependent on the vectors before it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Dropped {
    /// Its index in the input, 0-based.
    pub index: usize,
    /// The norm of what was left of it after the projection, relative to its own norm
    /// (0 for a vector the metric does not see: zero, or only on DOFs without mass).
    pub ratio: f64,
}

/// The outcome of [`orthonormalize`].
#[derive(Clone, Debug, PartialEq)]
pub struct Orthonormal {
    /// Orthonormal in the metric: QᵀAQ = I.
    pub vectors: Vec<Vec<f64>>,
    /// For each output vector, the index of the input vector it comes from.
    pub kept: Vec<usize>,
    pub dropped: Vec<Dropped>,
}

/// The vectors orthonormalised in order in the metric A: each one minus its components on
/// the vectors kept before it, then normalised; one whose remaining part is below `ratio`
/// of its own A-norm is dropped (it adds nothing to the span). The output spans what the
/// input spans, and its first k vectors span the first kept inputs (the order of a Ritz
/// basis means something: normal modes first, static corrections after).
///
/// Modified Gram–Schmidt, applied twice to each vector: one pass leaves the vectors
/// orthogonal only to ε·κ (κ the condition of the input set), and a basis of normal modes
/// plus static modes is ill-conditioned by nature (a static mode K⁻¹f is mostly the lowest
/// modes); a second pass brings the orthogonality back to round-off whatever κ ("twice is
/// enough"). A Cholesky factor of the Gram matrix VᵀAV, the other usual route, squares the
/// condition (κ(VᵀAV) = κ²), loses orthogonality like ε·κ², and tells a dependent vector
/// only by a small pivot, not in the order of the basis.
///
/// Errors when a vector is not finite or A is not positive on it (not a metric).
pub fn orthonormalize(metric: &Metric, vectors: &[Vec<f64>], ratio: f64) -> Result<Orthonormal> {
    let n = metric.size();
    let refs: Vec<&[f64]> = vectors.iter().map(Vec::as_slice).collect();
    check_lengths(n, &refs)?;
    let mut out = Orthonormal {
        vectors: Vec::new(),
        kept: Vec::new(),
        dropped: Vec::new(),
    };
    // A·q of each kept q: a projection coefficient is then one dot product.
    let mut a_q: Vec<Vec<f64>> = Vec::new();
    let mut av = vec![0.0; n];
    for (k, v) in vectors.iter().enumerate() {
        if v.iter().any(|x| !x.is_finite()) {
            return Err(Error::numerical(format!(
                "vector {} has a value that is not finite",
                k + 1
            )));
        }
        metric.apply(v, &mut av);
        let norm2 = positive_form(metric, v, &av, k)?;
        if norm2 <= 0.0 {
            out.dropped.push(Dropped {
                index: k,
                ratio: 0.0,
            });
            continue;
        }
        let mut w = v.clone();
        for _pass in 0..2 {
            for (q, aq) in out.vectors.iter().zip(&a_q) {
                let c = dot(aq, &w);
                for (wi, qi) in w.iter_mut().zip(q) {
                    *wi -= c * qi;
                }
            }
        }
        metric.apply(&w, &mut av);
        let left2 = positive_form(metric, &w, &av, k)?;
        let r = (left2.max(0.0) / norm2).sqrt();
        if r < ratio || left2 <= 0.0 {
            out.dropped.push(Dropped { index: k, ratio: r });
            continue;
        }
        let s = 1.0 / left2.sqrt();
        w.iter_mut().for_each(|x| *x *= s);
        out.vectors.push(w);
        a_q.push(av.iter().map(|x| x * s).collect());
        out.kept.push(k);
    }
    Ok(out)
}

/// vᵀAv from Av, refused when clearly negative (A not a metric), round-off below zero
/// taken as zero.
fn positive_form(metric: &Metric, v: &[f64], av: &[f64], k: usize) -> Result<f64> {
    let f = dot(v, av);
    if !f.is_finite() {
        return Err(Error::numerical(format!(
            "the norm of vector {} in the matrix is not finite",
            k + 1
        )));
    }
    if f < -NEGATIVE_FORM * metric.abs_form(v) {
        return Err(Error::numerical(format!(
            "the matrix is negative on vector {} (vᵀAv = {f:e}): it is not a metric to \
             orthonormalise in",
            k + 1
        )));
    }
    Ok(f.max(0.0))
}

/// ω² and the frequency in Hz of a Ritz vector of generalized stiffness k and mass m:
/// Code_Aster's FREQ of a vector that is not an eigenvector, √(k/m)/2π (0 when m is not
/// positive; a negative k, which a semi-definite stiffness does not give, counts as 0).
pub fn rayleigh_frequency(k: f64, m: f64) -> (f64, f64) {
    if !m.is_finite() || m <= 0.0 || !k.is_finite() {
        return (0.0, 0.0);
    }
    let omega2 = k / m;
    (
        omega2,
        omega2.max(0.0).sqrt() / (2.0 * std::f64::consts::PI),
    )
}

/// The modes of a structure reduced on a basis (Rayleigh–Ritz): with Φ the vectors, the
/// eigenpairs of (ΦᵀKΦ) y = ω² (ΦᵀMΦ) y, all of them, ω² ascending, restored as Φy and
/// mass-normalised (yᵀΦᵀMΦy = 1). In the span of the basis they are what the structure's
/// modes would be if it could move in that span only; a basis that holds exact modes
/// returns them. DYNA_LINE's ORTHO='OUI'. The small problem is dense (src/linalg/eigen/dense.rs);
/// vectors the mass does not see (infinite ω²) are dropped, as there.
pub fn rayleigh_ritz(k: &Metric, m: &Metric, vectors: &[Vec<f64>]) -> Result<ReducedModes> {
    let n = k.size();
    if m.size() != n {
        return Err(Error::internal(format!(
            "stiffness of size {n} and mass of size {}",
            m.size()
        )));
    }
    let refs: Vec<&[f64]> = vectors.iter().map(Vec::as_slice).collect();
    check_lengths(n, &refs)?;
    let b = vectors.len();
    let mut k_low = Vec::new();
    let mut m_low = Vec::new();
    for i in 0..b {
        for j in 0..=i {
            k_low.push((i, j, k.form(&vectors[i], &vectors[j])?));
            m_low.push((i, j, m.form(&vectors[i], &vectors[j])?));
        }
    }
    let kr = crate::linalg::eigen::sym::SymSparse::from_lower_triplets(b, &k_low);
    let mr = crate::linalg::eigen::sym::SymSparse::from_lower_triplets(b, &m_low);
    // δ only matters when the reduced stiffness is singular (a basis with rigid-body
    // motion): a shift far below its scale.
    let scale = k_low
        .iter()
        .filter(|e| e.0 == e.1)
        .map(|e| e.2.abs())
        .fold(0.0, f64::max);
    let modes =
        crate::linalg::eigen::dense::solve_dense(&kr, &mr, 1e-12 * scale.max(f64::MIN_POSITIVE))?;
    let shapes = modes
        .vectors
        .iter()
        .map(|y| {
            let mut phi = vec![0.0; n];
            for (c, v) in y.iter().zip(vectors) {
                for (p, x) in phi.iter_mut().zip(v) {
                    *p += c * x;
                }
            }
            phi
        })
        .collect();
    Ok(ReducedModes {
        omega2: modes.omega2,
        shapes,
    })
}

/// What [`rayleigh_ritz`] gives: ω² ascending and the mass-normalised vectors.
#[derive(Clone, Debug)]
pub struct ReducedModes {
    pub omega2: Vec<f64>,
    pub shapes: Vec<Vec<f64>>,
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A well-conditioned SPD matrix of size n: tridiagonal (4, -1) plus a coupling of
    /// the ends, both triangles.
    fn spd(n: usize) -> Vec<(usize, usize, f64)> {
        let mut e = Vec::new();
        for i in 0..n {
            e.push((i, i, 4.0 + i as f64 * 0.5));
            if i + 1 < n {
                e.push((i, i + 1, -1.0));
                e.push((i + 1, i, -1.0));
            }
        }
        e.push((0, n - 1, 0.3));
        e.push((n - 1, 0, 0.3));
        e
    }

    /// Deterministic pseudo-random vectors in [-1, 1) (a linear congruential generator):
    /// independent, with no structure the algorithm could lean on.
    fn vectors(n: usize, m: usize) -> Vec<Vec<f64>> {
        let mut state: u64 = 0x2545_f491_4f6c_dd1d;
        let mut next = move || {
            state = state
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            (state >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
        };
        (0..m).map(|_| (0..n).map(|_| next()).collect()).collect()
    }

    /// max |QᵀAQ − I|.
    fn orthonormality_error(a: &Metric, q: &[Vec<f64>]) -> f64 {
        let mut worst = 0.0f64;
        for (i, qi) in q.iter().enumerate() {
            for (j, qj) in q.iter().enumerate() {
                let g = a.form(qi, qj).unwrap();
                let target = if i == j { 1.0 } else { 0.0 };
                worst = worst.max((g - target).abs());
            }
        }
        worst
    }

    /// The largest relative error of the A-orthogonal projection of each vector of `v` on
    /// the orthonormal `q`: Σ q_j (q_jᵀ A v) against v.
    fn span_error(a: &Metric, q: &[Vec<f64>], v: &[Vec<f64>]) -> f64 {
        let mut worst = 0.0f64;
        for vk in v {
            let mut p = vec![0.0; vk.len()];
            for qj in q {
                let c = a.form(qj, vk).unwrap();
                for (pi, qi) in p.iter_mut().zip(qj) {
                    *pi += c * qi;
                }
            }
            let norm = vk.iter().map(|x| x * x).sum::<f64>().sqrt();
            let err = vk
                .iter()
                .zip(&p)
                .map(|(x, y)| (x - y).powi(2))
                .sum::<f64>()
                .sqrt();
            worst = worst.max(err / norm);
        }
        worst
    }

    #[test]
    fn two_vectors_in_a_diagonal_metric_give_the_exact_basis() {
        // A = diag(1, 4): (1, 0) has norm 1; (1, 1) minus its component 1 on it is
        // (0, 1), of norm 2: q2 = (0, 1/2).
        let entries = [(0, 0, 1.0), (1, 1, 4.0)];
        let a = Metric::new(2, &entries).unwrap();
        let o = orthonormalize(&a, &[vec![1.0, 0.0], vec![1.0, 1.0]], DEPENDENCE_RATIO).unwrap();
        assert_eq!(o.vectors, vec![vec![1.0, 0.0], vec![0.0, 0.5]]);
        assert_eq!(o.kept, vec![0, 1]);
        assert!(o.dropped.is_empty());
    }

    #[test]
    fn the_output_is_orthonormal_and_spans_the_input() {
        let n = 9;
        let entries = spd(n);
        let a = Metric::new(n, &entries).unwrap();
        let v = vectors(n, 6);
        let o = orthonormalize(&a, &v, DEPENDENCE_RATIO).unwrap();
        assert_eq!(o.kept, (0..6).collect::<Vec<_>>());
        let ortho = orthonormality_error(&a, &o.vectors);
        assert!(ortho < 1e-12, "QᵀAQ − I: {ortho:e}");
        let span = span_error(&a, &o.vectors, &v);
        assert!(span < 1e-12, "span: {span:e}");
        // The order is kept: q1 is v1 normalised.
        let n1 = a.form(&v[0], &v[0]).unwrap().sqrt();
        let d = v[0]
            .iter()
            .zip(&o.vectors[0])
            .map(|(x, q)| (x / n1 - q).abs())
            .fold(0.0, f64::max);
        assert!(d < 1e-15, "{d:e}");
    }

    #[test]
    fn an_ill_conditioned_set_stays_orthonormal_to_round_off() {
        // Monomials t^k on 12 points of [0, 1], k = 0..7: an ill-conditioned set. One
        // Gram–Schmidt pass leaves QᵀAQ 2.5e-12 from the identity (measured), the second
        // brings it below 1e-13.
        let n = 12;
        let entries = spd(n);
        let a = Metric::new(n, &entries).unwrap();
        let v: Vec<Vec<f64>> = (0..8)
            .map(|k| {
                (0..n)
                    .map(|i| (i as f64 / (n - 1) as f64).powi(k))
                    .collect()
            })
            .collect();
        let o = orthonormalize(&a, &v, DEPENDENCE_RATIO).unwrap();
        assert_eq!(o.vectors.len(), 8, "{:?}", o.dropped);
        let ortho = orthonormality_error(&a, &o.vectors);
        assert!(ortho < 1e-13, "QᵀAQ − I: {ortho:e}");
        let span = span_error(&a, &o.vectors, &v);
        assert!(span < 1e-12, "span: {span:e}");
    }

    #[test]
    fn dependent_vectors_are_dropped_and_named() {
        let n = 7;
        let entries = spd(n);
        let a = Metric::new(n, &entries).unwrap();
        let v = vectors(n, 3);
        // v3 = v1 + 2 v2 exactly dependent, v4 = v1 + 1e-10 v3' nearly so (below the
        // ratio), then an independent one, then a zero vector.
        let comb: Vec<f64> = v[0].iter().zip(&v[1]).map(|(x, y)| x + 2.0 * y).collect();
        let near: Vec<f64> = v[0].iter().zip(&v[2]).map(|(x, y)| x + 1e-10 * y).collect();
        let input = vec![
            v[0].clone(),
            v[1].clone(),
            comb,
            near,
            v[2].clone(),
            vec![0.0; n],
        ];
        let o = orthonormalize(&a, &input, DEPENDENCE_RATIO).unwrap();
        assert_eq!(o.kept, vec![0, 1, 4]);
        let dropped: Vec<usize> = o.dropped.iter().map(|d| d.index).collect();
        assert_eq!(dropped, vec![2, 3, 5]);
        assert!(o.dropped[0].ratio < 1e-14, "{:?}", o.dropped);
        assert!(
            o.dropped[1].ratio > 1e-12 && o.dropped[1].ratio < 1e-9,
            "{:?}",
            o.dropped
        );
        assert_eq!(o.dropped[2].ratio, 0.0);
        assert!(orthonormality_error(&a, &o.vectors) < 1e-12);
        // What was dropped is still in the span of what was kept.
        assert!(span_error(&a, &o.vectors, &input[..5]) < 1e-9);
        // A vector just above the ratio is kept.
        let above: Vec<f64> = v[0].iter().zip(&v[2]).map(|(x, y)| x + 1e-6 * y).collect();
        let o = orthonormalize(&a, &[v[0].clone(), above], DEPENDENCE_RATIO).unwrap();
        assert_eq!(o.kept, vec![0, 1]);
        assert!(orthonormality_error(&a, &o.vectors) < 1e-12);
    }

    #[test]
    fn a_vector_on_massless_dofs_only_is_dropped() {
        // A semi-definite mass: nothing on DOF 2.
        let entries = [(0, 0, 2.0), (1, 1, 1.0)];
        let a = Metric::new(3, &entries).unwrap();
        let o = orthonormalize(
            &a,
            &[vec![1.0, 0.0, 0.0], vec![0.0, 0.0, 5.0]],
            DEPENDENCE_RATIO,
        )
        .unwrap();
        assert_eq!(o.kept, vec![0]);
        assert_eq!(
            o.dropped,
            vec![Dropped {
                index: 1,
                ratio: 0.0
            }]
        );
    }

    #[test]
    fn an_indefinite_matrix_or_bad_vectors_are_refused() {
        let entries = [(0, 0, 1.0), (1, 1, -1.0)];
        let a = Metric::new(2, &entries).unwrap();
        let e = orthonormalize(&a, &[vec![0.0, 1.0]], DEPENDENCE_RATIO).unwrap_err();
        assert!(e.message.contains("not a metric"), "{}", e.message);
        let ok = [(0, 0, 1.0), (1, 1, 1.0)];
        let a = Metric::new(2, &ok).unwrap();
        assert!(orthonormalize(&a, &[vec![1.0]], DEPENDENCE_RATIO).is_err());
        assert!(orthonormalize(&a, &[vec![f64::NAN, 0.0]], DEPENDENCE_RATIO).is_err());
        assert!(Metric::new(2, &[(0, 2, 1.0)]).is_err());
    }

    #[test]
    fn concatenation_keeps_the_first_vectors_of_each_part() {
        let a = [1, 2, 3, 4];
        let b = [10, 20];
        let c = [100, 200, 300];
        let out = concatenate(&[(&a[..], Some(2)), (&b[..], Some(5)), (&c[..], None)]);
        assert_eq!(out.items, vec![1, 2, 10, 20, 100, 200, 300]);
        assert_eq!(
            out.origin,
            vec![(0, 0), (0, 1), (1, 0), (1, 1), (2, 0), (2, 1), (2, 2)]
        );
        assert_eq!(out.short, vec![(1, 5, 2)]);
        let none = concatenate(&[(&a[..], Some(0)), (&b[..], Some(1))]);
        assert_eq!(none.items, vec![10]);
        assert!(none.short.is_empty());
    }

    #[test]
    fn the_frequency_of_a_ritz_vector_is_its_rayleigh_quotient() {
        let (w2, f) = rayleigh_frequency(4.0 * std::f64::consts::PI.powi(2) * 9.0, 1.0);
        assert!((w2 - 36.0 * std::f64::consts::PI.powi(2)).abs() < 1e-12);
        assert!((f - 3.0).abs() < 1e-15, "{f}");
        assert_eq!(rayleigh_frequency(1.0, 0.0), (0.0, 0.0));
        assert_eq!(rayleigh_frequency(-1e-20, 1.0).1, 0.0);
    }
    /// Rayleigh–Ritz on a basis spanning the whole space gives the exact modes; on a
    /// two-vector basis of a 2-DOF chain the reduced problem's closed form.
    #[test]
    fn rayleigh_ritz_gives_the_modes_of_the_span() {
        // Two unit masses, springs k = 1 (wall–1) and 1 (1–2): ω² = (3 ∓ √5)/2.
        let k = vec![(0, 0, 2.0), (0, 1, -1.0), (1, 0, -1.0), (1, 1, 1.0)];
        let m = vec![(0, 0, 1.0), (1, 1, 1.0)];
        let km = Metric::new(2, &k).unwrap();
        let mm = Metric::new(2, &m).unwrap();
        // A skewed basis of the whole plane.
        let basis = vec![vec![1.0, 0.3], vec![0.2, 1.0]];
        let r = rayleigh_ritz(&km, &mm, &basis).unwrap();
        let exact = [(3.0 - 5f64.sqrt()) / 2.0, (3.0 + 5f64.sqrt()) / 2.0];
        for (w, e) in r.omega2.iter().zip(exact) {
            assert!((w - e).abs() < 1e-14, "{w} vs {e}");
        }
        for (phi, w) in r.shapes.iter().zip(&r.omega2) {
            assert!((mm.form(phi, phi).unwrap() - 1.0).abs() < 1e-14);
            assert!((km.form(phi, phi).unwrap() - w).abs() < 1e-14);
        }
        // One vector (1, 1): ω² = uᵀKu/uᵀMu = 1/2, the vector scaled to unit mass.
        let r = rayleigh_ritz(&km, &mm, &[vec![1.0, 1.0]]).unwrap();
        assert!((r.omega2[0] - 0.5).abs() < 1e-15);
        assert!((r.shapes[0][0].abs() - 0.5f64.sqrt()).abs() < 1e-15);
    }
}
