//! AFFE_CHAR_CINE: kinematic conditions eliminated at assembly (MECA_IMPO).

use super::common::selection::selection;
use super::OpContext;
use crate::args::Args;
use crate::error::{Error, Result};
use crate::mesh::Mesh;
use crate::model::loads::{Condition, ImposedComponent};
use crate::model::{Cmp, KinematicLoad, LoadKind, Model};
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
    let load = kinematic_load(kind, &model_name, &model, &mesh, args.facts_or_empty(key))?;
    warn_nonzero(ctx, &load)?;
    ctx.create(&name, ty)?;
    save_load(ctx.store, &name, &load)
}

/// Alarm MODEL_NONZERO_IMPO when a blocked DOF has a nonzero imposed value.
pub(crate) fn warn_nonzero(ctx: &mut OpContext<'_>, load: &KinematicLoad) -> Result<()> {
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
    Ok(())
}

/// The load of the MECA_IMPO (Cine) or DDL_IMPO (Meca) occurrences.
pub(crate) fn kinematic_load(
    kind: LoadKind,
    model_name: &str,
    model: &Model,
    mesh: &Mesh,
    occurrences: &[Args],
) -> Result<KinematicLoad> {
    let conditions = occurrences
        .iter()
        .map(condition)
        .collect::<Result<Vec<_>>>()?;
    KinematicLoad::build(kind, model_name, model, mesh, &conditions)
}

/// One occurrence: the component keywords are named after the components.
fn condition(occ: &Args) -> Result<Condition> {
    let components: Vec<ImposedComponent> = Cmp::ALL
        .iter()
        .filter_map(|&cmp| {
            occ.real(cmp.name()).map(|value| ImposedComponent {
                cmp,
                value,
                keyword: occ.key_path(cmp.name()),
            })
        })
        .collect();
    let clamp = occ.text("LIAISON") == Some("ENCASTRE");
    if components.is_empty() && !clamp {
        return Err(Error::input("no component given")
            .keyword(occ.path.clone())
            .hint("give at least one of DX DY DZ DRX DRY DRZ (or LIAISON='ENCASTRE')"));
    }
    Ok(Condition {
        on: selection(occ),
        components,
        clamp,
        keyword: occ.path.clone(),
    })
}
