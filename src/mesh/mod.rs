//! Meshes: nodes, cells and named groups, and the readers of the formats we claim.

use serde::{Deserialize, Serialize};

/// Cell types, named as in Code_Aster.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub enum CellKind {
    Poi1,
    Seg2,
    Seg3,
    Tria3,
    Tria6,
    Quad4,
    Quad8,
    Tetra4,
    Hexa8,
    Penta6,
    Pyram5,
}

impl CellKind {
    /// Code_Aster name (`POI1`, `SEG2`, ...).
    pub fn aster_name(self) -> &'static str {
        match self {
            CellKind::Poi1 => "POI1",
            CellKind::Seg2 => "SEG2",
            CellKind::Seg3 => "SEG3",
            CellKind::Tria3 => "TRIA3",
            CellKind::Tria6 => "TRIA6",
            CellKind::Quad4 => "QUAD4",
            CellKind::Quad8 => "QUAD8",
            CellKind::Tetra4 => "TETRA4",
            CellKind::Hexa8 => "HEXA8",
            CellKind::Penta6 => "PENTA6",
            CellKind::Pyram5 => "PYRAM5",
        }
    }
    pub fn node_count(self) -> usize {
        match self {
            CellKind::Poi1 => 1,
            CellKind::Seg2 => 2,
            CellKind::Seg3 => 3,
            CellKind::Tria3 => 3,
            CellKind::Tria6 => 6,
            CellKind::Quad4 => 4,
            CellKind::Quad8 => 8,
            CellKind::Tetra4 => 4,
            CellKind::Hexa8 => 8,
            CellKind::Penta6 => 6,
            CellKind::Pyram5 => 5,
        }
    }
}

#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Node {
    pub name: String,
    /// Always three coordinates; a 2D mesh has z = 0.
    pub coords: [f64; 3],
}

#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Cell {
    pub name: String,
    pub kind: CellKind,
    /// Indices into `Mesh::nodes`.
    pub nodes: Vec<usize>,
}

/// A named set of node or cell indices, in definition order.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Group {
    pub name: String,
    pub members: Vec<usize>,
}

#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Mesh {
    /// Space dimension declared by the file (2 or 3).
    pub dim: usize,
    pub nodes: Vec<Node>,
    pub cells: Vec<Cell>,
    /// GROUP_NO: indices into `nodes`.
    pub node_groups: Vec<Group>,
    /// GROUP_MA: indices into `cells`.
    pub cell_groups: Vec<Group>,
}

impl Mesh {
    pub fn node_index(&self, name: &str) -> Option<usize> {
        self.nodes.iter().position(|n| n.name == name)
    }
    pub fn cell_index(&self, name: &str) -> Option<usize> {
        self.cells.iter().position(|c| c.name == name)
    }
    pub fn node_group(&self, name: &str) -> Option<&Group> {
        self.node_groups.iter().find(|g| g.name == name)
    }
    pub fn cell_group(&self, name: &str) -> Option<&Group> {
        self.cell_groups.iter().find(|g| g.name == name)
    }
}
