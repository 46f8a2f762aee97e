//! [`DenseStructure`]: generalized (modal) matrices, small n: diagonal (the usual modal
//! case, a fast path) or full (PROJ_MATR_BASE of a non-orthogonal basis), with faer's
//! dense Cholesky for M and for the implicit matrix, and modal damping ratios.

use super::error::{check_len, invalid, TransientError};
use super::structure::{LinearSolver, Structure};
use faer::linalg::triangular_solve::{
    solve_lower_triangular_in_place, solve_upper_triangular_in_place,
};
use faer::{Mat, MatMut, Par, Side};

/// A dense symmetric matrix: diagonal or full.
#[derive(Clone, Debug)]
pub enum DenseMatrix {
    Diagonal(Vec<f64>),
    Full(Mat<f64>),
}

impl DenseMatrix {
    /// A row-major n × n matrix: diagonal when every off-diagonal entry is zero (a basis
    /// orthogonal for it, the fast path), full otherwise.
    pub fn from_row_major(n: usize, values: &[f64]) -> DenseMatrix {
        let diagonal = (0..n).all(|i| (0..n).all(|j| i == j || values[i * n + j] == 0.0));
        if diagonal {
            DenseMatrix::Diagonal((0..n).map(|i| values[i * n + i]).collect())
        } else {
            DenseMatrix::Full(Mat::from_fn(n, n, |i, j| values[i * n + j]))
        }
    }

    fn n(&self) -> usize {
        match self {
            DenseMatrix::Diagonal(d) => d.len(),
            DenseMatrix::Full(m) => m.nrows(),
        }
    }

    fn apply(&self, x: &[f64], out: &mut [f64]) {
        match self {
            DenseMatrix::Diagonal(d) => {
                for ((o, di), xi) in out.iter_mut().zip(d).zip(x) {
                    *o = di * xi;
                }
            }
            DenseMatrix::Full(m) => {
                for (i, o) in out.iter_mut().enumerate() {
                    *o = (0..m.ncols()).map(|j| m[(i, j)] * x[j]).sum();
                }
            }
        }
    }

    fn diag(&self, i: usize) -> f64 {
        match self {
            DenseMatrix::Diagonal(d) => d[i],
            DenseMatrix::Full(m) => m[(i, i)],
        }
    }

    fn to_full(&self) -> Mat<f64> {
        match self {
            DenseMatrix::Diagonal(d) => {
                Mat::from_fn(d.len(), d.len(), |i, j| if i == j { d[i] } else { 0.0 })
            }
            DenseMatrix::Full(m) => m.clone(),
        }
    }

    fn check(&self, what: &str, n: usize) -> Result<(), TransientError> {
        check_len(what, self.n(), n)?;
        let ok = match self {
            DenseMatrix::Diagonal(d) => d.iter().all(|v| v.is_finite()),
            DenseMatrix::Full(m) => {
                m.ncols() == n && (0..n).all(|j| (0..n).all(|i| m[(i, j)].is_finite()))
            }
        };
        if ok {
            Ok(())
        } else {
            Err(invalid(what, "not square or not finite"))
        }
    }
}

/// Cholesky factor L (A = L Lᵀ) or a diagonal, solved without allocating.
enum Factor {
    Diagonal(Vec<f64>),
    Chol(Mat<f64>),
}

impl Factor {
    fn new(a: &DenseMatrix, what: &str) -> Result<Factor, TransientError> {
        let singular = || TransientError::Singular {
            what: format!("{what} (not positive definite)"),
        };
        match a {
            DenseMatrix::Diagonal(d) => {
                if d.iter().all(|&v| v > 0.0) {
                    Ok(Factor::Diagonal(d.iter().map(|v| 1.0 / v).collect()))
                } else {
                    Err(singular())
                }
            }
            DenseMatrix::Full(m) => {
                let llt = m.llt(Side::Lower).map_err(|_| singular())?;
                Ok(Factor::Chol(llt.L().to_owned()))
            }
        }
    }

    fn solve(&self, x: &mut [f64]) {
        match self {
            Factor::Diagonal(inv) => x.iter_mut().zip(inv).for_each(|(v, d)| *v *= d),
            Factor::Chol(l) => {
                let n = x.len();
                let mut rhs = MatMut::from_column_major_slice_mut(x, n, 1);
                solve_lower_triangular_in_place(l.as_ref(), rhs.as_mut(), Par::Seq);
                solve_upper_triangular_in_place(l.transpose(), rhs.as_mut(), Par::Seq);
            }
        }
    }
}

impl LinearSolver for Factor {
    fn solve(&mut self, x: &mut [f64]) -> Result<(), TransientError> {
        Factor::solve(self, x);
        Ok(())
    }
}

/// Generalized mass, stiffness and (optional) damping.
pub struct DenseStructure {
    mass: DenseMatrix,
    stiffness: DenseMatrix,
    damping: Option<DenseMatrix>,
    mass_factor: Factor,
}

impl DenseStructure {
    /// Any combination of diagonal and full matrices of the same size.
    pub fn new(
        mass: DenseMatrix,
        stiffness: DenseMatrix,
        damping: Option<DenseMatrix>,
    ) -> Result<DenseStructure, TransientError> {
        let n = mass.n();
        mass.check("MATR_MASS", n)?;
        stiffness.check("MATR_RIGI", n)?;
        if let Some(c) = &damping {
            c.check("MATR_AMOR", n)?;
        }
        let mass_factor = Factor::new(&mass, "MATR_MASS")?;
        Ok(DenseStructure {
            mass,
            stiffness,
            damping,
            mass_factor,
        })
    }

    /// The modal fast path: diagonal M, K and (optional) C.
    pub fn diagonal(
        mass: Vec<f64>,
        stiffness: Vec<f64>,
        damping: Option<Vec<f64>>,
    ) -> Result<DenseStructure, TransientError> {
        DenseStructure::new(
            DenseMatrix::Diagonal(mass),
            DenseMatrix::Diagonal(stiffness),
            damping.map(DenseMatrix::Diagonal),
        )
    }

    /// Full matrices (row i, column j), e.g. PROJ_MATR_BASE on a non-orthogonal basis.
    pub fn full(
        mass: Mat<f64>,
        stiffness: Mat<f64>,
        damping: Option<Mat<f64>>,
    ) -> Result<DenseStructure, TransientError> {
        DenseStructure::new(
            DenseMatrix::Full(mass),
            DenseMatrix::Full(stiffness),
            damping.map(DenseMatrix::Full),
        )
    }

    /// Replaces the damping by modal damping ratios ξ_i (AMOR_MODAL/AMOR_REDUIT): the
    /// diagonal c_i = 2 ξ_i √(k_ii m_ii) (= 2 ξ_i ω_i m_i for diagonal matrices).
    pub fn with_damping_ratios(mut self, ratios: &[f64]) -> Result<Self, TransientError> {
        let n = self.mass.n();
        check_len("AMOR_REDUIT", ratios.len(), n)?;
        let c = (0..n)
            .map(|i| {
                let (k, m) = (self.stiffness.diag(i), self.mass.diag(i));
                2.0 * ratios[i] * (k * m).max(0.0).sqrt()
            })
            .collect();
        self.damping = Some(DenseMatrix::Diagonal(c));
        Ok(self)
    }
}

fn combine(
    a: &DenseMatrix,
    wa: f64,
    b: &DenseMatrix,
    wb: f64,
    c: Option<&DenseMatrix>,
    wc: f64,
) -> DenseMatrix {
    let all_diag = matches!(a, DenseMatrix::Diagonal(_))
        && matches!(b, DenseMatrix::Diagonal(_))
        && c.is_none_or(|c| matches!(c, DenseMatrix::Diagonal(_)));
    let n = a.n();
    if all_diag {
        DenseMatrix::Diagonal(
            (0..n)
                .map(|i| wa * a.diag(i) + wb * b.diag(i) + c.map_or(0.0, |c| wc * c.diag(i)))
                .collect(),
        )
    } else {
        let (fa, fb) = (a.to_full(), b.to_full());
        let fc = c.map(DenseMatrix::to_full);
        DenseMatrix::Full(Mat::from_fn(n, n, |i, j| {
            wa * fa[(i, j)] + wb * fb[(i, j)] + fc.as_ref().map_or(0.0, |m| wc * m[(i, j)])
        }))
    }
}

impl Structure for DenseStructure {
    fn n(&self) -> usize {
        self.mass.n()
    }

    fn apply_stiffness(&self, q: &[f64], out: &mut [f64]) {
        self.stiffness.apply(q, out);
    }

    fn apply_damping(&self, v: &[f64], out: &mut [f64]) {
        match &self.damping {
            Some(c) => c.apply(v, out),
            None => out.iter_mut().for_each(|o| *o = 0.0),
        }
    }

    fn apply_mass(&self, a: &[f64], out: &mut [f64]) {
        self.mass.apply(a, out);
    }

    fn has_damping(&self) -> bool {
        self.damping.is_some()
    }

    fn solve_mass(&self, rhs: &mut [f64]) -> Result<(), TransientError> {
        self.mass_factor.solve(rhs);
        Ok(())
    }

    fn factor(
        &self,
        a_m: f64,
        a_c: f64,
        a_k: f64,
    ) -> Result<Box<dyn LinearSolver + '_>, TransientError> {
        let s = combine(
            &self.mass,
            a_m,
            &self.stiffness,
            a_k,
            self.damping.as_ref(),
            a_c,
        );
        Ok(Box::new(Factor::new(
            &s,
            "the implicit matrix a_m M + a_c C + a_k K",
        )?))
    }

    /// Exact: the dense generalized eigenproblem (K + K_extra) x = λ M x.
    fn max_eigenvalue(&self, extra: &dyn Fn(&[f64], &mut [f64])) -> Result<f64, TransientError> {
        let n = self.n();
        let mut a = Mat::<f64>::zeros(n, n);
        let mut e = vec![0.0; n];
        let mut col = vec![0.0; n];
        for j in 0..n {
            e.iter_mut().for_each(|x| *x = 0.0);
            e[j] = 1.0;
            self.stiffness.apply(&e, &mut col);
            extra(&e, &mut col);
            // Scale by M^{-1/2} on both sides below; first store K_total.
            for i in 0..n {
                a[(i, j)] = col[i];
            }
        }
        let c = match &self.mass_factor {
            Factor::Diagonal(inv) => Mat::from_fn(n, n, |i, j| {
                0.5 * (a[(i, j)] + a[(j, i)]) * (inv[i] * inv[j]).sqrt()
            }),
            Factor::Chol(l) => {
                let sym = Mat::from_fn(n, n, |i, j| 0.5 * (a[(i, j)] + a[(j, i)]));
                let mut x = sym;
                solve_lower_triangular_in_place(l.as_ref(), x.as_mut(), Par::Seq);
                let mut y = x.transpose().to_owned();
                solve_lower_triangular_in_place(l.as_ref(), y.as_mut(), Par::Seq);
                y
            }
        };
        let eig = c
            .self_adjoint_eigen(Side::Lower)
            .map_err(|e| TransientError::Singular {
                what: format!("the stability eigenproblem ({e:?})"),
            })?;
        Ok((0..n).map(|i| eig.S()[i]).fold(0.0, f64::max))
    }
}
