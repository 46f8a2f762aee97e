//! AFFE_CARA_ELEM: discrete characteristics, beam and bar sections, orientations.

use super::OpContext;
use crate::args::Args;
use crate::error::Result;
use crate::model::CaraElem;
use crate::store::model::{load_model_and_mesh, save_cara_elem};

pub fn run(ctx: &mut OpContext<'_>, args: &Args) -> Result<()> {
    let name = ctx.result_name()?.to_string();
    let model_name = args.req_concept("MODELE")?.name.clone();
    let (model, mesh) = load_model_and_mesh(ctx.store, &model_name)?;
    let cara = CaraElem::build(&model_name, &model, &mesh, args)?;
    ctx.create(&name, "cara_elem")?;
    save_cara_elem(ctx.store, &name, &cara)
}
