//! CALC_VECT_ELEM (OPTION='CHAR_MECA'): the loads whose nodal forces ASSE_VECTEUR sums.

use super::OpContext;
use crate::args::Args;
use crate::error::Result;
use crate::store::gene::{self, VectElem};

pub fn run(ctx: &mut OpContext<'_>, args: &Args) -> Result<()> {
    let name = ctx.result_name()?.to_string();
    let charges: Vec<String> = args
        .concepts("CHARGE")
        .unwrap_or_default()
        .into_iter()
        .map(|c| c.name)
        .collect();
    // Read each load now, so that a concept that is not one fails here, named.
    for c in &charges {
        crate::store::model::load_load(ctx.store, c)?;
    }
    ctx.create(&name, "vect_elem_depl_r")?;
    for c in &charges {
        ctx.store.record_dependency(&name, c)?;
    }
    gene::save_vect_elem(ctx.store, &name, &VectElem { charges })
}
