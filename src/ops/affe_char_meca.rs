//! AFFE_CHAR_MECA: imposed DOFs (DDL_IMPO) and nodal forces (FORCE_NODALE). Code_Aster
//! dualises imposed DOFs with Lagrange multipliers; we eliminate them through the
//! numbering, which gives the same modes. The forces are assembled by ASSE_VECTEUR.

use super::common::selection::selection;
use super::OpContext;
use crate::args::Args;
use crate::error::{Error, Result};
use crate::model::loads::{Condition, ImposedComponent};
use crate::model::{Cmp, KinematicLoad, LoadKind};
use crate::store::model::{load_model_and_mesh, save_load};

/// FORCE_NODALE's keywords and the DOF each works on.
const FORCE_COMPONENTS: [(&str, Cmp); 6] = [
    ("FX", Cmp::Dx),
    ("FY", Cmp::Dy),
    ("FZ", Cmp::Dz),
    ("MX", Cmp::Drx),
    ("MY", Cmp::Dry),
    ("MZ", Cmp::Drz),
];

pub fn run(ctx: &mut OpContext<'_>, args: &Args) -> Result<()> {
    if !args.has("FORCE_NODALE") {
        return super::affe_char_cine::build(ctx, args, LoadKind::Meca, "DDL_IMPO", "char_meca");
    }
    let name = ctx.result_name()?.to_string();
    let model_name = args.req_concept("MODELE")?.name.clone();
    let (model, mesh) = load_model_and_mesh(ctx.store, &model_name)?;
    let mut load = super::affe_char_cine::kinematic_load(
        LoadKind::Meca,
        &model_name,
        &model,
        &mesh,
        args.facts_or_empty("DDL_IMPO"),
    )?;
    let occurrences = args
        .facts_or_empty("FORCE_NODALE")
        .iter()
        .map(force_condition)
        .collect::<Result<Vec<_>>>()?;
    load.forces = KinematicLoad::nodal_forces(&model, &mesh, &occurrences)?;
    ctx.create(&name, "char_meca")?;
    save_load(ctx.store, &name, &load)
}

fn force_condition(occ: &Args) -> Result<Condition> {
    let components: Vec<ImposedComponent> = FORCE_COMPONENTS
        .iter()
        .filter_map(|&(key, cmp)| {
            occ.real(key).map(|value| ImposedComponent {
                cmp,
                value,
                keyword: occ.key_path(key),
            })
        })
        .collect();
    if components.is_empty() {
        return Err(Error::input("no component given")
            .keyword(occ.path.clone())
            .hint("give at least one of FX FY FZ MX MY MZ"));
    }
    Ok(Condition {
        on: selection(occ),
        components,
        clamp: false,
        keyword: occ.path.clone(),
    })
}
