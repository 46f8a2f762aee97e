//! NUME_DDL_GENE: a generalized numbering, one unknown per vector of a modal basis.

use super::OpContext;
use crate::args::Args;
use crate::error::{Error, Result};
use crate::store::gene::{self, GeneNumbering};
use crate::store::modes as mode_store;

pub fn run(ctx: &mut OpContext<'_>, args: &Args) -> Result<()> {
    let name = ctx.result_name()?.to_string();
    let basis = args.req_concept("BASE")?.name.clone();
    let modes = mode_store::load_modes(ctx.store, &basis)?;
    if modes.modes.is_empty() {
        return Err(Error::input(format!(
            "{basis} holds no vector: the generalized numbering would be empty"
        ))
        .keyword("NUME_DDL_GENE/BASE"));
    }
    let num = GeneNumbering {
        basis: basis.clone(),
        size: modes.modes.len(),
        storage: args.req_text("STOCKAGE")?.to_string(),
    };
    ctx.create(&name, "nume_ddl_gene")?;
    ctx.store.record_dependency(&name, &basis)?;
    gene::save_numbering(ctx.store, &name, &num)?;
    ctx.say(&format!(
        "NUME_DDL_GENE {name}: {} generalized unknowns, one per vector of {basis}",
        num.size
    ))
}
