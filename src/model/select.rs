//! Cell/node selection for the model operators, over `mesh::select`, in mesh order.

use super::fe_model::Model;
use crate::error::{Error, Result};
use crate::mesh::select::Selection;
use crate::mesh::{CellKind, Mesh};

/// Cells chosen by the whole mesh, cell groups or cells of `sel`, sorted and without
/// repeats (the model keeps its elements in mesh order).
pub fn model_select_cells(mesh: &Mesh, sel: &Selection) -> Result<Vec<usize>> {
    let mut cells = crate::mesh::select::select_cells(mesh, sel)?;
    cells.sort_unstable();
    Ok(cells)
}

/// Nodes chosen by `sel` (with the nodes of its cells), sorted and without repeats.
pub fn model_select_nodes(mesh: &Mesh, sel: &Selection) -> Result<Vec<usize>> {
    let mut nodes = crate::mesh::select::select_nodes(mesh, sel)?;
    nodes.sort_unstable();
    Ok(nodes)
}

/// The POI1 cells carrying an element of `model` on the nodes `sel` names explicitly
/// (Code_Aster 13.x: characteristics of discrete elements given on nodes), in node order.
/// `mesh` is the model's mesh completed with its point cells. Every node must carry one.
pub fn model_point_cells(model: &Model, mesh: &Mesh, sel: &Selection) -> Result<Vec<usize>> {
    if !sel.names_nodes() {
        return Ok(Vec::new());
    }
    let nodes = crate::mesh::select::select_nodes(mesh, &sel.nodes_only())?;
    let mut out = Vec::new();
    for n in nodes {
        let on_node: Vec<usize> = model
            .elements
            .iter()
            .map(|e| e.cell)
            .filter(|&c| {
                mesh.cells
                    .get(c)
                    .is_some_and(|cell| cell.kind == CellKind::Poi1 && cell.nodes == [n])
            })
            .collect();
        if on_node.is_empty() {
            let name = mesh.nodes.get(n).map_or("?", |x| x.name.as_str());
            return Err(Error::input(format!(
                "node {name} carries no point element in the model"
            ))
            .keyword(sel.node_keyword().to_string())
            .hint("give the node an element: AFFE_MODELE(AFFE=_F(NOEUD=... or GROUP_NO=..., MODELISATION='DIS_T')), or a POI1 cell with CREA_MAILLAGE/CREA_POI1 modelled through GROUP_MA"));
        }
        out.extend(on_node);
    }
    Ok(out)
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
