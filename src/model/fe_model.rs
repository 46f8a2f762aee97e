//! The finite element model (AFFE_MODELE): which modelisation each cell carries.

use super::dof::Cmp;
use super::select::model_select_cells;
use crate::error::{Error, Result};
use crate::mesh::select::Selection;
use crate::mesh::{Cell, CellKind, Mesh};
use serde::{Deserialize, Serialize};
use std::collections::{BTreeMap, BTreeSet};

/// Mechanical modelisations we support (Code_Aster names in [`Modelisation::aster_name`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub enum Modelisation {
    /// DIS_T: discrete element, 3 translations per node (POI1, SEG2).
    DisT,
    /// DIS_TR: discrete element, 3 translations and 3 rotations per node (POI1, SEG2).
    DisTr,
    /// 2D_DIS_T: discrete element in the plane, DX DY (POI1, SEG2).
    Dis2dT,
    /// POU_D_E: 3D Euler-Bernoulli beam (SEG2).
    PouDE,
    /// BARRE: truss bar, axial stiffness only (SEG2).
    Barre,
}

impl Modelisation {
    pub const NAMES: [&'static str; 5] = ["DIS_T", "DIS_TR", "2D_DIS_T", "POU_D_E", "BARRE"];

    pub fn parse(name: &str) -> Option<Modelisation> {
        Some(match name {
            "DIS_T" => Modelisation::DisT,
            "DIS_TR" => Modelisation::DisTr,
            "2D_DIS_T" => Modelisation::Dis2dT,
            "POU_D_E" => Modelisation::PouDE,
            "BARRE" => Modelisation::Barre,
            _ => return None,
        })
    }

    pub fn aster_name(self) -> &'static str {
        match self {
            Modelisation::DisT => "DIS_T",
            Modelisation::DisTr => "DIS_TR",
            Modelisation::Dis2dT => "2D_DIS_T",
            Modelisation::PouDE => "POU_D_E",
            Modelisation::Barre => "BARRE",
        }
    }

    /// Components carried by every node of an element.
    pub fn components(self) -> &'static [Cmp] {
        match self {
            Modelisation::DisT | Modelisation::Barre => &[Cmp::Dx, Cmp::Dy, Cmp::Dz],
            Modelisation::Dis2dT => &[Cmp::Dx, Cmp::Dy],
            Modelisation::DisTr | Modelisation::PouDE => &Cmp::ALL,
        }
    }

    /// Cell kinds this modelisation has an element for.
    pub fn cell_kinds(self) -> &'static [CellKind] {
        match self {
            Modelisation::DisT | Modelisation::DisTr | Modelisation::Dis2dT => {
                &[CellKind::Poi1, CellKind::Seg2]
            }
            Modelisation::PouDE | Modelisation::Barre => &[CellKind::Seg2],
        }
    }

    pub fn is_discrete(self) -> bool {
        matches!(
            self,
            Modelisation::DisT | Modelisation::DisTr | Modelisation::Dis2dT
        )
    }
}

#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct ModelElement {
    /// Index into `Mesh::cells`.
    pub cell: usize,
    pub modelisation: Modelisation,
}

#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Model {
    /// Name of the mesh concept.
    pub mesh: String,
    /// One element per modelled cell, sorted by cell index.
    pub elements: Vec<ModelElement>,
    /// Point cells of the model itself, one per node given to AFFE_MODELE by GROUP_NO or
    /// NOEUD (Code_Aster 13.x's "late" cells: how 13.x files put discrete elements on
    /// nodes that have no POI1 cell). Point cell k is cell `mesh_cells + k` of the mesh
    /// as [`Model::extend_mesh`] completes it.
    #[serde(default)]
    pub point_cells: Vec<usize>,
    /// Number of cells of the mesh when the model was built.
    #[serde(default)]
    pub mesh_cells: usize,
}

/// Name given to the model's own point cell on `node` (for messages; no mesh cell can be
/// named so, since mesh names have no parentheses).
pub fn point_cell_name(node: &str) -> String {
    format!("POI1({node})")
}

/// One assignment of AFFE_MODELE: a modelisation on some cells, or (Code_Aster 13.x) on
/// nodes when `on` names nodes (discrete modelisations only: the operator checks it).
#[derive(Clone, Debug, PartialEq)]
pub struct ModelAssignment {
    pub modelisation: Modelisation,
    pub on: Selection,
    /// Keyword path of the modelisation, which errors about the assignment name.
    pub keyword: String,
}

/// A model being built, one assignment after another (the operator reads each from its
/// occurrence just before it is assigned, so errors come in the user's order).
pub struct ModelBuilder<'m> {
    mesh_name: String,
    mesh: &'m Mesh,
    by_cell: BTreeMap<usize, Modelisation>,
    point_cells: Vec<usize>,
}

impl<'m> ModelBuilder<'m> {
    pub fn new(mesh_name: &str, mesh: &'m Mesh) -> Self {
        ModelBuilder {
            mesh_name: mesh_name.to_string(),
            mesh,
            by_cell: BTreeMap::new(),
            point_cells: Vec::new(),
        }
    }

    /// A later assignment overrides an earlier one on the same cell. As in Code_Aster,
    /// cells whose type has no element for the modelisation are skipped (the whole mesh
    /// when it mixes cell types), but an assignment that reaches no cell is an error.
    pub fn assign(&mut self, a: &ModelAssignment) -> Result<()> {
        let (mesh, m) = (self.mesh, a.modelisation);
        if a.on.names_nodes() {
            // 13.x: elements on nodes, carried by point cells of the model.
            for n in crate::mesh::select::select_nodes(mesh, &a.on.nodes_only())? {
                let k = match self.point_cells.iter().position(|&p| p == n) {
                    Some(k) => k,
                    None => {
                        self.point_cells.push(n);
                        self.point_cells.len() - 1
                    }
                };
                self.by_cell.insert(mesh.cells.len() + k, m);
            }
            return Ok(());
        }
        let cells = model_select_cells(mesh, &a.on)?;
        let mut assigned = 0;
        for c in cells {
            let Some(cell) = mesh.cells.get(c) else {
                continue;
            };
            if m.cell_kinds().contains(&cell.kind) {
                self.by_cell.insert(c, m);
                assigned += 1;
            }
        }
        if assigned == 0 {
            let kinds: Vec<&str> = m.cell_kinds().iter().map(|k| k.aster_name()).collect();
            return Err(Error::input(format!(
                "{} assigned no element: none of the selected cells is a {}",
                m.aster_name(),
                kinds.join(" or ")
            ))
            .keyword(a.keyword.clone()));
        }
        Ok(())
    }

    pub fn finish(self) -> Model {
        Model {
            mesh: self.mesh_name,
            elements: self
                .by_cell
                .into_iter()
                .map(|(cell, modelisation)| ModelElement { cell, modelisation })
                .collect(),
            point_cells: self.point_cells,
            mesh_cells: self.mesh.cells.len(),
        }
    }
}

impl Model {
    /// The model of `affe`, assigned in order (see [`ModelBuilder::assign`]).
    pub fn build(mesh_name: &str, mesh: &Mesh, affe: &[ModelAssignment]) -> Result<Model> {
        let mut b = ModelBuilder::new(mesh_name, mesh);
        for a in affe {
            b.assign(a)?;
        }
        Ok(b.finish())
    }

    /// Add the model's own point cells (see [`Model::point_cells`]) to its mesh, so that
    /// every element's cell index is a cell of `mesh`.
    pub fn extend_mesh(&self, mesh: &mut Mesh) -> Result<()> {
        if self.point_cells.is_empty() {
            return Ok(());
        }
        if mesh.cells.len() != self.mesh_cells {
            return Err(Error::internal(format!(
                "mesh {} has {} cells, the model was built on {}",
                self.mesh,
                mesh.cells.len(),
                self.mesh_cells
            )));
        }
        for &n in &self.point_cells {
            let node = mesh.nodes.get(n).ok_or_else(|| {
                Error::internal(format!(
                    "model point cell on node index {n}, not in mesh {}",
                    self.mesh
                ))
            })?;
            let name = point_cell_name(&node.name);
            mesh.cells.push(Cell {
                name,
                kind: CellKind::Poi1,
                nodes: vec![n],
            });
        }
        Ok(())
    }

    pub fn element_of(&self, cell: usize) -> Option<&ModelElement> {
        self.elements
            .binary_search_by_key(&cell, |e| e.cell)
            .ok()
            .and_then(|i| self.elements.get(i))
    }

    /// Components carried by each node of the model (node index -> components).
    pub fn node_components(&self, mesh: &Mesh) -> BTreeMap<usize, BTreeSet<Cmp>> {
        let mut out: BTreeMap<usize, BTreeSet<Cmp>> = BTreeMap::new();
        for e in &self.elements {
            if let Some(cell) = mesh.cells.get(e.cell) {
                for &n in &cell.nodes {
                    out.entry(n)
                        .or_default()
                        .extend(e.modelisation.components().iter().copied());
                }
            }
        }
        out
    }
}
