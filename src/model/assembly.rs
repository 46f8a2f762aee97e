//! Assembly (ASSE_MATRICE): element matrices -> global sparse triplets on a numbering,
//! with the DOFs eliminated by AFFE_CHAR_MECA (numbering) and AFFE_CHAR_CINE.

use super::elem::{ElemMatrices, MatrixKind};
use super::loads::KinematicLoad;
use super::numbering::DofNumbering;
use crate::error::{Error, Result};
use crate::linalg::sparse;
use crate::mesh::Mesh;
use faer::sparse::SparseColMat;

#[derive(Clone, Debug, PartialEq)]
pub struct AssembledMatrix {
    pub numbering: DofNumbering,
    pub kind: MatrixKind,
    /// (row, col, value) in the full numbering, one entry per position (duplicates summed),
    /// sorted by (row, col); both triangles stored.
    pub triplets: Vec<(usize, usize, f64)>,
    /// DOFs eliminated: the numbering's (AFFE_CHAR_MECA) and AFFE_CHAR_CINE's.
    pub eliminated: Vec<bool>,
}

impl AssembledMatrix {
    pub fn size(&self) -> usize {
        self.numbering.len()
    }

    /// Full indices of the free DOFs, in order: reduced index i is full index
    /// `free_dofs()[i]`.
    pub fn free_dofs(&self) -> Vec<usize> {
        (0..self.size())
            .filter(|&i| !self.eliminated.get(i).copied().unwrap_or(false))
            .collect()
    }

    /// Reduced index of the DOF (node, component), if it exists and is free.
    pub fn reduced_index_of(&self, node: &str, cmp: super::Cmp) -> Option<usize> {
        self.reduced_index(self.numbering.index_of(node, cmp)?)
    }

    /// Reduced index of the DOF of full index `full`, if it exists and is free.
    pub fn reduced_index(&self, full: usize) -> Option<usize> {
        if full >= self.size() || self.eliminated.get(full).copied().unwrap_or(false) {
            return None;
        }
        Some(self.eliminated.iter().take(full).filter(|e| !**e).count())
    }

    /// The values of a full-numbering vector (e.g. a stored mode shape) on the free DOFs,
    /// in reduced order; `None` if it is shorter than the numbering.
    pub fn restrict(&self, full: &[f64]) -> Option<Vec<f64>> {
        self.free_dofs()
            .iter()
            .map(|&i| full.get(i).copied())
            .collect()
    }

    /// A vector on the free DOFs (e.g. a mode shape) written in the full numbering, zero on
    /// the eliminated DOFs. Errors if its length is not the number of free DOFs.
    pub fn expand(&self, reduced: &[f64]) -> Result<Vec<f64>> {
        let free = self.free_dofs();
        if reduced.len() != free.len() {
            return Err(Error::internal(format!(
                "vector of {} values for {} free DOFs",
                reduced.len(),
                free.len()
            )));
        }
        let mut full = vec![0.0; self.size()];
        for (&i, &v) in free.iter().zip(reduced) {
            if let Some(x) = full.get_mut(i) {
                *x = v;
            }
        }
        Ok(full)
    }

    /// The matrix restricted to the free DOFs.
    pub fn reduced(&self) -> Result<SparseColMat<usize, f64>> {
        sparse::reduced(self.size(), &self.triplets, &self.eliminated)
    }

    /// The full matrix (eliminated DOFs included).
    pub fn full(&self) -> Result<SparseColMat<usize, f64>> {
        sparse::from_triplets(self.size(), self.size(), &self.triplets)
    }
}

/// Why element matrices cannot be assembled, in the model's terms; the operator names
/// the keyword (ASSE_MATRICE: MATR_ELEM, NUME_DDL).
#[derive(Clone, Debug)]
pub enum AssemblyError {
    /// No element matrix at all.
    NoMatrix,
    /// Element matrices of two kinds (a stiffness and a mass).
    MixedKinds(MatrixKind, MatrixKind),
    /// A DOF of an element matrix that the numbering does not have.
    NotNumbered {
        node: String,
        cmp: super::dof::Cmp,
        model: String,
    },
    Other(Error),
}

impl std::fmt::Display for AssemblyError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            AssemblyError::NoMatrix => write!(f, "no element matrix given"),
            AssemblyError::MixedKinds(a, b) => write!(
                f,
                "cannot add {} and {} element matrices",
                a.aster_name(),
                b.aster_name()
            ),
            AssemblyError::NotNumbered { node, cmp, model } => write!(
                f,
                "DOF {cmp} of node {node} is not in the numbering (model {model})"
            ),
            AssemblyError::Other(e) => write!(f, "{e}"),
        }
    }
}

/// The error as it stands, without a keyword (operators name theirs).
impl From<AssemblyError> for Error {
    fn from(e: AssemblyError) -> Self {
        match e {
            AssemblyError::Other(e) => e,
            e => Error::input(e.to_string()),
        }
    }
}

/// Assemble element matrices (all of the same kind) on `numbering`; `cine` are the
/// AFFE_CHAR_CINE loads whose DOFs are eliminated on top of the numbering's.
pub fn assemble(
    numbering: &DofNumbering,
    mesh: &Mesh,
    mats: &[&ElemMatrices],
    cine: &[&KinematicLoad],
) -> Result<AssembledMatrix, AssemblyError> {
    let first = mats.first().ok_or(AssemblyError::NoMatrix)?;
    let kind = first.kind;
    if let Some(other) = mats.iter().find(|m| m.kind != kind) {
        return Err(AssemblyError::MixedKinds(kind, other.kind));
    }
    let map = numbering.index_map();
    let mut raw = Vec::new();
    for m in mats {
        for e in &m.elements {
            let mut idx = Vec::with_capacity(e.dofs.len());
            for &(n, c) in &e.dofs {
                let name = mesh.nodes.get(n).map(|x| x.name.as_str()).unwrap_or("?");
                let i = map
                    .get(&(name, c))
                    .ok_or_else(|| AssemblyError::NotNumbered {
                        node: name.to_string(),
                        cmp: c,
                        model: numbering.model.clone(),
                    })?;
                idx.push(*i);
            }
            let n = idx.len();
            for (a, &r) in idx.iter().enumerate() {
                for (b, &c) in idx.iter().enumerate() {
                    let v = e.values.get(a * n + b).copied().unwrap_or(0.0);
                    raw.push((r, c, v));
                }
            }
        }
    }
    let eliminated = numbering.mark(cine).map_err(AssemblyError::Other)?;
    Ok(AssembledMatrix {
        numbering: numbering.clone(),
        kind,
        triplets: sparse::consolidate(raw),
        eliminated,
    })
}
