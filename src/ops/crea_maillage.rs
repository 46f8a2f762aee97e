//! CREA_MAILLAGE: a copy of a mesh with new POI1 cells (CREA_POI1).
//!
//! As in Code_Aster, a node gets one POI1 cell however many CREA_POI1 occurrences name
//! it: a group per node and a group of all of them (sdnd123a's pattern) share the cells,
//! so that a model on one group and characteristics on the other meet on the same cell.

use super::common::selection::selection;
use super::OpContext;
use crate::args::Args;
use crate::error::Result;
use crate::mesh::{edit, select};
use crate::store::mesh::{load_mesh, save_mesh};
use std::collections::BTreeMap;

pub fn run(ctx: &mut OpContext<'_>, args: &Args) -> Result<()> {
    let name = ctx.result_name()?.to_string();
    let source = args.req_concept("MAILLAGE")?.name.clone();
    let mut mesh = load_mesh(ctx.store, &source)?;
    // node -> its POI1 cell, across every occurrence of this call.
    let mut poi1_of: BTreeMap<usize, usize> = BTreeMap::new();
    for occ in args.facts_or_empty("CREA_POI1") {
        let nodes = select::select_nodes(&mesh, &selection(occ))?;
        let new_nodes: Vec<usize> = nodes
            .iter()
            .copied()
            .filter(|n| !poi1_of.contains_key(n))
            .collect();
        let new_cells = edit::add_poi1(&mut mesh, &new_nodes)?;
        poi1_of.extend(new_nodes.iter().copied().zip(new_cells));
        let cells: Vec<usize> = nodes
            .iter()
            .filter_map(|n| poi1_of.get(n).copied())
            .collect();
        if let Some(g) = occ.text("NOM_GROUP_MA") {
            edit::add_cell_group(&mut mesh, g, cells.clone())
                .map_err(|e| e.keyword(occ.key_path("NOM_GROUP_MA")))?;
        }
        let shared = cells.len() - new_nodes.len();
        ctx.say(&format!(
            "{name}: {} POI1 cell(s) created{}{}",
            new_nodes.len(),
            occ.text("NOM_GROUP_MA")
                .map(|g| format!(" in GROUP_MA {g}"))
                .unwrap_or_default(),
            if shared > 0 {
                format!(", {shared} shared with an earlier occurrence (one POI1 per node)")
            } else {
                String::new()
            }
        ))?;
    }
    ctx.create(&name, "maillage_sdaster")?;
    save_mesh(ctx.store, &name, &mesh)
}
