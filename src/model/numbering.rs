//! DOF numbering (NUME_DDL): every DOF carried by the model's elements, ordered by node
//! (mesh order) then component (DX DY DZ DRX DRY DRZ), and which of them AFFE_CHAR_MECA
//! loads eliminate.

use super::dof::Cmp;
use super::elem::ElemMatrices;
use super::fe_model::Model;
use super::loads::KinematicLoad;
use super::relations::DofRelation;
use crate::error::{Error, Result};
use crate::mesh::Mesh;
use serde::{Deserialize, Serialize};
use std::collections::{BTreeMap, BTreeSet, HashMap};

/// Why element matrices give no numbering, in the model's terms; the operator names the
/// keyword (NUME_DDL: MATR_RIGI).
#[derive(Clone, Debug)]
pub enum NumberingError {
    /// No element matrix at all.
    NoMatrix,
    /// Element matrices of two models.
    DifferentModels(String, String),
    Other(Error),
}

impl std::fmt::Display for NumberingError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            NumberingError::NoMatrix => write!(f, "no element matrix given"),
            NumberingError::DifferentModels(a, b) => {
                write!(
                    f,
                    "element matrices come from different models ({a} and {b})"
                )
            }
            NumberingError::Other(e) => write!(f, "{e}"),
        }
    }
}

/// The error as it stands, without a keyword (operators name theirs).
impl From<NumberingError> for Error {
    fn from(e: NumberingError) -> Self {
        match e {
            NumberingError::Other(e) => e,
            e => Error::input(e.to_string()),
        }
    }
}

#[derive(Clone, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub struct NumberedDof {
    pub node: String,
    pub cmp: Cmp,
}

#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct DofNumbering {
    pub mesh: String,
    pub model: String,
    pub dofs: Vec<NumberedDof>,
    /// Eliminated by AFFE_CHAR_MECA (DDL_IMPO); same length as `dofs`.
    pub eliminated: Vec<bool>,
    /// AFFE_CHAR_MECA's linear relations (LIAISON_DDL), in load order.
    #[serde(default)]
    pub relations: Vec<DofRelation>,
}

impl DofNumbering {
    pub fn len(&self) -> usize {
        self.dofs.len()
    }
    pub fn is_empty(&self) -> bool {
        self.dofs.is_empty()
    }

    pub fn index_of(&self, node: &str, cmp: Cmp) -> Option<usize> {
        self.dofs
            .iter()
            .position(|d| d.node == node && d.cmp == cmp)
    }

    /// (node, component) -> index, for assembly.
    pub fn index_map(&self) -> HashMap<(&str, Cmp), usize> {
        self.dofs
            .iter()
            .enumerate()
            .map(|(i, d)| ((d.node.as_str(), d.cmp), i))
            .collect()
    }

    /// Numbering of the DOFs in `carried` (node index -> components).
    fn from_carried(
        mesh_name: &str,
        model_name: &str,
        mesh: &Mesh,
        carried: &BTreeMap<usize, BTreeSet<Cmp>>,
        loads: &[&KinematicLoad],
    ) -> Result<DofNumbering> {
        let mut dofs = Vec::new();
        for (&n, cmps) in carried {
            let node = mesh.nodes.get(n).ok_or_else(|| {
                Error::internal(format!("node index {n} is outside mesh {mesh_name}"))
            })?;
            for &cmp in cmps {
                dofs.push(NumberedDof {
                    node: node.name.clone(),
                    cmp,
                });
            }
        }
        let mut num = DofNumbering {
            mesh: mesh_name.to_string(),
            model: model_name.to_string(),
            eliminated: vec![false; dofs.len()],
            dofs,
            relations: Vec::new(),
        };
        let elim = num.mark(loads)?;
        num.eliminated = elim;
        num.relations = num.relations_of(loads)?;
        Ok(num)
    }

    /// NUME_DDL(MODELE=, CHARGE=).
    pub fn from_model(
        model_name: &str,
        model: &Model,
        mesh: &Mesh,
        loads: &[&KinematicLoad],
    ) -> Result<DofNumbering> {
        let carried = model.node_components(mesh);
        Self::from_carried(&model.mesh, model_name, mesh, &carried, loads)
    }

    /// NUME_DDL(MATR_RIGI=...): the DOFs of the element matrices, plus the loads they were
    /// computed with.
    pub fn from_elem_matrices(
        mesh: &Mesh,
        mats: &[&ElemMatrices],
    ) -> Result<DofNumbering, NumberingError> {
        let first = mats.first().ok_or(NumberingError::NoMatrix)?;
        let mut carried: BTreeMap<usize, BTreeSet<Cmp>> = BTreeMap::new();
        for m in mats {
            if m.model != first.model {
                return Err(NumberingError::DifferentModels(
                    first.model.clone(),
                    m.model.clone(),
                ));
            }
            for e in &m.elements {
                for &(n, c) in &e.dofs {
                    carried.entry(n).or_default().insert(c);
                }
            }
        }
        let loads: Vec<&KinematicLoad> = mats.iter().flat_map(|m| m.loads.iter()).collect();
        Self::from_carried(&first.mesh, &first.model, mesh, &carried, &loads)
            .map_err(NumberingError::Other)
    }

    /// Eliminated flags of this numbering combined with the DOFs blocked by `loads`.
    /// Every blocked DOF must be in the numbering.
    pub fn mark(&self, loads: &[&KinematicLoad]) -> Result<Vec<bool>> {
        let map = self.index_map();
        let mut elim = self.eliminated.clone();
        for load in loads {
            for b in &load.blocked {
                let i = map.get(&(b.node.as_str(), b.cmp)).ok_or_else(|| {
                    Error::input(format!(
                        "blocked DOF {} of node {} is not in the numbering of model {}",
                        b.cmp, b.node, self.model
                    ))
                    .hint("the load must be defined on the model the matrices come from")
                })?;
                if let Some(e) = elim.get_mut(*i) {
                    *e = true;
                }
            }
        }
        Ok(elim)
    }

    /// The linear relations of `loads` on this numbering's DOFs. Every DOF of a relation
    /// must be in the numbering.
    fn relations_of(&self, loads: &[&KinematicLoad]) -> Result<Vec<DofRelation>> {
        let map = self.index_map();
        let mut out = Vec::new();
        for load in loads {
            for rel in &load.relations {
                let terms = rel
                    .terms
                    .iter()
                    .map(|t| {
                        map.get(&(t.node.as_str(), t.cmp))
                            .map(|&i| (i, t.coef))
                            .ok_or_else(|| {
                                Error::input(format!(
                                    "DOF {} of node {} in a LIAISON_DDL relation is not in the numbering of model {}",
                                    t.cmp, t.node, self.model
                                ))
                                .hint("the load must be defined on the model the matrices come from")
                            })
                    })
                    .collect::<Result<Vec<_>>>()?;
                out.push(DofRelation {
                    terms,
                    rhs: rel.rhs,
                });
            }
        }
        Ok(out)
    }
}
