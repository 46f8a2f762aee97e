//! DEFI_GROUP: add or remove node and cell groups of a mesh (reuse).

use super::common::selection::selection;
use super::OpContext;
use crate::args::Args;
use crate::error::{Error, Result};
use crate::mesh::select::{self, Names, Selection};
use crate::mesh::{edit, Mesh};
use crate::store::mesh::{load_mesh, save_mesh};

pub fn run(ctx: &mut OpContext<'_>, args: &Args) -> Result<()> {
    let name = ctx.result_name()?.to_string();
    let source = args.req_concept("MAILLAGE")?.name.clone();
    let mut mesh = load_mesh(ctx.store, &source)?;

    // Removals first, as Code_Aster does, so a group can be redefined in one call.
    for occ in args.facts_or_empty("DETR_GROUP_MA") {
        for g in occ.texts("NOM").unwrap_or_default() {
            edit::remove_cell_group(&mut mesh, &g).map_err(|e| e.keyword(occ.key_path("NOM")))?;
        }
    }
    for occ in args.facts_or_empty("DETR_GROUP_NO") {
        for g in occ.texts("NOM").unwrap_or_default() {
            edit::remove_node_group(&mut mesh, &g).map_err(|e| e.keyword(occ.key_path("NOM")))?;
        }
    }
    for occ in args.facts_or_empty("CREA_GROUP_MA") {
        let g = occ.req_text("NOM")?.to_string();
        let cells = select::select_cells(&mesh, &selection(occ))?;
        edit::add_cell_group(&mut mesh, &g, cells).map_err(|e| e.keyword(occ.key_path("NOM")))?;
    }
    for occ in args.facts_or_empty("CREA_GROUP_NO") {
        for g in crea_group_no(&mut mesh, occ)? {
            ctx.alarm(
                "DEFI_GROUP_EXISTS",
                &format!("TOUT_GROUP_MA: GROUP_NO {g} already exists and is kept as it is"),
            )?;
        }
    }

    if ctx.info >= 2 {
        ctx.say(&format!("{name}: {}", mesh.summary()))?;
    }
    // With reuse the concept exists: only its rows are replaced.
    let exists = ctx.store.concept_type(&name)?.as_deref() == Some("maillage_sdaster");
    if !(exists && ctx.reuse == Some(name.as_str())) {
        ctx.create(&name, "maillage_sdaster")?;
    }
    save_mesh(ctx.store, &name, &mesh)
}

/// One CREA_GROUP_NO occurrence. Returns the groups TOUT_GROUP_MA skipped because a
/// GROUP_NO of that name exists (a Gmsh mesh already has one per physical group).
fn crea_group_no(mesh: &mut Mesh, occ: &Args) -> Result<Vec<String>> {
    let names = occ.texts("NOM").unwrap_or_default();
    let named = |e: Error| e.keyword(occ.key_path("NOM"));
    // One GROUP_NO per GROUP_MA: every one (TOUT_GROUP_MA), or those listed.
    let tout = occ.text("TOUT_GROUP_MA") == Some("OUI");
    let mut skipped = Vec::new();
    let per_group: Option<Vec<String>> = if tout {
        Some(mesh.cell_groups.iter().map(|g| g.name.clone()).collect())
    } else {
        occ.texts("GROUP_MA")
    };
    if let Some(groups) = per_group {
        if !names.is_empty() && names.len() != groups.len() {
            return Err(Error::validation(format!(
                "NOM gives {} name(s) for {} GROUP_MA",
                names.len(),
                groups.len()
            ))
            .keyword(occ.key_path("NOM"))
            .hint("give one name per GROUP_MA, or none to reuse the GROUP_MA names"));
        }
        for (k, g) in groups.iter().enumerate() {
            if tout && mesh.node_group(g).is_some() {
                skipped.push(g.clone());
                continue;
            }
            // The nodes of this one group, blamed on GROUP_MA as the user wrote it.
            let one = Selection {
                cell_groups: Names {
                    names: vec![g.clone()],
                    keyword: occ.key_path("GROUP_MA"),
                },
                ..Selection::default()
            };
            let nodes = select::select_nodes(mesh, &one)?;
            let new_name = names.get(k).unwrap_or(g);
            edit::add_node_group(mesh, new_name, nodes).map_err(named)?;
        }
        return Ok(skipped);
    }
    let name = names.first().ok_or_else(|| {
        Error::validation("NOM is required with NOEUD or GROUP_NO").keyword(occ.key_path("NOM"))
    })?;
    let nodes = select::select_nodes(mesh, &selection(occ))?;
    edit::add_node_group(mesh, name, nodes).map_err(named)?;
    Ok(skipped)
}
