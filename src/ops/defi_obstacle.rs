//! DEFI_OBSTACLE: an obstacle's shape for DYNA_VIBRA's shocks.

use super::OpContext;
use crate::args::Args;
use crate::error::Result;
use crate::store::gene::{self, ObstacleDef};

pub fn run(ctx: &mut OpContext<'_>, args: &Args) -> Result<()> {
    let name = ctx.result_name()?.to_string();
    let kind = args.req_text("TYPE")?.to_string();
    ctx.create(&name, "table_fonction")?;
    gene::save_obstacle(ctx.store, &name, &ObstacleDef { kind })
}
