//! DEFI_MATERIAU: a material (ELAS).

use super::OpContext;
use crate::args::Args;
use crate::error::Result;
use crate::model::Material;
use crate::store::model::save_material;

pub fn run(ctx: &mut OpContext<'_>, args: &Args) -> Result<()> {
    let name = ctx.result_name()?.to_string();
    let mat = Material::from_args(args)?;
    ctx.create(&name, "mater_sdaster")?;
    save_material(ctx.store, &name, &mat)
}
