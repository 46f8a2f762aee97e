//! Mesh locations: every cell, cell groups, cells, node groups and nodes by name, as
//! every Code_Aster operator that applies something "somewhere" accepts them. The
//! operators read them from the user's keywords into a [`Selection`]; each list carries
//! the keyword path it came from, which errors name.
//!
//! Several lists in one selection add up; the result lists each index once, in order of
//! first appearance.

use super::Mesh;
use crate::error::{Error, Result};

/// Names given in one list, and the keyword path errors about them name.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Names {
    pub names: Vec<String>,
    pub keyword: String,
}

impl Names {
    pub fn given(&self) -> bool {
        !self.names.is_empty()
    }
}

/// Where one occurrence applies something.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Selection {
    /// The whole mesh.
    pub all: bool,
    pub cell_groups: Names,
    pub cells: Names,
    pub node_groups: Names,
    pub nodes: Names,
}

impl Selection {
    /// Whether the selection names nodes (node groups or nodes) explicitly.
    pub fn names_nodes(&self) -> bool {
        self.node_groups.given() || self.nodes.given()
    }

    /// The keyword path of the first explicit node list (node groups before nodes).
    pub fn node_keyword(&self) -> &str {
        if self.node_groups.given() {
            &self.node_groups.keyword
        } else {
            &self.nodes.keyword
        }
    }

    /// Only the explicit node lists of this selection.
    pub fn nodes_only(&self) -> Selection {
        Selection {
            node_groups: self.node_groups.clone(),
            nodes: self.nodes.clone(),
            ..Selection::default()
        }
    }
}

/// Cells designated by the whole mesh, cell groups or cells of `sel` (its node lists
/// play no part).
pub fn select_cells(mesh: &Mesh, sel: &Selection) -> Result<Vec<usize>> {
    let mut out = Picker::new(mesh.cells.len());
    if sel.all {
        out.extend(0..mesh.cells.len());
    }
    named_cells(mesh, sel, &mut out)?;
    Ok(out.done())
}

/// Nodes designated by node groups or nodes (explicitly), and the nodes of the cells
/// designated by the whole mesh, cell groups or cells.
pub fn select_nodes(mesh: &Mesh, sel: &Selection) -> Result<Vec<usize>> {
    let mut out = Picker::new(mesh.nodes.len());
    if sel.all {
        // Every node of the mesh, including nodes no cell uses (Code_Aster's TOUT='OUI'
        // on nodes means the whole mesh).
        out.extend(0..mesh.nodes.len());
    }
    if sel.cell_groups.given() || sel.cells.given() {
        let mut cells = Picker::new(mesh.cells.len());
        named_cells(mesh, sel, &mut cells)?;
        out.extend(mesh.nodes_of_cells(&cells.done()));
    }
    for g in &sel.node_groups.names {
        let group = mesh.node_group(g).ok_or_else(|| {
            unknown(
                &sel.node_groups,
                g,
                "GROUP_NO",
                mesh.node_groups.iter().map(|g| g.name.as_str()),
                mesh.node_index(g).map(|_| Namesake::Node),
            )
        })?;
        out.extend(group.members.iter().copied());
    }
    for n in &sel.nodes.names {
        let i = mesh.node_index(n).ok_or_else(|| {
            unknown(
                &sel.nodes,
                n,
                "node",
                mesh.nodes.iter().map(|n| n.name.as_str()),
                mesh.node_group(n).map(|_| Namesake::NodeGroup),
            )
        })?;
        out.extend([i]);
    }
    Ok(out.done())
}

/// The cells of the cell groups, then the cells by name, of `sel`.
fn named_cells(mesh: &Mesh, sel: &Selection, out: &mut Picker) -> Result<()> {
    for g in &sel.cell_groups.names {
        let group = mesh.cell_group(g).ok_or_else(|| {
            unknown(
                &sel.cell_groups,
                g,
                "GROUP_MA",
                mesh.cell_groups.iter().map(|g| g.name.as_str()),
                mesh.cell_index(g).map(|_| Namesake::Cell),
            )
        })?;
        out.extend(group.members.iter().copied());
    }
    for m in &sel.cells.names {
        let i = mesh.cell_index(m).ok_or_else(|| {
            unknown(
                &sel.cells,
                m,
                "cell",
                mesh.cells.iter().map(|c| c.name.as_str()),
                mesh.cell_group(m).map(|_| Namesake::CellGroup),
            )
        })?;
        out.extend([i]);
    }
    Ok(())
}

/// Collects indices once each, in order of first appearance.
struct Picker {
    seen: Vec<bool>,
    out: Vec<usize>,
}

impl Picker {
    fn new(n: usize) -> Self {
        Picker {
            seen: vec![false; n],
            out: Vec::new(),
        }
    }
    fn extend(&mut self, it: impl IntoIterator<Item = usize>) {
        for i in it {
            if let Some(s) = self.seen.get_mut(i) {
                if !*s {
                    *s = true;
                    self.out.push(i);
                }
            }
        }
    }
    fn done(self) -> Vec<usize> {
        self.out
    }
}

/// What else in the mesh bears the name that was not found: Code_Aster 16 and later
/// removed `MAILLE`/`NOEUD` and name one cell or node by a group of the same name, which
/// their meshes carry; a 13.x mesh has the cell or node but not the group.
#[derive(Clone, Copy)]
enum Namesake {
    Cell,
    Node,
    CellGroup,
    NodeGroup,
}

/// "GROUP_MA 'X' is not in the mesh", naming a few names that exist, or the cell, node
/// or group of that name when there is one.
fn unknown<'a>(
    list: &Names,
    name: &str,
    what: &str,
    existing: impl Iterator<Item = &'a str>,
    namesake: Option<Namesake>,
) -> Error {
    let hint = match namesake {
        Some(Namesake::Cell) => format!(
            "the mesh has a cell named '{name}' but no GROUP_MA of that name: files written \
             for Code_Aster 16 or later name a cell by a group of the same name, which their \
             meshes carry; give MAILLE='{name}' (13.x spelling) or a mesh with that group \
             (MA = DEFI_GROUP(reuse=MA, MAILLAGE=MA, CREA_GROUP_MA=_F(NOM='{name}', MAILLE='{name}')))"
        ),
        Some(Namesake::Node) => format!(
            "the mesh has a node named '{name}' but no GROUP_NO of that name: files written \
             for Code_Aster 16 or later name a node by a group of the same name, which their \
             meshes carry; give NOEUD='{name}' (13.x spelling) or a mesh with that group \
             (MA = DEFI_GROUP(reuse=MA, MAILLAGE=MA, CREA_GROUP_NO=_F(NOM='{name}', NOEUD='{name}')))"
        ),
        Some(Namesake::CellGroup) => {
            format!("the mesh has a GROUP_MA named '{name}': give GROUP_MA='{name}'")
        }
        Some(Namesake::NodeGroup) => {
            format!("the mesh has a GROUP_NO named '{name}': give GROUP_NO='{name}'")
        }
        None => not_found_hint(name, what, existing),
    };
    Error::validation(format!("{what} '{name}' is not in the mesh"))
        .keyword(list.keyword.clone())
        .hint(hint)
}

/// Names of a kind listed in a hint: enough for the groups of a study's mesh, short enough
/// for the nodes of a large one.
const LISTED: usize = 20;

/// The hint for `name`, a `what` (GROUP_NO, GROUP_MA, node, cell) the mesh does not have:
/// "did you mean 'N2'?" when a name of the mesh is close (the one rule of
/// [`crate::suggest`]), then the names of that kind the mesh has.
pub fn not_found_hint<'a>(
    name: &str,
    what: &str,
    existing: impl Iterator<Item = &'a str>,
) -> String {
    let all: Vec<&str> = existing.collect();
    if all.is_empty() {
        return format!("the mesh has no {what}");
    }
    let mean = crate::suggest::did_you_mean(name, all.iter().copied());
    let shown: Vec<&str> = all.iter().take(LISTED).copied().collect();
    format!(
        "{mean}the mesh has {} {what}(s): {}{}",
        all.len(),
        shown.join(", "),
        if all.len() > shown.len() { ", ..." } else { "" }
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A 13.x-style mesh: cells and nodes by name, one group of its own.
    const MESH: &str = "COOR_3D\n N1 0 0 0\n N2 1 0 0\nFINSF\nPOI1\n P2 N2\nFINSF\n\
                        SEG2\n M1 N1 N2\nFINSF\nGROUP_MA\n LIAI\n M1\nFINSF\n\
                        GROUP_NO\n MASSES\n N2\nFINSF\nFIN\n";

    /// One name in the list of `key`, as AFFE_MODELE/AFFE would give it.
    fn args(key: &str, name: &str) -> Selection {
        let names = Names {
            names: vec![name.to_string()],
            keyword: format!("AFFE_MODELE/AFFE/{key}"),
        };
        let mut sel = Selection::default();
        match key {
            "GROUP_MA" => sel.cell_groups = names,
            "MAILLE" => sel.cells = names,
            "GROUP_NO" => sel.node_groups = names,
            _ => sel.nodes = names,
        }
        sel
    }

    fn cells_err(key: &str, name: &str) -> String {
        let mesh = crate::mesh::aster::parse(MESH, "t.mail").unwrap();
        select_cells(&mesh, &args(key, name))
            .unwrap_err()
            .to_string()
    }

    fn nodes_err(key: &str, name: &str) -> String {
        let mesh = crate::mesh::aster::parse(MESH, "t.mail").unwrap();
        select_nodes(&mesh, &args(key, name))
            .unwrap_err()
            .to_string()
    }

    #[test]
    fn a_group_named_after_a_cell_or_node_points_to_the_13x_spelling() {
        // Code_Aster 16+ spelling GROUP_MA='M1' on a mesh that has cell M1, no group M1.
        let e = cells_err("GROUP_MA", "P2");
        assert!(e.contains("GROUP_MA 'P2' is not in the mesh"), "{e}");
        assert!(e.contains("a cell named 'P2' but no GROUP_MA"), "{e}");
        assert!(e.contains("MAILLE='P2'"), "{e}");
        assert!(
            e.contains(
                "DEFI_GROUP(reuse=MA, MAILLAGE=MA, CREA_GROUP_MA=_F(NOM='P2', MAILLE='P2'))"
            ),
            "{e}"
        );
        let e = nodes_err("GROUP_NO", "N1");
        assert!(e.contains("GROUP_NO 'N1' is not in the mesh"), "{e}");
        assert!(e.contains("a node named 'N1' but no GROUP_NO"), "{e}");
        assert!(e.contains("NOEUD='N1'"), "{e}");
        assert!(e.contains("CREA_GROUP_NO=_F(NOM='N1', NOEUD='N1')"), "{e}");
        // The same through GROUP_MA on nodes (select_nodes takes the cells' nodes).
        let e = nodes_err("GROUP_MA", "M1");
        assert!(e.contains("a cell named 'M1'"), "{e}");
    }

    #[test]
    fn a_cell_or_node_named_after_a_group_points_to_the_group() {
        let e = cells_err("MAILLE", "LIAI");
        assert!(e.contains("cell 'LIAI' is not in the mesh"), "{e}");
        assert!(e.contains("give GROUP_MA='LIAI'"), "{e}");
        let e = nodes_err("NOEUD", "MASSES");
        assert!(e.contains("node 'MASSES' is not in the mesh"), "{e}");
        assert!(e.contains("give GROUP_NO='MASSES'"), "{e}");
    }

    #[test]
    fn an_unknown_name_lists_what_exists() {
        let e = cells_err("GROUP_MA", "NOPE");
        assert!(e.contains("the mesh has 1 GROUP_MA(s): LIAI"), "{e}");
        let e = nodes_err("NOEUD", "N9");
        assert!(
            e.contains("did you mean 'N1' or 'N2'? the mesh has 2 node(s): N1, N2"),
            "{e}"
        );
    }

    #[test]
    fn a_misspelt_group_is_suggested() {
        let e = nodes_err("GROUP_NO", "MASSE");
        assert!(
            e.contains("did you mean 'MASSES'? the mesh has 1 GROUP_NO(s): MASSES"),
            "{e}"
        );
        let e = cells_err("GROUP_MA", "LIAII");
        assert!(e.contains("did you mean 'LIAI'?"), "{e}");
    }
}
