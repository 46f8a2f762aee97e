//! Kinematic conditions: AFFE_CHAR_CINE (MECA_IMPO) and AFFE_CHAR_MECA (DDL_IMPO); and
//! AFFE_CHAR_MECA's nodal forces (FORCE_NODALE), which ASSE_VECTEUR assembles.
//!
//! Both are applied by eliminating the blocked DOFs (Code_Aster dualises AFFE_CHAR_MECA
//! with Lagrange multipliers; for homogeneous conditions both give the same modes).
//! Imposed values are stored as given; modal analysis only uses which DOFs are blocked
//! (the operators warn when a value is nonzero).

use super::dof::Cmp;
use super::fe_model::Model;
use super::select::model_select_nodes;
use crate::error::{Error, Result};
use crate::mesh::select::Selection;
use crate::mesh::Mesh;
use serde::{Deserialize, Serialize};
use std::collections::HashMap;

#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub enum LoadKind {
    /// AFFE_CHAR_CINE: eliminated at assembly (ASSE_MATRICE CHAR_CINE).
    Cine,
    /// AFFE_CHAR_MECA: part of the numbering (NUME_DDL / CALC_MATR_ELEM CHARGE).
    Meca,
}

#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct BlockedDof {
    pub node: String,
    pub cmp: Cmp,
    pub value: f64,
}

/// A force (FX, FY, FZ) or moment (MX, MY, MZ) at a node, by the DOF it works on.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct NodalForce {
    pub node: String,
    pub cmp: Cmp,
    pub value: f64,
}

#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct KinematicLoad {
    pub kind: LoadKind,
    pub model: String,
    /// In definition order; a DOF given twice keeps its last value.
    pub blocked: Vec<BlockedDof>,
    /// FORCE_NODALE, in definition order; a DOF given twice keeps its last value. Absent
    /// in loads stored before forces were read.
    #[serde(default)]
    pub forces: Vec<NodalForce>,
    /// LIAISON_DDL, in definition order. Absent in loads stored before relations were read.
    #[serde(default)]
    pub relations: Vec<NodalRelation>,
}

/// One term of a linear relation: `coef` times component `cmp` of `node`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct RelationTerm {
    pub node: String,
    pub cmp: Cmp,
    pub coef: f64,
}

/// A linear relation between DOFs (LIAISON_DDL): Σ coef·u = rhs.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct NodalRelation {
    pub terms: Vec<RelationTerm>,
    pub rhs: f64,
}

/// One component imposed by a condition, and the keyword path that gave it.
#[derive(Clone, Debug, PartialEq)]
pub struct ImposedComponent {
    pub cmp: Cmp,
    pub value: f64,
    pub keyword: String,
}

/// One condition (an occurrence of MECA_IMPO or DDL_IMPO): components imposed on the
/// nodes of `on`, or every component the nodes carry blocked (`clamp`).
#[derive(Clone, Debug, PartialEq)]
pub struct Condition {
    pub on: Selection,
    /// Given components, in Code_Aster order.
    pub components: Vec<ImposedComponent>,
    /// Every component each node carries, at zero (a clamp).
    pub clamp: bool,
    /// Keyword path of the condition, which errors about a whole node name.
    pub keyword: String,
}

impl KinematicLoad {
    /// Build from the conditions, in order. Every component must be carried by the node
    /// in the model, as Code_Aster requires.
    pub fn build(
        kind: LoadKind,
        model_name: &str,
        model: &Model,
        mesh: &Mesh,
        conditions: &[Condition],
    ) -> Result<KinematicLoad> {
        let carried = model.node_components(mesh);
        let mut blocked: Vec<BlockedDof> = Vec::new();
        // (node index, component) -> position in `blocked`: TOUT='OUI' on a large mesh
        // must not scan the list for every DOF.
        let mut seen: HashMap<(usize, Cmp), usize> = HashMap::new();
        for cond in conditions {
            let nodes = model_select_nodes(mesh, &cond.on)?;
            let encastre = cond.clamp;
            let given: Vec<(Cmp, f64)> = cond.components.iter().map(|c| (c.cmp, c.value)).collect();
            let keyword_of = |c: Cmp| {
                cond.components
                    .iter()
                    .find(|g| g.cmp == c)
                    .map_or_else(|| cond.keyword.clone(), |g| g.keyword.clone())
            };
            // TOUT='OUI' means the model's nodes: nodes without DOFs and components a node
            // does not carry are skipped (a mixed DIS_T/DIS_TR model with TOUT, DRX=0), but
            // each component must exist somewhere. Explicit NOEUD/GROUP_NO/GROUP_MA
            // selections are strict, as Code_Aster's "component absent on node" error.
            let everywhere = cond.on.all;
            let mut used: Vec<Cmp> = Vec::new();
            for n in nodes {
                let Some(node) = mesh.nodes.get(n) else {
                    continue;
                };
                let Some(cmps) = carried.get(&n) else {
                    if everywhere {
                        continue;
                    }
                    return Err(Error::input(format!(
                        "node {} carries no DOF in model {model_name}",
                        node.name
                    ))
                    .keyword(cond.keyword.clone())
                    .hint("block only nodes of modelled cells"));
                };
                let mut these = given.clone();
                if encastre {
                    these.extend(cmps.iter().map(|&c| (c, 0.0)));
                }
                for (c, v) in these {
                    if !cmps.contains(&c) {
                        if everywhere {
                            continue;
                        }
                        return Err(Error::input(format!(
                            "component {c} does not exist on node {} in model {model_name}",
                            node.name
                        ))
                        .keyword(keyword_of(c))
                        .hint(format!(
                            "the node carries {}",
                            cmps.iter().map(|c| c.name()).collect::<Vec<_>>().join(" ")
                        )));
                    }
                    if !used.contains(&c) {
                        used.push(c);
                    }
                    if let Some(b) = seen.get(&(n, c)).and_then(|&i| blocked.get_mut(i)) {
                        b.value = v;
                    } else {
                        seen.insert((n, c), blocked.len());
                        blocked.push(BlockedDof {
                            node: node.name.clone(),
                            cmp: c,
                            value: v,
                        });
                    }
                }
            }
            if let Some((c, _)) = given.iter().find(|(c, _)| !used.contains(c)) {
                return Err(Error::input(format!(
                    "component {c} exists on none of the selected nodes in model {model_name}"
                ))
                .keyword(keyword_of(*c)));
            }
        }
        Ok(KinematicLoad {
            kind,
            model: model_name.to_string(),
            blocked,
            forces: Vec::new(),
            relations: Vec::new(),
        })
    }

    /// FORCE_NODALE's occurrences (each a [`Condition`] whose components are the DOFs the
    /// forces work on: FX on DX, ..., MZ on DRZ) as forces at nodes. As Code_Aster, a
    /// component must exist on every node selected explicitly; a later occurrence
    /// overrides an earlier one at the same node and DOF.
    pub fn nodal_forces(
        model: &Model,
        mesh: &Mesh,
        occurrences: &[Condition],
    ) -> Result<Vec<NodalForce>> {
        let carried = model.node_components(mesh);
        let mut forces: Vec<NodalForce> = Vec::new();
        let mut seen: HashMap<(usize, Cmp), usize> = HashMap::new();
        for cond in occurrences {
            for n in model_select_nodes(mesh, &cond.on)? {
                let (Some(node), Some(cmps)) = (mesh.nodes.get(n), carried.get(&n)) else {
                    if cond.on.all {
                        continue;
                    }
                    return Err(Error::input(format!(
                        "node {} carries no DOF in the model: a force there acts on nothing",
                        mesh.nodes.get(n).map_or("?", |x| x.name.as_str())
                    ))
                    .keyword(cond.keyword.clone()));
                };
                for c in &cond.components {
                    if !cmps.contains(&c.cmp) {
                        if cond.on.all {
                            continue;
                        }
                        return Err(Error::input(format!(
                            "node {} has no DOF {} for this force in the model",
                            node.name, c.cmp
                        ))
                        .keyword(c.keyword.clone()));
                    }
                    if let Some(f) = seen.get(&(n, c.cmp)).and_then(|&i| forces.get_mut(i)) {
                        f.value = c.value;
                    } else {
                        seen.insert((n, c.cmp), forces.len());
                        forces.push(NodalForce {
                            node: node.name.clone(),
                            cmp: c.cmp,
                            value: c.value,
                        });
                    }
                }
            }
        }
        Ok(forces)
    }

    /// Blocked DOFs with a nonzero imposed value (ignored by modal analysis).
    pub fn nonzero(&self) -> Vec<&BlockedDof> {
        self.blocked.iter().filter(|b| b.value != 0.0).collect()
    }
}
