//! Private cell/node selection for the model operators (TOUT / GROUP_MA / MAILLE /
//! GROUP_NO / NOEUD). integration: the mesh helper writes `mesh::select`; switch these
//! two functions to it when merging.

use crate::args::Args;
use crate::error::{Error, Result};
use crate::mesh::Mesh;
use std::collections::BTreeSet;

fn unknown(what: &str, name: &str, mesh_name: &str, key: String) -> Error {
    Error::input(format!("{what} {name} is not in mesh {mesh_name}"))
        .keyword(key)
        .hint("check the spelling; names are case-sensitive")
}

/// Cells chosen by TOUT='OUI', GROUP_MA or MAILLE in one factor keyword occurrence,
/// sorted and without repeats.
pub fn model_select_cells(mesh: &Mesh, mesh_name: &str, args: &Args) -> Result<Vec<usize>> {
    let mut out = BTreeSet::new();
    if args.text("TOUT") == Some("OUI") {
        out.extend(0..mesh.cells.len());
    }
    for g in args.texts("GROUP_MA").unwrap_or_default() {
        let grp = mesh
            .cell_group(&g)
            .ok_or_else(|| unknown("GROUP_MA", &g, mesh_name, args.key_path("GROUP_MA")))?;
        out.extend(grp.members.iter().copied());
    }
    for m in args.texts("MAILLE").unwrap_or_default() {
        let i = mesh
            .cell_index(&m)
            .ok_or_else(|| unknown("cell (MAILLE)", &m, mesh_name, args.key_path("MAILLE")))?;
        out.insert(i);
    }
    Ok(out.into_iter().collect())
}

/// Nodes chosen by TOUT, GROUP_NO, NOEUD, GROUP_MA or MAILLE (the nodes of those cells),
/// sorted and without repeats.
pub fn model_select_nodes(mesh: &Mesh, mesh_name: &str, args: &Args) -> Result<Vec<usize>> {
    let mut out = BTreeSet::new();
    if args.text("TOUT") == Some("OUI") {
        out.extend(0..mesh.nodes.len());
    }
    for g in args.texts("GROUP_NO").unwrap_or_default() {
        let grp = mesh
            .node_group(&g)
            .ok_or_else(|| unknown("GROUP_NO", &g, mesh_name, args.key_path("GROUP_NO")))?;
        out.extend(grp.members.iter().copied());
    }
    for n in args.texts("NOEUD").unwrap_or_default() {
        let i = mesh
            .node_index(&n)
            .ok_or_else(|| unknown("node (NOEUD)", &n, mesh_name, args.key_path("NOEUD")))?;
        out.insert(i);
    }
    let has_cells = args.has("GROUP_MA") || args.has("MAILLE");
    if has_cells {
        let mut cell_args = Args::new(args.path.clone());
        for k in ["GROUP_MA", "MAILLE"] {
            if let Some((kk, v, s)) = args.simple.iter().find(|(kk, _, _)| kk == k) {
                cell_args.simple.push((kk.clone(), v.clone(), *s));
            }
        }
        for c in model_select_cells(mesh, mesh_name, &cell_args)? {
            if let Some(cell) = mesh.cells.get(c) {
                out.extend(cell.nodes.iter().copied());
            }
        }
    }
    Ok(out.into_iter().collect())
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
