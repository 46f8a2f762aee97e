//! AFFE_CHAR_CINE: kinematic conditions eliminated at assembly (MECA_IMPO).

use super::OpContext;
use crate::args::Args;
use crate::error::Result;
use crate::model::{KinematicLoad, LoadKind};
use crate::store::model::{load_model_and_mesh, save_load};

pub fn run(ctx: &mut OpContext<'_>, args: &Args) -> Result<()> {
    build(ctx, args, LoadKind::Cine, "MECA_IMPO", "char_cine_meca")
}

/// Shared by AFFE_CHAR_CINE and AFFE_CHAR_MECA: they differ only in keyword and type.
pub(crate) fn build(
    ctx: &mut OpContext<'_>,
    args: &Args,
    kind: LoadKind,
    key: &str,
    ty: &str,
) -> Result<()> {
    let name = ctx.result_name()?.to_string();
    let model_name = args.req_concept("MODELE")?.name.clone();
    let (model, mesh) = load_model_and_mesh(ctx.store, &model_name)?;
    let load = KinematicLoad::build(kind, &model_name, &model, &mesh, args.facts_or_empty(key))?;
    let nonzero = load.nonzero();
    if let Some(first) = nonzero.first() {
        let msg = format!(
            "{} nonzero imposed value(s) (e.g. {} = {} on {}): modal analysis only uses which DOFs are blocked, the values are stored but ignored",
            nonzero.len(),
            first.cmp,
            first.value,
            first.node
        );
        ctx.alarm("MODEL_NONZERO_IMPO", &msg)?;
    }
    ctx.create(&name, ty)?;
    save_load(ctx.store, &name, &load)
}
