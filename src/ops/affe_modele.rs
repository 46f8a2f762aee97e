//! AFFE_MODELE: assign modelisations to the cells of a mesh.

use super::common::selection::selection;
use super::OpContext;
use crate::args::Args;
use crate::error::{Error, Result};
use crate::mesh::Mesh;
use crate::model::fe_model::{ModelAssignment, ModelBuilder};
use crate::model::{Model, Modelisation};
use crate::store::model::{load_mesh, save_model};

pub fn run(ctx: &mut OpContext<'_>, args: &Args) -> Result<()> {
    let name = ctx.result_name()?.to_string();
    let mesh_name = args.req_concept("MAILLAGE")?.name.clone();
    let mesh = load_mesh(ctx.store, &mesh_name)?;
    let model = model(&mesh_name, &mesh, args.facts_or_empty("AFFE"))?;
    ctx.create(&name, "modele_sdaster")?;
    save_model(ctx.store, &name, &model)
}

/// The model of the AFFE occurrences, each read just before it is assigned so that
/// errors come in the user's order.
pub(crate) fn model(mesh_name: &str, mesh: &Mesh, affe: &[Args]) -> Result<Model> {
    let mut b = ModelBuilder::new(mesh_name, mesh);
    for occ in affe {
        b.assign(&assignment(occ)?)?;
    }
    Ok(b.finish())
}

/// One AFFE occurrence.
fn assignment(occ: &Args) -> Result<ModelAssignment> {
    let phen = occ.req_text("PHENOMENE")?;
    if phen != "MECANIQUE" {
        return Err(Error::input(format!("phenomenon {phen} is not supported"))
            .keyword(occ.key_path("PHENOMENE"))
            .hint("only PHENOMENE='MECANIQUE' is available"));
    }
    let names = occ.texts("MODELISATION").unwrap_or_default();
    let [name] = names.as_slice() else {
        return Err(
            Error::input("expected exactly one MODELISATION").keyword(occ.key_path("MODELISATION"))
        );
    };
    let modelisation = Modelisation::parse(name).ok_or_else(|| {
        Error::input(format!("unknown MODELISATION {name}"))
            .keyword(occ.key_path("MODELISATION"))
            .hint(format!(
                "expected one of {}",
                Modelisation::NAMES.join(", ")
            ))
    })?;
    let on = selection(occ);
    if on.names_nodes() && !modelisation.is_discrete() {
        return Err(Error::input(format!(
            "MODELISATION {name} cannot be assigned to nodes: only discrete elements (DIS_T, DIS_TR, 2D_DIS_T) live on nodes"
        ))
        .keyword(on.node_keyword().to_string())
        .hint("assign beams and bars to cells with GROUP_MA, MAILLE or TOUT"));
    }
    Ok(ModelAssignment {
        modelisation,
        on,
        keyword: occ.key_path("MODELISATION"),
    })
}
