//! AFFE_CHAR_MECA: imposed DOFs (DDL_IMPO). Code_Aster dualises them with Lagrange
//! multipliers; we eliminate them through the numbering, which gives the same modes.

use super::OpContext;
use crate::args::Args;
use crate::error::Result;
use crate::model::LoadKind;

pub fn run(ctx: &mut OpContext<'_>, args: &Args) -> Result<()> {
    super::affe_char_cine::build(ctx, args, LoadKind::Meca, "DDL_IMPO", "char_meca")
}
