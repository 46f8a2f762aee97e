//! Cell/node selection for the model operators (TOUT / GROUP_MA / MAILLE / GROUP_NO /
//! NOEUD), over `mesh::select`, in mesh order.

use crate::args::Args;
use crate::error::Result;
use crate::mesh::Mesh;

/// Cells chosen by TOUT='OUI', GROUP_MA or MAILLE in one factor keyword occurrence,
/// sorted and without repeats (the model keeps its elements in mesh order).
pub fn model_select_cells(mesh: &Mesh, _mesh_name: &str, args: &Args) -> Result<Vec<usize>> {
    let mut cells = crate::mesh::select::select_cells(mesh, args)?;
    cells.sort_unstable();
    Ok(cells)
}

/// Nodes chosen by TOUT, GROUP_NO, NOEUD, GROUP_MA or MAILLE (the nodes of those cells),
/// sorted and without repeats.
pub fn model_select_nodes(mesh: &Mesh, _mesh_name: &str, args: &Args) -> Result<Vec<usize>> {
    let mut nodes = crate::mesh::select::select_nodes(mesh, args)?;
    nodes.sort_unstable();
    Ok(nodes)
}

/// Names of the cell groups containing `cell`, for messages.
pub fn groups_of_cell(mesh: &Mesh, cell: usize) -> Vec<String> {
    mesh.cell_groups
        .iter()
        .filter(|g| g.members.contains(&cell))
        .map(|g| g.name.clone())
        .collect()
}

/// "cells M1, M2 (GROUP_MA G1)" for a set of cells, at most 8 names.
pub fn describe_cells(mesh: &Mesh, cells: &[usize]) -> String {
    let names: Vec<&str> = cells
        .iter()
        .take(8)
        .filter_map(|&c| mesh.cells.get(c).map(|x| x.name.as_str()))
        .collect();
    let more = if cells.len() > 8 {
        format!(" and {} more", cells.len() - 8)
    } else {
        String::new()
    };
    let mut groups: Vec<String> = cells
        .iter()
        .flat_map(|&c| groups_of_cell(mesh, c))
        .collect();
    groups.sort();
    groups.dedup();
    let g = if groups.is_empty() {
        String::new()
    } else {
        format!(" (GROUP_MA {})", groups.join(", "))
    };
    format!("cells {}{more}{g}", names.join(", "))
}
