//! CREA_MAILLAGE: a copy of a mesh with new POI1 cells (CREA_POI1).

use super::OpContext;
use crate::args::Args;
use crate::error::Result;
use crate::mesh::{edit, select};
use crate::store::mesh::{load_mesh, save_mesh};

pub fn run(ctx: &mut OpContext<'_>, args: &Args) -> Result<()> {
    let name = ctx.result_name()?.to_string();
    let source = args.req_concept("MAILLAGE")?.name.clone();
    let mut mesh = load_mesh(ctx.store, &source)?;
    for occ in args.facts_or_empty("CREA_POI1") {
        let nodes = select::select_nodes(&mesh, occ)?;
        let cells = edit::add_poi1(&mut mesh, &nodes)?;
        if let Some(g) = occ.text("NOM_GROUP_MA") {
            edit::add_cell_group(&mut mesh, g, cells.clone())
                .map_err(|e| e.keyword(occ.key_path("NOM_GROUP_MA")))?;
        }
        ctx.say(&format!(
            "{name}: {} POI1 cell(s) created{}",
            cells.len(),
            occ.text("NOM_GROUP_MA")
                .map(|g| format!(" in GROUP_MA {g}"))
                .unwrap_or_default()
        ))?;
    }
    ctx.create(&name, "maillage_sdaster")?;
    save_mesh(ctx.store, &name, &mesh)
}
