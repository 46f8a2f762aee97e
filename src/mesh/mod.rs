//! Meshes: nodes, cells and named groups, and the readers of the formats we claim.

pub mod aster;
pub mod check;
pub mod edit;
pub mod gmsh;
pub mod med;
pub mod med_write;
pub mod select;
pub mod transform;

use crate::error::Result;
use serde::{Deserialize, Serialize};
use std::path::Path;

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
    /// The kind a Code_Aster name (`SEG2`, case-insensitive) stands for.
    pub fn from_aster_name(name: &str) -> Option<CellKind> {
        CellKind::ALL
            .iter()
            .copied()
            .find(|k| k.aster_name().eq_ignore_ascii_case(name))
    }
    /// Every kind, in declaration order.
    pub const ALL: [CellKind; 11] = [
        CellKind::Poi1,
        CellKind::Seg2,
        CellKind::Seg3,
        CellKind::Tria3,
        CellKind::Tria6,
        CellKind::Quad4,
        CellKind::Quad8,
        CellKind::Tetra4,
        CellKind::Hexa8,
        CellKind::Penta6,
        CellKind::Pyram5,
    ];
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

impl Mesh {
    /// One line: node and cell counts, cells per type, group counts.
    pub fn summary(&self) -> String {
        let mut per_kind: Vec<(CellKind, usize)> = Vec::new();
        for c in &self.cells {
            match per_kind.iter_mut().find(|(k, _)| *k == c.kind) {
                Some((_, n)) => *n += 1,
                None => per_kind.push((c.kind, 1)),
            }
        }
        let kinds: Vec<String> = per_kind
            .iter()
            .map(|(k, n)| format!("{} {n}", k.aster_name()))
            .collect();
        format!(
            "{} nodes, {} cells ({}), {} GROUP_MA, {} GROUP_NO, dimension {}",
            self.nodes.len(),
            self.cells.len(),
            kinds.join(", "),
            self.cell_groups.len(),
            self.node_groups.len(),
            self.dim
        )
    }

    /// The nodes of `cells`, each once, in order of first appearance.
    pub fn nodes_of_cells(&self, cells: &[usize]) -> Vec<usize> {
        let mut seen = vec![false; self.nodes.len()];
        let mut out = Vec::new();
        for &c in cells {
            if let Some(cell) = self.cells.get(c) {
                for &n in &cell.nodes {
                    if let Some(s) = seen.get_mut(n) {
                        if !*s {
                            *s = true;
                            out.push(n);
                        }
                    }
                }
            }
        }
        out
    }
}

/// Mesh file formats (LIRE_MAILLAGE/FORMAT).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MeshFormat {
    Aster,
    Gmsh,
    Med,
}

impl MeshFormat {
    /// From the FORMAT keyword value (`ASTER`, `GMSH`, `MED`).
    pub fn from_keyword(s: &str) -> Option<MeshFormat> {
        match s.to_ascii_uppercase().as_str() {
            "ASTER" => Some(MeshFormat::Aster),
            "GMSH" => Some(MeshFormat::Gmsh),
            "MED" => Some(MeshFormat::Med),
            _ => None,
        }
    }
    /// Extension of a file of this format found beside the command file.
    pub fn extension(self) -> &'static str {
        match self {
            MeshFormat::Aster => "mail",
            MeshFormat::Gmsh => "msh",
            MeshFormat::Med => "med",
        }
    }
    /// Every extension looked for beside the command file, the usual one first
    /// (Code_Aster's own test cases name their MED meshes `.mmed`).
    pub fn extensions(self) -> &'static [&'static str] {
        match self {
            MeshFormat::Aster => &["mail"],
            MeshFormat::Gmsh => &["msh"],
            MeshFormat::Med => &["med", "mmed"],
        }
    }
}

/// Read a mesh file of the given format. `med_name` picks a mesh in a MED file holding
/// several (NOM_MED); the first one is read otherwise.
pub fn read_file(path: &Path, format: MeshFormat, med_name: Option<&str>) -> Result<Mesh> {
    match format {
        MeshFormat::Aster => aster::read_file(path),
        MeshFormat::Gmsh => gmsh::read_file(path),
        MeshFormat::Med => med::read_file(path, med_name),
    }
}
