//! MODE_ITER_SIMULT: the Code_Aster 13.x spelling of CALC_MODES (the option inside
//! CALC_FREQ, METHODE at the top level). The modes are CALC_MODES's, normalised to a
//! largest component of 1 as Code_Aster's MODE_ITER_SIMULT normalises them.

use super::{calc_modes, OpContext};
use crate::args::Args;
use crate::error::Result;

pub fn run(ctx: &mut OpContext<'_>, args: &Args) -> Result<()> {
    // The catalog's default (commands/MODE_ITER_SIMULT.toml), filled by the validation.
    let option = args.req_fact("CALC_FREQ")?.req_text("OPTION")?.to_string();
    calc_modes::run_with_option(ctx, args, &option)
}
