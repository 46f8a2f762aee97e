//! AFFE_MODELE: assign modelisations to the cells of a mesh.

use super::OpContext;
use crate::args::Args;
use crate::error::Result;
use crate::model::Model;
use crate::store::model::{load_mesh, save_model};

pub fn run(ctx: &mut OpContext<'_>, args: &Args) -> Result<()> {
    let name = ctx.result_name()?.to_string();
    let mesh_name = args.req_concept("MAILLAGE")?.name.clone();
    let mesh = load_mesh(ctx.store, &mesh_name)?;
    let model = Model::build(&mesh_name, &mesh, args.facts_or_empty("AFFE"))?;
    ctx.create(&name, "modele_sdaster")?;
    save_model(ctx.store, &name, &model)
}
