//! AFFE_MATERIAU: assign materials to cells (MAILLAGE or MODELE).

use super::common::selection::selection;
use super::OpContext;
use crate::args::Args;
use crate::error::{Error, Result};
use crate::model::material::MaterialAssignment;
use crate::model::MaterialField;
use crate::store::model::{load_material, load_mesh, load_model, save_material_field};

pub fn run(ctx: &mut OpContext<'_>, args: &Args) -> Result<()> {
    let name = ctx.result_name()?.to_string();
    let mesh_name = match (args.concept("MAILLAGE"), args.concept("MODELE")) {
        (Some(m), _) => m.name.clone(),
        (None, Some(mo)) => load_model(ctx.store, &mo.name)?.mesh,
        (None, None) => {
            return Err(Error::validation("give MAILLAGE or MODELE").keyword("AFFE_MATERIAU"))
        }
    };
    let mesh = load_mesh(ctx.store, &mesh_name)?;
    let mut affe = Vec::new();
    for occ in args.facts_or_empty("AFFE") {
        let mater = occ.concepts("MATER").unwrap_or_default();
        let [m] = mater.as_slice() else {
            return Err(
                Error::input("expected exactly one material").keyword(occ.key_path("MATER"))
            );
        };
        affe.push(MaterialAssignment {
            on: selection(occ),
            name: m.name.clone(),
            material: load_material(ctx.store, &m.name)?,
        });
    }
    let field = MaterialField::build(&mesh_name, &mesh, &affe)?;
    ctx.create(&name, "cham_mater")?;
    save_material_field(ctx.store, &name, &field)
}
