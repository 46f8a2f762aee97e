//! Changes to a mesh made by CREA_MAILLAGE and DEFI_GROUP: new POI1 cells, new and
//! removed groups. Names stay unique; a failed change leaves the mesh as it was.

use super::{Cell, CellKind, Group, Mesh};
use crate::error::{Error, Result};
use std::collections::HashSet;

/// Add one POI1 cell on each of `nodes` (in that order) and return their indices.
/// A new cell is named like its node when no cell has that name, else `P<node>`, else
/// `P<node>_<k>` with the smallest free k.
pub fn add_poi1(mesh: &mut Mesh, nodes: &[usize]) -> Result<Vec<usize>> {
    let mut taken: HashSet<String> = mesh.cells.iter().map(|c| c.name.clone()).collect();
    let mut new_cells = Vec::with_capacity(nodes.len());
    for &n in nodes {
        let node = mesh
            .nodes
            .get(n)
            .ok_or_else(|| Error::internal(format!("add_poi1: node index {n} out of range")))?;
        let mut name = node.name.clone();
        if taken.contains(&name) {
            name = format!("P{}", node.name);
        }
        let mut k = 1;
        while taken.contains(&name) {
            name = format!("P{}_{k}", node.name);
            k += 1;
        }
        taken.insert(name.clone());
        new_cells.push(Cell {
            name,
            kind: CellKind::Poi1,
            nodes: vec![n],
        });
    }
    let first = mesh.cells.len();
    mesh.cells.extend(new_cells);
    Ok((first..mesh.cells.len()).collect())
}

fn exists_error(kw: &str, name: &str) -> Error {
    Error::validation(format!("{kw} '{name}' already exists in the mesh")).hint(format!(
        "choose another name, or remove it first with DEFI_GROUP(DETR_{kw}=_F(NOM='{name}'))"
    ))
}

/// Add GROUP_MA `name` with `members` (cell indices); the name must be new.
pub fn add_cell_group(mesh: &mut Mesh, name: &str, members: Vec<usize>) -> Result<()> {
    if mesh.cell_group(name).is_some() {
        return Err(exists_error("GROUP_MA", name));
    }
    mesh.cell_groups.push(Group {
        name: name.to_string(),
        members,
    });
    Ok(())
}

/// Add GROUP_NO `name` with `members` (node indices); the name must be new.
pub fn add_node_group(mesh: &mut Mesh, name: &str, members: Vec<usize>) -> Result<()> {
    if mesh.node_group(name).is_some() {
        return Err(exists_error("GROUP_NO", name));
    }
    mesh.node_groups.push(Group {
        name: name.to_string(),
        members,
    });
    Ok(())
}

fn remove(groups: &mut Vec<Group>, kw: &str, name: &str) -> Result<()> {
    let i = groups.iter().position(|g| g.name == name).ok_or_else(|| {
        let names: Vec<&str> = groups.iter().take(8).map(|g| g.name.as_str()).collect();
        Error::validation(format!("{kw} '{name}' is not in the mesh")).hint(if names.is_empty() {
            format!("the mesh has no {kw}")
        } else {
            format!("existing {kw}: {}", names.join(", "))
        })
    })?;
    groups.remove(i);
    Ok(())
}

pub fn remove_cell_group(mesh: &mut Mesh, name: &str) -> Result<()> {
    remove(&mut mesh.cell_groups, "GROUP_MA", name)
}

pub fn remove_node_group(mesh: &mut Mesh, name: &str) -> Result<()> {
    remove(&mut mesh.node_groups, "GROUP_NO", name)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::Node;

    fn two_nodes() -> Mesh {
        let node = |name: &str, x: f64| Node {
            name: name.into(),
            coords: [x, 0.0, 0.0],
        };
        Mesh {
            dim: 3,
            nodes: vec![node("N1", 0.0), node("N2", 1.0)],
            cells: vec![Cell {
                name: "N2".into(),
                kind: CellKind::Seg2,
                nodes: vec![0, 1],
            }],
            ..Mesh::default()
        }
    }

    #[test]
    fn poi1_names_are_unique() {
        let mut m = two_nodes();
        let a = add_poi1(&mut m, &[0, 1]).unwrap();
        assert_eq!(a, vec![1, 2]);
        assert_eq!(m.cells[1].name, "N1");
        assert_eq!(m.cells[2].name, "PN2", "N2 is already a cell name");
        let b = add_poi1(&mut m, &[1]).unwrap();
        assert_eq!(m.cells[b[0]].name, "PN2_1");
        assert_eq!(m.cells[b[0]].nodes, vec![1]);
        assert_eq!(m.cells[b[0]].kind, CellKind::Poi1);
    }

    #[test]
    fn groups_are_added_once_and_removed() {
        let mut m = two_nodes();
        add_node_group(&mut m, "G", vec![1]).unwrap();
        let e = add_node_group(&mut m, "G", vec![0]).unwrap_err();
        assert!(e.to_string().contains("GROUP_NO 'G' already exists"), "{e}");
        remove_node_group(&mut m, "G").unwrap();
        assert!(m.node_groups.is_empty());
        let e = remove_cell_group(&mut m, "X").unwrap_err();
        assert!(
            e.to_string().contains("GROUP_MA 'X' is not in the mesh"),
            "{e}"
        );
    }
}
