//! Mesh locations given by keywords: `TOUT='OUI'`, `GROUP_MA`, `MAILLE`, `GROUP_NO`,
//! `NOEUD`, as every Code_Aster operator that applies something "somewhere" accepts them.
//!
//! Several keywords in one occurrence add up; the result lists each index once, in order
//! of first appearance.

use super::Mesh;
use crate::args::Args;
use crate::error::{Error, Result};

/// Cells designated by `TOUT='OUI'`, `GROUP_MA` or `MAILLE` in `args`.
pub fn select_cells(mesh: &Mesh, args: &Args) -> Result<Vec<usize>> {
    let mut out = Picker::new(mesh.cells.len());
    if is_tout(args) {
        out.extend(0..mesh.cells.len());
    }
    for g in args.texts("GROUP_MA").unwrap_or_default() {
        let group = mesh.cell_group(&g).ok_or_else(|| {
            unknown(
                args,
                "GROUP_MA",
                &g,
                "GROUP_MA",
                mesh.cell_groups.iter().map(|g| g.name.as_str()),
            )
        })?;
        out.extend(group.members.iter().copied());
    }
    for m in args.texts("MAILLE").unwrap_or_default() {
        let i = mesh.cell_index(&m).ok_or_else(|| {
            unknown(
                args,
                "MAILLE",
                &m,
                "cell",
                mesh.cells.iter().map(|c| c.name.as_str()),
            )
        })?;
        out.extend([i]);
    }
    Ok(out.done())
}

/// Nodes designated by `GROUP_NO` or `NOEUD` (explicitly), and the nodes of the cells
/// designated by `TOUT='OUI'`, `GROUP_MA` or `MAILLE`.
pub fn select_nodes(mesh: &Mesh, args: &Args) -> Result<Vec<usize>> {
    let mut out = Picker::new(mesh.nodes.len());
    if is_tout(args) {
        // Every node of the mesh, including nodes no cell uses (Code_Aster's TOUT='OUI'
        // on nodes means the whole mesh).
        out.extend(0..mesh.nodes.len());
    }
    if args.has("GROUP_MA") || args.has("MAILLE") {
        let mut cell_args = args.clone();
        cell_args
            .simple
            .retain(|(k, _, _)| k == "GROUP_MA" || k == "MAILLE");
        let cells = select_cells(mesh, &cell_args)?;
        out.extend(mesh.nodes_of_cells(&cells));
    }
    for g in args.texts("GROUP_NO").unwrap_or_default() {
        let group = mesh.node_group(&g).ok_or_else(|| {
            unknown(
                args,
                "GROUP_NO",
                &g,
                "GROUP_NO",
                mesh.node_groups.iter().map(|g| g.name.as_str()),
            )
        })?;
        out.extend(group.members.iter().copied());
    }
    for n in args.texts("NOEUD").unwrap_or_default() {
        let i = mesh.node_index(&n).ok_or_else(|| {
            unknown(
                args,
                "NOEUD",
                &n,
                "node",
                mesh.nodes.iter().map(|n| n.name.as_str()),
            )
        })?;
        out.extend([i]);
    }
    Ok(out.done())
}

fn is_tout(args: &Args) -> bool {
    args.text("TOUT")
        .is_some_and(|t| t.eq_ignore_ascii_case("OUI"))
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

/// "GROUP_MA 'X' is not in the mesh", naming a few names that exist.
fn unknown<'a>(
    args: &Args,
    key: &str,
    name: &str,
    what: &str,
    existing: impl Iterator<Item = &'a str>,
) -> Error {
    let all: Vec<&str> = existing.collect();
    let shown: Vec<&str> = all.iter().take(8).copied().collect();
    let hint = if all.is_empty() {
        format!("the mesh has no {what}")
    } else {
        format!(
            "the mesh has {} {what}(s): {}{}",
            all.len(),
            shown.join(", "),
            if all.len() > shown.len() { ", ..." } else { "" }
        )
    };
    Error::validation(format!("{what} '{name}' is not in the mesh"))
        .keyword(args.key_path(key))
        .hint(hint)
}
