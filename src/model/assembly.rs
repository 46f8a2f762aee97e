//! Assembly (ASSE_MATRICE): element matrices -> global sparse triplets on a numbering,
//! with the DOFs eliminated by AFFE_CHAR_MECA (numbering) and AFFE_CHAR_CINE.

use super::elem::{ElemMatrices, MatrixKind};
use super::loads::KinematicLoad;
use super::numbering::DofNumbering;
use super::relations::Dependence;
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
    /// The DOFs the numbering's linear relations (LIAISON_DDL) express in terms of the
    /// free ones; decided once here, from the relations and `eliminated`.
    dependence: Dependence,
}

impl AssembledMatrix {
    pub fn new(
        numbering: DofNumbering,
        kind: MatrixKind,
        triplets: Vec<(usize, usize, f64)>,
        eliminated: Vec<bool>,
    ) -> AssembledMatrix {
        let dependence = Dependence::build(&eliminated, &numbering.relations);
        AssembledMatrix {
            numbering,
            kind,
            triplets,
            eliminated,
            dependence,
        }
    }

    pub fn size(&self) -> usize {
        self.numbering.len()
    }

    /// Whether `other` is assembled on the same DOFs, blocked DOFs and relations (two
    /// matrices of one problem).
    pub fn same_dofs(&self, other: &AssembledMatrix) -> bool {
        self.numbering.dofs == other.numbering.dofs
            && self.eliminated == other.eliminated
            && self.dependence == other.dependence
    }

    /// The DOFs LIAISON_DDL relations express in terms of the free ones.
    pub fn dependence(&self) -> &Dependence {
        &self.dependence
    }

    /// An error for operators that work on the free DOFs of the physical numbering and
    /// write their results per free DOF, which do not take LIAISON_DDL relations yet.
    pub fn refuse_relations(&self, operator: &str) -> Result<()> {
        if self.dependence.is_empty() {
            return Ok(());
        }
        Err(Error::input(format!(
            "the matrices carry LIAISON_DDL relations, which {operator} does not take on the physical DOFs"
        ))
        .hint("relations are supported by CALC_MODES and the modal route: project on the modes (PROJ_MATR_BASE) and integrate with DYNA_VIBRA BASE_CALCUL='GENE'"))
    }

    /// An error naming `keyword` if this is a damping matrix (AMOR_MECA) given where a
    /// stiffness or a mass is read (MATR_RIGI, MATR_MASS). A stiffness given as a mass, or
    /// the reverse, is let through: Code_Aster files do that on purpose (a geometric
    /// stiffness as the "mass" of a buckling problem).
    pub fn refuse_damping(&self, name: &str, keyword: &str) -> Result<()> {
        if self.kind != MatrixKind::AmorMeca {
            return Ok(());
        }
        Err(Error::input(format!(
            "{name} is a damping matrix (OPTION='AMOR_MECA'), not a stiffness or a mass"
        ))
        .keyword(keyword)
        .hint("give the RIGI_MECA or MASS_MECA matrix here; the damping goes to DYNA_VIBRA's MATR_AMOR (or PROJ_MATR_BASE for a modal basis)"))
    }

    /// Full indices of the free DOFs (neither blocked nor expressed by a relation), in
    /// order: reduced index i is full index `free_dofs()[i]`.
    pub fn free_dofs(&self) -> Vec<usize> {
        (0..self.size()).filter(|&i| self.is_free(i)).collect()
    }

    fn is_free(&self, i: usize) -> bool {
        !self.eliminated.get(i).copied().unwrap_or(false) && !self.dependence.is_dependent(i)
    }

    /// Reduced index of the DOF (node, component), if it exists and is free.
    pub fn reduced_index_of(&self, node: &str, cmp: super::Cmp) -> Option<usize> {
        self.reduced_index(self.numbering.index_of(node, cmp)?)
    }

    /// Reduced index of the DOF of full index `full`, if it exists and is free.
    pub fn reduced_index(&self, full: usize) -> Option<usize> {
        if full >= self.size() || !self.is_free(full) {
            return None;
        }
        Some((0..full).filter(|&i| self.is_free(i)).count())
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
    /// the eliminated DOFs, the DOFs of LIAISON_DDL relations from their expressions.
    /// Errors if its length is not the number of free DOFs.
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
        self.dependence.complete(&mut full);
        Ok(full)
    }

    /// The free DOFs and, per DOF of the numbering, its reduced index (None: blocked or
    /// dependent).
    fn reduction(&self) -> (Vec<usize>, Vec<Option<usize>>) {
        let free = self.free_dofs();
        let mut map = vec![None; self.size()];
        for (r, &i) in free.iter().enumerate() {
            if let Some(m) = map.get_mut(i) {
                *m = Some(r);
            }
        }
        (free, map)
    }

    /// A linear function of the displacement given as a row r over the numbering (rᵀu),
    /// as a row over the free DOFs: Tᵀr, so that rᵀ(T·q) = (Tᵀr)ᵀq. Without relations, r
    /// on the free DOFs.
    pub fn row_on_free(&self, full: &[f64]) -> Vec<f64> {
        let (free, map) = self.reduction();
        let mut out = vec![0.0; free.len()];
        for (i, &ri) in full.iter().enumerate().filter(|(_, v)| **v != 0.0) {
            let terms: Vec<(usize, f64)> = match self.dependence.expression(i) {
                Some(expr) => expr.to_vec(),
                None => vec![(i, 1.0)],
            };
            for (j, t) in terms {
                if let Some(o) = map.get(j).copied().flatten().and_then(|r| out.get_mut(r)) {
                    *o += t * ri;
                }
            }
        }
        out
    }

    /// The matrix on the free DOFs: its rows and columns of blocked DOFs removed and,
    /// with LIAISON_DDL relations, TᵀAT (u = T·q, module `relations`).
    pub fn reduced(&self) -> Result<SparseColMat<usize, f64>> {
        if self.dependence.is_empty() {
            return sparse::reduced(self.size(), &self.triplets, &self.eliminated);
        }
        let (free, map) = self.reduction();
        let t = self.dependence.transform(&self.triplets, &map);
        sparse::from_triplets(free.len(), free.len(), &t)
    }

    /// [`Self::reduced`] as sorted triplets, one per nonzero position (both triangles).
    pub fn reduced_triplets(&self) -> Result<Vec<(usize, usize, f64)>> {
        let a = self.reduced()?;
        let mut out = Vec::new();
        for j in 0..a.ncols() {
            let rows = a.symbolic().row_idx_of_col_raw(j);
            let vals = a.val_of_col(j);
            for (&i, &v) in rows.iter().zip(vals) {
                out.push((i, j, v));
            }
        }
        out.sort_by_key(|e| (e.0, e.1));
        Ok(out)
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
    Ok(AssembledMatrix::new(
        numbering.clone(),
        kind,
        sparse::consolidate(raw),
        eliminated,
    ))
}
